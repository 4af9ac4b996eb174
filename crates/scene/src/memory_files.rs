//! Files held in memory in place of the file system, for a caller that has
//! none: the WebAssembly page (`crates/web`) loads a dropped or bundled
//! OBJ whose `mtllib` names an MTL it holds as bytes. Inside
//! [`with_files`], [`crate::input::read_regular`] reads a path whose file
//! name is one of the given files from memory, with the same size limit;
//! outside it nothing changes.

use std::cell::RefCell;
use std::path::Path;

use crate::error::{Error, Result};

thread_local! {
    static FILES: RefCell<Vec<(String, Vec<u8>)>> = const { RefCell::new(Vec::new()) };
}

/// Runs `f` with `files` (file name, bytes) readable by
/// [`crate::input::read_regular`] on this thread, matched by file name
/// (the folders of a path are ignored: dropped files have none).
pub fn with_files<R>(files: Vec<(String, Vec<u8>)>, f: impl FnOnce() -> R) -> R {
    let previous = FILES.with(|cell| cell.replace(files));
    let result = f();
    FILES.with(|cell| cell.replace(previous));
    result
}

/// Whether a [`with_files`] call holds the file `path` names.
pub(crate) fn holds(path: &Path) -> bool {
    name_of(path)
        .is_some_and(|name| FILES.with(|cell| cell.borrow().iter().any(|(n, _)| n == name)))
}

/// The file name of `path`, after the last `/` or `\\` (Windows
/// exporters name files with backslashes: `.\\Tex.jpg`).
fn name_of(path: &Path) -> Option<&str> {
    let name = path.file_name()?.to_str()?;
    name.rsplit('\\').next()
}

/// The bytes of `path` when a [`with_files`] call holds its file name,
/// checked against `max_bytes` like a file on disk.
pub(crate) fn read(path: &Path, what: &'static str, max_bytes: u64) -> Option<Result<Vec<u8>>> {
    let name = name_of(path)?;
    FILES.with(|cell| {
        let files = cell.borrow();
        let (_, bytes) = files.iter().find(|(n, _)| n == name)?;
        Some(if bytes.len() as u64 > max_bytes {
            Err(Error::Limit {
                what,
                value: bytes.len() as u64,
                limit: max_bytes,
            })
        } else {
            Ok(bytes.clone())
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_files_are_read_by_name_within_the_limit_and_only_inside() {
        let path = Path::new("some/folder/a.mtl");
        let files = vec![("a.mtl".to_owned(), b"newmtl x\n".to_vec())];
        with_files(files, || {
            let bytes = crate::input::read_regular(path, "MTL", 100).unwrap();
            assert_eq!(bytes, b"newmtl x\n");
            let err = crate::input::read_regular(path, "MTL", 3).unwrap_err();
            assert!(matches!(err, Error::Limit { value: 9, .. }), "{err}");
            assert!(holds(Path::new(".\\a.mtl")));
        });
        assert!(crate::input::read_regular(path, "MTL", 100).is_err());
        assert!(!holds(path));
    }
}
