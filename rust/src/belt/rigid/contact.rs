//! A rigid body lying on a pulley: the contact law of a chord on a circle.
//!
//! The belt on a drum of radius R is an arc; a rigid body of length l stands for a = l/R
//! of it. Kubas (section 2.1) touches the pulley at the mass centre, along the radial
//! there. That leaves a body free to turn about its mass centre on the drum (neither the
//! normal force nor the friction along the tangent has a moment about it), and a chain of
//! such bodies on a wrap has a motion that the drum does not resist: neighbouring bodies
//! turning opposite ways (a zig-zag whose joints go alternately in and out), held only by
//! the tension. Sliding friction feeds it: on the sliding capstan rig of
//! `tests/test_capstan.py` (θ = π/2) it grew from 0.5 to 20 mrad in 10 ms and threw the
//! belt off the sheave.
//!
//! Here a body rests on the drum with its two **ends**. Each end e is (R_e − |e − c|)/cos(a/2)
//! inside the drum, R_e = ρ/cos(a/2) the circle through the corners of the bodies'
//! polygon (for a body resting on the drum: its end's depth below the tangent line at ρ
//! under its mass centre, to first order), and is pushed along the body's own normal ν
//! with half the contact law at that depth. A body pressed in as a whole carries the
//! whole law (the linear penalty: k/2 per end, k as a node); a body turned by δ on the
//! drum has one end (l/2)·sin δ deeper and is turned back, so the zig-zag meets the
//! contact stiffness (a body turning on its end contacts: ω² = 3k/m, in the stable step).
//!
//! *The line's distance ρ.* A chord of length l whose ends lie on the circle of radius
//! R_e = l/(2·sin(a/2)) subtends exactly a; its mass centre lies at
//! ρ = R_e·cos(a/2) = (l/2)·cot(a/2) = R − l²/(12R) − … ([`contact_radius`]). Bodies resting
//! at ρ form the polygon whose sides are l and whose corners turn by a, so a wrap of θ holds
//! θ/a bodies, exactly the arc's length of belt: neither the a²/12 excess of the polygon
//! circumscribed about R (Kubas's contact at R) nor the a²/24 deficit of the inscribed one
//! (the node belt).
//!
//! *Forces along the body's normal.* No contact force has a component along the body's
//! axis, which carries the tension. Radial forces at the ends (the exact normals of a
//! chord on a circle) would have one, (N_a − N_b)·sin(a/2), stiffly coupled to the body's
//! turning: measured on the onset rig, it made the bodies of the slip arc ring at 14 kHz
//! with ±0.3 mm/s, so the creep law's stick limit met µs·N and dropped them to µk (the
//! friction averaged 0.83–0.98 of µ·N on the slip arcs, and the creep onset came near
//! e^{µk θ}); along the body's normal they rest steadily (±0.0005 mm/s), at µs·N. Radial
//! forces through the mass centre push a span's body next to the wrap along its axis
//! (1 % more tension in a frictionless drive's arcs than in its spans). The price: the
//! forces are not the gradient of the penalty energy (they differ by the body's tilt
//! against the drum, milliradians); no law without the axial part is, for a finite body
//! resting on two points.
//!
//! *Friction* acts on the body as one contact at its mass centre along its axis, with
//! the ends' summed normal force: no moment about the mass centre. A body turning with the
//! pulley moves its mass centre at ω·ρ: the surface speed the friction of a body is
//! measured against, and the lever of its friction about the pulley's centre
//! (`Model::friction_radius`); per contact the friction solves take the speed along the
//! body's axis that its mass centre has when it turns with the pulley,
//! ω·(ẑ × (x − c))·t (`PulleyContacts::lever`): ρ·ω for a body resting on the drum, more
//! for one landing or leaving.
//!
//! *Damping* acts on the rate of each end's depth, the end's radial speed relative to the
//! pulley's centre over cos(a/2): a body turning with the pulley has none. (Its ends'
//! speeds along the body's normal are ±ω·l/2: damping those dragged case G's 60 m bare
//! conveyor by 6.5 kN, against the node belt's 0.18 kN; on the depth's rate, 0.31 kN.)
//!
//! An open belt's end points (length 0) are points and touch the circle of radius R.

use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// ρ = (l/2)·cot(l/2R) = R − l²/(12R) − …: the distance from the pulley's centre of the
/// mass centre of a body of length `length` whose ends lie on the circle on which it
/// subtends `length`/`radius`, m (`radius` for a point).
#[inline]
pub fn contact_radius(length: f64, radius: f64) -> f64 {
    let half = 0.5 * length / radius;
    if half > 0.0 {
        0.5 * length / half.tan()
    } else {
        radius
    }
}

/// One body as the contact sees it.
#[derive(Debug, Clone, Copy)]
pub struct BodyOnPulley {
    /// Mass centre, m.
    pub position: V2,
    /// Velocity of the mass centre, m/s.
    pub velocity: V2,
    /// Axis angle, rad.
    pub angle: f64,
    /// Angular velocity, rad/s.
    pub spin: f64,
    /// Length, m (0: a point).
    pub length: f64,
}

/// The contact of one body with a pulley.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BodyContact {
    /// Force of the pulley on the body, N (the sum over its ends).
    pub force: V2,
    /// Its moment about the mass centre, N·m.
    pub torque: f64,
    /// Summed normal force of the ends, N (≥ 0; 0: no contact).
    pub normal_force: f64,
    /// Penetration, m: for a body the root mean square of its ends' depths over both ends
    /// (0 for an end off the drum), so that ½·k·d² is the linear penalty's energy
    /// Σ ½·(k/2)·dₑ²; for a point its depth.
    pub penetration: f64,
    /// Number of ends pressing (0, 1 or 2; a point: 0 or 1).
    pub ends: u8,
    /// Direction of the contact forces: the body's normal (perpendicular to its axis,
    /// outwards), or a point's radial; its perpendicular is the friction's direction.
    pub normal: V2,
}

/// The contact of `body` with a pulley of radius `radius` centred at `center` moving at
/// `center_velocity` (module docs). With n the outward unit vector from the pulley's
/// centre through the mass centre and ν the body's own normal (perpendicular to its axis,
/// outwards), each end e (at ±h from the mass centre) lies
/// depth = (R_e − |e − c|)/cos(a/2)
/// inside the drum (the circle R_e = ρ/cos(a/2) through the corners of the bodies'
/// polygon, ρ = [`contact_radius`], a = l/R; for a body resting on the drum this is its
/// depth below the tangent line at ρ under its mass centre, to first order) and is pushed
/// along ν with ½·`law`(depth, its approach speed along ν). A point (length 0)
/// gets the whole law at its depth under the circle of radius R, along its radial.
#[inline]
pub fn body_contact(
    body: &BodyOnPulley,
    center: V2,
    center_velocity: V2,
    radius: f64,
    law: impl Fn(f64, f64) -> f64,
) -> BodyContact {
    let chord = Chord::new(body.length, radius);
    body_contact_with(body, &chord, center, center_velocity, radius, law)
}

/// What the contact of a body of one length with a pulley of one radius needs of their
/// geometry: it depends on neither the body's place nor the time, so a pulley's contact
/// computes it once for a run of bodies of the same length (a tangent and a cosine saved
/// per body in contact and step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chord {
    /// Body length, m.
    pub length: f64,
    /// R_e = ρ/cos(a/2), the circle through the corners of the bodies' polygon, m.
    pub corner: f64,
    /// cos(a/2), a = l/R.
    pub cos_half: f64,
}

impl Chord {
    /// The chord of a body of `length` (m) on a pulley of `radius` (m).
    #[inline]
    pub fn new(length: f64, radius: f64) -> Chord {
        let rho = contact_radius(length, radius);
        let cos_half = (0.5 * length / radius).cos();
        Chord {
            length,
            corner: rho / cos_half,
            cos_half,
        }
    }
}

/// [`body_contact`] with the chord of the body's length on this pulley (`chord.length` must
/// be `body.length`) computed already.
#[inline]
pub fn body_contact_with(
    body: &BodyOnPulley,
    chord: &Chord,
    center: V2,
    center_velocity: V2,
    radius: f64,
    law: impl Fn(f64, f64) -> f64,
) -> BodyContact {
    debug_assert!(chord.length.to_bits() == body.length.to_bits());
    let mut out = BodyContact::default();
    let rel = body.position - center;
    let a = rel.norm();
    let radial = if a > 0.0 { rel / a } else { V2::new(1.0, 0.0) };
    // `rate`: the direction (scaled) whose dot product with the point's velocity relative
    // to the pulley's centre is the depth's rate: the radial at the point (over
    // cos(a/2) for a body's end), so that a body turning with the pulley has none.
    let mut press = |arm: V2, share: f64, depth: f64, normal: V2, rate: V2| {
        if depth <= 0.0 {
            return;
        }
        out.penetration += share * depth * depth;
        let v_end = body.velocity + V2::new(-body.spin * arm.y, body.spin * arm.x);
        let approach = -(v_end - center_velocity).dot(&rate);
        let fn_ = share * law(depth, approach);
        if fn_ <= 0.0 {
            return;
        }
        let f = normal * fn_;
        out.force += f;
        out.torque += arm.x * f.y - arm.y * f.x;
        out.normal_force += fn_;
        out.ends += 1;
    };
    if body.length > 0.0 {
        let (s, c) = body.angle.sin_cos();
        let half = V2::new(c, s) * (0.5 * body.length);
        let (corner, cos_half) = (chord.corner, chord.cos_half);
        let mut nu = V2::new(-s, c);
        if nu.dot(&radial) < 0.0 {
            nu = -nu;
        }
        out.normal = nu;
        for arm in [-half, half] {
            let e = rel + arm;
            let r = e.norm();
            let depth = (corner - r) / cos_half;
            let rate = if r > 0.0 { e / (r * cos_half) } else { nu };
            press(arm, 0.5, depth, nu, rate);
        }
    } else {
        out.normal = radial;
        press(V2::zeros(), 1.0, radius - a, radial, radial);
    }
    out.penetration = out.penetration.sqrt();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chord_on_its_circle_subtends_its_arc() {
        let (l, r): (f64, f64) = (0.3, 1.0);
        // The chord of length l whose ends lie on re = l/(2 sin(l/2r)) subtends l/r.
        let re = 0.5 * l / (0.5 * l / r).sin();
        assert!((2.0 * (0.5 * l / re).asin() - l / r).abs() < 1e-14);
        let rho = contact_radius(l, r);
        assert!((rho - (re * re - 0.25 * l * l).sqrt()).abs() < 1e-14);
        // ρ = R − l²/(12R) − l⁴/(720R³) − …
        assert!((rho - (r - l * l / (12.0 * r))).abs() < l.powi(4) / (500.0 * r.powi(3)));
    }

    #[test]
    fn a_tilted_body_is_turned_back() {
        let (l, r, k) = (0.1, 1.0, 1e6);
        let rho = contact_radius(l, r);
        let body = |angle: f64, depth: f64| BodyOnPulley {
            position: V2::new(0.0, rho - depth),
            velocity: V2::zeros(),
            angle,
            spin: 0.0,
            length: l,
        };
        let law = |d: f64, _: f64| k * d;
        let level = body_contact(&body(0.0, 1e-6), V2::zeros(), V2::zeros(), r, law);
        assert!((level.normal_force - k * 1e-6).abs() < 1e-6 * k * 1e-6 + 1e-9);
        assert!(level.torque.abs() < 1e-12);
        assert!(level.force.x.abs() < 1e-12 && level.force.y > 0.0);
        let tilted = body_contact(&body(0.01, 1e-6), V2::zeros(), V2::zeros(), r, law);
        assert!(tilted.torque < 0.0, "{tilted:?}");
        // Along the body's normal: nothing along its axis, which carries the tension.
        let axis = V2::new(0.01f64.cos(), 0.01f64.sin());
        assert!(tilted.force.dot(&axis).abs() < 1e-12 * tilted.force.norm());
        let other = body_contact(&body(-0.01, 1e-6), V2::zeros(), V2::zeros(), r, law);
        assert!(other.torque > 0.0);
        let clear = body_contact(&body(0.0, -1e-6), V2::zeros(), V2::zeros(), r, law);
        assert_eq!(clear.normal_force, 0.0);
    }
}
