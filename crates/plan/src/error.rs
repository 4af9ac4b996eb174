//! The error type of the plan crate: a hider that is not registered, a
//! knob that does not apply to the chosen hider, a model that cannot be
//! loaded, and the scene crate's errors.

use std::num::ParseIntError;

/// Everything that can go wrong choosing, building or feeding a hider.
///
/// The messages name the command-line flag (`--algo`, `--depth-format`,
/// `--svg`...) or the model at fault, so the `hider` tool prints them as
/// they are.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// No registered hider has this name.
    #[error("unknown --algo '{name}' (one of: {known})")]
    UnknownHider {
        /// The name asked for.
        name: String,
        /// Every registered name, comma separated.
        known: String,
    },
    /// A [`HiderConfig`](crate::HiderConfig) knob was set for a hider that
    /// does not have it.
    #[error("{message}")]
    KnobNotApplicable {
        /// The hider asked for.
        hider: &'static str,
        /// The knob, as its command-line flag (`--depth-source`).
        knob: &'static str,
        /// The whole sentence: which hiders the knob applies to.
        message: String,
    },
    /// An OBJ model could not be loaded.
    #[error("cannot load model {model}")]
    Load {
        /// The path given.
        model: String,
        /// Why.
        #[source]
        source: hider_scene::Error,
    },
    /// A number in a `gen:` spec does not parse.
    #[error("gen:{spec}: bad {what} '{value}'")]
    GeneratedNumber {
        /// The spec after `gen:`.
        spec: String,
        /// What the number is (`segment count`, `seed`...).
        what: &'static str,
        /// The text given.
        value: String,
        /// Why it does not parse.
        #[source]
        source: ParseIntError,
    },
    /// A `gen:` spec names no generated scene or asks for too much.
    #[error("{0}")]
    Generated(String),
    /// The scene crate's error (preparing, analysing, rendering).
    #[error(transparent)]
    Scene(#[from] hider_scene::Error),
}

/// `Result` with [`PlanError`].
pub type Result<T, E = PlanError> = std::result::Result<T, E>;

/// An error and its chain of causes as the one line the `hider` and
/// `hider-bench` tools print: the messages joined by `": "`, leaving out a
/// cause whose message its parent already ends with (errors that print
/// their source themselves).
///
/// ```
/// use std::error::Error;
/// use std::fmt;
///
/// #[derive(Debug)]
/// struct Write(std::io::Error);
/// impl fmt::Display for Write {
///     fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
///         f.write_str("cannot write out.png")
///     }
/// }
/// impl Error for Write {
///     fn source(&self) -> Option<&(dyn Error + 'static)> {
///         Some(&self.0)
///     }
/// }
///
/// let e = Write(std::io::Error::other("disk full"));
/// assert_eq!(hider_plan::error_line(&e), "cannot write out.png: disk full");
/// ```
pub fn error_line(error: &(dyn std::error::Error + 'static)) -> String {
    let mut chain: Vec<String> = Vec::new();
    let mut cause = Some(error);
    while let Some(e) = cause {
        let message = e.to_string();
        if !chain.last().is_some_and(|prev| prev.ends_with(&message)) {
            chain.push(message);
        }
        cause = e.source();
    }
    chain.join(": ")
}
