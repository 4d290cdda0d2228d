//! Internal belt forces of the node formulation: axial Kelvin-Voigt elements, bending
//! springs and gravity. Element e joins node e to node e+1; the last element closes the loop.
//!
//! This file is the axial pass (elements in SSE2 pairs, node weights folded in, and the
//! iterator form the integrator fuses with); [`bending`](mod@bending) holds the bending
//! springs and [`stage`] the stage functions the pipeline calls.

mod bending;
pub mod stage;
pub mod zener;

pub use bending::{bending, bending_angle, bending_open};

use nalgebra::Vector2;
use std::cell::Cell;

type V2 = Vector2<f64>;

/// Left normal (counter-clockwise perpendicular) of a vector.
#[inline(always)]
pub fn perp(a: V2) -> V2 {
    V2::new(-a.y, a.x)
}

#[inline(always)]
pub(crate) fn next(i: usize, n: usize) -> usize {
    if i + 1 == n {
        0
    } else {
        i + 1
    }
}

/// Two elements' values (lanes 0 and 1): the axial pass computes elements in pairs.
type Pair = [f64; 2];

/// `[f(0), f(1)]`.
#[inline(always)]
fn lanes<T>(f: impl FnMut(usize) -> T) -> [T; 2] {
    std::array::from_fn(f)
}

/// Square roots of both lanes in one SSE2 instruction (correctly rounded, so the same bits
/// as `f64::sqrt` on each). The compiler does not pair them by itself in the fused sweep.
#[inline(always)]
fn sqrt2(a: Pair) -> Pair {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_loadu_pd, _mm_sqrt_pd, _mm_storeu_pd};
        let mut out = [0.0; 2];
        // SAFETY: SSE2 is part of the x86-64 baseline; the pointers are to two local
        // arrays of two f64 each (unaligned loads and stores need no alignment).
        unsafe { _mm_storeu_pd(out.as_mut_ptr(), _mm_sqrt_pd(_mm_loadu_pd(a.as_ptr()))) };
        out
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        a.map(f64::sqrt)
    }
}

/// `a / b` in both lanes in one SSE2 instruction (correctly rounded, the same bits as two
/// divisions).
#[inline(always)]
fn div2(a: Pair, b: Pair) -> Pair {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_div_pd, _mm_loadu_pd, _mm_storeu_pd};
        let mut out = [0.0; 2];
        // SAFETY: as in `sqrt2`.
        unsafe {
            _mm_storeu_pd(
                out.as_mut_ptr(),
                _mm_div_pd(_mm_loadu_pd(a.as_ptr()), _mm_loadu_pd(b.as_ptr())),
            )
        };
        out
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        lanes(|i| a[i] / b[i])
    }
}

/// Two axial elements (element vectors `d`): tension k(l − l⁰), clipped at zero for a
/// slack tension-only belt, and the force d·T/l each puts on its first node (minus that on
/// its second).
#[inline(always)]
fn elastic_elements<const TENSION_ONLY: bool>(d: [V2; 2], k: Pair, l0: Pair) -> (Pair, [V2; 2]) {
    let l = sqrt2(lanes(|i| d[i].x * d[i].x + d[i].y * d[i].y));
    let t = lanes(|i| {
        let t = k[i] * (l[i] - l0[i]);
        // A select, not `max`: a NaN tension must stay NaN for the divergence check.
        if TENSION_ONLY && t < 0.0 {
            0.0
        } else {
            t
        }
    });
    let r = div2(t, l);
    (t, lanes(|i| d[i] * r[i]))
}

/// Two Kelvin-Voigt elements: T = k(l − l⁰) + c·dl/dt with dl/dt = d·(v₂ − v₁)/l (`dv` =
/// v₂ − v₁); a slack tension-only element (l < l⁰) and a negative total carry nothing.
#[inline(always)]
fn damped_elements<const TENSION_ONLY: bool>(
    d: [V2; 2],
    dv: [V2; 2],
    k: Pair,
    c: Pair,
    l0: Pair,
) -> (Pair, [V2; 2]) {
    let l = sqrt2(lanes(|i| d[i].x * d[i].x + d[i].y * d[i].y));
    let rate = div2(lanes(|i| d[i].x * dv[i].x + d[i].y * dv[i].y), l);
    let t = lanes(|i| {
        let stretch = l[i] - l0[i];
        let t = k[i] * stretch + c[i] * rate[i];
        if TENSION_ONLY && (stretch < 0.0 || t < 0.0) {
            0.0
        } else {
            t
        }
    });
    let r = div2(t, l);
    (t, lanes(|i| d[i] * r[i]))
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

/// A per-element or per-node parameter of the axial pass: one value for the whole belt
/// (`f64`, held in a register) or one value per item (a slice, streamed from memory). A
/// uniform belt passes scalars and the pass streams three arrays less (24 B per node-step;
/// see `docs/performance.md`); anything else (e.g. node masses that differ) passes the
/// arrays. Both are the same values, so the forces are the same to the last bit.
pub trait PerItem: Copy {
    /// The value of item `i`.
    fn at(self, i: usize) -> f64;
    /// The values of items `start..`, in order.
    fn iter_from(self, start: usize) -> impl Iterator<Item = f64>;
}

impl PerItem for f64 {
    #[inline(always)]
    fn at(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn iter_from(self, _: usize) -> impl Iterator<Item = f64> {
        std::iter::repeat(self)
    }
}

impl<T: AsRef<[f64]> + ?Sized> PerItem for &T {
    #[inline(always)]
    fn at(self, i: usize) -> f64 {
        self.as_ref()[i]
    }
    #[inline(always)]
    fn iter_from(self, start: usize) -> impl Iterator<Item = f64> {
        self.as_ref()[start..].iter().copied()
    }
}

/// Where the axial pass puts each element's tension (N): an array, or nowhere
/// ([`NoTensions`]) when nothing will read them (stepping without recording: 8 B per
/// node-step less).
pub trait Tensions {
    /// Tension of element `e`.
    fn set(&mut self, e: usize, t: f64);
}

impl<T: AsMut<[f64]> + ?Sized> Tensions for &mut T {
    #[inline(always)]
    fn set(&mut self, e: usize, t: f64) {
        self.as_mut()[e] = t;
    }
}

/// Drops the tensions (see [`Tensions`]).
pub struct NoTensions;

impl Tensions for NoTensions {
    #[inline(always)]
    fn set(&mut self, _: usize, _: f64) {}
}

/// The belt's axial elements and node weights, as the axial pass needs them.
#[derive(Debug, Clone, Copy)]
pub struct AxialBelt<'a> {
    /// Element stiffness EA/l⁰, N/m.
    pub stiffness: &'a [f64],
    /// Element damping, N·s/m (read only when `damped`).
    pub damping: &'a [f64],
    /// Element rest length, m.
    pub rest_length: &'a [f64],
    /// Node mass for the weights, kg.
    pub mass: &'a [f64],
    /// The common (stiffness, damping, rest length, mass) when every element and node has
    /// the same, bit for bit: the pass then reads scalars instead of the arrays.
    pub uniform: Option<Uniform>,
    /// Kelvin-Voigt elements (with dashpots) or elastic ones.
    pub damped: bool,
    /// An open belt: the last entry (node n−1 back to node 0) is no element; the pass
    /// skips it (one branch per pass) and its tension is 0.
    pub open: bool,
    /// A slack element carries nothing.
    pub tension_only: bool,
    /// Gravitational acceleration, m/s² (0 without a gravity stage).
    pub gravity: f64,
}

/// Parameters shared by every element and node of a uniform belt (see [`AxialBelt`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Uniform {
    /// Element stiffness EA/l⁰, N/m.
    pub stiffness: f64,
    /// Element damping, N·s/m.
    pub damping: f64,
    /// Element rest length, m.
    pub rest_length: f64,
    /// Node mass, kg.
    pub mass: f64,
}

impl Uniform {
    /// The common values, if every element of each array is the same bit for bit.
    pub fn of(
        stiffness: &[f64],
        damping: &[f64],
        rest_length: &[f64],
        mass: &[f64],
    ) -> Option<Uniform> {
        Some(Uniform {
            stiffness: all_same(stiffness)?,
            damping: all_same(damping)?,
            rest_length: all_same(rest_length)?,
            mass: all_same(mass)?,
        })
    }
}

/// The common value if every element of `values` is the same, bit for bit.
pub fn all_same(values: &[f64]) -> Option<f64> {
    let first = *values.first()?;
    values
        .iter()
        .all(|v| v.to_bits() == first.to_bits())
        .then_some(first)
}

/// Axial springs (elastic, thesis eq. 4.40, or Kelvin-Voigt, eq. 4.40 + 4.56) and gravity,
/// eq. 4.49: the element tension acts along each element, the weight m·g on each node.
/// **Writes** (does not add to) `force`: this is the first stage that touches it, so no
/// reset or gravity pass is needed. Puts each element tension in `tension`.
///
/// `nodes` yields every node's (position, velocity) in order, exactly once, as the pass
/// reaches it: read from the state, or integrated just then (the integration fused with
/// the next step's axial pass, which may read each node's old force from `force` before
/// the pass overwrites it: the force of node i is written only once node i+1 has been
/// taken). Returns `nodes`, exhausted (the fused integration keeps its finiteness flag in
/// it). See [`axial`], [`axial_damped`] and `docs/performance.md`.
#[inline(always)]
pub fn axial_pass<I: Iterator<Item = (V2, V2)>>(
    belt: &AxialBelt,
    nodes: I,
    tension: &mut impl Tensions,
    force: &[Cell<V2>],
) -> I {
    // Chosen outside the loop: the clipping of a tension-only belt (a compile-time
    // constant, so the loop does not test it), scalar or array parameters, the law.
    if belt.tension_only {
        axial_params::<true, I>(belt, nodes, tension, force)
    } else {
        axial_params::<false, I>(belt, nodes, tension, force)
    }
}

/// [`axial_pass`] with scalar or array parameters.
#[inline(always)]
fn axial_params<const TENSION_ONLY: bool, I: Iterator<Item = (V2, V2)>>(
    belt: &AxialBelt,
    nodes: I,
    tension: &mut impl Tensions,
    force: &[Cell<V2>],
) -> I {
    match belt.uniform {
        Some(u) => axial_elements::<TENSION_ONLY, I>(
            belt,
            nodes,
            (u.stiffness, u.damping, u.rest_length, u.mass),
            tension,
            force,
        ),
        None => axial_elements::<TENSION_ONLY, I>(
            belt,
            nodes,
            (belt.stiffness, belt.damping, belt.rest_length, belt.mass),
            tension,
            force,
        ),
    }
}

/// [`axial_pass`] with the element law chosen.
#[inline(always)]
fn axial_elements<const TENSION_ONLY: bool, I: Iterator<Item = (V2, V2)>>(
    belt: &AxialBelt,
    nodes: I,
    params: (impl PerItem, impl PerItem, impl PerItem, impl PerItem),
    tension: &mut impl Tensions,
    force: &[Cell<V2>],
) -> I {
    let (gravity, open) = (belt.gravity, belt.open);
    if belt.damped {
        let law = damped_elements::<TENSION_ONLY>;
        axial_sweep(nodes, params, (gravity, open), law, tension, force)
    } else {
        let law = |d, _, k, _, l0| elastic_elements::<TENSION_ONLY>(d, k, l0);
        axial_sweep(nodes, params, (gravity, open), law, tension, force)
    }
}

/// The one loop of the axial pass: elements e and e+1 (a square root and a division
/// each, paired in one SSE2 instruction) and then nodes e and e+1, which need the force of
/// element e−1, carried from the previous iteration. `law` computes two elements from
/// their vectors, relative velocities, stiffnesses, damping and rest lengths; the first,
/// the last and an odd one out are computed alone (in both lanes). With `open`, the
/// closing entry is no element (an open belt).
#[inline(always)]
fn axial_sweep<I: Iterator<Item = (V2, V2)>>(
    mut nodes: I,
    (k, c, l0, mass): (impl PerItem, impl PerItem, impl PerItem, impl PerItem),
    (gravity, open): (f64, bool),
    law: impl Fn([V2; 2], [V2; 2], Pair, Pair, Pair) -> (Pair, [V2; 2]),
    tension: &mut impl Tensions,
    force: &[Cell<V2>],
) -> I {
    let n = force.len();
    let alone = |d: V2, dv: V2, k: f64, c: f64, l0: f64| {
        let (t, fe) = law([d; 2], [dv; 2], [k; 2], [c; 2], [l0; 2]);
        (t[0], fe[0])
    };
    let (x0, v0) = nodes.next().expect("one item per node");
    let (x1, v1) = nodes.next().expect("one item per node");
    let (t_first, fe_first) = alone(x1 - x0, v1 - v0, k.at(0), c.at(0), l0.at(0));
    tension.set(0, t_first);
    let (mut xa, mut va, mut prev) = (x1, v1, fe_first);
    // Elements 1..n−2 and nodes 1..n−2 (nodes 2..n−1 taken), two per iteration (one
    // loop count, so the loop tests nothing else), then an odd one out.
    let mut take = || nodes.next().expect("one item per node");
    let pairs = force[1..n - 1].chunks_exact(2);
    let odd = pairs.remainder();
    for (e, pair) in (1..).step_by(2).zip(pairs) {
        let ((xb, vb), (xc, vc)) = (take(), take());
        let (t, fe) = law(
            [xb - xa, xc - xb],
            [vb - va, vc - vb],
            [k.at(e), k.at(e + 1)],
            [c.at(e), c.at(e + 1)],
            [l0.at(e), l0.at(e + 1)],
        );
        tension.set(e, t[0]);
        tension.set(e + 1, t[1]);
        pair[0].set(node_force(prev, fe[0], mass.at(e), gravity));
        pair[1].set(node_force(fe[0], fe[1], mass.at(e + 1), gravity));
        (xa, va, prev) = (xc, vc, fe[1]);
    }
    if let [f] = odd {
        let e = n - 2;
        let (xb, vb) = take();
        let (t, fe) = alone(xb - xa, vb - va, k.at(e), c.at(e), l0.at(e));
        tension.set(e, t);
        f.set(node_force(prev, fe, mass.at(e), gravity));
        (xa, va, prev) = (xb, vb, fe);
    }
    // The closing element n−1 runs from node n−1 (now in xa) to node 0 (none if open).
    let (t_last, fe_last) = if open {
        (0.0, V2::zeros())
    } else {
        alone(x0 - xa, v0 - va, k.at(n - 1), c.at(n - 1), l0.at(n - 1))
    };
    tension.set(n - 1, t_last);
    force[n - 1].set(node_force(prev, fe_last, mass.at(n - 1), gravity));
    force[0].set(first_node_force(fe_first, fe_last, mass.at(0), gravity));
    nodes
}

/// Elastic axial springs and gravity ([`axial_pass`] on the nodes at rest in `x`), for
/// the kernel tests.
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
    let at_rest = vec![V2::zeros(); x.len()];
    axial_with(
        x,
        &at_rest,
        (k, k, false),
        l0,
        tension_only,
        mass,
        gravity,
        tension,
        force,
    );
}

/// Kelvin-Voigt axial elements and gravity ([`axial_pass`] on the nodes in `x`, `v`), for
/// the kernel tests.
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
    axial_with(
        x,
        v,
        (k, c, true),
        l0,
        tension_only,
        mass,
        gravity,
        tension,
        force,
    );
}

/// [`axial_pass`] on arrays: `springs` = (stiffness, damping, damped).
#[allow(clippy::too_many_arguments)]
fn axial_with(
    x: &[V2],
    v: &[V2],
    springs: (&[f64], &[f64], bool),
    l0: &[f64],
    tension_only: bool,
    mass: &[f64],
    gravity: f64,
    tension: &mut [f64],
    force: &mut [V2],
) {
    let (stiffness, damping, damped) = springs;
    let belt = AxialBelt {
        stiffness,
        damping,
        rest_length: l0,
        mass,
        uniform: None,
        damped,
        open: false,
        tension_only,
        gravity,
    };
    let nodes = x.iter().zip(v).map(|(&x, &v)| (x, v));
    let _ = axial_pass(
        &belt,
        nodes,
        &mut &mut *tension,
        Cell::from_mut(force).as_slice_of_cells(),
    );
}
