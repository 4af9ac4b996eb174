//! The output paths of `hider render`, checked before any work: an output
//! that clobbers an input or another output, or that cannot be written
//! because its folder does not exist, is refused at once, not after a
//! render of minutes. And the buffers the outputs need: the hider is
//! asked for those alone ([`frame_buffers`]).

use std::path::{Path, PathBuf};

use anyhow::{Result, bail};
use hider::scene::FrameBuffers;

/// The buffers `hider render` asks its hider to write
/// ([`hider::scene::Frame::set_buffers`]): the ids always (the colour pass
/// colours the PNG from them, the cut-out stage tests them, the closing
/// line counts the covered pixels, and `--ids-out` writes them), the depth
/// only for `--depth-out`, and the colour only from a hider that resolves
/// colour itself (otherwise the PNG's colours are the colour pass's,
/// which writes every pixel). A hider that ignores the request writes
/// everything, which changes no output.
pub fn frame_buffers(depth_out: bool, resolves_color: bool) -> FrameBuffers {
    FrameBuffers {
        ids: true,
        depth: depth_out,
        color: resolves_color,
    }
}

/// What a path names, for comparing two paths: the file it resolves to
/// when it exists (with its device and inode on Unix, so that a hard link
/// is the file it links), else its folder resolved and its name. `None`
/// for a device or a pipe, which several outputs may share (`/dev/null`).
#[derive(Debug)]
struct Identity {
    path: PathBuf,
    inode: Option<(u64, u64)>,
}

impl PartialEq for Identity {
    fn eq(&self, other: &Self) -> bool {
        self.path == other.path || (self.inode.is_some() && self.inode == other.inode)
    }
}

fn identity(path: &Path) -> Option<Identity> {
    if let Ok(meta) = std::fs::metadata(path) {
        if !meta.is_file() {
            return None;
        }
        #[cfg(unix)]
        let inode = {
            use std::os::unix::fs::MetadataExt;
            Some((meta.dev(), meta.ino()))
        };
        #[cfg(not(unix))]
        let inode = None;
        return Some(Identity {
            path: std::fs::canonicalize(path).ok()?,
            inode,
        });
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let folder = std::fs::canonicalize(parent).ok()?;
    Some(Identity {
        path: folder.join(path.file_name()?),
        inode: None,
    })
}

/// Checks `outputs` (flag, path) against each other and against `inputs`:
/// each output's folder exists and is a folder, no output is a folder, no
/// two outputs are one file, and no output is an input.
pub fn check(outputs: &[(&str, &Path)], inputs: &[PathBuf]) -> Result<()> {
    let mut seen: Vec<(&str, Identity)> = Vec::new();
    for &(flag, path) in outputs {
        if path.is_dir() {
            bail!("{flag} {}: is a folder, not a file", path.display());
        }
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if !parent.is_dir() {
            bail!(
                "{flag} {}: the folder {} does not exist",
                path.display(),
                parent.display()
            );
        }
        let Some(id) = identity(path) else {
            continue;
        };
        if let Some((other, _)) = seen.iter().find(|(_, p)| *p == id) {
            bail!(
                "{flag} {}: the same file as {other}; each output needs its own file",
                path.display()
            );
        }
        if inputs
            .iter()
            .any(|input| identity(input).as_ref() == Some(&id))
        {
            bail!(
                "{flag} {}: is an input of the render; choose another output file",
                path.display()
            );
        }
        seen.push((flag, id));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--ids-out` alone (the PNG coloured by the colour pass) asks a
    /// pixel-centre hider for the ids only; the depth comes with
    /// `--depth-out`, the colour from a hider that resolves it.
    #[test]
    fn the_hider_is_asked_for_what_the_outputs_need() {
        assert_eq!(frame_buffers(false, false), FrameBuffers::IDS);
        assert_eq!(frame_buffers(true, false), FrameBuffers::IDS_DEPTH);
        let colour = frame_buffers(false, true);
        assert!(colour.ids && colour.color && !colour.depth);
        assert_eq!(frame_buffers(true, true), FrameBuffers::ALL);
    }

    #[test]
    fn clobbering_and_missing_folders_are_refused() {
        let dir = std::env::temp_dir().join(format!("hider-outputs-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let model = dir.join("m.obj");
        std::fs::write(&model, "v 0 0 0\n").unwrap();
        let (a, b) = (dir.join("a.png"), dir.join("b.i32"));
        assert!(
            check(
                &[("-o", &a), ("--ids-out", &b)],
                std::slice::from_ref(&model)
            )
            .is_ok()
        );
        let same = check(&[("-o", &a), ("--ids-out", &a)], &[]).unwrap_err();
        assert!(same.to_string().contains("the same file as -o"), "{same}");
        // The same file spelled another way.
        let other = dir.join(".").join("a.png");
        assert!(check(&[("-o", &a), ("--depth-out", &other)], &[]).is_err());
        let input = check(&[("-o", &model)], std::slice::from_ref(&model)).unwrap_err();
        assert!(input.to_string().contains("is an input"), "{input}");
        let missing = dir.join("nodir").join("a.i32");
        let e = check(&[("--ids-out", &missing)], &[]).unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        assert!(check(&[("-o", &dir)], &[]).is_err());
        // Devices may be shared.
        let null = Path::new("/dev/null");
        assert!(check(&[("-o", null), ("--ids-out", null)], &[]).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
