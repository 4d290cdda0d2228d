//! The stable step of central differences, from a Gershgorin bound of each degree of
//! freedom's stiffness.

use super::{Model, Stage};
use crate::error::{BeltError, BeltResult};

/// A stable step and the stiffness bounds it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct StableStep {
    /// Time step in use, s.
    pub dt: f64,
    /// Estimated critical (stability-limit) time step, s.
    pub dt_limit: f64,
    /// Which term sets the limit.
    pub dt_cause: String,
    /// Gershgorin bound of the stiffness seen by each node, N/m.
    pub node_stiffness_bound: Vec<f64>,
    /// Same bound for each takeup's translation, N/m (0 for fixed pulleys).
    pub takeup_stiffness_bound: Vec<f64>,
}

impl Model {
    /// Estimate the critical step of central differences from a Gershgorin bound of each
    /// degree of freedom's stiffness: ω² ≤ K/m and Δt_crit = (2/ω)(√(1+ζ²) − ζ).
    ///
    /// Per node, K sums the axial row 2(k_{i−1}+k_i) (exact for a uniform chain, whose
    /// highest mode has ω = 2√(k/m)), the bending row 16·k_θ/l² (zig-zag mode), and the
    /// stiffest contact a node may meet (pulley or idler penalty). Takeups add the contact
    /// stiffness of every node that can sit on their wrap. Every contact stiffness is
    /// taken times `contact_scale` (1 for the model's own step; the relaxation's
    /// continuation asks for softer ones). The step is the scene's `solver.time_step`
    /// (an error above the limit) or `solver.time_step_fraction` of the limit.
    pub fn stable_step(&self, contact_scale: f64) -> BeltResult<StableStep> {
        let n = self.nodes;
        // A rigid body turning on its two end contacts (k/2 each at the lever l/2,
        // `belt::rigid::contact`): ω² = 2·(k/2)·(l/2)²/(m·l²/12) = 3k/m, i.e. 3k as a
        // stiffness on its translation (and 3c for the damping).
        let k_contact = self
            .pulleys
            .iter()
            .enumerate()
            .map(|(j, p)| {
                let turning = if self.rests_on_ends(j) { 3.0 } else { 1.0 };
                let (k, c) = p.contact_bound(contact_scale);
                (turning * k, turning * c)
            })
            .chain(
                self.idlers
                    .iter()
                    .map(|d| (d.contact_stiffness * contact_scale, d.contact_damping)),
            )
            .fold((0.0f64, 0.0f64), |acc, (k, c)| (acc.0.max(k), acc.1.max(c)));
        let mut limit = f64::INFINITY;
        let mut cause = String::new();
        let mut node_stiffness_bound = vec![0.0; n];
        for (i, bound) in node_stiffness_bound.iter_mut().enumerate() {
            let prev = (i + n - 1) % n;
            let next = (i + 1) % n;
            // A viscoelastic belt's instantaneous stiffness, (1 + r)·k (`belt::node::zener`).
            let stiffening = self.zener.map_or(1.0, |z| z.stiffening());
            let k_ax = 2.0 * stiffening * (self.axial_stiffness[prev] + self.axial_stiffness[i]);
            let c_ax = 2.0 * (self.axial_damping[prev] + self.axial_damping[i]);
            let l = 0.5 * (self.rest_length[prev] + self.rest_length[i]);
            let (k_ax, c_ax, k_bend) = if self.is_rigid() {
                rigid_body_bounds(self, i, k_ax, c_ax)
            } else {
                (k_ax, c_ax, 0.0)
            };
            let k_bend = if self.is_rigid() {
                k_bend
            } else if self.has_stage(Stage::Bending) {
                (self.bending_stiffness[prev]
                    + 4.0 * self.bending_stiffness[i]
                    + self.bending_stiffness[next])
                    * 16.0
                    / 6.0
                    / (l * l)
            } else {
                0.0
            };
            let k_total = k_ax + k_bend + k_contact.0;
            let c_total = c_ax + k_contact.1;
            *bound = k_total;
            // The belt-only mass: loads only add mass to a node, which lowers its ω, so the
            // limit found here holds whatever material the node carries during a run.
            let m = self.mass[i];
            let omega = (k_total / m).sqrt();
            let zeta = c_total / (2.0 * m * omega);
            let dt = 2.0 / omega * ((1.0 + zeta * zeta).sqrt() - zeta);
            if dt < limit {
                limit = dt;
                let dominant = if k_contact.0 >= k_ax.max(k_bend) {
                    "contact"
                } else if k_ax >= k_bend {
                    if self.is_rigid() {
                        "translational SDE"
                    } else {
                        "axial"
                    }
                } else if self.is_rigid() {
                    "torsional SDE"
                } else {
                    "bending"
                };
                cause = format!(
                    "{dominant} stiffness at node {i}: K = {k_total:.4e} N/m on {m:.4e} kg"
                );
            }
        }
        let mut takeup_stiffness_bound = vec![0.0; self.pulleys.len()];
        for (j, p) in self.pulleys.iter().enumerate() {
            let (contact_stiffness, contact_damping) = p.contact_bound(contact_scale);
            if let (Some(t), true) = (&p.takeup, contact_stiffness > 0.0) {
                let wrap = self.path.wrap_angles[j];
                let nodes_on_wrap = (wrap * p.radius / self.element_length()).ceil() + 2.0;
                let k = nodes_on_wrap * contact_stiffness;
                takeup_stiffness_bound[j] = k;
                let omega = (k / t.moving_mass).sqrt();
                let c = nodes_on_wrap * contact_damping;
                let zeta = c / (2.0 * t.moving_mass * omega);
                let dt = 2.0 / omega * ((1.0 + zeta * zeta).sqrt() - zeta);
                if dt < limit {
                    limit = dt;
                    cause = format!("contact stiffness on the takeup {}", p.name);
                }
            }
        }
        // Bearing drag: the explicit update ω ← ω·(1 − b·Δt/I) turns the spin around above
        // Δt = I/b (a drag may only slow a pulley down), and is unstable above 2·I/b.
        for p in &self.pulleys {
            if p.bearing_damping > 0.0 {
                let dt = p.inertia / p.bearing_damping;
                if dt < limit {
                    limit = dt;
                    cause = format!(
                        "bearing damping of pulley {}: b = {:.4e} N·m·s/rad on I = {:.4e} kg·m²",
                        p.name, p.bearing_damping, p.inertia
                    );
                }
            }
        }
        // PI speed controllers: K_p a damper and K_i a spring on the pulley alone.
        for p in &self.pulleys {
            if let Some(c) = &p.control {
                let dt = crate::drives::controller::stable_step(c, p.inertia);
                if dt < limit {
                    limit = dt;
                    cause = format!(
                        "speed controller of pulley {}: K_p = {:.4e} N·m·s/rad, K_i = {:.4e} N·m/rad on I = {:.4e} kg·m²",
                        p.name, c.kp, c.ki, p.inertia
                    );
                }
            }
        }
        // DOL motors: the curve's slope (and a coupling's) is a damper.
        for p in &self.pulleys {
            if let Some(mm) = &p.motor {
                let dt = mm.stable_step(p.inertia);
                if dt < limit {
                    limit = dt;
                    cause = format!(
                        "motor of pulley {}: the slope of its torque curve (or coupling) as a damper",
                        p.name
                    );
                }
            }
        }
        let dt = match self.scene.solver.time_step {
            Some(dt) => {
                if dt > limit {
                    return Err(BeltError::TimeStepTooLarge {
                        requested: dt,
                        limit,
                        cause,
                    });
                }
                dt
            }
            None => self.scene.solver.time_step_fraction * limit,
        };
        Ok(StableStep {
            dt,
            dt_limit: limit,
            dt_cause: cause,
            node_stiffness_bound,
            takeup_stiffness_bound,
        })
    }
}

/// The rigid-body belt's bounds at body `i`, as stiffness and damping on its translation:
/// from the node belt's axial row 2(k_{i−1} + k_i) (`k_ax`, and `c_ax` for the dampers),
/// (translational, damping, torsional).
///
/// A translational SDE couples the ends of two bodies, each end moving with the body's
/// translation and its rotation times l/2. In mass-weighted coordinates one SDE is k·BᵀB
/// with B = (1/√m)[I, √3·n₁, −I, −√3·n₂] (I = m·l²/12 makes the lever (l/2)/√I = √3/√m),
/// whose largest eigenvalue is k·|B|² ≤ 8k/m: four times the node belt's 2k/m, so the
/// translational row is 4× the node row. A torsional SDE c_φ on two bodies of inertia I
/// adds 2c_φ/I per joint, 24·c_φ/l² per joint as a stiffness on the translation (×m).
fn rigid_body_bounds(m: &Model, i: usize, k_ax: f64, c_ax: f64) -> (f64, f64, f64) {
    if m.ends.is_some() {
        return open_chain_bounds(m, i);
    }
    let n = m.nodes;
    let prev = (i + n - 1) % n;
    let l = m.rest_length[i];
    let k_tor = 24.0 * (m.bending_stiffness[prev] + m.bending_stiffness[i]) / (l * l);
    let c_tor = 24.0 * (m.torsional_damping[prev] + m.torsional_damping[i]) / (l * l);
    (4.0 * k_ax, 4.0 * c_ax + c_tor, k_tor)
}

/// The open rigid-body chain's bounds at belt point `i` (a body or an end point), as
/// stiffness and damping on its translation (translational, damping, torsional), joint by
/// joint: a translational SDE of stiffness k between points a and b has the largest
/// mass-weighted eigenvalue k·(αₐ + α_b), α = 1/m + (l/2)²/I, which is 4/m for a thin link
/// (the closed chain's 8k/m for two equal bodies) and 1/m for a point; a torsional SDE
/// c_φ(1/Iₐ + 1/I_b). A point's bound is the sum over its joints (at most two), times its
/// mass; for the closed chain this is [`rigid_body_bounds`]'s. The end joints are stiffer
/// (2c_x) and the end points lighter (ρl/2 without a hanging mass) than the rest, so the
/// ends may set the step (by at most about 10 % for a pulled end).
fn open_chain_bounds(m: &Model, i: usize) -> (f64, f64, f64) {
    let alpha = |j: usize| {
        let l = m.rest_length[j];
        if l > 0.0 {
            1.0 / m.mass[j] + 0.25 * l * l / m.body_inertia[j]
        } else {
            1.0 / m.mass[j]
        }
    };
    let (mut k, mut c, mut tor) = (0.0, 0.0, 0.0);
    for e in [i.wrapping_sub(1), i] {
        if e >= m.elements {
            continue;
        }
        let a = alpha(e) + alpha(e + 1);
        k += m.axial_stiffness[e] * a;
        c += m.axial_damping[e] * a;
        if m.bending_stiffness[e] > 0.0 {
            let inv = 1.0 / m.body_inertia[e] + 1.0 / m.body_inertia[e + 1];
            tor += m.bending_stiffness[e] * inv;
            c += m.torsional_damping[e] * inv;
        }
    }
    let mass = m.mass[i];
    (k * mass, c * mass, tor * mass)
}
