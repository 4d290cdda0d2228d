//! Scenes shared by the integration tests.
#![allow(dead_code)]

use beltrs::scene::{BeltParams, PulleySpec, Scene, TakeupSpec};

/// Case H (reference-cases.md): Hustrulid's two-pulley vertical loop with a gravity takeup.
pub fn case_h(elements: usize) -> Scene {
    Scene {
        belt: BeltParams {
            axial_stiffness: 300e6 * 1.0 * 0.0254,
            mass_per_length: 100.0,
            bending_stiffness: 300e6 * 1.0 * 0.0254f64.powi(3) / 12.0,
            elements: Some(elements),
            ..Default::default()
        },
        pulleys: vec![
            PulleySpec {
                name: "upper".into(),
                center: [0.0, 100.0],
                radius: 5.0,
                mass: 600.0,
                inertia: Some(15_000.0),
                contact_stiffness: 2e8,
                ..Default::default()
            },
            PulleySpec {
                name: "takeup".into(),
                center: [0.0, 0.0],
                radius: 5.0,
                mass: 600.0,
                inertia: Some(15_000.0),
                contact_stiffness: 2e8,
                takeup: Some(TakeupSpec {
                    counterweight: 30_000.0,
                    ..Default::default()
                }),
                ..Default::default()
            },
        ],
        ..Default::default()
    }
}
