//! Bulk material on the belt (`docs/loads.md`).
//!
//! A load puts `m'_L` kg of material on each metre of unstretched belt between a loading
//! point and a discharge point fixed in space. The material moves with the belt: each step
//! the belt points nearest the two points are tracked (one element each, local search, as
//! the idlers track theirs), which gives the loaded zone in material coordinates σ (metres
//! of unstretched belt from node 0, σ_i = i·l for node i). Node i carries
//! m_i = m_belt,i + Σ m'_L·|[σ_i − l/2, σ_i + l/2] ∩ zone|, continuous in the zone edges, so
//! the load enters and leaves smoothly. Only the nodes whose tributary length the edges
//! swept this step are recomputed: O(1) per step.
//!
//! A node whose mass grows from m to m' gets the velocity v·m/m' (the material enters at
//! rest along the belt, and the belt pays its momentum: DIN 22101's acceleration resistance
//! Q·v at the loading point); a node whose mass falls keeps its velocity (the material leaves
//! with it). Each node's mass is a pure function of the current zones, so a checkpoint that
//! stores the edges and masses resumes bit for bit.

pub mod stage;

use crate::contact::segment_distance;
use crate::error::{BeltError, BeltResult};
use crate::geometry::{BeltPath, Segment};
use crate::scene::{LoadSpec, LOAD_POINT_TOLERANCE};
use nalgebra::Vector2;
use std::f64::consts::TAU;

type V2 = Vector2<f64>;

/// A run of belt between the two points "wraps a pulley" when it holds more than this much
/// of one pulley's wrap, rad (10°): the points may sit a little past a tangent point.
pub const WRAP_TOLERANCE: f64 = TAU / 36.0;

/// A compiled load.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadModel {
    /// Material per metre of unstretched belt, kg/m.
    pub mass_per_length: f64,
    /// Loading point, m.
    pub start: V2,
    /// Discharge point, m.
    pub end: V2,
    /// Points of the initial path nearest `start` and `end`, m (where tracking starts).
    pub start_on_path: V2,
    /// See `start_on_path`.
    pub end_on_path: V2,
    /// True if the loaded zone runs in node order from the start point to the end point
    /// (the belt, running forward in node order, carries the material from start to end);
    /// false if it runs in node order from end to start.
    pub forward: bool,
}

/// Where one load's zone is now: the element each edge tracks and the edges' material
/// coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LoadEdges {
    /// Element nearest the loading point.
    pub start_element: usize,
    /// Element nearest the discharge point.
    pub end_element: usize,
    /// Material coordinate of the belt point nearest the loading point, m, in [0, L).
    pub start: f64,
    /// Material coordinate of the belt point nearest the discharge point, m, in [0, L).
    pub end: f64,
}

/// The loaded zone in material coordinates: it begins at `lo` ∈ [0, L) and runs `len` m in
/// node order (wrapping past node 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zone {
    /// First material coordinate, m.
    pub lo: f64,
    /// Length along the unstretched belt, m.
    pub len: f64,
}

/// Uniform belt discretisation the loads work on: `nodes` elements of `l` m.
#[derive(Debug, Clone, Copy)]
pub struct Belt {
    /// Number of nodes (= elements).
    pub nodes: usize,
    /// Element rest length, m.
    pub l: f64,
}

impl Belt {
    /// Unstretched belt length, m.
    #[inline]
    pub fn length(&self) -> f64 {
        self.nodes as f64 * self.l
    }

    /// Material coordinate of the point at fraction `gamma` of element `e`, in [0, L).
    #[inline]
    fn coordinate(&self, e: usize, gamma: f64) -> f64 {
        let s = (e as f64 + gamma) * self.l;
        if s >= self.length() {
            s - self.length()
        } else {
            s
        }
    }

    /// Node whose tributary length [σ_i − l/2, σ_i + l/2) holds `s` ∈ [0, L).
    #[inline]
    fn node_at(&self, s: f64) -> usize {
        ((s / self.l + 0.5).floor() as usize) % self.nodes
    }

    /// Length of node `i`'s tributary interval inside `zone`, m.
    #[inline]
    fn overlap(&self, i: usize, zone: Zone) -> f64 {
        let a = (i as f64 - 0.5) * self.l;
        let b = a + self.l;
        let big = self.length();
        // The node intervals tile [−l/2, L − l/2); the zone copy shifted by −L catches the
        // part of a zone that wraps past node 0.
        let part = |lo: f64, hi: f64| (b.min(hi) - a.max(lo)).max(0.0);
        part(zone.lo, zone.lo + zone.len) + part(zone.lo - big, zone.lo + zone.len - big)
    }
}

impl LoadModel {
    /// The zone these edges bound.
    #[inline]
    pub fn zone(&self, edges: &LoadEdges, belt: Belt) -> Zone {
        let (lo, hi) = if self.forward {
            (edges.start, edges.end)
        } else {
            (edges.end, edges.start)
        };
        Zone {
            lo,
            len: (hi - lo).rem_euclid(belt.length()),
        }
    }
}

/// Arc length along `path` of the path point nearest `p`, and the distance to it.
pub(crate) fn project_on_path(path: &BeltPath, p: V2) -> (f64, f64) {
    let mut best = (f64::INFINITY, 0.0);
    for (k, seg) in path.segments.iter().enumerate() {
        let (dist, local) = match *seg {
            Segment::Line { a, b } => {
                let (d, gamma, _) = segment_distance(p, a, b);
                (d, gamma * (b - a).norm())
            }
            Segment::Arc {
                center,
                radius,
                start,
                sweep,
            } => {
                let rel = p - center;
                let theta = rel.y.atan2(rel.x);
                let phi = ((theta - start) * sweep.signum()).rem_euclid(TAU);
                if phi <= sweep.abs() {
                    ((rel.norm() - radius).abs(), radius * phi)
                } else {
                    let d0 = (p - seg.point(0.0)).norm();
                    let d1 = (p - seg.point(seg.length())).norm();
                    if d0 <= d1 {
                        (d0, 0.0)
                    } else {
                        (d1, seg.length())
                    }
                }
            }
        };
        if dist < best.0 {
            best = (dist, path.starts[k] + local);
        }
    }
    (best.1, best.0)
}

/// Largest angle of any one pulley's wrap inside the path run [from, from + len], rad.
fn run_wrap(path: &BeltPath, from: f64, len: f64) -> f64 {
    let total = path.length;
    let mut worst: f64 = 0.0;
    for (k, seg) in path.segments.iter().enumerate() {
        let Segment::Arc { radius, .. } = *seg else {
            continue;
        };
        let (a, b) = (path.starts[k], path.starts[k] + seg.length());
        let mut inside = 0.0;
        // The run may wrap past the path's start: test it and its copy one loop on.
        for shift in [0.0, total] {
            let (lo, hi) = (from - shift, from + len - shift);
            inside += (b.min(hi) - a.max(lo)).max(0.0);
        }
        worst = worst.max(inside / radius);
    }
    worst
}

/// Compile the loads of a scene on the initial path. Errors name the load and the rule: a
/// point farther than [`LOAD_POINT_TOLERANCE`] from the path, an ambiguous zone (both runs
/// between the points, or neither, wrap a pulley by more than [`WRAP_TOLERANCE`]), a zone
/// shorter than one element. Every load is validated; one of zero mass is then dropped (it
/// would only cost a stage and the uniform-mass fast path).
pub fn compile(loads: &[LoadSpec], path: &BeltPath, element: f64) -> BeltResult<Vec<LoadModel>> {
    let mut out = Vec::with_capacity(loads.len());
    for (i, l) in loads.iter().enumerate() {
        let f = format!("loads[{i}]");
        let mut ends = [(0.0, V2::zeros()); 2];
        for (k, (key, p)) in [("start", l.start), ("end", l.end)].into_iter().enumerate() {
            let p = V2::new(p[0], p[1]);
            let (s, dist) = project_on_path(path, p);
            if dist > LOAD_POINT_TOLERANCE {
                return Err(BeltError::invalid(
                    format!("{f}.{key}"),
                    format!("[{}, {}]", p.x, p.y),
                    format!(
                        "is {dist:.6} m from the belt path; a loading or discharge point must lie within {LOAD_POINT_TOLERANCE} m of it"
                    ),
                ));
            }
            ends[k] = (s, path.point(s));
        }
        let (s0, s1) = (ends[0].0, ends[1].0);
        let forward_len = (s1 - s0).rem_euclid(path.length);
        let backward_len = (s0 - s1).rem_euclid(path.length);
        let forward_wraps = run_wrap(path, s0, forward_len) > WRAP_TOLERANCE;
        let backward_wraps = run_wrap(path, s1, backward_len) > WRAP_TOLERANCE;
        if forward_wraps == backward_wraps {
            let which = if forward_wraps { "both" } else { "neither" };
            return Err(BeltError::invalid(
                format!("{f}.end"),
                format!("[{}, {}]", l.end[0], l.end[1]),
                format!(
                    "{which} of the two runs of belt between loads[{i}].start = [{}, {}] and this point wrap{} a pulley (by more than 10°): the loaded zone is ambiguous; put both points on one strand with no pulley between them",
                    l.start[0],
                    l.start[1],
                    if forward_wraps { "" } else { "s" }
                ),
            ));
        }
        let forward = !forward_wraps;
        let zone_len = if forward { forward_len } else { backward_len };
        if zone_len < element {
            return Err(BeltError::invalid(
                format!("{f}.end"),
                format!("[{}, {}]", l.end[0], l.end[1]),
                format!(
                    "is {zone_len:.6} m along the belt from loads[{i}].start; the loaded zone must be at least one element ({element:.6} m) long"
                ),
            ));
        }
        out.push(LoadModel {
            mass_per_length: l.mass_per_length,
            start: V2::new(l.start[0], l.start[1]),
            end: V2::new(l.end[0], l.end[1]),
            start_on_path: ends[0].1,
            end_on_path: ends[1].1,
            forward,
        });
    }
    out.retain(|l| l.mass_per_length > 0.0);
    Ok(out)
}

/// Step `element` to the neighbour nearer `p` while there is one (the local search of the
/// idler tracking); returns the fraction along the final element of its point nearest `p`.
fn track(element: &mut usize, x: &[V2], p: V2) -> f64 {
    let n = x.len();
    let dist_of = |e: usize| segment_distance(p, x[e], x[(e + 1) % n]);
    let mut e = *element % n;
    let mut best = dist_of(e);
    for _ in 0..n {
        let back = dist_of((e + n - 1) % n);
        let fwd = dist_of((e + 1) % n);
        if back.0 < best.0 && back.0 <= fwd.0 {
            e = (e + n - 1) % n;
            best = back;
        } else if fwd.0 < best.0 {
            e = (e + 1) % n;
            best = fwd;
        } else {
            break;
        }
    }
    *element = e;
    best.1
}

/// The element nearest `p` (one global search).
fn nearest_element(x: &[V2], p: V2) -> usize {
    let n = x.len();
    (0..n)
        .min_by(|&a, &b| {
            let da = segment_distance(p, x[a], x[(a + 1) % n]).0;
            let db = segment_distance(p, x[b], x[(b + 1) % n]).0;
            da.total_cmp(&db)
        })
        .unwrap_or(0)
}

/// Edges of each load on the belt at `x`, found by one global search from the path points
/// nearest the loading and discharge points, then tracked to the points themselves.
pub fn initial_edges(loads: &[LoadModel], x: &[V2], belt: Belt) -> Vec<LoadEdges> {
    loads
        .iter()
        .map(|l| {
            let mut start_element = nearest_element(x, l.start_on_path);
            let mut end_element = nearest_element(x, l.end_on_path);
            let gs = track(&mut start_element, x, l.start);
            let ge = track(&mut end_element, x, l.end);
            LoadEdges {
                start_element,
                end_element,
                start: belt.coordinate(start_element, gs),
                end: belt.coordinate(end_element, ge),
            }
        })
        .collect()
}

/// Mass of node `i`: its belt mass plus the material of every load on its tributary length.
#[inline]
fn node_mass(
    i: usize,
    belt_mass: &[f64],
    loads: &[LoadModel],
    edges: &[LoadEdges],
    belt: Belt,
) -> f64 {
    let mut m = belt_mass[i];
    for (l, e) in loads.iter().zip(edges) {
        m += l.mass_per_length * belt.overlap(i, l.zone(e, belt));
    }
    m
}

/// Every node's mass (belt plus material) for the zones `edges`.
pub fn node_masses(
    belt_mass: &[f64],
    loads: &[LoadModel],
    edges: &[LoadEdges],
    belt: Belt,
) -> Vec<f64> {
    (0..belt_mass.len())
        .map(|i| node_mass(i, belt_mass, loads, edges, belt))
        .collect()
}

/// The node masses the loads stage keeps up to date, and whether it also keeps the
/// dynamics' inertia (the physical one: then a node gaining mass keeps its momentum).
pub struct MassArrays<'a> {
    /// Physical node masses (belt + material): gravity, energies, results, kg.
    pub node_mass: &'a mut [f64],
    /// The integrator's masses and inverses, when they are the physical ones (dynamics);
    /// `None` in the static relaxation (fictitious masses: only the weights change).
    pub inertia: Option<(&'a mut [f64], &'a mut [f64])>,
    /// The rigid-body belt's rotations, kept with `inertia` in dynamics: `None` for the
    /// node belt and in the relaxation.
    pub bodies: Option<Bodies<'a>>,
}

/// A rigid-body belt's rotational inertia as the loads change its body masses: the
/// material lies along the body like the belt, so a body of mass m has
/// I = I_belt·m/m_belt (= m·l²/12, Kubas eq. 2), and a body gaining material keeps its
/// angular momentum (the material arrives without spin), as its translation keeps its
/// momentum.
pub struct Bodies<'a> {
    /// The belt's own body inertias, kg·m² (`Model::body_inertia`).
    pub belt_inertia: &'a [f64],
    /// The integrator's body inertias, kg·m².
    pub inertia: &'a mut [f64],
    /// The body spins, rad/s.
    pub spin: &'a mut [f64],
}

/// Inertia of a body of belt mass `belt_mass` and belt inertia `belt_inertia` carrying
/// `mass` in all (belt and material), kg·m².
#[inline]
pub fn body_inertia(belt_inertia: f64, belt_mass: f64, mass: f64) -> f64 {
    belt_inertia * (mass / belt_mass)
}

/// The loads stage: track the zone edges to the belt at `x`, recompute the masses of the
/// nodes whose tributary length an edge swept, and keep their momentum when they gain
/// material (`v` are the half-step velocities). O(1) per step.
pub fn update(
    loads: &[LoadModel],
    belt_mass: &[f64],
    belt: Belt,
    x: &[V2],
    v: &mut [V2],
    edges: &mut [LoadEdges],
    masses: &mut MassArrays<'_>,
) {
    // Nodes to recompute: from the node holding each edge's old coordinate to the one
    // holding its new one, the shorter way round (an edge moves a fraction of an element
    // per step): a handful per edge. A node in the sweep of two loads' edges is recomputed
    // twice and ends with the value for every load's new edges.
    let n = belt.nodes;
    for k in 0..loads.len() {
        let old = edges[k];
        let gs = track(&mut edges[k].start_element, x, loads[k].start);
        let ge = track(&mut edges[k].end_element, x, loads[k].end);
        edges[k].start = belt.coordinate(edges[k].start_element, gs);
        edges[k].end = belt.coordinate(edges[k].end_element, ge);
        for (from, to) in [(old.start, edges[k].start), (old.end, edges[k].end)] {
            if from.to_bits() == to.to_bits() {
                continue;
            }
            let (a, b) = (belt.node_at(from), belt.node_at(to));
            let ahead = (b + n - a) % n;
            let (first, count) = if ahead <= n - ahead {
                (a, ahead + 1)
            } else {
                (b, n - ahead + 1)
            };
            for j in 0..count {
                let i = (first + j) % n;
                let new = node_mass(i, belt_mass, loads, edges, belt);
                let before = masses.node_mass[i];
                if new.to_bits() == before.to_bits() {
                    continue;
                }
                masses.node_mass[i] = new;
                if let Some((mass, inv_mass)) = masses.inertia.as_mut() {
                    if new > before {
                        v[i] *= before / new;
                    }
                    mass[i] = new;
                    inv_mass[i] = 1.0 / new;
                    if let Some(b) = masses.bodies.as_mut() {
                        if new > before {
                            b.spin[i] *= before / new;
                        }
                        b.inertia[i] = body_inertia(b.belt_inertia[i], belt_mass[i], new);
                    }
                }
            }
        }
    }
}

/// Length of each load's zone along the unstretched belt, m (its material is
/// `mass_per_length` times this).
pub fn zone_lengths(loads: &[LoadModel], edges: &[LoadEdges], belt: Belt) -> Vec<f64> {
    loads
        .iter()
        .zip(edges)
        .map(|(l, e)| l.zone(e, belt).len)
        .collect()
}
