//! The compiled model: read-only arrays and the list of stages this scene needs.
//!
//! Compilation turns a validated [`Scene`] into per-element and per-node arrays, places the
//! belt on its path, estimates the stable time step and decides which stages run. Nothing
//! here changes during a run; the mutable part lives in [`crate::state::State`].

use crate::error::{BeltError, BeltResult};
use crate::forces;
use crate::friction::Prescribed;
use crate::geometry::BeltPath;
use crate::loads::LoadModel;
use crate::scene::{BrakeSpec, DriveSpec, FrictionModel, Scene, MAX_ELEMENTS};
use nalgebra::Vector2;

/// Smallest time step a scene may compile to, s. A stable step below it means that a
/// stiffness, damping or mass is out of proportion (usually wrong units): one simulated
/// second would take more than 10⁹ steps, and a step that underflows to zero would never
/// advance time. Such scenes are refused at compile time (docs/runtime.md).
pub const MIN_TIME_STEP: f64 = 1e-9;

/// One step of the force evaluation. The compiled list holds only the stages a scene needs
/// (a disabled effect is not in the list, so it costs nothing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Bulk material on the belt: tracks each load's zone and updates the masses of the
    /// nodes at its edges (`crate::loads`). Runs first, so every later stage sees them.
    Loads,
    /// Node weights m·g (thesis eq. 4.49).
    Gravity,
    /// Elastic axial springs (thesis eq. 4.40).
    Axial,
    /// Kelvin-Voigt axial springs with dashpots (thesis eq. 4.40 + 4.56), replaces `Axial`.
    AxialDamped,
    /// Rotational bending springs (thesis eq. 4.47, signs re-derived).
    Bending,
    /// Nodal penalty contact with pulleys (thesis eq. 4.70–4.75).
    PulleyContact,
    /// Centre-line penalty contact with idlers (thesis eq. 4.95–4.102).
    IdlerContact,
    /// DIN 22101 running resistance at the idlers: a stick-capable tangential force up to
    /// f·(N + m_R·g) opposing the belt's motion over the ground.
    RunningResistance,
    /// Drive torques T(t, ω) (thesis eq. 4.66).
    Drives,
    /// Stick-force friction between belt and pulleys (thesis eq. 4.76–4.94, figure 4.9).
    PulleyFriction,
    /// Stick-force friction between belt and idlers (thesis eq. 4.103–4.117, re-derived).
    IdlerFriction,
    /// Speed-controlled drives: the torque that makes a pulley follow its starting curve,
    /// within the motor's limit (`docs/drives.md`). Solved with the belt friction when the
    /// pulley has friction; this stage takes the result (or solves a pulley without).
    SpeedDrives,
    /// Coulomb brakes with holding at rest.
    Brakes,
    /// Gravity-takeup translation (thesis eq. 4.63–4.65).
    Takeups,
}

impl Stage {
    /// Stable snake_case name, as shown in Python (`model.stages`).
    pub fn name(self) -> &'static str {
        match self {
            Stage::Loads => "loads",
            Stage::Gravity => "gravity",
            Stage::Axial => "axial",
            Stage::AxialDamped => "axial_damped",
            Stage::Bending => "bending",
            Stage::PulleyContact => "pulley_contact",
            Stage::IdlerContact => "idler_contact",
            Stage::RunningResistance => "running_resistance",
            Stage::Drives => "drives",
            Stage::PulleyFriction => "pulley_friction",
            Stage::IdlerFriction => "idler_friction",
            Stage::SpeedDrives => "speed_drives",
            Stage::Brakes => "brakes",
            Stage::Takeups => "takeups",
        }
    }
}

/// Compiled gravity takeup.
#[derive(Debug, Clone, PartialEq)]
pub struct TakeupModel {
    /// Unit vector of the takeup line (direction of the counterweight pull).
    pub direction: Vector2<f64>,
    /// Translating mass: pulley + counterweight, kg.
    pub moving_mass: f64,
    /// Constant force along `direction` from the counterweight and the pulley weight, N.
    pub pull: f64,
    /// Travel limits from the initial position, m.
    pub travel_min: f64,
    /// Travel limits from the initial position, m.
    pub travel_max: f64,
}

/// Compiled pulley.
#[derive(Debug, Clone, PartialEq)]
pub struct PulleyModel {
    /// Name for messages.
    pub name: String,
    /// Initial centre, m.
    pub center: Vector2<f64>,
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia including drive inertia, kg·m².
    pub inertia: f64,
    /// Contact stiffness, N/m.
    pub contact_stiffness: f64,
    /// Contact damping, N·s/m (the scene's absolute value, or 2ζ√(k·m) from its ratio).
    pub contact_damping: f64,
    /// Friction model.
    pub friction: FrictionModel,
    /// Takeup, if the pulley translates.
    pub takeup: Option<TakeupModel>,
    /// Drive, if any.
    pub drive: Option<DriveSpec>,
    /// Brake, if any.
    pub brake: Option<BrakeSpec>,
    /// Search margin beyond the radius for the contact window, m.
    pub window_margin: f64,
}

impl PulleyModel {
    /// The brake's hold at time `time` (s): at rest, up to its capacity then.
    #[inline]
    pub fn brake_hold(&self, time: f64) -> Option<Prescribed> {
        self.brake
            .as_ref()
            .map(|b| Prescribed::at_rest(b.capacity.eval(time)))
    }

    /// The speed-controlled drive's hold for the step from `time` to `time + dt` (s): the
    /// pulley speed at the mid-step, where central differences place it, is the curve's
    /// belt speed there over the radius, ω(t + Δt/2) = v(t + Δt/2)/r, up to `max_torque`.
    #[inline]
    pub fn speed_hold(&self, time: f64, dt: f64) -> Option<Prescribed> {
        let drive = self.drive.as_ref()?;
        let curve = drive.start_curve.as_ref()?;
        Some(Prescribed {
            omega: curve.speed_at(time + 0.5 * dt) / self.radius,
            capacity: drive.max_torque,
        })
    }
}

/// Compiled idler.
#[derive(Debug, Clone, PartialEq)]
pub struct IdlerModel {
    /// Centre, m.
    pub center: Vector2<f64>,
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia, kg·m².
    pub inertia: f64,
    /// Contact stiffness, N/m.
    pub contact_stiffness: f64,
    /// Contact damping, N·s/m.
    pub contact_damping: f64,
    /// Friction model.
    pub friction: FrictionModel,
    /// DIN 22101 running-resistance coefficient f, dimensionless.
    pub resistance: f64,
    /// Rotating mass of the roll, kg (its weight adds to the bearing load).
    pub rotating_mass: f64,
}

/// The read-only compiled model.
#[derive(Debug, Clone)]
pub struct Model {
    /// The scene this model was compiled from.
    pub scene: Scene,
    /// Number of nodes (= number of elements; the belt is a closed loop).
    pub nodes: usize,
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
    /// Gravitational acceleration, m/s².
    pub gravity: f64,
    /// Pulleys.
    pub pulleys: Vec<PulleyModel>,
    /// Idlers.
    pub idlers: Vec<IdlerModel>,
    /// Bulk material loads.
    pub loads: Vec<LoadModel>,
    /// The initial path.
    pub path: BeltPath,
    /// Initial node positions, m.
    pub initial_positions: Vec<Vector2<f64>>,
    /// Stages this scene runs, in order.
    pub stages: Vec<Stage>,
    /// Time step in use, s.
    pub dt: f64,
    /// Estimated critical (stability-limit) time step, s.
    pub dt_limit: f64,
    /// Which term sets the limit.
    pub dt_cause: String,
    /// Gershgorin bound of the stiffness seen by each node, N/m (also used for the mass
    /// scaling of the fast relaxation).
    pub node_stiffness_bound: Vec<f64>,
    /// Same bound for each takeup's translation, N/m (0 for fixed pulleys).
    pub takeup_stiffness_bound: Vec<f64>,
    /// Smallest idler radius, pulley radius or element length, m: the static relaxation
    /// moves no node by more than a quarter of it per step.
    pub relaxation_move_limit: f64,
}

impl Model {
    /// The axial elements and node weights as the axial pass reads them: Kelvin-Voigt
    /// elements if the model has the damped stage and `damping` is on, weights if it has a
    /// gravity stage.
    pub fn axial_belt<'a>(&'a self, damping: bool, node_mass: &'a [f64]) -> forces::AxialBelt<'a> {
        forces::AxialBelt {
            stiffness: &self.axial_stiffness,
            damping: &self.axial_damping,
            rest_length: &self.rest_length,
            mass: node_mass,
            uniform: self.uniform,
            damped: damping && self.has_stage(Stage::AxialDamped),
            tension_only: self.tension_only,
            gravity: if self.has_stage(Stage::Gravity) {
                self.gravity
            } else {
                0.0
            },
        }
    }

    /// Validate the scene and compile it.
    pub fn compile(scene: &Scene) -> BeltResult<Model> {
        scene.validate()?;
        let path = BeltPath::from_pulleys(&scene.pulleys)?;
        path.check_spans_clear(&scene.pulleys)?;
        if !(path.length.is_finite() && path.length > 0.0) {
            return Err(BeltError::invalid(
                "pulleys",
                format!("a belt path of {} m", path.length),
                "the path length must be finite and > 0 (centres or radii too large)",
            ));
        }
        let belt = &scene.belt;
        let belt_length = belt.length.unwrap_or(path.length);
        let min_radius = scene
            .pulleys
            .iter()
            .map(|p| p.radius)
            .fold(f64::INFINITY, f64::min);
        // Strain needed to stretch the belt onto the path.
        let strain = path.length / belt_length - 1.0;
        let max_strain = belt.max_placement_strain;
        if strain > max_strain {
            return Err(BeltError::invalid(
                "belt.length",
                belt_length,
                format!(
                    "the belt is too short for its path of {:.6} m: it would be stretched by {:.2} % (limit belt.max_placement_strain = {} %; raise it for a pre-strained belt)",
                    path.length,
                    100.0 * strain,
                    100.0 * max_strain
                ),
            ));
        }
        if strain < -max_strain {
            return Err(BeltError::invalid(
                "belt.length",
                belt_length,
                format!(
                    "the belt is too long for its path of {:.6} m: it would be compressed by {:.2} % (limit belt.max_placement_strain = {} %)",
                    path.length,
                    -100.0 * strain,
                    100.0 * max_strain
                ),
            ));
        }
        let n = match belt.elements {
            Some(n) => n,
            None => {
                let wanted = (belt_length / (belt.max_element_angle * min_radius)).ceil();
                if wanted > MAX_ELEMENTS as f64 {
                    return Err(BeltError::invalid(
                        "belt.max_element_angle",
                        belt.max_element_angle,
                        format!(
                            "a {belt_length} m belt needs {wanted:e} elements of at most this arc on the smallest pulley (radius {min_radius} m), more than {MAX_ELEMENTS}; give belt.elements or check the units"
                        ),
                    ));
                }
                wanted as usize
            }
        };
        if n < 3 {
            return Err(BeltError::invalid(
                "belt.elements",
                n,
                "a closed belt needs at least 3 elements",
            ));
        }
        let l0 = belt_length / n as f64;
        // An element longer than the smallest radius spans more than 60° of that pulley: the
        // chord then cuts deep into the pulley between the nodes and nodal contact fails.
        if l0 > min_radius {
            return Err(BeltError::invalid(
                "belt.elements",
                n,
                format!(
                    "elements of {l0:.6} m are longer than the smallest pulley radius {min_radius} m can hold (limit: one radius, a 60° chord); use more elements"
                ),
            ));
        }
        let (initial_positions, _chord) = path.equal_chord_nodes(n)?;

        let rho = belt.mass_per_length;
        let k = belt.axial_stiffness / l0;
        let m_el = rho * l0;
        let c = 2.0 * m_el * belt.damping_ratio * (k / m_el).sqrt();
        let rest_length = vec![l0; n];
        let axial_stiffness = vec![k; n];
        let axial_damping = vec![c; n];
        let mass = vec![m_el; n];
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        let bending_stiffness = vec![belt.bending_stiffness / l0; n];

        let pulleys: Vec<PulleyModel> = scene
            .pulleys
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let drive_inertia = p.drive.as_ref().map_or(0.0, |d| d.inertia);
                PulleyModel {
                    name: if p.name.is_empty() {
                        format!("pulleys[{i}]")
                    } else {
                        p.name.clone()
                    },
                    center: Vector2::new(p.center[0], p.center[1]),
                    radius: p.radius,
                    inertia: p.polar_inertia() + drive_inertia,
                    contact_stiffness: p.contact_stiffness,
                    contact_damping: crate::scene::contact_damping(
                        p.contact_damping,
                        p.contact_damping_ratio,
                        p.contact_stiffness,
                        m_el,
                    ),
                    friction: p.friction,
                    takeup: p.takeup.as_ref().map(|t| {
                        let dir = Vector2::new(t.direction[0], t.direction[1]);
                        TakeupModel {
                            direction: dir,
                            moving_mass: p.mass + t.counterweight,
                            // Counterweight pulls along the line; the pulley's own weight
                            // acts along −y.
                            pull: t.counterweight * scene.gravity - p.mass * scene.gravity * dir.y,
                            travel_min: t.travel_min,
                            travel_max: t.travel_max,
                        }
                    }),
                    drive: p.drive.clone(),
                    brake: p.brake.clone(),
                    window_margin: l0,
                }
            })
            .collect();
        let idlers: Vec<IdlerModel> = scene
            .idlers
            .iter()
            .map(|d| IdlerModel {
                center: Vector2::new(d.center[0], d.center[1]),
                radius: d.radius,
                inertia: d.inertia,
                contact_stiffness: d.contact_stiffness,
                contact_damping: crate::scene::contact_damping(
                    d.contact_damping,
                    d.contact_damping_ratio,
                    d.contact_stiffness,
                    m_el,
                ),
                friction: d.friction,
                resistance: d.resistance,
                rotating_mass: d.rotating_mass,
            })
            .collect();
        // Validated whole; a load of zero mass is then dropped (it would only cost a stage
        // and the uniform-mass fast path).
        let mut loads = crate::loads::compile(&scene.loads, &path, l0)?;
        loads.retain(|l| l.mass_per_length > 0.0);

        let stages = Self::select_stages(scene, &pulleys, &idlers, &loads);
        // With loads the node masses change during the run: never read them as uniform.
        let uniform = if loads.is_empty() {
            forces::Uniform::of(&axial_stiffness, &axial_damping, &rest_length, &mass)
        } else {
            None
        };
        let mut model = Model {
            scene: scene.clone(),
            nodes: n,
            mass,
            inv_mass,
            rest_length,
            axial_stiffness,
            axial_damping,
            bending_stiffness,
            uniform,
            tension_only: belt.tension_only,
            gravity: scene.gravity,
            pulleys,
            idlers,
            loads,
            path,
            initial_positions,
            stages,
            dt: 0.0,
            dt_limit: 0.0,
            dt_cause: String::new(),
            node_stiffness_bound: Vec::new(),
            takeup_stiffness_bound: Vec::new(),
            relaxation_move_limit: 0.0,
        };
        model.relaxation_move_limit = model
            .idlers
            .iter()
            .map(|d| d.radius)
            .chain(model.pulleys.iter().map(|p| p.radius))
            .chain(model.rest_length.iter().copied())
            .fold(f64::INFINITY, f64::min);
        model.estimate_time_step()?;
        Ok(model)
    }

    fn select_stages(
        scene: &Scene,
        pulleys: &[PulleyModel],
        idlers: &[IdlerModel],
        loads: &[LoadModel],
    ) -> Vec<Stage> {
        let mut stages = Vec::new();
        if !loads.is_empty() {
            stages.push(Stage::Loads);
        }
        if scene.gravity > 0.0 {
            stages.push(Stage::Gravity);
        }
        stages.push(if scene.belt.damping_ratio > 0.0 {
            Stage::AxialDamped
        } else {
            Stage::Axial
        });
        if scene.belt.bending_stiffness > 0.0 {
            stages.push(Stage::Bending);
        }
        if pulleys.iter().any(|p| p.contact_stiffness > 0.0) {
            stages.push(Stage::PulleyContact);
        }
        if !idlers.is_empty() {
            stages.push(Stage::IdlerContact);
        }
        if idlers.iter().any(|d| d.resistance > 0.0) {
            stages.push(Stage::RunningResistance);
        }
        if pulleys.iter().any(|p| p.drive.is_some()) {
            stages.push(Stage::Drives);
        }
        if pulleys.iter().any(|p| !p.friction.is_none()) {
            stages.push(Stage::PulleyFriction);
        }
        if idlers.iter().any(|d| !d.friction.is_none()) {
            stages.push(Stage::IdlerFriction);
        }
        if pulleys
            .iter()
            .any(|p| p.drive.as_ref().is_some_and(|d| d.start_curve.is_some()))
        {
            stages.push(Stage::SpeedDrives);
        }
        if pulleys.iter().any(|p| p.brake.is_some()) {
            stages.push(Stage::Brakes);
        }
        if pulleys.iter().any(|p| p.takeup.is_some()) {
            stages.push(Stage::Takeups);
        }
        stages
    }

    /// True if the compiled model runs `stage`.
    pub fn has_stage(&self, stage: Stage) -> bool {
        self.stages.contains(&stage)
    }

    /// Estimate the critical step of central differences from a Gershgorin bound of each
    /// degree of freedom's stiffness: ω² ≤ K/m and Δt_crit = (2/ω)(√(1+ζ²) − ζ).
    ///
    /// Per node, K sums the axial row 2(k_{i−1}+k_i) (exact for a uniform chain, whose
    /// highest mode has ω = 2√(k/m)), the bending row 16·k_θ/l² (zig-zag mode), and the
    /// stiffest contact a node may meet (pulley or idler penalty). Takeups add the contact
    /// stiffness of every node that can sit on their wrap.
    fn estimate_time_step(&mut self) -> BeltResult<()> {
        let n = self.nodes;
        let k_contact = self
            .pulleys
            .iter()
            .map(|p| (p.contact_stiffness, p.contact_damping))
            .chain(
                self.idlers
                    .iter()
                    .map(|d| (d.contact_stiffness, d.contact_damping)),
            )
            .fold((0.0f64, 0.0f64), |acc, (k, c)| (acc.0.max(k), acc.1.max(c)));
        let mut limit = f64::INFINITY;
        let mut cause = String::new();
        self.node_stiffness_bound = vec![0.0; n];
        for i in 0..n {
            let prev = (i + n - 1) % n;
            let next = (i + 1) % n;
            let k_ax = 2.0 * (self.axial_stiffness[prev] + self.axial_stiffness[i]);
            let c_ax = 2.0 * (self.axial_damping[prev] + self.axial_damping[i]);
            let l = 0.5 * (self.rest_length[prev] + self.rest_length[i]);
            let k_bend = if self.has_stage(Stage::Bending) {
                (self.bending_stiffness[prev]
                    + 4.0 * self.bending_stiffness[i]
                    + self.bending_stiffness[next])
                    * 16.0
                    / 6.0
                    / (l * l)
            } else {
                0.0
            };
            let k_total = k_ax + k_bend + k_contact.0;
            let c_total = c_ax + k_contact.1;
            self.node_stiffness_bound[i] = k_total;
            // The belt-only mass: loads only add mass to a node, which lowers its ω, so the
            // limit found here holds whatever material the node carries during a run.
            let m = self.mass[i];
            let omega = (k_total / m).sqrt();
            let zeta = c_total / (2.0 * m * omega);
            let dt = 2.0 / omega * ((1.0 + zeta * zeta).sqrt() - zeta);
            if dt < limit {
                limit = dt;
                let dominant = if k_contact.0 >= k_ax.max(k_bend) {
                    "contact"
                } else if k_ax >= k_bend {
                    "axial"
                } else {
                    "bending"
                };
                cause = format!(
                    "{dominant} stiffness at node {i}: K = {k_total:.4e} N/m on {m:.4e} kg"
                );
            }
        }
        self.takeup_stiffness_bound = vec![0.0; self.pulleys.len()];
        for (j, p) in self.pulleys.iter().enumerate() {
            if let (Some(t), true) = (&p.takeup, p.contact_stiffness > 0.0) {
                let wrap = self.path.wrap_angles[j];
                let nodes_on_wrap = (wrap * p.radius / self.rest_length[0]).ceil() + 2.0;
                let k = nodes_on_wrap * p.contact_stiffness;
                self.takeup_stiffness_bound[j] = k;
                let omega = (k / t.moving_mass).sqrt();
                let c = nodes_on_wrap * p.contact_damping;
                let zeta = c / (2.0 * t.moving_mass * omega);
                let dt = 2.0 / omega * ((1.0 + zeta * zeta).sqrt() - zeta);
                if dt < limit {
                    limit = dt;
                    cause = format!("contact stiffness on the takeup {}", p.name);
                }
            }
        }
        self.dt_limit = limit;
        self.dt_cause = cause;
        self.dt = match self.scene.solver.time_step {
            Some(dt) => {
                if dt > limit {
                    return Err(BeltError::TimeStepTooLarge {
                        requested: dt,
                        limit,
                        cause: self.dt_cause.clone(),
                    });
                }
                dt
            }
            None => self.scene.solver.time_step_fraction * limit,
        };
        if !(self.dt >= MIN_TIME_STEP && self.dt.is_finite()) {
            let (field, value) = match self.scene.solver.time_step {
                Some(dt) => ("solver.time_step", dt),
                None => (
                    "solver.time_step_fraction",
                    self.scene.solver.time_step_fraction,
                ),
            };
            return Err(BeltError::invalid(
                field,
                value,
                format!(
                    "gives a time step of {:e} s (stability limit {limit:e} s, set by {}), below the floor of {MIN_TIME_STEP:e} s or not finite: one second would take over 10^9 steps; a stiffness, damping or mass is out of proportion (check the units)",
                    self.dt, self.dt_cause
                ),
            ));
        }
        Ok(())
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
