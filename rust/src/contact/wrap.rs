//! Wrap contact: a belt element that runs onto a pulley is measured along the belt's path
//! round the pulley (its straight parts plus the arc it lies on), not along its chord.
//!
//! Why (issue 12, docs/case-g.md "The chordal ripple"). With straight elements and nodal
//! contact, the belt round a pulley is a polygon whose nodes stick to the drum: a chain on a
//! sprocket. The strand leaves from the last node on the drum along a chord, so its speed
//! varies as cos α over each node's last θ of travel (θ the element's angle on the drum) and
//! its mean speed is short of ω·r by θ²/24 (the chord is shorter than the arc). On a drum held
//! to its speed curve this speed ripple of 1 − cos(θ/2) at the node-passing frequency v/l
//! becomes tension waves (±10–20 kN on case G at the default 30° elements) and torque spikes
//! (each node landing on the drum is brought to the drum's surface speed within one step).
//!
//! Here an element whose straight segment would cut the pulley's circle, or whose node lies
//! inside it, is the shortest path from its first node to its second outside the circle, the
//! way a string wraps a cylinder: a straight part from each node outside the circle to its
//! tangent point, and the arc between them (a node inside the circle is taken at its radial
//! projection). Its length L = t_p + r·φ + t_q sets the element's tension T (the same
//! Kelvin-Voigt law as the axial pass, with dL/dt for the damper), and the forces are
//! −T·∂L/∂x on the nodes: along the tangent line for a node off the drum, along the drum's
//! tangent for a node on it. The arc presses on the pulley: it receives T·(∂L/∂p + ∂L/∂q)
//! through its centre (the element's forces have no moment about the centre; torque reaches
//! the pulley through friction only). So the strand leaves on the tangent, a node lifts off
//! where the belt does, the wrap holds the arc's length (no mean-speed deficit), and nothing
//! kicks as a node lands or lifts: the path length, its gradient and the arc's load are
//! continuous in the node positions.
//!
//! The arc's normal load T·φ (∫T dφ over the arc) is what the belt's friction on the drum
//! can use; it is shared between the two nodes by where the arc's middle lies along the
//! element, and the friction solve sees each node with its share, along the outward normal
//! at its end of the arc (a node off the drum then sticks along its tangent line, which is
//! the belt material's motion at the tangent point). Nodal penalty contact still keeps the
//! nodes out of the drum.

use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Left normal (counter-clockwise perpendicular).
#[inline]
fn perp(a: V2) -> V2 {
    V2::new(-a.y, a.x)
}

/// `a` turned counter-clockwise by the angle whose cosine and sine are `cos`, `sin`.
#[inline]
fn turn(a: V2, cos: f64, sin: f64) -> V2 {
    V2::new(a.x * cos - a.y * sin, a.x * sin + a.y * cos)
}

/// One element wrapped round a circle: the shortest path from its first node `p` to its
/// second `q` that stays outside the circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wrap {
    /// Path length L = t_p + r·φ + t_q, m.
    pub length: f64,
    /// ∂L/∂p: the unit vector from the tangent point to `p` for a node outside the circle;
    /// (r/ρ) times the drum's tangent for a node inside it (ρ its distance from the centre).
    pub grad_p: V2,
    /// ∂L/∂q, as `grad_p`.
    pub grad_q: V2,
    /// Outward unit normal of the circle where the path from `p` meets it (the tangent point,
    /// or `p`'s radial projection).
    pub normal_p: V2,
    /// The same where the path leaves the circle towards `q`.
    pub normal_q: V2,
    /// Wrapped angle φ, rad (≥ 0).
    pub angle: f64,
    /// Straight length from `p` to its tangent point, m (0 for a node inside).
    pub tangent_p: f64,
    /// Straight length from the circle to `q`, m.
    pub tangent_q: f64,
    /// Fraction of the arc's normal load (T·φ) carried by `q`: where the arc's middle lies
    /// along the path, (t_p + r·φ/2)/L; `p` carries the rest.
    pub share_q: f64,
    /// +1 if the path turns counter-clockwise round the centre from `p` to `q`, −1 if
    /// clockwise.
    pub sense: f64,
}

/// The end of a wrapped path at node `x`: (outward normal where the path meets the circle,
/// straight length to it, ∂L/∂x). `sign` is +sense for the first node and −sense for the
/// second (the path runs into the arc from the first and out of it to the second).
#[inline]
fn end(rel: V2, rho: f64, r: f64, sign: f64) -> (V2, f64, V2) {
    let u = rel / rho;
    if rho <= r {
        // Inside (or on): the radial projection; L depends on the node's angle only.
        return (u, 0.0, -sign * (r / rho) * perp(u));
    }
    // Outside: the tangent point is turned by β = acos(r/ρ) from the node's direction,
    // forwards along the path for the first node, backwards for the second.
    let cos = r / rho;
    let tangent = (rho * rho - r * r).sqrt();
    let sin = sign * tangent / rho;
    let normal = turn(u, cos, sin);
    (normal, tangent, -sign * perp(normal))
}

/// The wrapped path of the element from `p` to `q` round the circle of centre `c` and
/// radius `r`, or `None` where the straight segment stays clear of the circle (both nodes
/// outside it and the segment not cutting it), or would leave it at once (a node just
/// inside whose neighbour lies ahead of its tangent): the element is then its chord.
pub fn wrap(p: V2, q: V2, c: V2, r: f64) -> Option<Wrap> {
    let (rp, rq) = (p - c, q - c);
    let (rho_p, rho_q) = (rp.norm(), rq.norm());
    let d = q - p;
    if !(rho_p > 0.0 && rho_q > 0.0 && d.norm_squared() > 0.0) {
        return None;
    }
    if rho_p >= r && rho_q >= r {
        let (dist, _, _) = super::segment_distance(c, p, q);
        if dist >= r {
            return None;
        }
    }
    // The path passes the centre on the side the chord does: counter-clockwise round it if
    // the centre lies to the left of p → q.
    let cross = d.x * (-rp.y) - d.y * (-rp.x);
    let sense = if cross >= 0.0 { 1.0 } else { -1.0 };
    let (normal_p, tangent_p, grad_p) = end(rp, rho_p, r, sense);
    let (normal_q, tangent_q, grad_q) = end(rq, rho_q, r, -sense);
    let sin = normal_p.x * normal_q.y - normal_p.y * normal_q.x;
    let cos = normal_p.dot(&normal_q);
    let angle = sense * sin.atan2(cos);
    if angle < 0.0 {
        return None;
    }
    let length = tangent_p + r * angle + tangent_q;
    if length.is_nan() || length <= 0.0 {
        return None;
    }
    Some(Wrap {
        length,
        grad_p,
        grad_q,
        normal_p,
        normal_q,
        angle,
        tangent_p,
        tangent_q,
        share_q: (tangent_p + 0.5 * r * angle) / length,
        sense,
    })
}

/// The axial law of the belt's elements, as the axial pass applies it (tension-only clip,
/// damper on or off), for the elements the wrap contact measures again.
#[derive(Debug, Clone, Copy)]
pub struct ElementLaw<'a> {
    /// k per element, N/m.
    pub stiffness: &'a [f64],
    /// c per element, N·s/m.
    pub damping: &'a [f64],
    /// l⁰ per element, m.
    pub rest_length: &'a [f64],
    /// The dampers act (the axial pass is the damped one and damping is on).
    pub damped: bool,
    /// A slack element carries nothing.
    pub tension_only: bool,
    /// The viscoelastic arm force of each element, N (`belt::node::zener`); empty: none.
    pub arm: &'a [f64],
}

impl ElementLaw<'_> {
    /// Tension of element `e` at length `l` (m) lengthening at `rate` (m/s): the axial
    /// pass's formula (`belt::node`), so that the chord force it applied is removed exactly,
    /// plus the element's viscoelastic arm force (`belt::node::zener`: the one law of the
    /// Zener element, for the chord and for the wrapped path alike).
    #[inline]
    pub fn tension(&self, e: usize, l: f64, rate: f64) -> f64 {
        let stretch = l - self.rest_length[e];
        let t = if self.damped {
            self.stiffness[e] * stretch + self.damping[e] * rate
        } else {
            self.stiffness[e] * stretch
        };
        // The Zener element: its Maxwell arm's force in parallel (none when empty).
        let t = match self.arm.get(e) {
            Some(&sigma) => t + sigma,
            None => t,
        };
        if self.tension_only && ((self.damped && stretch < 0.0) || t < 0.0) {
            0.0
        } else {
            t
        }
    }
}

impl ElementLaw<'_> {
    /// Elastic strain energy of element `e` at length `l` (m): ½·k·(l − l⁰)², none when
    /// slack and tension-only, J (the record's strain energy, `record::sample`).
    #[inline]
    pub fn energy(&self, e: usize, l: f64) -> f64 {
        let x = l - self.rest_length[e];
        if self.tension_only && x < 0.0 {
            0.0
        } else {
            0.5 * self.stiffness[e] * x * x
        }
    }
}

/// The force −T·∂L/∂x on a node outside the circle by `depth` (m) along the outward unit
/// `radial`, with its inward radial part capped at `stiffness`·depth: a node just off the
/// drum is pulled back as a penalty spring would push it in (bounded stiffness), not along
/// the exact tangent line, whose radial pull grows as √depth (infinitely stiff at the
/// surface: the relaxation and the explicit step could not settle it). The cap acts within
/// depth < 8T²/(k²r) (5 µm for T = 50 kN, k = 1e8 N/m, r = 0.4 m) only, and moves a node
/// within 4T/k of a tangent point by at most T²/(k·r) of force (1e-3·T at 40 kN).
#[inline]
fn capped(pull: V2, radial: V2, depth: f64, stiffness: f64) -> V2 {
    let inward = -pull.dot(&radial);
    let cap = stiffness * depth;
    if inward > cap {
        pull + radial * (inward - cap)
    } else {
        pull
    }
}

/// One wrapped element applied: its chord force (from the axial pass) is replaced by the
/// wrap's forces, the radial pull on a node just off the drum capped by `stiffness` (N/m,
/// half the contact stiffness: each node has two elements; see [`capped`]). Returns
/// (tension, force on the pulley).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn apply_wrap(
    g: &Wrap,
    e: usize,
    (i, j): (usize, usize),
    x: &[V2],
    v: &[V2],
    (center, center_velocity): (V2, V2),
    (radius, stiffness): (f64, f64),
    law: &ElementLaw,
    force: &mut [V2],
) -> (f64, V2) {
    let d = x[j] - x[i];
    let l = d.norm();
    let chord_rate = d.dot(&(v[j] - v[i])) / l;
    let chord = d * (law.tension(e, l, chord_rate) / l);
    let rate = g.grad_p.dot(&(v[i] - center_velocity)) + g.grad_q.dot(&(v[j] - center_velocity));
    let t = law.tension(e, g.length, rate);
    let end_force = |k: usize, grad: V2, tangent: f64| {
        let pull = grad * -t;
        if tangent > 0.0 && t > 0.0 {
            let rel = x[k] - center;
            let rho = rel.norm();
            capped(pull, rel / rho, rho - radius, stiffness)
        } else {
            pull
        }
    };
    let (fp, fq) = (
        end_force(i, g.grad_p, g.tangent_p),
        end_force(j, g.grad_q, g.tangent_q),
    );
    force[i] += fp - chord;
    force[j] += fq + chord;
    (t, -(fp + fq))
}
