//! One-dimensional root finders of the node placement: a bisection that can be replayed
//! from an estimate of its crossing (same steps, same bits, few evaluations), regula falsi
//! with the Illinois modification, and the bracket of a chord's end.

/// The midpoint of the bracket after `steps` bisection steps on `below(mid)` (true: the
/// root is above `mid`), stopping early when `done(lo, hi)`. With `crossing` = an estimate of
/// where `below` turns false, good to within `margin`, a midpoint further than `margin` from
/// it is decided without calling `below`: the same steps, the same result, far fewer
/// evaluations.
pub(super) fn bisect_replayed(
    mut lo: f64,
    mut hi: f64,
    steps: usize,
    crossing: Option<f64>,
    margin: f64,
    mut below: impl FnMut(f64) -> bool,
    done: impl Fn(f64, f64) -> bool,
) -> f64 {
    for _ in 0..steps {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            // Converged to adjacent floats: every further step repeats this one.
            break;
        }
        let is_below = match crossing {
            Some(c) if mid < c - margin => true,
            Some(c) if mid > c + margin => false,
            _ => below(mid),
        };
        if is_below {
            lo = mid;
        } else {
            hi = mid;
        }
        if done(lo, hi) {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// The root of `f` in `[lo, hi]` (with `f(lo) = flo < 0 ≤ fhi = f(hi)`) by regula falsi with
/// the Illinois modification: stops when `|f| ≤ tolerance`, the bracket can shrink no
/// further, or after `max_evals` evaluations. If the bracket is not a sign change, its
/// midpoint.
pub(super) fn illinois(
    mut lo: f64,
    mut flo: f64,
    mut hi: f64,
    mut fhi: f64,
    tolerance: f64,
    max_evals: usize,
    mut f: impl FnMut(f64) -> f64,
) -> f64 {
    if !(flo < 0.0 && fhi >= 0.0) {
        return 0.5 * (lo + hi);
    }
    // A root at an end (e.g. a chord along a straight span, found by the first guess):
    // the secant would fall on that end and degrade to bisection.
    if fhi <= tolerance {
        return hi;
    }
    if -flo <= tolerance {
        return lo;
    }
    let mut x = hi;
    let mut side = 0i8;
    for _ in 0..max_evals {
        let guess = (lo * fhi - hi * flo) / (fhi - flo);
        // Falls back to bisection when the secant leaves the bracket (round-off).
        x = if guess > lo && guess < hi {
            guess
        } else {
            0.5 * (lo + hi)
        };
        if !(x > lo && x < hi) {
            break;
        }
        let fx = f(x);
        if fx.abs() <= tolerance {
            break;
        }
        if fx < 0.0 {
            (lo, flo) = (x, fx);
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, fhi) = (x, fx);
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    x
}

/// Bracket the crossing of `gap` (distance from the point at `s0`, minus `chord`) past `s0`:
/// the arc is at least the chord, so start at `s0 + chord` and step by a quarter chord up to
/// `s0 + 4·chord`. Returns `(lo, gap(lo), hi, gap(hi))`, `gap(hi) ≥ 0` unless none was found.
pub(super) fn chord_bracket(
    s0: f64,
    chord: f64,
    gap: &impl Fn(f64) -> f64,
) -> (f64, f64, f64, f64) {
    let (mut lo, mut glo) = (s0, -chord);
    let mut hi = s0 + chord;
    let mut ghi = gap(hi);
    while ghi < 0.0 && hi < s0 + 4.0 * chord {
        (lo, glo) = (hi, ghi);
        hi += 0.25 * chord;
        ghi = gap(hi);
    }
    (lo, glo, hi, ghi)
}
