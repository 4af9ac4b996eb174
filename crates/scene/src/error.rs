//! The error type of the scene crate and of every hider.

use std::path::{Path, PathBuf};

/// Everything that can go wrong loading, preparing or rendering a scene.
///
/// Each variant names what was wrong and where (file, line, item, value), so
/// the CLI can print it as one line.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// A file's contents could not be parsed.
    #[error("{}: {message}", location(path, *line))]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number (0 when the whole file is at fault; the
        /// message then names the file alone).
        line: usize,
        /// What was wrong, quoting the offending text or value.
        message: String,
    },
    /// A value in a scene built in memory is invalid (NaN coordinate,
    /// index out of range, ...).
    #[error("invalid scene: {0}")]
    InvalidScene(String),
    /// A generated scene spec (`gen:NAME[:ARGS]`) that names no generated
    /// scene, does not parse, or asks for too much; the message quotes it.
    #[error("{0}")]
    Generated(String),
    /// A camera or view that cannot be used.
    #[error("invalid camera: {0}")]
    Camera(String),
    /// A requested size or count is over a documented limit; checked before
    /// anything is allocated.
    #[error("{what} {value} is over the limit of {limit}")]
    Limit {
        /// What was too large.
        what: &'static str,
        /// The requested value.
        value: u64,
        /// The limit.
        limit: u64,
    },
    /// A memory budget ran out (a hider's `max_bytes`, or the working
    /// memory a hider needs is over its documented bound); checked before
    /// allocating. Python raises it as `MemoryError`.
    #[error("{what} {value} is over the limit of {limit}")]
    Budget {
        /// Which memory.
        what: &'static str,
        /// The bytes needed.
        value: u64,
        /// The budget.
        limit: u64,
    },
    /// A requested value is out of its valid range.
    #[error("{what} must be {expected}, got {value}")]
    OutOfRange {
        /// What the value is.
        what: &'static str,
        /// The accepted range, in words.
        expected: &'static str,
        /// The value given.
        value: String,
    },
    /// An image could not be encoded or decoded.
    #[error("{}: {message}", path.display())]
    Image {
        /// The file.
        path: PathBuf,
        /// The codec's message.
        message: String,
    },
    /// The render was stopped through its [`Cancel`](crate::Cancel)
    /// token: cancelled, or out of time. Front ends name their own
    /// timeout (`--timeout`, `timeout=`); Python raises a timeout as
    /// `TimeoutError`.
    /// (No `From` conversion: it would make `?` in closures ambiguous;
    /// hiders poll with [`Cancel::poll`](crate::Cancel::poll).)
    #[error(transparent)]
    Cancelled(crate::cancel::Cancelled),
    /// A hider could not finish (a budget it documents ran out, ...).
    #[error("{hider}: {message}")]
    Render {
        /// The hider's name.
        hider: String,
        /// What went wrong.
        message: String,
    },
}

/// `Result` with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// `file:line`, or the file alone when the whole file is at fault (line 0):
/// an editor jumping to line 0 helps nobody.
fn location(path: &Path, line: usize) -> String {
    match line {
        0 => path.display().to_string(),
        _ => format!("{}:{line}", path.display()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parse_error_names_the_line_only_when_there_is_one() {
        let at = |line| Error::Parse {
            path: "m.obj".into(),
            line,
            message: "bad".into(),
        };
        assert_eq!(at(7).to_string(), "m.obj:7: bad");
        assert_eq!(at(0).to_string(), "m.obj: bad");
    }
}
