//! The design state a run starts from (the `[initial]` table, `docs/design-start.md`).
//!
//! Without it the belt is placed unstretched (or uniformly stretched to `belt.length`) on
//! the pulleys' tangent path, at rest, and a run begins with a static relaxation
//! (`Simulation::stabilise`). With it the belt is placed already stretched to a given
//! tension profile (the static design tensions of DIN 22101 / ISO 5048 or CEMA,
//! `beltrs.statics`), optionally along a given path (a conveyor's vertical curves) and
//! moving at a given speed, so that a run starts in (or within a short settle of) steady
//! running or a loaded standstill, with no relaxation.

use super::validate::check_finite;
use crate::error::{BeltError, BeltResult};
use serde::{Deserialize, Serialize};

/// The design state: tensions along the belt, belt speed, and the path the belt is placed
/// on. Compiled by `crate::model` (`model/design.rs`): the belt's unstretched length is
/// ∫ ds / (1 + T(s)/EA) over the path, node i sits where the stretched elements before it
/// end (each element's chord is l⁰·(1 + T/EA), deeper on a drum by its contact
/// penetration), every node moves at `speed` along the path, every pulley turns with the
/// belt and every idler with friction rolls with it. The takeups start where the scene puts
/// them (travel 0): the design tensions fix the belt length that fits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct InitialState {
    /// Belt tension, N, finite, ≥ 0, at each `distance`: piecewise linear in between and
    /// periodic round the loop (from the last distance back to the first). One value: the
    /// same tension everywhere. Required (at least one value).
    pub tension: Vec<f64>,
    /// Arc lengths along the initial path at which `tension` is given, m, measured from
    /// the path's start (node 0) in the order of the nodes: strictly increasing, from ≥ 0
    /// to below the path length. Default `[]`: allowed with a single tension only (0 then).
    pub distance: Vec<f64>,
    /// Belt speed along the path in node order, m/s, finite (negative: against node
    /// order). Every node starts at this speed along the path, every pulley the path runs
    /// round and every idler with friction rolling with the belt. Default 0 (at rest).
    pub speed: f64,
    /// The path the belt is placed on, as corners (x, y, radius), m, in node order, closing
    /// from the last to the first: straight spans between the corners, each corner rounded
    /// by a circular arc of its radius tangent to both spans (a drum wrap: the drum's
    /// centre-line radius; a vertical curve: its radius). A corner where the path turns
    /// needs a radius > 0 and a turn below 179° (give a 180° drum wrap as two 90° corners);
    /// the arcs may not overrun their spans. Node 0 sits where corner 0's arc begins. The
    /// path may not pass inside a pulley or an idler with contact. Default `[]`: the
    /// pulleys' tangent path (`belt.length`'s path).
    pub path: Vec<[f64; 3]>,
    /// Place each straight span that rests on idler rolls in its static sag under the
    /// weight of belt and material at the design tension (`model/sag.rs`; the discrete
    /// form of the parabola q·x·(a − x)/(2T) between the rolls, each roll pressed by the
    /// load it carries). `false`: straight from roll to roll (the spans then sink into
    /// their sag in the first second of the run). Default `true`.
    pub sag: bool,
}

impl Default for InitialState {
    fn default() -> Self {
        InitialState {
            tension: Vec::new(),
            distance: Vec::new(),
            speed: 0.0,
            path: Vec::new(),
            sag: true,
        }
    }
}

impl InitialState {
    /// The rules that need no geometry (the path-dependent ones are checked when the
    /// model is compiled): tensions finite and ≥ 0, distances finite, ≥ 0 and increasing,
    /// as many as tensions, speed finite, corners finite with radii ≥ 0.
    pub fn validate(&self) -> BeltResult<()> {
        if self.tension.is_empty() {
            return Err(BeltError::invalid(
                "initial.tension",
                "[]",
                "give at least one tension (N): the design tension along the belt",
            ));
        }
        for (i, &t) in self.tension.iter().enumerate() {
            check_finite(&format!("initial.tension[{i}]"), t)?;
            if t < 0.0 {
                return Err(BeltError::invalid(
                    format!("initial.tension[{i}]"),
                    t,
                    "must be ≥ 0 (N): a belt in compression has no design state (raise the takeup tension)",
                ));
            }
        }
        if self.distance.is_empty() {
            if self.tension.len() != 1 {
                return Err(BeltError::invalid(
                    "initial.distance",
                    "[]",
                    format!(
                        "give a distance (m along the path) for each of the {} tensions",
                        self.tension.len()
                    ),
                ));
            }
        } else if self.distance.len() != self.tension.len() {
            return Err(BeltError::invalid(
                "initial.distance",
                format!("{} values", self.distance.len()),
                format!(
                    "needs as many values as initial.tension ({})",
                    self.tension.len()
                ),
            ));
        }
        for (i, &d) in self.distance.iter().enumerate() {
            check_finite(&format!("initial.distance[{i}]"), d)?;
            if d < 0.0 {
                return Err(BeltError::invalid(
                    format!("initial.distance[{i}]"),
                    d,
                    "must be ≥ 0 (m along the path from node 0)",
                ));
            }
            if i > 0 && d <= self.distance[i - 1] {
                return Err(BeltError::invalid(
                    format!("initial.distance[{i}]"),
                    d,
                    format!(
                        "must increase strictly (previous value {})",
                        self.distance[i - 1]
                    ),
                ));
            }
        }
        check_finite("initial.speed", self.speed)?;
        if !self.path.is_empty() && self.path.len() < 2 {
            return Err(BeltError::invalid(
                "initial.path",
                format!("{} corner", self.path.len()),
                "a closed path needs at least two corners (or none: the pulleys' path)",
            ));
        }
        for (i, c) in self.path.iter().enumerate() {
            check_finite(&format!("initial.path[{i}][0]"), c[0])?;
            check_finite(&format!("initial.path[{i}][1]"), c[1])?;
            check_finite(&format!("initial.path[{i}][2]"), c[2])?;
            if c[2] < 0.0 {
                return Err(BeltError::invalid(
                    format!("initial.path[{i}][2]"),
                    c[2],
                    "the corner radius must be ≥ 0 (m)",
                ));
            }
        }
        Ok(())
    }

    /// The tension at arc length `s` (m) on a path of length `length` (m): piecewise linear
    /// through the table, periodic.
    pub fn tension_at(&self, s: f64, length: f64) -> f64 {
        let n = self.tension.len();
        if n == 1 {
            return self.tension[0];
        }
        let s = s.rem_euclid(length);
        let d = &self.distance;
        // after the last point or before the first: the closing interval
        if s >= d[n - 1] || s < d[0] {
            let span = d[0] + length - d[n - 1];
            let x = if s >= d[n - 1] {
                s - d[n - 1]
            } else {
                s + length - d[n - 1]
            };
            let w = if span > 0.0 { x / span } else { 0.0 };
            return self.tension[n - 1] + (self.tension[0] - self.tension[n - 1]) * w;
        }
        let k = d.partition_point(|&x| x <= s) - 1;
        let w = (s - d[k]) / (d[k + 1] - d[k]);
        self.tension[k] + (self.tension[k + 1] - self.tension[k]) * w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tension_is_linear_and_periodic() {
        let init = InitialState {
            tension: vec![10.0, 30.0, 20.0],
            distance: vec![1.0, 3.0, 5.0],
            ..Default::default()
        };
        let length = 9.0; // the closing interval runs from 5 to 1 + 9 = 10
        assert_eq!(init.tension_at(2.0, length), 20.0);
        assert_eq!(init.tension_at(4.0, length), 25.0);
        assert_eq!(init.tension_at(7.5, length), 15.0);
        assert_eq!(init.tension_at(0.0, length), 12.0);
        assert_eq!(init.tension_at(9.0 + 2.0, length), 20.0);
        assert!(init.validate().is_ok());
        let one = InitialState {
            tension: vec![7.0],
            ..Default::default()
        };
        assert_eq!(one.tension_at(3.3, length), 7.0);
    }
}
