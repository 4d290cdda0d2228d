//! Plain data describing a scene: belt, pulleys, idlers and solver settings.
//!
//! Over ~600 lines on purpose: this file is the scene format's top-level tables (belt,
//! pulley, idler, drive, takeup, solver, recording), each with its defaults, in file order,
//! so that the schema reads as a scene file does; the rules (validate.rs, rules.rs), the
//! named choices (forms.rs) and the stops and design-state tables are already apart.
//!
//! Everything here is SI: metres, kilograms, seconds, newtons, radians. Each parameter
//! struct implements [`Default`] with the documented defaults, so a scene can be built as
//! `PulleySpec { radius: 0.5, ..Default::default() }`. Nothing here is checked until
//! [`Scene::validate`] runs (it is called by [`crate::model::Model::compile`]).
//!
//! These types are the one schema of a scene: their serde form is what a Python dict, a
//! TOML scene file and a checkpoint hold (`docs/scene-format.md`). Defaults are the
//! [`Default`] impls here (Python's dataclasses take theirs from them), every table denies
//! unknown keys, and [`read`] turns any plain-value tree into a scene with messages naming
//! the full path, the value and the rule. Adding a field: see "Adding a scene field" in
//! `docs/scene-format.md`.
//!
//! Length: this file holds one type per scene table with every field's unit, default and
//! rule documented where it is declared, which puts it a little over the ~600-line guide;
//! the ends of an open belt (`ends.rs`), the serde forms (`forms.rs`), the reader
//! (`read.rs`) and the rules (`validate.rs`) live apart.

use crate::drives::controller::SpeedController;
use crate::drives::motor::Motor;
use crate::drives::sharing::TorqueFollow;
use crate::error::{BeltError, BeltResult};
pub use crate::friction::creep::CreepFriction;
use crate::start_curve::StartCurve;
use serde::{Deserialize, Serialize};

mod ends;
mod forms;
mod initial;
pub mod read;
mod rules;
mod stops;
mod validate;

pub use ends::{BeltEndSpec, EndHold};

pub(crate) use forms::required;
pub use forms::{BrakeKeys, FrictionKeys, FrictionKind};
pub use initial::InitialState;
pub use rules::{
    Formulation, IntegratorKind, DEFAULT_ABSOLUTE_TOLERANCE, DEFAULT_RELATIVE_TOLERANCE,
};
pub use stops::{HoldbackSpec, TakeupKind};
pub(crate) use validate::check_finite;

/// Most belt elements a scene may have (given or derived), 10⁶: about 100 MB of model and
/// state, and minutes of placement and ~0.1 s per step; more is almost surely a unit slip
/// (e.g. a radius in millimetres), and would exhaust memory rather than fail cleanly.
pub const MAX_ELEMENTS: usize = 1_000_000;

/// How the belt meets the pulleys (`belt.pulley_contact`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PulleyContact {
    /// Nodal penalty contact (thesis eq. 4.70–4.75): the belt round a pulley is a polygon of
    /// chords whose nodes touch it; nodes placed at equal chords.
    #[default]
    Nodes,
    /// Wrap contact (`contact::wrap`, docs/wrap-contact.md): an element on a pulley is
    /// measured along its path round it (tangents and arc), so the strand leaves on the
    /// tangent without chordal ripple; nodes placed at equal arc length.
    Wrap,
}

/// How the belt meets the idler rolls (`belt.idler_contact`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum IdlerContactKind {
    /// Centre-line penalty contact of the straight elements (thesis eq. 4.95–4.102).
    #[default]
    Segment,
    /// Wrap contact (`contact::roll_wrap`, docs/wrap-contact.md): an element over a roll is
    /// measured along its path over it, so its nodes lie on the belt's continuous path at
    /// every phase (no chordal action at the rolls). Node belt, closed loop.
    Wrap,
}

/// Belt properties (the `[belt]` table).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltParams {
    /// Discrete belt model. Default: [`Formulation::NodeKelvinVoigt`].
    pub formulation: Formulation,
    /// Axial stiffness EA, N. Default 7.62e6 (case H: E = 300 MPa, 1 m × 0.0254 m).
    pub axial_stiffness: f64,
    /// Mass per unit unstretched length ρA, kg/m. Default 100.
    pub mass_per_length: f64,
    /// Bending stiffness EI, N·m². Zero disables the bending stage. Default 0.
    pub bending_stiffness: f64,
    /// Axial damping as a fraction of the critical damping of one element (thesis eq. 4.3),
    /// dimensionless. Zero disables the damping term. Default 0.
    pub damping_ratio: f64,
    /// Voigt damping of the belt material as a retardation time τ = η/E, s (Guo & Wang
    /// 2020: σ = Eε + ηε̇): each element's (node belt) or spring-damper's (rigid-body belt)
    /// damping is τ times its stiffness, b = τ·EA/l (and τ·EI/l for the rigid bodies'
    /// torsional spring-dampers). Finite, ≥ 0; not with `damping_ratio` > 0. `None`: the
    /// damping follows `damping_ratio`. Default `None`.
    pub damping_time: Option<f64>,
    /// Loss factor tan δ of the belt material, dimensionless, in [0, 1]: each element of the
    /// node belt becomes a Zener (standard linear solid) element, its Kelvin-Voigt spring
    /// with a Maxwell arm in parallel whose loss factor peaks at this value at
    /// `loss_frequency` (`belt::node::zener`, docs/wrap-contact.md "A viscoelastic belt").
    /// `axial_stiffness` stays the relaxed (static) stiffness; the instantaneous one is
    /// (1 + r)·EA, r = 2η² + 2η√(1 + η²). 0 (default): no arm, Kelvin-Voigt elements only.
    /// Node belt under central differences only.
    pub loss_factor: f64,
    /// Frequency at which the loss factor peaks, Hz, > 0. Default 5 (the band of a long
    /// conveyor's longitudinal strand modes, 1–20 Hz; tan δ is above half its peak from
    /// about f/3.7 to 3.7·f).
    pub loss_frequency: f64,
    /// Unstretched belt length, m. `None`: the length of the initial pulley path, so that
    /// the belt is placed unstretched. Default `None`.
    pub length: Option<f64>,
    /// Number of elements (= number of nodes for a closed loop, one fewer than the nodes
    /// for an open belt), 3 to [`MAX_ELEMENTS`].
    /// `None`: the fewest
    /// elements whose unstretched length is at most the arc of `max_element_angle` on the
    /// smallest pulley (thesis §6.1), and, while `max_element_angle` is at its default, on
    /// every pulley with friction at most the arc that keeps the node-discrete
    /// Euler–Eytelwein ratio over its wrap within 0.5 % (`model::FRICTION_RATIO_ERROR`,
    /// `docs/belt-drives.md`). Default `None`.
    pub elements: Option<usize>,
    /// Largest arc angle an element may span on the smallest pulley when `elements` is
    /// `None`, rad. Default π/6 (30°, as in the thesis).
    pub max_element_angle: f64,
    /// If true, elements carry no compression (a slack element has zero force; its bending
    /// springs still act). If false the axial spring is linear in compression too, as in the
    /// thesis. Default false.
    pub tension_only: bool,
    /// Largest strain, dimensionless, > 0, at which the belt may be placed on its initial
    /// path (|path length / `length` − 1|): a placement stretched or compressed more is
    /// refused as a belt too short or too long for its path (usually a unit slip). Raise it
    /// for pre-strained elastic drive belts (the belt-drive literature's benchmarks are
    /// pre-strained 5.26 %). Default 0.1 (10 %).
    pub max_placement_strain: f64,
    /// How the belt meets the pulleys: [`PulleyContact::Nodes`] (thesis, default) or
    /// [`PulleyContact::Wrap`] (no chordal ripple; docs/wrap-contact.md).
    pub pulley_contact: PulleyContact,
    /// How the belt meets the idler rolls: [`IdlerContactKind::Segment`] (thesis, default)
    /// or [`IdlerContactKind::Wrap`] (docs/wrap-contact.md, "The rolls' chordal action").
    pub idler_contact: IdlerContactKind,
    /// The belt's first end, for an open belt (give `start` and `end` together): the
    /// belt runs from it round the pulleys in order to `end` (`docs/open-belts.md`).
    /// `None`: a closed loop. Default `None`.
    pub start: Option<BeltEndSpec>,
    /// The belt's last end, for an open belt (with `start`). Default `None`.
    pub end: Option<BeltEndSpec>,
}

impl BeltParams {
    /// True for an open belt (both ends given; validation refuses one alone).
    pub fn is_open(&self) -> bool {
        self.start.is_some() && self.end.is_some()
    }
}

impl Default for BeltParams {
    fn default() -> Self {
        BeltParams {
            formulation: Formulation::NodeKelvinVoigt,
            axial_stiffness: 7.62e6,
            mass_per_length: 100.0,
            bending_stiffness: 0.0,
            damping_ratio: 0.0,
            damping_time: None,
            loss_factor: 0.0,
            loss_frequency: 5.0,
            length: None,
            elements: None,
            max_element_angle: std::f64::consts::PI / 6.0,
            tension_only: false,
            max_placement_strain: DEFAULT_MAX_PLACEMENT_STRAIN,
            pulley_contact: PulleyContact::Nodes,
            idler_contact: IdlerContactKind::Segment,
            start: None,
            end: None,
        }
    }
}

/// Default of [`BeltParams::max_placement_strain`]: 10 %.
pub const DEFAULT_MAX_PLACEMENT_STRAIN: f64 = 0.1;

/// Default contact damping as a fraction of critical, per node: ζ = 0.2 (`docs/belt-drives.md`).
///
/// Undamped penalty contact with friction lets the belt bounce off the pulleys: on a small
/// two-pulley drive (R = 0.1 m, 200 elements, µ = 0.5) about one node in 25 of the wrap
/// touches on average and the driven pulley turns at 47 % of the creep-theory speed. Any
/// damping from ζ = 0.01 up removes it (driven speed within 0.1 % for ζ = 0.01 … 0.5 at
/// contact stiffnesses 1e8 … 1e10 N/m and belt speeds 2 and 10 m/s); 0.2 keeps a factor 20
/// of margin and costs 18 % of the stable step where contact sets it (0.5 would cost 38 %).
pub const DEFAULT_CONTACT_DAMPING_RATIO: f64 = 0.2;

/// The normal contact damping, N·s/m, of a contact of stiffness `stiffness` (N/m) on a
/// belt node of mass `node_mass` (kg): `absolute` if given, else c = 2ζ√(k·m) with ζ =
/// `ratio` (default [`DEFAULT_CONTACT_DAMPING_RATIO`]), the critical damping of the node
/// on the contact spring times ζ.
pub fn contact_damping(
    absolute: Option<f64>,
    ratio: Option<f64>,
    stiffness: f64,
    node_mass: f64,
) -> f64 {
    absolute.unwrap_or_else(|| {
        2.0 * ratio.unwrap_or(DEFAULT_CONTACT_DAMPING_RATIO) * (stiffness * node_mass).sqrt()
    })
}

/// Sense in which the belt wraps a pulley as it travels along the loop in node order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Wrap {
    /// The belt goes counter-clockwise around the pulley (pulley on the belt's left).
    #[default]
    CounterClockwise,
    /// The belt goes clockwise around the pulley (pulley on the belt's right).
    Clockwise,
}

impl Wrap {
    /// +1 for counter-clockwise, −1 for clockwise.
    pub fn sign(self) -> f64 {
        match self {
            Wrap::CounterClockwise => 1.0,
            Wrap::Clockwise => -1.0,
        }
    }
}

/// Friction between the belt and a pulley or idler. In a scene it is the `friction` table
/// ([`FrictionKeys`]), absent for none.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum FrictionModel {
    /// Frictionless contact: no friction stage is compiled for this body.
    #[default]
    None,
    /// Stick-force friction (Taylor & Preece, extended by Hustrulid, thesis eq. 4.76–4.94).
    StickForce {
        /// Static coefficient µs, dimensionless, ≥ µk.
        static_coefficient: f64,
        /// Kinetic (dynamic) coefficient µk, dimensionless, ≥ 0.
        kinetic_coefficient: f64,
    },
    /// Kubas's (2014) creep-rate friction (eq. 12–19): µ as a function of the creep
    /// displacement Δ (memory per contact point, in the state) and the relative speed,
    /// `crate::friction::creep` and `docs/belt-drives.md`.
    Creep(CreepFriction),
}

impl FrictionModel {
    /// True if this model adds no friction force at all.
    pub fn is_none(&self) -> bool {
        match *self {
            FrictionModel::None => true,
            FrictionModel::StickForce {
                static_coefficient, ..
            } => static_coefficient == 0.0,
            FrictionModel::Creep(c) => c.static_coefficient == 0.0,
        }
    }

    /// The static coefficient µs (0 without friction).
    pub fn static_coefficient(&self) -> f64 {
        match *self {
            FrictionModel::None => 0.0,
            FrictionModel::StickForce {
                static_coefficient, ..
            } => static_coefficient,
            FrictionModel::Creep(c) => c.static_coefficient,
        }
    }

    /// True for the creep model (it keeps a memory per contact point in the state).
    pub fn is_creep(&self) -> bool {
        matches!(self, FrictionModel::Creep(c) if c.static_coefficient > 0.0)
    }
}

/// A function of time given as a piecewise-linear table, held constant beyond its ends.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// Abscissae, strictly increasing (s for time tables, rad/s for speed tables).
    pub x: Vec<f64>,
    /// Ordinates, same length as `x`.
    pub y: Vec<f64>,
}

impl Table {
    /// A constant function.
    pub fn constant(value: f64) -> Self {
        Table {
            x: vec![0.0],
            y: vec![value],
        }
    }

    /// Piecewise-linear interpolation, constant extrapolation. An empty table is 0.
    pub fn eval(&self, x: f64) -> f64 {
        let n = self.x.len();
        if n == 0 {
            return 0.0;
        }
        if x <= self.x[0] {
            return self.y[0];
        }
        if x >= self.x[n - 1] {
            return self.y[n - 1];
        }
        // Tables are short (a handful of points): a linear scan beats a binary search.
        let mut i = 1;
        while self.x[i] < x {
            i += 1;
        }
        let (x0, x1, y0, y1) = (self.x[i - 1], self.x[i], self.y[i - 1], self.y[i]);
        y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    }
}

// The drive's keys are declared once for the engine's type and its scene form
// (`forms::drive_forms`).
forms::drive_forms! {
/// A drive on a pulley. Torque-controlled (thesis eq. 4.66): T(t, ω) = f(t)·g(ω) − b·ω.
/// Speed-controlled (a VFD following a [`StartCurve`], `docs/drives.md`): each step the
/// motor supplies the torque that makes the pulley follow the curve, within ±`max_torque`,
/// plus the load torque −b·ω; the torque table must then be zero and `speed_factor` empty.
///
/// In a scene its tables are the keys `time`/`torque` and `speed`/`speed_factor`
/// ([`DriveKeys`]).
pub struct DriveSpec {
    /// f(t): torque against time, N·m, positive counter-clockwise. Default: 0.
    pub torque: Table,
    /// g(ω): dimensionless factor against pulley speed ω (rad/s), e.g. a motor curve
    /// normalised to 1 at stall. Empty: g = 1. Default empty.
    pub speed_factor: Table,
    /// b: viscous torque coefficient, N·m·s/rad (a load torque proportional to speed).
    /// Default 0.
    pub viscous: f64,
    /// I_D: inertia of motor, gearbox and coupling added to the pulley, kg·m². Default 0.
    pub inertia: f64,
    /// Starting curve of a speed-controlled drive; `None`: torque-controlled. Default `None`.
    pub start_curve: Option<StartCurve>,
    /// Torque limit of a speed-controlled drive's motor (e.g. its breakdown torque), N·m,
    /// > 0, may be +∞; only with `start_curve` or `follow`. Default +∞.
    pub max_torque: f64,
    /// PI speed controller following `start_curve` (`crate::drives::controller`); `None`:
    /// the ideal speed follower. Default `None`.
    pub controller: Option<SpeedController>,
    /// Master–slave torque sharing: this drive applies a ratio of another drive's torque
    /// (`crate::drives::sharing`). Default `None`.
    pub follow: Option<TorqueFollow>,
    /// Induction motor started direct on line, with its gearbox and optional fluid
    /// coupling (`crate::drives::motor`). Default `None`.
    pub motor: Option<Motor>,
    /// Flywheel on the drive's high-speed shaft (the driven side of a coupling, so it
    /// turns with the belt), kg·m², ≥ 0: counts i²·flywheel at the pulley, i the motor's
    /// `gear_ratio` (1 without a motor). Default 0.
    pub flywheel: f64,
    /// Time the motor loses power (a power failure or a stop), s, absolute simulated time:
    /// from then on it supplies no torque (no torque table, speed-controlled hold, PI
    /// controller or follower torque; a DOL motor is switched off and its rotor coasts) and
    /// the pulley coasts; the load torque −b·ω stays. `None`: never. Default
    /// `None` (`docs/stops-takeups.md`).
    pub power_off: Option<f64>,
}
}

impl Default for DriveSpec {
    fn default() -> Self {
        DriveSpec {
            torque: Table::constant(0.0),
            speed_factor: Table::default(),
            viscous: 0.0,
            inertia: 0.0,
            start_curve: None,
            max_torque: f64::INFINITY,
            controller: None,
            follow: None,
            motor: None,
            flywheel: 0.0,
            power_off: None,
        }
    }
}

impl DriveSpec {
    /// Drive torque at time `t` (s) and pulley speed `omega` (rad/s), N·m: after
    /// `power_off` only the load torque −b·ω.
    #[inline]
    pub fn torque_at(&self, t: f64, omega: f64) -> f64 {
        if !self.powered(t) {
            return -self.viscous * omega;
        }
        let factor = if self.speed_factor.x.is_empty() {
            1.0
        } else {
            self.speed_factor.eval(omega)
        };
        self.torque.eval(t) * factor - self.viscous * omega
    }
}

/// A brake: a Coulomb torque that opposes rotation and holds the pulley at rest up to its
/// capacity (stick/slip, never reversing the motion; `docs/stops-takeups.md`). The capacity
/// is a table against time, or a `torque` applied at `applied` and built up over `rise`;
/// with a `deceleration` target the brake supplies only the torque (up to `torque`) that
/// decelerates the pulley surface at that rate.
/// In a scene its table is the keys `time`/`capacity`, `torque`, `deceleration`, `applied`
/// and `rise` ([`BrakeKeys`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(into = "BrakeKeys", try_from = "BrakeKeys")]
pub struct BrakeSpec {
    /// Holding/braking torque capacity against time, N·m, ≥ 0. Default 0. Left at its
    /// default when `torque` is given.
    pub capacity: Table,
    /// Braking torque (the capacity) from `applied` on, N·m, finite, > 0. `None`: the
    /// `capacity` table. Default `None`.
    pub torque: Option<f64>,
    /// Deceleration target of the belt at the pulley surface, m/s², finite, > 0: the brake
    /// supplies the torque, up to `torque`, that slows the pulley at this rate, and holds
    /// it at rest once stopped. Only with `torque`. `None`: a plain torque brake. Default
    /// `None`.
    pub deceleration: Option<f64>,
    /// Time the brake is applied, s, absolute simulated time, finite; before it the brake
    /// is released. Only with `torque`. Default 0.
    pub applied: f64,
    /// Time the torque takes to build up from 0 to `torque` (linear), s, finite, ≥ 0. Only
    /// with `torque`. Default 0.
    pub rise: f64,
}

impl Default for BrakeSpec {
    fn default() -> Self {
        BrakeSpec {
            capacity: Table::constant(0.0),
            torque: None,
            deceleration: None,
            applied: 0.0,
            rise: 0.0,
        }
    }
}

/// A takeup: the pulley translates on a straight line, pulled by a counterweight (gravity,
/// thesis eq. 4.63), a winch or a screw ([`TakeupKind`], `docs/stops-takeups.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TakeupSpec {
    /// Kind of takeup. Default [`TakeupKind::Gravity`].
    pub kind: TakeupKind,
    /// Unit vector along which the counterweight pulls. Default (0, −1): a vertical gravity
    /// takeup hanging in the loop.
    pub direction: [f64; 2],
    /// Counterweight mass, kg. It moves with the pulley. Default 0.
    pub counterweight: f64,
    /// Lowest travel along `direction` from the initial position, m (a hard stop; `-inf`
    /// for none). Default −∞.
    pub travel_min: f64,
    /// Highest travel along `direction` from the initial position, m. Default +∞.
    pub travel_max: f64,
    /// Force the takeup pulls the pulley with along `direction`, N, finite, > 0: a winch's
    /// set force, or the force a screw (`"fixed"`) takeup is tightened to at rest. Required
    /// for those kinds, refused for a gravity takeup. Default `None`.
    pub force: Option<f64>,
    /// Winch speed limit: largest carriage speed along the line, m/s, > 0, may be +∞. Only
    /// for a winch. Default +∞.
    pub max_speed: f64,
    /// Lock the carriage where it is when the first stop of the scene begins (the earliest
    /// drive `power_off` or brake `applied` time). Default false.
    pub lock_on_stop: bool,
}

impl Default for TakeupSpec {
    fn default() -> Self {
        TakeupSpec {
            direction: [0.0, -1.0],
            counterweight: 0.0,
            travel_min: f64::NEG_INFINITY,
            travel_max: f64::INFINITY,
            kind: TakeupKind::Gravity,
            force: None,
            max_speed: f64::INFINITY,
            lock_on_stop: false,
        }
    }
}

/// A pulley: fixed centre and free rotation, optionally a gravity takeup, a drive and a brake.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PulleySpec {
    /// Name used in messages and results; unique among the pulleys unless empty. Default ""
    /// (messages then use the index).
    pub name: String,
    /// Centre, m.
    pub center: [f64; 2],
    /// Radius to the belt centre line, m. Default 0.5.
    pub radius: f64,
    /// Pulley mass, kg. Default 100.
    pub mass: f64,
    /// Polar moment of inertia, kg·m². `None`: mass·radius² (as the thesis code). Default `None`.
    pub inertia: Option<f64>,
    /// Sense of the wrap. Default counter-clockwise.
    pub wrap: Wrap,
    /// Belt–pulley friction. Default frictionless.
    #[serde(with = "forms::friction")]
    pub friction: FrictionModel,
    /// Nodal penalty stiffness, N/m of penetration (thesis eq. 4.71 with k_c/R_p). Zero
    /// switches contact with this pulley off (the belt passes through it); with zero on
    /// every pulley no pulley-contact stage is compiled. Default 1e9.
    pub contact_stiffness: f64,
    /// Normal contact damping, N·s/m (not in the thesis), acting on the approach speed only.
    /// `None`: from `contact_damping_ratio`. Give one or the other, not both. Default `None`.
    pub contact_damping: Option<f64>,
    /// Normal contact damping as a fraction ζ of the critical damping of one belt node on
    /// the contact spring, dimensionless: c = 2ζ√(k·m), m the belt's node mass ρ·l (without
    /// material). `None`: [`DEFAULT_CONTACT_DAMPING_RATIO`] unless `contact_damping` is
    /// given. Default `None`.
    pub contact_damping_ratio: Option<f64>,
    /// Linear viscous drag of the bearings, N·m·s/rad, ≥ 0: torque −b·ω on the pulley (a
    /// free pulley spins down as ω₀·e^(−b·t/I)). 0 compiles no `bearing_drag` stage.
    /// Default 0.
    pub bearing_damping: f64,
    /// Gravity takeup, if this pulley translates. Default `None`.
    pub takeup: Option<TakeupSpec>,
    /// Drive torque, if any. Default `None`.
    pub drive: Option<DriveSpec>,
    /// Brake, if any. Default `None`.
    pub brake: Option<BrakeSpec>,
    /// Kubas's damped nonlinear contact law (eq. 4–11) in place of the linear penalty
    /// (`contact_stiffness`, `contact_damping`): N = c₁p² + c₂p + δ(p)·b·ṗ, never pulling.
    /// `None`: the linear law. Default `None`.
    pub nonlinear_contact: Option<crate::contact::nonlinear::NonlinearContact>,
    /// Holdback (a one-way clutch that stops the pulley turning backwards), if any.
    /// Default `None`.
    pub holdback: Option<HoldbackSpec>,
}

impl Default for PulleySpec {
    fn default() -> Self {
        PulleySpec {
            name: String::new(),
            center: [0.0, 0.0],
            radius: 0.5,
            mass: 100.0,
            inertia: None,
            wrap: Wrap::CounterClockwise,
            friction: FrictionModel::None,
            contact_stiffness: 1e9,
            contact_damping: None,
            contact_damping_ratio: None,
            bearing_damping: 0.0,
            takeup: None,
            drive: None,
            brake: None,
            nonlinear_contact: None,
            holdback: None,
        }
    }
}

impl PulleySpec {
    /// Polar moment of inertia, kg·m², with the default applied.
    pub fn polar_inertia(&self) -> f64 {
        self.inertia
            .unwrap_or(self.mass * self.radius * self.radius)
    }
}

/// An idler roll in contact with the belt centre line (thesis eq. 4.95–4.117).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IdlerSpec {
    /// Centre, m.
    pub center: [f64; 2],
    /// Radius, m. Default 0.0635 (5 in roll).
    pub radius: f64,
    /// Polar moment of inertia of the rotating parts, kg·m². Default 0.01.
    pub inertia: f64,
    /// Penalty stiffness, N/m of penetration. Default 1e8.
    pub contact_stiffness: f64,
    /// Normal contact damping, N·s/m, on the approach speed only. `None`: from
    /// `contact_damping_ratio`. Give one or the other, not both. Default `None`.
    pub contact_damping: Option<f64>,
    /// Normal contact damping as a fraction ζ of critical, c = 2ζ√(k·m), m the belt's node
    /// mass ρ·l. `None`: [`DEFAULT_CONTACT_DAMPING_RATIO`] unless `contact_damping` is given.
    /// Default `None`.
    pub contact_damping_ratio: Option<f64>,
    /// Belt–idler friction. Default frictionless (the roll then never turns).
    #[serde(with = "forms::friction")]
    pub friction: FrictionModel,
    /// Running resistance: DIN 22101's artificial friction coefficient f, dimensionless,
    /// ≥ 0. The belt meets a tangential force at the contact point that opposes its motion
    /// relative to the ground, up to f·(N + `rotating_mass`·g), N the contact normal force
    /// (stick-capable: it holds a belt at rest below that limit). Zero on every idler
    /// compiles no running-resistance stage. Default 0.
    pub resistance: f64,
    /// Rotating mass of the roll, kg, ≥ 0: its weight adds to the load on the bearings in
    /// the running-resistance limit f·(N + m_R·g). (The roll's inertia is `inertia`.)
    /// Default 0.
    pub rotating_mass: f64,
}

impl Default for IdlerSpec {
    fn default() -> Self {
        IdlerSpec {
            center: [0.0, 0.0],
            radius: 0.0635,
            inertia: 0.01,
            contact_stiffness: 1e8,
            contact_damping: None,
            contact_damping_ratio: None,
            friction: FrictionModel::None,
            resistance: 0.0,
            rotating_mass: 0.0,
        }
    }
}

/// Bulk material lying on the belt between a loading point and a discharge point
/// (`docs/loads.md`). The material moves with the belt: each step the belt material points
/// nearest `start` and `end` are found, and every node carries the material on its
/// tributary length inside the zone between them, so node masses change during a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LoadSpec {
    /// Material per metre of unstretched belt, kg/m, finite, ≥ 0 (a volumetric feeder: the
    /// same whatever the belt speed). Default 0.
    pub mass_per_length: f64,
    /// Loading point (x, y), m: where material enters (e.g. under the tail chute). Within
    /// [`LOAD_POINT_TOLERANCE`] of the initial belt path. Default (0, 0).
    pub start: [f64; 2],
    /// Discharge point (x, y), m: where material leaves (e.g. the head pulley's top
    /// tangent point). Within [`LOAD_POINT_TOLERANCE`] of the initial belt path. The loaded
    /// zone is the run of belt between the two points that does not wrap a pulley.
    /// Default (0, 0).
    pub end: [f64; 2],
}

impl Default for LoadSpec {
    fn default() -> Self {
        LoadSpec {
            mass_per_length: 0.0,
            start: [0.0, 0.0],
            end: [0.0, 0.0],
        }
    }
}

/// Farthest a load's `start` or `end` may lie from the initial belt path, m.
pub const LOAD_POINT_TOLERANCE: f64 = 1.0;

/// Time-stepping settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SolverParams {
    /// Fixed time step, s. `None`: `time_step_fraction` × the estimated stability limit.
    /// A value above the limit is refused. Default `None`.
    pub time_step: Option<f64>,
    /// Fraction of the stability limit used when `time_step` is `None`, in (0, 1].
    /// Default 0.5 (the thesis ran at half its limit).
    pub time_step_fraction: f64,
    /// Time integrator: `"central_difference"` (default) or `"rkf45"` (adaptive, with the
    /// tolerances below; effects solved for a fixed step, stick-force friction, speed
    /// holds, brakes, running resistance and loads, are refused under it).
    pub integrator: IntegratorKind,
    /// RKF45's relative tolerance on each generalized coordinate, speed and friction
    /// memory per step, dimensionless, > 0. Default 1e-8 ([`DEFAULT_RELATIVE_TOLERANCE`]:
    /// positions are of the scene's size, deformations 10⁻³–10⁻⁵ of it). Used only with
    /// `"rkf45"`.
    pub relative_tolerance: f64,
    /// RKF45's absolute tolerance per step, in each component's SI unit (m, rad, m/s,
    /// rad/s), ≥ 0. Default 1e-11. Used only with `"rkf45"`.
    pub absolute_tolerance: f64,
}

impl Default for SolverParams {
    fn default() -> Self {
        SolverParams {
            time_step: None,
            time_step_fraction: 0.5,
            integrator: IntegratorKind::CentralDifference,
            relative_tolerance: DEFAULT_RELATIVE_TOLERANCE,
            absolute_tolerance: DEFAULT_ABSOLUTE_TOLERANCE,
        }
    }
}

/// Optional large arrays a run can record, as named in scene files (`recording.channels`)
/// and in results: the element tensions, node positions and velocities, and the contact
/// forces of every belt point on every pulley with their angles (`Result.contact_normal`,
/// `contact_friction`, `contact_angle`). Everything else (time, pulley and idler
/// quantities) is always recorded; `beltrs run` adds the energies.
pub const RECORDING_CHANNELS: [&str; 4] = [
    "tension",
    "node_position",
    "node_velocity",
    "contact_forces",
];

/// The channels recorded when a scene file does not list them: all but the contact
/// forces, which are opt-in (3 × pulleys × nodes values per instant).
pub const DEFAULT_RECORDING_CHANNELS: [&str; 3] = ["tension", "node_position", "node_velocity"];

/// How a scene file asks to be run and recorded (the `[recording]` table). The engine
/// itself does not use it: the command line (`beltrs run`) does. It is read and checked
/// here so that a scene given in any form is checked by the same rules.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RecordingParams {
    /// Simulated time of the run, s, ≥ 0. Default 1.
    pub duration: f64,
    /// Sample about every this many seconds (rounded to whole steps), s, > 0. `None`: see
    /// `every`; if both are `None`, 0.01 s. Default `None`.
    pub interval: Option<f64>,
    /// Sample every this many steps, ≥ 1. Give `interval` or `every`, not both. Default
    /// `None`.
    pub every: Option<u64>,
    /// Optional large arrays to record, from [`RECORDING_CHANNELS`]. Default:
    /// [`DEFAULT_RECORDING_CHANNELS`] (all but `contact_forces`).
    #[serde(deserialize_with = "forms::strings")]
    pub channels: Vec<String>,
    /// Relax to static equilibrium before the run. Default true.
    pub stabilise: bool,
    /// Keep belt friction on while relaxing; only with `stabilise` (else it would have no
    /// effect, and is refused). Default false.
    pub stabilise_friction: bool,
}

impl Default for RecordingParams {
    fn default() -> Self {
        RecordingParams {
            duration: 1.0,
            interval: None,
            every: None,
            channels: DEFAULT_RECORDING_CHANNELS
                .iter()
                .map(|s| s.to_string())
                .collect(),
            stabilise: true,
            stabilise_friction: false,
        }
    }
}

/// A whole scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Scene {
    /// Belt properties.
    pub belt: BeltParams,
    /// Pulleys in the order the belt meets them; the loop closes from the last to the first.
    #[serde(deserialize_with = "forms::tables")]
    pub pulleys: Vec<PulleySpec>,
    /// Idlers (in any order).
    #[serde(deserialize_with = "forms::tables")]
    pub idlers: Vec<IdlerSpec>,
    /// Bulk material loads on the belt (any order). Default none.
    #[serde(deserialize_with = "forms::tables")]
    pub loads: Vec<LoadSpec>,
    /// Gravitational acceleration, m/s², acting in −y. Zero disables the gravity stage.
    /// Default 9.81.
    pub gravity: f64,
    /// Time-stepping settings.
    pub solver: SolverParams,
    /// How the scene asks to be run and recorded (not used by the engine itself: the command
    /// line and `beltrs.Scene.recording` do). Checked with the scene.
    pub recording: RecordingParams,
    /// The design state to start from ([`InitialState`]); `None`: the belt placed
    /// unstretched on the pulleys' path, at rest, to be relaxed. Default `None`.
    pub initial: Option<InitialState>,
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            belt: BeltParams::default(),
            pulleys: Vec::new(),
            idlers: Vec::new(),
            loads: Vec::new(),
            gravity: 9.81,
            solver: SolverParams::default(),
            recording: RecordingParams::default(),
            initial: None,
        }
    }
}
