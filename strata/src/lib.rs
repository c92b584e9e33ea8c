//! # strata: stratified sample values for a path tracer
//!
//! Clone one [`PixelSampler`] per thread and ask it for values by (pixel, sample index,
//! dimension):
//!
//! ```
//! use strata::{PixelSampler, Seed, Sequence};
//! // Z-ordered Sobol' for a 640x480 image, a bounce's draws in one group of 8 dimensions
//! let mut sampler = PixelSampler::new(Sequence::zjoint(640, 480, 8)?, 64, Seed(7))?;
//! for index in 0..64 {
//!     sampler.start_pixel_sample([12, 34], index, 0);
//!     let [fx, fy] = sampler.get_pixel_2d(); // where in the pixel (dimensions 0-1)
//!     let lens = sampler.get_2d(); // dimensions 2-3
//!     for bounce in 0..4 {
//!         sampler.start_bounce(bounce); // each bounce at a fixed dimension budget
//!         let light = sampler.get_2d(); // a point on a light
//!         let direction = sampler.get_2d(); // the next direction
//!         # let _ = (light, direction);
//!     }
//!     # let _ = (fx, fy, lens);
//! }
//! # Ok::<(), strata::Error>(())
//! ```
//!
//! Every value is a pure function of (seed, pixel, index, dimension): the same image whatever the
//! order of pixels, tiles or threads. Each draw (a 1D value or a 2D pair) is stratified on its
//! own, independent of the other draws, pixels and seeds but where its sequence says otherwise,
//! and nothing allocates after construction. Draws are plain arrays (`[f32; 2]`), so no math
//! library is imposed: `glam::Vec2::from(sampler.get_2d())` converts. [`pixel`] has the
//! guarantees, the [sequences](pixel#sequences), the dimension layout of a bouncing renderer, the
//! `rand` bridge and the GPU port.
//!
//! ## What else is here
//!
//! * [`samplers`]: the point sets and sequences that need no standard library: the classic ones
//!   (random, regular, jittered, N-rooks, multi-jittered, correlated multi-jittered, Latin
//!   hypercube, uncorrelated jitter), Sobol' (with Joe and Kuo's direction numbers for 1000
//!   dimensions), Halton, rank-1 lattices and stochastic pmj02, behind the [`Sampler`] (2D) and
//!   [`SamplerNd`] traits, with stateless forms ([`samplers::sobol::owen_scrambled`],
//!   [`samplers::halton::scrambled_radical_inverse`], [`samplers::Pmj02Stochastic::point`]);
//! * the primitives they are made of: [`float`] (conversion that never gives 1.0), [`hash`]
//!   (hashes, seed streams, Kensler's permutation), [`scramble`] (Owen scrambling, the nested
//!   index shuffle), [`digital`] (generator matrices), [`morton`], [`counts`] (which counts a
//!   fixed-count sampler takes).
//!
//! The lab crate (`strata-lab`) has the rest: the constructed PMJ sequences, blue noise,
//! orthogonal arrays, the registry of every sampler by name, spectra, convergence studies, the
//! conformance suite that checks any sequence (yours too), and the programs.
//!
//! ## Features and dependencies
//!
//! The crate is `#![no_std]` with `alloc`, and depends on `rand_core` (the [`pixel::PixelRng`]
//! bridge) and `rand_pcg` (the generator of `random`) alone. The `std` feature (default) adds
//! `pixel::warp` (mappings of 2D draws onto discs and spheres, which need `sin`, `cos`, `sqrt`
//! and `ln`) and the run-time choice of AVX2 in `SobolNd::fill`; nothing else changes with it: no
//! item changes its type or value (a test compares what a caller can name with and without it).
//! The `portable` feature builds the SIMD lanes as plain arrays and drops the AVX2 path (no
//! `core::arch` intrinsics, for Miri or an unusual target): the same items and the same values,
//! slower draws.
//!
//! ## Values
//!
//! The same seed gives the same bits on every platform, with SIMD on or off, for every sampler,
//! sequence and stateless function (golden digests pin them); a release that changes a value
//! says so in the changelog under "value-breaking", which states the policy. The `pixel::warp`
//! mappings use the platform's `sin`, `cos` and `ln`, and are not covered.

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

pub mod counts;
pub mod digital;
mod error;
pub mod float;
pub mod hash;
pub mod morton;
pub mod pixel;
mod sampler;
pub mod samplers;
pub mod scramble;

pub use error::{Error, Result};
pub use pixel::{Padding, PixelSampler, Sequence};
pub use sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
