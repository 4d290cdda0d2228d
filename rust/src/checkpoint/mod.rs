//! Checkpoints: the whole simulation state and the scene it belongs to, in one file, so a
//! run can stop and resume bit-for-bit.
//!
//! # Format (version 5; versions before 4 are refused, naming their version)
//!
//! All integers are little-endian; every `f64` of the state is stored as its raw IEEE-754
//! bits (`f64::to_bits`), so reloading is exact, including −0, ±∞ and NaN payloads.
//!
//! | bytes | content |
//! |---|---|
//! | 0..8 | magic `BELTRSCK` |
//! | 8..12 | format version, `u32` (5) |
//! | 12..16 | reserved, `u32` (0) |
//! | 16..24 | payload length L, `u64` |
//! | 24..24+L | payload |
//! | 24+L..28+L | CRC-32 (IEEE 802.3) of bytes 0..24+L, `u32` |
//!
//! The payload holds, in order: the engine version that wrote it (a string); from version
//! 5, the belt formulation and the integrator the state belongs to (their scene names, e.g.
//! `rigid_body`, `rkf45`: checked against the compiled scene on load); the scene
//! (every field of [`Scene`], so parameters changed during a run, e.g. a counterweight or a
//! drive, are kept), as a byte string holding the serde form of the one scene schema
//! ([`crate::scene`], the same keys as a scene file) in CBOR, whose floats keep every bit;
//! the node count and the time step the model was compiled to (checked
//! on load: the scene must compile to the same model); and the [`State`]: time, step,
//! node positions and half-step velocities, pulley speeds and angles, takeup travel and
//! speed, idler speeds, the contact window of each pulley, the element each idler tracks,
//! the drive work, the node masses (belt and material) and each load's zone edges (start
//! element, end element, start and end material coordinates), the memory of each
//! pulley's drive (PI error integral, lagged torque, speed of a fluid-coupled motor; added
//! within version 4, so a version 4 file that ends before it reads as zero memory), the
//! speed at which each pulley's deceleration brake began its ramp (added within version 4
//! after the drive memory; a version 4 file that ends before it reads as no ramp begun);
//! from version 5, the rigid belt bodies' angles and angular speeds (empty arrays for the
//! node belt), the adaptive integrator's next step and its accepted and rejected step
//! counts; and last the friction memory (the creep displacement of every belt point on
//! every pulley, empty without creep friction; a file that ends before it, such as any
//! version 4 file, reads with an empty one). Strings, byte strings and arrays are a `u64`
//! length followed by the items.
//!
//! Version 5 added the formulation and integrator tags and the state of the rigid-body
//! belt and of the adaptive integrator; version 4 files (node belt, central differences)
//! are still read.
//!
//! Version 4 replaced the hand-written scene encodings of versions 1 to 3 (version 3 had
//! added the contact damping options and the belt's placement limit to them) by the scene
//! schema's serde form, so that a new scene field needs no change here. Versions 1 to 3 are
//! refused with their version number (re-run from the scene file).
//!
//! Nothing else influences the next step: the stepper's scratch buffers are rebuilt on
//! every force evaluation. The recording is not part of a checkpoint.
//!
//! Writes are atomic ([`write_atomic`]): the bytes go to a temporary file in the same
//! directory, which is flushed to disk (`fsync`) and then renamed over the target, so a
//! crash leaves either the old checkpoint or the new one, never a partial file.

//!
//! Files: this one holds the format (header, checksum, encode/decode, the checks on load);
//! `codec.rs` the byte-level writer and reader of the payload (scene and state); `file.rs`
//! the file side (atomic writes, safe reads).

mod codec;
mod file;

use crate::error::{BeltError, BeltResult};
use crate::model::Model;
use crate::scene::Scene;
use crate::simulation::Simulation;
use crate::state::State;
use codec::{read_scene, read_state, write_scene, write_state, Reader, Writer};
use file::read_file;
pub use file::write_atomic;
use std::path::Path;

/// First eight bytes of every checkpoint file.
pub const MAGIC: [u8; 8] = *b"BELTRSCK";
/// Version of the format written by this build.
pub const FORMAT_VERSION: u32 = 5;
/// Oldest version this build reads. Version 4 stores the scene in its serde form; the
/// hand-written scene encoding of versions 1 to 3 is no longer read (such a file is refused
/// with its version: re-run from the scene file).
pub const OLDEST_READ_VERSION: u32 = 4;
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
    w.str(sim.model.formulation.name());
    w.str(sim.model.integrator.name());
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
            "format version {version}; this build of beltrs reads versions {OLDEST_READ_VERSION} to {FORMAT_VERSION} (a file of an older version was written by an older beltrs: re-run from the scene file)"
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
    let tags = if version >= 5 {
        Some((r.str("formulation")?, r.str("integrator")?))
    } else {
        None
    };
    let scene = read_scene(&mut r)?;
    let nodes = r.u64("node count")?;
    let dt = r.f64("time step")?;
    let state = read_state(&mut r)?;
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
    if let Some((formulation, integrator)) = tags {
        let compiled = (model.formulation.name(), model.integrator.name());
        if (formulation.as_str(), integrator.as_str()) != compiled {
            return Err(format!(
                "corrupt: tagged as a {formulation} belt integrated by {integrator}, but its scene compiles to a {} belt integrated by {}",
                compiled.0, compiled.1
            ));
        }
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
        ("drive memories", s.drive_memory.len(), p),
        ("brake ramps", s.brake_ramp.len(), p),
        (
            "belt body angles",
            s.body_angle.len(),
            m.initial_angles.len(),
        ),
        (
            "belt body speeds",
            s.body_spin.len(),
            m.initial_angles.len(),
        ),
        (
            "friction memory values",
            s.creep.len(),
            m.creep_memory_len(),
        ),
        ("arm forces", s.arm_force.len(), m.arm_len()),
        ("arm lengths", s.arm_length.len(), m.arm_len()),
        ("sliding lists", s.sliding.len(), p),
    ];
    for (what, have, want) in sizes {
        if have != want {
            return Err(format!("corrupt: {have} {what} for a model with {want}"));
        }
    }
    if let Some(&i) = s.sliding.iter().flatten().find(|&&i| i >= n) {
        return Err(format!(
            "corrupt: sliding point {i} beyond the {n} belt points"
        ));
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

#[cfg(test)]
mod tests {
    use super::crc32;

    #[test]
    fn crc32_matches_the_standard_check_value() {
        // The CRC-32/ISO-HDLC check value of "123456789".
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }
}
