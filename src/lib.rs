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
//! independence and stratification. With `default-features = false` the crate is `no_std`
//! (with `alloc`) and depends only on `rand` and `glam` (re-exported as [`glam`]): see
//! [Features](#features). On a GPU: the draws of six of the sequences are 32-bit integer
//! arithmetic ([`pixel::kernel`]), and [`pixel::WGSL`] is the same kernel as a WGSL shader,
//! tested bit for bit against the CPU on a Vulkan device ([`pixel`](pixel#on-a-gpu) says
//! exactly what is covered).
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
//!   number of threads (see [Stability of values](#stability-of-values)).
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
//! ## Stability of values
//!
//! The values are part of the interface: a renderer's images, a study's tables and a test's
//! expectations depend on them. Within a minor version (`0.y.*`, and `x.*` from 1.0), for the
//! same seed, parameters, index and dimension, every registered sampler, every
//! [`PixelSampler`] sequence and every stateless function (`sobol::owen_scrambled`,
//! `Pmj02Stochastic::point`, `halton::scrambled_radical_inverse`, [`scramble`], [`digital`],
//! [`pixel::kernel`]) gives the same bits, whatever the platform (x86-64 with or without SIMD,
//! other architectures), the number of threads, or the order of calls. A release that changes
//! any of them bumps the minor version and lists the change in `CHANGELOG.md` under
//! "value-breaking". What pins this: golden digests of every sampler and sequence
//! (`tests/golden.rs`, run by CI once with the SIMD lane types compiled out,
//! `--cfg strata_portable`), the GPU test of the WGSL kernel, and tests that the SIMD lanes,
//! the bulk `fill` paths and the thread counts give the scalar bits. Floating point: samplers
//! compute in integer fixed point or with IEEE operations that are exact or correctly rounded
//! (`+ - * /`, `sqrt`); the optimisers' `exp` is `libm`'s, not the platform's. Not covered: the
//! [`pixel::warp`] mappings and the analysis tools, which use the platform's `sin`, `cos`, `ln`
//! and `exp`.
//!
//! ## Features
//!
//! * `std` (default): the standard library, the other samplers (PMJ, blue noise, orthogonal
//!   arrays), [`conformance`], [`analysis`]. Without it (`default-features = false`) the crate
//!   is `#![no_std]` (with `alloc`), for embedded and WASM renderers: [`PixelSampler`] with
//!   every [`Sequence`]; the classic samplers (`random`, `regular`, `jittered`, `nrooks`,
//!   `multijittered`, `cmj`, `latin`, `uncorrelated`), Sobol', Halton, the lattices and
//!   stochastic pmj02, with the [`registry`] of these; and the stateless functions
//!   ([`samplers::sobol::owen_scrambled`],
//!   [`samplers::Pmj02Stochastic::point`], [`samplers::halton::scrambled_radical_inverse`],
//!   the lattice's [`samplers::lattice::GENERATOR`], [`scramble`], [`digital`], [`hash`],
//!   [`float`]), none of which allocates; `alloc` holds the samplers' stored points. For a GPU
//!   the crate gives its kernel as WGSL ([`pixel::WGSL`]); the Rust code itself is not compiled
//!   for GPU targets here (its kernel is 32-bit arithmetic, but no rust-gpu build is tested).
//! * `spectrum` (default): power spectra, point-set measures and the convergence studies
//!   ([`spectrum`], [`analysis`]).
//! * `io` (default): pictures, EXR and CSV output and plots ([`io`]).
//! * `lloyd` (default): Lloyd relaxation on the periodic Voronoi diagram (`spade`).
//! * `joe-kuo` (default): Joe and Kuo's Sobol' direction numbers for 1000 dimensions.

#![cfg_attr(docsrs, feature(doc_cfg))]
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
pub mod digital;
mod entry;
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
pub mod power;
pub mod registry;
mod sampler;
pub mod samplers;
pub mod scramble;
#[cfg(feature = "spectrum")]
pub mod spectrum;
#[cfg(feature = "std")]
mod stats;

pub use error::{Error, Result};
pub use glam;
pub use pixel::{Padding, PixelSampler, Sequence};
pub use sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};

/// The README's code examples, compiled and run by `cargo test`.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
