//! Reading the files a scene names (the OBJ, its MTL files, its textures)
//! within bounds: only regular files, checked before opening (a FIFO or a
//! device named by `mtllib` or `map_Kd` would block or never end), and no
//! more than a stated number of bytes, checked before reading.

use std::io::Read;
use std::path::Path;

use crate::error::{Error, Result};

/// Largest MTL file read, in bytes: material libraries are small text
/// files; anything this large is not one.
pub const MAX_MTL_BYTES: u64 = 64 << 20;

/// Largest texture file read, in bytes (a compressed image: its decoded
/// size is bounded by [`crate::shade::MAX_TEXTURE_SIDE`] too).
pub const MAX_TEXTURE_FILE_BYTES: u64 = 512 << 20;

/// Checks that `path` names a regular file (symbolic links followed) of
/// at most `max_bytes`, without opening it; `what` names the limit in
/// errors ("MTL file size in bytes").
pub fn check_regular(path: &Path, what: &'static str, max_bytes: u64) -> Result<u64> {
    let meta = std::fs::metadata(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    if !meta.is_file() {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: 0,
            // `what` names the size limit, not the kind of file, so it
            // stays out of this message.
            message: "is not a regular file (a folder, a device or a pipe), so it is not read"
                .to_string(),
        });
    }
    if meta.len() > max_bytes {
        return Err(Error::Limit {
            what,
            value: meta.len(),
            limit: max_bytes,
        });
    }
    Ok(meta.len())
}

/// The bytes of the regular file `path`, at most `max_bytes` (checked
/// before reading, and while reading should the file grow).
pub fn read_regular(path: &Path, what: &'static str, max_bytes: u64) -> Result<Vec<u8>> {
    if let Some(held) = crate::memory_files::read(path, what, max_bytes) {
        return held;
    }
    let len = check_regular(path, what, max_bytes)?;
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(Error::Limit {
            what,
            value: bytes.len() as u64,
            limit: max_bytes,
        });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_regular_files_within_the_limit_are_read() {
        let dir = std::env::temp_dir().join(format!("hider-input-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let small = dir.join("a.mtl");
        std::fs::write(&small, "newmtl a\n").unwrap();
        assert_eq!(
            read_regular(&small, "MTL file size in bytes", 100)
                .unwrap()
                .len(),
            9
        );
        let e = read_regular(&small, "MTL file size in bytes", 4).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Limit {
                    value: 9,
                    limit: 4,
                    ..
                }
            ),
            "{e}"
        );
        let e = read_regular(&dir, "MTL file size in bytes", 100).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        // The limit's name is not a kind of file: it once read "not read
        // as MTL file size in bytes".
        assert!(!e.to_string().contains("size in bytes"), "{e}");
        // A device is refused without opening it (reading /dev/zero never
        // ends).
        let e = read_regular(Path::new("/dev/zero"), "MTL file size in bytes", 100).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
