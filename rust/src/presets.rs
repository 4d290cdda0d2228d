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
