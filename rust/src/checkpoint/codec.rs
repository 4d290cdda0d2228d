//! The checkpoint payload, byte by byte: a little-endian writer and a bounds-checked
//! reader (every length checked against the bytes left before anything is allocated), and
//! the scene and state in the order of the format (`super`'s module docs).

use crate::drives::controller::DriveMemory;
use crate::loads::LoadEdges;
use crate::scene::Scene;
use crate::state::{ContactWindow, State};
use nalgebra::Vector2;

#[derive(Default)]
pub(super) struct Writer {
    pub(super) buf: Vec<u8>,
}

impl Writer {
    pub(super) fn u64(&mut self, v: u64) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    pub(super) fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }
    pub(super) fn str(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }
    fn bytes(&mut self, b: &[u8]) {
        self.u64(b.len() as u64);
        self.buf.extend_from_slice(b);
    }
    fn f64s(&mut self, v: &[f64]) {
        self.u64(v.len() as u64);
        v.iter().for_each(|&x| self.f64(x));
    }
    fn vec2s(&mut self, v: &[Vector2<f64>]) {
        self.u64(v.len() as u64);
        for p in v {
            self.f64(p.x);
            self.f64(p.y);
        }
    }
}

pub(super) struct Reader<'a> {
    pub(super) bytes: &'a [u8],
    pub(super) pos: usize,
    /// Format version of the file being read.
    pub(super) version: u32,
}

pub(super) type Decoded<T> = Result<T, String>;

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, what: &str) -> Decoded<&'a [u8]> {
        if self.bytes.len() - self.pos < n {
            return Err(format!(
                "corrupt: {what} at payload byte {} runs past the end of the payload",
                self.pos
            ));
        }
        let s = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    pub(super) fn u64(&mut self, what: &str) -> Decoded<u64> {
        Ok(u64::from_le_bytes(
            self.take(8, what)?.try_into().expect("8 bytes"),
        ))
    }
    fn usize(&mut self, what: &str) -> Decoded<usize> {
        let v = self.u64(what)?;
        usize::try_from(v).map_err(|_| format!("corrupt: {what} = {v} does not fit"))
    }
    pub(super) fn f64(&mut self, what: &str) -> Decoded<f64> {
        Ok(f64::from_bits(self.u64(what)?))
    }
    /// A length prefix, checked against the bytes left before anything is allocated.
    fn len(&mut self, what: &str, item_bytes: usize) -> Decoded<usize> {
        let n = self.usize(what)?;
        let left = self.bytes.len() - self.pos;
        if n.checked_mul(item_bytes).is_none_or(|b| b > left) {
            return Err(format!(
                "corrupt: {what} announces {n} items, more than the {left} bytes left"
            ));
        }
        Ok(n)
    }
    pub(super) fn str(&mut self, what: &str) -> Decoded<String> {
        let s = self.bytes(what)?;
        String::from_utf8(s.to_vec()).map_err(|_| format!("corrupt: {what} is not UTF-8"))
    }
    fn bytes(&mut self, what: &str) -> Decoded<&'a [u8]> {
        let n = self.len(what, 1)?;
        self.take(n, what)
    }
    fn f64s(&mut self, what: &str) -> Decoded<Vec<f64>> {
        let n = self.len(what, 8)?;
        (0..n).map(|_| self.f64(what)).collect()
    }
    fn vec2s(&mut self, what: &str) -> Decoded<Vec<Vector2<f64>>> {
        let n = self.len(what, 16)?;
        (0..n)
            .map(|_| Ok(Vector2::new(self.f64(what)?, self.f64(what)?)))
            .collect()
    }
}

/// The scene: its serde form (the one scene schema, [`crate::scene`]) in CBOR, as a
/// length-prefixed byte string. Floats keep every bit.
pub(super) fn write_scene(w: &mut Writer, s: &Scene) {
    let mut bytes = Vec::new();
    // Serialising plain data into a Vec cannot fail: no I/O, no fallible Serialize impl.
    ciborium::into_writer(s, &mut bytes).expect("a scene always serialises");
    w.bytes(&bytes);
}

pub(super) fn read_scene(r: &mut Reader<'_>) -> Decoded<Scene> {
    let bytes = r.bytes("scene")?;
    ciborium::from_reader(bytes).map_err(|e| format!("corrupt: the scene does not read back: {e}"))
}

pub(super) fn write_state(w: &mut Writer, s: &State) {
    w.f64(s.time);
    w.u64(s.step);
    w.vec2s(&s.position);
    w.vec2s(&s.velocity);
    w.f64s(&s.pulley_omega);
    w.f64s(&s.pulley_angle);
    w.f64s(&s.takeup_travel);
    w.f64s(&s.takeup_speed);
    w.f64s(&s.idler_omega);
    w.u64(s.pulley_window.len() as u64);
    for win in &s.pulley_window {
        w.u64(win.first as u64);
        w.u64(win.len as u64);
    }
    w.u64(s.idler_element.len() as u64);
    for &e in &s.idler_element {
        w.u64(e as u64);
    }
    w.f64(s.drive_work);
    w.f64s(&s.node_mass);
    w.u64(s.load_edges.len() as u64);
    for e in &s.load_edges {
        w.u64(e.start_element as u64);
        w.u64(e.end_element as u64);
        w.f64(e.start);
        w.f64(e.end);
    }
    // Added within version 4: files written before it end here (read as zero memory).
    w.u64(s.drive_memory.len() as u64);
    for c in &s.drive_memory {
        w.f64(c.integral);
        w.f64(c.torque);
        w.f64(c.motor_speed);
    }
    // Added within version 4 after the drive memory: older files end before it.
    w.f64s(&s.brake_ramp);
    // Version 5: the rigid belt bodies and the adaptive integrator.
    w.f64s(&s.body_angle);
    w.f64s(&s.body_spin);
    w.f64(s.adaptive_step);
    w.u64(s.accepted_steps);
    w.u64(s.rejected_steps);
    // Version 5, last: the friction (creep) memory.
    w.f64s(&s.creep);
    // Added within version 5 after the friction memory (absent from older files: no
    // viscoelastic arms): the Zener arms' forces and lengths.
    w.f64s(&s.arm_force);
    w.f64s(&s.arm_length);
    // Added within version 5 after the arms (absent from older files: every contact at
    // rest): stick-force friction's memory, the sliding points of each pulley.
    w.u64(s.sliding.len() as u64);
    for list in &s.sliding {
        w.u64(list.len() as u64);
        for &i in list {
            w.u64(i as u64);
        }
    }
}

pub(super) fn read_state(r: &mut Reader<'_>) -> Decoded<State> {
    let time = r.f64("time")?;
    let step = r.u64("step")?;
    let position = r.vec2s("node positions")?;
    let velocity = r.vec2s("node velocities")?;
    let pulley_omega = r.f64s("pulley speeds")?;
    let pulley_angle = r.f64s("pulley angles")?;
    let takeup_travel = r.f64s("takeup travel")?;
    let takeup_speed = r.f64s("takeup speeds")?;
    let idler_omega = r.f64s("idler speeds")?;
    let n = r.len("pulley contact windows", 16)?;
    let pulley_window = (0..n)
        .map(|_| {
            Ok(ContactWindow {
                first: r.usize("pulley contact window")?,
                len: r.usize("pulley contact window")?,
            })
        })
        .collect::<Decoded<Vec<_>>>()?;
    let n = r.len("idler elements", 8)?;
    let idler_element = (0..n)
        .map(|_| r.usize("idler element"))
        .collect::<Decoded<Vec<_>>>()?;
    let drive_work = r.f64("drive work")?;
    let node_mass = r.f64s("node masses")?;
    let n = r.len("load zones", 32)?;
    let load_edges = (0..n)
        .map(|_| {
            Ok(LoadEdges {
                start_element: r.usize("load zone")?,
                end_element: r.usize("load zone")?,
                start: r.f64("load zone")?,
                end: r.f64("load zone")?,
            })
        })
        .collect::<Decoded<Vec<_>>>()?;
    // Controller memory: always in version 5; added within version 4, so absent from
    // older version 4 files (zero memory).
    let drive_memory = if r.version >= 5 || r.pos < r.bytes.len() {
        let n = r.len("drive memories", 24)?;
        (0..n)
            .map(|_| {
                Ok(DriveMemory {
                    integral: r.f64("drive memory")?,
                    torque: r.f64("drive memory")?,
                    motor_speed: r.f64("drive memory")?,
                })
            })
            .collect::<Decoded<Vec<_>>>()?
    } else {
        vec![DriveMemory::default(); pulley_omega.len()]
    };
    // Added within version 4 after the drive memory (absent from older version 4 files:
    // none begun); always in version 5.
    let brake_ramp = if r.version >= 5 || r.pos < r.bytes.len() {
        r.f64s("brake ramps")?
    } else {
        vec![0.0; pulley_omega.len()]
    };
    let (body_angle, body_spin, adaptive_step, accepted_steps, rejected_steps) = if r.version >= 5 {
        (
            r.f64s("belt body angles")?,
            r.f64s("belt body speeds")?,
            r.f64("adaptive step")?,
            r.u64("accepted steps")?,
            r.u64("rejected steps")?,
        )
    } else {
        (Vec::new(), Vec::new(), 0.0, 0, 0)
    };
    // The friction (creep) memory, last in version 5; a file that ends before it (any
    // version 4 file, written before creep friction existed) reads with an empty one.
    let creep = if r.pos < r.bytes.len() {
        r.f64s("friction memory")?
    } else {
        Vec::new()
    };
    let (arm_force, arm_length) = if r.pos < r.bytes.len() {
        (r.f64s("arm forces")?, r.f64s("arm lengths")?)
    } else {
        (Vec::new(), Vec::new())
    };
    let sliding = if r.pos < r.bytes.len() {
        let n = r.len("sliding lists", 8)?;
        (0..n)
            .map(|_| {
                let m = r.len("sliding points", 8)?;
                // Ascending, as the friction solve writes and reads them.
                let mut list = (0..m)
                    .map(|_| r.usize("sliding point"))
                    .collect::<Decoded<Vec<usize>>>()?;
                list.sort_unstable();
                Ok(list)
            })
            .collect::<Decoded<Vec<Vec<usize>>>>()?
    } else {
        vec![Vec::new(); pulley_omega.len()]
    };
    Ok(State {
        sliding,
        time,
        step,
        position,
        velocity,
        pulley_omega,
        pulley_angle,
        takeup_travel,
        takeup_speed,
        idler_omega,
        pulley_window,
        idler_element,
        drive_work,
        node_mass,
        load_edges,
        drive_memory,
        body_angle,
        body_spin,
        adaptive_step,
        accepted_steps,
        rejected_steps,
        brake_ramp,
        creep,
        arm_force,
        arm_length,
    })
}
