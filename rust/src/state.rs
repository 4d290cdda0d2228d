//! The mutable state of a run: plain arrays that can be copied, saved and restored.

use crate::drives::controller::DriveMemory;
use crate::loads::LoadEdges;
use crate::model::Model;
use nalgebra::Vector2;

/// Contiguous run of node indices (circular) that a pulley searches for contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ContactWindow {
    /// First node of the window.
    pub first: usize,
    /// Number of nodes in the window (0: search the whole belt).
    pub len: usize,
}

/// Everything that changes during a run: the generalized coordinates (node positions,
/// pulley angles, takeup travel; layout in [`DofLayout`]), their velocities, and a memory
/// block for effects that need history (contact windows, idler elements, load zones, the
/// drives' work).
///
/// The velocities are the integrator's: with central differences (the only integrator so
/// far) they are half-step values, `velocity` holding v(t − Δt/2) when the state is at
/// time t, so that the scheme needs no second force array. Physical velocities at t are
/// v(t − Δt/2) + a(t)·Δt/2; the recorder and the energies centre them so
/// (`record::sample`). Stages read them as the velocity of the step about to be taken
/// (damping, friction's relative speeds, a speed drive's mid-step target).
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Simulated time, s.
    pub time: f64,
    /// Steps taken since the model was compiled.
    pub step: u64,
    /// Node positions, m.
    pub position: Vec<Vector2<f64>>,
    /// Node velocities at t − Δt/2, m/s.
    pub velocity: Vec<Vector2<f64>>,
    /// Pulley angular speeds at t − Δt/2, rad/s (counter-clockwise positive).
    pub pulley_omega: Vec<f64>,
    /// Pulley rotation angles, rad.
    pub pulley_angle: Vec<f64>,
    /// Takeup travel along its line from the initial centre, m (0 for fixed pulleys).
    pub takeup_travel: Vec<f64>,
    /// Takeup speed along its line at t − Δt/2, m/s.
    pub takeup_speed: Vec<f64>,
    /// Idler angular speeds at t − Δt/2, rad/s.
    pub idler_omega: Vec<f64>,
    /// Contact search window of each pulley.
    pub pulley_window: Vec<ContactWindow>,
    /// Element each idler touched (or was nearest to) last.
    pub idler_element: Vec<usize>,
    /// Work done by drive torques since the start, J.
    pub drive_work: f64,
    /// Node masses now: the belt's plus the material on the node's tributary length, kg
    /// (equal to `Model::mass` without loads).
    pub node_mass: Vec<f64>,
    /// Where each load's zone is (`crate::loads`).
    pub load_edges: Vec<LoadEdges>,
    /// Angle φ of each rigid belt body's axis from the x axis, rad (rigid-body belt; empty
    /// for the node belt). The bodies' mass centres are `position`.
    pub body_angle: Vec<f64>,
    /// Angular speed of each rigid belt body, rad/s, at the velocities' instant (empty for
    /// the node belt).
    pub body_spin: Vec<f64>,
    /// The adaptive integrator's next step, s (0: not yet chosen; unused by central
    /// differences). Part of the state so that a resumed run takes the same steps.
    pub adaptive_step: f64,
    /// Steps the adaptive integrator accepted since the model was compiled.
    pub accepted_steps: u64,
    /// Steps the adaptive integrator rejected (and retried smaller) since the model was
    /// compiled.
    pub rejected_steps: u64,
    /// Speed at which each pulley's deceleration brake began its ramp, rad/s (the pulley's
    /// speed in the first step from its `applied` time); 0 before, and for other pulleys
    /// (`crate::drives::brake`).
    pub brake_ramp: Vec<f64>,
    /// Memory of each pulley's PI speed controller (error integral, lagged torque; zero
    /// for pulleys without one).
    pub drive_memory: Vec<DriveMemory>,
    /// Friction memory: the creep displacement Δ of each (belt point, pulley) pair, m, at
    /// `creep[i * pulleys + j]` (`crate::friction::creep`), reset to 0 when the point
    /// leaves the pulley. Empty unless a pulley has creep friction. An ODE state: the
    /// integrators advance it with the rates of the evaluations (`Scratch::creep_rate`):
    /// central differences by one explicit step, RKF45 as part of its state vector.
    pub creep: Vec<f64>,
    /// Viscoelastic belt (`belt.loss_factor` > 0, `belt::node::zener`): the force of each
    /// element's Maxwell arm, N. Empty otherwise. Advanced exactly after each step.
    pub arm_force: Vec<f64>,
    /// The element lengths the arm forces were advanced to, m (empty with them).
    pub arm_length: Vec<f64>,
    /// Stick-force friction's memory (`crate::friction`): for each pulley, the belt points
    /// that slid on it in the last step, in ascending order. Coulomb's law gives a sliding
    /// contact µk and a contact at rest µs; the next step's solve reads which is which
    /// from here (docs/wrap-contact.md, "Session 10: the drums' stick–slip").
    pub sliding: Vec<Vec<usize>>,
}

impl State {
    /// The state on the initial path: at rest, or moving as a design start says
    /// ([`Model::initial_motion`]).
    pub fn initial(model: &Model) -> State {
        let n = model.nodes;
        let position = model.initial_positions.clone();
        // One global search at start-up; afterwards each idler tracks its element along
        // the strand it supports.
        let idler_element = model
            .idlers
            .iter()
            .map(|d| crate::contact::supported_element(d.center, &position))
            .collect();
        let load_edges = crate::loads::initial_edges(&model.loads, &position, model.load_belt());
        let node_mass =
            crate::loads::node_masses(&model.mass, &model.loads, &load_edges, model.load_belt());
        let motion = model.initial_motion.as_ref();
        State {
            time: 0.0,
            step: 0,
            velocity: motion.map_or_else(|| vec![Vector2::zeros(); n], |m| m.velocity.clone()),
            position,
            pulley_omega: motion.map_or_else(
                || vec![0.0; model.pulleys.len()],
                |m| m.pulley_omega.clone(),
            ),
            pulley_angle: vec![0.0; model.pulleys.len()],
            takeup_travel: vec![0.0; model.pulleys.len()],
            takeup_speed: vec![0.0; model.pulleys.len()],
            idler_omega: motion
                .map_or_else(|| vec![0.0; model.idlers.len()], |m| m.idler_omega.clone()),
            pulley_window: vec![ContactWindow::default(); model.pulleys.len()],
            idler_element,
            drive_work: 0.0,
            node_mass,
            load_edges,
            body_angle: model.initial_angles.clone(),
            body_spin: match motion {
                Some(m) if m.body_spin.len() == model.initial_angles.len() => m.body_spin.clone(),
                _ => vec![0.0; model.initial_angles.len()],
            },
            adaptive_step: 0.0,
            accepted_steps: 0,
            rejected_steps: 0,
            brake_ramp: vec![0.0; model.pulleys.len()],
            drive_memory: vec![DriveMemory::default(); model.pulleys.len()],
            creep: vec![0.0; model.creep_memory_len()],
            arm_force: vec![0.0; model.arm_len()],
            arm_length: if model.zener.is_some() {
                crate::belt::node::zener::lengths(&model.initial_positions, model.elements)
            } else {
                Vec::new()
            },
            sliding: vec![Vec::new(); model.pulleys.len()],
        }
    }

    /// Current centre of pulley `j`, m.
    #[inline]
    pub fn pulley_center(&self, model: &Model, j: usize) -> Vector2<f64> {
        let p = &model.pulleys[j];
        match &p.takeup {
            Some(t) => p.center + t.direction * self.takeup_travel[j],
            None => p.center,
        }
    }

    /// Velocity of the centre of pulley `j` at t − Δt/2, m/s.
    #[inline]
    pub fn pulley_center_velocity(&self, model: &Model, j: usize) -> Vector2<f64> {
        match &model.pulleys[j].takeup {
            Some(t) => t.direction * self.takeup_speed[j],
            None => Vector2::zeros(),
        }
    }

    /// Set every velocity to zero (kinetic-energy damping, thesis §6.2).
    pub fn zero_velocities(&mut self) {
        self.velocity.iter_mut().for_each(|v| *v = Vector2::zeros());
        self.pulley_omega.iter_mut().for_each(|w| *w = 0.0);
        self.takeup_speed.iter_mut().for_each(|w| *w = 0.0);
        self.idler_omega.iter_mut().for_each(|w| *w = 0.0);
        self.body_spin.iter_mut().for_each(|w| *w = 0.0);
    }
}

/// One rigid scalar degree of freedom of the generalized coordinates, after the belt's
/// (the nodes' positions, two per node). Each has a speed in [`State`], a generalized
/// force in the evaluation's outputs and an inertia.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rigid {
    /// Translation of the takeup of pulley `j` along its line (`takeup_travel[j]`,
    /// `takeup_speed[j]`), m.
    Takeup(usize),
    /// Rotation of pulley `j` (`pulley_angle[j]`, `pulley_omega[j]`), rad.
    Pulley(usize),
    /// Rotation of idler `k` (`idler_omega[k]`; its angle is not kept: nothing reads it),
    /// rad.
    Idler(usize),
    /// Rotation of rigid belt body `i` about its mass centre (`body_angle[i]`,
    /// `body_spin[i]`), rad.
    Body(usize),
}

/// The layout of the generalized coordinates: the belt's degrees of freedom (two per
/// node, or per body's mass centre), then the rigid ones in a fixed order (takeups,
/// pulleys, idlers, and the rigid-body belt's body rotations). Integrators,
/// relaxations, energies and diagnostics loop over it once instead of per body kind.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct DofLayout {
    /// Belt nodes (each two degrees of freedom, x and y).
    pub nodes: usize,
    /// The rigid degrees of freedom, in order.
    pub rigid: Vec<Rigid>,
}

impl DofLayout {
    /// The layout of a model with `nodes` nodes, these pulleys (true: it has a takeup)
    /// and `idlers` idlers.
    pub fn new(nodes: usize, takeups: &[bool], idlers: usize) -> DofLayout {
        let rigid = (takeups.iter().enumerate())
            .filter(|(_, &t)| t)
            .map(|(j, _)| Rigid::Takeup(j))
            .chain((0..takeups.len()).map(Rigid::Pulley))
            .chain((0..idlers).map(Rigid::Idler))
            .collect();
        DofLayout { nodes, rigid }
    }

    /// This layout with the rotations of the rigid belt bodies `bodies` (belt point
    /// indices) appended. An open rigid-body belt's end points are points, not bodies:
    /// they have no rotation.
    pub fn with_bodies(mut self, bodies: std::ops::Range<usize>) -> DofLayout {
        self.rigid.extend(bodies.map(Rigid::Body));
        self
    }

    /// The rigid degrees of freedom that drives, brakes, stops or takeups act on (the
    /// takeups and pulleys, first in the order), and the free rotations after them (idlers
    /// and belt bodies: inertia and torque only). The central-difference update moves the
    /// free ones in tight loops of their own: on a long conveyor they are thousands.
    pub fn driven(&self) -> &[Rigid] {
        let free = self
            .rigid
            .iter()
            .position(|d| matches!(d, Rigid::Idler(_) | Rigid::Body(_)))
            .unwrap_or(self.rigid.len());
        &self.rigid[..free]
    }

    /// Number of generalized coordinates.
    pub fn len(&self) -> usize {
        2 * self.nodes + self.rigid.len()
    }

    /// True when there is nothing to move.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl State {
    /// Speed of a rigid degree of freedom (m/s or rad/s, at the state's velocity instant).
    #[inline(always)]
    pub fn rigid_speed(&self, d: Rigid) -> f64 {
        match d {
            Rigid::Takeup(j) => self.takeup_speed[j],
            Rigid::Pulley(j) => self.pulley_omega[j],
            Rigid::Idler(k) => self.idler_omega[k],
            Rigid::Body(i) => self.body_spin[i],
        }
    }

    /// Coordinate (`None` where it is not kept) and speed of a rigid degree of freedom.
    #[inline(always)]
    pub fn rigid(&self, d: Rigid) -> (Option<f64>, f64) {
        match d {
            Rigid::Takeup(j) => (Some(self.takeup_travel[j]), self.takeup_speed[j]),
            Rigid::Pulley(j) => (Some(self.pulley_angle[j]), self.pulley_omega[j]),
            Rigid::Idler(k) => (None, self.idler_omega[k]),
            Rigid::Body(i) => (Some(self.body_angle[i]), self.body_spin[i]),
        }
    }

    /// Mutable speed of a rigid degree of freedom.
    #[inline(always)]
    pub fn rigid_speed_mut(&mut self, d: Rigid) -> &mut f64 {
        match d {
            Rigid::Takeup(j) => &mut self.takeup_speed[j],
            Rigid::Pulley(j) => &mut self.pulley_omega[j],
            Rigid::Idler(k) => &mut self.idler_omega[k],
            Rigid::Body(i) => &mut self.body_spin[i],
        }
    }

    /// Coordinate and speed of a rigid degree of freedom, the coordinate `None` where it is
    /// not kept (idler angles).
    #[inline(always)]
    pub fn rigid_mut(&mut self, d: Rigid) -> (Option<&mut f64>, &mut f64) {
        match d {
            Rigid::Takeup(j) => (Some(&mut self.takeup_travel[j]), &mut self.takeup_speed[j]),
            Rigid::Pulley(j) => (Some(&mut self.pulley_angle[j]), &mut self.pulley_omega[j]),
            Rigid::Idler(k) => (None, &mut self.idler_omega[k]),
            Rigid::Body(i) => (Some(&mut self.body_angle[i]), &mut self.body_spin[i]),
        }
    }
}
