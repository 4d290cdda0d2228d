//! The compiled model: read-only arrays and the list of stages this scene needs.
//!
//! Compilation turns a validated [`Scene`] into per-element and per-node arrays, places the
//! belt on its path, estimates the stable time step and decides which stages run, each
//! part in its own file: [`path`], [`belt`], [`pulleys`], [`idlers`], loads
//! (`crate::loads::compile`), [`stages`], [`stable_step`]. Nothing here changes after
//! compilation (a relaxation keeps its own step and contact scale); the mutable part lives
//! in [`crate::state::State`].

mod belt;
mod belt_rigid;
mod design;
mod design_rigid;
mod idlers;
mod open;
mod path;
mod pulleys;
mod sag;
mod stable_step;
mod stages;

pub use belt::{FRICTION_RATIO_ERROR, RIGID_BODY_ANGLE_FACTOR};
pub use design::InitialMotion;
pub use idlers::IdlerModel;
pub use open::{EndModel, OpenEnds};
pub use pulleys::{PulleyModel, TakeupModel};
pub use stable_step::StableStep;
pub use stages::Stage;

use crate::error::{BeltError, BeltResult};
use crate::forces;
use crate::geometry::BeltPath;
use crate::integrate::Integrator;
use crate::loads::LoadModel;
use crate::scene::{Formulation, Scene};
use crate::state::DofLayout;
use nalgebra::Vector2;

/// Smallest time step a scene may compile to, s. A stable step below it means that a
/// stiffness, damping or mass is out of proportion (usually wrong units): one simulated
/// second would take more than 10⁹ steps, and a step that underflows to zero would never
/// advance time. Such scenes are refused at compile time (docs/runtime.md).
pub const MIN_TIME_STEP: f64 = 1e-9;

/// The read-only compiled model.
#[derive(Debug, Clone)]
pub struct Model {
    /// The scene this model was compiled from.
    pub scene: Scene,
    /// Number of nodes (= number of elements for a closed loop; one more for an open belt).
    /// The rigid-body belt's nodes are its bodies' mass centres, and an open one's two end
    /// points besides (`belt_rigid`).
    pub nodes: usize,
    /// Number of belt elements: `nodes` for a closed loop, `nodes − 1` for an open belt
    /// (whose arrays keep a last entry that is no element).
    pub elements: usize,
    /// The ends of an open belt (node 0 and node n−1); `None` for a closed loop.
    pub ends: Option<OpenEnds>,
    /// Node masses of the belt alone, kg (thesis eq. 4.4). With loads the masses change
    /// during a run: the current ones (belt + material) are `State::node_mass`.
    pub mass: Vec<f64>,
    /// 1 / node mass, 1/kg.
    pub inv_mass: Vec<f64>,
    /// Element rest lengths, m. Element e joins node e and node e+1 (mod n).
    pub rest_length: Vec<f64>,
    /// Element axial stiffness EA/l⁰, N/m (thesis eq. 4.1).
    pub axial_stiffness: Vec<f64>,
    /// Element damping coefficient, N·s/m (thesis eq. 4.3).
    pub axial_damping: Vec<f64>,
    /// Bending spring at each node, N·m/rad: EI / (mean length of the two elements) (eq. 4.11).
    pub bending_stiffness: Vec<f64>,
    /// The common stiffness, damping, rest length and node mass when every element and
    /// node has the same (a uniform belt), else None; the axial pass then reads scalars
    /// instead of four arrays. Compiled from the arrays above: whatever changes them
    /// during a run (e.g. node masses that vary) must recompute it with
    /// [`forces::Uniform::of`].
    pub uniform: Option<forces::Uniform>,
    /// Elements carry no compression.
    pub tension_only: bool,
    /// Wrap contact with the pulleys (`belt.pulley_contact = "wrap"`, `contact::wrap`);
    /// false: nodal contact (the node belt's only).
    pub wrap_contact: bool,
    /// The rigid-body belt's wrap joints (`belt.pulley_contact = "wrap"`,
    /// `belt::rigid::wrap_joint`): each joint where a strand meets a drum measured along the
    /// string's path.
    pub rigid_wrap: bool,
    /// Wrap contact with the idler rolls (`belt.idler_contact = "wrap"`,
    /// `contact::roll_wrap`); false: centre-line segment contact.
    pub roll_wrap: bool,
    /// The belt formulation. With [`Formulation::RigidBody`] the "nodes" are the bodies'
    /// mass centres and the "elements" the joints between them (joint e joins body e and
    /// e+1): `mass`, `rest_length` (body length), `axial_stiffness` and `axial_damping`
    /// (translational SDE c_x = EA/l, b_x), `bending_stiffness` (torsional SDE c_φ = EI/l)
    /// are read per body and per joint (`crate::belt::rigid`).
    pub formulation: Formulation,
    /// Body inertias about their mass centres, kg·m² (rigid-body belt; empty otherwise).
    pub body_inertia: Vec<f64>,
    /// Torsional SDE damping per joint, N·m·s/rad (rigid-body belt; empty otherwise).
    pub torsional_damping: Vec<f64>,
    /// Initial body angles, rad (rigid-body belt; empty otherwise).
    pub initial_angles: Vec<f64>,
    /// Gravitational acceleration, m/s².
    pub gravity: f64,
    /// Pulleys.
    pub pulleys: Vec<PulleyModel>,
    /// Idlers.
    pub idlers: Vec<IdlerModel>,
    /// Bulk material loads.
    pub loads: Vec<LoadModel>,
    /// The initial path round the pulleys (their tangents and wraps).
    pub path: BeltPath,
    /// The path the belt is placed on when a design state gives one (`initial.path`);
    /// `None`: on [`Model::path`].
    pub placement: Option<BeltPath>,
    /// Initial node positions, m.
    pub initial_positions: Vec<Vector2<f64>>,
    /// Initial speeds of a design start (`scene.initial`); `None`: at rest.
    pub initial_motion: Option<InitialMotion>,
    /// Stages this scene runs, in order.
    pub stages: Vec<Stage>,
    /// Some pulley has a PI speed controller or a fluid-coupled motor, whose memory the
    /// integrator advances after each step (`crate::drives::controller::advance_all`,
    /// `crate::drives::motor::advance_all`).
    pub has_drive_memory: bool,
    /// The time integrator of dynamic runs.
    pub integrator: Integrator,
    /// Layout of the generalized coordinates (belt nodes, then takeups, pulleys, idlers).
    pub dofs: DofLayout,
    /// Time step in use, s.
    pub dt: f64,
    /// Estimated critical (stability-limit) time step, s.
    pub dt_limit: f64,
    /// Which term sets the limit.
    pub dt_cause: String,
    /// Gershgorin bound of the stiffness seen by each node, N/m.
    pub node_stiffness_bound: Vec<f64>,
    /// Same bound for each takeup's translation, N/m (0 for fixed pulleys).
    pub takeup_stiffness_bound: Vec<f64>,
    /// Smallest idler radius, pulley radius or element length, m: the static relaxation
    /// moves no node by more than a quarter of it per step.
    pub relaxation_move_limit: f64,
    /// The viscoelastic (Zener) arm of every element (`belt.loss_factor` > 0,
    /// `belt::node::zener`); `None`: Kelvin-Voigt elements only.
    pub zener: Option<crate::belt::node::zener::Zener>,
}

impl Model {
    /// The axial elements and node weights as the axial pass reads them: Kelvin-Voigt
    /// elements if the model has the damped stage and `damping` is on, weights if the
    /// scene has gravity.
    pub fn axial_belt<'a>(&'a self, damping: bool, node_mass: &'a [f64]) -> forces::AxialBelt<'a> {
        forces::AxialBelt {
            stiffness: &self.axial_stiffness,
            damping: &self.axial_damping,
            rest_length: &self.rest_length,
            mass: node_mass,
            uniform: self.uniform,
            damped: damping && self.has_stage(Stage::AxialDamped),
            open: self.ends.is_some(),
            tension_only: self.tension_only,
            gravity: if self.gravity > 0.0 {
                self.gravity
            } else {
                0.0
            },
        }
    }

    /// Length of the arm state ([`crate::state::State::arm_force`]): one per element with a
    /// viscoelastic belt, else 0.
    pub fn arm_len(&self) -> usize {
        if self.zener.is_some() {
            self.elements
        } else {
            0
        }
    }

    /// The element law as the axial pass applies it (dampers if the model has them and
    /// `damping`), with the arm forces `arm` (N per element; empty: none).
    pub fn element_law<'a>(
        &'a self,
        damping: bool,
        arm: &'a [f64],
    ) -> crate::contact::wrap::ElementLaw<'a> {
        crate::contact::wrap::ElementLaw {
            stiffness: &self.axial_stiffness,
            damping: &self.axial_damping,
            rest_length: &self.rest_length,
            damped: damping && self.has_stage(Stage::AxialDamped),
            tension_only: self.tension_only,
            arm,
        }
    }

    /// Validate the scene and compile it.
    pub fn compile(scene: &Scene) -> BeltResult<Model> {
        scene.validate()?;
        if scene.belt.is_open() {
            if scene.belt.idler_contact == crate::scene::IdlerContactKind::Wrap {
                return Err(BeltError::invalid(
                    "belt.idler_contact",
                    "wrap",
                    "an open belt (belt.start/belt.end) meets its rolls on its elements' centre lines (\"segment\"); wrap contact is for a closed loop",
                ));
            }
            if scene.belt.pulley_contact == crate::scene::PulleyContact::Wrap {
                return Err(BeltError::invalid(
                    "belt.pulley_contact",
                    "wrap",
                    "an open belt (belt.start/belt.end) meets its pulleys at the nodes (\"nodes\"); wrap contact is for a closed loop",
                ));
            }
            if scene.initial.is_some() {
                return Err(BeltError::invalid(
                    "initial",
                    "a design start",
                    "an open belt (belt.start/belt.end) starts from its placement; a design start ([initial]) is for a closed loop",
                ));
            }
        }
        let path = if scene.belt.is_open() {
            open::path(scene)?
        } else {
            path::compile(scene)?
        };
        let placement = match scene.initial.as_ref().filter(|i| !i.path.is_empty()) {
            Some(initial) => Some(design::path_from_corners(scene, &initial.path)?),
            None => None,
        };
        let on = placement.as_ref().unwrap_or(&path);
        let formulation = scene.belt.formulation;
        let (belt, rigid) = match formulation {
            Formulation::NodeKelvinVoigt => (belt::compile(scene, on)?, None),
            Formulation::RigidBody => {
                let (belt, rigid) = belt_rigid::compile(scene, on)?;
                (belt, Some(rigid))
            }
        };
        let mut pulleys = pulleys::compile(scene, belt.element_length);
        let mut idlers = idlers::compile(scene, belt.element_length);
        for d in &mut idlers {
            let (at, dist) = crate::loads::project_on_path(on, d.center);
            if dist > 0.0 {
                let up = (on.point(at) - d.center) / dist;
                d.wrap_center = d.center - up * (d.wrap_radius - d.radius);
            }
        }
        let loads = crate::loads::compile(&scene.loads, on, belt.element_length)?;
        if scene.pulleys.iter().any(|p| {
            p.drive
                .as_ref()
                .is_some_and(|d| d.controller.is_some() || d.follow.is_some())
        }) {
            let load_belt = crate::loads::Belt {
                nodes: belt.nodes,
                l: belt.element_length,
            };
            let edges = crate::loads::initial_edges(&loads, &belt.initial_positions, load_belt);
            let masses = crate::loads::node_masses(&belt.mass, &loads, &edges, load_belt);
            crate::drives::controller::compile(scene, &mut pulleys, &idlers, masses.iter().sum())?;
        }
        let has_drive_memory = pulleys
            .iter()
            .any(|p| p.control.is_some() || p.motor.as_ref().is_some_and(|m| m.coupling.is_some()));
        let stages = stages::select(scene, &pulleys, &idlers, &loads, belt.ends.as_ref());
        // With loads the node masses change during the run: never read them as uniform.
        let uniform = if loads.is_empty() && rigid.is_none() {
            forces::Uniform::of(
                &belt.axial_stiffness,
                &belt.axial_damping,
                &belt.rest_length,
                &belt.mass,
            )
        } else {
            None
        };
        let takeups: Vec<bool> = pulleys.iter().map(|p| p.takeup.is_some()).collect();
        let relaxation_move_limit = idlers
            .iter()
            .map(|d| d.radius)
            .chain(pulleys.iter().map(|p| p.radius))
            .chain(belt.rest_length.iter().copied().filter(|&l| l > 0.0))
            .fold(f64::INFINITY, f64::min);
        let mut model = Model {
            scene: scene.clone(),
            nodes: belt.nodes,
            elements: if belt.ends.is_some() {
                belt.nodes - 1
            } else {
                belt.nodes
            },
            ends: belt.ends,
            mass: belt.mass,
            inv_mass: belt.inv_mass,
            rest_length: belt.rest_length,
            axial_stiffness: belt.axial_stiffness,
            axial_damping: belt.axial_damping,
            bending_stiffness: belt.bending_stiffness,
            uniform,
            tension_only: scene.belt.tension_only,
            wrap_contact: scene.belt.pulley_contact == crate::scene::PulleyContact::Wrap
                && formulation != Formulation::RigidBody,
            rigid_wrap: scene.belt.pulley_contact == crate::scene::PulleyContact::Wrap
                && formulation == Formulation::RigidBody,
            roll_wrap: scene.belt.idler_contact == crate::scene::IdlerContactKind::Wrap,
            formulation,
            gravity: scene.gravity,
            dofs: DofLayout::new(belt.nodes, &takeups, idlers.len()).with_bodies(
                match (&rigid, belt.ends) {
                    (None, _) => 0..0,
                    (Some(_), None) => 0..belt.nodes,
                    // An open belt's end points are points: no rotation.
                    (Some(_), Some(_)) => 1..belt.nodes - 1,
                },
            ),
            pulleys,
            idlers,
            loads,
            path,
            placement,
            initial_positions: belt.initial_positions,
            initial_motion: belt.motion,
            body_inertia: rigid.as_ref().map_or(Vec::new(), |r| r.inertia.clone()),
            torsional_damping: rigid
                .as_ref()
                .map_or(Vec::new(), |r| r.torsional_damping.clone()),
            initial_angles: rigid.map_or(Vec::new(), |r| r.angles),
            stages,
            has_drive_memory,
            integrator: Integrator::of(scene),
            dt: 0.0,
            dt_limit: 0.0,
            dt_cause: String::new(),
            node_stiffness_bound: Vec::new(),
            takeup_stiffness_bound: Vec::new(),
            relaxation_move_limit,
            zener: (scene.belt.loss_factor > 0.0).then(|| {
                crate::belt::node::zener::Zener::from_loss_factor(
                    scene.belt.loss_factor,
                    scene.belt.loss_frequency,
                )
            }),
        };
        let stable = model.stable_step(1.0)?;
        if !(stable.dt >= MIN_TIME_STEP && stable.dt.is_finite()) {
            let (field, value) = match scene.solver.time_step {
                Some(dt) => ("solver.time_step", dt),
                None => ("solver.time_step_fraction", scene.solver.time_step_fraction),
            };
            return Err(BeltError::invalid(
                field,
                value,
                format!(
                    "gives a time step of {:e} s (stability limit {:e} s, set by {}), below the floor of {MIN_TIME_STEP:e} s or not finite: one second would take over 10^9 steps; a stiffness, damping or mass is out of proportion (check the units)",
                    stable.dt, stable.dt_limit, stable.dt_cause
                ),
            ));
        }
        model.dt = stable.dt;
        model.dt_limit = stable.dt_limit;
        model.dt_cause = stable.dt_cause;
        model.node_stiffness_bound = stable.node_stiffness_bound;
        model.takeup_stiffness_bound = stable.takeup_stiffness_bound;
        Ok(model)
    }

    /// Length of the friction memory ([`crate::state::State::creep`]): one creep
    /// displacement per (belt point, pulley) pair if any pulley has creep friction, else 0.
    pub fn creep_memory_len(&self) -> usize {
        if self.pulleys.iter().any(|p| p.friction.is_creep()) {
            self.nodes * self.pulleys.len()
        } else {
            0
        }
    }

    /// True for the rigid-body belt ([`Formulation::RigidBody`]).
    #[inline]
    pub fn is_rigid(&self) -> bool {
        self.formulation == Formulation::RigidBody
    }

    /// True if the rigid bodies rest on pulley `j` with their two ends
    /// (`belt::rigid::contact`): rigid bodies on a pulley with the linear penalty. Under
    /// Kubas's nonlinear law they touch at their mass centres, as in the paper.
    #[inline]
    pub fn rests_on_ends(&self, j: usize) -> bool {
        self.is_rigid() && self.pulleys[j].nonlinear.is_none()
    }

    /// The radius at which pulley `j`'s friction acts on the belt points, m: the surface
    /// speed ω·r a point touching it is measured against and the lever of its friction.
    /// The pulley's radius for nodes (and for rigid bodies touching at their mass
    /// centres); for rigid bodies resting on their ends, their mass centres' distance
    /// ρ = (l/2)·cot(l/2R) (`belt::rigid::contact`).
    #[inline]
    pub fn friction_radius(&self, j: usize) -> f64 {
        let r = self.pulleys[j].radius;
        if self.rests_on_ends(j) {
            crate::belt::rigid::contact::contact_radius(self.element_length(), r)
        } else {
            r
        }
    }

    /// True if the compiled model runs `stage`.
    pub fn has_stage(&self, stage: Stage) -> bool {
        self.stages.contains(&stage)
    }

    /// The unstretched belt length each element stands for, m, one per element: the node
    /// belt's element rest lengths; for the rigid-body belt, half of each of the two belt
    /// points' lengths that a joint joins (the body length l between two bodies, l/2 from
    /// an open belt's end point to its body). They add up to the belt's length.
    pub fn element_rest_length(&self) -> Vec<f64> {
        if !self.is_rigid() {
            return self.rest_length[..self.elements].to_vec();
        }
        let n = self.nodes;
        (0..self.elements)
            .map(|e| 0.5 * (self.rest_length[e] + self.rest_length[(e + 1) % n]))
            .collect()
    }

    /// The length of an element (node belt) or a body (rigid-body belt), m: the first
    /// positive rest length (an open rigid-body belt's end points have none).
    pub fn element_length(&self) -> f64 {
        self.rest_length
            .iter()
            .copied()
            .find(|&l| l > 0.0)
            .unwrap_or(0.0)
    }

    /// Total belt mass, kg.
    pub fn belt_mass(&self) -> f64 {
        self.mass.iter().sum()
    }

    /// The uniform discretisation the loads work on (every element has the same rest
    /// length by construction).
    pub fn load_belt(&self) -> crate::loads::Belt {
        crate::loads::Belt {
            nodes: self.nodes,
            l: self.rest_length[0],
        }
    }
}
