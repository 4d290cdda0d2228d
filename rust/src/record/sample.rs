//! Sampling the state into the recording, and the energies (computed only when asked:
//! [`super::Channels::energy`] or [`Simulation::current_energies`]).

use super::Energies;
use crate::integrate::Inertia;
use crate::model::Model;
use crate::model::Stage;
use crate::pipeline::Scratch;
use crate::simulation::Simulation;
use crate::state::{Rigid, State};

impl Simulation {
    /// Energies at the current state; call right after an evaluation (uses the
    /// accelerations to centre the half-step velocities on t).
    pub(crate) fn energies(&self) -> Energies {
        let (m, s, sc) = (&self.model, &self.state, &self.scratch);
        let half = self.velocity_lag();
        let mut e = Energies {
            drive_work: s.drive_work,
            ..Default::default()
        };
        let n = m.nodes;
        let rigid = m.is_rigid();
        if rigid {
            (e.strain, e.bending) = crate::belt::rigid::stage::chain_energy(m, s);
            e.strain += crate::belt::rigid::stage::wrap_energy(m, s);
        }
        for i in 0..n {
            let v = s.velocity[i] + sc.force[i] * (half * self.inertia.inv_mass[i]);
            e.kinetic += 0.5 * s.node_mass[i] * v.norm_squared();
            if m.gravity > 0.0 {
                e.gravity += s.node_mass[i] * m.gravity * s.position[i].y;
            }
            if rigid || i >= m.elements {
                continue; // rigid: no node elements; open belt: its last entry is no element
            }
            let j = (i + 1) % n;
            let stretch = (s.position[j] - s.position[i]).norm() - m.rest_length[i];
            if !(m.tension_only && stretch < 0.0) {
                e.strain += 0.5 * m.axial_stiffness[i] * stretch * stretch;
            }
        }
        // The potential of the end pulls (an open belt), −F·x, with gravity's (exact for a
        // constant pull).
        if let Some(ends) = m.ends {
            for (i, end) in [(0, ends.start), (n - 1, ends.end)] {
                e.gravity -= end.pull(s.time).dot(&s.position[i]);
            }
        }
        if m.has_stage(Stage::Bending) {
            for i in 0..n {
                let theta = crate::forces::bending_angle(&s.position, i);
                e.bending += 0.5 * m.bending_stiffness[i] * theta * theta;
            }
        }
        // Kinetic energy of every rigid degree of freedom at t, with its physical inertia.
        for &d in &m.dofs.rigid {
            let mass = self.inertia.rigid(m, d);
            let w = s.rigid_speed(d) + half * sc.rigid_force(m, d) / mass;
            e.kinetic += 0.5 * mass * w * w;
        }
        let law = m.element_law(false, &[]); // the elements' strain energy
        for (j, p) in m.pulleys.iter().enumerate() {
            if let Some(t) = &p.takeup {
                e.gravity -= t.pull * s.takeup_travel[j];
            }
            match &p.nonlinear {
                None => {
                    for &d in &sc.contacts[j].penetration {
                        e.contact += 0.5 * p.contact_stiffness * d * d;
                    }
                }
                Some(law) => {
                    for &d in &sc.contacts[j].penetration {
                        e.contact += law.energy(d);
                    }
                }
            }
            // Elements wrapped on the pulley store their energy at their path length, not
            // their chord's (contact::wrap).
            for &(i, length) in &sc.contacts[j].wrapped {
                let chord = (s.position[(i + 1) % n] - s.position[i]).norm();
                e.strain += law.energy(i, length) - law.energy(i, chord);
            }
        }
        // Every part pressing on an idler roll, as the force counts them (not only the
        // deepest).
        for c in &sc.idler_contacts {
            e.contact += c.energy;
            // Elements wrapped over a roll (contact::roll_wrap), as on a pulley above.
            e.strain += c.strain;
        }
        e
    }

    /// Append the current state to the recording; call right after an evaluation.
    pub(crate) fn sample(&mut self) {
        let energies = self.recording.channels.energy.then(|| self.energies());
        let half = self.velocity_lag();
        let (m, s, sc) = (&self.model, &self.state, &self.scratch);
        let r = &mut self.recording;
        // The speed of a rigid degree of freedom at t (centred from the half step).
        let speed =
            |d: Rigid| s.rigid_speed(d) + half * sc.rigid_force(m, d) / self.inertia.rigid(m, d);
        r.time.push(s.time);
        if r.channels.tension {
            r.tension.extend_from_slice(&sc.tension[..r.elements]);
        }
        if r.channels.node_position {
            for x in &s.position {
                r.node_position.extend_from_slice(&[x.x, x.y]);
            }
        }
        if r.channels.node_velocity {
            for (v, (f, im)) in s
                .velocity
                .iter()
                .zip(sc.force.iter().zip(&self.inertia.inv_mass))
            {
                let w = v + f * (half * im);
                r.node_velocity.extend_from_slice(&[w.x, w.y]);
            }
        }
        for j in 0..m.pulleys.len() {
            let c = s.pulley_center(m, j);
            r.pulley_position.extend_from_slice(&[c.x, c.y]);
            r.takeup_travel.push(s.takeup_travel[j]);
            r.pulley_speed.push(speed(Rigid::Pulley(j)));
            r.friction_torque.push(sc.friction[j].torque);
            r.drive_torque.push(sc.drive_torque[j]);
            r.brake_torque.push(sc.brake_torque[j]);
            r.pulley_force
                .extend_from_slice(&[sc.pulley_force[j].x, sc.pulley_force[j].y]);
            r.normal_force
                .push(sc.contacts[j].normal_force.iter().sum());
            r.friction_force.push(sc.friction[j].tangential);
            r.contact_nodes.push(sc.contacts[j].len() as f64);
            r.slipping_nodes.push(sc.friction[j].slipping as f64);
            r.motor_speed
                .push(motor_speed(m, s, sc, &self.inertia, j, half));
        }
        for k in 0..m.idlers.len() {
            let c = &sc.idler_contacts[k];
            r.idler_force
                .push(if c.active { c.normal_force } else { 0.0 });
            r.idler_speed.push(speed(Rigid::Idler(k)));
        }
        if r.channels.contact_forces {
            let n = m.nodes;
            for (j, c) in sc.contacts.iter().enumerate() {
                let base = r.contact_normal.len();
                r.contact_normal.resize(base + n, 0.0);
                r.contact_friction.resize(base + n, 0.0);
                r.contact_angle.resize(base + n, f64::NAN);
                let center = s.pulley_center(m, j);
                // The friction stage lists one force per contact when friction acted.
                let friction = (c.friction.len() == c.len()).then_some(&c.friction);
                for (k, &i) in c.node.iter().enumerate() {
                    r.contact_normal[base + i] += c.normal_force[k];
                    if let Some(f) = friction {
                        r.contact_friction[base + i] += f[k];
                    }
                    let d = s.position[i] - center;
                    r.contact_angle[base + i] = d.y.atan2(d.x);
                }
            }
        }
        if let Some(e) = energies {
            r.energy.extend_from_slice(&[
                e.kinetic,
                e.strain,
                e.bending,
                e.gravity,
                e.contact,
                e.total(),
                e.drive_work,
            ]);
        }
    }
}

/// Speed of pulley `j`'s DOL motor at its shaft at t, rad/s, in the motor's sense of
/// rotation (NaN without a motor), centred from the half step (`half`, s) as every
/// recorded speed: σ·i·ω when geared rigidly; behind a fluid coupling the rotor's own
/// speed moved by half a step of (T_motor − T_coupling)/J_r.
fn motor_speed(m: &Model, s: &State, sc: &Scratch, inertia: &Inertia, j: usize, half: f64) -> f64 {
    let Some(mm) = &m.pulleys[j].motor else {
        return f64::NAN;
    };
    match mm.coupling {
        None => {
            let d = Rigid::Pulley(j);
            let omega = s.rigid_speed(d) + half * sc.rigid_force(m, d) / inertia.rigid(m, d);
            mm.factor * omega
        }
        Some(_) => {
            let out = sc.motor[j];
            let accel = if out.active {
                (out.motor_torque - out.coupling_torque) / mm.rotor_inertia
            } else {
                0.0
            };
            s.drive_memory[j].motor_speed + half * accel
        }
    }
}
