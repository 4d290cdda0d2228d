//! The checkpoint file: atomic writes (a temporary file, flushed, then renamed) and safe
//! reads (regular files only, the header checked before the payload is read, Ctrl-C polled).

use super::{check_header, HEADER_BYTES};
use crate::error::{BeltError, BeltResult};
use std::io::Write;
use std::path::Path;

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

/// The bytes of the checkpoint file at `path`, read safely: anything but a regular file is
/// refused before it is opened (a FIFO would block, `/dev/zero` never ends), the header
/// is read and checked (magic, version, and the declared length against the file's size)
/// before anything else, and the rest is read in chunks that poll [`crate::interrupt`].
pub(super) fn read_file(path: &Path) -> Result<Vec<u8>, String> {
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
