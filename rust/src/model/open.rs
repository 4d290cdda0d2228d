//! Open belts (`belt.start` and `belt.end`): the path from the start point round the
//! pulleys in order to the end point, the placement of the belt points on it (the node
//! belt's nodes with equal chords; the rigid-body belt's end points and mass centres,
//! `super::belt_rigid`), and the compiled ends (anchors, pulls, hanging masses).
//!
//! The node belt of an open belt keeps the closed loop's arrays: n nodes and n entries
//! per element, the last (node n−1 back to node 0) being no element at all (the axial
//! pass skips it, [`crate::forces::AxialBelt::open`]; its stiffness and damping are zero).
//! So the closed loop's fast paths are untouched, and an open belt costs one branch per
//! pass.

use crate::error::{BeltError, BeltResult};
use crate::geometry::{BeltPath, Segment};
use crate::scene::{BeltEndSpec, EndHold, PulleySpec, Scene};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

impl EndModel {
    /// The pull on a pulled end at time `t` (s), N (zero for the other holds).
    #[inline]
    pub fn pull(&self, t: f64) -> V2 {
        match *self {
            EndModel::Force {
                direction,
                force,
                rate,
            } => direction * (force + rate * t).max(0.0),
            _ => V2::zeros(),
        }
    }
}

/// How a compiled end of an open belt is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndModel {
    /// Fixed at this point, m: the node does not move.
    Anchor(V2),
    /// Pulled along the unit vector `direction` (the initial span, away from the pulley)
    /// by `force` + `rate`·t N, held at 0 from below.
    Force {
        /// Unit vector of the pull.
        direction: V2,
        /// Pull at t = 0, N.
        force: f64,
        /// Its rate of change, N/s.
        rate: f64,
    },
    /// A hanging mass, kg, added to the end node (its weight comes with the node's).
    Mass(f64),
}

/// The compiled ends of an open belt: node 0 and node n−1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpenEnds {
    /// The first node's end (`belt.start`).
    pub start: EndModel,
    /// The last node's end (`belt.end`).
    pub end: EndModel,
}

/// The path of an open belt: a span from the start point to the first pulley, the wraps
/// and spans between the pulleys in order, and a span from the last pulley to the end
/// point (no closing span). Each end point must lie outside every pulley, and no span may
/// pass through a pulley.
pub(super) fn path(scene: &Scene) -> BeltResult<BeltPath> {
    let b = &scene.belt;
    let (Some(start), Some(end)) = (&b.start, &b.end) else {
        unreachable!("validated: an open belt has both ends");
    };
    for (field, e) in [("belt.start", start), ("belt.end", end)] {
        let p = e.at();
        for (k, q) in scene.pulleys.iter().enumerate() {
            let dist = (p[0] - q.center[0]).hypot(p[1] - q.center[1]);
            if dist <= q.radius {
                return Err(BeltError::invalid(
                    format!("{field}.point"),
                    format!("[{}, {}]", p[0], p[1]),
                    format!(
                        "lies inside pulleys[{k}] ({dist:.6} m from its centre, radius {} m): a belt end must lie outside every pulley",
                        q.radius
                    ),
                ));
            }
        }
    }
    // The closed path round [start point, pulleys..., end point] (the points as pulleys of
    // radius 0), without its closing span and the points' empty wraps.
    let point = |e: &BeltEndSpec| PulleySpec {
        center: e.at(),
        radius: 0.0,
        contact_stiffness: 0.0,
        ..PulleySpec::default()
    };
    let mut all = Vec::with_capacity(scene.pulleys.len() + 2);
    all.push(point(start));
    all.extend(scene.pulleys.iter().cloned());
    all.push(point(end));
    let closed = BeltPath::from_pulleys(&all).map_err(|_| {
        BeltError::invalid(
            "belt.start",
            format!("{:?}", start.at()),
            "no open belt path exists from belt.start round the pulleys with their wraps to belt.end",
        )
    })?;
    let m = closed.segments.len();
    let segments: Vec<Segment> = closed.segments[1..m - 2].to_vec();
    let mut starts = Vec::with_capacity(segments.len());
    let mut length = 0.0;
    for s in &segments {
        starts.push(length);
        length += s.length();
    }
    let wrap_angles = closed.wrap_angles[1..closed.wrap_angles.len() - 1].to_vec();
    let path = BeltPath {
        segments,
        starts,
        length,
        wrap_angles,
    };
    for (k, seg) in path.segments.iter().enumerate() {
        let Segment::Line { a, b } = *seg else {
            continue;
        };
        for (j, p) in scene.pulleys.iter().enumerate() {
            if p.contact_stiffness == 0.0 {
                continue;
            }
            let dist =
                crate::geometry::point_segment_distance(V2::new(p.center[0], p.center[1]), a, b);
            if dist < p.radius * (1.0 - 1e-9) {
                return Err(BeltError::invalid(
                    format!("pulleys[{j}].center"),
                    format!("[{}, {}]", p.center[0], p.center[1]),
                    format!(
                        "span {} of the open belt passes through this pulley ({dist:.6} m from its centre, radius {} m): the path does not go round the pulleys in the order and wraps given",
                        k / 2,
                        p.radius
                    ),
                ));
            }
        }
    }
    if !(path.length.is_finite() && path.length > 0.0) {
        return Err(BeltError::invalid(
            "belt.start.point",
            format!("{:?}", start.at()),
            format!(
                "the open belt path is {} m long: it must be finite and > 0",
                path.length
            ),
        ));
    }
    Ok(path)
}

/// Point at arc length `s` of an open path, continued straight beyond its ends.
fn point(path: &BeltPath, s: f64) -> V2 {
    if s <= 0.0 {
        let Segment::Line { a, b } = path.segments[0] else {
            return path.point(0.0);
        };
        return a + (b - a).normalize() * s;
    }
    if s >= path.length {
        let Segment::Line { a, b } = path.segments[path.segments.len() - 1] else {
            return path.point(path.length);
        };
        return b + (b - a).normalize() * (s - path.length);
    }
    let k = match path.starts.binary_search_by(|x| x.total_cmp(&s)) {
        Ok(k) => k,
        Err(k) => k - 1,
    };
    let seg = &path.segments[k];
    seg.point((s - path.starts[k]).min(seg.length()))
}

/// From arc length `s0`, the arc length of the next point at straight-line distance
/// `chord` (a chord never exceeds its arc, and an element spans at most 60° of a pulley,
/// so the point lies within [s0 + chord, s0 + 2·chord]), by 60 bisection steps.
fn next_at_chord(path: &BeltPath, s0: f64, chord: f64) -> f64 {
    let p0 = point(path, s0);
    let (mut lo, mut hi) = (s0 + chord * (1.0 - 1e-12), s0 + 2.0 * chord);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            break;
        }
        if (point(path, mid) - p0).norm() < chord {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Place `n` points on the open path, the first at the start point and the last at the
/// end point, with equal chords between them, or (`half_ends`) with the first and the
/// last chord half as long as the others (the rigid-body belt: its end points, then the
/// bodies' mass centres one body length apart, the first and last half a body from the
/// ends). Returns the positions.
pub(super) fn place(path: &BeltPath, n: usize, half_ends: bool) -> BeltResult<Vec<V2>> {
    let factor = |k: usize| {
        if half_ends && (k == 0 || k == n - 2) {
            0.5
        } else {
            1.0
        }
    };
    let walk = |chord: f64| -> BeltResult<f64> {
        let mut s = 0.0;
        for k in 0..n - 1 {
            s = next_at_chord(path, s, chord * factor(k));
            crate::interrupt::check(64)?;
        }
        Ok(s - path.length)
    };
    // The walk of whole chords' worth of arcs reaches the end or beyond; 0.9 of it falls
    // short (chords are at least 0.955 of their arcs for elements of at most 60°).
    let chords = (0..n - 1).map(factor).sum::<f64>();
    let arc = path.length / chords;
    let (mut lo, mut hi) = (0.9 * arc, arc);
    let (mut flo, mut fhi) = (walk(lo)?, walk(hi)?);
    // Regula falsi (Illinois) on the nearly linear walk, down to rounding.
    let mut chord = hi;
    for _ in 0..100 {
        if fhi == 0.0 || hi - lo <= 1e-14 * arc {
            break;
        }
        chord = hi - fhi * (hi - lo) / (fhi - flo);
        let fc = walk(chord)?;
        if fc.abs() <= 1e-13 * path.length {
            break;
        }
        if (fc < 0.0) == (flo < 0.0) {
            lo = chord;
            flo = fc;
            fhi *= 0.5;
        } else {
            hi = chord;
            fhi = fc;
            flo *= 0.5;
        }
    }
    let mut nodes = Vec::with_capacity(n);
    let mut s = 0.0;
    for k in 0..n - 1 {
        nodes.push(point(path, s));
        s = next_at_chord(path, s, chord * factor(k));
    }
    // The last point at the end point itself (the walk lands there to rounding).
    nodes.push(point(path, path.length));
    Ok(nodes)
}

/// The compiled ends: anchors at their points, pulls along the initial end spans (away
/// from the pulleys), masses as given. `nodes` are the belt points: the first two and the
/// last two give the span directions.
pub(super) fn ends(scene: &Scene, nodes: &[V2]) -> OpenEnds {
    let n = nodes.len();
    let b = &scene.belt;
    let (Some(start), Some(end)) = (&b.start, &b.end) else {
        unreachable!("validated: an open belt has both ends");
    };
    let compile = |e: &BeltEndSpec, at: V2, inward: V2| match e.hold {
        EndHold::Anchor => EndModel::Anchor(at),
        EndHold::Force => EndModel::Force {
            direction: (at - inward).normalize(),
            force: e.force.unwrap_or(0.0),
            rate: e.force_rate.unwrap_or(0.0),
        },
        EndHold::Mass => EndModel::Mass(e.mass.unwrap_or(0.0)),
    };
    OpenEnds {
        start: compile(start, nodes[0], nodes[1]),
        end: compile(end, nodes[n - 1], nodes[n - 2]),
    }
}
