//! What a run keeps: flat, row-major buffers that the bindings hand to NumPy.

/// Which arrays to record. Time, energies and the per-pulley/takeup arrays are small and
/// always kept; the per-node and per-element arrays can be switched off.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Channels {
    /// Element tensions `[n_out, n_elements]`.
    pub tension: bool,
    /// Node positions `[n_out, n_nodes, 2]`.
    pub node_position: bool,
    /// Node velocities `[n_out, n_nodes, 2]`.
    pub node_velocity: bool,
}

impl Default for Channels {
    fn default() -> Self {
        Channels {
            tension: true,
            node_position: true,
            node_velocity: true,
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
    /// Nodes (= elements).
    pub nodes: usize,
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
}

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
            pulleys,
            idlers,
            ..Default::default()
        }
    }

    /// Number of recorded instants.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True if nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// Bytes held by the buffers.
    pub fn bytes(&self) -> usize {
        8 * (self.time.len()
            + self.tension.len()
            + self.node_position.len()
            + self.node_velocity.len()
            + self.pulley_position.len()
            + self.takeup_travel.len()
            + self.pulley_speed.len()
            + self.friction_torque.len()
            + self.drive_torque.len()
            + self.brake_torque.len()
            + self.pulley_force.len()
            + self.normal_force.len()
            + self.friction_force.len()
            + self.contact_nodes.len()
            + self.slipping_nodes.len()
            + self.idler_force.len()
            + self.idler_speed.len()
            + self.energy.len())
    }
}
