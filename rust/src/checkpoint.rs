//! Checkpoints: the whole simulation state and the scene it belongs to, in one file, so a
//! run can stop and resume bit-for-bit.
//!
//! # Format (version 3; versions 1 and 2 are still read)
//!
//! All integers are little-endian; every `f64` is stored as its raw IEEE-754 bits
//! (`f64::to_bits`), so reloading is exact, including −0, ±∞ and NaN payloads.
//!
//! | bytes | content |
//! |---|---|
//! | 0..8 | magic `BELTRSCK` |
//! | 8..12 | format version, `u32` (3) |
//! | 12..16 | reserved, `u32` (0) |
//! | 16..24 | payload length L, `u64` |
//! | 24..24+L | payload |
//! | 24+L..28+L | CRC-32 (IEEE 802.3) of bytes 0..24+L, `u32` |
//!
//! The payload holds, in order: the engine version that wrote it (a string); the scene
//! (every field of [`Scene`], so parameters changed during a run, e.g. a counterweight or a
//! drive, are kept; a drive is tagged 1 when torque-controlled, 2 when speed-controlled, in
//! which case its starting curve and torque limit follow its other fields, so files of
//! torque drives are unchanged); the node count and the time step the model was compiled to (checked
//! on load: the scene must compile to the same model); and the [`State`]: time, step,
//! node positions and half-step velocities, pulley speeds and angles, takeup travel and
//! speed, idler speeds, the contact window of each pulley, the element each idler tracks,
//! and the drive work. Strings and arrays are a `u64` length followed by the items.
//!
//! Version 2 adds, to each idler, its running resistance and rotating mass (after its
//! friction); to the scene, the loads (after the idlers: count, then mass per length,
//! start x, y, end x, y of each); and to the state, after the drive work, the node masses
//! (belt and material) and each load's zone edges (start element, end element, start and
//! end material coordinates). A version-1 file reads as a scene without resistance or
//! loads, whose node masses are the belt's.
//!
//! Version 3 writes each pulley's and idler's contact damping as two options (a tag byte 0/1,
//! then the `f64` when 1): `contact_damping` (N·s/m) then `contact_damping_ratio`, in place
//! of the one `f64`; and the belt's `max_placement_strain` after `tension_only`. Earlier
//! files read as an absolute damping (their value, 0 for none: the run resumes unchanged)
//! and a placement limit of 5 % (the fixed rule then).
//!
//! Nothing else influences the next step: the stepper's scratch buffers are rebuilt on
//! every force evaluation. The recording is not part of a checkpoint.
//!
//! Writes are atomic ([`write_atomic`]): the bytes go to a temporary file in the same
//! directory, which is flushed to disk (`fsync`) and then renamed over the target, so a
//! crash leaves either the old checkpoint or the new one, never a partial file.

use crate::error::{BeltError, BeltResult};
use crate::loads::LoadEdges;
use crate::model::Model;
use crate::scene::{
    BeltParams, BrakeSpec, DriveSpec, Formulation, FrictionModel, IdlerSpec, LoadSpec, PulleySpec,
    Scene, SolverParams, Table, TakeupSpec, Wrap,
};
use crate::simulation::Simulation;
use crate::start_curve::{StartCurve, StartShape};
use crate::state::{ContactWindow, State};
use nalgebra::Vector2;
use std::io::Write;
use std::path::Path;

/// First eight bytes of every checkpoint file.
pub const MAGIC: [u8; 8] = *b"BELTRSCK";
/// Version of the format written by this build.
pub const FORMAT_VERSION: u32 = 3;
/// Oldest version this build reads.
pub const OLDEST_READ_VERSION: u32 = 1;
const HEADER_BYTES: usize = 24;
const CHECKSUM_BYTES: usize = 4;

const CRC_TABLE: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
            k += 1;
        }
        table[i] = c;
        i += 1;
    }
    table
};

/// CRC-32 (IEEE 802.3, the one of zip and PNG) of `bytes`.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c = CRC_TABLE[((c ^ b as u32) & 0xff) as usize] ^ (c >> 8);
    }
    !c
}

/// Serialise a simulation (its scene and state) into checkpoint bytes.
pub fn encode(sim: &Simulation) -> Vec<u8> {
    let mut w = Writer::default();
    w.str(env!("CARGO_PKG_VERSION"));
    write_scene(&mut w, &sim.model.scene);
    w.u64(sim.model.nodes as u64);
    w.f64(sim.model.dt);
    write_state(&mut w, &sim.state);
    let payload = w.buf;
    let mut out = Vec::with_capacity(HEADER_BYTES + payload.len() + CHECKSUM_BYTES);
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&payload);
    let crc = crc32(&out);
    out.extend_from_slice(&crc.to_le_bytes());
    out
}

/// Check the header of a checkpoint file of `total` bytes whose first bytes are `head` (the
/// whole header, or the whole file if it is shorter): magic, format version, and the
/// declared payload length against the file's size. Returns the version and the payload
/// length.
fn check_header(head: &[u8], total: u64) -> Result<(u32, u64), String> {
    if total < (HEADER_BYTES + CHECKSUM_BYTES) as u64 {
        return Err(format!(
            "truncated: {total} bytes, shorter than the {}-byte header and checksum",
            HEADER_BYTES + CHECKSUM_BYTES
        ));
    }
    let bytes = head;
    if bytes[0..8] != MAGIC {
        return Err(format!(
            "not a beltrs checkpoint (the file starts with {:?}, expected {:?})",
            String::from_utf8_lossy(&bytes[0..8]),
            std::str::from_utf8(&MAGIC).unwrap_or("BELTRSCK")
        ));
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if !(OLDEST_READ_VERSION..=FORMAT_VERSION).contains(&version) {
        return Err(format!(
            "format version {version}; this build of beltrs reads versions {OLDEST_READ_VERSION} to {FORMAT_VERSION}"
        ));
    }
    let payload_len = u64::from_le_bytes(bytes[16..24].try_into().expect("8 bytes"));
    let expected = (HEADER_BYTES as u64 + CHECKSUM_BYTES as u64).saturating_add(payload_len);
    if total != expected {
        return Err(format!(
            "{}: the file has {} bytes, its header announces {}",
            if total < expected {
                "truncated"
            } else {
                "trailing data"
            },
            total,
            expected
        ));
    }
    Ok((version, payload_len))
}

/// Rebuild a simulation from checkpoint bytes. The scene is recompiled and must give the
/// same model (node count and time step, bit for bit). Errors describe the problem
/// (the caller adds the file name).
pub fn decode(bytes: &[u8]) -> Result<Simulation, String> {
    let (version, payload_len) = check_header(bytes, bytes.len() as u64)?;
    let end = HEADER_BYTES + payload_len as usize;
    let stored = u32::from_le_bytes(bytes[end..end + 4].try_into().expect("4 bytes"));
    let actual = crc32(&bytes[..end]);
    if stored != actual {
        return Err(format!(
            "corrupt: checksum mismatch (stored CRC-32 {stored:#010x}, computed {actual:#010x})"
        ));
    }
    let mut r = Reader {
        bytes: &bytes[HEADER_BYTES..end],
        pos: 0,
        version,
    };
    let _writer_version = r.str("engine version")?;
    let scene = read_scene(&mut r)?;
    let nodes = r.u64("node count")?;
    let dt = r.f64("time step")?;
    let mut state = read_state(&mut r)?;
    if r.pos != r.bytes.len() {
        return Err(format!(
            "corrupt: {} unread bytes after the state",
            r.bytes.len() - r.pos
        ));
    }
    let model = Model::compile(&scene)
        .map_err(|e| format!("its scene does not compile with this build: {e}"))?;
    if model.nodes as u64 != nodes || model.dt.to_bits() != dt.to_bits() {
        return Err(format!(
            "its scene compiles to {} nodes and Δt = {:e} s with this build, but was saved with {} nodes and Δt = {:e} s; an exact resume is impossible",
            model.nodes, model.dt, nodes, dt
        ));
    }
    if version < 2 {
        // No loads existed: the node masses are the belt's.
        state.node_mass = model.mass.clone();
    }
    check_state_fits(&state, &model)?;
    Ok(Simulation::from_parts(model, state))
}

fn check_state_fits(s: &State, m: &Model) -> Result<(), String> {
    let (n, p, q) = (m.nodes, m.pulleys.len(), m.idlers.len());
    let sizes = [
        ("node positions", s.position.len(), n),
        ("node velocities", s.velocity.len(), n),
        ("pulley speeds", s.pulley_omega.len(), p),
        ("pulley angles", s.pulley_angle.len(), p),
        ("takeup travel", s.takeup_travel.len(), p),
        ("takeup speeds", s.takeup_speed.len(), p),
        ("idler speeds", s.idler_omega.len(), q),
        ("pulley contact windows", s.pulley_window.len(), p),
        ("idler elements", s.idler_element.len(), q),
        ("node masses", s.node_mass.len(), n),
        ("load zones", s.load_edges.len(), m.loads.len()),
    ];
    for (what, have, want) in sizes {
        if have != want {
            return Err(format!("corrupt: {have} {what} for a model with {want}"));
        }
    }
    for (j, w) in s.pulley_window.iter().enumerate() {
        if w.first >= n || w.len > n {
            return Err(format!(
                "corrupt: contact window of pulley {j} ({}, {}) outside the {n} nodes",
                w.first, w.len
            ));
        }
    }
    for (k, &e) in s.idler_element.iter().enumerate() {
        if e >= n {
            return Err(format!("corrupt: idler {k} tracks element {e} of {n}"));
        }
    }
    for (k, e) in s.load_edges.iter().enumerate() {
        if e.start_element >= n || e.end_element >= n {
            return Err(format!(
                "corrupt: load {k} tracks elements {} and {} of {n}",
                e.start_element, e.end_element
            ));
        }
    }
    if let Some(i) = s
        .node_mass
        .iter()
        .position(|m| !(m.is_finite() && *m > 0.0))
    {
        return Err(format!("corrupt: node {i} has mass {} kg", s.node_mass[i]));
    }
    Ok(())
}

/// Write `bytes` to `path` atomically: to a temporary file in the same directory, flushed
/// to disk, then renamed over `path` (and the directory flushed). `before_rename` runs
/// once the temporary file is complete, just before the rename; an error from it aborts
/// the write like a crash would (tests use it), leaving `path` untouched. On any error the
/// temporary file is removed.
pub fn write_atomic(
    path: &Path,
    bytes: &[u8],
    before_rename: impl FnOnce(&Path) -> std::io::Result<()>,
) -> BeltResult<()> {
    let fail = |problem: String| BeltError::Checkpoint {
        path: path.display().to_string(),
        problem,
    };
    let name = path
        .file_name()
        .ok_or_else(|| fail("not a file name".into()))?
        .to_string_lossy()
        .into_owned();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    // Unique per call: saves from several threads of one process (or one thread's saves
    // to the same path) never share a temporary file.
    static SAVES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let call = SAVES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!(".{name}.{}.{call}.tmp", std::process::id()));
    let write = || -> std::io::Result<()> {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        drop(f);
        before_rename(&tmp)?;
        std::fs::rename(&tmp, path)?;
        // Make the rename itself durable. Some platforms cannot open a directory; the
        // file is complete either way.
        if let Ok(d) = std::fs::File::open(&dir) {
            let _ = d.sync_all();
        }
        Ok(())
    };
    write().map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        fail(format!("cannot write: {e}"))
    })
}

/// Save the simulation's scene and state to `path` (atomically).
pub fn save(sim: &Simulation, path: &Path) -> BeltResult<()> {
    write_atomic(path, &encode(sim), |_| Ok(()))
}

/// Load a simulation from the checkpoint at `path`.
pub fn load(path: &Path) -> BeltResult<Simulation> {
    let fail = |problem: String| BeltError::Checkpoint {
        path: path.display().to_string(),
        problem,
    };
    let bytes = read_file(path).map_err(fail)?;
    decode(&bytes).map_err(fail)
}

/// The bytes of the checkpoint file at `path`, read safely: anything but a regular file is
/// refused before it is opened (a FIFO would block, `/dev/zero` never ends), the header
/// is read and checked (magic, version, and the declared length against the file's size)
/// before anything else, and the rest is read in chunks that poll [`crate::interrupt`].
fn read_file(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let cannot = |e: std::io::Error| format!("cannot read: {e}");
    let regular = |meta: &std::fs::Metadata| -> Result<u64, String> {
        if meta.is_file() {
            return Ok(meta.len());
        }
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "a device, FIFO or socket"
        };
        Err(format!("not a regular file ({kind})"))
    };
    regular(&std::fs::metadata(path).map_err(cannot)?)?;
    let mut file = std::fs::File::open(path).map_err(cannot)?;
    // Again on the open file: the path may have been replaced in between.
    let size = regular(&file.metadata().map_err(cannot)?)?;
    let mut head = vec![0u8; HEADER_BYTES.min(size as usize)];
    file.read_exact(&mut head).map_err(cannot)?;
    check_header(&head, size)?;
    let mut bytes = head;
    bytes.reserve_exact(size as usize - bytes.len());
    const CHUNK: u64 = 1 << 20;
    loop {
        let got = (&mut file)
            .take(CHUNK)
            .read_to_end(&mut bytes)
            .map_err(cannot)?;
        if got == 0 || bytes.len() as u64 > size {
            break;
        }
        crate::interrupt::check(CHUNK / 8).map_err(|_| "interrupted".to_string())?;
    }
    if bytes.len() as u64 != size {
        return Err(format!(
            "the file changed while it was read ({size} bytes, then {})",
            bytes.len()
        ));
    }
    Ok(bytes)
}

/// Load a checkpoint and check that it holds `scene` (e.g. the scene file a user resumes
/// with): a different scene is an error naming the first part that differs.
pub fn load_for(path: &Path, scene: &Scene) -> BeltResult<Simulation> {
    let sim = load(path)?;
    if let Some(diff) = scene_difference(&sim.model.scene, scene) {
        return Err(BeltError::Checkpoint {
            path: path.display().to_string(),
            problem: format!("it holds a different scene than the one given: {diff}"),
        });
    }
    Ok(sim)
}

/// The first part in which two scenes differ (`None` if they are equal), as
/// "pulleys[1]: ... in the checkpoint, ... given".
pub fn scene_difference(saved: &Scene, given: &Scene) -> Option<String> {
    fn show(field: &str, a: &dyn std::fmt::Debug, b: &dyn std::fmt::Debug) -> String {
        format!("{field}: {a:?} in the checkpoint, {b:?} given")
    }
    if saved.gravity.to_bits() != given.gravity.to_bits() {
        return Some(show("gravity", &saved.gravity, &given.gravity));
    }
    if saved.belt != given.belt {
        return Some(show("belt", &saved.belt, &given.belt));
    }
    if saved.solver != given.solver {
        return Some(show("solver", &saved.solver, &given.solver));
    }
    if saved.pulleys.len() != given.pulleys.len() {
        return Some(format!(
            "pulleys: {} in the checkpoint, {} given",
            saved.pulleys.len(),
            given.pulleys.len()
        ));
    }
    for (i, (a, b)) in saved.pulleys.iter().zip(&given.pulleys).enumerate() {
        if a != b {
            return Some(show(&format!("pulleys[{i}]"), a, b));
        }
    }
    if saved.idlers.len() != given.idlers.len() {
        return Some(format!(
            "idlers: {} in the checkpoint, {} given",
            saved.idlers.len(),
            given.idlers.len()
        ));
    }
    for (i, (a, b)) in saved.idlers.iter().zip(&given.idlers).enumerate() {
        if a != b {
            return Some(show(&format!("idlers[{i}]"), a, b));
        }
    }
    if saved.loads.len() != given.loads.len() {
        return Some(format!(
            "loads: {} in the checkpoint, {} given",
            saved.loads.len(),
            given.loads.len()
        ));
    }
    for (i, (a, b)) in saved.loads.iter().zip(&given.loads).enumerate() {
        if a != b {
            return Some(show(&format!("loads[{i}]"), a, b));
        }
    }
    None
}

#[derive(Default)]
struct Writer {
    buf: Vec<u8>,
}

impl Writer {
    fn u8(&mut self, v: u8) {
        self.buf.push(v);
    }
    fn u64(&mut self, v: u64) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    fn f64(&mut self, v: f64) {
        self.u64(v.to_bits());
    }
    fn bool(&mut self, v: bool) {
        self.u8(v as u8);
    }
    fn str(&mut self, s: &str) {
        self.u64(s.len() as u64);
        self.buf.extend_from_slice(s.as_bytes());
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
    fn opt_f64(&mut self, v: Option<f64>) {
        match v {
            None => self.u8(0),
            Some(x) => {
                self.u8(1);
                self.f64(x);
            }
        }
    }
    fn table(&mut self, t: &Table) {
        self.f64s(&t.x);
        self.f64s(&t.y);
    }
    fn friction(&mut self, f: &FrictionModel) {
        match *f {
            FrictionModel::None => self.u8(0),
            FrictionModel::StickForce {
                static_coefficient,
                kinetic_coefficient,
            } => {
                self.u8(1);
                self.f64(static_coefficient);
                self.f64(kinetic_coefficient);
            }
        }
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Format version of the file being read.
    version: u32,
}

type Decoded<T> = Result<T, String>;

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
    fn u8(&mut self, what: &str) -> Decoded<u8> {
        Ok(self.take(1, what)?[0])
    }
    fn u64(&mut self, what: &str) -> Decoded<u64> {
        Ok(u64::from_le_bytes(
            self.take(8, what)?.try_into().expect("8 bytes"),
        ))
    }
    fn usize(&mut self, what: &str) -> Decoded<usize> {
        let v = self.u64(what)?;
        usize::try_from(v).map_err(|_| format!("corrupt: {what} = {v} does not fit"))
    }
    fn f64(&mut self, what: &str) -> Decoded<f64> {
        Ok(f64::from_bits(self.u64(what)?))
    }
    fn bool(&mut self, what: &str) -> Decoded<bool> {
        match self.u8(what)? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("corrupt: {what} has flag byte {b}")),
        }
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
    fn str(&mut self, what: &str) -> Decoded<String> {
        let n = self.len(what, 1)?;
        let s = self.take(n, what)?;
        String::from_utf8(s.to_vec()).map_err(|_| format!("corrupt: {what} is not UTF-8"))
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
    /// A body's (contact_damping, contact_damping_ratio): both optional from version 3; before,
    /// an absolute damping (0 for none), kept as given so the run resumes unchanged.
    fn contact_damping(&mut self, what: &str) -> Decoded<(Option<f64>, Option<f64>)> {
        if self.version >= 3 {
            Ok((self.opt_f64(what)?, self.opt_f64(what)?))
        } else {
            Ok((Some(self.f64(what)?), None))
        }
    }
    fn opt_f64(&mut self, what: &str) -> Decoded<Option<f64>> {
        Ok(if self.bool(what)? {
            Some(self.f64(what)?)
        } else {
            None
        })
    }
    fn table(&mut self, what: &str) -> Decoded<Table> {
        Ok(Table {
            x: self.f64s(what)?,
            y: self.f64s(what)?,
        })
    }
    fn friction(&mut self, what: &str) -> Decoded<FrictionModel> {
        match self.u8(what)? {
            0 => Ok(FrictionModel::None),
            1 => Ok(FrictionModel::StickForce {
                static_coefficient: self.f64(what)?,
                kinetic_coefficient: self.f64(what)?,
            }),
            t => Err(format!("corrupt: {what} has model tag {t}")),
        }
    }
}

fn write_scene(w: &mut Writer, s: &Scene) {
    let b = &s.belt;
    w.u8(match b.formulation {
        Formulation::NodeKelvinVoigt => 0,
    });
    w.f64(b.axial_stiffness);
    w.f64(b.mass_per_length);
    w.f64(b.bending_stiffness);
    w.f64(b.damping_ratio);
    w.opt_f64(b.length);
    match b.elements {
        None => w.u8(0),
        Some(n) => {
            w.u8(1);
            w.u64(n as u64);
        }
    }
    w.f64(b.max_element_angle);
    w.bool(b.tension_only);
    w.f64(b.max_placement_strain);
    w.u64(s.pulleys.len() as u64);
    for p in &s.pulleys {
        w.str(&p.name);
        w.f64(p.center[0]);
        w.f64(p.center[1]);
        w.f64(p.radius);
        w.f64(p.mass);
        w.opt_f64(p.inertia);
        w.u8(match p.wrap {
            Wrap::CounterClockwise => 0,
            Wrap::Clockwise => 1,
        });
        w.friction(&p.friction);
        w.f64(p.contact_stiffness);
        w.opt_f64(p.contact_damping);
        w.opt_f64(p.contact_damping_ratio);
        match &p.takeup {
            None => w.u8(0),
            Some(t) => {
                w.u8(1);
                w.f64(t.direction[0]);
                w.f64(t.direction[1]);
                w.f64(t.counterweight);
                w.f64(t.travel_min);
                w.f64(t.travel_max);
            }
        }
        match &p.drive {
            None => w.u8(0),
            Some(d) => {
                w.u8(if d.start_curve.is_some() { 2 } else { 1 });
                w.table(&d.torque);
                w.table(&d.speed_factor);
                w.f64(d.viscous);
                w.f64(d.inertia);
                if let Some(c) = &d.start_curve {
                    w.u8(match c.shape {
                        StartShape::Harrison => 0,
                        StartShape::Nordell => 1,
                        StartShape::Cubic => 2,
                        StartShape::Linear => 3,
                    });
                    w.f64(c.speed);
                    w.f64(c.ramp);
                    w.f64(c.start);
                    w.f64(c.prestart);
                    w.opt_f64(c.creep_speed);
                    w.opt_f64(c.creep_ramp);
                    w.f64(d.max_torque);
                }
            }
        }
        match &p.brake {
            None => w.u8(0),
            Some(br) => {
                w.u8(1);
                w.table(&br.capacity);
            }
        }
    }
    w.u64(s.idlers.len() as u64);
    for d in &s.idlers {
        w.f64(d.center[0]);
        w.f64(d.center[1]);
        w.f64(d.radius);
        w.f64(d.inertia);
        w.f64(d.contact_stiffness);
        w.opt_f64(d.contact_damping);
        w.opt_f64(d.contact_damping_ratio);
        w.friction(&d.friction);
        w.f64(d.resistance);
        w.f64(d.rotating_mass);
    }
    w.u64(s.loads.len() as u64);
    for l in &s.loads {
        w.f64(l.mass_per_length);
        w.f64(l.start[0]);
        w.f64(l.start[1]);
        w.f64(l.end[0]);
        w.f64(l.end[1]);
    }
    w.f64(s.gravity);
    w.opt_f64(s.solver.time_step);
    w.f64(s.solver.time_step_fraction);
}

fn read_scene(r: &mut Reader<'_>) -> Decoded<Scene> {
    let formulation = match r.u8("belt.formulation")? {
        0 => Formulation::NodeKelvinVoigt,
        t => return Err(format!("corrupt: belt.formulation tag {t}")),
    };
    let belt = BeltParams {
        formulation,
        axial_stiffness: r.f64("belt.axial_stiffness")?,
        mass_per_length: r.f64("belt.mass_per_length")?,
        bending_stiffness: r.f64("belt.bending_stiffness")?,
        damping_ratio: r.f64("belt.damping_ratio")?,
        length: r.opt_f64("belt.length")?,
        elements: if r.bool("belt.elements")? {
            Some(r.usize("belt.elements")?)
        } else {
            None
        },
        max_element_angle: r.f64("belt.max_element_angle")?,
        tension_only: r.bool("belt.tension_only")?,
        // Versions before 3 had the fixed limit of 5 %.
        max_placement_strain: if r.version >= 3 {
            r.f64("belt.max_placement_strain")?
        } else {
            0.05
        },
    };
    // The smallest records (no options, empty name) take 56 and 43 bytes (version 3; 62
    // and 49 before): bounds for the length checks.
    let n_pulleys = r.len("pulleys", 56)?;
    let mut pulleys = Vec::with_capacity(n_pulleys);
    for i in 0..n_pulleys {
        let f = |k: &str| format!("pulleys[{i}].{k}");
        let name = r.str(&f("name"))?;
        let center = [r.f64(&f("center"))?, r.f64(&f("center"))?];
        let radius = r.f64(&f("radius"))?;
        let mass = r.f64(&f("mass"))?;
        let inertia = r.opt_f64(&f("inertia"))?;
        let wrap = match r.u8(&f("wrap"))? {
            0 => Wrap::CounterClockwise,
            1 => Wrap::Clockwise,
            t => return Err(format!("corrupt: {} tag {t}", f("wrap"))),
        };
        let friction = r.friction(&f("friction"))?;
        let contact_stiffness = r.f64(&f("contact_stiffness"))?;
        let (contact_damping, contact_damping_ratio) = r.contact_damping(&f("contact_damping"))?;
        let takeup = if r.bool(&f("takeup"))? {
            Some(TakeupSpec {
                direction: [r.f64(&f("takeup"))?, r.f64(&f("takeup"))?],
                counterweight: r.f64(&f("takeup"))?,
                travel_min: r.f64(&f("takeup"))?,
                travel_max: r.f64(&f("takeup"))?,
            })
        } else {
            None
        };
        let drive = match r.u8(&f("drive"))? {
            0 => None,
            tag @ (1 | 2) => {
                let mut d = DriveSpec {
                    torque: r.table(&f("drive.torque"))?,
                    speed_factor: r.table(&f("drive.speed_factor"))?,
                    viscous: r.f64(&f("drive.viscous"))?,
                    inertia: r.f64(&f("drive.inertia"))?,
                    ..DriveSpec::default()
                };
                if tag == 2 {
                    let what = f("drive.start_curve");
                    let shape = match r.u8(&what)? {
                        t @ 0..=3 => StartShape::ALL[t as usize],
                        t => return Err(format!("corrupt: {what}.shape tag {t}")),
                    };
                    d.start_curve = Some(StartCurve {
                        shape,
                        speed: r.f64(&what)?,
                        ramp: r.f64(&what)?,
                        start: r.f64(&what)?,
                        prestart: r.f64(&what)?,
                        creep_speed: r.opt_f64(&what)?,
                        creep_ramp: r.opt_f64(&what)?,
                    });
                    d.max_torque = r.f64(&f("drive.max_torque"))?;
                }
                Some(d)
            }
            t => return Err(format!("corrupt: {} tag {t}", f("drive"))),
        };
        let brake = if r.bool(&f("brake"))? {
            Some(BrakeSpec {
                capacity: r.table(&f("brake.capacity"))?,
            })
        } else {
            None
        };
        pulleys.push(PulleySpec {
            name,
            center,
            radius,
            mass,
            inertia,
            wrap,
            friction,
            contact_stiffness,
            contact_damping,
            contact_damping_ratio,
            takeup,
            drive,
            brake,
        });
    }
    let n_idlers = r.len("idlers", 43)?;
    let mut idlers = Vec::with_capacity(n_idlers);
    for i in 0..n_idlers {
        let f = format!("idlers[{i}]");
        let mut spec = IdlerSpec {
            center: [r.f64(&f)?, r.f64(&f)?],
            radius: r.f64(&f)?,
            inertia: r.f64(&f)?,
            contact_stiffness: r.f64(&f)?,
            ..IdlerSpec::default()
        };
        (spec.contact_damping, spec.contact_damping_ratio) = r.contact_damping(&f)?;
        spec.friction = r.friction(&f)?;
        if r.version >= 2 {
            spec.resistance = r.f64(&f)?;
            spec.rotating_mass = r.f64(&f)?;
        }
        idlers.push(spec);
    }
    let mut loads = Vec::new();
    if r.version >= 2 {
        let n_loads = r.len("loads", 40)?;
        for i in 0..n_loads {
            let f = format!("loads[{i}]");
            loads.push(LoadSpec {
                mass_per_length: r.f64(&f)?,
                start: [r.f64(&f)?, r.f64(&f)?],
                end: [r.f64(&f)?, r.f64(&f)?],
            });
        }
    }
    let gravity = r.f64("gravity")?;
    let solver = SolverParams {
        time_step: r.opt_f64("solver.time_step")?,
        time_step_fraction: r.f64("solver.time_step_fraction")?,
    };
    Ok(Scene {
        belt,
        pulleys,
        idlers,
        loads,
        gravity,
        solver,
    })
}

fn write_state(w: &mut Writer, s: &State) {
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
}

fn read_state(r: &mut Reader<'_>) -> Decoded<State> {
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
    let (node_mass, load_edges) = if r.version >= 2 {
        let node_mass = r.f64s("node masses")?;
        let n = r.len("load zones", 32)?;
        let edges = (0..n)
            .map(|_| {
                Ok(LoadEdges {
                    start_element: r.usize("load zone")?,
                    end_element: r.usize("load zone")?,
                    start: r.f64("load zone")?,
                    end: r.f64("load zone")?,
                })
            })
            .collect::<Decoded<Vec<_>>>()?;
        (node_mass, edges)
    } else {
        // Filled in from the model by `decode`.
        (Vec::new(), Vec::new())
    };
    Ok(State {
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
    })
}

#[cfg(test)]
mod tests {
    use super::crc32;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        // The CRC-32/ISO-HDLC check value of "123456789".
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }
}
