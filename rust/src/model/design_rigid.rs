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

/// The rigid belt's wrap joints (`belt::rigid::wrap_joint`) on the closed chain of bodies of
/// length `l0` (m) placed on `vertices` (body k from vertex k to k + 1), on the drums
/// (centre, radius) `drums`: for each boundary joint, (B, side, x, t_C) — the body whose end
/// stands off the drum's body's by side·x·t_C.
pub(crate) fn wrap_offsets(
    vertices: &[V2],
    l0: f64,
    drums: &[(V2, f64)],
) -> Vec<(usize, f64, f64, V2)> {
    use crate::belt::rigid::sdes::{LinkState, SdeParams};
    let n = vertices.len();
    let (centres, angles) = bodies(vertices);
    let links = |i: usize| LinkState {
        position: centres[i],
        angle: angles[i],
        velocity: V2::zeros(),
        angular_velocity: 0.0,
        length: l0,
    };
    let params = |_: usize| SdeParams {
        translational_stiffness: 1.0,
        translational_damping: 0.0,
        torsional_stiffness: 0.0,
        torsional_damping: 0.0,
    };
    let mut out = Vec::new();
    for &(center, radius) in drums {
        crate::belt::rigid::wrap_joint::for_each_wrap(
            &links,
            n,
            true,
            0,
            n,
            center,
            radius,
            &params,
            |a| {
                out.push((a.slider(), a.side(), a.load.offset, a.load.tangent));
            },
        );
    }
    out
}

/// Move each wrap joint's body B (`offsets` of [`wrap_offsets`]) so that its end at the
/// joint stands off the drum's body's by side·x·t_C and its other end keeps its joint's
/// gap: the walk gave B's chord x·(t_C·t_B) more, half at each end.
pub(crate) fn stand_off(
    centres: &mut [V2],
    angles: &mut [f64],
    l0: f64,
    offsets: &[(usize, f64, f64, V2)],
) {
    for &(b, side, x, tc) in offsets {
        let tb = V2::new(angles[b].cos(), angles[b].sin());
        let half = tb * (0.5 * l0);
        let (left, right) = (centres[b] - half, centres[b] + half);
        let along = x * tc.dot(&tb);
        let at_joint = (tc * x - tb * (0.5 * along)) * side;
        let at_far = tb * (0.5 * along * side);
        // Entering (side −1): B's right end is at the joint; leaving: its left end.
        let (left, right) = if side < 0.0 {
            (left + at_far, right + at_joint)
        } else {
            (left + at_joint, right + at_far)
        };
        let d = right - left;
        centres[b] = 0.5 * (left + right);
        angles[b] = d.y.atan2(d.x);
    }
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

    /// Two drums of radius 0.5 m 12 m apart, the top span on nine rolls of radius 0.1 m at
    /// a pitch of 1.2 m (1e8 N/m), the bottom span on nine more, a 30 kg/m belt (EA = 100 MN) of 5 cm rigid bodies in
    /// gravity, placed at 5 kN at rest, its spans in their sag or straight: the node belt's
    /// sag kernel scene (`design_tests::span_on_rolls`) with rigid bodies.
    fn rigid_span_on_rolls(sag: bool) -> crate::scene::Scene {
        use crate::scene::{IdlerSpec, InitialState};
        let mut scene = two_drums(0.0);
        scene.pulleys[1].center = [12.0, 0.0];
        scene.gravity = 9.81;
        scene.belt.mass_per_length = 30.0;
        scene.belt.axial_stiffness = 1e8;
        scene.belt.elements = Some(((24.0 + std::f64::consts::PI) / 0.05) as usize);
        // carry rolls under the top strand, return rolls under the bottom one
        scene.idlers = [0.4, -0.6]
            .iter()
            .flat_map(|&y| {
                (0..9).map(move |k| IdlerSpec {
                    center: [1.2 + 1.2 * k as f64, y],
                    radius: 0.1,
                    contact_stiffness: 1e8,
                    ..Default::default()
                })
            })
            .collect();
        scene.initial = Some(InitialState {
            tension: vec![5e3],
            sag,
            ..Default::default()
        });
        scene
    }

    #[test]
    fn rigid_sag_placement_hangs_the_spans_and_holds_the_joints() {
        // q = 294.3 N/m, T = 5 kN, a = 1.2 m: mid-span sag q·a²/(8T) = 10.6 mm, slope
        // θ = q·a/2T = 0.035 at the rolls, roll load q·a = 353 N, its depth 3.5 µm.
        let (t, q, a) = (5e3, 30.0 * 9.81, 1.2);
        let mut sim = crate::Simulation::new(&rigid_span_on_rolls(true)).unwrap();
        let l = sim.model.element_length();
        // (1) Every joint carries T at t = 0: the chords between joint points are walked on
        // the sagged curve with each gap l·T/EA along its joint's bisector. Measured: 1.5 N
        // (3·10⁻⁴ of T; the tangent points' bodies, as without sag). 10⁻³ of T.
        let worst = sim
            .tensions()
            .iter()
            .map(|x| (x - t).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-3 * t, "{worst} N");
        // (2) Each inner roll carries one pitch of belt, q·a, within one body's weight (the
        // lumping of the loads on the bodies; the node belt's kernel test holds the same).
        // Measured: 353.19–353.34 N against 353.16 N.
        sim.tensions();
        let rolls: Vec<f64> = sim.scratch.idler_contacts[1..8]
            .iter()
            .map(|c| c.normal_force)
            .collect();
        for (k, f) in rolls.iter().enumerate() {
            assert!(
                (f - q * a).abs() < q * l,
                "roll {}: {f} N vs {} N",
                k + 1,
                q * a
            );
        }
        // (3) The mass centres hang in each span's parabola q·x·(a − x)/(2T) below the rolls'
        // contact points (q·a/k below their tops), which the catenary matches to
        // (q·a/T)²/96 of the sag (5 µm). The model's own departures from the continuous
        // belt, all lifting the span: a roll presses the mass centres' chord over it at γ,
        // each body hands its share half to each of its joints, so the roll's kink 2θ is
        // spread over three joints ((1 − γ)θ, θ, γθ, one body apart) and the chord at the
        // roll lies θ·l/2·(1 + 2γ(1 − γ)) ≤ 3θ·l/4 below the two tangents' meeting point
        // (the node belt: 2θ·γ(1 − γ)·l ≤ θ·l/2), which lifts the whole span by that;
        // each mass centre is the middle of a chord of the joints' parabola, q·l²/(8T)
        // above it; the chord's tilt φ on the roll, R·φ²/2. Measured: the worst body
        // 1.30 mm off at l = 5 cm, the lift 3θ·l/4 = 1.31 mm (γ ≈ 1/2 on these rolls).
        let theta = q * a / (2.0 * t);
        let tolerance = 0.75 * theta * l + q * l * l / (8.0 * t) + 0.1 * theta * theta / 2.0 + 5e-6;
        let delta = q * a / 1e8;
        let x: Vec<V2> = sim.state.position.clone();
        let mut checked = 0;
        for k in 1..7 {
            let xa = 1.2 + a * k as f64;
            let span: Vec<V2> = x
                .iter()
                .copied()
                .filter(|p| p.y > 0.3 && p.x > xa + 2.0 * l && p.x < xa + a - 2.0 * l)
                .collect();
            for p in &span {
                let u = p.x - xa;
                let parabola = delta + q * u * (a - u) / (2.0 * t);
                let catenary =
                    delta + t / q * ((q * a / (2.0 * t)).cosh() - (q * (u - 0.5 * a) / t).cosh());
                let sag = 0.5 - p.y;
                assert!(
                    (sag - parabola).abs() < tolerance,
                    "x = {u}: {sag} vs {parabola}"
                );
                assert!(
                    (sag - catenary).abs() < tolerance,
                    "x = {u}: {sag} vs {catenary}"
                );
                checked += 1;
            }
            let lowest = span.iter().map(|p| 0.5 - p.y).fold(0.0, f64::max);
            let mid = delta + q * a * a / (8.0 * t);
            assert!(
                (lowest - mid).abs() < tolerance,
                "span {k}: {lowest} vs {mid}"
            );
        }
        assert!(checked > 100, "{checked} bodies checked");
    }

    #[test]
    fn rigid_sag_placement_stays_at_rest() {
        // At rest for 0.2 s (the drums held by nothing, free to turn): placed straight the
        // spans sink into their sag (10.6 mm) and ring the joints by 12.4 kN of 5 kN
        // (measured); placed in their sag no joint leaves T by more than 392 N (measured;
        // the node belt's own sag placement on the same scene: 555 N: on this stiff belt,
        // EA/l = 2·10⁹ N/m, 0.2 µm of a joint is 400 N, and the transition bodies at the
        // tangent points and the drums' wraps ring both formulations alike). Asserted:
        // within 10 % of T (the node belt's figure), and straight at least 10 times worse.
        let run = |sag: bool| {
            let mut sim = crate::Simulation::new(&rigid_span_on_rolls(sag)).unwrap();
            let mut worst = 0.0f64;
            for _ in 0..20 {
                sim.advance_to(sim.state.time + 0.01, u64::MAX).unwrap();
                let w = sim
                    .tensions()
                    .iter()
                    .map(|x| (x - 5e3).abs())
                    .fold(0.0, f64::max);
                worst = worst.max(w);
            }
            worst
        };
        let (sagged, straight) = (run(true), run(false));
        assert!(sagged < 0.1 * 5e3, "{sagged} N");
        assert!(straight > 5.0 * sagged, "{straight} N vs {sagged} N");
    }
}
