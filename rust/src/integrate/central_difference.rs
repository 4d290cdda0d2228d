//! Explicit central differences (thesis eq. 4.58–4.60, 4.62, 4.64–4.65):
//! v(t + Δt/2) = v(t − Δt/2) + Δt·F(t)/m, x(t + Δt) = x(t) + Δt·v(t + Δt/2), for the belt
//! nodes and every rigid degree of freedom of the layout ([`crate::state::DofLayout`]).
//!
//! The fast path: unless profiling, each node update is fused with the next step's axial
//! pass ([`crate::forces::axial_pass`]), one sweep over the nodes instead of two, with the
//! same operations on the same values (so the same bits). This is why the state keeps
//! half-step velocities: the update needs only F(t), never a second force array.

use crate::drives::brake::Holder;
use crate::error::{BeltError, BeltResult};
use crate::forces;
use crate::pipeline::Effects;
use crate::simulation::Simulation;
use crate::state::Rigid;
use nalgebra::Vector2;
use std::cell::Cell;

type V2 = Vector2<f64>;

/// The central-difference update of one node, v ← v + Δt·f/m, x ← x + Δt·v, and a
/// running flag of whether every new position is finite.
///
/// The finiteness check is a flag per position, not one running sum (a chain of dependent
/// additions through every node, which the compiler may not reorder). Testing the new
/// positions suffices: x + v·Δt with Δt > 0 is finite only if the old position and the new
/// velocity are finite (or it overflows), so a non-finite force, velocity or position is
/// caught in the step that produces it.
///
/// On x86-64 the update is written with SSE2 (part of the x86-64 baseline, so always
/// present), one node per 128-bit register: left to itself the compiler vectorises across
/// nodes and spends most of the loop de-interleaving x and y, which made it about 1.6×
/// slower (docs/performance.md). The arithmetic is the same operations in the same order as
/// the portable version, so the result is the same to the last bit.
#[derive(Clone, Copy)]
struct AllFinite {
    #[cfg(target_arch = "x86_64")]
    mask: std::arch::x86_64::__m128d,
    #[cfg(not(target_arch = "x86_64"))]
    finite: bool,
}

#[cfg(target_arch = "x86_64")]
impl AllFinite {
    #[inline(always)]
    fn new() -> AllFinite {
        use std::arch::x86_64::{_mm_castsi128_pd, _mm_set1_epi64x};
        // SAFETY: SSE2 is part of the x86-64 baseline; these only build a register.
        unsafe {
            AllFinite {
                mask: _mm_castsi128_pd(_mm_set1_epi64x(-1)),
            }
        }
    }

    #[inline(always)]
    fn integrate_node(&mut self, x: &mut V2, v: &mut V2, f: V2, inv_mass: f64, dt: f64) {
        use std::arch::x86_64::{
            _mm_add_pd, _mm_and_pd, _mm_castsi128_pd, _mm_cmplt_pd, _mm_loadu_pd, _mm_mul_pd,
            _mm_set1_epi64x, _mm_set1_pd, _mm_storeu_pd,
        };
        // SAFETY: SSE2 is part of the x86-64 baseline, so the intrinsics are available on
        // every x86-64 target. Each pointer is to the two contiguous f64 of one live
        // Vector2<f64> (nalgebra stores it as [f64; 2]), borrowed for this call (shared for
        // f, exclusive for x and v); the unaligned loads and stores need no alignment.
        unsafe {
            let magnitude = _mm_castsi128_pd(_mm_set1_epi64x(i64::MAX));
            let vn = _mm_add_pd(
                _mm_loadu_pd(v.as_ptr()),
                _mm_mul_pd(_mm_loadu_pd(f.as_ptr()), _mm_set1_pd(dt * inv_mass)),
            );
            _mm_storeu_pd(v.as_mut_ptr(), vn);
            let xn = _mm_add_pd(_mm_loadu_pd(x.as_ptr()), _mm_mul_pd(vn, _mm_set1_pd(dt)));
            _mm_storeu_pd(x.as_mut_ptr(), xn);
            let finite = _mm_cmplt_pd(_mm_and_pd(xn, magnitude), _mm_set1_pd(f64::INFINITY));
            self.mask = _mm_and_pd(self.mask, finite);
        }
    }

    #[inline(always)]
    fn all(self) -> bool {
        // SAFETY: SSE2 is part of the x86-64 baseline.
        unsafe { std::arch::x86_64::_mm_movemask_pd(self.mask) == 0b11 }
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl AllFinite {
    fn new() -> AllFinite {
        AllFinite { finite: true }
    }

    #[inline(always)]
    fn integrate_node(&mut self, x: &mut V2, v: &mut V2, f: V2, inv_mass: f64, dt: f64) {
        *v += f * (dt * inv_mass);
        *x += *v * dt;
        self.finite &= x.x.is_finite() & x.y.is_finite();
    }

    fn all(self) -> bool {
        self.finite
    }
}

/// The nodes as the central-difference update moves them, one per `next`: yields each
/// node's new (position, velocity) and keeps the [`AllFinite`] flag.
struct Moving<N, M> {
    nodes: N,
    inv_mass: M,
    dt: f64,
    finite: AllFinite,
}

impl<'a, N, M> Iterator for Moving<N, M>
where
    N: Iterator<Item = ((&'a mut V2, &'a mut V2), &'a Cell<V2>)>,
    M: Iterator<Item = f64>,
{
    type Item = (V2, V2);

    #[inline(always)]
    fn next(&mut self) -> Option<(V2, V2)> {
        let ((x, v), f) = self.nodes.next()?;
        let im = self.inv_mass.next()?;
        self.finite.integrate_node(x, v, f.get(), im, self.dt);
        Some((*x, *v))
    }
}

impl Simulation {
    /// One central-difference update with step `dt` (s): the model's in dynamics, the
    /// relaxation's own there.
    pub(crate) fn integrate(&mut self, dt: f64) -> BeltResult<()> {
        self.integrate_then(dt, None)
    }

    /// [`Simulation::integrate`]; with `Some(tensions)`, the next step's axial pass
    /// ([`forces::axial_pass`], all effects on) is fused into the node loop: each node is
    /// moved and then used at once for its elements, one sweep over the nodes instead of
    /// two, the same operations on the same values (so the same bits). The element
    /// tensions are written only if `tensions`. The caller then evaluates with
    /// `axial_done`.
    pub(crate) fn integrate_then(&mut self, dt: f64, axial: Option<bool>) -> BeltResult<()> {
        let m = &self.model;
        let s = &mut self.state;
        let sc = &mut self.scratch;
        let (x, v) = (&mut s.position, &mut s.velocity);
        let f = Cell::from_mut(sc.force.as_mut_slice()).as_slice_of_cells();
        let next =
            axial.map(|tensions| (m.axial_belt(Effects::ALL.damping, &s.node_mass), tensions));
        let tension = &mut sc.tension;
        let nodes_finite = match self.inertia.same_inv_mass {
            Some(im) => integrate_nodes(x, v, f, std::iter::repeat(im), dt, next, tension),
            None => integrate_nodes(
                x,
                v,
                f,
                self.inertia.inv_mass.iter().copied(),
                dt,
                next,
                tension,
            ),
        };
        let check = self.integrate_rigid(dt, dt);
        self.finish_step(dt, nodes_finite, check)
    }

    /// Close a step of `drift` (s): advance time (not in the static relaxation) and step
    /// count, and report the first
    /// non-finite quantity unless the nodes were finite and `check` (and the drives'
    /// work) is.
    fn finish_step(&mut self, drift: f64, nodes_finite: bool, check: f64) -> BeltResult<()> {
        if let Some(z) = &self.model.zener {
            crate::belt::node::zener::advance_all(
                z,
                &self.model.axial_stiffness,
                self.model.elements,
                &mut self.state,
                drift,
                self.inertia.physical,
                (&mut self.scratch.wrap_excess, &mut self.scratch.arm_excess),
            );
        }
        let s = &mut self.state;
        // The static relaxation's steps (fictitious masses) are not time: it holds still
        // whatever depends on time (e.g. a rising end pull), as it restores it afterwards.
        if self.inertia.physical {
            s.time += drift;
        }
        s.step += 1;
        if !(nodes_finite && (check + s.drive_work).is_finite()) {
            return Err(self.locate_non_finite());
        }
        Ok(())
    }

    /// The central-difference update of every rigid degree of freedom of the layout:
    /// speed += kick·F/m (or the held speed), coordinate += drift·speed, the drives' work,
    /// the takeups' stops; and the friction memory, Δ += drift·dΔ/dt. Returns a sum that is finite only if every value is.
    fn integrate_rigid(&mut self, kick: f64, drift: f64) -> f64 {
        let (m, s, sc) = (&self.model, &mut self.state, &self.scratch);
        let (time, physical) = (s.time, self.inertia.physical);
        let mut check = 0.0;
        // The friction memory, dΔ/dt from the evaluation (explicit Euler over the drift).
        for &(k, rate) in &sc.creep_rate {
            s.creep[k] += drift * rate;
        }
        for &d in m.dofs.driven() {
            let force = sc.rigid_force(m, d);
            let mass = self.inertia.rigid(m, d);
            let (coordinate, speed) = s.rigid_mut(d);
            let old = *speed;
            // A holding brake stops a pulley this step, a speed-controlled drive within its
            // limit puts it on its curve; say so exactly.
            let held = match d {
                Rigid::Pulley(j) => sc.held[j],
                _ => None,
            };
            let mut new = held.unwrap_or(old + kick * force / mass);
            // A takeup's lock and winch limit act in dynamics only (the relaxation moves on
            // fictitious masses to the static state, a screw takeup to its set force).
            if let (Rigid::Takeup(j), true) = (d, physical) {
                if let Some(t) = &m.pulleys[j].takeup {
                    new = crate::drives::takeup::carriage_speed(t, time, new);
                }
            }
            *speed = new;
            if let Some(q) = coordinate {
                *q += new * drift;
            }
            match d {
                Rigid::Pulley(j) => {
                    s.drive_work += sc.drive_torque[j] * 0.5 * (old + new) * drift;
                    check += new + s.pulley_angle[j];
                }
                Rigid::Takeup(j) => {
                    if let Some(t) = &m.pulleys[j].takeup {
                        crate::drives::takeup::apply_stops(
                            t,
                            &mut s.takeup_travel[j],
                            &mut s.takeup_speed[j],
                        );
                    }
                    check += s.takeup_travel[j] + s.takeup_speed[j];
                }
                // Not in `driven()`: the free rotations move below.
                Rigid::Idler(_) | Rigid::Body(_) => {}
            }
        }
        // The free rotations (idlers, belt bodies): the same update, speed += kick·M/I,
        // without the per-kind dispatch (a 1 km conveyor has about a thousand idlers).
        for ((w, &torque), idler) in (s.idler_omega.iter_mut())
            .zip(&sc.idler_torque)
            .zip(&m.idlers)
        {
            *w += kick * torque / idler.inertia;
            check += *w;
        }
        for (((w, angle), &torque), &inertia) in (s.body_spin.iter_mut())
            .zip(s.body_angle.iter_mut())
            .zip(&sc.body_torque)
            .zip(&self.inertia.body_inertia)
        {
            *w += kick * torque / inertia;
            *angle += *w * drift;
            check += *w + *angle;
        }
        if m.has_drive_memory {
            crate::drives::controller::advance_all(m, s, sc, drift);
            crate::drives::motor::advance_all(m, s, sc, kick);
        }
        check
    }

    /// The first non-finite quantity of the state, as an error naming time, step, place
    /// and quantity.
    pub(crate) fn locate_non_finite(&self) -> BeltError {
        let s = &self.state;
        let diverged = |quantity: &str, location: String| BeltError::Diverged {
            time: s.time,
            step: s.step,
            quantity: quantity.to_string(),
            location,
        };
        for i in 0..self.model.nodes {
            let (x, v) = (s.position[i], s.velocity[i]);
            // No force check: a non-finite force makes the node's new velocity non-finite
            // (f·Δt/m is infinite or NaN, and so is v + it), so a force was never the first
            // non-finite quantity found; and after a fused integration the force array
            // already holds the next step's axial forces.
            let checks = [
                ("position x", x.x),
                ("position y", x.y),
                ("velocity x", v.x),
                ("velocity y", v.y),
            ];
            for (q, val) in checks {
                if !val.is_finite() {
                    let e = if i == 0 { self.model.nodes - 1 } else { i - 1 };
                    return diverged(q, format!("node {i} (between elements {e} and {i})"));
                }
            }
        }
        for &d in &self.model.dofs.rigid {
            let (coordinate, speed) = s.rigid(d);
            let coordinate = coordinate.unwrap_or(0.0);
            let (quantity, place) = match d {
                Rigid::Pulley(j) if !speed.is_finite() => ("angular speed", j),
                Rigid::Pulley(j) if !coordinate.is_finite() => ("rotation angle", j),
                Rigid::Takeup(j) if !(speed.is_finite() && coordinate.is_finite()) => {
                    ("takeup travel", j)
                }
                Rigid::Idler(k) if !speed.is_finite() => {
                    return diverged("angular speed", format!("idler {k}"))
                }
                Rigid::Body(i) if !(speed.is_finite() && coordinate.is_finite()) => {
                    let q = if speed.is_finite() {
                        "body angle"
                    } else {
                        "body angular speed"
                    };
                    return diverged(q, format!("belt body {i}"));
                }
                _ => continue,
            };
            return diverged(
                quantity,
                format!("pulley {}", self.model.pulleys[place].name),
            );
        }
        if !s.drive_work.is_finite() {
            return diverged("work done", "the drives".to_string());
        }
        diverged("energy", "the model".to_string())
    }

    /// `steps` steps of: evaluate all forces, `between` (e.g. record), integrate. Unless
    /// profiling (which times the axial stage on its own), each integration but the last
    /// is fused with the next step's axial pass ([`Simulation::integrate_then`]): the same
    /// arithmetic in one sweep over the nodes instead of two. Each call starts with a
    /// complete evaluation, so nothing carries over between calls (a changed scene or
    /// state, a relaxation or a checkpoint in between sees the usual forces). Element
    /// tensions are written only if `tensions`. A scene with material loads is not fused:
    /// its loads stage changes node masses before the axial pass adds the weights.
    pub(crate) fn central_difference_steps(
        &mut self,
        steps: u64,
        tensions: bool,
        mut between: impl FnMut(&mut Self) -> BeltResult<()>,
    ) -> BeltResult<()> {
        // The fused axial pass is the node belt's.
        let fuse = self.profile.is_none() && self.model.loads.is_empty() && !self.model.is_rigid();
        let dt = self.model.dt;
        let mut axial_done = false;
        for k in 0..steps {
            // Between whole steps only: an interrupted call leaves a consistent state (the
            // fused axial pass is redone by the next call's complete evaluation).
            crate::interrupt::check(self.model.nodes as u64)?;
            self.evaluate_after(Effects::ALL, dt, axial_done);
            between(self)?;
            axial_done = fuse && k + 1 < steps;
            self.integrate_then(dt, axial_done.then_some(tensions))?;
        }
        Ok(())
    }
}

/// A remainder below this fraction of a step at the end of a run (plus the rounding the
/// sum of the steps can carry, see [`Simulation::central_difference_to`]) is not time to
/// simulate: the run ends there without a shortened step.
pub const END_SNAP: f64 = 1e-9;

impl Simulation {
    /// Central differences towards `end` (s), at most `max_steps` steps in this call:
    /// whole steps while one fits, then one shortened step onto `end` and the return to
    /// the scheme's half-step velocities ([`Simulation::recentre`]). `between` runs after
    /// each force evaluation, as in [`Simulation::central_difference_steps`]. Returns
    /// true once at `end` (the state's time is then `end` exactly).
    pub(crate) fn central_difference_to(
        &mut self,
        end: f64,
        max_steps: u64,
        mut between: impl FnMut(&mut Self) -> BeltResult<()>,
    ) -> BeltResult<bool> {
        let dt = self.model.dt;
        // The time is a running sum of steps: after n steps it carries up to n rounding
        // errors of half an ulp of the time each. A remainder within that (and
        // END_SNAP·Δt) is rounding, not time to simulate: a step that falls short of
        // `end` by it alone counts as fitting, and no shortened step follows.
        let rounding = END_SNAP * dt + self.state.step as f64 * f64::EPSILON * end.abs();
        let whole = ((end - self.state.time + rounding) / dt).floor().max(0.0);
        let steps = if whole < max_steps as f64 {
            whole as u64
        } else {
            max_steps
        };
        self.central_difference_steps(steps, true, &mut between)?;
        if (steps as f64) < whole {
            return Ok(false);
        }
        let rest = end - self.state.time;
        if rest > rounding {
            // Velocities v(t − Δt/2) → v(t + r/2): a kick of (Δt + r)/2, a drift of r.
            let kick = 0.5 * (dt + rest);
            crate::interrupt::check(self.model.nodes as u64)?;
            self.evaluate_full(Effects::ALL, kick, rest, 1.0, false);
            between(self)?;
            self.integrate_short(kick, rest)?;
            self.state.time = end;
            self.recentre(rest);
        } else {
            self.state.time = end;
        }
        Ok(true)
    }

    /// A step with a kick and a drift of their own (the shortened last step of a run):
    /// v ← v + kick·f/m, x ← x + drift·v, and the same for the rigid degrees of freedom.
    fn integrate_short(&mut self, kick: f64, drift: f64) -> BeltResult<()> {
        let (s, sc) = (&mut self.state, &self.scratch);
        let mut finite = true;
        for (((x, v), f), im) in s
            .position
            .iter_mut()
            .zip(s.velocity.iter_mut())
            .zip(&sc.force)
            .zip(&self.inertia.inv_mass)
        {
            *v += f * (kick * im);
            *x += *v * drift;
            finite &= x.x.is_finite() && x.y.is_finite();
        }
        let check = self.integrate_rigid(kick, drift);
        self.finish_step(drift, finite, check)
    }

    /// After a shortened step of `drift` (s) the velocities are v(t − drift/2); bring them
    /// back to the scheme's v(t − Δt/2) with the accelerations at t:
    /// v ← v + a(t)·(drift − Δt)/2. The next step then kicks by Δt from there, which is
    /// the variable-step central difference's kick (drift + Δt)/2 from v(t − drift/2)
    /// (exactly so where the forces do not depend on velocity). A pulley held by a brake or
    /// a speed-controlled drive is put at its held speed at t − Δt/2; a fluid-coupled
    /// motor's speed is shifted like the pulleys'.
    fn recentre(&mut self, drift: f64) {
        self.evaluate(Effects::ALL);
        let (m, s, sc) = (&self.model, &mut self.state, &self.scratch);
        let dt = m.dt;
        let shift = 0.5 * (drift - dt);
        for ((v, f), im) in s
            .velocity
            .iter_mut()
            .zip(&sc.force)
            .zip(&self.inertia.inv_mass)
        {
            *v += f * (shift * im);
        }
        for &d in &m.dofs.rigid {
            let force = sc.rigid_force(m, d);
            let mass = self.inertia.rigid(m, d);
            let held = match d {
                // A drive on its curve, or a brake or holdback holding at rest: the held
                // speed at t − Δt/2 (a brake slowing at a set rate moves on like a free
                // pulley under its torque, which is that rate).
                Rigid::Pulley(j) if sc.held[j].is_some() => {
                    let omega = s.pulley_omega[j];
                    match m.pulleys[j].hold(s.time - dt, dt, dt, omega, s.brake_ramp[j]) {
                        Some((h, Holder::Drive)) => Some(h.omega),
                        Some((h, Holder::Brake)) if h.omega == 0.0 => Some(0.0),
                        _ => None,
                    }
                }
                Rigid::Takeup(j) => m.pulleys[j]
                    .takeup
                    .as_ref()
                    .filter(|t| s.time >= t.lock_time)
                    .map(|_| 0.0),
                _ => None,
            };
            let speed = s.rigid_speed_mut(d);
            *speed = held.unwrap_or(*speed + shift * force / mass);
        }
        // A motor behind a fluid coupling keeps its speed at the half step like a pulley.
        if m.has_drive_memory {
            crate::drives::motor::advance_all(m, s, sc, shift);
        }
    }
}

/// Central differences on the nodes: v ← v + Δt·f/m, x ← x + Δt·v, and then, with
/// `next` = Some((belt, tensions)), the axial pass of the new state on each node as it
/// moves ([`Simulation::integrate_then`]). Returns whether every new position is finite.
#[inline(always)]
fn integrate_nodes(
    x: &mut [V2],
    v: &mut [V2],
    f: &[Cell<V2>],
    inv_mass: impl Iterator<Item = f64>,
    dt: f64,
    next: Option<(forces::AxialBelt, bool)>,
    tension: &mut [f64],
) -> bool {
    let nodes = Moving {
        nodes: x.iter_mut().zip(v.iter_mut()).zip(f),
        inv_mass,
        dt,
        finite: AllFinite::new(),
    };
    let moved = match next {
        None => {
            let mut nodes = nodes;
            nodes.by_ref().for_each(drop);
            nodes
        }
        Some((belt, true)) => forces::axial_pass(&belt, nodes, &mut &mut *tension, f),
        Some((belt, false)) => forces::axial_pass(&belt, nodes, &mut forces::NoTensions, f),
    };
    moved.finite.all()
}
