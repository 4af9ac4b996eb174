//! File output that never leaves a partial file under the final name and
//! never replaces what is not a file.
//!
//! A regular file (or a path that does not exist yet) is written
//! atomically: to a temporary file beside the target, then renamed, so an
//! interrupted or failed run leaves the old content. Anything else the path
//! names (a character device such as `/dev/null` or `/dev/full`, a FIFO, a
//! socket) is written through, as a shell redirection would: renaming over
//! it would replace the device or pipe with a regular file. A symbolic link
//! is followed: its target is written (atomically when the target is a
//! regular file) and the link itself stays a link. Every write error,
//! including one that only shows when the data is flushed, is returned.

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// How [`write_atomic`] writes to a path.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Target {
    /// A temporary file beside this path, renamed over it.
    Rename(PathBuf),
    /// Open this path and write into it (devices, FIFOs, dangling links).
    Through(PathBuf),
}

/// Decides how to write `path`: by rename when it is absent or a regular
/// file (after following symbolic links), through it otherwise.
fn target(path: &Path) -> Target {
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return Target::Rename(path.to_path_buf());
    };
    if meta.file_type().is_symlink() {
        // Resolve the whole chain; a dangling link is written through, which
        // creates its target where the link points.
        return match std::fs::canonicalize(path) {
            Ok(resolved) => target(&resolved),
            Err(_) => Target::Through(path.to_path_buf()),
        };
    }
    if meta.is_file() {
        Target::Rename(path.to_path_buf())
    } else {
        Target::Through(path.to_path_buf())
    }
}

/// Writes a file without ever leaving a partial one under its name (see
/// the module docs for what is written through instead).
///
/// `write` fills a buffered writer; for a regular file it is a temporary
/// file in the same folder as `path` (so the rename cannot cross file
/// systems), renamed to `path` only after `write` succeeded and the data
/// was flushed and synced. On any error the temporary file is removed and
/// `path` is left as it was. Errors name `path` as the caller gave it.
pub fn write_atomic<F>(path: &Path, write: F) -> Result<()>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<()>,
{
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let target = match target(path) {
        Target::Through(p) => {
            let file = OpenOptions::new()
                .write(true)
                .create(true)
                .truncate(true)
                .open(&p)
                .map_err(io_err)?;
            let mut writer = BufWriter::new(file);
            // No sync: devices and pipes do not support it, and nothing is
            // renamed afterwards that would rely on it.
            return write(&mut writer).and_then(|()| writer.flush().map_err(io_err));
        }
        Target::Rename(p) => p,
    };
    let tmp = temp_path(&target);
    let file = File::create(&tmp).map_err(io_err)?;
    let mut writer = BufWriter::new(file);
    let result = write(&mut writer).and_then(|()| {
        writer.flush().map_err(io_err)?;
        writer.get_ref().sync_all().map_err(io_err)
    });
    drop(writer);
    match result.and_then(|()| std::fs::rename(&tmp, &target).map_err(io_err)) {
        Ok(()) => Ok(()),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests;
