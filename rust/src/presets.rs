//! Built-in scenes shared by the Rust tests, examples and benchmarks (the Python side has
//! its own builders in `beltrs.scenes`).

use crate::scene::{BeltParams, PulleySpec, Scene, TakeupSpec};

/// Case H (reference-cases.md): Hustrulid's two-pulley vertical loop with a gravity takeup,
/// frictionless, at `elements` elements. Upper pulley at (0, 100) m, takeup pulley at the
/// origin, both 5 m radius, 600 kg, 15 000 kg·m²; 30 000 kg counterweight; belt
/// EA = 7.62 MN, EI = 409.7 N·m², 100 kg/m; contact 2e8 N/m (the thesis code's KC/R).
pub fn case_h(elements: usize) -> Scene {
    let pulley = |name: &str, center: [f64; 2]| PulleySpec {
        name: name.into(),
        center,
        radius: 5.0,
        mass: 600.0,
        inertia: Some(15_000.0),
        contact_stiffness: 2e8,
        ..Default::default()
    };
    Scene {
        belt: BeltParams {
            axial_stiffness: 300e6 * 1.0 * 0.0254,
            mass_per_length: 100.0,
            bending_stiffness: 300e6 * 1.0 * 0.0254f64.powi(3) / 12.0,
            elements: Some(elements),
            ..Default::default()
        },
        pulleys: vec![
            pulley("upper", [0.0, 100.0]),
            PulleySpec {
                takeup: Some(TakeupSpec {
                    counterweight: 30_000.0,
                    ..Default::default()
                }),
                ..pulley("takeup", [0.0, 0.0])
            },
        ],
        ..Default::default()
    }
}

/// Case K (Kubas 2014, section 4; `docs/kubas.md`): a poly-V belt drive with the rigid-body
/// belt. Two pulleys of radius 0.027 m, 2.4·10⁻⁴ kg·m², centres 0.515 m apart, the drive
/// ("drive") at the origin; 150 bodies, m = 0.096·l kg; EA = c_tra = 1.52·10⁵ N (c_tra read
/// per unit strain), EI = c_tor·l (c_tor = 0.026 N·m/rad per joint), translational damping
/// b_tra = 20.5 N·s/m per joint as the ratio ζ = b_tra/(2√(EA·ρA)) = 0.0849 (the same
/// for every body length); Kubas's nonlinear contact (its case K values, the default
/// [`NonlinearContact`](crate::contact::nonlinear::NonlinearContact)); stick-force friction
/// µs = 1.05, µk = 1.0; the drive torque rising linearly to 15 N·m (counter-clockwise) over
/// `ramp_time` s; the driven pulley ("driven") resisting with 15 N·m at 8π rad/s,
/// proportional to its speed. The belt is `preload_strain` shorter than its path around
/// the pulleys (1/(1 + strain)): 0.00344 gives a static tension of 556 N ("slightly above
/// 550 N", measured after the relaxation: the mass centres sink into the pulleys and the
/// bodies' joints lie outside the rims, `docs/kubas.md`).
pub fn case_k(ramp_time: f64, preload_strain: f64) -> Scene {
    use crate::contact::nonlinear::NonlinearContact;
    use crate::scene::{DriveSpec, Formulation, FrictionModel, Table};
    let (radius, distance, bodies) = (0.027, 0.515, 150usize);
    let (ea, rho) = (1.52e5, 0.096);
    let path = 2.0 * distance + std::f64::consts::TAU * radius;
    let length = path / (1.0 + preload_strain);
    let pulley = |name: &str, center: [f64; 2], drive: DriveSpec| PulleySpec {
        name: name.into(),
        center,
        radius,
        mass: 2.0 * 2.4e-4 / (radius * radius),
        inertia: Some(2.4e-4),
        friction: FrictionModel::StickForce {
            static_coefficient: 1.05,
            kinetic_coefficient: 1.0,
        },
        nonlinear_contact: Some(NonlinearContact::default()),
        drive: Some(drive),
        ..Default::default()
    };
    Scene {
        belt: BeltParams {
            formulation: Formulation::RigidBody,
            axial_stiffness: ea,
            mass_per_length: rho,
            bending_stiffness: 0.026 * length / bodies as f64,
            damping_ratio: 20.5 / (2.0 * (ea * rho).sqrt()),
            length: Some(length),
            elements: Some(bodies),
            ..Default::default()
        },
        pulleys: vec![
            pulley(
                "drive",
                [0.0, 0.0],
                DriveSpec {
                    torque: Table {
                        x: vec![0.0, ramp_time],
                        y: vec![0.0, 15.0],
                    },
                    ..Default::default()
                },
            ),
            pulley(
                "driven",
                [distance, 0.0],
                DriveSpec {
                    viscous: 15.0 / (8.0 * std::f64::consts::PI),
                    ..Default::default()
                },
            ),
        ],
        gravity: 9.81,
        ..Default::default()
    }
}
