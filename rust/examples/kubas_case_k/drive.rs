//! A standalone two-pulley belt transmission with Kubas's (2014) rigid-body belt, assembled
//! from the kernels (contact eq. 4–11, creep friction eq. 12–19, SDEs eq. 20–23, pulleys
//! eq. 24) and integrated with RKF45, outside `Simulation`. Used by the `kubas_case_k`
//! example (full second) and by a short cargo test.
//!
//! State vector (8n + 4 for n bodies): x, y, φ of every body; their rates; θ of both pulleys;
//! their rates; the creep memory Δ of every (body, pulley) pair.
//!
//! Sign convention: the belt runs clockwise (the paper's figure 11: drive speed negative),
//! the drive pulley at the origin, the driven one at (centre_distance, 0), gravity along −y.
//! The tight span is the bottom one.
#![allow(dead_code)]

use beltrs::belt::rigid::link_inertia;
use beltrs::belt::rigid::sdes::{chain_loads, joint, LinkState, SdeParams};
use beltrs::contact::nonlinear::{circle_gap, cubic_step, NonlinearContact};
use beltrs::drives::resistance::{friction_torque_on_pulley, SpeedResistance};
use beltrs::friction::creep::CreepFriction;
use beltrs::integrate::rkf45::{Rkf45, Rkf45Params, Rkf45Stats};
use nalgebra::Vector2;
use std::f64::consts::PI;

type V2 = Vector2<f64>;

/// How the paper's c_tra is read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CtraReading {
    /// c_tra is the stiffness of one SDE, N/m (literal): EA = c_tra·l.
    PerElement,
    /// c_tra is the stiffness per unit strain, N: EA = c_tra, SDE stiffness c_tra/l.
    PerUnitStrain,
}

/// Case K's parameters (Kubas section 4; /work/shared/docs/reference-cases.md).
#[derive(Debug, Clone, Copy)]
pub struct CaseK {
    /// Number of bodies.
    pub bodies: usize,
    /// Pulley radius r_p (both), m.
    pub radius: f64,
    /// Pulley centre distance, m.
    pub centre_distance: f64,
    /// Pulley inertia (both), kg·m².
    pub pulley_inertia: f64,
    /// Belt mass per unit body length (mᵢ = 0.096·lᵢ), kg/m.
    pub mass_per_length: f64,
    /// c_tra as printed: 1.52·10⁵.
    pub c_tra: f64,
    /// How c_tra is read.
    pub reading: CtraReading,
    /// b_tra, N·s/m (per SDE, as printed).
    pub b_tra: f64,
    /// c_tor, N·m/rad.
    pub c_tor: f64,
    /// b_tor, N·m·s/rad.
    pub b_tor: f64,
    /// Contact law.
    pub contact: NonlinearContact,
    /// Friction law.
    pub friction: CreepFriction,
    /// Static belt tension to set up before the run ("slightly above 550 N"), N.
    pub preload: f64,
    /// Drive torque reached at `ramp_time`, N·m.
    pub drive_torque: f64,
    /// Time to reach the drive torque, s.
    pub ramp_time: f64,
    /// Resistance on the driven pulley.
    pub resistance: SpeedResistance,
    /// Gravity, m/s².
    pub gravity: f64,
    /// RKF45 tolerance: rtol = tol, atol = tol × the component's scale (see `scales`).
    pub tolerance: f64,
}

impl CaseK {
    /// The paper's values with the given c_tra reading.
    pub fn paper(reading: CtraReading) -> Self {
        CaseK {
            bodies: 150,
            radius: 0.027,
            centre_distance: 0.515,
            pulley_inertia: 2.4e-4,
            mass_per_length: 0.096,
            c_tra: 1.52e5,
            reading,
            b_tra: 20.5,
            c_tor: 0.026,
            b_tor: 0.0,
            contact: NonlinearContact::default(),
            friction: CreepFriction::default(),
            preload: 555.0,
            drive_torque: 15.0,
            ramp_time: 0.3,
            resistance: SpeedResistance::viscous_reaching(15.0, 8.0 * PI).unwrap(),
            gravity: 9.81,
            tolerance: 1e-5,
        }
    }

    /// SDE stiffness for bodies of length `l`, N/m.
    pub fn sde_stiffness(&self, l: f64) -> f64 {
        match self.reading {
            CtraReading::PerElement => self.c_tra,
            CtraReading::PerUnitStrain => self.c_tra / l,
        }
    }

    /// EA for bodies of length `l`, N.
    pub fn axial_rigidity(&self, l: f64) -> f64 {
        self.sde_stiffness(l) * l
    }
}

/// One sample of the run.
#[derive(Debug, Clone, Copy, Default)]
pub struct Sample {
    /// Time, s.
    pub time: f64,
    /// Pulley angles, rad.
    pub theta: [f64; 2],
    /// Pulley speeds, rad/s.
    pub omega: [f64; 2],
    /// Mean SDE tension in the middle third of the bottom (tight) span, N.
    pub tight: f64,
    /// Mean SDE tension in the middle third of the top (slack) span, N.
    pub slack: f64,
    /// Mean SDE tension over the whole belt, N.
    pub mean: f64,
    /// Force in SDE 0, N.
    pub sde0: f64,
    /// Bodies in contact with each pulley.
    pub contacts: [usize; 2],
    /// Bodies in contact whose |v_T| is below Δv (creep range), over both pulleys.
    pub creeping: usize,
}

/// The assembled system: geometry, per-body data and scratch.
pub struct System {
    /// Parameters.
    pub case: CaseK,
    /// Body length, m.
    pub length: f64,
    /// Body mass, kg.
    pub mass: f64,
    /// Body inertia, kg·m².
    pub inertia: f64,
    /// SDE parameters.
    pub sde: SdeParams,
    /// Pulley centres, m.
    pub centres: [V2; 2],
    /// Whether friction and drive torques act (off while settling).
    pub friction_on: bool,
    /// Extra velocity drag while settling, 1/s (0 in the run).
    pub drag: f64,
    links: Vec<LinkState>,
    force: Vec<V2>,
    torque: Vec<f64>,
    tension: Vec<f64>,
}

impl System {
    /// A system with bodies of length `length`.
    pub fn new(case: CaseK, length: f64) -> Self {
        let n = case.bodies;
        let mass = case.mass_per_length * length;
        System {
            case,
            length,
            mass,
            inertia: link_inertia(mass, length),
            sde: SdeParams {
                translational_stiffness: case.sde_stiffness(length),
                translational_damping: case.b_tra,
                torsional_stiffness: case.c_tor,
                torsional_damping: case.b_tor,
            },
            centres: [V2::zeros(), V2::new(case.centre_distance, 0.0)],
            friction_on: true,
            drag: 0.0,
            links: vec![
                LinkState {
                    position: V2::zeros(),
                    angle: 0.0,
                    velocity: V2::zeros(),
                    angular_velocity: 0.0,
                    length,
                };
                n
            ],
            force: vec![V2::zeros(); n],
            torque: vec![0.0; n],
            tension: vec![0.0; n],
        }
    }

    /// Length of the state vector.
    pub fn state_len(&self) -> usize {
        8 * self.case.bodies + 4
    }

    /// Absolute-tolerance scales per component: positions 10⁻³ m (so a tolerance of 10⁻⁵
    /// holds positions to 10 nm, 3·10⁻⁴ of a tight-span SDE elongation under the per-strain
    /// reading), angles 0.1 rad, speeds 1 m/s, body spins 10 rad/s, pulley angles 1 rad,
    /// pulley speeds 10 rad/s, creep Δmax.
    pub fn scales(&self) -> Vec<f64> {
        let n = self.case.bodies;
        let mut s = vec![0.0; self.state_len()];
        for i in 0..n {
            s[3 * i] = 1e-3;
            s[3 * i + 1] = 1e-3;
            s[3 * i + 2] = 0.1;
            s[3 * n + 3 * i] = 1.0;
            s[3 * n + 3 * i + 1] = 1.0;
            s[3 * n + 3 * i + 2] = 10.0;
        }
        s[6 * n] = 1.0;
        s[6 * n + 1] = 1.0;
        s[6 * n + 2] = 10.0;
        s[6 * n + 3] = 10.0;
        for v in &mut s[6 * n + 4..] {
            *v = self.case.friction.creep_limit;
        }
        s
    }

    /// Bodies placed with their mass centres on the stadium of radius `rho` about both pulley
    /// centres, equally spaced, aligned with the path, at rest; clockwise order.
    pub fn place(&self, rho: f64) -> Vec<f64> {
        let n = self.case.bodies;
        let d = self.case.centre_distance;
        let arc = PI * rho;
        let total = 2.0 * d + 2.0 * arc;
        let mut y = vec![0.0; self.state_len()];
        for i in 0..n {
            // Start on the top span above the drive pulley, moving +x (clockwise).
            let s = total * i as f64 / n as f64;
            let (p, ang) = if s < d {
                (V2::new(s, rho), 0.0)
            } else if s < d + arc {
                let a = PI / 2.0 - (s - d) / rho;
                (
                    self.centres[1] + V2::new(a.cos(), a.sin()) * rho,
                    a - PI / 2.0,
                )
            } else if s < 2.0 * d + arc {
                (V2::new(d - (s - d - arc), -rho), -PI)
            } else {
                let a = -PI / 2.0 - (s - 2.0 * d - arc) / rho;
                (V2::new(a.cos(), a.sin()) * rho, a - PI / 2.0)
            };
            y[3 * i] = p.x;
            y[3 * i + 1] = p.y;
            y[3 * i + 2] = ang;
        }
        y
    }

    fn unpack(&mut self, y: &[f64]) {
        let n = self.case.bodies;
        for i in 0..n {
            let l = &mut self.links[i];
            l.position = V2::new(y[3 * i], y[3 * i + 1]);
            l.angle = y[3 * i + 2];
            l.velocity = V2::new(y[3 * n + 3 * i], y[3 * n + 3 * i + 1]);
            l.angular_velocity = y[3 * n + 3 * i + 2];
        }
    }

    /// Drive torque at time t (eq. 10 ramp to the set value, clockwise = negative), N·m.
    pub fn drive_torque(&self, t: f64) -> f64 {
        -cubic_step(t, 0.0, 0.0, self.case.ramp_time, self.case.drive_torque)
    }

    /// The right-hand side: dy/dt at (t, y).
    pub fn derivative(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.case.bodies;
        self.unpack(y);
        self.force
            .iter_mut()
            .for_each(|f| *f = V2::new(0.0, -self.mass * self.case.gravity));
        self.torque.iter_mut().for_each(|m| *m = 0.0);
        chain_loads(
            &self.links,
            &self.sde,
            true,
            &mut self.force,
            &mut self.torque,
            &mut self.tension,
        );
        let omega = [y[6 * n + 2], y[6 * n + 3]];
        let mut belt_torque = [0.0; 2];
        for j in 0..2 {
            for i in 0..n {
                let l = &self.links[i];
                let cr = 6 * n + 4 + 2 * i + j;
                dy[cr] = 0.0;
                let Some(g) = circle_gap(
                    l.position,
                    l.velocity,
                    self.centres[j],
                    V2::zeros(),
                    self.case.radius,
                ) else {
                    continue;
                };
                if g.penetration <= 0.0 {
                    continue;
                }
                let normal = self
                    .case
                    .contact
                    .normal_force(g.penetration, g.penetration_rate);
                self.force[i] += g.normal * normal;
                if !self.friction_on {
                    continue;
                }
                // τ̂ = Ẑ × r̂ (eq. 17); pulley point at the mass centre moves at θ̇·|r| along τ̂
                // (eq. 14 with the full lever); v_T = (v_p − v_i)·τ̂ (eq. 15, 18).
                let tau = V2::new(-g.normal.y, g.normal.x);
                let v_rel = omega[j] * g.distance - l.velocity.dot(&tau);
                let creep = y[cr];
                let mu = self.case.friction.coefficient(creep, v_rel);
                let friction = tau * (mu * normal);
                self.force[i] += friction;
                belt_torque[j] += friction_torque_on_pulley(l.position - self.centres[j], friction);
                dy[cr] = self.case.friction.creep_rate(creep, v_rel);
            }
        }
        for i in 0..n {
            let l = &self.links[i];
            dy[3 * i] = l.velocity.x;
            dy[3 * i + 1] = l.velocity.y;
            dy[3 * i + 2] = l.angular_velocity;
            let a = self.force[i] / self.mass - l.velocity * self.drag;
            dy[3 * n + 3 * i] = a.x;
            dy[3 * n + 3 * i + 1] = a.y;
            dy[3 * n + 3 * i + 2] = self.torque[i] / self.inertia - l.angular_velocity * self.drag;
        }
        let (drive, resist) = if self.friction_on {
            (self.drive_torque(t), self.case.resistance.torque(omega[1]))
        } else {
            (0.0, 0.0)
        };
        dy[6 * n] = omega[0];
        dy[6 * n + 1] = omega[1];
        let inertia = self.case.pulley_inertia;
        dy[6 * n + 2] = (drive + belt_torque[0]) / inertia - omega[0] * self.drag;
        dy[6 * n + 3] = (resist + belt_torque[1]) / inertia - omega[1] * self.drag;
    }

    /// After an accepted step: forget the creep of contacts that have separated.
    pub fn release_separated(&self, y: &mut [f64]) {
        let n = self.case.bodies;
        for i in 0..n {
            let p = V2::new(y[3 * i], y[3 * i + 1]);
            for j in 0..2 {
                if (p - self.centres[j]).norm() >= self.case.radius {
                    y[6 * n + 4 + 2 * i + j] = 0.0;
                }
            }
        }
    }

    /// Tensions and counts at state y.
    pub fn sample(&mut self, t: f64, y: &[f64]) -> Sample {
        let n = self.case.bodies;
        self.unpack(y);
        let d = self.case.centre_distance;
        let (mut tight, mut nt, mut slack, mut ns, mut mean) = (0.0, 0, 0.0, 0, 0.0);
        let mut sde0 = 0.0;
        for e in 0..n {
            let r = (e + 1) % n;
            let jl = joint(&self.links[e], &self.links[r], &self.sde);
            let mid = 0.5 * (self.links[e].position + self.links[r].position);
            if e == 0 {
                sde0 = jl.tension;
            }
            mean += jl.tension;
            if mid.x > d / 3.0 && mid.x < 2.0 * d / 3.0 {
                if mid.y < 0.0 {
                    tight += jl.tension;
                    nt += 1;
                } else {
                    slack += jl.tension;
                    ns += 1;
                }
            }
        }
        let mut contacts = [0; 2];
        let mut creeping = 0;
        let omega = [y[6 * n + 2], y[6 * n + 3]];
        for j in 0..2 {
            for l in &self.links {
                let r = l.position - self.centres[j];
                let dist = r.norm();
                if dist < self.case.radius {
                    contacts[j] += 1;
                    let tau = V2::new(-r.y, r.x) / dist;
                    if (omega[j] * dist - l.velocity.dot(&tau)).abs()
                        < self.case.friction.transition_speed
                    {
                        creeping += 1;
                    }
                }
            }
        }
        Sample {
            time: t,
            theta: [y[6 * n], y[6 * n + 1]],
            omega,
            tight: tight / nt.max(1) as f64,
            slack: slack / ns.max(1) as f64,
            mean: mean / n as f64,
            sde0,
            contacts,
            creeping,
        }
    }
}

/// Integrate `sys` from (t, y) to `t_end` with RKF45, releasing separated creep memory after
/// every accepted step, sampling every `every` seconds into `out`.
pub fn run(
    sys: &mut System,
    rk: &mut Rkf45,
    t: &mut f64,
    y: &mut [f64],
    t_end: f64,
    every: f64,
    out: &mut Vec<Sample>,
) -> Result<(), String> {
    let mut next = *t;
    while *t < t_end {
        if *t >= next - 1e-15 {
            out.push(sys.sample(*t, y));
            next += every;
        }
        let target = next.min(t_end);
        while *t < target {
            rk.step(t, y, target, &mut |tt, yy, dd| sys.derivative(tt, yy, dd))
                .map_err(|e| e.to_string())?;
            sys.release_separated(y);
        }
    }
    out.push(sys.sample(*t, y));
    Ok(())
}

/// Result of setting up the preload.
#[derive(Debug, Clone)]
pub struct Settled {
    /// Body length found, m.
    pub length: f64,
    /// Mean SDE tension after settling, N.
    pub preload: f64,
    /// Settling passes run.
    pub passes: usize,
    /// State at the end (at rest, friction memory zero).
    pub state: Vec<f64>,
    /// RKF45 counters of the settling.
    pub stats: Rkf45Stats,
}

/// One settling pass with bodies of length `l`: placed on the stadium, then 0.06 s without
/// friction or torques and with a velocity drag (dynamic relaxation). Returns the sample at
/// the end, the state (velocities zeroed) and the RKF45 counters.
pub fn settle_pass(case: CaseK, l: f64) -> Result<(Sample, Vec<f64>, Rkf45Stats), String> {
    let mut sys = System::new(case, l);
    sys.friction_on = false;
    // Drag of 100/s: a 10 ms decay, six of them in the settling time, and far below the SDE
    // and contact frequencies (10⁴–10⁵ rad/s), so it does not stiffen the system.
    let t_settle = 0.06;
    sys.drag = 100.0;
    // Centres sit inside the rim by the penetration that carries the wrap load:
    // N per body ≈ T·(spacing/ρ).
    let p0 = case.contact.penetration_for(case.preload * l / case.radius);
    let mut y = sys.place(case.radius - p0);
    let params = Rkf45Params {
        relative_tolerance: case.tolerance,
        absolute_tolerance: case.tolerance,
        ..Default::default()
    };
    let mut rk = Rkf45::new(params, y.len()).map_err(|e| e.to_string())?;
    rk.set_absolute_scales(&sys.scales())
        .map_err(|e| e.to_string())?;
    let mut t = 0.0;
    rk.advance_to(&mut t, &mut y, t_settle, &mut |tt, yy, dd| {
        sys.derivative(tt, yy, dd)
    })
    .map_err(|e| e.to_string())?;
    let s = sys.sample(t, &y);
    let m = case.bodies;
    for v in &mut y[3 * m..6 * m] {
        *v = 0.0;
    }
    y[6 * m + 2] = 0.0;
    y[6 * m + 3] = 0.0;
    Ok((s, y, rk.stats))
}

/// The body length of the first settling pass: the pitch path at the preload's strain (a
/// fixed point under the literal reading, where EA depends on l).
pub fn first_length(case: &CaseK) -> f64 {
    let n = case.bodies as f64;
    let path = 2.0 * case.centre_distance + 2.0 * PI * case.radius;
    let mut l = path / n;
    for _ in 0..50 {
        l = path / n / (1.0 + case.preload / case.axial_rigidity(l));
    }
    l
}

/// Find the body length that gives the requested preload: settle (see [`settle_pass`]),
/// measure the mean SDE tension, and correct the length by Newton's rule dT/dl = −k (the
/// loop stretches by n·δl over n SDEs in series). Repeats until the preload is within 0.2 %,
/// at most 6 passes.
pub fn settle(case: CaseK) -> Result<Settled, String> {
    let mut l = first_length(&case);
    let mut stats = Rkf45Stats::default();
    for pass in 1..=6 {
        let (s, state, st) = settle_pass(case, l)?;
        stats.accepted += st.accepted;
        stats.rejected += st.rejected;
        stats.evaluations += st.evaluations;
        if (s.mean - case.preload).abs() < 2e-3 * case.preload || pass == 6 {
            return Ok(Settled {
                length: l,
                preload: s.mean,
                passes: pass,
                state,
                stats,
            });
        }
        l += (s.mean - case.preload) / case.sde_stiffness(l);
    }
    unreachable!()
}
