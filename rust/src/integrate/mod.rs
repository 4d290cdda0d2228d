//! Integrators: how the state moves under the forces of one evaluation
//! ([`crate::pipeline::evaluate`]).
//!
//! - [`central_difference`]: explicit central differences with the automatic stable
//!   step (thesis eq. 4.58–4.65), with the fast path that fuses each node update with the
//!   next step's axial pass.
//! - [`relax`]: static relaxation (FIRE, kinetic-energy damping) with its own step,
//!   fictitious masses and a continuation in contact stiffness.
//! - [`rkf45`]: adaptive Runge–Kutta–Fehlberg 4(5) over a flat state vector and a
//!   derivative callback (Kubas 2014's integrator), and [`adaptive`], which runs it on the
//!   whole layout of a [`crate::Simulation`] ([`Integrator::Rkf45`]).
//!
//! [`Integrator`] is the seam: [`crate::Simulation`] matches on the model's integrator to
//! advance; a new one is a file here, a variant and an arm (docs/architecture.md).

pub mod adaptive;
pub mod central_difference;
pub mod relax;
pub mod rkf45;

use crate::model::Model;
use crate::state::Rigid;

/// The time integrator of a dynamic run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Integrator {
    /// Explicit central differences at the model's stable step (thesis eq. 4.58–4.60).
    #[default]
    CentralDifference,
    /// Adaptive Runge–Kutta–Fehlberg 4(5) with these settings ([`adaptive`]).
    Rkf45(rkf45::Rkf45Params),
}

impl Integrator {
    /// Stable snake_case name (the scene's `solver.integrator`).
    pub fn name(self) -> &'static str {
        match self {
            Integrator::CentralDifference => "central_difference",
            Integrator::Rkf45(_) => "rkf45",
        }
    }

    /// The integrator `scene` asks for.
    pub fn of(scene: &crate::scene::Scene) -> Integrator {
        let s = &scene.solver;
        match s.integrator {
            crate::scene::IntegratorKind::CentralDifference => Integrator::CentralDifference,
            crate::scene::IntegratorKind::Rkf45 => Integrator::Rkf45(rkf45::Rkf45Params {
                relative_tolerance: s.relative_tolerance,
                absolute_tolerance: s.absolute_tolerance,
                ..Default::default()
            }),
        }
    }
}

/// Mass arrays used for inertia: physical for dynamics, scaled for fast relaxation.
#[derive(Debug, Clone)]
pub struct Inertia {
    /// Node masses, kg.
    pub mass: Vec<f64>,
    /// 1 / node mass, 1/kg.
    pub inv_mass: Vec<f64>,
    /// `inv_mass` when every node has the same (a uniform belt in dynamics): the
    /// integration then streams one array less.
    pub same_inv_mass: Option<f64>,
    /// Translating mass of each pulley's takeup, kg (∞ without a takeup).
    pub takeup_mass: Vec<f64>,
    /// Inertia of each rigid belt body about its mass centre, kg·m² (empty for the node
    /// belt): the model's, or the relaxation's fictitious ones.
    pub body_inertia: Vec<f64>,
    /// True for the physical masses (dynamics): the loads stage then keeps `mass` and
    /// `inv_mass` equal to the state's node masses. False for the relaxation's fictitious
    /// masses.
    pub physical: bool,
}

impl Inertia {
    /// The physical masses: `node_mass` (the state's: belt and material).
    pub fn physical(model: &Model, node_mass: &[f64]) -> Inertia {
        let inv_mass: Vec<f64> = node_mass.iter().map(|m| 1.0 / m).collect();
        Inertia {
            mass: node_mass.to_vec(),
            // With loads the masses change during the run: never take them as uniform.
            same_inv_mass: if model.loads.is_empty() {
                crate::forces::all_same(&inv_mass)
            } else {
                None
            },
            inv_mass,
            takeup_mass: model
                .pulleys
                .iter()
                .map(|p| p.takeup.as_ref().map_or(f64::INFINITY, |t| t.moving_mass))
                .collect(),
            // A body carrying material turns with its inertia (`crate::loads::Bodies`).
            body_inertia: (model.body_inertia.iter().enumerate())
                .map(|(i, &inertia)| {
                    crate::loads::body_inertia(inertia, model.mass[i], node_mass[i])
                })
                .collect(),
            physical: true,
        }
    }

    /// Inertia of a rigid degree of freedom (kg or kg·m²).
    #[inline(always)]
    pub fn rigid(&self, model: &Model, d: Rigid) -> f64 {
        match d {
            Rigid::Takeup(j) => self.takeup_mass[j],
            Rigid::Pulley(j) => model.pulleys[j].inertia,
            Rigid::Idler(k) => model.idlers[k].inertia,
            Rigid::Body(i) => self.body_inertia[i],
        }
    }
}

impl crate::pipeline::Scratch {
    /// Generalized force on a rigid degree of freedom from the last evaluation (N or N·m).
    #[inline(always)]
    pub fn rigid_force(&self, model: &Model, d: Rigid) -> f64 {
        match d {
            Rigid::Takeup(j) => match &model.pulleys[j].takeup {
                Some(t) => self.takeup_force(j, t),
                None => 0.0,
            },
            Rigid::Pulley(j) => self.pulley_torque(j),
            Rigid::Idler(k) => self.idler_torque[k],
            Rigid::Body(i) => self.body_torque[i],
        }
    }
}
