//! The sampler families, one per file.
//!
//! Which sampler is where: the table of the crate docs ([Samplers](crate#samplers)), generated
//! from the registry ([`crate::registry::table`]), where each sampler's file declares its name,
//! kind, promises, rates and paper.
//!
//! Fixed-count samplers share one piece of machinery, [`Blocks`]: a cursor walks through blocks
//! of `N` samples and gives each block its own key, `stream_seed(seed, block)`; every point is a
//! function of (block key, index in block), computed on demand with hashing and
//! [`Permutation`]s (no tables, no allocation, O(1) per point), or
//! read from a set generated at once ([`Sets`]). Progressive samplers share another: when a
//! sequence of `2^32` points is exhausted, a new, independent one starts.

#[cfg(feature = "std")]
pub mod best_candidate;
mod blocks;
#[cfg(feature = "std")]
pub mod bnot;
#[cfg(feature = "std")]
pub mod ccvt;
pub mod halton;
pub(crate) mod jittered;
pub(crate) mod latin;
pub mod lattice;
#[cfg(feature = "lloyd")]
pub mod lloyd;
pub(crate) mod multijitter;
#[cfg(feature = "std")]
pub mod net02bn;
#[cfg(feature = "std")]
pub mod oa;
pub mod pmj;
#[cfg(feature = "std")]
pub mod poisson;
mod progressive;
pub(crate) mod random;
pub(crate) mod regular;
pub mod sobol;
pub(crate) mod uncorrelated;

#[cfg(feature = "std")]
pub use best_candidate::BestCandidate;
pub use blocks::{BlockCursor, Blocks, SetGenerator, Sets};
#[cfg(feature = "std")]
pub use bnot::{Bnot, BnotSets};
#[cfg(feature = "std")]
pub use ccvt::{Ccvt, CcvtSets};
pub use halton::{Halton, HaltonNd};
pub use jittered::Jittered;
pub use latin::{LatinHypercube, NRooks};
pub use lattice::{Fibonacci, Lattice, LatticeNd};
#[cfg(feature = "lloyd")]
pub use lloyd::{Lloyd, LloydSets};
pub use multijitter::{Cmj, MultiJittered};
#[cfg(feature = "std")]
pub use net02bn::{Net02Bn, Net02BnSets};
#[cfg(feature = "std")]
pub use oa::{Bose, Bush};
pub use pmj::Pmj02Stochastic;
#[cfg(feature = "std")]
pub use pmj::{Pmj, Pmj02Bn};
#[cfg(feature = "std")]
pub use poisson::{Bridson, BridsonDisk, DartThrowing, PoissonDisk};
pub(crate) use progressive::Epochs;
pub use random::{Random, RandomNd};
pub use regular::Regular;
pub use sobol::{Sobol, SobolNd};
pub use uncorrelated::UncorrelatedJitter;

use alloc::format;
use alloc::vec::Vec;

use crate::error::{Error, Result};
use crate::hash::{Permutation, key32, stream_seed};

// The count rules check it, so it lives with them, in the entry types below the samplers.
pub use crate::entry::MAX_FIXED_COUNT;

/// The most dimensions a D-dimensional sampler accepts (more than any integrand needs; the
/// limit bounds allocations sized by `D`).
pub const MAX_DIMENSIONS: u32 = 1 << 16;

/// Validates a dimension count: 1 to `max`; `note` (empty, or starting with a space) follows
/// the allowed range in the error.
pub(crate) fn check_dims(sampler: &'static str, dims: u32, max: u32, note: &str) -> Result<()> {
    if dims == 0 || dims > max {
        return Err(Error::parameter(
            sampler,
            "dims",
            dims,
            format!("1 to {max}{note}"),
        ));
    }
    Ok(())
}

/// Validates a point count of a sampler that makes 1 to `max` points.
#[cfg(feature = "std")]
pub(crate) fn check_count(sampler: &'static str, count: u64, max: u64) -> Result<()> {
    if count == 0 || count > max {
        return Err(Error::count(
            sampler,
            count,
            format!("the count must be between 1 and {max}"),
        ));
    }
    Ok(())
}

/// Replaces `out` with `k` independent permutations of `[0, len)` for block key `key` (one per
/// dimension or group of dimensions, permutation `d` keyed by stream `d` of `key`).
pub(crate) fn block_permutations(out: &mut Vec<Permutation>, len: u32, key: u64, k: u32) {
    out.clear();
    out.extend(
        (0..k as u64).map(|d| Permutation::new(len, key32(stream_seed(key, d))).expect("len >= 1")),
    );
}
