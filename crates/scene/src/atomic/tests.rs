use super::*;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-atomic-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    write_atomic(path, |w| {
        w.write_all(text.as_bytes()).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

fn temp_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect()
}

#[test]
fn failed_write_leaves_no_file_and_keeps_old_content() {
    let dir = temp_dir("fail");
    let path = dir.join("out.bin");
    write_text(&path, "first").unwrap();
    let err = write_atomic(&path, |w| {
        w.write_all(b"partial").unwrap();
        Err(Error::InvalidScene("stop half way".into()))
    });
    assert!(err.is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"first");
    assert!(temp_files(&dir).is_empty());
    let fresh = dir.join("never.bin");
    let _ = write_atomic(&fresh, |_| Err(Error::InvalidScene("no".into())));
    assert!(!fresh.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_stays_a_link_and_its_target_is_written() {
    let dir = temp_dir("link");
    let real = dir.join("real.txt");
    std::fs::write(&real, "old").unwrap();
    let link = dir.join("link.txt");
    std::os::unix::fs::symlink("real.txt", &link).unwrap();
    write_text(&link, "new").unwrap();
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
    // A dangling link is written through: its target appears.
    let dangling = dir.join("dangling.txt");
    std::os::unix::fs::symlink("made.txt", &dangling).unwrap();
    write_text(&dangling, "made").unwrap();
    assert!(
        std::fs::symlink_metadata(&dangling)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("made.txt")).unwrap(),
        "made"
    );
    assert!(temp_files(&dir).is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn a_fifo_is_written_through_and_stays_a_fifo() {
    use std::os::unix::fs::FileTypeExt;
    let dir = temp_dir("fifo");
    let fifo = dir.join("pipe");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("mkfifo unavailable: skipped");
        return;
    }
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    write_text(&fifo, "through the pipe").unwrap();
    assert_eq!(reader.join().unwrap(), b"through the pipe");
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    assert!(temp_files(&dir).is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn devices_are_written_through_and_their_errors_reported() {
    use std::os::unix::fs::FileTypeExt;
    let is_device =
        |p: &str| std::fs::symlink_metadata(p).is_ok_and(|m| m.file_type().is_char_device());
    if !is_device("/dev/null") || !is_device("/dev/full") {
        eprintln!("no /dev/null or /dev/full: skipped");
        return;
    }
    write_text(Path::new("/dev/null"), "gone").unwrap();
    assert!(is_device("/dev/null"));
    let e = write_text(Path::new("/dev/full"), "no room").unwrap_err();
    assert!(e.to_string().contains("No space left on device"), "{e}");
    assert!(e.to_string().starts_with("/dev/full: "), "{e}");
    assert!(is_device("/dev/full"));
}
