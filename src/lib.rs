//! # strata-lab: see and measure sample patterns
//!
//! The research side of `strata`: every pattern of the stratification lecture beyond the
//! renderer crate's (`strata`), the tools that measure patterns (ours or anyone's), and the
//! example programs built on them.
//!
//! * [`registry`]: every sampler by name, the renderer crate's and the lab's, each with its
//!   facts (paper, counts, promise, published rates) and its parameters;
//! * [`samplers`]: the constructed PMJ sequences, blue noise (Poisson disk, best candidate,
//!   Lloyd, CCVT, BNOT, blue-noise nets) and orthogonal arrays;
//! * [`spectrum`]: periodograms, expected power spectra, radial means, anisotropy, the
//!   point-set measures and error images;
//! * [`analysis`]: integrands with exact values, convergence studies, discrepancies, fits;
//! * [`conformance`]: the statistical battery any path-tracer sequence runs through;
//! * [`power`]: periodic power diagrams (BNOT and CCVT); [`pointsets`]: point-set files
//!   (CSV, UTK); [`io`]: pictures, EXR, CSV, plots.
//!
//! ## Samplers
//!
//! The table is generated from the registry ([`registry::table`]); `variance` gives the
//! published rates `N^r` of the estimate's variance on discontinuous / smooth 2D integrands.
//!
#![doc = include_str!("../docs/samplers.md")]

#![warn(missing_docs, missing_debug_implementations)]
#![warn(clippy::undocumented_unsafe_blocks)]

pub mod analysis;
pub mod conformance;
mod entry;
mod grid;
pub mod io;
mod occupancy;
pub mod pointsets;
pub mod power;
pub mod registry;
pub mod samplers;
pub mod spectrum;
mod stats;
#[cfg(test)]
mod strata_checks;

/// The README's code examples, compiled and run by `cargo test`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
