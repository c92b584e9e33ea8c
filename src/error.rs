//! The lab's one error type: the renderer crate's refusals ([`strata::Error`]: a count, a
//! parameter or an input not allowed) and the lab's own (a sampler not in the registry, a goal
//! an optimiser cannot reach, a file that cannot be read or written).
//!
//! Each message says what was wrong *and* what is allowed, so that a program prints it as is:
//! `jittered cannot make 10 samples: the count must be a perfect square (nearest allowed: 9 or
//! 16)`.

use std::fmt;
use std::sync::Arc;

/// Shorthand for `Result<T, strata_lab::Error>`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong, with what would have been allowed.
///
/// The [`Display`](fmt::Display) form is one line, meant for end users; match on the variants to
/// react programmatically.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Error {
    /// A refusal of the renderer's crate, or one of its kind in the lab (an invalid count,
    /// parameter or input; made by [`Error::count`], [`Error::parameter`], [`Error::input`]).
    Strata(strata::Error),
    /// No sampler is registered under this name.
    UnknownSampler {
        /// The name that was asked for.
        name: String,
        /// Every registered name.
        known: Vec<&'static str>,
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
        /// [`source`](std::error::Error::source)).
        source: Arc<dyn std::error::Error + Send + Sync>,
    },
}

impl PartialEq for Error {
    /// Equal variants with equal fields; I/O errors compare by path and message.
    fn eq(&self, other: &Self) -> bool {
        use Error::*;
        match (self, other) {
            (Strata(a), Strata(b)) => a == b,
            (UnknownSampler { name: a, known: b }, UnknownSampler { name: c, known: d }) => {
                a == c && b == d
            }
            (
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

impl From<strata::Error> for Error {
    fn from(e: strata::Error) -> Self {
        Error::Strata(e)
    }
}

impl Error {
    /// Shorthand for [`strata::Error::InvalidCount`].
    pub fn count(sampler: &'static str, count: u64, allowed: impl Into<String>) -> Self {
        strata::Error::count(sampler, count, allowed).into()
    }

    /// Shorthand for [`strata::Error::InvalidParameter`]; `parameter` is named as on the
    /// command line (`radius`, `iterations`, ...).
    pub fn parameter(
        context: &'static str,
        parameter: &'static str,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        strata::Error::parameter(context, parameter, value, allowed).into()
    }

    /// Shorthand for [`strata::Error::InvalidInput`] (a point set, a frequency grid, a file's
    /// contents, ... that is unusable).
    pub fn input(context: &'static str, message: impl Into<String>) -> Self {
        strata::Error::input(context, message).into()
    }

    /// Shorthand for [`Error::Io`]: `path` names the file (`path.display()` of a `Path`),
    /// `source` is the underlying error (an `std::io::Error`, an encoder's error, or a message).
    pub fn io(
        path: impl Into<String>,
        source: impl Into<Box<dyn std::error::Error + Send + Sync>>,
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
            Error::Strata(e) => e.fmt(f),
            Error::UnknownSampler { name, known } => {
                write!(
                    f,
                    "unknown sampler '{name}'; known samplers: {}",
                    known.join(", ")
                )
            }
            Error::Unreachable { context, message } => write!(f, "{context}: {message}"),
            Error::Io { path, source } => write!(f, "{path}: {source}"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Strata(e) => Some(e),
            Error::Io { source, .. } => Some(source.as_ref()),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::error::Error as _;

    #[test]
    fn io_errors_keep_their_source() {
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
    fn the_renderer_crate_s_refusals_read_the_same_through_the_lab() {
        let core = strata::Error::count("jittered", 10, "the count must be a perfect square");
        let lab = Error::from(core.clone());
        assert_eq!(lab.to_string(), core.to_string());
        assert_eq!(
            lab,
            Error::count("jittered", 10, "the count must be a perfect square")
        );
        assert_ne!(
            lab,
            Error::count("jittered", 11, "the count must be a perfect square")
        );
    }
}
