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
//! regular file) and the link itself stays a link. A regular file replaced
//! keeps its permissions. Every write error, including one that only shows
//! when the data is flushed, is returned. [`OutputSet`] writes several
//! outputs all or none.

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

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
/// was flushed and synced; a file replaced keeps its permissions. On any
/// error the temporary file is removed and `path` is left as it was.
/// Errors name `path` as the caller gave it.
pub fn write_atomic<F>(path: &Path, write: F) -> Result<()>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<()>,
{
    let mut set = OutputSet::new();
    set.stage(path, write)?;
    set.commit()
}

/// One output staged in an [`OutputSet`].
#[derive(Debug)]
struct Staged {
    /// The path as the caller gave it (for messages).
    path: PathBuf,
    /// The temporary file holding the data.
    tmp: PathBuf,
    /// Where the data goes.
    target: Target,
}

/// Several outputs written all or none: each is staged to a temporary file
/// as it is produced ([`Self::stage`]: beside its target for a regular
/// file, in the temporary folder for a device or a pipe), and only
/// [`Self::commit`], after every one was staged, moves them into place.
/// An error while staging (a full disk, an encoder's failure) leaves every
/// target as it was; a set dropped without commit removes its temporary
/// files. A regular file replaced keeps its permissions.
///
/// ```
/// use std::io::Write;
/// use hider_scene::atomic::OutputSet;
/// let dir = std::env::temp_dir().join(format!("hider-set-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let (a, b) = (dir.join("a.txt"), dir.join("b.txt"));
/// let mut set = OutputSet::new();
/// set.stage(&a, |w| w.write_all(b"one").map_err(|e| hider_scene::Error::Io { path: a.clone(), source: e }))?;
/// assert!(!a.exists(), "nothing is in place before the commit");
/// set.stage(&b, |w| w.write_all(b"two").map_err(|e| hider_scene::Error::Io { path: b.clone(), source: e }))?;
/// set.commit()?;
/// assert_eq!(std::fs::read(&a)?, b"one");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Default)]
pub struct OutputSet {
    staged: Vec<Staged>,
}

impl OutputSet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes the data of `path` with `write` into a temporary file, to be
    /// moved into place by [`Self::commit`].
    pub fn stage<F>(&mut self, path: &Path, write: F) -> Result<()>
    where
        F: FnOnce(&mut BufWriter<File>) -> Result<()>,
    {
        let io_err = |source| Error::Io {
            path: path.to_path_buf(),
            source,
        };
        let target = target(path);
        let tmp = match &target {
            Target::Rename(p) => temp_path(p),
            Target::Through(_) => temp_path(&std::env::temp_dir().join("hider-output")),
        };
        let file = File::create(&tmp).map_err(io_err)?;
        // Registered first, so that a failure below removes the file.
        self.staged.push(Staged {
            path: path.to_path_buf(),
            tmp: tmp.clone(),
            target,
        });
        let mut writer = BufWriter::new(file);
        write(&mut writer)?;
        writer.flush().map_err(io_err)?;
        writer.get_ref().sync_all().map_err(io_err)
    }

    /// Moves every staged output into place: regular files by rename
    /// (keeping a replaced file's permissions), then devices and pipes by
    /// copying into them.
    pub fn commit(mut self) -> Result<()> {
        let staged = std::mem::take(&mut self.staged);
        let mut result = Ok(());
        for s in &staged {
            if let Target::Rename(target) = &s.target {
                if let Ok(meta) = std::fs::metadata(target) {
                    let _ = std::fs::set_permissions(&s.tmp, meta.permissions());
                }
                if let Err(source) = std::fs::rename(&s.tmp, target) {
                    result = Err(Error::Io {
                        path: s.path.clone(),
                        source,
                    });
                    break;
                }
            }
        }
        if result.is_ok() {
            for s in &staged {
                if let Target::Through(target) = &s.target
                    && let Err(source) = copy_through(&s.tmp, target)
                {
                    result = Err(Error::Io {
                        path: s.path.clone(),
                        source,
                    });
                    break;
                }
            }
        }
        for s in &staged {
            let _ = std::fs::remove_file(&s.tmp);
        }
        result
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        for s in &self.staged {
            let _ = std::fs::remove_file(&s.tmp);
        }
    }
}

/// Writes the data of `tmp` into `target` (a device, a pipe or a dangling
/// link), reporting errors that only show when the data is flushed.
fn copy_through(tmp: &Path, target: &Path) -> std::io::Result<()> {
    let mut from = File::open(tmp)?;
    let to = OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .open(target)?;
    let mut writer = BufWriter::new(to);
    std::io::copy(&mut from, &mut writer)?;
    // No sync: devices and pipes do not support it.
    writer.flush()
}

/// A temporary name beside `path`, unique to this process and to this
/// call (sets written from several threads at once never share one).
fn temp_path(path: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let k = NEXT.fetch_add(1, Ordering::Relaxed);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    path.with_file_name(format!(".{name}.{}.{k}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests;
