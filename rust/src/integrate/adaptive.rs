//! Adaptive Runge–Kutta–Fehlberg 4(5) ([`super::rkf45`]) on the whole state of a
//! simulation: every generalized coordinate and speed of the layout
//! ([`crate::state::DofLayout`]: belt points, takeups, pulleys, idlers, rigid belt bodies)
//! and the drives' work, as one flat vector whose derivative is the pipeline's force
//! evaluation ([`crate::pipeline::evaluate`]).
//!
//! - Velocities are at the state's time (not half a step behind, as with central
//!   differences); the recorder reads them as they are.
//! - The integrator owns its steps: it lands on every recording instant (the grid
//!   `record_start + k·every·Δt`, Δt the model's central-difference step as the grid's
//!   unit) and on the end of the run, and its next step is part of the state
//!   (`State::adaptive_step`), so that a run resumed from a checkpoint takes the same steps
//!   bit for bit.
//! - The error norm is the RMS of eᵢ/(atol + rtol·|yᵢ|) over all components in their SI
//!   units (m, rad, m/s, rad/s; the drives' work is left out of the norm).
//! - After each accepted step the takeups' stops are applied, as central differences do.
//! - The creep friction memory ([`crate::friction::creep`]) is part of the vector: the
//!   creep displacement Δ of every (belt point, pulley) pair, with dΔ/dt from the force
//!   evaluation (the relative speed v, 0 while Δ is held at ±Δmax). Its error enters the
//!   norm (in m) like every other component; the pairs not in contact are dormant
//!   ([`Rkf45::set_dormant_from`]): zero, with zero rate, they are left out of the mean.
//!   The law is applied as it is (no stick limit, which belongs to a fixed step).
//! - Each accepted state is evaluated at once (the next step's first Fehlberg stage,
//!   handed to the integrator, so it costs no extra evaluation), and the creep memory is
//!   settled from its contacts: a pair that is not in contact forgets its creep (a contact
//!   that separates starts afresh), and a Δ beyond ±Δmax (a stage can cross the limit
//!   within a step) is put back on it. Neither changes the derivative (a separated pair has
//!   no friction and no rate; µ₁ is flat beyond Δmax, and the rate is the same on the
//!   limit as beyond it), so the first stage stays exact, and between steps the memory is
//!   always that of the play model: zero off the pulleys, within ±Δmax on them.
//!
//! Effects solved for a fixed step (stick-force friction, speed holds, brakes, running
//! resistance, loads) are refused by the scene rules under this integrator.

use super::rkf45::Rkf45;
use crate::error::BeltResult;
use crate::pipeline::Effects;
use crate::simulation::Simulation;
use crate::state::Rigid;
use nalgebra::Vector2;

/// The rigid degrees of freedom before the belt bodies' rotations, and the bodies' range
/// of belt points (`DofLayout::with_bodies` appends them last, in order): the flat state
/// reads and writes the bodies' angles, spins, torques and inertias as slices, in the
/// layout's order (the same vector as one dispatch per degree of freedom).
fn split_bodies(rigid: &[Rigid]) -> (&[Rigid], std::ops::Range<usize>) {
    let p = (rigid.iter())
        .position(|d| matches!(d, Rigid::Body(_)))
        .unwrap_or(rigid.len());
    let bodies = match rigid.get(p) {
        Some(&Rigid::Body(i)) => i..i + (rigid.len() - p),
        _ => 0..0,
    };
    debug_assert!((rigid[p..].iter().zip(bodies.clone())).all(|(&d, i)| d == Rigid::Body(i)));
    (&rigid[..p], bodies)
}

/// Absolute-tolerance scale of the drives' work in the error norm: large enough that it
/// never sets the step (the work is an output, not a state the forces depend on).
const WORK_SCALE: f64 = 1e300;

impl Simulation {
    /// Number of components of the flat state: positions and rigid coordinates, speeds,
    /// the drives' work, the creep memory.
    fn flat_len(&self) -> usize {
        let m = &self.model;
        let coordinates = m
            .dofs
            .rigid
            .iter()
            .filter(|&&d| self.state.rigid(d).0.is_some())
            .count();
        4 * m.nodes + coordinates + m.dofs.rigid.len() + 1 + self.state.creep.len()
    }

    /// The state as one flat vector (see [`Simulation::flat_len`]).
    fn pack(&self, y: &mut Vec<f64>) {
        let s = &self.state;
        let (head, bodies) = split_bodies(&self.model.dofs.rigid);
        y.clear();
        y.extend(s.position.iter().flat_map(|p| [p.x, p.y]));
        for &d in head {
            if let (Some(q), _) = s.rigid(d) {
                y.push(q);
            }
        }
        y.extend_from_slice(&s.body_angle[bodies.clone()]);
        y.extend(s.velocity.iter().flat_map(|v| [v.x, v.y]));
        y.extend(head.iter().map(|&d| s.rigid_speed(d)));
        y.extend_from_slice(&s.body_spin[bodies]);
        y.push(s.drive_work);
        y.extend_from_slice(&s.creep);
    }

    /// Put a flat vector back into the state.
    fn unpack(&mut self, y: &[f64]) {
        let n = self.model.nodes;
        let s = &mut self.state;
        // Pairs through chunks (no bounds check per component).
        for (p, c) in s.position.iter_mut().zip(y.chunks_exact(2)) {
            *p = Vector2::new(c[0], c[1]);
        }
        let (head, bodies) = split_bodies(&self.model.dofs.rigid);
        let nb = bodies.len();
        let mut k = 2 * s.position.len();
        for &d in head {
            if let (Some(q), _) = s.rigid_mut(d) {
                *q = y[k];
                k += 1;
            }
        }
        s.body_angle[bodies.clone()].copy_from_slice(&y[k..k + nb]);
        k += nb;
        for (v, c) in s.velocity.iter_mut().zip(y[k..].chunks_exact(2)) {
            *v = Vector2::new(c[0], c[1]);
        }
        k += 2 * s.velocity.len();
        debug_assert_eq!(s.velocity.len(), n);
        for &d in head {
            *s.rigid_speed_mut(d) = y[k];
            k += 1;
        }
        s.body_spin[bodies].copy_from_slice(&y[k..k + nb]);
        k += nb;
        s.drive_work = y[k];
        s.creep.copy_from_slice(&y[k + 1..]);
    }

    /// dy/dt at (t, y): the speeds, and the accelerations of one force evaluation.
    fn derivative(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.state.time = t;
        self.unpack(y);
        self.rates(dy);
    }

    /// dy/dt at the state: the speeds, the accelerations of one force evaluation, the
    /// drives' power and the creep rates.
    fn rates(&mut self, dy: &mut [f64]) {
        let dt = self.model.dt;
        self.evaluate_full(Effects::ALL, dt, dt, 1.0, false);
        let (m, s, sc) = (&self.model, &self.state, &self.scratch);
        for (d, v) in dy.chunks_exact_mut(2).zip(&s.velocity) {
            d[0] = v.x;
            d[1] = v.y;
        }
        let (head, bodies) = split_bodies(&m.dofs.rigid);
        let nb = bodies.len();
        let mut k = 2 * s.velocity.len();
        for &d in head {
            if let (Some(_), speed) = s.rigid(d) {
                dy[k] = speed;
                k += 1;
            }
        }
        dy[k..k + nb].copy_from_slice(&s.body_spin[bodies.clone()]);
        k += nb;
        let accelerations = dy[k..].chunks_exact_mut(2).zip(&sc.force);
        for ((d, f), im) in accelerations.zip(&self.inertia.inv_mass) {
            d[0] = f.x * im;
            d[1] = f.y * im;
            k += 2;
        }
        let mut power = 0.0;
        for &d in head {
            dy[k] = sc.rigid_force(m, d) / self.inertia.rigid(m, d);
            k += 1;
            if let Rigid::Pulley(j) = d {
                power += sc.drive_torque[j] * s.pulley_omega[j];
            }
        }
        let spin_rates = dy[k..k + nb]
            .iter_mut()
            .zip(&sc.body_torque[bodies.clone()]);
        for ((rate, &torque), &inertia) in spin_rates.zip(&self.inertia.body_inertia[bodies]) {
            *rate = torque / inertia;
        }
        k += nb;
        dy[k] = power;
        let creep = &mut dy[k + 1..];
        creep.fill(0.0);
        for &(i, rate) in &sc.creep_rate {
            creep[i] = rate;
        }
    }

    /// Settle the creep memory after an accepted step, from the evaluation of the accepted
    /// state: the pairs in contact keep their creep, put back within ±Δmax; the others
    /// forget it (module docs). `y` is the accepted state vector (read only).
    fn settle_creep(&mut self, y: &[f64]) {
        if self.state.creep.is_empty() {
            return;
        }
        let (m, s, sc) = (&self.model, &mut self.state, &self.scratch);
        let start = y.len() - s.creep.len();
        let stride = m.pulleys.len();
        s.creep.fill(0.0);
        for (j, p) in m.pulleys.iter().enumerate() {
            let crate::scene::FrictionModel::Creep(law) = p.friction else {
                continue;
            };
            let limit = law.creep_limit;
            for &i in &sc.contacts[j].node {
                let idx = i * stride + j;
                s.creep[idx] = y[start + idx].clamp(-limit, limit);
            }
        }
    }

    /// The adaptive integrator of this model with its next step from the state.
    fn adaptive(&self, len: usize) -> BeltResult<Rkf45> {
        let super::Integrator::Rkf45(mut params) = self.model.integrator else {
            unreachable!("only called for the RKF45 integrator");
        };
        params.initial_step = self.state.adaptive_step;
        let mut rk = Rkf45::new(params, len)?;
        let mut scales = vec![1.0; len];
        let work = len - self.state.creep.len() - 1;
        scales[work] = WORK_SCALE;
        rk.set_absolute_scales(&scales)?;
        rk.set_dormant_from(work + 1);
        Ok(rk)
    }

    /// One accepted RKF45 step from the state towards `target` (s), landing on it when
    /// within `snap` (s) of it: the state, its time, the step counters and the next step
    /// are updated, the takeups' stops applied, the accepted state evaluated (the next
    /// step's first stage, handed to `rk`) and its creep memory settled.
    fn adaptive_step(
        &mut self,
        rk: &mut Rkf45,
        y: &mut Vec<f64>,
        target: f64,
        snap: f64,
    ) -> BeltResult<()> {
        crate::interrupt::check(self.model.nodes as u64)?;
        self.pack(y);
        let mut t = self.state.time;
        let rejected = rk.stats.rejected;
        let result = rk.step(&mut t, y, target, &mut |tt, yy, dd| {
            self.derivative(tt, yy, dd)
        });
        self.state.rejected_steps += rk.stats.rejected - rejected;
        if let Err(e) = result {
            // The state holds the last trial stage; `y` is still the step's start.
            let start = y.clone();
            return Err(self.adaptive_failure(e, start));
        }
        self.unpack(y);
        self.state.time = t;
        self.state.step += 1;
        self.state.accepted_steps += 1;
        self.state.adaptive_step = rk.next_step();
        let m = &self.model;
        for (j, p) in m.pulleys.iter().enumerate() {
            if let Some(tk) = &p.takeup {
                let s = &mut self.state;
                crate::drives::takeup::apply_stops(
                    tk,
                    &mut s.takeup_travel[j],
                    &mut s.takeup_speed[j],
                );
            }
        }
        if y.iter().any(|v| !v.is_finite()) {
            return Err(self.locate_non_finite());
        }
        if (target - self.state.time).abs() <= snap {
            self.state.time = target;
        }
        // The first stage of the next step, and the contacts that settle the memory.
        self.rates(rk.known_first_stage());
        self.settle_creep(y);
        Ok(())
    }

    /// The error of a failed step, with the state put back at the step's start `y0`.
    fn adaptive_failure(&mut self, e: super::rkf45::StepError, y0: Vec<f64>) -> crate::BeltError {
        let time = match &e {
            super::rkf45::StepError::StepTooSmall { time, .. }
            | super::rkf45::StepError::NonFinite { time, .. } => *time,
        };
        self.unpack(&y0);
        self.state.time = time;
        let err: crate::BeltError = e.into();
        match err {
            crate::BeltError::Diverged { .. } => crate::BeltError::Diverged {
                time,
                step: self.state.step,
                quantity: "state (RKF45 could not take a finite step)".into(),
                location: "the model".into(),
            },
            other => other,
        }
    }

    /// RKF45 towards `end` (s), at most `max_steps` accepted steps in this call, sampling
    /// the recording on its time grid ([`Simulation::begin_recording`]) before each step
    /// that starts on it. Returns true once the state is at `end` exactly.
    pub(crate) fn adaptive_to(
        &mut self,
        end: f64,
        max_steps: u64,
        record: bool,
    ) -> BeltResult<bool> {
        let len = self.flat_len();
        let mut rk = self.adaptive(len)?;
        let mut y = Vec::with_capacity(len);
        let unit = self.model.dt;
        // A recording instant within this of the time is the time (rounding of the sums).
        let snap = |t: f64| 1e-9 * unit + 4.0 * f64::EPSILON * t.abs();
        let mut taken = 0;
        while self.state.time < end {
            if taken == max_steps {
                return Ok(false);
            }
            let mut target = end;
            if record {
                // The next instant of the grid at or after now.
                let every = self.record_every;
                let mut index = self.record_counter.div_ceil(every) * every;
                let mut at = self.record_start + index as f64 * unit;
                while at < self.state.time - snap(at) {
                    index += every;
                    at = self.record_start + index as f64 * unit;
                }
                if (at - self.state.time).abs() <= snap(at) {
                    self.evaluate(Effects::ALL);
                    self.record_counter = index;
                    self.record_if_due()?;
                    self.record_counter = index + 1;
                    let every = self.record_every;
                    let next = self.record_counter.div_ceil(every) * every;
                    target = end.min(self.record_start + next as f64 * unit);
                } else {
                    target = end.min(at);
                }
            }
            self.adaptive_step(&mut rk, &mut y, target, snap(target))?;
            taken += 1;
        }
        self.state.time = end;
        Ok(true)
    }
}
