//! The stepper: runs the compiled stages on (model, state), integrates with central
//! differences (thesis eq. 4.58–4.60), records results and relaxes to static equilibrium.

use crate::contact::{self, IdlerBody, IdlerContact, PulleyBody, PulleyContacts};
use crate::error::{BeltError, BeltResult};
use crate::forces;
use crate::friction::{self, FrictionIdler, FrictionOutcome, FrictionPulley, StickScratch};
use crate::model::{Model, Stage, TakeupModel};
use crate::record::{Channels, Energies, Recording};
use crate::scene::{FrictionModel, Scene};
use crate::state::State;
use nalgebra::Vector2;
use std::cell::Cell;
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
}

impl Effects {
    /// Everything the model has.
    pub const ALL: Effects = Effects {
        friction: true,
        drives: true,
        quasi_static_friction: false,
        damping: true,
    };
}

/// Per-step working buffers owned by the stepper (never part of the state).
#[derive(Debug, Clone)]
pub struct Scratch {
    /// Net force on each node, N.
    pub force: Vec<V2>,
    /// Element tension, N.
    pub tension: Vec<f64>,
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
    /// Brake torque on each pulley, N·m.
    pub brake_torque: Vec<f64>,
    /// Speed (rad/s) each pulley is held to at the end of this step by its brake (0) or
    /// speed-controlled drive (the curve), when the holder can hold it; the integrator then
    /// sets it exactly. `None`: the pulley moves under its net torque.
    pub held: Vec<Option<f64>>,
    /// Contact of each idler.
    pub idler_contacts: Vec<IdlerContact>,
    /// Friction torque on each idler, N·m.
    pub idler_torque: Vec<f64>,
    /// Running-resistance force of each idler on the belt, N, along the contact tangent
    /// (the belt receives −f·t; 0 when the idler has none or is not touched).
    pub idler_resistance: Vec<f64>,
}

impl Scratch {
    /// Net torque on pulley `j` from the last force evaluation (belt friction, drive and
    /// brake), N·m.
    fn pulley_torque(&self, j: usize) -> f64 {
        self.friction[j].torque + self.drive_torque[j] + self.brake_torque[j]
    }

    /// Net force along its line on takeup `t` of pulley `j` (counterweight pull plus the
    /// belt's force on the pulley), N.
    fn takeup_force(&self, j: usize, t: &TakeupModel) -> f64 {
        t.direction.dot(&self.pulley_force[j]) + t.pull
    }

    fn new(model: &Model) -> Scratch {
        let (n, p, q) = (model.nodes, model.pulleys.len(), model.idlers.len());
        Scratch {
            force: vec![V2::zeros(); n],
            tension: vec![0.0; n],
            contacts: vec![PulleyContacts::default(); p],
            stick: vec![StickScratch::default(); p],
            pulley_force: vec![V2::zeros(); p],
            friction: vec![FrictionOutcome::default(); p],
            drive_torque: vec![0.0; p],
            brake_torque: vec![0.0; p],
            held: vec![None; p],
            idler_contacts: vec![IdlerContact::default(); q],
            idler_torque: vec![0.0; q],
            idler_resistance: vec![0.0; q],
        }
    }
}

/// Mass arrays used for inertia: physical for dynamics, scaled for fast relaxation.
#[derive(Debug, Clone)]
struct Inertia {
    mass: Vec<f64>,
    inv_mass: Vec<f64>,
    /// `inv_mass` when every node has the same (a uniform belt in dynamics): the
    /// integration then streams one array less.
    same_inv_mass: Option<f64>,
    takeup_mass: Vec<f64>,
    /// True for the physical masses (dynamics): the loads stage then keeps `mass` and
    /// `inv_mass` equal to the state's node masses. False for the relaxation's fictitious
    /// masses.
    physical: bool,
}

impl Inertia {
    /// The physical masses: `node_mass` (the state's: belt and material).
    fn physical(model: &Model, node_mass: &[f64]) -> Inertia {
        let inv_mass: Vec<f64> = node_mass.iter().map(|m| 1.0 / m).collect();
        Inertia {
            mass: node_mass.to_vec(),
            // With loads the masses change during the run: never take them as uniform.
            same_inv_mass: if model.loads.is_empty() {
                forces::all_same(&inv_mass)
            } else {
                None
            },
            inv_mass,
            takeup_mass: model
                .pulleys
                .iter()
                .map(|p| p.takeup.as_ref().map_or(f64::INFINITY, |t| t.moving_mass))
                .collect(),
            physical: true,
        }
    }

    /// Fictitious masses m̃ = K·Δt² that put every degree of freedom at the same distance
    /// from its stability limit (ωΔt ≤ 1), as in Underwood's dynamic relaxation. K is the
    /// Gershgorin row sum: a node touching a moving (takeup) pulley is coupled to it through
    /// the contact stiffness, which adds an off-diagonal term to both rows, so the node
    /// bound gains one contact stiffness and the takeup bound doubles. Without those terms
    /// the node–takeup mode sits at ωΔt ≈ √2 and FIRE's longer steps turn it unstable.
    fn scaled(model: &Model) -> Inertia {
        let dt2 = model.dt * model.dt;
        let takeup_contact = model
            .pulleys
            .iter()
            .filter(|p| p.takeup.is_some())
            .map(|p| p.contact_stiffness)
            .fold(0.0, f64::max);
        let mass: Vec<f64> = model
            .node_stiffness_bound
            .iter()
            .map(|k| (k + takeup_contact) * dt2)
            .collect();
        let inv_mass: Vec<f64> = mass.iter().map(|m| 1.0 / m).collect();
        let takeup_mass = model
            .pulleys
            .iter()
            .enumerate()
            .map(|(j, p)| match &p.takeup {
                // A takeup without pulley contact feels only its pull: keep its true mass.
                Some(t) if model.takeup_stiffness_bound[j] == 0.0 => t.moving_mass,
                Some(_) => 2.0 * model.takeup_stiffness_bound[j] * dt2,
                None => f64::INFINITY,
            })
            .collect();
        Inertia {
            mass,
            same_inv_mass: forces::all_same(&inv_mass),
            inv_mass,
            takeup_mass,
            physical: false,
        }
    }
}

/// Contact stiffness, as a multiple of the stiffest belt element (EA/l), at which the
/// static relaxation starts its continuation in contact stiffness.
pub const CONTINUATION_START: f64 = 100.0;
/// Factor between successive contact stiffnesses of the continuation.
pub const CONTINUATION_FACTOR: f64 = 10.0;
/// Most stages of the continuation (it starts no softer than 10^-8 of the scene's contact).
pub const CONTINUATION_STAGES: i32 = 8;

/// The scene with every pulley and idler contact stiffness multiplied by `scale`.
fn soften_contact(scene: &Scene, scale: f64) -> Scene {
    let mut soft = scene.clone();
    for p in &mut soft.pulleys {
        p.contact_stiffness *= scale;
    }
    for d in &mut soft.idlers {
        d.contact_stiffness *= scale;
    }
    soft
}

/// Static relaxation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Relaxation {
    /// Kinetic-energy damping (thesis §6.2): velocities are zeroed at kinetic-energy
    /// peaks. Each degree of freedom is reset at its own peak (the thesis resets all at the
    /// peak of the total, which stalls with stiff contact; see `docs/statics.md`).
    #[default]
    KineticEnergy,
    /// FIRE (Bitzek et al. 2006): inertial relaxation that mixes the velocity towards the
    /// force and restarts when the power turns negative: same equilibrium, ~100× fewer steps.
    Fire,
}

/// Options of [`Simulation::stabilise`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabiliseOptions {
    /// Method. Default [`Relaxation::Fire`].
    pub method: Relaxation,
    /// Keep belt friction on while relaxing (thesis §6.3 / fig. 6.6 locks in lower
    /// tensions). Default false.
    pub friction: bool,
    /// Converged when the largest out-of-balance force on any node or takeup is below this
    /// fraction of the largest element tension. Default 1e-7.
    pub tolerance: f64,
    /// Give up after this many steps. Default 5·10⁶.
    pub max_steps: u64,
}

impl Default for StabiliseOptions {
    fn default() -> Self {
        StabiliseOptions {
            method: Relaxation::Fire,
            friction: false,
            tolerance: 1e-7,
            max_steps: 5_000_000,
        }
    }
}

/// What [`Simulation::stabilise`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabiliseReport {
    /// Relaxation steps taken.
    pub steps: u64,
    /// Final out-of-balance force relative to the largest tension.
    pub residual: f64,
    /// Whether the tolerance was met.
    pub converged: bool,
    /// Number of times the velocities were zeroed.
    pub resets: u64,
    /// Whether the caller's interrupt hook stopped it ([`crate::interrupt`]); the state is
    /// the last relaxation step's, at rest.
    pub interrupted: bool,
}

impl StabiliseReport {
    /// Continue this report with a later relaxation `r`: steps and resets add up, the
    /// residual and the verdict are the later one's.
    fn then(&mut self, r: StabiliseReport) {
        self.steps += r.steps;
        self.resets += r.resets;
        self.residual = r.residual;
        self.converged = r.converged;
        self.interrupted = r.interrupted;
    }
}

/// The central-difference update of one node, v ← v + Δt·f/m, x ← x + Δt·v, and a
/// running flag of whether every new position is finite.
///
/// The finiteness check is a flag per position, not one running sum (a chain of dependent
/// additions through every node, which the compiler may not reorder). Testing the new
/// positions suffices: x + v·Δt with Δt > 0 is finite only if the old position and the new
/// velocity are finite (or it overflows), so a non-finite force, velocity or position is
/// caught in the step that produces it.
///
/// On x86-64 the update is written with SSE2 (part of the x86-64 baseline, so always
/// present), one node per 128-bit register: left to itself the compiler vectorises across
/// nodes and spends most of the loop de-interleaving x and y, which made it about 1.6×
/// slower (docs/performance.md). The arithmetic is the same operations in the same order as
/// the portable version, so the result is the same to the last bit.
#[derive(Clone, Copy)]
struct AllFinite {
    #[cfg(target_arch = "x86_64")]
    mask: std::arch::x86_64::__m128d,
    #[cfg(not(target_arch = "x86_64"))]
    finite: bool,
}

#[cfg(target_arch = "x86_64")]
impl AllFinite {
    #[inline(always)]
    fn new() -> AllFinite {
        use std::arch::x86_64::{_mm_castsi128_pd, _mm_set1_epi64x};
        // SAFETY: SSE2 is part of the x86-64 baseline; these only build a register.
        unsafe {
            AllFinite {
                mask: _mm_castsi128_pd(_mm_set1_epi64x(-1)),
            }
        }
    }

    #[inline(always)]
    fn integrate_node(&mut self, x: &mut V2, v: &mut V2, f: V2, inv_mass: f64, dt: f64) {
        use std::arch::x86_64::{
            _mm_add_pd, _mm_and_pd, _mm_castsi128_pd, _mm_cmplt_pd, _mm_loadu_pd, _mm_mul_pd,
            _mm_set1_epi64x, _mm_set1_pd, _mm_storeu_pd,
        };
        // SAFETY: SSE2 is part of the x86-64 baseline, so the intrinsics are available on
        // every x86-64 target. Each pointer is to the two contiguous f64 of one live
        // Vector2<f64> (nalgebra stores it as [f64; 2]), borrowed for this call (shared for
        // f, exclusive for x and v); the unaligned loads and stores need no alignment.
        unsafe {
            let magnitude = _mm_castsi128_pd(_mm_set1_epi64x(i64::MAX));
            let vn = _mm_add_pd(
                _mm_loadu_pd(v.as_ptr()),
                _mm_mul_pd(_mm_loadu_pd(f.as_ptr()), _mm_set1_pd(dt * inv_mass)),
            );
            _mm_storeu_pd(v.as_mut_ptr(), vn);
            let xn = _mm_add_pd(_mm_loadu_pd(x.as_ptr()), _mm_mul_pd(vn, _mm_set1_pd(dt)));
            _mm_storeu_pd(x.as_mut_ptr(), xn);
            let finite = _mm_cmplt_pd(_mm_and_pd(xn, magnitude), _mm_set1_pd(f64::INFINITY));
            self.mask = _mm_and_pd(self.mask, finite);
        }
    }

    #[inline(always)]
    fn all(self) -> bool {
        // SAFETY: SSE2 is part of the x86-64 baseline.
        unsafe { std::arch::x86_64::_mm_movemask_pd(self.mask) == 0b11 }
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl AllFinite {
    fn new() -> AllFinite {
        AllFinite { finite: true }
    }

    #[inline(always)]
    fn integrate_node(&mut self, x: &mut V2, v: &mut V2, f: V2, inv_mass: f64, dt: f64) {
        *v += f * (dt * inv_mass);
        *x += *v * dt;
        self.finite &= x.x.is_finite() & x.y.is_finite();
    }

    fn all(self) -> bool {
        self.finite
    }
}

/// The nodes as the central-difference update moves them, one per `next`: yields each
/// node's new (position, velocity) and keeps the [`AllFinite`] flag.
struct Moving<N, M> {
    nodes: N,
    inv_mass: M,
    dt: f64,
    finite: AllFinite,
}

impl<'a, N, M> Iterator for Moving<N, M>
where
    N: Iterator<Item = ((&'a mut V2, &'a mut V2), &'a Cell<V2>)>,
    M: Iterator<Item = f64>,
{
    type Item = (V2, V2);

    #[inline(always)]
    fn next(&mut self) -> Option<(V2, V2)> {
        let ((x, v), f) = self.nodes.next()?;
        let im = self.inv_mass.next()?;
        self.finite.integrate_node(x, v, f.get(), im, self.dt);
        Some((*x, *v))
    }
}

/// Model, state, scratch buffers and the current recording.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// The compiled model (read-only).
    pub model: Model,
    /// The mutable state.
    pub state: State,
    scratch: Scratch,
    inertia: Inertia,
    /// Results of the current or last run.
    pub recording: Recording,
    record_every: u64,
    record_counter: u64,
    max_samples: usize,
    /// Per-stage wall time, s (same order as `model.stages`), when profiling is on.
    pub profile: Option<Vec<f64>>,
}

impl Simulation {
    /// Compile a scene and place the belt at rest on its initial path.
    pub fn new(scene: &Scene) -> BeltResult<Simulation> {
        let model = Model::compile(scene)?;
        let state = State::initial(&model);
        Ok(Self::from_parts(model, state))
    }

    /// A simulation of `model` at `state` (e.g. read back from a checkpoint). The state's
    /// array lengths must match the model (checked by the checkpoint reader).
    pub(crate) fn from_parts(model: Model, state: State) -> Simulation {
        let scratch = Scratch::new(&model);
        let inertia = Inertia::physical(&model, &state.node_mass);
        let recording = Recording::new(
            Channels::default(),
            model.nodes,
            model.pulleys.len(),
            model.idlers.len(),
        );
        Simulation {
            model,
            state,
            scratch,
            inertia,
            recording,
            record_every: 1,
            record_counter: 0,
            max_samples: usize::MAX,
            profile: None,
        }
    }

    /// Replace the scene (e.g. a new counterweight or drive torque) and keep the state.
    /// The belt discretisation and the set of pulleys and idlers must not change.
    pub fn set_scene(&mut self, scene: &Scene) -> BeltResult<()> {
        let model = Model::compile(scene)?;
        if model.nodes != self.model.nodes
            || model.pulleys.len() != self.model.pulleys.len()
            || model.idlers.len() != self.model.idlers.len()
        {
            return Err(BeltError::Usage(format!(
                "the new scene has {} nodes, {} pulleys and {} idlers, the running one {}, {} and {}: only parameters may change during a run",
                model.nodes,
                model.pulleys.len(),
                model.idlers.len(),
                self.model.nodes,
                self.model.pulleys.len(),
                self.model.idlers.len()
            )));
        }
        for (j, (a, b)) in model.pulleys.iter().zip(&self.model.pulleys).enumerate() {
            if a.center != b.center
                || a.takeup.as_ref().map(|t| t.direction) != b.takeup.as_ref().map(|t| t.direction)
            {
                return Err(BeltError::Usage(format!(
                    "pulleys[{j}]: the centre and takeup line may not change during a run"
                )));
            }
        }
        let profile = self.profile.as_ref().map(|_| vec![0.0; model.stages.len()]);
        // The belt masses or the loads may have changed: re-place the material at once
        // (the nodes keep their velocities); changed load points are found anew.
        if model.loads.len() != self.model.loads.len()
            || model
                .loads
                .iter()
                .zip(&self.model.loads)
                .any(|(a, b)| a.start != b.start || a.end != b.end || a.forward != b.forward)
        {
            self.state.load_edges =
                crate::loads::initial_edges(&model.loads, &self.state.position, model.load_belt());
        }
        self.state.node_mass = crate::loads::node_masses(
            &model.mass,
            &model.loads,
            &self.state.load_edges,
            model.load_belt(),
        );
        self.scratch = Scratch::new(&model);
        self.inertia = Inertia::physical(&model, &self.state.node_mass);
        self.model = model;
        self.profile = profile;
        Ok(())
    }

    /// Turn per-stage timing on (zeroing it) or off.
    pub fn set_profiling(&mut self, on: bool) {
        self.profile = if on {
            Some(vec![0.0; self.model.stages.len()])
        } else {
            None
        };
    }

    /// Evaluate all forces at the current state (thesis eq. 4.57).
    fn evaluate(&mut self, effects: Effects) {
        self.evaluate_after(effects, false);
    }

    /// Evaluate the forces; with `axial_done`, the axial pass has run already (fused with
    /// the last integration, [`Simulation::integrate_then`]) and the other stages add to it.
    fn evaluate_after(&mut self, effects: Effects, axial_done: bool) {
        let m = &self.model;
        let s = &mut self.state;
        let sc = &mut self.scratch;
        let inertia = &mut self.inertia;
        let dt = m.dt;
        // The friction solve divides the relative speed by this step; an infinite step
        // drops the velocity term (quasi-static friction).
        let friction_dt = if effects.quasi_static_friction {
            f64::INFINITY
        } else {
            dt
        };
        // Every model has an axial stage, which writes all node forces (with the weights
        // when the model has a gravity stage), so the force array needs no reset here.
        debug_assert!(m.has_stage(Stage::Axial) || m.has_stage(Stage::AxialDamped));
        sc.drive_torque.iter_mut().for_each(|t| *t = 0.0);
        sc.brake_torque.iter_mut().for_each(|t| *t = 0.0);
        sc.held.iter_mut().for_each(|h| *h = None);
        sc.friction
            .iter_mut()
            .for_each(|f| *f = FrictionOutcome::default());
        sc.idler_torque.iter_mut().for_each(|t| *t = 0.0);
        sc.idler_resistance.iter_mut().for_each(|f| *f = 0.0);
        for (k, &stage) in m.stages.iter().enumerate() {
            let started = self.profile.as_ref().map(|_| Instant::now());
            match stage {
                Stage::Loads => {
                    let physical = inertia.physical;
                    crate::loads::update(
                        &m.loads,
                        &m.mass,
                        m.load_belt(),
                        &s.position,
                        &mut s.velocity,
                        &mut s.load_edges,
                        &mut crate::loads::MassArrays {
                            node_mass: &mut s.node_mass,
                            inertia: physical.then_some((&mut inertia.mass, &mut inertia.inv_mass)),
                        },
                    );
                }
                // The axial pass writes every node force (no reset pass) and adds the
                // weights (no gravity pass): see forces::axial and docs/performance.md.
                Stage::Gravity => {}
                // Done already when the last integration was fused with this pass.
                Stage::Axial | Stage::AxialDamped if axial_done => {}
                // The relaxation runs damped elements undamped (see `Effects::damping`).
                Stage::Axial | Stage::AxialDamped => {
                    let _ = forces::axial_pass(
                        &m.axial_belt(effects.damping, &s.node_mass),
                        s.position.iter().zip(&s.velocity).map(|(&x, &v)| (x, v)),
                        &mut sc.tension.as_mut_slice(),
                        Cell::from_mut(sc.force.as_mut_slice()).as_slice_of_cells(),
                    );
                }
                Stage::Bending => forces::bending(&s.position, &m.bending_stiffness, &mut sc.force),
                Stage::PulleyContact => {
                    for (j, p) in m.pulleys.iter().enumerate() {
                        // Zero stiffness: the belt passes through this pulley (no contact).
                        if p.contact_stiffness == 0.0 {
                            continue;
                        }
                        let body = PulleyBody {
                            center: s.pulley_center(m, j),
                            center_velocity: s.pulley_center_velocity(m, j),
                            radius: p.radius,
                            stiffness: p.contact_stiffness,
                            damping: if effects.damping {
                                p.contact_damping
                            } else {
                                0.0
                            },
                            margin: p.window_margin,
                        };
                        contact::update_window(
                            &mut s.pulley_window[j],
                            &s.position,
                            &body,
                            s.step.is_multiple_of(contact::FULL_SCAN_INTERVAL),
                        );
                        sc.pulley_force[j] = contact::pulley_contact(
                            &s.pulley_window[j],
                            &s.position,
                            &s.velocity,
                            &body,
                            &mut sc.force,
                            &mut sc.contacts[j],
                        );
                    }
                }
                Stage::IdlerContact => {
                    for (k, d) in m.idlers.iter().enumerate() {
                        let body = IdlerBody {
                            center: d.center,
                            radius: d.radius,
                            stiffness: d.contact_stiffness,
                            damping: if effects.damping {
                                d.contact_damping
                            } else {
                                0.0
                            },
                        };
                        sc.idler_contacts[k] = contact::idler_contact(
                            &mut s.idler_element[k],
                            &s.position,
                            &s.velocity,
                            &body,
                            &mut sc.force,
                        );
                    }
                }
                // A friction-like resistance: on with friction (quasi-static in the
                // relaxation, where `friction_dt` is infinite).
                Stage::RunningResistance => {
                    if effects.friction {
                        for (k, d) in m.idlers.iter().enumerate() {
                            let c = sc.idler_contacts[k];
                            if !c.active || d.resistance == 0.0 {
                                continue;
                            }
                            let limit =
                                d.resistance * (c.normal_force + d.rotating_mass * m.gravity);
                            let (f, _) = friction::running_resistance(
                                &c,
                                limit,
                                &s.velocity,
                                &inertia.mass,
                                friction_dt,
                                &mut sc.force,
                            );
                            sc.idler_resistance[k] = f;
                        }
                    }
                }
                Stage::Drives => {
                    if effects.drives {
                        for (j, p) in m.pulleys.iter().enumerate() {
                            if let Some(d) = &p.drive {
                                sc.drive_torque[j] = d.torque_at(s.time, s.pulley_omega[j]);
                            }
                        }
                    }
                }
                Stage::PulleyFriction => {
                    if effects.friction {
                        for (j, p) in m.pulleys.iter().enumerate() {
                            let FrictionModel::StickForce {
                                static_coefficient,
                                kinetic_coefficient,
                            } = p.friction
                            else {
                                continue;
                            };
                            if static_coefficient == 0.0 || sc.contacts[j].is_empty() {
                                continue;
                            }
                            let fp = FrictionPulley {
                                radius: p.radius,
                                inertia: p.inertia,
                                omega: s.pulley_omega[j],
                                center_velocity: s.pulley_center_velocity(m, j),
                                applied_torque: sc.drive_torque[j],
                                mu_static: static_coefficient,
                                mu_kinetic: kinetic_coefficient,
                                prescribed: if effects.drives {
                                    p.brake_hold(s.time).or_else(|| p.speed_hold(s.time, dt))
                                } else {
                                    None
                                },
                            };
                            let out = friction::pulley_stick_friction(
                                &sc.contacts[j],
                                &fp,
                                &s.velocity,
                                &inertia.mass,
                                friction_dt,
                                &mut sc.force,
                                &mut sc.stick[j],
                            );
                            sc.pulley_force[j] += out.force;
                            sc.friction[j] = out;
                        }
                    }
                }
                Stage::IdlerFriction => {
                    if effects.friction {
                        for (k, d) in m.idlers.iter().enumerate() {
                            let FrictionModel::StickForce {
                                static_coefficient,
                                kinetic_coefficient,
                            } = d.friction
                            else {
                                continue;
                            };
                            let c = sc.idler_contacts[k];
                            if !c.active || static_coefficient == 0.0 {
                                continue;
                            }
                            let fi = FrictionIdler {
                                radius: d.radius,
                                inertia: d.inertia,
                                omega: s.idler_omega[k],
                                mu_static: static_coefficient,
                                mu_kinetic: kinetic_coefficient,
                            };
                            let (f, _) = friction::idler_stick_friction(
                                &c,
                                &fi,
                                &s.velocity,
                                &inertia.mass,
                                friction_dt,
                                &mut sc.force,
                            );
                            sc.idler_torque[k] = d.radius * f;
                        }
                    }
                }
                // Prescribed pulley motion with a limited torque: a brake holds at rest, a
                // speed-controlled drive to its curve (a pulley has at most one of them).
                Stage::SpeedDrives | Stage::Brakes => {
                    if effects.drives {
                        let brakes = stage == Stage::Brakes;
                        for (j, p) in m.pulleys.iter().enumerate() {
                            let hold = if brakes {
                                p.brake_hold(s.time)
                            } else {
                                p.speed_hold(s.time, dt)
                            };
                            let Some(hold) = hold else {
                                continue;
                            };
                            let (torque, holds) = match sc.friction[j].held_torque {
                                // Solved with the belt friction.
                                Some(t) => (t, sc.friction[j].holds),
                                // Torque that gives the prescribed speed this step, within
                                // the capacity (a brake never reverses the motion).
                                None => {
                                    let other = sc.drive_torque[j] + sc.friction[j].torque;
                                    hold.limit(
                                        p.inertia * hold.alpha(s.pulley_omega[j], dt) - other,
                                    )
                                }
                            };
                            if brakes {
                                sc.brake_torque[j] = torque;
                            } else {
                                // The motor's torque adds to the drive's load torque −b·ω.
                                sc.drive_torque[j] += torque;
                            }
                            if holds {
                                sc.held[j] = Some(hold.omega);
                            }
                        }
                    }
                }
                Stage::Takeups => {}
            }
            if let (Some(t0), Some(profile)) = (started, self.profile.as_mut()) {
                profile[k] += t0.elapsed().as_secs_f64();
            }
        }
    }

    /// Central-difference update (thesis eq. 4.59–4.60, 4.62, 4.64–4.65).
    fn integrate(&mut self) -> BeltResult<()> {
        self.integrate_then(None)
    }

    /// [`Simulation::integrate`]; with `Some(tensions)`, the next step's axial pass
    /// ([`forces::axial_pass`], all effects on) is fused into the node loop: each node is
    /// moved and then used at once for its elements, one sweep over the nodes instead of
    /// two, the same operations on the same values (so the same bits). The element
    /// tensions are written only if `tensions`. The caller then runs
    /// [`Simulation::evaluate_after`] with `axial_done`.
    fn integrate_then(&mut self, axial: Option<bool>) -> BeltResult<()> {
        let m = &self.model;
        let s = &mut self.state;
        let sc = &mut self.scratch;
        let dt = m.dt;
        let (x, v) = (&mut s.position, &mut s.velocity);
        let f = Cell::from_mut(sc.force.as_mut_slice()).as_slice_of_cells();
        let next =
            axial.map(|tensions| (m.axial_belt(Effects::ALL.damping, &s.node_mass), tensions));
        let tension = &mut sc.tension;
        let nodes_finite = match self.inertia.same_inv_mass {
            Some(im) => Self::integrate_nodes(x, v, f, std::iter::repeat(im), dt, next, tension),
            None => Self::integrate_nodes(
                x,
                v,
                f,
                self.inertia.inv_mass.iter().copied(),
                dt,
                next,
                tension,
            ),
        };
        let sc = &self.scratch;
        let mut check = 0.0;
        for (j, p) in m.pulleys.iter().enumerate() {
            let torque = sc.pulley_torque(j);
            let old = s.pulley_omega[j];
            // A holding brake stops the pulley this step, a speed-controlled drive within its
            // limit puts it on its curve; say so exactly.
            let new = match sc.held[j] {
                Some(omega) => omega,
                None => old + dt * torque / p.inertia,
            };
            s.drive_work += sc.drive_torque[j] * 0.5 * (old + new) * dt;
            s.pulley_omega[j] = new;
            s.pulley_angle[j] += new * dt;
            check += new + s.pulley_angle[j];
            if let Some(t) = &p.takeup {
                let f = sc.takeup_force(j, t);
                s.takeup_speed[j] += dt * f / self.inertia.takeup_mass[j];
                s.takeup_travel[j] += dt * s.takeup_speed[j];
                if s.takeup_travel[j] < t.travel_min {
                    s.takeup_travel[j] = t.travel_min;
                    s.takeup_speed[j] = s.takeup_speed[j].max(0.0);
                } else if s.takeup_travel[j] > t.travel_max {
                    s.takeup_travel[j] = t.travel_max;
                    s.takeup_speed[j] = s.takeup_speed[j].min(0.0);
                }
                check += s.takeup_travel[j] + s.takeup_speed[j];
            }
        }
        for (k, d) in m.idlers.iter().enumerate() {
            s.idler_omega[k] += dt * sc.idler_torque[k] / d.inertia;
            check += s.idler_omega[k];
        }
        s.time += dt;
        s.step += 1;
        check += s.drive_work;
        if !(nodes_finite && check.is_finite()) {
            return Err(self.locate_non_finite());
        }
        Ok(())
    }

    /// Central differences on the nodes: v ← v + Δt·f/m, x ← x + Δt·v, and then, with
    /// `next` = Some((belt, tensions)), the axial pass of the new state on each node as it
    /// moves ([`Simulation::integrate_then`]). Returns whether every new position is finite.
    #[inline(always)]
    fn integrate_nodes(
        x: &mut [V2],
        v: &mut [V2],
        f: &[Cell<V2>],
        inv_mass: impl Iterator<Item = f64>,
        dt: f64,
        next: Option<(forces::AxialBelt, bool)>,
        tension: &mut [f64],
    ) -> bool {
        let nodes = Moving {
            nodes: x.iter_mut().zip(v.iter_mut()).zip(f),
            inv_mass,
            dt,
            finite: AllFinite::new(),
        };
        let moved = match next {
            None => {
                let mut nodes = nodes;
                nodes.by_ref().for_each(drop);
                nodes
            }
            Some((belt, true)) => forces::axial_pass(&belt, nodes, &mut &mut *tension, f),
            Some((belt, false)) => forces::axial_pass(&belt, nodes, &mut forces::NoTensions, f),
        };
        moved.finite.all()
    }

    fn locate_non_finite(&self) -> BeltError {
        let s = &self.state;
        let diverged = |quantity: &str, location: String| BeltError::Diverged {
            time: s.time,
            step: s.step,
            quantity: quantity.to_string(),
            location,
        };
        for i in 0..self.model.nodes {
            let (x, v) = (s.position[i], s.velocity[i]);
            // No force check: a non-finite force makes the node's new velocity non-finite
            // (f·Δt/m is infinite or NaN, and so is v + it), so a force was never the first
            // non-finite quantity found; and after a fused integration the force array
            // already holds the next step's axial forces.
            let checks = [
                ("position x", x.x),
                ("position y", x.y),
                ("velocity x", v.x),
                ("velocity y", v.y),
            ];
            for (q, val) in checks {
                if !val.is_finite() {
                    let e = if i == 0 { self.model.nodes - 1 } else { i - 1 };
                    return diverged(q, format!("node {i} (between elements {e} and {i})"));
                }
            }
        }
        for (j, p) in self.model.pulleys.iter().enumerate() {
            if !s.pulley_omega[j].is_finite() {
                return diverged("angular speed", format!("pulley {}", p.name));
            }
            if !s.pulley_angle[j].is_finite() {
                return diverged("rotation angle", format!("pulley {}", p.name));
            }
            if !s.takeup_travel[j].is_finite() || !s.takeup_speed[j].is_finite() {
                return diverged("takeup travel", format!("pulley {}", p.name));
            }
        }
        for k in 0..self.model.idlers.len() {
            if !s.idler_omega[k].is_finite() {
                return diverged("angular speed", format!("idler {k}"));
            }
        }
        if !s.drive_work.is_finite() {
            return diverged("work done", "the drives".to_string());
        }
        diverged("energy", "the model".to_string())
    }

    /// Advance `steps` steps without recording.
    pub fn step(&mut self, steps: u64) -> BeltResult<()> {
        self.steps_with(steps, false, |_| Ok(()))
    }

    /// `steps` steps of: evaluate all forces, `between` (e.g. record), integrate. Unless
    /// profiling (which times the axial stage on its own), each integration but the last
    /// is fused with the next step's axial pass ([`Simulation::integrate_then`]): the same
    /// arithmetic in one sweep over the nodes instead of two. Each call starts with a
    /// complete evaluation, so nothing carries over between calls (a changed scene or
    /// state, a relaxation or a checkpoint in between sees the usual forces). Element
    /// tensions are written only if `tensions`. A scene with material loads is not fused:
    /// its loads stage changes node masses before the axial pass adds the weights.
    fn steps_with(
        &mut self,
        steps: u64,
        tensions: bool,
        mut between: impl FnMut(&mut Self) -> BeltResult<()>,
    ) -> BeltResult<()> {
        let fuse = self.profile.is_none() && self.model.loads.is_empty();
        let mut axial_done = false;
        for k in 0..steps {
            // Between whole steps only: an interrupted call leaves a consistent state (the
            // fused axial pass is redone by the next call's complete evaluation).
            crate::interrupt::check(self.model.nodes as u64)?;
            self.evaluate_after(Effects::ALL, axial_done);
            between(self)?;
            axial_done = fuse && k + 1 < steps;
            self.integrate_then(axial_done.then_some(tensions))?;
        }
        Ok(())
    }

    /// Start a new recording: the state is sampled now and every `every` steps, keeping at
    /// most `max_samples` instants (≥ 2). When the buffer is full, every other instant is
    /// dropped and the interval doubles ([`Recording::decimate`]), so the recording always
    /// spans the whole run on a uniform grid and its memory stays below
    /// `max_samples × Recording::bytes_per_sample()`.
    pub fn begin_recording(&mut self, channels: Channels, every: u64, max_samples: usize) {
        self.recording = Recording::new(
            channels,
            self.model.nodes,
            self.model.pulleys.len(),
            self.model.idlers.len(),
        );
        self.record_every = every.max(1);
        self.record_counter = 0;
        self.max_samples = max_samples.max(2);
    }

    /// Steps between recorded instants now (the requested interval, doubled at each
    /// decimation).
    pub fn record_every(&self) -> u64 {
        self.record_every
    }

    /// Bound on the number of recorded instants of the current recording.
    pub fn max_samples(&self) -> usize {
        self.max_samples
    }

    /// Sample if the step counter is on the recording grid, decimating first when full.
    fn record_if_due(&mut self) -> BeltResult<()> {
        if !self.record_counter.is_multiple_of(self.record_every) {
            return Ok(());
        }
        if self.recording.len() >= self.max_samples {
            self.recording.decimate();
            self.record_every = self.record_every.saturating_mul(2);
            if !self.record_counter.is_multiple_of(self.record_every) {
                return Ok(());
            }
        }
        self.recording.reserve_one(self.max_samples);
        self.sample();
        // A finite state can still give non-finite derived values (energies of nodes
        // 10^157 m away, forces of an absurd gravity): the run stops, and the recording
        // keeps only finite rows.
        if let Some((quantity, part)) = self.recording.last_row_non_finite() {
            self.recording.pop_row();
            return Err(self.non_finite_sample(quantity, part));
        }
        Ok(())
    }

    /// Advance `steps` steps, recording as set by [`Simulation::begin_recording`]. On a
    /// blow-up the recording keeps everything sampled before it.
    pub fn advance(&mut self, steps: u64) -> BeltResult<()> {
        self.steps_with(steps, true, |sim| {
            sim.record_if_due()?;
            sim.record_counter += 1;
            Ok(())
        })
    }

    /// Close a recording: sample the final state if it falls on the recording grid. A
    /// non-finite sample is not kept and gives [`BeltError::Diverged`].
    pub fn end_recording(&mut self) -> BeltResult<()> {
        if self.record_counter.is_multiple_of(self.record_every) {
            self.evaluate(Effects::ALL);
            self.record_if_due()?;
        }
        Ok(())
    }

    /// The divergence error for a sample whose recorded `quantity` of `part` is not
    /// finite: the first non-finite state value if there is one, else the first non-finite
    /// node force (a finite state with forces that overflow), else the recorded value.
    fn non_finite_sample(&self, quantity: String, part: crate::record::Part) -> BeltError {
        use crate::record::Part;
        let state_error = self.locate_non_finite();
        if let BeltError::Diverged { ref quantity, .. } = state_error {
            if quantity != "energy" {
                return state_error;
            }
        }
        let (quantity, location) = match self
            .scratch
            .force
            .iter()
            .enumerate()
            .find(|(_, f)| !(f.x.is_finite() && f.y.is_finite()))
        {
            Some((i, f)) => (
                format!("force {}", if f.x.is_finite() { "y" } else { "x" }),
                format!("node {i}"),
            ),
            None => {
                let s = &self.state;
                let argmax = |key: &dyn Fn(usize) -> f64| {
                    (0..self.model.nodes).max_by(|&a, &b| key(a).total_cmp(&key(b)))
                };
                // An energy overflows where its density is largest: name that node.
                let half = 0.5 * self.model.dt;
                let spinning = self.model.pulleys.iter().enumerate().position(|(j, p)| {
                    let w = s.pulley_omega[j] + half * self.scratch.pulley_torque(j) / p.inertia;
                    !(0.5 * p.inertia * w * w).is_finite()
                });
                let part = match quantity.as_str() {
                    "kinetic energy" if spinning.is_some() => spinning.map_or(part, Part::Pulley),
                    "kinetic energy" => argmax(&|i| s.velocity[i].norm()).map_or(part, Part::Node),
                    "gravity energy" => argmax(&|i| s.position[i].y.abs()).map_or(part, Part::Node),
                    "strain energy" => {
                        argmax(&|i| (s.position[(i + 1) % self.model.nodes] - s.position[i]).norm())
                            .map_or(part, Part::Element)
                    }
                    _ => part,
                };
                let location = match part {
                    Part::Node(i) => format!("node {i}"),
                    Part::Element(i) => format!("element {i}"),
                    Part::Pulley(j) => format!("pulley {}", self.model.pulleys[j].name),
                    Part::Idler(k) => format!("idler {k}"),
                    Part::Model => "the model".to_string(),
                };
                (quantity, location)
            }
        };
        BeltError::Diverged {
            time: self.state.time,
            step: self.state.step,
            quantity,
            location,
        }
    }

    /// Run for `duration` seconds (rounded to whole steps), sampling every `every` steps.
    /// The recording is unbounded here; use [`Simulation::begin_recording`] with a bound for
    /// long runs.
    pub fn run(&mut self, duration: f64, every: u64, channels: Channels) -> BeltResult<&Recording> {
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(BeltError::invalid(
                "duration",
                duration,
                "must be a finite number ≥ 0",
            ));
        }
        let steps = (duration / self.model.dt).round() as u64;
        self.begin_recording(channels, every, usize::MAX);
        self.advance(steps)?;
        self.end_recording()?;
        Ok(&self.recording)
    }

    /// Energies at the current state; call right after `evaluate` (uses the accelerations
    /// to centre the half-step velocities on t).
    fn energies(&self) -> Energies {
        let m = &self.model;
        let s = &self.state;
        let sc = &self.scratch;
        let half = 0.5 * m.dt;
        let mut e = Energies {
            drive_work: s.drive_work,
            ..Default::default()
        };
        let n = m.nodes;
        for i in 0..n {
            let v = s.velocity[i] + sc.force[i] * (half * self.inertia.inv_mass[i]);
            e.kinetic += 0.5 * s.node_mass[i] * v.norm_squared();
            if m.gravity > 0.0 {
                e.gravity += s.node_mass[i] * m.gravity * s.position[i].y;
            }
            let j = (i + 1) % n;
            let stretch = (s.position[j] - s.position[i]).norm() - m.rest_length[i];
            if !(m.tension_only && stretch < 0.0) {
                e.strain += 0.5 * m.axial_stiffness[i] * stretch * stretch;
            }
        }
        if m.has_stage(Stage::Bending) {
            for i in 0..n {
                let theta = forces::bending_angle(&s.position, i);
                e.bending += 0.5 * m.bending_stiffness[i] * theta * theta;
            }
        }
        for (j, p) in m.pulleys.iter().enumerate() {
            let torque = sc.pulley_torque(j);
            let w = s.pulley_omega[j] + half * torque / p.inertia;
            e.kinetic += 0.5 * p.inertia * w * w;
            if let Some(t) = &p.takeup {
                let f = sc.takeup_force(j, t);
                let u = s.takeup_speed[j] + half * f / self.inertia.takeup_mass[j];
                e.kinetic += 0.5 * t.moving_mass * u * u;
                e.gravity -= t.pull * s.takeup_travel[j];
            }
            for (&d, k) in sc.contacts[j]
                .penetration
                .iter()
                .zip(std::iter::repeat(p.contact_stiffness))
            {
                e.contact += 0.5 * k * d * d;
            }
        }
        for (k, d) in m.idlers.iter().enumerate() {
            let w = s.idler_omega[k] + half * sc.idler_torque[k] / d.inertia;
            e.kinetic += 0.5 * d.inertia * w * w;
            // Every part pressing on the roll, as the force counts them (not only the
            // deepest).
            e.contact += sc.idler_contacts[k].energy;
        }
        e
    }

    /// Energies of the current state, J (evaluates the forces once).
    pub fn current_energies(&mut self) -> Energies {
        self.evaluate(Effects::ALL);
        self.energies()
    }

    /// Append the current state to the recording; call right after `evaluate`.
    fn sample(&mut self) {
        let e = self.energies();
        let m = &self.model;
        let s = &self.state;
        let sc = &self.scratch;
        let r = &mut self.recording;
        let half = 0.5 * m.dt;
        r.time.push(s.time);
        if r.channels.tension {
            r.tension.extend_from_slice(&sc.tension);
        }
        if r.channels.node_position {
            for x in &s.position {
                r.node_position.extend_from_slice(&[x.x, x.y]);
            }
        }
        if r.channels.node_velocity {
            for (v, (f, im)) in s
                .velocity
                .iter()
                .zip(sc.force.iter().zip(&self.inertia.inv_mass))
            {
                let w = v + f * (half * im);
                r.node_velocity.extend_from_slice(&[w.x, w.y]);
            }
        }
        for (j, p) in m.pulleys.iter().enumerate() {
            let c = s.pulley_center(m, j);
            r.pulley_position.extend_from_slice(&[c.x, c.y]);
            r.takeup_travel.push(s.takeup_travel[j]);
            let torque = sc.pulley_torque(j);
            r.pulley_speed
                .push(s.pulley_omega[j] + half * torque / p.inertia);
            r.friction_torque.push(sc.friction[j].torque);
            r.drive_torque.push(sc.drive_torque[j]);
            r.brake_torque.push(sc.brake_torque[j]);
            r.pulley_force
                .extend_from_slice(&[sc.pulley_force[j].x, sc.pulley_force[j].y]);
            r.normal_force
                .push(sc.contacts[j].normal_force.iter().sum());
            r.friction_force.push(sc.friction[j].tangential);
            r.contact_nodes.push(sc.contacts[j].len() as f64);
            r.slipping_nodes.push(sc.friction[j].slipping as f64);
        }
        for (k, d) in m.idlers.iter().enumerate() {
            let c = &sc.idler_contacts[k];
            r.idler_force
                .push(if c.active { c.normal_force } else { 0.0 });
            r.idler_speed
                .push(s.idler_omega[k] + half * sc.idler_torque[k] / d.inertia);
        }
        r.energy.extend_from_slice(&[
            e.kinetic,
            e.strain,
            e.bending,
            e.gravity,
            e.contact,
            e.total(),
            e.drive_work,
        ]);
    }

    /// Largest out-of-balance force on a node or takeup relative to the largest tension.
    fn residual(&self) -> f64 {
        let sc = &self.scratch;
        let mut worst = sc.force.iter().map(|f| f.norm()).fold(0.0, f64::max);
        for (j, p) in self.model.pulleys.iter().enumerate() {
            if let Some(t) = &p.takeup {
                worst = worst.max(sc.takeup_force(j, t).abs());
            }
        }
        let scale = sc
            .tension
            .iter()
            .map(|t| t.abs())
            .fold(0.0, f64::max)
            .max(
                self.model
                    .mass
                    .iter()
                    .fold(0.0, |a: f64, &m| a.max(m * self.model.gravity)),
            )
            .max(f64::MIN_POSITIVE);
        worst / scale
    }

    /// Relax to static equilibrium (thesis §6.2). Drives and brakes are off; friction is
    /// off unless `options.friction`. Both methods run on fictitious masses m̃ = K·Δt²
    /// (Underwood's dynamic relaxation), since time is not physical here; gravity still acts
    /// on the true masses. Simulated time does not advance. On return all velocities are zero.
    ///
    /// Stiff contact makes the relaxation ill-conditioned (the slow takeup mode moves the
    /// contact nodes, whose fictitious masses scale with the contact stiffness). When the
    /// contact is more than [`CONTINUATION_START`]× stiffer than the stiffest belt element,
    /// the relaxation is continued in contact stiffness: it starts at that ratio and
    /// multiplies the stiffness by [`CONTINUATION_FACTOR`] per stage up to the scene's
    /// value, each stage starting from the previous equilibrium. The report sums the steps.
    pub fn stabilise(&mut self, options: &StabiliseOptions) -> BeltResult<StabiliseReport> {
        if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
            return Err(BeltError::invalid(
                "tolerance",
                options.tolerance,
                "must be > 0",
            ));
        }
        let ladder = self.contact_continuation();
        if ladder.is_empty() {
            return self.relax(options);
        }
        let full = self.model.clone();
        let stages = self.relax_softened(&full.scene, &ladder, options);
        // Back to the scene's own stiffness, whatever the softened stages did.
        self.model = full;
        self.scratch = Scratch::new(&self.model);
        self.inertia = Inertia::physical(&self.model, &self.state.node_mass);
        let mut total = stages?;
        let remaining = options.max_steps - total.steps;
        // Converged only once the scene's own stiffness has relaxed too.
        if total.converged {
            total.converged = false;
            if remaining > 0 {
                let r = self.relax(&StabiliseOptions {
                    max_steps: remaining,
                    ..*options
                })?;
                total.then(r);
            }
        }
        Ok(total)
    }

    /// Relax at each contact-stiffness `scales` of `scene` in turn, each stage from the
    /// previous one's equilibrium, stopping at the first that does not converge. Leaves the
    /// softened model in place (the caller restores the scene's own).
    fn relax_softened(
        &mut self,
        scene: &Scene,
        scales: &[f64],
        options: &StabiliseOptions,
    ) -> BeltResult<StabiliseReport> {
        let mut total = StabiliseReport {
            steps: 0,
            residual: f64::INFINITY,
            converged: false,
            resets: 0,
            interrupted: false,
        };
        for &scale in scales {
            self.model = Model::compile(&soften_contact(scene, scale))?;
            self.scratch = Scratch::new(&self.model);
            let r = self.relax(&StabiliseOptions {
                max_steps: options.max_steps - total.steps,
                ..*options
            })?;
            total.then(r);
            if !r.converged {
                break;
            }
        }
        Ok(total)
    }

    /// Contact-stiffness scales (< 1) of the continuation stages, softest first; empty if
    /// the contact is not much stiffer than the belt.
    fn contact_continuation(&self) -> Vec<f64> {
        let m = &self.model;
        let stiffest_contact = m
            .pulleys
            .iter()
            .map(|p| p.contact_stiffness)
            .chain(m.idlers.iter().map(|d| d.contact_stiffness))
            .fold(0.0, f64::max);
        let stiffest_element = m
            .axial_stiffness
            .iter()
            .zip(&m.rest_length)
            .map(|(ea, l)| ea / l)
            .fold(0.0, f64::max);
        // At most CONTINUATION_STAGES stages: an absurdly soft belt (EA → 0) must not ask
        // for an endless ladder (found by the fuzzer: EA = 5e-324 allocated without end).
        let floor = CONTINUATION_FACTOR.powi(-CONTINUATION_STAGES);
        let start = (CONTINUATION_START * stiffest_element / stiffest_contact).max(floor);
        let mut ladder = Vec::new();
        let mut scale = start;
        while scale < 1.0 / CONTINUATION_FACTOR.sqrt() {
            ladder.push(scale);
            scale *= CONTINUATION_FACTOR;
        }
        ladder
    }

    /// One relaxation at the current model's stiffnesses.
    fn relax(&mut self, options: &StabiliseOptions) -> BeltResult<StabiliseReport> {
        let (time, step) = (self.state.time, self.state.step);
        let effects = Effects {
            friction: options.friction,
            drives: false,
            quasi_static_friction: true,
            damping: false,
        };
        self.state.zero_velocities();
        self.inertia = Inertia::scaled(&self.model);
        let result = match options.method {
            Relaxation::KineticEnergy => self.relax_kinetic(effects, options),
            Relaxation::Fire => self.relax_fire(effects, options),
        };
        self.inertia = Inertia::physical(&self.model, &self.state.node_mass);
        self.state.zero_velocities();
        self.state.time = time;
        self.state.step = step;
        result
    }

    fn relax_kinetic(
        &mut self,
        effects: Effects,
        options: &StabiliseOptions,
    ) -> BeltResult<StabiliseReport> {
        let mut resets = 0;
        let mut residual = f64::INFINITY;
        for k in 0..options.max_steps {
            crate::interrupt::report(k);
            if crate::interrupt::check(self.model.nodes as u64).is_err() {
                return Ok(StabiliseReport {
                    steps: k,
                    residual,
                    converged: false,
                    resets,
                    interrupted: true,
                });
            }
            self.evaluate(effects);
            if k.is_multiple_of(32) {
                residual = self.residual();
                if residual < options.tolerance {
                    return Ok(StabiliseReport {
                        steps: k,
                        residual,
                        converged: true,
                        resets,
                        interrupted: false,
                    });
                }
            }
            // Thesis §6.2 zeroes every velocity at a peak of the total kinetic energy. With
            // stiff contact the total is dominated by fast contact modes and the global
            // reset stalls the slow ones, so each degree of freedom is reset at its own
            // kinetic-energy peak (where its power F·v turns negative).
            resets += self.reset_at_local_peaks();
            self.limit_relaxation_move();
            self.integrate()?;
        }
        Ok(StabiliseReport {
            steps: options.max_steps,
            residual,
            converged: false,
            resets,
            interrupted: false,
        })
    }

    fn reset_at_local_peaks(&mut self) -> u64 {
        let s = &mut self.state;
        let sc = &self.scratch;
        let mut resets = 0;
        for (v, f) in s.velocity.iter_mut().zip(&sc.force) {
            if v.dot(f) < 0.0 {
                *v = V2::zeros();
                resets += 1;
            }
        }
        for (j, p) in self.model.pulleys.iter().enumerate() {
            if let Some(t) = &p.takeup {
                let f = sc.takeup_force(j, t);
                if s.takeup_speed[j] * f < 0.0 {
                    s.takeup_speed[j] = 0.0;
                    resets += 1;
                }
            }
            let t = sc.pulley_torque(j);
            if s.pulley_omega[j] * t < 0.0 {
                s.pulley_omega[j] = 0.0;
                resets += 1;
            }
        }
        for (w, t) in s.idler_omega.iter_mut().zip(&sc.idler_torque) {
            if *w * t < 0.0 {
                *w = 0.0;
                resets += 1;
            }
        }
        resets
    }

    fn relax_fire(
        &mut self,
        effects: Effects,
        options: &StabiliseOptions,
    ) -> BeltResult<StabiliseReport> {
        const N_MIN: u32 = 5;
        const F_INC: f64 = 1.1;
        const F_DEC: f64 = 0.5;
        const ALPHA_START: f64 = 0.1;
        const F_ALPHA: f64 = 0.99;
        let dt0 = self.model.dt;
        // The scaled masses put every degree of freedom at ωΔt ≤ 1 for Δt = dt0; allow
        // FIRE to grow the step up to 1.5·dt0 (still below the limit ωΔt = 2).
        let dt_max = 1.5 * dt0;
        let mut dt = dt0;
        let mut alpha = ALPHA_START;
        let mut positive = 0u32;
        let mut resets = 0;
        let mut residual = f64::INFINITY;
        let mut result = Ok(());
        for k in 0..options.max_steps {
            crate::interrupt::report(k);
            if crate::interrupt::check(self.model.nodes as u64).is_err() {
                return Ok(StabiliseReport {
                    steps: k,
                    residual,
                    converged: false,
                    resets,
                    interrupted: true,
                });
            }
            self.evaluate(effects);
            if k.is_multiple_of(32) {
                residual = self.residual();
                if residual < options.tolerance {
                    self.model.dt = dt0;
                    return Ok(StabiliseReport {
                        steps: k,
                        residual,
                        converged: true,
                        resets,
                        interrupted: false,
                    });
                }
            }
            // FIRE mixing on the node and takeup velocities (pulleys spin only by friction).
            let (power, vnorm2, fnorm2) = self.fire_norms();
            if power > 0.0 {
                let mix = alpha * (vnorm2 / fnorm2.max(f64::MIN_POSITIVE)).sqrt();
                self.fire_mix(1.0 - alpha, mix);
                positive += 1;
                if positive > N_MIN {
                    dt = (dt * F_INC).min(dt_max);
                    alpha *= F_ALPHA;
                }
            } else {
                self.state.zero_velocities();
                resets += 1;
                positive = 0;
                dt = (dt * F_DEC).max(dt0);
                alpha = ALPHA_START;
            }
            self.model.dt = dt;
            self.limit_relaxation_move();
            let step = self.integrate();
            self.model.dt = dt0;
            if let Err(e) = step {
                result = Err(e);
                break;
            }
        }
        self.model.dt = dt0;
        result?;
        Ok(StabiliseReport {
            steps: options.max_steps,
            residual,
            converged: false,
            resets,
            interrupted: false,
        })
    }

    /// Relaxation moves are fictitious and can build up speed; a node that moved further
    /// than a quarter of the smallest idler radius, pulley radius or element length in one
    /// step could tunnel through a roll (centre-line contact only sees penetration). Scale
    /// the node's velocity so that its next move (after the coming force update) stays
    /// within that bound.
    fn limit_relaxation_move(&mut self) {
        let m = &self.model;
        let cap = 0.25 * m.relaxation_move_limit;
        let dt = m.dt;
        let s = &mut self.state;
        for ((v, f), im) in s
            .velocity
            .iter_mut()
            .zip(&self.scratch.force)
            .zip(&self.inertia.inv_mass)
        {
            let next = *v + f * (dt * im);
            let step = next.norm() * dt;
            if step > cap {
                *v = next * (cap / step) - f * (dt * im);
            }
        }
    }

    /// FIRE works in mass-weighted coordinates (p = √m̃·v, g = F/√m̃), so that mixing the
    /// velocity towards the force never puts a light degree of freedom out of step.
    /// Returns (power F·v, |p|², |g|²).
    fn fire_norms(&self) -> (f64, f64, f64) {
        let s = &self.state;
        let sc = &self.scratch;
        let (mut p, mut vv, mut ff) = (0.0, 0.0, 0.0);
        for ((v, f), m) in s.velocity.iter().zip(&sc.force).zip(&self.inertia.mass) {
            p += v.dot(f);
            vv += m * v.norm_squared();
            ff += f.norm_squared() / m;
        }
        for (j, pl) in self.model.pulleys.iter().enumerate() {
            if let Some(t) = &pl.takeup {
                let f = sc.takeup_force(j, t);
                let v = s.takeup_speed[j];
                let m = self.inertia.takeup_mass[j];
                p += v * f;
                vv += m * v * v;
                ff += f * f / m;
            }
        }
        for (j, pl) in self.model.pulleys.iter().enumerate() {
            let (w, t) = (s.pulley_omega[j], sc.pulley_torque(j));
            p += w * t;
            vv += pl.inertia * w * w;
            ff += t * t / pl.inertia;
        }
        for (k, d) in self.model.idlers.iter().enumerate() {
            let (w, t) = (s.idler_omega[k], sc.idler_torque[k]);
            p += w * t;
            vv += d.inertia * w * w;
            ff += t * t / d.inertia;
        }
        (p, vv, ff)
    }

    /// p ← keep·p + mix·g in mass-weighted coordinates: v ← keep·v + mix·F/m̃.
    fn fire_mix(&mut self, keep: f64, mix: f64) {
        let s = &mut self.state;
        let sc = &self.scratch;
        for ((v, f), im) in s
            .velocity
            .iter_mut()
            .zip(&sc.force)
            .zip(&self.inertia.inv_mass)
        {
            *v = *v * keep + f * (mix * im);
        }
        for (j, pl) in self.model.pulleys.iter().enumerate() {
            if let Some(t) = &pl.takeup {
                let f = sc.takeup_force(j, t);
                s.takeup_speed[j] =
                    s.takeup_speed[j] * keep + f * mix / self.inertia.takeup_mass[j];
            }
        }
        for (j, pl) in self.model.pulleys.iter().enumerate() {
            let t = sc.pulley_torque(j);
            s.pulley_omega[j] = s.pulley_omega[j] * keep + t * mix / pl.inertia;
        }
        for (k, d) in self.model.idlers.iter().enumerate() {
            s.idler_omega[k] = s.idler_omega[k] * keep + sc.idler_torque[k] * mix / d.inertia;
        }
    }

    /// Forces at the current state without stepping (for inspection and tests).
    pub fn forces(&mut self) -> &[V2] {
        self.evaluate(Effects::ALL);
        &self.scratch.force
    }

    /// Element tensions at the current state, N.
    pub fn tensions(&mut self) -> &[f64] {
        self.evaluate(Effects::ALL);
        &self.scratch.tension
    }

    /// Number of pulley contacts that slip at the current state (all effects on).
    pub fn slipping_contacts(&mut self) -> usize {
        self.evaluate(Effects::ALL);
        self.scratch.friction.iter().map(|f| f.slipping).sum()
    }

    /// Force of the belt on takeup pulley `j` along its takeup line, against the
    /// counterweight, N (0 for a pulley without a takeup). In static equilibrium it equals
    /// the counterweight pull, (counterweight + pulley mass)·g along the line.
    pub fn takeup_force(&mut self, j: usize) -> f64 {
        self.evaluate(Effects::ALL);
        match &self.model.pulleys[j].takeup {
            Some(t) => -t.direction.dot(&self.scratch.pulley_force[j]),
            None => 0.0,
        }
    }
}
