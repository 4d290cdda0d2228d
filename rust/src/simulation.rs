//! The simulation: a compiled [`Model`] (read-only), a [`State`] (mutable), the
//! stepper's scratch buffers and the current recording. Advancing matches on the model's
//! [`Integrator`]; each integrator calls the one force evaluation
//! ([`crate::pipeline::evaluate`]).

use crate::error::{BeltError, BeltResult};
use crate::integrate::{Inertia, Integrator};
use crate::model::Model;
use crate::pipeline::{self, Effects, Scratch, StageContext};
use crate::record::{Channels, Energies, Recording};
use crate::scene::Scene;
use crate::state::State;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Model, state, scratch buffers and the current recording.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// The compiled model (read-only).
    pub model: Model,
    /// The mutable state.
    pub state: State,
    pub(crate) scratch: Scratch,
    pub(crate) inertia: Inertia,
    /// Results of the current or last run.
    pub recording: Recording,
    pub(crate) record_every: u64,
    pub(crate) record_counter: u64,
    /// Time the current recording started, s (the adaptive integrator's recording grid
    /// starts there).
    pub(crate) record_start: f64,
    pub(crate) max_samples: usize,
    /// Per-stage wall time, s (same order as `model.stages`), when profiling is on.
    pub profile: Option<Vec<f64>>,
}

impl Simulation {
    /// Compile a scene and place the belt on its initial path: at rest, or in its design
    /// state (`[initial]`) with the drives' memory primed to hold it
    /// (`crate::drives::prime`).
    pub fn new(scene: &Scene) -> BeltResult<Simulation> {
        let model = Model::compile(scene)?;
        let state = State::initial(&model);
        let mut sim = Self::from_parts(model, state);
        sim.prime_drives();
        Ok(sim)
    }

    /// A simulation of `model` at `state` (e.g. read back from a checkpoint). The state's
    /// array lengths must match the model (checked by the checkpoint reader).
    pub(crate) fn from_parts(model: Model, state: State) -> Simulation {
        let scratch = Scratch::new(&model);
        let inertia = Inertia::physical(&model, &state.node_mass);
        let recording = Recording::new(
            Channels::default(),
            model.nodes,
            model.pulleys.len(),
            model.idlers.len(),
        )
        .with_elements(model.elements);
        Simulation {
            model,
            state,
            scratch,
            inertia,
            recording,
            record_every: 1,
            record_counter: 0,
            record_start: 0.0,
            max_samples: usize::MAX,
            profile: None,
        }
    }

    /// Replace the scene (e.g. a new counterweight or drive torque) and keep the state.
    /// The belt discretisation and the set of pulleys and idlers must not change.
    pub fn set_scene(&mut self, scene: &Scene) -> BeltResult<()> {
        let model = Model::compile(scene)?;
        if model.nodes != self.model.nodes
            || model.pulleys.len() != self.model.pulleys.len()
            || model.idlers.len() != self.model.idlers.len()
        {
            return Err(BeltError::Usage(format!(
                "the new scene has {} nodes, {} pulleys and {} idlers, the running one {}, {} and {}: only parameters may change during a run",
                model.nodes,
                model.pulleys.len(),
                model.idlers.len(),
                self.model.nodes,
                self.model.pulleys.len(),
                self.model.idlers.len()
            )));
        }
        if model.formulation != self.model.formulation || model.integrator != self.model.integrator
        {
            return Err(BeltError::Usage(format!(
                "the new scene asks for a {} belt integrated by {}, the running one is a {} belt integrated by {}: the formulation and the integrator may not change during a run",
                model.formulation.name(),
                model.integrator.name(),
                self.model.formulation.name(),
                self.model.integrator.name()
            )));
        }
        for (j, (a, b)) in model.pulleys.iter().zip(&self.model.pulleys).enumerate() {
            if a.center != b.center
                || a.takeup.as_ref().map(|t| t.direction) != b.takeup.as_ref().map(|t| t.direction)
            {
                return Err(BeltError::Usage(format!(
                    "pulleys[{j}]: the centre and takeup line may not change during a run"
                )));
            }
        }
        // A changed brake begins its deceleration ramp anew.
        for (j, (a, b)) in model.pulleys.iter().zip(&self.model.pulleys).enumerate() {
            if a.brake != b.brake {
                self.state.brake_ramp[j] = 0.0;
            }
        }
        let profile = self.profile.as_ref().map(|_| vec![0.0; model.stages.len()]);
        // The belt masses or the loads may have changed: re-place the material at once
        // (the nodes keep their velocities); changed load points are found anew.
        if model.loads.len() != self.model.loads.len()
            || model
                .loads
                .iter()
                .zip(&self.model.loads)
                .any(|(a, b)| a.start != b.start || a.end != b.end || a.forward != b.forward)
        {
            self.state.load_edges =
                crate::loads::initial_edges(&model.loads, &self.state.position, model.load_belt());
        }
        self.state.node_mass = crate::loads::node_masses(
            &model.mass,
            &model.loads,
            &self.state.load_edges,
            model.load_belt(),
        );
        // Friction memory: kept while the model keeps one, zero when creep friction is
        // switched on, dropped when it is switched off.
        if self.state.creep.len() != model.creep_memory_len() {
            self.state.creep = vec![0.0; model.creep_memory_len()];
        }
        // Stick-force friction's memory: kept while the pulleys and points are the same.
        if self.state.sliding.len() != model.pulleys.len()
            || self.state.position.len() != self.model.nodes
        {
            self.state.sliding = vec![Vec::new(); model.pulleys.len()];
        }
        // Viscoelastic arms: kept while the model keeps them, started relaxed at the
        // current lengths when switched on, dropped when switched off.
        if self.state.arm_force.len() != model.arm_len() {
            self.state.arm_force = vec![0.0; model.arm_len()];
            self.state.arm_length = if model.zener.is_some() {
                crate::belt::node::zener::lengths(&self.state.position, model.elements)
            } else {
                Vec::new()
            };
        }
        self.scratch = Scratch::new(&model);
        self.scratch.contact_detail = self.recording.channels.contact_forces;
        self.inertia = Inertia::physical(&model, &self.state.node_mass);
        self.model = model;
        self.profile = profile;
        Ok(())
    }

    /// How far the stored velocities lag the state's time, s: half a step with central
    /// differences (v(t − Δt/2)), none with the adaptive integrator (v(t)). The recorder
    /// and the energies centre velocities on t with it.
    #[inline]
    pub fn velocity_lag(&self) -> f64 {
        match self.model.integrator {
            Integrator::CentralDifference => 0.5 * self.model.dt,
            Integrator::Rkf45(_) => 0.0,
        }
    }

    /// Turn per-stage timing on (zeroing it) or off.
    pub fn set_profiling(&mut self, on: bool) {
        self.profile = if on {
            Some(vec![0.0; self.model.stages.len()])
        } else {
            None
        };
    }

    /// Evaluate all forces at the current state (thesis eq. 4.57) with `effects`, for a
    /// coming step `dt`.
    pub(crate) fn evaluate(&mut self, effects: Effects) {
        self.evaluate_after(effects, self.model.dt, false);
    }

    /// Evaluate the forces for a step `dt`; with `axial_done`, the axial pass has run
    /// already (fused with the last integration) and the other stages add to it.
    pub(crate) fn evaluate_after(&mut self, effects: Effects, dt: f64, axial_done: bool) {
        self.evaluate_full(effects, dt, dt, 1.0, axial_done);
    }

    /// [`Simulation::evaluate_after`] with every contact stiffness scaled by
    /// `contact_scale` (the relaxation's continuation).
    pub(crate) fn evaluate_scaled(
        &mut self,
        effects: Effects,
        dt: f64,
        contact_scale: f64,
        axial_done: bool,
    ) {
        self.evaluate_full(effects, dt, dt, contact_scale, axial_done);
    }

    /// The force evaluation with every setting: `kick` and `drift` of the coming
    /// integration (see [`StageContext`]), `contact_scale`, `axial_done`.
    pub(crate) fn evaluate_full(
        &mut self,
        effects: Effects,
        kick: f64,
        drift: f64,
        contact_scale: f64,
        axial_done: bool,
    ) {
        let mut cx = StageContext {
            model: &self.model,
            state: &mut self.state,
            scratch: &mut self.scratch,
            inertia: &mut self.inertia,
            effects,
            dt: kick,
            drift,
            contact_scale,
        };
        pipeline::evaluate(&mut cx, axial_done, self.profile.as_deref_mut());
    }

    /// Advance `steps` steps without recording.
    pub fn step(&mut self, steps: u64) -> BeltResult<()> {
        self.steps_with(steps, false, |_| Ok(()))
    }

    /// `steps` steps of the model's integrator, calling `between` (e.g. record) after each
    /// force evaluation; element tensions are written only if `tensions`.
    fn steps_with(
        &mut self,
        steps: u64,
        tensions: bool,
        between: impl FnMut(&mut Self) -> BeltResult<()>,
    ) -> BeltResult<()> {
        match self.model.integrator {
            Integrator::CentralDifference => {
                self.central_difference_steps(steps, tensions, between)
            }
            // An adaptive integrator has no steps of its own size: `steps` model steps of
            // time, without recording.
            Integrator::Rkf45(_) => {
                let end = self.state.time + steps as f64 * self.model.dt;
                self.adaptive_to(end, u64::MAX, false).map(drop)
            }
        }
    }

    /// Start a new recording: the state is sampled now and every `every` steps, keeping at
    /// most `max_samples` instants (≥ 2). When the buffer is full, every other instant is
    /// dropped and the interval doubles ([`Recording::decimate`]), so the recording always
    /// spans the whole run on a uniform grid and its memory stays below
    /// `max_samples × Recording::bytes_per_sample()`.
    pub fn begin_recording(&mut self, channels: Channels, every: u64, max_samples: usize) {
        self.scratch.contact_detail = channels.contact_forces;
        self.recording = Recording::new(
            channels,
            self.model.nodes,
            self.model.pulleys.len(),
            self.model.idlers.len(),
        )
        .with_elements(self.model.elements);
        self.record_every = every.max(1);
        self.record_counter = 0;
        self.record_start = self.state.time;
        self.max_samples = max_samples.max(2);
    }

    /// Steps between recorded instants now (the requested interval, doubled at each
    /// decimation).
    pub fn record_every(&self) -> u64 {
        self.record_every
    }

    /// Bound on the number of recorded instants of the current recording.
    pub fn max_samples(&self) -> usize {
        self.max_samples
    }

    /// Sample if the step counter is on the recording grid, decimating first when full.
    pub(crate) fn record_if_due(&mut self) -> BeltResult<()> {
        if !self.record_counter.is_multiple_of(self.record_every) {
            return Ok(());
        }
        if self.recording.len() >= self.max_samples {
            self.recording.decimate();
            self.record_every = self.record_every.saturating_mul(2);
            if !self.record_counter.is_multiple_of(self.record_every) {
                return Ok(());
            }
        }
        self.recording.reserve_one(self.max_samples);
        self.sample_finite()
    }

    /// Take a sample. A finite state can still give non-finite derived values (energies
    /// of nodes 10^157 m away, forces of an absurd gravity): the run stops, and the
    /// recording keeps only finite rows.
    fn sample_finite(&mut self) -> BeltResult<()> {
        self.sample();
        if let Some((quantity, part)) = self.recording.last_row_non_finite() {
            self.recording.pop_row();
            return Err(self.non_finite_sample(quantity, part));
        }
        Ok(())
    }

    /// Advance `steps` steps, recording as set by [`Simulation::begin_recording`]. On a
    /// blow-up the recording keeps everything sampled before it.
    pub fn advance(&mut self, steps: u64) -> BeltResult<()> {
        if let Integrator::Rkf45(_) = self.model.integrator {
            // `steps` model steps of time, recorded on the recording's time grid.
            let end = self.state.time + steps as f64 * self.model.dt;
            return self.adaptive_to(end, u64::MAX, true).map(drop);
        }
        self.steps_with(steps, true, |sim| {
            sim.record_if_due()?;
            sim.record_counter += 1;
            Ok(())
        })
    }

    /// Advance towards simulated time `end` (s), recording as set by
    /// [`Simulation::begin_recording`], taking at most `max_steps` steps in this call (so
    /// that a caller can check for Ctrl-C or save a checkpoint between calls). Returns
    /// true once the state is at `end` exactly: the integrator owns its steps (central
    /// differences take whole steps and then one shortened step onto `end`). On a blow-up
    /// the recording keeps everything sampled before it.
    pub fn advance_to(&mut self, end: f64, max_steps: u64) -> BeltResult<bool> {
        if !end.is_finite() || end < self.state.time {
            return Err(BeltError::invalid(
                "end time",
                end,
                format!(
                    "must be finite and not before the current time {} s",
                    self.state.time
                ),
            ));
        }
        let record = |sim: &mut Self| {
            sim.record_if_due()?;
            sim.record_counter += 1;
            Ok(())
        };
        match self.model.integrator {
            Integrator::CentralDifference => self.central_difference_to(end, max_steps, record),
            Integrator::Rkf45(_) => self.adaptive_to(end, max_steps, true),
        }
    }

    /// Close a recording: sample the final state (the end of the run), which the
    /// recording's grid may not hold; the last interval is then shorter. A non-finite
    /// sample is not kept and gives [`BeltError::Diverged`].
    pub fn end_recording(&mut self) -> BeltResult<()> {
        self.evaluate(Effects::ALL);
        if self.recording.len() >= self.max_samples {
            self.recording.decimate();
            self.record_every = self.record_every.saturating_mul(2);
        }
        self.recording.reserve_one(self.max_samples);
        self.sample_finite()
    }

    /// Close a recording cut short (e.g. by Ctrl-C): sample the final state only if it is
    /// on the recording grid, so every sample stays on it. A non-finite sample is not
    /// kept and gives [`BeltError::Diverged`].
    pub fn end_recording_on_grid(&mut self) -> BeltResult<()> {
        if self.record_counter.is_multiple_of(self.record_every) {
            self.evaluate(Effects::ALL);
            self.record_if_due()?;
        }
        Ok(())
    }

    /// Run for `duration` seconds, recording about every `interval` seconds (rounded to
    /// whole steps, at least one) and at the end, which lands exactly at the current time
    /// plus `duration`. The recording is unbounded here; use
    /// [`Simulation::begin_recording`] with a bound for long runs.
    pub fn run(
        &mut self,
        duration: f64,
        interval: f64,
        channels: Channels,
    ) -> BeltResult<&Recording> {
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(BeltError::invalid(
                "duration",
                duration,
                "must be a finite number ≥ 0",
            ));
        }
        if !(interval.is_finite() && interval > 0.0) {
            return Err(BeltError::invalid(
                "interval",
                interval,
                "must be a finite number > 0 (s)",
            ));
        }
        let every = (interval / self.model.dt)
            .round()
            .clamp(1.0, u64::MAX as f64) as u64;
        self.begin_recording(channels, every, usize::MAX);
        self.advance_to(self.state.time + duration, u64::MAX)?;
        self.end_recording()?;
        Ok(&self.recording)
    }

    /// The divergence error for a sample whose recorded `quantity` of `part` is not
    /// finite: the first non-finite state value if there is one, else the first non-finite
    /// node force (a finite state with forces that overflow), else the recorded value.
    fn non_finite_sample(&self, quantity: String, part: crate::record::Part) -> BeltError {
        use crate::record::Part;
        use crate::state::Rigid;
        let state_error = self.locate_non_finite();
        if let BeltError::Diverged { ref quantity, .. } = state_error {
            if quantity != "energy" {
                return state_error;
            }
        }
        let (quantity, location) = match self
            .scratch
            .force
            .iter()
            .enumerate()
            .find(|(_, f)| !(f.x.is_finite() && f.y.is_finite()))
        {
            Some((i, f)) => (
                format!("force {}", if f.x.is_finite() { "y" } else { "x" }),
                format!("node {i}"),
            ),
            None => {
                let (m, s, sc) = (&self.model, &self.state, &self.scratch);
                let argmax = |key: &dyn Fn(usize) -> f64| {
                    (0..m.nodes).max_by(|&a, &b| key(a).total_cmp(&key(b)))
                };
                // An energy overflows where its density is largest: name that node.
                let half = self.velocity_lag();
                let spinning = m.dofs.rigid.iter().find_map(|&d| {
                    let mass = self.inertia.rigid(m, d);
                    let w = s.rigid_speed(d) + half * sc.rigid_force(m, d) / mass;
                    if (0.5 * mass * w * w).is_finite() {
                        return None;
                    }
                    Some(match d {
                        Rigid::Takeup(j) | Rigid::Pulley(j) => Part::Pulley(j),
                        Rigid::Idler(k) => Part::Idler(k),
                        Rigid::Body(i) => Part::Node(i),
                    })
                });
                let part = match quantity.as_str() {
                    "kinetic energy" if spinning.is_some() => spinning.unwrap_or(part),
                    "kinetic energy" => argmax(&|i| s.velocity[i].norm()).map_or(part, Part::Node),
                    "gravity energy" => argmax(&|i| s.position[i].y.abs()).map_or(part, Part::Node),
                    "strain energy" => {
                        argmax(&|i| (s.position[(i + 1) % m.nodes] - s.position[i]).norm())
                            .map_or(part, Part::Element)
                    }
                    _ => part,
                };
                let location = match part {
                    Part::Node(i) => format!("node {i}"),
                    Part::Element(i) => format!("element {i}"),
                    Part::Pulley(j) => format!("pulley {}", m.pulleys[j].name),
                    Part::Idler(k) => format!("idler {k}"),
                    Part::Model => "the model".to_string(),
                };
                (quantity, location)
            }
        };
        BeltError::Diverged {
            time: self.state.time,
            step: self.state.step,
            quantity,
            location,
        }
    }

    /// Energies of the current state, J (evaluates the forces once).
    pub fn current_energies(&mut self) -> Energies {
        self.evaluate(Effects::ALL);
        self.energies()
    }

    /// Forces at the current state without stepping (for inspection and tests).
    pub fn forces(&mut self) -> &[V2] {
        self.evaluate(Effects::ALL);
        &self.scratch.force
    }

    /// Element tensions at the current state, N (one per element: `model.elements`).
    pub fn tensions(&mut self) -> &[f64] {
        self.evaluate(Effects::ALL);
        &self.scratch.tension[..self.model.elements]
    }

    /// Number of pulley contacts that slip at the current state (all effects on).
    pub fn slipping_contacts(&mut self) -> usize {
        self.evaluate(Effects::ALL);
        self.scratch.friction.iter().map(|f| f.slipping).sum()
    }

    /// Force of the belt on takeup pulley `j` along its takeup line, against the
    /// counterweight, N (0 for a pulley without a takeup). In static equilibrium it equals
    /// the counterweight pull, (counterweight + pulley mass)·g along the line.
    pub fn takeup_force(&mut self, j: usize) -> f64 {
        self.evaluate(Effects::ALL);
        match &self.model.pulleys[j].takeup {
            Some(t) => -t.direction.dot(&self.scratch.pulley_force[j]),
            None => 0.0,
        }
    }
}
