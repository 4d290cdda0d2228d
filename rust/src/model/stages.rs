//! The stage list: which effects a compiled scene evaluates, in order.

use super::{EndModel, IdlerModel, OpenEnds, PulleyModel};
use crate::loads::LoadModel;
use crate::scene::Scene;

/// One step of the force evaluation. The compiled list holds only the stages a scene needs
/// (a disabled effect is not in the list, so it costs nothing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Bulk material on the belt: tracks each load's zone and updates the masses of the
    /// nodes at its edges (`crate::loads`). Runs first, so every later stage sees them.
    Loads,
    /// Elastic axial springs (thesis eq. 4.40), with the node weights m·g (eq. 4.49) when
    /// the scene has gravity (folded into the same pass: docs/performance.md).
    Axial,
    /// Kelvin-Voigt axial springs with dashpots (thesis eq. 4.40 + 4.56), replaces `Axial`.
    AxialDamped,
    /// The viscoelastic arms of Zener belt elements (`belt.loss_factor` > 0,
    /// `crate::belt::node::zener`), added to the axial pass's forces.
    BeltArms,
    /// Rotational bending springs (thesis eq. 4.47, signs re-derived).
    Bending,
    /// The rigid-body belt's spring-dampers between bodies and the body weights (Kubas
    /// eq. 20–23), replacing `Axial`/`AxialDamped` and `Bending`.
    RigidChain,
    /// Nodal penalty contact with pulleys (thesis eq. 4.70–4.75).
    PulleyContact,
    /// Centre-line penalty contact with idlers (thesis eq. 4.95–4.102).
    IdlerContact,
    /// DIN 22101 running resistance at the idlers: a stick-capable tangential force up to
    /// f·(N + m_R·g) opposing the belt's motion over the ground.
    RunningResistance,
    /// Drive torques T(t, ω) (thesis eq. 4.66).
    Drives,
    /// DOL induction motors, rigid or through a fluid coupling (`crate::drives::motor`).
    Motors,
    /// PI speed controllers and torque followers (`crate::drives::controller`,
    /// `crate::drives::sharing`): torques known before the friction solve.
    SpeedControl,
    /// Linear viscous drag in the pulley bearings, −b·ω (`crate::drives::bearing`).
    BearingDrag,
    /// Stick-force friction between belt and pulleys (thesis eq. 4.76–4.94, figure 4.9).
    PulleyFriction,
    /// Stick-force friction between belt and idlers (thesis eq. 4.103–4.117, re-derived).
    IdlerFriction,
    /// Speed-controlled drives: the torque that makes a pulley follow its starting curve,
    /// within the motor's limit (`docs/drives.md`). Solved with the belt friction when the
    /// pulley has friction; this stage takes the result (or solves a pulley without).
    SpeedDrives,
    /// Brakes (torque or deceleration target) with holding at rest, together with the
    /// holdback of the same pulley (`crate::drives::brake`).
    Brakes,
    /// Holdbacks of pulleys without a brake: one-way clutches against reverse rotation
    /// (`crate::drives::holdback`).
    Holdbacks,
    /// The pulls on the ends of an open belt (`belt.start`/`belt.end` with `hold =
    /// "force"`), before the contacts and friction see the node forces.
    EndPulls,
    /// The anchors of an open belt (`hold = "anchor"`): the anchored end node takes no
    /// net force (the anchor's reaction), so it stays at its point. Runs last.
    EndAnchors,
}

impl Stage {
    /// Stable snake_case name, as shown in Python (`model.stages`).
    pub fn name(self) -> &'static str {
        match self {
            Stage::Loads => "loads",
            Stage::Axial => "axial",
            Stage::AxialDamped => "axial_damped",
            Stage::BeltArms => "belt_arms",
            Stage::Bending => "bending",
            Stage::RigidChain => "rigid_chain",
            Stage::PulleyContact => "pulley_contact",
            Stage::IdlerContact => "idler_contact",
            Stage::RunningResistance => "running_resistance",
            Stage::Drives => "drives",
            Stage::Motors => "motors",
            Stage::SpeedControl => "speed_control",
            Stage::BearingDrag => "bearing_drag",
            Stage::PulleyFriction => "pulley_friction",
            Stage::IdlerFriction => "idler_friction",
            Stage::SpeedDrives => "speed_drives",
            Stage::Brakes => "brakes",
            Stage::Holdbacks => "holdbacks",
            Stage::EndPulls => "end_pulls",
            Stage::EndAnchors => "end_anchors",
        }
    }
}

/// The stages `scene` needs, in the order they run: an effect the scene does not use
/// is not in the list (and costs nothing).
pub(super) fn select(
    scene: &Scene,
    pulleys: &[PulleyModel],
    idlers: &[IdlerModel],
    loads: &[LoadModel],
    ends: Option<&OpenEnds>,
) -> Vec<Stage> {
    let ends = ends.map_or(vec![], |e| vec![e.start, e.end]);
    let mut stages = Vec::new();
    if !loads.is_empty() {
        stages.push(Stage::Loads);
    }
    match scene.belt.formulation {
        crate::scene::Formulation::NodeKelvinVoigt => {
            let voigt = scene.belt.damping_time.is_some_and(|t| t > 0.0);
            stages.push(if scene.belt.damping_ratio > 0.0 || voigt {
                Stage::AxialDamped
            } else {
                Stage::Axial
            });
            if scene.belt.loss_factor > 0.0 {
                stages.push(Stage::BeltArms);
            }
            if scene.belt.bending_stiffness > 0.0 {
                stages.push(Stage::Bending);
            }
        }
        crate::scene::Formulation::RigidBody => stages.push(Stage::RigidChain),
    }
    if ends.iter().any(|e| matches!(e, EndModel::Force { .. })) {
        stages.push(Stage::EndPulls);
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
    if pulleys.iter().any(|p| p.motor.is_some()) {
        stages.push(Stage::Motors);
    }
    if pulleys
        .iter()
        .any(|p| p.control.is_some() || p.follow.is_some())
    {
        stages.push(Stage::SpeedControl);
    }
    if pulleys.iter().any(|p| p.bearing_damping > 0.0) {
        stages.push(Stage::BearingDrag);
    }
    if pulleys.iter().any(|p| !p.friction.is_none()) {
        stages.push(Stage::PulleyFriction);
    }
    if idlers.iter().any(|d| !d.friction.is_none()) {
        stages.push(Stage::IdlerFriction);
    }
    if pulleys
        .iter()
        .any(|p| p.drive.as_ref().is_some_and(|d| d.start_curve.is_some()) && p.control.is_none())
    {
        stages.push(Stage::SpeedDrives);
    }
    if pulleys.iter().any(|p| p.brake.is_some()) {
        stages.push(Stage::Brakes);
    }
    if pulleys
        .iter()
        .any(|p| p.brake.is_none() && p.holdback.is_some())
    {
        stages.push(Stage::Holdbacks);
    }
    if ends.iter().any(|e| matches!(e, EndModel::Anchor(_))) {
        stages.push(Stage::EndAnchors);
    }
    stages
}
