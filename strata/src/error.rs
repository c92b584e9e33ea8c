//! The crate's one error type.
//!
//! Every constructor and every analysis entry point validates its input and returns
//! [`Result<T, Error>`](Result). Each message says what was wrong *and* what is allowed, so that a
//! command-line tool can print it as is: `jittered cannot make 10 samples: the count must be a
//! perfect square (nearest allowed: 9 or 16)`.

use alloc::sync::Arc;
use core::fmt;

use crate::prelude::*;

/// Shorthand for `Result<T, strata::Error>`.
pub type Result<T, E = Error> = core::result::Result<T, E>;

/// What went wrong, with what would have been allowed.
///
/// The [`Display`](fmt::Display) form is one line, meant for end users; match on the variants to
/// react programmatically.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Error {
    /// No sampler is registered under this name.
    UnknownSampler {
        /// The name that was asked for.
        name: String,
        /// Every registered name.
        known: Vec<&'static str>,
    },
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
        /// Who refused (a sampler name, or a module such as `spectrum`).
        context: &'static str,
        /// The parameter's name, as on the command line (`radius`, `iterations`, ...).
        parameter: &'static str,
        /// The value that was given, formatted.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// Input data (a point set, a frequency grid, ...) is unusable.
    InvalidInput {
        /// Who refused.
        context: &'static str,
        /// What was wrong and what is allowed.
        message: String,
    },
    /// The request is valid in itself but cannot be met (for example a Poisson-disk radius that
    /// leaves no room for the requested number of points).
    Unreachable {
        /// Who gave up.
        context: &'static str,
        /// What could not be done, how far it got, and what would work.
        message: String,
    },
    /// Writing or reading a file failed.
    Io {
        /// The file involved.
        path: String,
        /// The operating system's or encoder's error (also given by
        /// [`source`](core::error::Error::source)).
        source: Arc<dyn core::error::Error + Send + Sync>,
    },
}

impl PartialEq for Error {
    /// Equal variants with equal fields; I/O errors compare by path and message.
    fn eq(&self, other: &Self) -> bool {
        use Error::*;
        match (self, other) {
            (UnknownSampler { name: a, known: b }, UnknownSampler { name: c, known: d }) => {
                a == c && b == d
            }
            (
                InvalidCount {
                    sampler: a,
                    count: b,
                    allowed: c,
                },
                InvalidCount {
                    sampler: d,
                    count: e,
                    allowed: f,
                },
            ) => a == d && b == e && c == f,
            (
                InvalidParameter {
                    context: a,
                    parameter: b,
                    value: c,
                    allowed: d,
                },
                InvalidParameter {
                    context: e,
                    parameter: f,
                    value: g,
                    allowed: h,
                },
            ) => a == e && b == f && c == g && d == h,
            (
                InvalidInput {
                    context: a,
                    message: b,
                },
                InvalidInput {
                    context: c,
                    message: d,
                },
            )
            | (
                Unreachable {
                    context: a,
                    message: b,
                },
                Unreachable {
                    context: c,
                    message: d,
                },
            ) => a == c && b == d,
            (Io { path: a, source: b }, Io { path: c, source: d }) => {
                a == c && b.to_string() == d.to_string()
            }
            _ => false,
        }
    }
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

    /// Shorthand for [`Error::Io`]: `path` names the file (`path.display()` of a `Path`),
    /// `source` is the underlying error (an `std::io::Error`, an encoder's error, or a message).
    pub fn io(
        path: impl Into<String>,
        source: impl Into<Box<dyn core::error::Error + Send + Sync>>,
    ) -> Self {
        Error::Io {
            path: path.into(),
            source: Arc::from(source.into()),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::UnknownSampler { name, known } => {
                write!(
                    f,
                    "unknown sampler '{name}'; known samplers: {}",
                    known.join(", ")
                )
            }
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
            Error::Unreachable { context, message } => write!(f, "{context}: {message}"),
            Error::Io { path, source } => write!(f, "{path}: {source}"),
        }
    }
}

impl core::error::Error for Error {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Error::Io { source, .. } => Some(source.as_ref()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[cfg(feature = "std")]
    fn io_errors_keep_their_source() {
        use std::error::Error as _;
        let e = Error::io(
            "out/x.png",
            std::io::Error::new(std::io::ErrorKind::PermissionDenied, "denied"),
        );
        assert_eq!(e.to_string(), "out/x.png: denied");
        let source = e.source().expect("a source");
        let io = source
            .downcast_ref::<std::io::Error>()
            .expect("an io::Error");
        assert_eq!(io.kind(), std::io::ErrorKind::PermissionDenied);
        assert_eq!(e.clone(), e);
    }

    #[test]
    fn messages_say_what_is_allowed() {
        let e = Error::count("jittered", 10, "the count must be a perfect square");
        assert_eq!(
            e.to_string(),
            "jittered cannot make 10 samples: the count must be a perfect square"
        );
    }
}
