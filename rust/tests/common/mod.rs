//! Scenes shared by the integration tests.
#![allow(dead_code)]

use beltrs::scene::Scene;

/// Case H (reference-cases.md): Hustrulid's two-pulley vertical loop with a gravity takeup.
pub fn case_h(elements: usize) -> Scene {
    beltrs::presets::case_h(elements)
}
