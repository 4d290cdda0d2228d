//! Internal belt forces of the node formulation: axial Kelvin-Voigt elements, bending
//! springs and gravity. Element e joins node e to node e+1; the last element closes the loop.

use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Left normal (counter-clockwise perpendicular) of a vector.
#[inline(always)]
pub fn perp(a: V2) -> V2 {
    V2::new(-a.y, a.x)
}

#[inline(always)]
fn next(i: usize, n: usize) -> usize {
    if i + 1 == n {
        0
    } else {
        i + 1
    }
}

/// Add node weights −m·g ŷ (thesis eq. 4.49).
pub fn gravity(mass: &[f64], g: f64, force: &mut [V2]) {
    for (f, &m) in force.iter_mut().zip(mass) {
        f.y -= m * g;
    }
}

/// Elastic axial springs, thesis eq. 4.40: the force k(l − l⁰) acts along each element.
/// Writes the element force (tension positive, N) to `tension`.
pub fn axial(
    x: &[V2],
    k: &[f64],
    l0: &[f64],
    tension_only: bool,
    force: &mut [V2],
    tension: &mut [f64],
) {
    let n = x.len();
    for e in 0..n {
        let j = next(e, n);
        let d = x[j] - x[e];
        let l = d.norm();
        let mut t = k[e] * (l - l0[e]);
        if tension_only && t < 0.0 {
            t = 0.0;
        }
        tension[e] = t;
        let f = d * (t / l);
        force[e] += f;
        force[j] -= f;
    }
}

/// Kelvin-Voigt axial elements, thesis eq. 4.40 + 4.56: T = k(l − l⁰) + c·dl/dt.
/// With `tension_only`, a slack element (l < l⁰) carries nothing and the total is clipped
/// at zero (a dashpot cannot push a slack belt).
#[allow(clippy::too_many_arguments)]
pub fn axial_damped(
    x: &[V2],
    v: &[V2],
    k: &[f64],
    c: &[f64],
    l0: &[f64],
    tension_only: bool,
    force: &mut [V2],
    tension: &mut [f64],
) {
    let n = x.len();
    for e in 0..n {
        let j = next(e, n);
        let d = x[j] - x[e];
        let l = d.norm();
        let rate = d.dot(&(v[j] - v[e])) / l;
        let stretch = l - l0[e];
        let mut t = k[e] * stretch + c[e] * rate;
        if tension_only && (stretch < 0.0 || t < 0.0) {
            t = 0.0;
        }
        tension[e] = t;
        let f = d * (t / l);
        force[e] += f;
        force[j] -= f;
    }
}

/// Rotational bending springs, potential ½·k_θ·θ² per node (thesis eq. 4.11, 4.31).
///
/// θ_j is the signed angle from element j−1 to element j. The gradient is
/// ∂θ/∂x_{j+1} = b⊥/|b|², ∂θ/∂x_{j−1} = a⊥/|a|², ∂θ/∂x_j = −(both), with a = x_j − x_{j−1},
/// b = x_{j+1} − x_j and ⊥ the left normal. (The thesis' eq. 4.47 prints B_v twice and has
/// OCR-damaged signs; this form is checked against finite differences in the tests.)
///
/// Cost: each element vector and its 1/|·|² are computed once and carried to the next node
/// (one division per node), and θ = atan(cross/dot) while the angle is below 45°
/// (dot > |cross|), which is the same angle as atan2(cross, dot) but about twice as fast;
/// atan2 is kept for sharper kinks. See `docs/performance.md`.
pub fn bending(x: &[V2], k_theta: &[f64], force: &mut [V2]) {
    let n = x.len();
    if n < 3 {
        return;
    }
    let mut a = x[0] - x[n - 1];
    let mut inv_a2 = 1.0 / a.norm_squared();
    for j in 0..n {
        let prev = if j == 0 { n - 1 } else { j - 1 };
        let nx = next(j, n);
        let b = x[nx] - x[j];
        let inv_b2 = 1.0 / b.norm_squared();
        let theta = angle(a.perp(&b), a.dot(&b));
        let moment = k_theta[j] * theta;
        let ga = perp(a) * (moment * inv_a2);
        let gb = perp(b) * (moment * inv_b2);
        force[nx] -= gb;
        force[prev] -= ga;
        force[j] += ga + gb;
        a = b;
        inv_a2 = inv_b2;
    }
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
