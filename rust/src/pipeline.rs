//! One force evaluation as a short list of named, timed stages (as Rapier's
//! `PhysicsPipeline::step`): [`evaluate`] runs the stages the model compiled, in order,
//! each a function in the module of its effect. A stage reads the model, the state and
//! the outputs of the stages before it, and adds to the scratch outputs; the integrator
//! then moves the state with them.

use crate::contact::{IdlerContact, PulleyContacts};
use crate::drives::controller::ControlOutput;
use crate::drives::motor::MotorOutput;
use crate::friction::{FrictionOutcome, StickScratch};
use crate::integrate::Inertia;
use crate::model::{Model, Stage, TakeupModel};
use crate::state::State;
use nalgebra::Vector2;
use std::time::Instant;

type V2 = Vector2<f64>;

/// Which optional effects the force evaluation applies (stabilisation turns some off).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Effects {
    /// Belt friction on pulleys and idlers.
    pub friction: bool,
    /// Drive torques and brakes.
    pub drives: bool,
    /// Quasi-static friction (static relaxation): the stick force balances the tangential
    /// force on a node but does not cancel its velocity relative to the surface (the
    /// m·v_n/Δt term is dropped), so friction acts as a constraint on the path to
    /// equilibrium and never as a velocity-dependent drag that stalls the relaxation.
    pub quasi_static_friction: bool,
    /// Axial and contact damping. The static relaxation turns them off: they do not change
    /// the equilibrium, and on the fictitious masses (which can be far lighter than the
    /// physical ones) an explicit damper would be unstable.
    pub damping: bool,
    /// The static relaxation with friction: hold the pulleys that a stopped conveyor holds
    /// at rest ([`crate::model::PulleyModel::rest_hold`], `crate::drives::hold::rest_holds`),
    /// with `drives` off. Off in dynamics.
    pub hold_at_rest: bool,
}

impl Effects {
    /// A damping coefficient as these effects apply it: 0 when damping is off.
    #[inline]
    pub fn damped(self, coefficient: f64) -> f64 {
        if self.damping {
            coefficient
        } else {
            0.0
        }
    }

    /// Everything the model has.
    pub const ALL: Effects = Effects {
        friction: true,
        drives: true,
        quasi_static_friction: false,
        damping: true,
        hold_at_rest: false,
    };
}

/// Per-step working buffers owned by the stepper (never part of the state): the outputs
/// of the stages of one force evaluation.
#[derive(Debug, Clone)]
pub struct Scratch {
    /// Net force on each node, N.
    pub force: Vec<V2>,
    /// Element tension, N.
    pub tension: Vec<f64>,
    /// Net torque on each rigid belt body about its mass centre, N·m (empty for the node
    /// belt).
    pub body_torque: Vec<f64>,
    /// Contacts of each pulley.
    pub contacts: Vec<PulleyContacts>,
    /// Friction scratch of each pulley.
    pub stick: Vec<StickScratch>,
    /// Resultant belt force on each pulley (contact + friction), N.
    pub pulley_force: Vec<V2>,
    /// Belt friction on each pulley.
    pub friction: Vec<FrictionOutcome>,
    /// Drive torque on each pulley, N·m.
    pub drive_torque: Vec<f64>,
    /// Brake torque on each pulley (brake and holdback), N·m.
    pub brake_torque: Vec<f64>,
    /// Bearing drag torque on each pulley, N·m (−b·ω).
    pub bearing_torque: Vec<f64>,
    /// Moment of the rigid belt's normal contact forces on each pulley about its centre,
    /// N·m (`contact::pulley_body_contact`; 0 for the node belt, whose contact forces are
    /// radial).
    pub contact_torque: Vec<f64>,
    /// Speed (rad/s) each pulley is held to at the end of this step by its brake (0) or
    /// speed-controlled drive (the curve), when the holder can hold it; the integrator then
    /// sets it exactly. `None`: the pulley moves under its net torque.
    pub held: Vec<Option<f64>>,
    /// Contact of each idler.
    pub idler_contacts: Vec<IdlerContact>,
    /// Wrap contact on the rolls (`contact::roll_wrap`): per element, the stamp of the last
    /// evaluation that measured it along a wrapped path (a pulley's or a roll's). Empty
    /// until used.
    pub wrap_mark: Vec<u64>,
    /// This evaluation's stamp in `wrap_mark` (counts the wrap-contact idler evaluations).
    pub wrap_stamp: u64,
    /// Elements measured along a wrapped path (a pulley's or a roll's) in the last
    /// evaluation, with their path length minus their chord, m: the viscoelastic arms
    /// (`belt::node::zener::advance_all`) follow the length the element's spring sees.
    pub wrap_excess: Vec<(usize, f64)>,
    /// The rigid belt's wrap joints (`belt::rigid::wrap_joint`) of this evaluation: (pulley,
    /// the body B whose end stands off the drum's body, [`WrapLoad::slide`]). Empty
    /// without them.
    ///
    /// [`WrapLoad::slide`]: crate::belt::rigid::wrap_joint::WrapLoad::slide
    pub wrap_slide: Vec<(usize, usize, V2)>,
    /// Dense per-element copy of `wrap_excess` used while the arms advance (zero between).
    pub arm_excess: Vec<f64>,
    /// Friction torque on each idler, N·m.
    pub idler_torque: Vec<f64>,
    /// Running-resistance force of each idler on the belt, N, along the contact tangent
    /// (the belt receives −f·t; 0 when the idler has none or is not touched).
    pub idler_resistance: Vec<f64>,
    /// What each pulley's PI speed controller decided (`crate::drives::controller`).
    pub control: Vec<ControlOutput>,
    /// What each pulley's DOL motor did (`crate::drives::motor`).
    pub motor: Vec<MotorOutput>,
    /// Rates of the friction memory from this evaluation: (index into
    /// [`State::creep`], dΔ/dt in m/s). The integrator advances the memory with them.
    pub creep_rate: Vec<(usize, f64)>,
    /// Keep each pulley contact's friction force (`PulleyContacts::friction`) for the
    /// recording of contact forces (`Channels::contact_forces`). Off: the friction stages
    /// skip it, at no cost.
    pub contact_detail: bool,
}

impl Scratch {
    /// Net torque on pulley `j` from the last force evaluation (belt friction, drive,
    /// brake, bearing drag and the rigid belt's normal contact), N·m.
    #[inline]
    pub fn pulley_torque(&self, j: usize) -> f64 {
        self.friction[j].torque
            + self.drive_torque[j]
            + self.brake_torque[j]
            + self.bearing_torque[j]
            + self.contact_torque[j]
    }

    /// Net force along its line on takeup `t` of pulley `j` (counterweight pull plus the
    /// belt's force on the pulley), N.
    #[inline]
    pub fn takeup_force(&self, j: usize, t: &TakeupModel) -> f64 {
        t.direction.dot(&self.pulley_force[j]) + t.pull
    }

    /// Buffers sized for `model`.
    pub fn new(model: &Model) -> Scratch {
        let (n, p, q) = (model.nodes, model.pulleys.len(), model.idlers.len());
        Scratch {
            force: vec![V2::zeros(); n],
            tension: vec![0.0; n],
            body_torque: vec![0.0; if model.is_rigid() { n } else { 0 }],
            contacts: vec![PulleyContacts::default(); p],
            stick: vec![StickScratch::default(); p],
            pulley_force: vec![V2::zeros(); p],
            friction: vec![FrictionOutcome::default(); p],
            drive_torque: vec![0.0; p],
            brake_torque: vec![0.0; p],
            bearing_torque: vec![0.0; p],
            contact_torque: vec![0.0; p],
            held: vec![None; p],
            idler_contacts: vec![IdlerContact::default(); q],
            wrap_mark: Vec::new(),
            wrap_stamp: 0,
            wrap_excess: Vec::new(),
            wrap_slide: Vec::new(),
            arm_excess: Vec::new(),
            idler_torque: vec![0.0; q],
            idler_resistance: vec![0.0; q],
            control: vec![ControlOutput::default(); p],
            motor: vec![MotorOutput::default(); p],
            creep_rate: Vec::new(),
            contact_detail: false,
        }
    }

    /// Zero the per-body outputs that stages add to or may leave unset. The node forces
    /// (and body torques) need no reset: the axial or rigid-chain stage, one of which every
    /// model has, writes them all.
    fn clear_body_outputs(&mut self) {
        self.drive_torque.iter_mut().for_each(|t| *t = 0.0);
        self.brake_torque.iter_mut().for_each(|t| *t = 0.0);
        self.bearing_torque.iter_mut().for_each(|t| *t = 0.0);
        self.contact_torque.iter_mut().for_each(|t| *t = 0.0);
        self.held.iter_mut().for_each(|h| *h = None);
        self.friction
            .iter_mut()
            .for_each(|f| *f = FrictionOutcome::default());
        self.idler_torque.iter_mut().for_each(|t| *t = 0.0);
        self.idler_resistance.iter_mut().for_each(|f| *f = 0.0);
        self.creep_rate.clear();
    }
}

/// What one stage function sees: the read-only model, the mutable state, the outputs of
/// the evaluation so far, the masses the integrator uses, and the evaluation's settings.
pub struct StageContext<'a> {
    /// The compiled model (read-only).
    pub model: &'a Model,
    /// The state being evaluated.
    pub state: &'a mut State,
    /// Stage outputs.
    pub scratch: &'a mut Scratch,
    /// The masses the integrator moves the state with (physical, or the relaxation's).
    pub inertia: &'a mut Inertia,
    /// Which optional effects apply.
    pub effects: Effects,
    /// The velocity update (kick) of the coming integration, s: the model's step in
    /// dynamics, the relaxation's own otherwise, and (Δt + Δt_end)/2 before a final
    /// shortened step. Friction and prescribed speeds are solved for it.
    pub dt: f64,
    /// The position update (drift) of the coming integration, s: equal to `dt` but before
    /// a shortened step. A speed-controlled drive aims at its curve half of it ahead.
    pub drift: f64,
    /// Factor on every contact stiffness (1 in dynamics; the relaxation's continuation
    /// softens the contact with it, without touching the model).
    pub contact_scale: f64,
}

impl StageContext<'_> {
    /// The step the friction solve divides relative speeds by: infinite (the velocity
    /// term dropped) for quasi-static friction.
    #[inline]
    pub fn friction_dt(&self) -> f64 {
        if self.effects.quasi_static_friction {
            f64::INFINITY
        } else {
            self.dt
        }
    }

    /// The step the creep friction law is solved for (`dt` of
    /// [`crate::friction::creep::pulley_creep_friction`]): `Some(∞)` for quasi-static
    /// friction, `None` under an adaptive integrator (the law applied as it is, its memory
    /// integrated with the state), the kick of the coming step under central differences
    /// (the law with its stick limit).
    #[inline]
    pub fn creep_step(&self) -> Option<f64> {
        if self.effects.quasi_static_friction {
            Some(f64::INFINITY)
        } else {
            match self.model.integrator {
                crate::integrate::Integrator::Rkf45(_) => None,
                crate::integrate::Integrator::CentralDifference => Some(self.dt),
            }
        }
    }
}

/// Evaluate all forces at the current state (thesis eq. 4.57): run the model's stages in
/// order. With `axial_done`, the axial pass has run already (fused with the last
/// integration, see `integrate::central_difference`) and the other stages add to it.
/// With `profile`, each stage's wall time is added to its entry (same order as
/// `model.stages`); without, nothing is timed.
pub fn evaluate(cx: &mut StageContext<'_>, axial_done: bool, mut profile: Option<&mut [f64]>) {
    let model = cx.model;
    debug_assert!(
        model.has_stage(Stage::Axial)
            || model.has_stage(Stage::AxialDamped)
            || model.has_stage(Stage::RigidChain)
    );
    cx.scratch.clear_body_outputs();
    for (k, &stage) in model.stages.iter().enumerate() {
        let started = profile.as_ref().map(|_| Instant::now());
        match stage {
            Stage::Loads => crate::loads::stage::update_loads(cx),
            // Done already when the last integration was fused with this pass.
            Stage::Axial | Stage::AxialDamped if axial_done => {}
            Stage::Axial | Stage::AxialDamped => crate::belt::node::stage::axial(cx),
            Stage::BeltArms => crate::belt::node::zener::arm_stage(cx),
            Stage::Bending => crate::belt::node::stage::bending(cx),
            Stage::RigidChain => crate::belt::rigid::stage::chain(cx),
            Stage::PulleyContact => crate::contact::stage::pulley_contact(cx),
            Stage::IdlerContact => crate::contact::stage::idler_contact(cx),
            Stage::RunningResistance => crate::friction::stage::running_resistance(cx),
            Stage::Drives => crate::drives::torque::torque_drives(cx),
            Stage::Motors => crate::drives::motor::motors(cx),
            Stage::SpeedControl => crate::drives::controller::speed_control(cx),
            Stage::BearingDrag => crate::drives::bearing::bearing_drag(cx),
            Stage::PulleyFriction => crate::friction::stage::pulley_friction(cx),
            Stage::IdlerFriction => crate::friction::stage::idler_friction(cx),
            Stage::SpeedDrives => crate::drives::hold::speed_drives(cx),
            Stage::Brakes => crate::drives::brake::brakes(cx),
            Stage::Holdbacks => crate::drives::holdback::holdbacks(cx),
            Stage::EndPulls => crate::belt::ends::end_pulls(cx),
            Stage::EndAnchors => crate::belt::ends::end_anchors(cx),
        }
        if let (Some(t0), Some(profile)) = (started, profile.as_mut()) {
            profile[k] += t0.elapsed().as_secs_f64();
        }
    }
    if cx.effects.hold_at_rest {
        crate::drives::hold::rest_holds(cx);
    }
}
