//! The samplers that build without `std`, one family per file: the classic ones (random,
//! regular, jittered, N-rooks, multi-jittered, correlated multi-jittered, Latin hypercube,
//! uncorrelated jitter), Sobol' (and Faure's base-4 sequence in its binary form), Halton, the
//! rank-1 lattices and stochastic pmj02, with the stateless functions behind them. The other
//! samplers (the constructed PMJ sequences, blue noise, orthogonal arrays) are the lab's
//! (`strata-lab`), which also lists every sampler by name.
//!
//! Fixed-count samplers share one piece of machinery, [`Fixed`] over their [`Blocks`]: it walks
//! through blocks of `N` samples and gives each block its own key, `stream_seed(block, seed)`;
//! every point is a function of (block key, index in block), computed on demand with hashing
//! and [`Permutation`]s (no tables, no allocation, O(1) per point). Progressive samplers share
//! another, [`Epochs`]: when a sequence of `2^32` points is exhausted, a new, independent one
//! starts.

mod blocks;
pub mod halton;
mod jittered;
mod latin;
pub mod lattice;
mod multijitter;
mod pmj02;
mod progressive;
mod random;
mod regular;
pub mod sobol;
mod uncorrelated;

pub use blocks::{Blocks, Fixed};
pub use halton::{Halton, HaltonNd};
pub use jittered::Jittered;
pub use latin::{LatinHypercube, NRooks};
pub use lattice::{Fibonacci, Lattice, LatticeNd};
pub use multijitter::{Cmj, MultiJittered};
pub use pmj02::Pmj02Stochastic;
pub use progressive::{Epochs, MAX_SEQUENCE_LEN};
pub use random::{Random, RandomNd};
pub use regular::Regular;
pub use sobol::{Sobol, SobolNd};
pub use uncorrelated::UncorrelatedJitter;

use alloc::format;
use alloc::vec::Vec;

use crate::error::{Error, Result};
use crate::hash::{Permutation, key32, stream_seed};

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

/// Replaces `out` with `k` independent permutations of `[0, len)` for block key `key` (one per
/// dimension or group of dimensions, permutation `d` keyed by stream `d` of `key`).
pub(crate) fn block_permutations(out: &mut Vec<Permutation>, len: u32, key: u64, k: u32) {
    out.clear();
    out.extend(
        (0..k as u64).map(|d| Permutation::new(len, key32(stream_seed(d, key))).expect("len >= 1")),
    );
}
