//! Every hider's name as a type: what the registry holds, what errors
//! carry, and what a front end parses its `--algo` or `algo=` into.

use std::fmt;
use std::str::FromStr;

use crate::error::PlanError;

/// Declares [`AlgoName`] from its variants and their registry names, in
/// registry order.
macro_rules! algo_names {
    ($($variant:ident => $name:literal),* $(,)?) => {
        /// A registered hider's name (`hider render --algo NAME`), or
        /// [`AlgoName::Auto`], the planner's choice.
        ///
        /// ```
        /// use hider_plan::AlgoName;
        /// let name: AlgoName = "zbuffer-tiled".parse()?;
        /// assert_eq!(name, AlgoName::ZbufferTiled);
        /// assert_eq!(name.to_string(), "zbuffer-tiled");
        /// assert!("nonesuch".parse::<AlgoName>().is_err());
        /// # Ok::<(), hider_plan::PlanError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum AlgoName {
            /// `auto`: the planner picks one of the others.
            Auto,
            $(
                #[doc = concat!("`", $name, "`")]
                $variant,
            )*
        }

        impl AlgoName {
            /// Every registered hider's name, in registry order (without
            /// [`AlgoName::Auto`]).
            pub const REGISTERED: &'static [AlgoName] = &[$(AlgoName::$variant),*];

            /// The name as the registry and the command line spell it.
            pub fn as_str(self) -> &'static str {
                match self {
                    AlgoName::Auto => "auto",
                    $(AlgoName::$variant => $name,)*
                }
            }
        }
    };
}

algo_names! {
    Zbuffer => "zbuffer",
    ZbufferF64 => "zbuffer-f64",
    ZbufferReversed => "zbuffer-reversed",
    ZbufferTiled => "zbuffer-tiled",
    ZbufferFixed24 => "zbuffer-fixed24",
    ZbufferFixed16 => "zbuffer-fixed16",
    PainterNaive => "painter-naive",
    ZbufferLinearZ => "zbuffer-linear-z",
    Scanline => "scanline",
    Painter => "painter",
    Warnock => "warnock",
    Warnock4x4 => "warnock-4x4",
    Abuffer => "abuffer",
    AbufferCarpenter => "abuffer-carpenter",
    Ssaa4 => "ssaa-4",
    Ssaa8 => "ssaa-8",
    Ssaa16 => "ssaa-16",
    Ssaa32 => "ssaa-32",
    SsaaSorted => "ssaa-sorted",
    Oracle => "oracle",
}

impl fmt::Display for AlgoName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for AlgoName {
    type Err = PlanError;

    /// A registered name or `auto`; anything else is
    /// [`PlanError::UnknownHider`] listing the registered names.
    fn from_str(name: &str) -> Result<Self, PlanError> {
        if name == "auto" {
            return Ok(AlgoName::Auto);
        }
        AlgoName::REGISTERED
            .iter()
            .copied()
            .find(|a| a.as_str() == name)
            .ok_or_else(|| PlanError::UnknownHider {
                name: name.to_owned(),
                known: AlgoName::REGISTERED.to_vec(),
            })
    }
}
