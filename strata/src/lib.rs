//! # strata: sample values for a path tracer
//!
//! Clone one [`PixelSampler`] per thread and ask it for values by (pixel, sample index,
//! dimension):
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
