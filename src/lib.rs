//! # strata-lab: see and measure sample patterns
//!
//! The research side of `strata`: every pattern of the stratification lecture beyond the
//! renderer crate's ([`strata`], which a path tracer links alone), the tools that measure
//! patterns (ours or anyone's), and the programs built on them. Where the samples go decides the
//! error of a Monte Carlo estimate: its variance is `sum_{w != 0} |f^(w)|^2 E[|S^(w)|^2]`, the
//! integrand's power spectrum times the pattern's expected power spectrum (Subr and Kautz 2013;
//! Pilleboue et al. 2015), which [`spectrum`] measures and [`analysis`] checks against
//! convergence studies.
//!
//! ```
//! use strata::{Sampler, Seed};
//! use strata_lab::registry::{self, Params};
//! let mut s = registry::build("pmj02bn", &Params::new(64).seed(Seed(3)))?;
//! let mut points = vec![[0.0f32; 2]; 64];
//! s.fill(&mut points);
//! let spectrum = strata_lab::spectrum::periodogram(&points, 16)?;
//! // the DC term is N, and the spectrum of this blue-noise net is low near DC
//! assert!((spectrum.get(0, 0).unwrap() - 64.0).abs() < 1e-9);
//! assert!(spectrum.get(1, 0).unwrap() < 1.0);
//! # Ok::<(), strata_lab::Error>(())
//! ```
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
//! Points lie in `[0,1)^2` and never reach 1.0; everything is seeded ([`strata::Seed`]): the
//! same seed gives the same bits on every platform and with any number of threads, which golden
//! digests pin; constructors and analyses return [`Error`] saying what was wrong and what is
//! allowed, never a panic on user input.
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
mod counts;
mod entry;
mod error;
mod grid;
pub mod io;
mod occupancy;
pub mod pointsets;
pub mod power;
pub mod registry;
mod rng;
pub mod samplers;
pub mod spectrum;
mod stats;
#[cfg(test)]
mod strata_checks;

pub use error::{Error, Result};

/// The README's code examples, compiled and run by `cargo test`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
