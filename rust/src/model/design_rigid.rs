//! The rigid-body belt's design-state placement (issue 12; `docs/design-start.md`).
//!
//! A rigid body's joint (Kubas eq. 20–22) is a zero-free-length spring-damper c_x = EA/l
//! between the end of one body and the start of the next, so its force is c_x·|gap|. The
//! placement walks the *joint points* (vertices V_k, the middles of the gaps) instead of
//! the mass centres, and puts body k on the chord from V_k to V_{k+1}, centred on it:
//!
//! - with e_k = g_k/cos(α_k/2) (g_k = l·T/EA the design gap, α_k the turn between the two
//!   bodies at V_k) and chords |V_{k+1} − V_k| = l + (e_k + e_{k+1})/2, the gap at V_k is
//!   (e_k/2)(u_{k−1} + u_k) = g_k along the bisector: every joint's elastic force is
//!   exactly the design tension T (up to the change of e between neighbours, at a wrap's
//!   two ends);
//! - on a pulley's wrap (linear penalty) a body rests on its two ends on the drum's tangent
//!   line under its mass centre at ρ = (l/2)·cot(l/2R) (`crate::belt::rigid::contact`),
//!   pressed in by δ = N/k under the load N = 2T·sin(φ/2) of its two joints (φ the turn per
//!   body). Its mass centre then lies at ρ − δ, so the vertices lie on the circle
//!   r_v = (ρ − δ)/cos(φ/2), with φ from 2(ρ − δ)·tan(φ/2) = l + g/cos(φ/2)
//!   ([`wrap_pitch`]). The vertex curve is the belt path with each wrap's arc replaced by
//!   that circle (a strand point inside it is moved out along its radial: the strand line
//!   is cut where it meets the circle).
//!
//! Every body on a strand or inside a wrap is then in force and torque balance with its
//! joints and the drum. The body spanning a strand's tangent point is not exactly: it has
//! one end on the line and one on the circle (torque about T·(l/2)·sin(α/4)); the
//! bending springs c_φ = EI/l are not balanced there either. Both are local and small
//! against T (measured in `design_rigid_tests`).

use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// ρ = (l/2)·cot(l/2R), m: where a rigid body resting with its two ends on a drum (linear
/// penalty) has its mass centre; the contact's own radius, so that the placement rests
/// each body where the contact holds it.
use crate::belt::rigid::contact::contact_radius as rest_radius;

/// The turn per body φ (rad) and the vertex radius r_v (m) of a uniform wrap of bodies of
/// length `l` (m) at tension `t` (N) on a drum of radius `radius` (m) and contact stiffness
/// `k` (N/m), for a belt of axial stiffness `ea` (N): the solution of
/// 2(ρ − δ)·tan(φ/2) = l + g/cos(φ/2) with g = l·t/EA and δ = 2t·sin(φ/2)/k
/// (fixed point, converged to 10⁻¹⁴ in a few steps since δ ≪ ρ).
pub(crate) fn wrap_pitch(l: f64, t: f64, radius: f64, k: f64, ea: f64) -> (f64, f64) {
    let rho = rest_radius(l, radius);
    let g = l * t / ea;
    let mut phi = l / radius;
    let mut depth = 0.0;
    for _ in 0..50 {
        depth = if k > 0.0 {
            2.0 * t * (0.5 * phi).sin() / k
        } else {
            0.0
        };
        // tan(φ/2) = (l + g/cos(φ/2)) / (2(ρ − δ))
        let next = 2.0 * ((l + g / (0.5 * phi).cos()) / (2.0 * (rho - depth))).atan();
        let done = (next - phi).abs() <= 1e-15 * phi;
        phi = next;
        if done {
            break;
        }
    }
    (phi, (rho - depth) / (0.5 * phi).cos())
}

/// A point of the vertex curve: `p` (a point of the belt path) moved out along its radial
/// onto the vertex circle of any `wraps` entry (centre, r_v) it lies inside.
pub(crate) fn onto_vertex_circles(p: V2, wraps: &[(V2, f64)]) -> V2 {
    for &(c, rv) in wraps {
        let d = p - c;
        let r = d.norm();
        if r < rv && r > 0.0 {
            return c + d * (rv / r);
        }
    }
    p
}

/// The bodies on the closed polygon of joint points `vertices`: body k centred on the
/// chord from vertex k to vertex k+1, along it. Returns (mass centres, angles).
pub(crate) fn bodies(vertices: &[V2]) -> (Vec<V2>, Vec<f64>) {
    let n = vertices.len();
    (0..n)
        .map(|k| {
            let (a, b) = (vertices[k], vertices[(k + 1) % n]);
            let d = b - a;
            (0.5 * (a + b), d.y.atan2(d.x))
        })
        .unzip()
}

/// cos(α_k/2) at each vertex k of a closed polygon (α_k the turn between chord k−1 and
/// chord k).
pub(crate) fn half_turn_cosines(vertices: &[V2]) -> Vec<f64> {
    let n = vertices.len();
    (0..n)
        .map(|k| {
            let a = (vertices[k] - vertices[(k + n - 1) % n]).normalize();
            let b = (vertices[(k + 1) % n] - vertices[k]).normalize();
            let turn = (a.x * b.y - a.y * b.x).atan2(a.dot(&b));
            (0.5 * turn).cos()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_uniform_wrap_has_its_design_gap_and_depth() {
        let (l, t, r, k, ea) = (0.05, 20e3, 0.25, 1e8, 1e6);
        let (phi, rv) = wrap_pitch(l, t, r, k, ea);
        let depth = 2.0 * t * (0.5 * phi).sin() / k;
        let rc = rv * (0.5 * phi).cos();
        assert!((rc - (rest_radius(l, r) - depth)).abs() < 1e-14);
        // bodies ⊥ the radial at ±φ/2: the gap between them is 2rc·sin(φ/2) − l·cos(φ/2)
        let gap = 2.0 * rc * (0.5 * phi).sin() - l * (0.5 * phi).cos();
        assert!((gap - l * t / ea).abs() < 1e-15, "{gap}");
    }

    /// Two drums of radius 0.5 m, 4 m apart, the rigid-body belt of 120 bodies (10.6° on
    /// a drum), EA = 1 MN, 10 kg/m, contact 1e8 N/m, no gravity, placed at 20 kN at rest.
    fn two_drums(speed: f64) -> crate::scene::Scene {
        use crate::scene::{BeltParams, Formulation, InitialState, PulleySpec, Scene};
        let pulley = |x: f64| PulleySpec {
            center: [x, 0.0],
            radius: 0.5,
            contact_stiffness: 1e8,
            ..Default::default()
        };
        let mut scene = Scene {
            belt: BeltParams {
                formulation: Formulation::RigidBody,
                axial_stiffness: 1e6,
                mass_per_length: 10.0,
                elements: Some(120),
                ..Default::default()
            },
            pulleys: vec![pulley(0.0), pulley(4.0)],
            gravity: 0.0,
            initial: Some(InitialState {
                tension: vec![T],
                speed,
                ..Default::default()
            }),
            ..Default::default()
        };
        scene.recording.stabilise = false;
        scene
    }

    const T: f64 = 20e3;

    #[test]
    fn rigid_design_start_carries_its_tension_and_stays_at_rest() {
        // At t = 0 every joint carries T: exactly on the strands and inside the wraps; at
        // the joints next to a tangent point, where the body spans the cut between the line
        // and the vertex circle, the gap is off its bisector (measured: 17 N of 20 kN,
        // 0.085 %; the node-walk construction of the refused start put 2.7 MN there).
        let scene = two_drums(0.0);
        let mut sim = crate::Simulation::new(&scene).unwrap();
        let t0 = sim.tensions().to_vec();
        for (e, t) in t0.iter().enumerate() {
            assert!((t - T).abs() < 2e-3 * T, "joint {e}: {t} N");
        }
        // Each 180° wrap pulls its drum with 2T along the strands (measured 39 995 N);
        // across them, the two transition bodies' imbalance (measured 304 N, 0.8 %).
        let f = sim.scratch.pulley_force.clone();
        for (j, f) in f.iter().enumerate() {
            let sign = if j == 0 { 1.0 } else { -1.0 };
            assert!(
                (sign * f.x - 2.0 * T).abs() < 1e-3 * 2.0 * T,
                "pulley {j}: {f:?}"
            );
            assert!(f.y.abs() < 0.02 * 2.0 * T, "pulley {j}: {f:?}");
        }
        // At rest it stays at rest: over 0.2 s (40 passes of a stress wave round the loop)
        // no joint leaves T by more than 0.5 % (measured 45 N, 0.23 %; the node belt's
        // design start on this scene: 134 N) and no body moves faster than 0.25 m/s
        // (measured 0.17 m/s on the wraps: a ringing of the bodies on their end contacts,
        // √(3k/m) = 1.8·10⁴ rad/s, i.e. about 10 µm; node belt 0.04 m/s).
        let (mut vmax, mut tmax) = (0.0f64, 0.0f64);
        for _ in 0..20 {
            sim.advance_to(sim.state.time + 0.01, u64::MAX).unwrap();
            let v = sim
                .state
                .velocity
                .iter()
                .map(|v| v.norm())
                .fold(0.0, f64::max);
            vmax = vmax.max(v);
            let w = sim
                .tensions()
                .iter()
                .map(|t| (t - T).abs())
                .fold(0.0, f64::max);
            tmax = tmax.max(w);
        }
        assert!(tmax < 5e-3 * T, "{tmax} N");
        assert!(vmax < 0.25, "{vmax} m/s");
    }

    #[test]
    fn running_start_spins_the_wrap_bodies() {
        // At 2 m/s the chain moves one pitch (l + g/cos(φ/2)) per turn φ on a wrap: bodies
        // there spin at v·φ/pitch = v/(ρ − δ)·(φ/2)/tan(φ/2) ≈ v/R (to φ²·l²/R² terms,
        // below 10⁻⁴ here); strand bodies do not turn; the pulleys turn with their bodies.
        let scene = two_drums(2.0);
        let sim = crate::Simulation::new(&scene).unwrap();
        let l = sim.model.element_length();
        let (phi, rv) = wrap_pitch(l, T, 0.5, 1e8, 1e6);
        let expected = 2.0 * phi / (2.0 * rv * (0.5 * phi).sin());
        assert!((expected - 4.0).abs() < 4e-4, "{expected}");
        let spin = &sim.state.body_spin;
        let wrap = spin
            .iter()
            .filter(|w| (**w - expected).abs() < 1e-4 * expected)
            .count();
        let strand = spin.iter().filter(|w| w.abs() < 1e-12).count();
        assert!(wrap >= 28 && strand >= 70, "{wrap} {strand}: {spin:?}");
        for w in &sim.state.pulley_omega {
            assert!((w - expected).abs() < 1e-4 * expected, "{w}");
        }
    }
}
