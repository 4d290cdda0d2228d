//! The design-state start (the scene's `[initial]` table, `docs/design-start.md`): the belt
//! placed on its path already stretched to the design tensions and moving at the design
//! speed, so that a run needs no static relaxation.
//!
//! Placement. With T(s) the design tension at arc length s of the path and EA the axial
//! stiffness, element e of rest length l⁰ must have the chord l⁰·(1 + T/EA) (the engine's
//! tension is EA·(chord/l⁰ − 1), thesis eq. 4.1). The nodes are walked along the path with
//! these chords, and l⁰ is solved (secant) so that the n-th chord closes the loop exactly:
//! the unstretched belt length n·l⁰ is then ≈ ∫ ds/(1 + T/EA). On a drum with nodal
//! penalty contact of stiffness k a node carrying N = 2T·sin(φ/2) (φ the element's angle)
//! sits δ = N/k inside the radius r; its chords there shrink by (r − δ)/r, which the walk
//! pre-compensates (chord/(1 − δ/r)) before the nodes are moved in by δ. Without this a
//! 0.4 m drum at 50 kN and 1e8 N/m would lose 6·10⁻⁴ of strain on the wrap, as much as the
//! design strain itself.
//!
//! Motion. Every node gets the speed along the path's tangent, every pulley the path runs
//! round and every idler with friction the speed that rolls it with the belt. The
//! central-difference velocities are half-step values; taking the speeds at t = 0 instead
//! of t − Δt/2 errs by Δt·v²/r on a drum (about 10⁻⁵ m/s): negligible.

use crate::error::{BeltError, BeltResult};
use crate::geometry::{BeltPath, Segment};
use crate::scene::{InitialState, Scene};
use nalgebra::Vector2;
use std::f64::consts::PI;

type V2 = Vector2<f64>;

/// Largest sweep of one arc piece of a path corner that is not a pulley's wrap (a vertical
/// curve), rad: 5°. Curves are split so that a bulk load's zone, which is told from the
/// other run by the pulley wraps it crosses (`crate::loads::WRAP_TOLERANCE`, 10°), never
/// mistakes a long curve for a wrap.
const CURVE_PIECE: f64 = PI / 36.0;

/// Largest turn at one corner of a given path, rad (179°): a 180° drum wrap is two corners.
const MAX_TURN: f64 = PI * 179.0 / 180.0;

/// The speeds a design start gives every body at t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialMotion {
    /// Node velocities, m/s.
    pub velocity: Vec<V2>,
    /// Pulley angular speeds, rad/s (counter-clockwise positive).
    pub pulley_omega: Vec<f64>,
    /// Idler angular speeds, rad/s.
    pub idler_omega: Vec<f64>,
    /// Rigid-body belt: each body's spin, rad/s (about v/(ρ − δ) on a wrap, 0 on a strand;
    /// `super::design_rigid`). Empty for the node belt.
    pub body_spin: Vec<f64>,
}

/// The placed belt of a design start.
pub(super) struct DesignPlacement {
    /// Number of nodes (= elements).
    pub nodes: usize,
    /// Element rest length l⁰, m.
    pub rest_length: f64,
    /// Node positions (the rigid-body belt: the bodies' mass centres), m.
    pub positions: Vec<V2>,
    /// Rigid-body belt: the bodies' angles, rad (`super::design_rigid`); `None` for nodes.
    pub angles: Option<Vec<f64>>,
    /// Initial speeds.
    pub motion: InitialMotion,
}

/// The pulleys the belt rests on with penalty contact (not the nonlinear contact of a
/// belt drive's grooves), as (centre, radius) in m.
fn contact_drums(scene: &Scene) -> Vec<(V2, f64)> {
    scene
        .pulleys
        .iter()
        .filter(|p| p.contact_stiffness > 0.0 && p.nonlinear_contact.is_none())
        .map(|p| (V2::new(p.center[0], p.center[1]), p.radius))
        .collect()
}

/// True if the arc (`center`, `radius`) is the wrap of a pulley of the scene; returns the
/// pulley's contact stiffness (N/m).
fn pulley_of_arc(scene: &Scene, center: V2, radius: f64) -> Option<(usize, f64)> {
    scene.pulleys.iter().enumerate().find_map(|(j, p)| {
        let c = V2::new(p.center[0], p.center[1]);
        let tol = 1e-6 * p.radius + 1e-9;
        ((c - center).norm() <= tol && (p.radius - radius).abs() <= tol)
            .then_some((j, p.contact_stiffness))
    })
}

/// The closed path through `corners` (x, y, radius) of `initial.path`: straight spans
/// between the corners, each corner rounded by an arc of its radius tangent to both spans;
/// curve arcs (no pulley's wrap) are split into pieces of at most [`CURVE_PIECE`].
/// Errors name the corner and the rule.
pub(super) fn path_from_corners(scene: &Scene, corners: &[[f64; 3]]) -> BeltResult<BeltPath> {
    let m = corners.len();
    let at = |k: usize| V2::new(corners[k % m][0], corners[k % m][1]);
    let mut dirs = Vec::with_capacity(m);
    let mut lens = Vec::with_capacity(m);
    for k in 0..m {
        let d = at(k + 1) - at(k);
        let len = d.norm();
        if len <= 0.0 {
            return Err(BeltError::invalid(
                format!("initial.path[{}]", (k + 1) % m),
                format!("[{}, {}]", at(k + 1).x, at(k + 1).y),
                "repeats the previous corner",
            ));
        }
        dirs.push(d / len);
        lens.push(len);
    }
    // Turn and tangent length at each corner (corner k joins span k−1 and span k).
    let mut turn = vec![0.0; m];
    let mut tangent = vec![0.0; m];
    for k in 0..m {
        let (a, b) = (dirs[(k + m - 1) % m], dirs[k]);
        let phi = (a.x * b.y - a.y * b.x).atan2(a.dot(&b));
        let r = corners[k][2];
        if phi.abs() > MAX_TURN {
            return Err(BeltError::invalid(
                format!("initial.path[{k}]"),
                format!("[{}, {}, {}]", corners[k][0], corners[k][1], r),
                format!(
                    "the path turns by {:.2}° here, more than 179°: give a drum's 180° wrap as two 90° corners",
                    phi.abs().to_degrees()
                ),
            ));
        }
        if phi.abs() > 1e-12 && r <= 0.0 {
            return Err(BeltError::invalid(
                format!("initial.path[{k}][2]"),
                r,
                format!(
                    "the path turns by {:.4}° at this corner: a belt cannot kink, give the corner a radius > 0 (m: the drum's or the curve's)",
                    phi.abs().to_degrees()
                ),
            ));
        }
        turn[k] = if phi.abs() > 1e-12 { phi } else { 0.0 };
        tangent[k] = r * (turn[k].abs() / 2.0).tan();
    }
    for k in 0..m {
        let j = (k + 1) % m;
        if tangent[k] + tangent[j] > lens[k] * (1.0 + 1e-9) {
            return Err(BeltError::invalid(
                format!("initial.path[{j}][2]"),
                corners[j][2],
                format!(
                    "the arcs at corners {k} and {j} need {:.6} m of the {:.6} m span between them: a radius is too large",
                    tangent[k] + tangent[j],
                    lens[k]
                ),
            ));
        }
    }
    let mut segments = Vec::new();
    for k in 0..m {
        let (din, dout) = (dirs[(k + m - 1) % m], dirs[k]);
        let c = at(k);
        if turn[k] != 0.0 {
            let r = corners[k][2];
            let p_in = c - din * tangent[k];
            let left = V2::new(-din.y, din.x);
            let center = p_in + left * (r * turn[k].signum());
            let start = (p_in - center).y.atan2((p_in - center).x);
            let pieces = if pulley_of_arc(scene, center, r).is_some() {
                1
            } else {
                (turn[k].abs() / CURVE_PIECE).ceil() as usize
            };
            let step = turn[k] / pieces as f64;
            for q in 0..pieces {
                segments.push(Segment::Arc {
                    center,
                    radius: r,
                    start: start + step * q as f64,
                    sweep: step,
                });
            }
        }
        let a = c + dout * tangent[k];
        let b = at(k + 1) - dout * tangent[(k + 1) % m];
        segments.push(Segment::Line { a, b });
    }
    let mut starts = Vec::with_capacity(segments.len());
    let mut total = 0.0;
    for s in &segments {
        starts.push(total);
        total += s.length();
    }
    let path = BeltPath {
        segments,
        starts,
        length: total,
        wrap_angles: Vec::new(),
    };
    check_clear(scene, &path)?;
    Ok(path)
}

/// A given path may not pass inside a pulley or an idler with contact (the belt would start
/// inside it).
fn check_clear(scene: &Scene, path: &BeltPath) -> BeltResult<()> {
    let bodies = scene
        .pulleys
        .iter()
        .enumerate()
        .map(|(j, p)| {
            (
                format!("pulleys[{j}]"),
                p.center,
                p.radius,
                p.contact_stiffness,
            )
        })
        .chain(scene.idlers.iter().enumerate().map(|(k, d)| {
            (
                format!("idlers[{k}]"),
                d.center,
                d.radius,
                d.contact_stiffness,
            )
        }));
    for (name, center, radius, k) in bodies {
        if k == 0.0 {
            continue;
        }
        let (s, dist) = crate::loads::project_on_path(path, V2::new(center[0], center[1]));
        if dist < radius * (1.0 - 1e-6) - 1e-9 {
            return Err(BeltError::invalid(
                "initial.path",
                format!("{} corners", path.segments.len()),
                format!(
                    "passes {dist:.6} m from the centre of {name} (radius {radius} m) at {s:.6} m along the path: the belt would start inside it"
                ),
            ));
        }
    }
    Ok(())
}

/// Unit tangent of `path` at arc length `s` (taken modulo the length), in node order.
pub(crate) fn tangent(path: &BeltPath, s: f64) -> V2 {
    let s = s.rem_euclid(path.length);
    let k = path.starts.partition_point(|&x| x <= s).max(1) - 1;
    match path.segments[k] {
        Segment::Line { a, b } => {
            let d = b - a;
            let n = d.norm();
            if n > 0.0 {
                d / n
            } else {
                tangent(path, path.starts[(k + 1) % path.starts.len()])
            }
        }
        Segment::Arc {
            radius,
            start,
            sweep,
            ..
        } => {
            let angle = start + sweep.signum() * (s - path.starts[k]) / radius;
            V2::new(-angle.sin(), angle.cos()) * sweep.signum()
        }
    }
}

/// A contact wrap on the path: its arc-length range, centre, radius and contact stiffness.
struct ContactWrap {
    from: f64,
    to: f64,
    center: V2,
    radius: f64,
    stiffness: f64,
    pulley: usize,
}

/// Place the belt of `scene` on `path` at the design state `init` (see the module docs).
pub(super) fn place(
    scene: &Scene,
    init: &InitialState,
    path: &BeltPath,
) -> BeltResult<DesignPlacement> {
    let length = path.length;
    if let Some((i, &d)) = init
        .distance
        .iter()
        .enumerate()
        .find(|(_, d)| **d >= length)
    {
        return Err(BeltError::invalid(
            format!("initial.distance[{i}]"),
            d,
            format!("must be below the path length {length:.6} m (distances run from node 0 round the loop)"),
        ));
    }
    let belt = &scene.belt;
    let ea = belt.axial_stiffness;
    for (i, &t) in init.tension.iter().enumerate() {
        if t / ea > belt.max_placement_strain {
            return Err(BeltError::invalid(
                format!("initial.tension[{i}]"),
                t,
                format!(
                    "stretches the belt (EA = {ea} N) by {:.2} %, beyond belt.max_placement_strain = {} % (check the units)",
                    100.0 * t / ea,
                    100.0 * belt.max_placement_strain
                ),
            ));
        }
    }
    let strain = |s: f64| init.tension_at(s, length) / ea;
    // Unstretched length ∫ ds/(1 + ε), midpoint rule (it only sizes the elements and
    // starts the closure solve).
    let samples = 4096usize.max(8 * init.tension.len());
    let h = length / samples as f64;
    let rest: f64 = (0..samples)
        .map(|i| h / (1.0 + strain((i as f64 + 0.5) * h)))
        .sum();
    let min_radius = scene
        .pulleys
        .iter()
        .map(|p| p.radius)
        .fold(f64::INFINITY, f64::min);
    let n = match belt.elements {
        Some(n) => n,
        None => {
            let wanted = (rest / (belt.max_element_angle * min_radius)).ceil();
            if wanted > crate::scene::MAX_ELEMENTS as f64 {
                return Err(BeltError::invalid(
                    "belt.max_element_angle",
                    belt.max_element_angle,
                    format!("a {rest} m belt needs {wanted:e} elements of at most this arc on the smallest pulley (radius {min_radius} m); give belt.elements or check the units"),
                ));
            }
            (wanted as usize).max(3)
        }
    };
    let wraps: Vec<ContactWrap> = path
        .segments
        .iter()
        .zip(&path.starts)
        .filter_map(|(seg, &from)| match *seg {
            Segment::Arc { center, radius, .. } => pulley_of_arc(scene, center, radius)
                .filter(|&(_, k)| k > 0.0)
                .map(|(pulley, stiffness)| ContactWrap {
                    from,
                    to: from + seg.length(),
                    center,
                    radius,
                    stiffness,
                    pulley,
                }),
            _ => None,
        })
        .collect();
    let wrap_at = |s: f64| {
        let s = s.rem_euclid(length);
        wraps.iter().find(|w| s >= w.from && s <= w.to)
    };
    // The belt's runs round the pulleys for the walk, (from, to) in arc length: the wraps
    // of one pulley that the path splits (at a corner placed on the drum, or at node 0)
    // joined, the run through node 0 ending past the path length.
    let mut runs: Vec<(f64, f64, usize)> = Vec::new();
    for w in &wraps {
        match runs.last_mut() {
            Some(r) if r.2 == w.pulley && (w.from - r.1).abs() <= 1e-9 * length => r.1 = w.to,
            _ => runs.push((w.from, w.to, w.pulley)),
        }
    }
    if runs.len() > 1 {
        let (first, last) = (runs[0], runs[runs.len() - 1]);
        if first.2 == last.2 && first.0 <= 1e-9 * length && (length - last.1) <= 1e-9 * length {
            runs.pop();
            runs[0] = (last.0 - length, first.1, first.2);
        }
    }
    // The run holding arc length s, as (from, to) unwrapped round s.
    let run_at = |s: f64| {
        let base = s - s.rem_euclid(length);
        [base - length, base, base + length]
            .iter()
            .flat_map(|&b| runs.iter().map(move |r| (b + r.0, b + r.1)))
            .find(|&(from, to)| s >= from && s <= to)
    };
    // The start (unwrapped: arc length from node 0, possibly past the path length) of
    // the first run beginning in (s, s + reach].
    let wrap_ahead = |s: f64, reach: f64| {
        let base = s - s.rem_euclid(length);
        [base, base + length]
            .iter()
            .flat_map(|&b| runs.iter().map(move |r| b + r.0))
            .filter(|&from| from > s && from <= s + reach)
            .min_by(f64::total_cmp)
    };
    for w in &wraps {
        let t = init.tension_at(0.5 * (w.from + w.to), length);
        let l0 = rest / n as f64;
        let sink = 2.0 * t * (0.5 * l0 / w.radius).sin() / w.stiffness;
        if sink > 0.1 * w.radius {
            return Err(BeltError::invalid(
                format!("pulleys[{}].contact_stiffness", w.pulley),
                w.stiffness,
                format!("is too soft for the design tension {t:.6} N: each node would sink {sink:.3e} m, more than a tenth of the radius {} m", w.radius),
            ));
        }
    }
    // With wrap contact an element on a drum is measured along its path round it
    // (`contact::wrap`): nodes at equal arc length there, not sunk by a penetration.
    // The rigid-body belt walks its joint points instead (`super::design_rigid`): on a
    // wrap they lie on the vertex circle, which already holds the bodies' depth (its wrap
    // joints, `belt::rigid::wrap_joint`, change only the joint that meets a strand).
    let rigid = belt.formulation == crate::scene::Formulation::RigidBody;
    let wrap_contact = belt.pulley_contact == crate::scene::PulleyContact::Wrap && !rigid;
    // The rigid belt's wrap joints (`belt::rigid::wrap_joint`): the boundary joints stand off
    // along the drums (`design_rigid::wrap_offsets`).
    let wrap_joints = belt.pulley_contact == crate::scene::PulleyContact::Wrap && rigid;
    let drums = contact_drums(scene);
    let sink_wraps: &[ContactWrap] = if wrap_contact || rigid { &[] } else { &wraps };
    // With wrap contact on the rolls (`belt.idler_contact = "wrap"`, `contact::roll_wrap`)
    // the belt bends over each roll at the roll, and an element over one is as long as its
    // path there.
    let roll_wrap = belt.idler_contact == crate::scene::IdlerContactKind::Wrap;
    // The vertex circles (centre, r_v) of the wraps for bodies of length l⁰, each at its
    // wrap's middle tension.
    let circles = |l0: f64| -> Vec<(V2, f64)> {
        if !rigid {
            return Vec::new();
        }
        wraps
            .iter()
            .map(|w| {
                let t = init.tension_at(0.5 * (w.from + w.to), length);
                let (_, rv) = super::design_rigid::wrap_pitch(l0, t, w.radius, w.stiffness, ea);
                (w.center, rv)
            })
            .collect()
    };
    // A rigid joint's design gap l⁰·T/EA becomes e = gap/cos(α/2) along each of its two
    // bodies' chords (half each): the chord's strain is scaled by the mean of 1/cos(α/2)
    // at its two ends (from the previous pass).
    let mut factor = vec![1.0; n];
    // With the wrap joints the rigid belt's strands run straight onto a joint on each
    // drum's vertex circle (`design_rigid::Landing`), found from the previous pass (plain
    // joints: none, the vertex curve as before).
    let landings = std::cell::RefCell::new(Vec::<super::design_rigid::Landing>::new());
    // The sag of the spans on rolls (`super::sag`), updated between passes.
    let sag = std::cell::RefCell::new(super::sag::SagShape::default());
    let point = |s: f64| sag.borrow().point(path, s);
    // Walk n elements from node 0: element e gets the chord l⁰·(1 + T/EA) at its middle
    // plus `extra[e]` (what sinking its nodes into a drum will take off it).
    let walk = |l0: f64,
                extra: &[f64],
                factor: &[f64],
                mut out: Option<&mut Vec<f64>>|
     -> BeltResult<f64> {
        let on = circles(l0);
        let kinks = landings.borrow();
        let point = |s: f64| super::design_rigid::landed(point, s, &kinks, length, &on);
        let mut s = 0.0;
        for (e, f) in extra.iter().zip(factor) {
            if let Some(o) = out.as_deref_mut() {
                o.push(s);
            }
            // the tension at the element's middle: half its stretched length on
            let guess = l0 * (1.0 + strain(s + 0.5 * l0) * f);
            let chord = l0 * (1.0 + strain(s + 0.5 * guess) * f) + e;
            let kink = if roll_wrap {
                sag.borrow().kink_in(s, s + 1.01 * chord)
            } else {
                None
            };
            let to_kink = kink.map(|k| (k, (point(k.s) - point(s)).norm()));
            // With wrap contact an element on a drum is as long as its path there: along
            // the arc, and from the wrap's ends straight (the sag shape's chord) to a node
            // on a line. Measured piecewise so that the walk is continuous in l⁰ where a
            // node crosses a tangent point: taking the whole element along the path's
            // arc length as soon as its end reached the wrap skipped the sagged line's
            // excess length (chord − Δs, up to 7e-5 m per element), a jump that kept the
            // secant from closing (a 137.5 m builder conveyor with roll wrap: closure gap
            // 9.9 µm).
            let wrapped = if wrap_contact {
                match run_at(s) {
                    Some((_, end)) => Some(if s + chord <= end {
                        s + chord
                    } else {
                        crate::geometry::next_at_chord_on(point, end, chord - (end - s))
                    }),
                    None => wrap_ahead(s, 1.01 * chord).and_then(|from| {
                        let d = (point(from) - point(s)).norm();
                        (d < chord).then_some(from + chord - d)
                    }),
                }
            } else {
                None
            };
            s = if let Some(next) = wrapped {
                next
            } else if let Some((k, _)) = to_kink.filter(|&(_, d)| d < chord) {
                // over a roll: measured along the belt's path over the wrap contact's
                // circle there (tangent, arc, tangent), as the contact measures it
                let p = point(s);
                let over = |t: f64| {
                    let q = point(t);
                    crate::contact::wrap::wrap(p, q, k.center, k.radius)
                        .map_or_else(|| (q - p).norm(), |g| g.length)
                };
                crate::geometry::next_at_length(over, s, chord)
            } else {
                crate::geometry::next_at_chord_on(point, s, chord)
            };
            crate::interrupt::check(64)?;
        }
        Ok(s - length)
    };
    // l⁰ that closes the loop: secant (the walk is nearly linear in it, slope ≈ n).
    let close = |extra: &[f64], factor: &[f64]| -> BeltResult<f64> {
        let (mut a, mut b) = (rest / n as f64, rest / n as f64 * (1.0 - 1e-4));
        let (mut fa, mut fb) = (walk(a, extra, factor, None)?, walk(b, extra, factor, None)?);
        let tolerance = 1e-12 * length;
        for _ in 0..40 {
            if fb.abs() <= tolerance || fb == fa {
                break;
            }
            let c = b - fb * (b - a) / (fb - fa);
            (a, fa) = (b, fb);
            b = c;
            fb = walk(b, extra, factor, None)?;
            if (b - a).abs() <= 1e-14 * b {
                break; // at the walk's rounding noise
            }
        }
        if fb.is_nan() || fb.abs() > 1e-9 * length {
            return Err(BeltError::invalid(
                "initial",
                format!("a closure gap of {fb:e} m"),
                "the design placement did not close round the path (the tension table may change too fast for the elements)",
            ));
        }
        Ok(b)
    };
    // Sink each node on a contact wrap by its penetration N/k, N the resultant of the design
    // tensions of its two elements along the inward normal.
    let sink = |nominal: &[V2]| -> Vec<V2> {
        let mut positions = nominal.to_vec();
        for i in 0..n {
            let x = nominal[i];
            let (s, _) = crate::loads::project_on_path(path, x);
            let Some(w) = wrap_at(s) else { continue };
            let (prev, next) = (nominal[(i + n - 1) % n], nominal[(i + 1) % n]);
            let mid = |p: V2, q: V2| crate::loads::project_on_path(path, 0.5 * (p + q)).0;
            let t_prev = init.tension_at(mid(prev, x), length);
            let t_next = init.tension_at(mid(x, next), length);
            let force = (next - x).normalize() * t_next + (prev - x).normalize() * t_prev;
            let inward = (w.center - x).normalize();
            positions[i] = x + inward * (force.dot(&inward).max(0.0) / w.stiffness);
        }
        positions
    };
    // Sinking shortens the chords on a wrap (by about δ/r) and, less, those running onto
    // it: walk again with each element lengthened by what the last sinking took off it
    // (a fixed point; the second correction is below 10⁻³ of the first). The sag is a
    // fixed point too: its shape depends on where the nodes fall between the rolls, and
    // its extra length moves them along; it is redone until no node moves by 1 µm.
    let sags = init.sag && scene.gravity > 0.0 && !scene.idlers.is_empty();
    let passes = if sags || rigid { 8 } else { 3 };
    let mut extra = vec![0.0; n];
    let mut l0 = close(&extra, &factor)?;
    let mut at = Vec::with_capacity(n);
    let mut positions = Vec::new();
    let mut previous: Vec<f64> = Vec::new();
    // The contact rolls' arc lengths on the path (the landings' pivots), the same every pass.
    let rolls_at: Vec<f64> = if wrap_joints {
        scene
            .idlers
            .iter()
            .filter(|d| d.contact_stiffness > 0.0)
            .map(|d| crate::loads::project_on_path(path, V2::new(d.center[0], d.center[1])).0)
            .collect()
    } else {
        Vec::new()
    };
    for pass in 0..passes {
        at.clear();
        walk(l0, &extra, &factor, Some(&mut at))?;
        let on = circles(l0);
        let nominal: Vec<V2> = {
            let kinks = landings.borrow();
            at.iter()
                .map(|&s| super::design_rigid::landed(point, s, &kinks, length, &on))
                .collect()
        };
        positions = if sink_wraps.is_empty() {
            nominal
        } else {
            sink(&nominal)
        };
        let settled =
            previous.len() == n && at.iter().zip(&previous).all(|(a, b)| (a - b).abs() <= 1e-6);
        if (sink_wraps.is_empty() && !sags && !rigid)
            || pass == passes - 1
            || (pass >= 2 && settled)
        {
            break;
        }
        previous.clone_from(&at);
        if wrap_joints {
            // Each strand's ends on the drums (tangent point, pivot, drum centre, radius):
            // its line from the pivot is turned onto a joint there (`design_rigid::landed`).
            let ends: Vec<(f64, f64, V2, f64)> = runs
                .iter()
                .flat_map(|&(from, to, pulley)| {
                    let p = &scene.pulleys[pulley];
                    let c = V2::new(p.center[0], p.center[1]);
                    [(from, -1.0), (to, 1.0)].map(|(s, out)| {
                        // the strand's pivot: the nearest roll on it, else half the strand
                        let free = if out > 0.0 {
                            wrap_ahead(s, length).map_or(0.5 * length, |f| 0.5 * (f - s))
                        } else {
                            let behind = runs
                                .iter()
                                .flat_map(|r| [r.1 - length, r.1, r.1 + length])
                                .filter(|&t| t < s - 1e-9)
                                .fold(f64::NEG_INFINITY, f64::max);
                            0.5 * (s - behind).min(length)
                        };
                        let roll = rolls_at
                            .iter()
                            .map(|&t| (out * (t - s)).rem_euclid(length))
                            .filter(|&g| g > 4.0 * l0 && g < free)
                            .fold(free, f64::min);
                        // clear of the bodies resting on the roll
                        let roll = if roll < free { roll - 2.0 * l0 } else { roll };
                        (s, s + out * roll, c, p.radius)
                    })
                })
                .collect();
            *landings.borrow_mut() =
                super::design_rigid::landings(&at, &positions, l0, &ends, length);
        }
        if rigid {
            let cosines = super::design_rigid::half_turn_cosines(&positions);
            for e in 0..n {
                factor[e] = 0.5 * (1.0 / cosines[e] + 1.0 / cosines[(e + 1) % n]);
            }
        }
        if wrap_joints {
            // Each wrap joint's body B takes its stand-off x·(t_C·t_B) on its chord.
            let (_, angles) = super::design_rigid::bodies(&positions);
            extra.iter_mut().for_each(|e| *e = 0.0);
            for (b, _, x, tc) in super::design_rigid::wrap_offsets(&positions, l0, &drums) {
                extra[b] = x * tc.dot(&V2::new(angles[b].cos(), angles[b].sin()));
            }
        }
        if !sink_wraps.is_empty() {
            for e in 0..n {
                let chord = (positions[(e + 1) % n] - positions[e]).norm();
                let guess = l0 * (1.0 + strain(at[e] + 0.5 * l0));
                let target = l0 * (1.0 + strain(at[e] + 0.5 * guess));
                extra[e] += target - chord;
            }
        }
        if sags {
            let mass = if rigid {
                // the joint points carry half of each body beside them (its weight and
                // material at its mass centre, the middle of its chord)
                let (centres, _) = super::design_rigid::bodies(&positions);
                let body = node_masses(scene, path, &centres, l0)?;
                (0..n)
                    .map(|k| 0.5 * (body[(k + n - 1) % n] + body[k]))
                    .collect()
            } else {
                node_masses(scene, path, &positions, l0)?
            };
            let shape = super::sag::shape(
                scene,
                path,
                &at,
                &mass,
                |s| init.tension_at(s, length),
                roll_wrap.then_some(l0),
                rigid,
            );
            *sag.borrow_mut() = shape;
        }
        l0 = close(&extra, &factor)?;
    }
    if l0 > min_radius {
        return Err(BeltError::invalid(
            "belt.elements",
            n,
            format!("elements of {l0:.6} m are longer than the smallest pulley radius {min_radius} m can hold (limit: one radius, a 60° chord); use more elements"),
        ));
    }
    let speed = init.speed;
    if rigid {
        return Ok(rigid_placement(scene, path, n, l0, &positions, speed));
    }
    // along the placed belt: the tangent of the placement curve (central difference)
    let h = 1e-4 * l0;
    let velocity = at
        .iter()
        .map(|&s| {
            let d = point(s + h) - point(s - h);
            let n = d.norm();
            if n > 0.0 {
                d * (speed / n)
            } else {
                tangent(path, s) * speed
            }
        })
        .collect();
    // A body the path runs round turns with the belt: its surface at the belt, ω ẑ × r
    // (r from its centre to the nearest path point), moves at the belt's velocity v t.
    let rolling = |center: [f64; 2], radius: f64, turns: bool| -> f64 {
        if !turns || speed == 0.0 {
            return 0.0;
        }
        let c = V2::new(center[0], center[1]);
        let (s, dist) = crate::loads::project_on_path(path, c);
        if dist <= 0.0 || (dist - radius).abs() > 0.05 * radius {
            return 0.0; // the belt does not run round it
        }
        let (t, r) = (tangent(path, s), path.point(s) - c);
        speed * (t.y * r.x - t.x * r.y) / (dist * dist)
    };
    let pulley_omega = scene
        .pulleys
        .iter()
        .map(|p| rolling(p.center, p.radius, true))
        .collect();
    let idler_omega = scene
        .idlers
        .iter()
        .map(|d| rolling(d.center, d.radius, !d.friction.is_none()))
        .collect();
    Ok(DesignPlacement {
        nodes: n,
        rest_length: l0,
        positions,
        angles: None,
        motion: InitialMotion {
            velocity,
            pulley_omega,
            idler_omega,
            body_spin: Vec::new(),
        },
    })
}

/// The rigid-body belt of `n` bodies of length `l0` (m) on the joint points `vertices`
/// (`super::design_rigid`), moving at `speed` (m/s): each body along its chord at `speed`,
/// turning at the rate its chord turns as the chain moves on by one chord
/// (speed·(angle_{k+1} − angle_{k−1})/(2·chord): about v/(ρ − δ) on a wrap, 0 on a strand);
/// pulleys the path runs round at the bodies' spin there, idlers rolling with the strand.
fn rigid_placement(
    scene: &Scene,
    path: &BeltPath,
    n: usize,
    l0: f64,
    vertices: &[V2],
    speed: f64,
) -> DesignPlacement {
    let (mut centres, mut angles) = super::design_rigid::bodies(vertices);
    if scene.belt.pulley_contact == crate::scene::PulleyContact::Wrap {
        let drums = contact_drums(scene);
        let offsets = super::design_rigid::wrap_offsets(vertices, l0, &drums);
        super::design_rigid::stand_off(&mut centres, &mut angles, l0, &offsets);
    }
    let axis = |k: usize| V2::new(angles[k].cos(), angles[k].sin());
    let velocity = (0..n).map(|k| axis(k) * speed).collect();
    let body_spin: Vec<f64> = (0..n)
        .map(|k| {
            let (a, b) = (angles[(k + n - 1) % n], angles[(k + 1) % n]);
            let chord = (vertices[(k + 1) % n] - vertices[k]).norm();
            speed * crate::belt::rigid::sdes::wrap_angle(b - a) / (2.0 * chord)
        })
        .collect();
    // A pulley turns with the bodies on it (their spin there); an idler with the strand.
    let turning = |center: [f64; 2], radius: f64| -> Option<f64> {
        let c = V2::new(center[0], center[1]);
        let (_, dist) = crate::loads::project_on_path(path, c);
        if speed == 0.0 || dist <= 0.0 || (dist - radius).abs() > 0.05 * radius {
            return None;
        }
        // the median spin of the bodies on it (those next to where the strands land turn
        // at their own rates), else the nearest body's
        let mut on: Vec<f64> = (0..n)
            .filter(|&i| (centres[i] - c).norm() < radius)
            .map(|i| body_spin[i])
            .collect();
        if on.is_empty() {
            let k = (0..n)
                .min_by(|&i, &j| ((centres[i] - c).norm()).total_cmp(&(centres[j] - c).norm()))?;
            return Some(body_spin[k]);
        }
        on.sort_by(f64::total_cmp);
        Some(on[on.len() / 2])
    };
    let pulley_omega = scene
        .pulleys
        .iter()
        .map(|p| turning(p.center, p.radius).unwrap_or(0.0))
        .collect();
    let idler_omega = scene
        .idlers
        .iter()
        .map(|d| {
            if d.friction.is_none() {
                return 0.0;
            }
            let c = V2::new(d.center[0], d.center[1]);
            let (s, dist) = crate::loads::project_on_path(path, c);
            if speed == 0.0 || dist <= 0.0 || (dist - d.radius).abs() > 0.05 * d.radius {
                return 0.0;
            }
            let (t, r) = (tangent(path, s), path.point(s) - c);
            speed * (t.y * r.x - t.x * r.y) / (dist * dist)
        })
        .collect();
    DesignPlacement {
        nodes: n,
        rest_length: l0,
        positions: centres,
        angles: Some(angles),
        motion: InitialMotion {
            velocity,
            pulley_omega,
            idler_omega,
            body_spin,
        },
    }
}

/// The nodes' masses, kg (belt plus the loads' material where it lies on `positions`), for
/// elements of rest length `l0` (m).
fn node_masses(scene: &Scene, path: &BeltPath, positions: &[V2], l0: f64) -> BeltResult<Vec<f64>> {
    let n = positions.len();
    let belt_mass = vec![scene.belt.mass_per_length * l0; n];
    let loads = crate::loads::compile(&scene.loads, path, l0)?;
    if loads.is_empty() {
        return Ok(belt_mass);
    }
    let belt = crate::loads::Belt { nodes: n, l: l0 };
    let edges = crate::loads::initial_edges(&loads, positions, belt);
    Ok(crate::loads::node_masses(&belt_mass, &loads, &edges, belt))
}

#[cfg(test)]
#[path = "design_tests.rs"]
mod tests;
