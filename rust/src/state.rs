//! The mutable state of a run: plain arrays that can be copied, saved and restored.

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

/// Everything that changes during a run. Velocities are central-difference half-step
/// values: `velocity` holds v(t − Δt/2) when the state is at time t.
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
}

impl State {
    /// The state at rest on the initial path.
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
        State {
            time: 0.0,
            step: 0,
            velocity: vec![Vector2::zeros(); n],
            position,
            pulley_omega: vec![0.0; model.pulleys.len()],
            pulley_angle: vec![0.0; model.pulleys.len()],
            takeup_travel: vec![0.0; model.pulleys.len()],
            takeup_speed: vec![0.0; model.pulleys.len()],
            idler_omega: vec![0.0; model.idlers.len()],
            pulley_window: vec![ContactWindow::default(); model.pulleys.len()],
            idler_element,
            drive_work: 0.0,
            node_mass,
            load_edges,
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
    }
}
