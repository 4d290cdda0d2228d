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

/// One axial element: tension k(l − l⁰), clipped at zero for a slack `tension_only` belt,
/// and the force d·T/l it puts on its first node (minus that on its second).
#[inline(always)]
fn elastic_element(d: V2, k: f64, l0: f64, tension_only: bool) -> (f64, V2) {
    let l = (d.x * d.x + d.y * d.y).sqrt();
    let t = k * (l - l0);
    // A select, not `max`: a NaN tension must stay NaN for the divergence check.
    let t = if tension_only && t < 0.0 { 0.0 } else { t };
    (t, d * (t / l))
}

/// Force on a node from the element before it (`prev`, that element's force on its first
/// node), the element after it (`cur`) and its weight −m·g ŷ (thesis eq. 4.49), summed in
/// the order of the former separate passes (reset, gravity, elements in order), so that
/// the forces are the same to the last bit.
#[inline(always)]
fn node_force(prev: V2, cur: V2, m: f64, gravity: f64) -> V2 {
    V2::new(
        (0.0 - prev.x) + cur.x,
        ((0.0 - m * gravity) - prev.y) + cur.y,
    )
}

/// Node 0: its sum started with element 0 (before the closing element n−1).
#[inline(always)]
fn first_node_force(first: V2, closing: V2, m: f64, gravity: f64) -> V2 {
    V2::new(
        (0.0 + first.x) - closing.x,
        ((0.0 - m * gravity) + first.y) - closing.y,
    )
}

/// Elastic axial springs, thesis eq. 4.40, and gravity, eq. 4.49: the force k(l − l⁰) acts
/// along each element, the weight m·g on each node (`gravity` = 0 without a gravity stage).
/// **Writes** (does not add to) `force`: this is the first stage that touches it, so no
/// reset or gravity pass is needed. Writes the element tension (positive in tension, N) to
/// `tension`.
///
/// One pass: element e (one square root and one division) and then node e, which needs the
/// force of element e−1, carried from the previous iteration. The compiler vectorises this
/// loop (two elements per SSE2 register) despite the carried value. See
/// `docs/performance.md`.
#[allow(clippy::too_many_arguments)]
pub fn axial(
    x: &[V2],
    k: &[f64],
    l0: &[f64],
    tension_only: bool,
    mass: &[f64],
    gravity: f64,
    tension: &mut [f64],
    force: &mut [V2],
) {
    let n = x.len();
    let (t_last, fe_last) = elastic_element(x[0] - x[n - 1], k[n - 1], l0[n - 1], tension_only);
    let (t_first, fe_first) = elastic_element(x[1] - x[0], k[0], l0[0], tension_only);
    (tension[0], tension[n - 1]) = (t_first, t_last);
    let mut prev = fe_first;
    // Elements 1..n−2 and nodes 1..n−2.
    let inner = 1..n - 1;
    for (((((f, te), (a, b)), &k), &l0), &m) in force[inner.clone()]
        .iter_mut()
        .zip(&mut tension[inner.clone()])
        .zip(x[1..].iter().zip(&x[2..]))
        .zip(&k[inner.clone()])
        .zip(&l0[inner.clone()])
        .zip(&mass[inner])
    {
        let (t, fe) = elastic_element(b - a, k, l0, tension_only);
        *te = t;
        *f = node_force(prev, fe, m, gravity);
        prev = fe;
    }
    force[n - 1] = node_force(prev, fe_last, mass[n - 1], gravity);
    force[0] = first_node_force(fe_first, fe_last, mass[0], gravity);
}

/// One Kelvin-Voigt element: T = k(l − l⁰) + c·dl/dt with dl/dt = d·(v₂ − v₁)/l; a slack
/// `tension_only` element (l < l⁰) and a negative total carry nothing.
#[inline(always)]
fn damped_element(d: V2, dv: V2, k: f64, c: f64, l0: f64, tension_only: bool) -> (f64, V2) {
    let l = (d.x * d.x + d.y * d.y).sqrt();
    let rate = (d.x * dv.x + d.y * dv.y) / l;
    let stretch = l - l0;
    let t = k * stretch + c * rate;
    let t = if tension_only && (stretch < 0.0 || t < 0.0) {
        0.0
    } else {
        t
    };
    (t, d * (t / l))
}

/// Kelvin-Voigt axial elements, thesis eq. 4.40 + 4.56: T = k(l − l⁰) + c·dl/dt, and
/// gravity, as [`axial`] (which see: `force` is written, not added to). With
/// `tension_only`, a slack element (l < l⁰) carries nothing and the total is clipped at
/// zero (a dashpot cannot push a slack belt).
#[allow(clippy::too_many_arguments)]
pub fn axial_damped(
    x: &[V2],
    v: &[V2],
    k: &[f64],
    c: &[f64],
    l0: &[f64],
    tension_only: bool,
    mass: &[f64],
    gravity: f64,
    tension: &mut [f64],
    force: &mut [V2],
) {
    let n = x.len();
    let element = |e: usize, j: usize| {
        damped_element(x[j] - x[e], v[j] - v[e], k[e], c[e], l0[e], tension_only)
    };
    let (t_last, fe_last) = element(n - 1, 0);
    let (t_first, fe_first) = element(0, 1);
    (tension[0], tension[n - 1]) = (t_first, t_last);
    let mut prev = fe_first;
    let inner = 1..n - 1;
    for ((((((f, te), (xa, xb)), (va, vb)), (&k, &c)), &l0), &m) in force[inner.clone()]
        .iter_mut()
        .zip(&mut tension[inner.clone()])
        .zip(x[1..].iter().zip(&x[2..]))
        .zip(v[1..].iter().zip(&v[2..]))
        .zip(k[inner.clone()].iter().zip(&c[inner.clone()]))
        .zip(&l0[inner.clone()])
        .zip(&mass[inner])
    {
        let (t, fe) = damped_element(xb - xa, vb - va, k, c, l0, tension_only);
        *te = t;
        *f = node_force(prev, fe, m, gravity);
        prev = fe;
    }
    force[n - 1] = node_force(prev, fe_last, mass[n - 1], gravity);
    force[0] = first_node_force(fe_first, fe_last, mass[0], gravity);
}

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
