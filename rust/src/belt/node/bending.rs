//! Rotational bending springs of the node belt (thesis eq. 4.11, 4.31, 4.47).

use super::{next, perp};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Rotational bending springs, potential ½·k_θ·θ² per node (thesis eq. 4.11, 4.31).
///
/// θ_j is the signed angle from element j−1 to element j. The gradient is
/// ∂θ/∂x_{j+1} = b⊥/|b|², ∂θ/∂x_{j−1} = a⊥/|a|², ∂θ/∂x_j = −(both), with a = x_j − x_{j−1},
/// b = x_{j+1} − x_j and ⊥ the left normal. (The thesis' eq. 4.47 prints B_v twice and has
/// OCR-damaged signs; this form is checked against finite differences in the tests.)
///
/// Cost: each element vector and its 1/|·|² are computed once and carried to the next node
/// (one division per node), each node's force is read and written once (no bounds checks),
/// and θ = atan(cross/dot) while the angle is below 45°
/// (dot > |cross|), which is the same angle as atan2(cross, dot) but about twice as fast;
/// atan2 is kept for sharper kinks. See `docs/performance.md`.
pub fn bending(x: &[V2], k_theta: &[f64], force: &mut [V2]) {
    let n = x.len();
    if n < 3 {
        return;
    }
    // The pull of the spring at node j on its neighbours: ga_j on node j−1, gb_j on node
    // j+1 (with minus signs), ga_j + gb_j on node j itself. Element vectors and their
    // 1/|·|² are carried from one node to the next.
    let spring = |a: V2, inv_a2: f64, b: V2, k: f64| -> (V2, V2, f64) {
        let inv_b2 = 1.0 / b.norm_squared();
        let moment = k * angle(a.perp(&b), a.dot(&b));
        (
            perp(a) * (moment * inv_a2),
            perp(b) * (moment * inv_b2),
            inv_b2,
        )
    };
    let a0 = x[0] - x[n - 1];
    let b0 = x[1] - x[0];
    let (ga0, gb0, inv_b0) = spring(a0, 1.0 / a0.norm_squared(), b0, k_theta[0]);
    let b1 = x[2] - x[1];
    let (ga1, gb1, inv_b1) = spring(b0, inv_b0, b1, k_theta[1]);
    // Node j−1 is complete once the spring at j is known: it gets −gb_{j−2}, then
    // +(ga+gb)_{j−1}, then −ga_j, the order in which the former scatter loop added them,
    // so the sums are the same to the last bit.
    let (mut gb_before, mut g_prev, mut gb_prev) = (gb0, ga1 + gb1, gb1);
    let (mut a, mut inv_a2) = (b1, inv_b1);
    for ((f, (xj, xn)), &k) in force[1..n - 2]
        .iter_mut()
        .zip(x[2..].iter().zip(&x[3..]))
        .zip(&k_theta[2..n - 1])
    {
        let b = xn - xj;
        let (ga, gb, inv_b2) = spring(a, inv_a2, b, k);
        *f = ((*f - gb_before) + g_prev) - ga;
        (gb_before, g_prev, gb_prev) = (gb_prev, ga + gb, gb);
        (a, inv_a2) = (b, inv_b2);
    }
    // The closing element and the three nodes whose sums wrap around the loop.
    let b = x[0] - x[n - 1];
    let (ga, gb, _) = spring(a, inv_a2, b, k_theta[n - 1]);
    force[n - 2] = ((force[n - 2] - gb_before) + g_prev) - ga;
    force[n - 1] = ((force[n - 1] - ga0) - gb_prev) + (ga + gb);
    force[0] = ((force[0] + (ga0 + gb0)) - ga1) - gb;
}

/// Signed angle atan2(cross, dot), rad, through atan(cross/dot) when the angle is below 45°.
#[inline(always)]
fn angle(cross: f64, dot: f64) -> f64 {
    if dot > cross.abs() {
        (cross / dot).atan()
    } else {
        cross.atan2(dot)
    }
}

/// Signed bending angle at every node, rad (for energies and output).
pub fn bending_angle(x: &[V2], j: usize) -> f64 {
    let n = x.len();
    let prev = if j == 0 { n - 1 } else { j - 1 };
    let a = x[j] - x[prev];
    let b = x[next(j, n)] - x[j];
    a.perp(&b).atan2(a.dot(&b))
}

/// [`bending`] for an open belt: springs at the interior nodes 1..n−2 only (an end has
/// one element, so no angle), summed in a plain loop (open belts are short).
pub fn bending_open(x: &[V2], k_theta: &[f64], force: &mut [V2]) {
    let n = x.len();
    for j in 1..n.saturating_sub(1) {
        let (a, b) = (x[j] - x[j - 1], x[j + 1] - x[j]);
        let moment = k_theta[j] * angle(a.perp(&b), a.dot(&b));
        let ga = perp(a) * (moment / a.norm_squared());
        let gb = perp(b) * (moment / b.norm_squared());
        force[j - 1] -= ga;
        force[j] += ga + gb;
        force[j + 1] -= gb;
    }
}
