//! A frame's buffers that no render is asked for cost no memory
//! ([`Frame::new_for`]): the operating system maps zeroed pages only when
//! they are first written. Its own test binary, so that no other test
//! allocates while the resident size is read.

use hider_scene::{Frame, FrameBuffers, NO_ID};

/// This process's resident bytes (Linux: `/proc/self/statm`, pages).
#[cfg(target_os = "linux")]
fn resident() -> usize {
    let statm = std::fs::read_to_string("/proc/self/statm").expect("statm");
    let pages: usize = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .expect("resident pages");
    // The page size of every Linux target the project builds for.
    pages * 4096
}

#[cfg(target_os = "linux")]
#[test]
fn buffers_not_asked_for_are_not_resident() {
    const MIB: usize = 1 << 20;
    let (w, h) = (4096u32, 4096u32);
    // 64 MiB a buffer: ids and depth are written, the colour is not.
    let buffer = w as usize * h as usize * 4;
    let before = resident();
    let frame = Frame::new_for(w, h, FrameBuffers::IDS_DEPTH).unwrap();
    let grown = resident() - before;
    assert!(frame.ids.iter().all(|&id| id == NO_ID));
    assert!(frame.depth.iter().all(|&d| d == 1.0));
    assert_eq!(frame.color.len(), w as usize * h as usize);
    assert!(
        grown >= 2 * buffer - 8 * MIB && grown < 2 * buffer + 16 * MIB,
        "{} MiB resident for ids and depth of {} MiB each",
        grown / MIB,
        buffer / MIB
    );
    drop(frame);
    // The measure sees a colour buffer that is written: `Frame::new`
    // clears all three.
    let before = resident();
    let full = Frame::new(w, h).unwrap();
    let grown = resident() - before;
    assert!(
        grown >= 3 * buffer - 8 * MIB,
        "{} MiB resident for three buffers of {} MiB",
        grown / MIB,
        buffer / MIB
    );
    assert_eq!(full.buffers(), FrameBuffers::ALL);
}
