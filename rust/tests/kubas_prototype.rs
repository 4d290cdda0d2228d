//! A short check of the case K prototype (rust/examples/kubas_case_k, docs/kubas.md): one
//! settling pass of the 150-body belt without friction must leave the tension uniform.
#[path = "../examples/kubas_case_k/drive.rs"]
mod drive;

use drive::{first_length, settle_pass, CaseK, CtraReading};

/// Without friction a belt at rest on two free pulleys carries one tension everywhere
/// (capstan law with µ = 0); the spans' means must agree to 0.5 % (the residual is the
/// chordal rattle of 8 mm bodies on a 27 mm pulley, damped for 0.06 s). The first length
/// guess ignores the polygon of chords and the contact penetration: its preload must come
/// out within 10 % of the target, and above it (chords on the arcs shorten the path).
#[test]
fn frictionless_settling_gives_uniform_tension() {
    let case = CaseK::paper(CtraReading::PerUnitStrain);
    let l = first_length(&case);
    let (s, state, stats) = settle_pass(case, l).unwrap();
    assert!(
        (s.tight - s.slack).abs() < 5e-3 * s.mean,
        "tight {} slack {} mean {}",
        s.tight,
        s.slack,
        s.mean
    );
    assert!(
        s.mean > case.preload && s.mean < 1.1 * case.preload,
        "mean {}",
        s.mean
    );
    assert!(state.iter().all(|v| v.is_finite()));
    assert!(stats.rejected < stats.accepted / 10, "{stats:?}");
}
