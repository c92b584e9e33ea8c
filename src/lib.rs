//! # strata: sample patterns for Monte Carlo rendering
//!
//! ## In a path tracer
//!
//! Clone one [`PixelSampler`] per thread and ask it for values by (pixel, sample index,
//! dimension). Each draw is stratified on its own (a (0,m,2)-net at every power of two for
//! `pmj02` and `sobol`) and independent of every other draw, pixel and seed:
//!
//! ```
//! use strata::{PixelSampler, Seed, Sequence};
//! let mut sampler = PixelSampler::new(Sequence::sobol(), 64, Seed(7))?;
//! for index in 0..64 {
//!     sampler.start_pixel_sample([12, 34], index, 0);
//!     let film = sampler.get_pixel_2d(); // where in the pixel (dimensions 0-1)
//!     let lens = sampler.get_2d(); // dimensions 2-3
//!     for bounce in 0..4 {
//!         sampler.start_bounce(bounce); // each bounce at a fixed dimension budget
//!         let light = sampler.get_2d(); // a point on a light
//!         let direction = sampler.get_2d(); // the next direction
//!         # let _ = (light, direction);
//!     }
//!     # let _ = (film, lens);
//! }
//! # Ok::<(), strata::Error>(())
//! ```
//!
//! [`pixel`] has the guarantees, the dimension layout of a bouncing renderer, a `rand` bridge
//! and mappings of 2D draws; [`conformance`] checks any sequence (yours too) for bias,
//! independence and stratification. With `default-features = false` the crate is `no_std` (it
//! needs `alloc` only for the pmj02 table) and depends only on `rand` and `glam` (re-exported as
//! [`glam`], with `libm`): see [Features](#features).
//!
//! ## The idea in brief
//!
//! A Monte Carlo estimate `(1/N) sum f(x_k)` is the integral of `f` against the sampling pattern
//! `S(x) = (1/N) sum delta(x - x_k)`. In the Fourier domain that is the DC term of the
//! convolution of `f^` with `S^` (Durand 2011). For patterns whose expected spectrum vanishes
//! away from DC the estimate is unbiased, and its variance is
//!
//! ```text
//! Var = sum_{w != 0} |f^(w)|^2 E[|S^(w)|^2]          (Subr and Kautz 2013; Pilleboue et al. 2015)
//! ```
//!
//! the integrand's power spectrum times the pattern's **expected power spectrum**. Natural
//! integrands keep their energy at low frequencies, so a good pattern has little power near DC:
//! jittered sampling pushes it out (variance `N^-1.5` to `N^-2` in 2D instead of random's
//! `N^-1`), blue noise empties a whole disc around DC, and low-discrepancy nets do both at every
//! power of two.
//!
//! ## Samplers
//!
//! Every sampler implements [`Sampler`] (2D points) and, where it has them, [`SamplerNd`]
//! (D dimensions); [`registry`] builds them by name. The table is generated from the registry
//! ([`registry::table`]); `variance` gives the published rates `N^r` of the estimate's variance
//! on discontinuous / smooth 2D integrands.
//!
#![doc = include_str!("../docs/samplers.md")]
//!
//! ## Contract
//!
//! * Points lie in `[0,1)^2`; `f32` coordinates never equal 1.0 ([`float`] explains how).
//! * Everything is seeded ([`Seed`]): same seed, same bits, on every platform and with any
//!   number of threads.
//! * Constructors validate their parameters and return [`Result`]; the [`Error`] says what was
//!   wrong and what is allowed. Nothing panics on user input.
//!
//! ```
//! use strata::{Sampler, registry::{self, Params}};
//! let mut s = registry::build("jittered", &Params::new(64).seed(3))?;
//! let mut points = vec![strata::glam::Vec2::ZERO; 64];
//! s.fill(&mut points);
//! let mean_x: f32 = points.iter().map(|p| p.x).sum::<f32>() / 64.0;
//! assert!((mean_x - 0.5).abs() < 0.05);
//! # Ok::<(), strata::Error>(())
//! ```
//!
//! ## Features
//!
//! * `std` (default): the standard library, every sampler, [`registry`], [`conformance`],
//!   [`analysis`]. Without it (`default-features = false`) the crate is `#![no_std]`, for
//!   rust-gpu shaders, embedded and WASM renderers: [`PixelSampler`] with every
//!   [`Sequence`], and the stateless functions ([`samplers::sobol::owen_scrambled`],
//!   [`samplers::Pmj02Stochastic::point_at`], [`samplers::halton::scrambled_radical_inverse`],
//!   the lattice's [`samplers::lattice::GENERATOR`], [`hash`], [`float`]), none of which
//!   allocates; `alloc` holds the pmj02 adapter's table and the samplers' stored points.
//! * `spectrum` (default): power spectra, point-set measures and the convergence studies
//!   ([`spectrum`], [`analysis`]).
//! * `io` (default): pictures, EXR and CSV output and plots ([`io`]).
//! * `lloyd` (default): Lloyd relaxation on the periodic Voronoi diagram (`spade`).
//! * `joe-kuo` (default): Joe and Kuo's Sobol' direction numbers for 1000 dimensions.

#![cfg_attr(all(not(feature = "std"), not(test)), no_std)]
#![warn(missing_docs, missing_debug_implementations)]
#![warn(clippy::undocumented_unsafe_blocks)]

extern crate alloc;

/// `alloc`'s types under their `std` names, for the files that build without `std`.
#[allow(unused_imports)]
mod prelude {
    pub(crate) use alloc::borrow::ToOwned;
    pub(crate) use alloc::boxed::Box;
    pub(crate) use alloc::string::{String, ToString};
    pub(crate) use alloc::vec::Vec;
    pub(crate) use alloc::{format, vec};
}

#[cfg(feature = "std")]
pub mod analysis;
#[cfg(feature = "std")]
pub mod conformance;
mod error;
pub mod float;
#[cfg(feature = "std")]
mod grid;
pub mod hash;
#[cfg(feature = "io")]
pub mod io;
#[cfg_attr(not(feature = "std"), allow(dead_code))]
mod morton;
#[cfg(feature = "std")]
mod occupancy;
pub mod pixel;
#[cfg(feature = "std")]
pub mod pointsets;
#[cfg(feature = "std")]
pub mod registry;
mod sampler;
pub mod samplers;
#[cfg(feature = "spectrum")]
pub mod spectrum;
#[cfg(feature = "std")]
mod stats;

pub use error::{Error, Result};
pub use glam;
pub use pixel::{PixelSampler, Sequence};
pub use sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};

/// The README's code examples, compiled and run by `cargo test`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
