//! Sag placement for a design start (`initial.sag`, `docs/design-start.md`): each straight
//! span of the placement path that rests on idler rolls is placed in its static sag under
//! the weight of belt and material at the design tension.
//!
//! Statics of the discrete belt. On a straight line of the path (unit direction d, normal
//! n pointing up, n·ŷ = cos β) node j sits at abscissa x_j (its arc length on the line)
//! with an offset y_j along n. With element tensions H_e (the design tension at the
//! element's middle; the slopes are small, so the tension is its component along the line
//! to a relative (q·a/2T)²/2, 10⁻³ at the steepest), node j's balance along n is
//!
//! H_j·(y_{j+1} − y_j)/Δx_j − H_{j−1}·(y_j − y_{j−1})/Δx_{j−1} + R_j = m_j·g·cos β,
//!
//! with m_j the node's mass (belt plus material) and R_j the rolls' push: a roll touching
//! the line from below at abscissa x_k, on the element from node e to e + 1 at γ = (x_k −
//! x_e)/Δx_e, presses with k·δ, δ = h_k − ((1 − γ)·y_e + γ·y_{e+1}) its penetration (h_k the
//! roll top's offset, 0 on a path laid on the rolls), shared by the lever rule as the
//! idler contact does (`contact::idler_contact`); on an element tilted by φ the contact
//! point lies R·sin φ downhill of the roll's top and R·(1 − cos φ) below it (R the roll's
//! radius), with φ from the last solve (a fixed point). This is linear and tridiagonal in y; the
//! line's ends (its tangent points on a drum, or where a curve begins) are held at offset 0. A roll that
//! would pull (δ < 0) is dropped and the system solved again. Between two rolls the nodes
//! then lie on the funicular polygon of the node loads: on the parabola q·x·(a − x)/(2H)
//! through the contact points to within the chord of one element next to each roll, and
//! within (q·a/H)²/96 of the catenary (H/q)·(cosh(q·a/2H) − cosh(q·(x − a/2)/H)).

use crate::geometry::{BeltPath, Segment};
use crate::scene::Scene;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// The sag offsets of the placement: per line of the path, its unit normal (up) and the
/// knots (arc length s, offset y) in increasing s, with offset 0 at both ends of the line.
#[derive(Debug, Clone, Default)]
pub(super) struct SagShape {
    lines: Vec<SagLine>,
    /// The kinks on the rolls (`kinked` placement), in increasing arc length: the belt's
    /// path bends there, over the roll, not at the nodes. Each: its arc length, and the
    /// circle the wrap contact measures the belt's path over there (centre, radius, m).
    kinks: Vec<Kink>,
}

/// A kink of the sag shape on a roll: its arc length `s`, and the wrap contact's circle
/// there (`center`, `radius`, m: [`crate::contact::roll_wrap::wrap_radius`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Kink {
    pub s: f64,
    pub center: V2,
    pub radius: f64,
}

#[derive(Debug, Clone)]
struct SagLine {
    from: f64,
    to: f64,
    normal: V2,
    knots: Vec<(f64, f64)>,
}

impl SagShape {
    /// The first kink on a roll at arc length in (s0, s1], if any (no wrap round the path's
    /// end: the lines do not cross node 0's arc length).
    pub fn kink_in(&self, s0: f64, s1: f64) -> Option<Kink> {
        let k = self.kinks.partition_point(|k| k.s <= s0);
        self.kinks.get(k).copied().filter(|k| k.s <= s1)
    }

    /// The placement point at arc length `s` (modulo the path length): the path's point
    /// moved along its line's normal by the interpolated offset.
    pub fn point(&self, path: &BeltPath, s: f64) -> V2 {
        let p = path.point(s);
        let s = s.rem_euclid(path.length);
        match self.lines.iter().find(|l| s > l.from && s < l.to) {
            None => p,
            Some(l) => {
                let k = l.knots.partition_point(|&(x, _)| x <= s);
                if k == 0 || k >= l.knots.len() {
                    return p;
                }
                let ((s0, y0), (s1, y1)) = (l.knots[k - 1], l.knots[k]);
                let w = if s1 > s0 { (s - s0) / (s1 - s0) } else { 0.0 };
                p + l.normal * (y0 + (y1 - y0) * w)
            }
        }
    }
}

/// A roll under a line: abscissa on the line (m), top's offset (m), radius (m: with
/// `kinked`, the wrap contact's circle's, its top the roll's), stiffness (N/m).
struct Roll {
    x: f64,
    top: f64,
    radius: f64,
    stiffness: f64,
}

/// The sag of every straight line of `path` that rests on rolls, for nodes at arc lengths
/// `at` (increasing from node 0, below the path length) of masses `mass` (kg), with the
/// design tension `tension(s)` (N) at arc length s. `kinked` = Some(l), for elements of
/// l m: the belt bends over each roll at the roll (wrap contact on the rolls, `contact::roll_wrap`): the element over a
/// roll is its two straight pieces from its nodes to the roll's top, the roll a support
/// (its reaction the tension times the slope change there), instead of a penalty spring
/// on the element's chord; the kink is where the belt's straight pieces meet when they are
/// tangent to the wrap contact's circle over the roll (radius
/// [`crate::contact::roll_wrap::wrap_radius`] for elements of l m), so that an
/// element measured over the circle is as long as its pieces less the arc's shortcut.
///
/// `centres`: the points are the rigid-body belt's joint points (`super::design_rigid`),
/// each body the straight chord between two of them, its mass centre at the chord's middle.
/// The rolls touch the polygon of the mass centres (the rigid belt's idler contact, lever
/// rule onto the two bodies), and each body, whose joints are its only moments about its
/// mass centre, hands its load from weight and rolls half to each of its two joints: a roll
/// on the centres' chord from body e to body e + 1 at γ presses points e, e + 1, e + 2 with
/// the shares ((1 − γ)/2, 1/2, γ/2) and reads its depth with the same weights (a
/// pentadiagonal system). The masses are then the points' shares of the bodies (half of
/// each neighbour). Not with `kinked`.
pub(super) fn shape(
    scene: &Scene,
    path: &BeltPath,
    at: &[f64],
    mass: &[f64],
    tension: impl Fn(f64) -> f64,
    kinked: Option<f64>,
    centres: bool,
) -> SagShape {
    let (kinked, element) = match kinked {
        Some(l) if !centres => (true, l),
        _ => (false, 0.0),
    };
    let n = at.len();
    let g = scene.gravity;
    let mut lines = Vec::new();
    let mut kinks = Vec::new();
    if g <= 0.0 || n < 3 {
        return SagShape { lines, kinks };
    }
    let speed = crate::contact::roll_wrap::scene_speed(scene);
    for (seg, &from) in path.segments.iter().zip(&path.starts) {
        let Segment::Line { a, b } = *seg else {
            continue;
        };
        let len = (b - a).norm();
        if len <= 0.0 {
            continue;
        }
        let d = (b - a) / len;
        let mut normal = V2::new(-d.y, d.x);
        if normal.y < 0.0 {
            normal = -normal;
        }
        let cos_beta = normal.y;
        if cos_beta <= 1e-9 {
            continue; // a vertical line hangs straight
        }
        let rolls: Vec<Roll> = scene
            .idlers
            .iter()
            .filter(|r| r.contact_stiffness > 0.0)
            .filter_map(|r| {
                let c = V2::new(r.center[0], r.center[1]) - a;
                let (x, off) = (c.dot(&d), c.dot(&normal));
                let top = off + r.radius;
                (x > 0.0 && x < len && off < 0.0 && top.abs() <= 1e-3 * r.radius + 1e-6).then_some(
                    Roll {
                        x,
                        top,
                        radius: if kinked {
                            crate::contact::roll_wrap::wrap_radius(r.radius, element, speed, g)
                        } else {
                            r.radius
                        },
                        stiffness: r.contact_stiffness,
                    },
                )
            })
            .collect();
        if rolls.is_empty() {
            continue;
        }
        // The nodes on the line, in order (node order may run either way along it and
        // wrap round node 0). A node within `end` of one of the line's ends is on that end
        // (offset 0), not an unknown: at rest under one tension with an even number of
        // elements a node falls on the tangent point to rounding (at − from = len), and
        // its element of zero length made the system singular (NaN offsets, a walk at half
        // steps, a closure gap of 0.16 m on a 112 m builder conveyor at rest).
        let to = from + len;
        let end = 1e-9 * len.max(1.0);
        let on_line = |s: f64| s > from + end && s < to - end;
        let first = match (0..n).find(|&i| on_line(at[i])) {
            Some(i) => i,
            None => continue,
        };
        let first = if first == 0 && on_line(at[n - 1]) {
            // the run wraps round node 0: start after the last node off the line
            (0..n).rev().find(|&i| !on_line(at[i])).map_or(0, |i| i + 1)
        } else {
            first
        };
        let mut idx = Vec::new();
        let mut i = first;
        while idx.len() < n && on_line(at[i % n]) {
            idx.push(i % n);
            i += 1;
        }
        let m = idx.len();
        if m == 0 {
            continue;
        }
        // Abscissae with the line's two ends as the fixed supports (offset 0). The belt
        // leaves a drum at its tangent point: the node beyond it lies on the wrap, below
        // the line's extension (by d²/2r, d its distance past the end), so taking that node
        // at offset 0 on the extension would pin the span 0.1–0.2 m too far out and sag
        // the last node before the drum into it (measured: 0.8 mm inside a 0.315 m drum,
        // 10 mm before its top, an 80 kN penalty kick at the first step). The knots of
        // the shape hold offset 0 at the ends for the same reason.
        let xs: Vec<f64> = std::iter::once(0.0)
            .chain(idx.iter().map(|&i| at[i] - from))
            .chain(std::iter::once(len))
            .collect();
        // Element tensions between consecutive points (m + 1 elements).
        let h: Vec<f64> = (0..=m)
            .map(|e| tension(from + 0.5 * (xs[e] + xs[e + 1])))
            .collect();
        let weight: Vec<f64> = idx.iter().map(|&i| mass[i] * g * cos_beta).collect();
        let mut active = vec![true; rolls.len()];
        // The slope of the element over each roll: a tilted element's closest point to
        // the roll's centre (its foot) lies R·sin φ downhill of the top, and the element
        // touches when its foot lies R·(1 − cos φ) below the top (29 µm on a 0.1 m roll
        // at φ = 0.024, eight times the penetration that carries the span).
        let mut slope = vec![0.0; rolls.len()];
        // Kinked: the belt's turn over each roll (from the last solve). Its straight pieces,
        // tangent to the circle, meet ρ = R/cos(θ/2) from the centre, R·(1/cos(θ/2) − 1)
        // above the circle (R·θ²/8: 0.2 µm on a 0.0665 m roll at θ = 0.035, 53 µm at
        // θ = 0.08 on a 0.2 m circle; taking the circle's top instead started nodes that
        // deep inside it).
        let mut bend = vec![0.0; rolls.len()];
        let mut y = vec![0.0; m + 2];
        // The points the rolls touch the chords between: the nodes (with the line's ends),
        // or with `centres` the bodies' mass centres, the middles of the points' chords.
        let cx: Vec<f64> = if centres {
            xs.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect()
        } else {
            xs.clone()
        };
        // The contact point c's offset and its shares of the points (index, weight).
        let stencil = |c: usize, gamma: f64| -> [(usize, f64); 3] {
            if centres {
                [(c, 0.5 * (1.0 - gamma)), (c + 1, 0.5), (c + 2, 0.5 * gamma)]
            } else {
                [(c, 1.0 - gamma), (c + 1, gamma), (c, 0.0)]
            }
        };
        // The offset of contact point c itself.
        let point_y = |y: &[f64], c: usize| {
            if centres {
                0.5 * (y[c] + y[c + 1])
            } else {
                y[c]
            }
        };
        let height = |y: &[f64], c: usize, gamma: f64| -> f64 {
            stencil(c, gamma).iter().map(|&(i, w)| w * y[i]).sum()
        };
        // The element (the centres' chord) under the foot of roll k and the foot's share γ
        // along it.
        let place = |r: &Roll, phi: f64, theta: f64| {
            let (sin, cos) = (phi.atan().sin(), phi.atan().cos());
            let rho = r.radius / (0.5 * theta).cos();
            let foot = r.x - rho * sin;
            let e = cx.partition_point(|&x| x <= foot).clamp(1, cx.len() - 1) - 1;
            let gamma = ((foot - cx[e]) / (cx[e + 1] - cx[e])).clamp(0.0, 1.0);
            (
                e,
                gamma,
                r.top - r.radius * (1.0 - cos) + (rho - r.radius) * cos,
            )
        };
        // Kinked: the roll (by index) bending element e, and the kink (abscissa, offset).
        let kink_of =
            |active: &[bool], slope: &[f64], bend: &[f64]| -> Vec<Option<(usize, f64, f64)>> {
                let mut kink = vec![None; m + 1];
                if kinked {
                    for (k, r) in rolls.iter().enumerate().filter(|&(k, _)| active[k]) {
                        let (e, gamma, top) = place(r, slope[k], bend[k]);
                        if kink[e].is_none() {
                            kink[e] = Some((k, xs[e] + gamma * (xs[e + 1] - xs[e]), top));
                        }
                    }
                }
                kink
            };
        // The piece of element e from node e (`left`) or to node e + 1 to its kink:
        // (its horizontal length, the kink's offset), or None (no kink).
        let piece = |kink: &[Option<(usize, f64, f64)>], e: usize, left: bool| {
            kink[e].map(|(_, xk, yk)| {
                let dx = if left { xk - xs[e] } else { xs[e + 1] - xk };
                (dx.max(1e-9 * (xs[e + 1] - xs[e])), yk)
            })
        };
        let mut kink = kink_of(&active, &slope, &bend);
        for _ in 0..16 {
            // unknowns y[1..=m]; rows j = 1..=m
            let mut lo = vec![0.0; m + 2];
            let mut di = vec![0.0; m + 2];
            let mut up = vec![0.0; m + 2];
            let (mut lo2, mut up2) = (vec![0.0; m + 2], vec![0.0; m + 2]);
            let mut rhs = vec![0.0; m + 2];
            for j in 1..=m {
                rhs[j] = weight[j - 1];
                // the element before node j: to node j − 1, or from its kink
                let kl = match piece(&kink, j - 1, false) {
                    Some((dx, yk)) => {
                        let k = h[j - 1] / dx;
                        rhs[j] -= k * yk;
                        k
                    }
                    None => {
                        lo[j] = h[j - 1] / (xs[j] - xs[j - 1]);
                        lo[j]
                    }
                };
                let kr = match piece(&kink, j, true) {
                    Some((dx, yk)) => {
                        let k = h[j] / dx;
                        rhs[j] -= k * yk;
                        k
                    }
                    None => {
                        up[j] = h[j] / (xs[j + 1] - xs[j]);
                        up[j]
                    }
                };
                di[j] = -(kl + kr);
            }
            for (k, (r, &phi)) in rolls
                .iter()
                .zip(&slope)
                .enumerate()
                .filter(|&(k, _)| active[k])
            {
                let (e, gamma, top) = place(r, phi, 0.0);
                if kink[e].is_some_and(|(kk, _, _)| kk == k) {
                    continue; // a support, in the rows above
                }
                let k = r.stiffness;
                // force k·(top − Σ w_i·y_i) to each point i of the stencil (share w_i)
                let shares = stencil(e, gamma);
                for &(row, share) in &shares {
                    if row == 0 || row == m + 1 || share == 0.0 {
                        continue;
                    }
                    rhs[row] -= share * k * top;
                    for &(col, w) in &shares {
                        if col == 0 || col == m + 1 {
                            continue;
                        }
                        let c = share * k * w;
                        match col as isize - row as isize {
                            0 => di[row] -= c,
                            -1 => lo[row] -= c,
                            1 => up[row] -= c,
                            -2 => lo2[row] -= c,
                            _ => up2[row] -= c,
                        }
                    }
                }
            }
            let next = solve_band(&mut [lo2, lo, di, up, up2], &mut rhs, m);
            let moved = next
                .iter()
                .zip(&y)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            y = next;
            let mut changed = false;
            for (k, (((r, on), phi), theta)) in rolls
                .iter()
                .zip(active.iter_mut())
                .zip(slope.iter_mut())
                .zip(bend.iter_mut())
                .enumerate()
            {
                let (e, gamma, top) = place(r, *phi, *theta);
                // A kink: the pieces' turn θ, and their bisector's slope, along which the
                // kink lies from the circle's centre (the element's chord slope would put
                // it off the bisector, one piece cutting into the circle: 0.8 mm into a
                // 0.63 m circle at θ = 0.08, an 80 kN kick per roll).
                // Each piece's slope read to its node, or to the next one out where the kink
                // lies within 10⁻³ of an element of it (a slope over a piece of micrometres
                // is rounding, and once threw the kink metres off; reading every piece under
                // a quarter element to the next node started a roll at 30 kN).
                let bisector = kink[e].filter(|&(kk, _, _)| kk == k).map(|(_, xk, yk)| {
                    let near = 1e-3 * (xs[e + 1] - xs[e]);
                    let a = if xk - xs[e] < near && e > 0 { e - 1 } else { e };
                    let b = if xs[e + 1] - xk < near && e + 1 < m + 1 {
                        e + 2
                    } else {
                        e + 1
                    };
                    let left = ((yk - y[a]) / (xk - xs[a]).max(1e-12)).atan();
                    let right = ((y[b] - yk) / (xs[b] - xk).max(1e-12)).atan();
                    ((left - right).clamp(0.0, 0.5), (0.5 * (left + right)).tan())
                });
                let pull = match kink[e] {
                    // A support pulls where the belt bends down over it (its reaction,
                    // the tension times the slope change, is negative).
                    Some((kk, xk, yk)) if kk == k => {
                        (yk - y[e]) / (xk - xs[e]).max(1e-12)
                            < (y[e + 1] - yk) / (xs[e + 1] - xk).max(1e-12)
                    }
                    _ => top - height(&y, e, gamma) < 0.0,
                };
                if *on && pull {
                    *on = false;
                    changed = true;
                }
                match bisector {
                    Some((turn, slope)) => (*theta, *phi) = (turn, slope),
                    None => *phi = (point_y(&y, e + 1) - point_y(&y, e)) / (cx[e + 1] - cx[e]),
                }
            }
            let next_kink = kink_of(&active, &slope, &bend);
            let kink_moved = next_kink.iter().zip(&kink).any(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => {
                    a.0 != b.0 || (a.1 - b.1).abs() > 1e-9 || (a.2 - b.2).abs() > 1e-10
                }
                (None, None) => false,
                _ => true,
            });
            kink = next_kink;
            changed |= kink_moved;
            if !changed && moved <= 1e-10 {
                break;
            }
        }
        let mut knots = Vec::with_capacity(m + 2);
        knots.push((from, 0.0));
        // The wrap contact's circle under roll k: its top the roll's.
        let circle = |k: usize| {
            let r = &rolls[k];
            (a + d * r.x + normal * (r.top - r.radius), r.radius)
        };
        if let Some((k, xk, yk)) = kink[0] {
            knots.push((from + xk.max(0.0), yk));
            let (center, radius) = circle(k);
            kinks.push(Kink {
                s: from + xk.max(0.0),
                center,
                radius,
            });
        }
        for j in 1..=m {
            knots.push((from + xs[j], y[j]));
            if let Some((k, xk, yk)) = kink[j] {
                let xk = xk.min(len);
                knots.push((from + xk, yk));
                let (center, radius) = circle(k);
                kinks.push(Kink {
                    s: from + xk,
                    center,
                    radius,
                });
            }
        }
        knots.push((to, 0.0));
        lines.push(SagLine {
            from,
            to,
            normal,
            knots,
        });
    }
    kinks.sort_by(|a, b| a.s.total_cmp(&b.s));
    SagShape { lines, kinks }
}

/// The solution y[1..=m] (y[0] = y[m + 1] = 0) of the banded system whose row j has
/// `band[d][j]` on column j + d − 2 (d = 0..5: two diagonals below, the diagonal, two
/// above), right side `rhs[j]`: Gaussian elimination without pivoting, which the
/// placement's matrices allow (symmetric and definite: the tensions' second differences and
/// the rolls' rank-one stencils, all of one sign). Tridiagonal rows (the node belt) are
/// Thomas's algorithm.
fn solve_band(band: &mut [Vec<f64>; 5], rhs: &mut [f64], m: usize) -> Vec<f64> {
    for i in 1..=m {
        let pivot = band[2][i];
        for r in (i + 1)..=(i + 2).min(m) {
            let f = band[i + 2 - r][r] / pivot;
            if f == 0.0 {
                continue;
            }
            for c in i..=(i + 2).min(m) {
                band[c + 2 - r][r] -= f * band[c + 2 - i][i];
            }
            rhs[r] -= f * rhs[i];
        }
    }
    let mut y = vec![0.0; m + 2];
    for i in (1..=m).rev() {
        let mut v = rhs[i];
        for c in (i + 1)..=(i + 2).min(m) {
            v -= band[c + 2 - i][i] * y[c];
        }
        y[i] = v / band[2][i];
    }
    y
}
