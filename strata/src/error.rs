//! The crate's one error type.
//!
//! Every constructor validates its input and returns [`Result<T, Error>`](Result). Each message
//! says what was wrong *and* what is allowed, so that a command-line tool can print it as is: `jittered cannot make 10 samples: the count must be a
//! perfect square (nearest allowed: 9 or 16)`.

use core::fmt;

use crate::prelude::*;

/// Shorthand for `Result<T, strata::Error>`.
pub type Result<T, E = Error> = core::result::Result<T, E>;

/// What went wrong, with what would have been allowed.
///
/// The [`Display`](fmt::Display) form is one line, meant for end users; match on the variants to
/// react programmatically.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// The sampler cannot produce this many samples (zero, not a square, too large, ...).
    InvalidCount {
        /// The sampler (or tool) that refused.
        sampler: &'static str,
        /// The count that was asked for.
        count: u64,
        /// What counts are allowed, with the nearest allowed ones where that helps.
        allowed: String,
    },
    /// A parameter is outside its allowed range or is not taken by this sampler.
    InvalidParameter {
        /// Who refused (a sampler's name, or a function such as `SeedPermutation::new`).
        context: &'static str,
        /// The parameter's name (`side`, `tile`, `dims`, ...).
        parameter: &'static str,
        /// The value that was given, formatted.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// Input data (a renderer's estimates, a table, ...) is unusable.
    InvalidInput {
        /// Who refused.
        context: &'static str,
        /// What was wrong and what is allowed.
        message: String,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidCount`].
    pub fn count(sampler: &'static str, count: u64, allowed: impl Into<String>) -> Self {
        Error::InvalidCount {
            sampler,
            count,
            allowed: allowed.into(),
        }
    }

    /// Shorthand for [`Error::InvalidParameter`].
    pub fn parameter(
        context: &'static str,
        parameter: &'static str,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::InvalidParameter {
            context,
            parameter,
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// Shorthand for [`Error::InvalidInput`].
    pub fn input(context: &'static str, message: impl Into<String>) -> Self {
        Error::InvalidInput {
            context,
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidCount {
                sampler,
                count,
                allowed,
            } => write!(f, "{sampler} cannot make {count} samples: {allowed}"),
            Error::InvalidParameter {
                context,
                parameter,
                value,
                allowed,
            } => write!(
                f,
                "{context}: {parameter} = {value} is not allowed: {allowed}"
            ),
            Error::InvalidInput { context, message } => write!(f, "{context}: {message}"),
        }
    }
}

impl core::error::Error for Error {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_say_what_is_allowed() {
        let e = Error::count("jittered", 10, "the count must be a perfect square");
        assert_eq!(
            e.to_string(),
            "jittered cannot make 10 samples: the count must be a perfect square"
        );
    }
}
