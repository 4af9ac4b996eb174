//! Usage errors of the command-line tools in one line.
//!
//! clap's own messages for a bad value span several lines (the error, a
//! tip, the usage, a pointer to `--help`); the project's tools print one
//! line naming the flag and the value, and exit with status 2.
//! [`usage_error_line`] folds any clap error into that line.
//!
//! ```
//! use clap::Parser;
//! #[derive(Parser)]
//! struct Cli {
//!     #[arg(long)]
//!     size: u32,
//! }
//! let e = Cli::try_parse_from(["tool", "--size", "big"]).err().unwrap();
//! let line = hider_cli::cli_error::usage_error_line(&e);
//! assert!(line.starts_with("--size 'big': "), "{line}");
//! assert!(!line.contains('\n'));
//! ```

use clap::error::{ContextKind, ContextValue, ErrorKind};

/// The flag of a clap argument description (`--size <SIZE>` -> `--size`).
fn flag(context: Option<&ContextValue>) -> Option<String> {
    match context? {
        ContextValue::String(s) => s.split_whitespace().next().map(str::to_owned),
        ContextValue::Strings(v) => Some(
            v.iter()
                .filter_map(|s| s.split_whitespace().next())
                .collect::<Vec<_>>()
                .join(", "),
        ),
        _ => None,
    }
}

/// A clap usage error as the one line a tool prints after `tool: error: `: the flag, the value and why for a bad value; clap's first
/// paragraph with its tips joined for anything else.
pub fn usage_error_line(e: &clap::Error) -> String {
    let arg = flag(e.get(ContextKind::InvalidArg));
    let value = match e.get(ContextKind::InvalidValue) {
        Some(ContextValue::String(v)) => Some(v.clone()),
        _ => None,
    };
    match (e.kind(), arg, value) {
        (ErrorKind::ValueValidation, Some(arg), Some(value)) => {
            let why = std::error::Error::source(e)
                .map(|s| s.to_string())
                .unwrap_or_else(|| "is not valid".to_owned());
            format!("{arg} '{value}': {why}")
        }
        (ErrorKind::InvalidValue, Some(arg), Some(value)) => {
            let valid = match e.get(ContextKind::ValidValue) {
                Some(ContextValue::Strings(v)) if !v.is_empty() => Some(v.join(", ")),
                _ => None,
            };
            match (value.is_empty(), valid) {
                (true, None) => format!("{arg} needs a value"),
                (true, Some(valid)) => format!("{arg} needs a value: one of {valid}"),
                (false, Some(valid)) => format!("{arg} '{value}': must be one of {valid}"),
                (false, None) => format!("{arg} '{value}' is not valid"),
            }
        }
        (ErrorKind::ArgumentConflict, Some(arg), _) => match flag(e.get(ContextKind::PriorArg)) {
            Some(prior) if prior == arg => format!("{arg} is given more than once"),
            Some(prior) => format!("{arg} cannot be used with {prior}"),
            None => collapse(&e.render().to_string()),
        },
        (ErrorKind::MissingRequiredArgument, Some(arg), _) => {
            format!("missing {arg} (see --help)")
        }
        _ => collapse(&e.render().to_string()),
    }
}

/// clap's rendered message in one line: the error without its `error: `
/// prefix, then its tips, joined by "; "; usage and help pointers left
/// out.
fn collapse(rendered: &str) -> String {
    let mut parts: Vec<&str> = Vec::new();
    for line in rendered.lines().map(str::trim) {
        if line.starts_with("Usage:") || line.starts_with("For more information") {
            break;
        }
        if !line.is_empty() {
            parts.push(line.strip_prefix("error: ").unwrap_or(line));
        }
    }
    parts.join("; ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clap_paragraphs_fold_into_one_line() {
        let text = "error: unexpected argument '--nope' found\n\n  tip: to pass '--nope' as a \
                    value, use '-- --nope'\n\nUsage: hider render [OPTIONS]\n\nFor more \
                    information, try '--help'.\n";
        assert_eq!(
            collapse(text),
            "unexpected argument '--nope' found; tip: to pass '--nope' as a value, use '-- --nope'"
        );
    }
}
