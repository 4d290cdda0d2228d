//! What a run keeps: flat, row-major buffers that the bindings hand to NumPy, and the
//! sampling of the state into them ([`sample`]).

mod sample;

/// Which arrays to record. Time and the per-pulley/takeup/idler arrays are small and
/// always kept; the per-node and per-element arrays can be switched off, and the energies
/// (a pass over every node and element per sample) are computed only when asked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Channels {
    /// Element tensions `[n_out, n_elements]`.
    pub tension: bool,
    /// Node positions `[n_out, n_nodes, 2]`.
    pub node_position: bool,
    /// Node velocities `[n_out, n_nodes, 2]`.
    pub node_velocity: bool,
    /// Energies `[n_out, 7]` ([`ENERGY_COLUMNS`]). Default false: opt-in.
    pub energy: bool,
    /// Contact forces of every belt point on every pulley, with the point's angle
    /// (`contact_normal`, `contact_friction`, `contact_angle`, each `[n_out, n_pulleys,
    /// n_nodes]`). Default false: opt-in; off, the friction stages keep no per-contact
    /// forces.
    pub contact_forces: bool,
}

impl Default for Channels {
    fn default() -> Self {
        Channels {
            tension: true,
            node_position: true,
            node_velocity: true,
            energy: false,
            contact_forces: false,
        }
    }
}

/// Energies at one instant, J.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy of nodes, pulleys, takeups and idlers.
    pub kinetic: f64,
    /// Axial strain energy.
    pub strain: f64,
    /// Bending energy.
    pub bending: f64,
    /// Gravitational potential of the nodes and the takeup pull (zero at y = 0 and at the
    /// initial takeup position).
    pub gravity: f64,
    /// Penalty energy stored in contacts.
    pub contact: f64,
    /// Work done by drive torques since the start.
    pub drive_work: f64,
}

impl Energies {
    /// Mechanical energy: kinetic + strain + bending + gravity + contact.
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.bending + self.gravity + self.contact
    }
}

/// Recorded results. Every buffer is row-major with the shapes documented per field.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Recording {
    /// Channels being recorded.
    pub channels: Channels,
    /// Nodes.
    pub nodes: usize,
    /// Elements (the nodes of a closed loop, one fewer for an open belt); the width of
    /// `tension`.
    pub elements: usize,
    /// Pulleys.
    pub pulleys: usize,
    /// Idlers.
    pub idlers: usize,
    /// Time, s. `[n_out]`.
    pub time: Vec<f64>,
    /// Element tension, N. `[n_out, n_elements]`.
    pub tension: Vec<f64>,
    /// Node positions, m. `[n_out, n_nodes, 2]`.
    pub node_position: Vec<f64>,
    /// Node velocities (mean of the two half steps), m/s. `[n_out, n_nodes, 2]`.
    pub node_velocity: Vec<f64>,
    /// Pulley centres, m. `[n_out, n_pulleys, 2]`.
    pub pulley_position: Vec<f64>,
    /// Takeup travel along its line from the initial position, m. `[n_out, n_pulleys]`
    /// (zero for fixed pulleys).
    pub takeup_travel: Vec<f64>,
    /// Pulley angular speed, rad/s, counter-clockwise positive. `[n_out, n_pulleys]`.
    pub pulley_speed: Vec<f64>,
    /// Torque of belt friction on each pulley, N·m. `[n_out, n_pulleys]`.
    pub friction_torque: Vec<f64>,
    /// Drive torque applied to each pulley, N·m. `[n_out, n_pulleys]`.
    pub drive_torque: Vec<f64>,
    /// Brake torque applied to each pulley, N·m. `[n_out, n_pulleys]`.
    pub brake_torque: Vec<f64>,
    /// Resultant belt force (contact + friction) on each pulley, N. `[n_out, n_pulleys, 2]`.
    pub pulley_force: Vec<f64>,
    /// Sum of nodal normal contact forces on each pulley, N. `[n_out, n_pulleys]`.
    pub normal_force: Vec<f64>,
    /// Sum of tangential friction forces on each pulley, N. `[n_out, n_pulleys]`.
    pub friction_force: Vec<f64>,
    /// Nodes in contact with each pulley. `[n_out, n_pulleys]`.
    pub contact_nodes: Vec<f64>,
    /// Slipping nodes on each pulley. `[n_out, n_pulleys]`.
    pub slipping_nodes: Vec<f64>,
    /// Idler normal force, N. `[n_out, n_idlers]`.
    pub idler_force: Vec<f64>,
    /// Idler speed, rad/s. `[n_out, n_idlers]`.
    pub idler_speed: Vec<f64>,
    /// Energies, J: columns kinetic, strain, bending, gravity, contact, total, drive_work.
    /// `[n_out, 7]`.
    pub energy: Vec<f64>,
    /// Normal contact force of pulley j on belt point i (node, or rigid body's mass
    /// centre), N, ≥ 0; 0 where the point does not touch the pulley. Summed over the
    /// points it is `normal_force`. `[n_out, n_pulleys, n_nodes]`.
    pub contact_normal: Vec<f64>,
    /// Friction force of belt point i on pulley j, N, along the pulley's counter-clockwise
    /// tangent at the point; 0 where the point does not touch it or no friction acts.
    /// Summed over the points it is `friction_force`. `[n_out, n_pulleys, n_nodes]`.
    pub contact_friction: Vec<f64>,
    /// Angle of belt point i about the centre of pulley j, rad, counter-clockwise from +x,
    /// in (−π, π]; NaN where the point does not touch the pulley.
    /// `[n_out, n_pulleys, n_nodes]`.
    pub contact_angle: Vec<f64>,
}

/// The part of the model a recorded value belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Belt node (index).
    Node(usize),
    /// Belt element (index).
    Element(usize),
    /// Pulley (index).
    Pulley(usize),
    /// Idler (index).
    Idler(usize),
    /// The model as a whole (time, energies).
    Model,
}

/// Buffers of a recording ([`Recording::buffers_mut`]).
const BUFFERS: usize = 21;
/// Index of `contact_angle` among the buffers (NaN by design off the pulleys).
const CONTACT_ANGLE: usize = 20;

/// Column names of [`Recording::energy`].
pub const ENERGY_COLUMNS: [&str; 7] = [
    "kinetic",
    "strain",
    "bending",
    "gravity",
    "contact",
    "total",
    "drive_work",
];

impl Recording {
    /// Empty recording for a model's sizes.
    pub fn new(channels: Channels, nodes: usize, pulleys: usize, idlers: usize) -> Self {
        Recording {
            channels,
            nodes,
            elements: nodes,
            pulleys,
            idlers,
            ..Default::default()
        }
    }

    /// The same with `elements` elements (an open belt: one fewer than the nodes).
    pub fn with_elements(mut self, elements: usize) -> Self {
        self.elements = elements;
        self
    }

    /// Number of recorded instants.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True if nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Every buffer, in a fixed order (the order of [`Recording::row_widths`]).
    fn buffers_mut(&mut self) -> [&mut Vec<f64>; BUFFERS] {
        [
            &mut self.time,
            &mut self.tension,
            &mut self.node_position,
            &mut self.node_velocity,
            &mut self.pulley_position,
            &mut self.takeup_travel,
            &mut self.pulley_speed,
            &mut self.friction_torque,
            &mut self.drive_torque,
            &mut self.brake_torque,
            &mut self.pulley_force,
            &mut self.normal_force,
            &mut self.friction_force,
            &mut self.contact_nodes,
            &mut self.slipping_nodes,
            &mut self.idler_force,
            &mut self.idler_speed,
            &mut self.energy,
            &mut self.contact_normal,
            &mut self.contact_friction,
            &mut self.contact_angle,
        ]
    }

    /// Values each buffer gains per recorded instant, same order as the buffers.
    fn row_widths(&self) -> [usize; BUFFERS] {
        let (n, p, q) = (self.nodes, self.pulleys, self.idlers);
        let c = &self.channels;
        let contact = if c.contact_forces { p * n } else { 0 };
        [
            1,
            if c.tension { self.elements } else { 0 },
            if c.node_position { 2 * n } else { 0 },
            if c.node_velocity { 2 * n } else { 0 },
            2 * p,
            p,
            p,
            p,
            p,
            p,
            2 * p,
            p,
            p,
            p,
            p,
            q,
            q,
            if c.energy { ENERGY_COLUMNS.len() } else { 0 },
            contact,
            contact,
            contact,
        ]
    }

    /// Bytes one recorded instant takes: 8 × (8 + n·(1 + 2 + 2) + 13·p + 2·q + 3·p·n)
    /// with all channels on (n nodes, p pulleys, q idlers); the channels that are off drop
    /// out (the energies' 7 of the 8, the contact forces' 3·p·n).
    pub fn bytes_per_sample(&self) -> usize {
        8 * self.row_widths().iter().sum::<usize>()
    }

    /// Make room for one more instant without letting any buffer's capacity exceed
    /// `max_samples` instants: growth doubles as `Vec` does, but is capped at the bound, so
    /// the memory held never exceeds `max_samples × bytes_per_sample()`.
    pub(crate) fn reserve_one(&mut self, max_samples: usize) {
        let rows = self.len();
        if rows < self.time.capacity() {
            return;
        }
        let target = (2 * rows).max(64).min(max_samples.max(rows + 1));
        let widths = self.row_widths();
        for (buf, w) in self.buffers_mut().into_iter().zip(widths) {
            let want = target * w;
            if want > buf.capacity() {
                buf.reserve_exact(want - buf.len());
            }
        }
    }

    /// Keep every other instant (the 1st, 3rd, 5th, ...), in place. Used by the recorder
    /// when it reaches its bound: the kept samples stay on a uniform grid of twice the
    /// interval, covering the whole run.
    pub fn decimate(&mut self) {
        let rows = self.len();
        if rows == 0 {
            return;
        }
        let widths = self.row_widths();
        for (buf, w) in self.buffers_mut().into_iter().zip(widths) {
            let mut dst = 0;
            for r in (0..rows).step_by(2) {
                buf.copy_within(r * w..(r + 1) * w, dst);
                dst += w;
            }
            buf.truncate(dst);
        }
    }

    /// Where the last recorded instant first holds a non-finite value (`None` if it is
    /// finite or nothing is recorded): the quantity and the part it belongs to.
    pub fn last_row_non_finite(&mut self) -> Option<(String, Part)> {
        if self.is_empty() {
            return None;
        }
        let widths = self.row_widths();
        let (buffer, offset) = self
            .buffers_mut()
            .into_iter()
            .zip(widths)
            .enumerate()
            .find_map(|(b, (buf, w))| {
                if b == CONTACT_ANGLE {
                    return None; // NaN marks the points off the pulley
                }
                let row = &buf[buf.len() - w..];
                row.iter().position(|v| !v.is_finite()).map(|o| (b, o))
            })?;
        let xy = if offset % 2 == 0 { "x" } else { "y" };
        Some(match buffer {
            0 => ("time".into(), Part::Model),
            1 => ("tension".into(), Part::Element(offset)),
            2 => (format!("position {xy}"), Part::Node(offset / 2)),
            3 => (format!("velocity {xy}"), Part::Node(offset / 2)),
            4 => (format!("position {xy}"), Part::Pulley(offset / 2)),
            5 => ("takeup travel".into(), Part::Pulley(offset)),
            6 => ("angular speed".into(), Part::Pulley(offset)),
            7 => ("friction torque".into(), Part::Pulley(offset)),
            8 => ("drive torque".into(), Part::Pulley(offset)),
            9 => ("brake torque".into(), Part::Pulley(offset)),
            10 => (format!("belt force {xy}"), Part::Pulley(offset / 2)),
            11 => ("normal force".into(), Part::Pulley(offset)),
            12 => ("friction force".into(), Part::Pulley(offset)),
            13 => ("contact count".into(), Part::Pulley(offset)),
            14 => ("slipping count".into(), Part::Pulley(offset)),
            15 => ("normal force".into(), Part::Idler(offset)),
            16 => ("angular speed".into(), Part::Idler(offset)),
            18 | 19 => (
                if buffer == 18 {
                    "contact normal force".into()
                } else {
                    "contact friction force".into()
                },
                Part::Node(offset % self.nodes.max(1)),
            ),
            _ => (
                format!(
                    "{} energy",
                    ENERGY_COLUMNS[offset.min(ENERGY_COLUMNS.len() - 1)]
                ),
                Part::Model,
            ),
        })
    }

    /// Drop the last recorded instant.
    pub fn pop_row(&mut self) {
        let rows = self.len();
        if rows == 0 {
            return;
        }
        let widths = self.row_widths();
        for (buf, w) in self.buffers_mut().into_iter().zip(widths) {
            buf.truncate((rows - 1) * w);
        }
    }

    /// Move the recorded buffers out (trimmed to their length), leaving an empty recording
    /// of the same sizes: the bindings hand them to NumPy without a copy.
    pub fn take(&mut self) -> Recording {
        let empty = Recording::new(self.channels, self.nodes, self.pulleys, self.idlers)
            .with_elements(self.elements);
        let mut out = std::mem::replace(self, empty);
        for buf in out.buffers_mut() {
            buf.shrink_to_fit();
        }
        out
    }

    /// Bytes held by the buffers (their length, not their capacity).
    pub fn bytes(&self) -> usize {
        self.len() * self.bytes_per_sample()
    }

    /// Bytes allocated by the buffers (their capacity).
    pub fn allocated_bytes(&mut self) -> usize {
        8 * self
            .buffers_mut()
            .iter()
            .map(|b| b.capacity())
            .sum::<usize>()
    }
}
