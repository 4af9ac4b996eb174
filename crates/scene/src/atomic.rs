//! Atomic file output: write to a temporary file beside the target, then
//! rename, so an interrupted or failed run never leaves a partial file
//! under the final name.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// Writes a file atomically: `write` fills a buffered temporary file in the
/// same folder as `path` (so the rename cannot cross file systems), which is
/// renamed to `path` only after `write` succeeded and the data was flushed.
/// On any error the temporary file is removed and `path` is left as it was.
pub fn write_atomic<F>(path: &Path, write: F) -> Result<()>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<()>,
{
    let tmp = temp_path(path);
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = File::create(&tmp).map_err(io_err)?;
    let mut writer = BufWriter::new(file);
    let result = write(&mut writer).and_then(|()| {
        writer.flush().map_err(io_err)?;
        writer.get_ref().sync_all().map_err(io_err)
    });
    drop(writer);
    match result.and_then(|()| std::fs::rename(&tmp, path).map_err(io_err)) {
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
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_no_file_and_keeps_old_content() {
        let dir = std::env::temp_dir().join(format!("hider-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("out.bin");
        write_atomic(&path, |w| {
            w.write_all(b"first").map_err(|source| Error::Io {
                path: path.clone(),
                source,
            })
        })
        .unwrap();
        let err = write_atomic(&path, |w| {
            w.write_all(b"partial").unwrap();
            Err(Error::InvalidScene("stop half way".into()))
        });
        assert!(err.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        let leftovers: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
        let fresh = dir.join("never.bin");
        let _ = write_atomic(&fresh, |_| Err(Error::InvalidScene("no".into())));
        assert!(!fresh.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
