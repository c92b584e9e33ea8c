//! The renderer's crate in a `#![no_std]` library: every adapter sequence of `Sequence::NAMES`
//! by (pixel, index, dimension, seed), Sobol' by (index, dimension, seed), stochastic pmj02 by
//! index, Halton, hashing, Kensler's permutation and float conversion, and a classic sampler
//! (jittered), exported so that the linker keeps them. Built, not run: it links only if nothing
//! brings `std`.

#![no_std]

use core::alloc::{GlobalAlloc, Layout};

use strata::samplers::{Jittered, Pmj02Stochastic, halton, sobol};
use strata::{PixelSampler, Sampler, Seed, Sequence, float, hash};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// An allocator that has nothing to give: the functions below never ask, but the joint
/// sequences' construction (their tables), which then fails to allocate: the link is what is
/// checked.
struct NoAlloc;

// SAFETY: alloc returns null (an allocation failure), which GlobalAlloc allows; dealloc is
// never given a pointer this allocator returned, since it returns none.
unsafe impl GlobalAlloc for NoAlloc {
    unsafe fn alloc(&self, _: Layout) -> *mut u8 {
        core::ptr::null_mut()
    }
    unsafe fn dealloc(&self, _: *mut u8, _: Layout) {}
}

#[global_allocator]
static ALLOCATOR: NoAlloc = NoAlloc;

/// Sobol' (Owen-scrambled) by index, dimension and seed.
#[unsafe(no_mangle)]
pub extern "C" fn strata_sobol(index: u32, dim: u32, seed: u64) -> f32 {
    sobol::owen_scrambled(index, dim, Seed(seed)).unwrap_or(-1.0)
}

/// Sequence `k` of `Sequence::NAMES` (every one of them, by the list: a new sequence is linked
/// here the day it is added) for pixel (x, y) of a 1920 x 1080 image at 64 samples per pixel
/// (a square, for jittered): the draw at `dim`; -1 past the list.
#[unsafe(no_mangle)]
pub extern "C" fn strata_sequence(k: u32, x: u32, y: u32, index: u64, dim: u32, seed: u64) -> f32 {
    let Some(name) = Sequence::NAMES.get(k as usize) else {
        return -1.0;
    };
    match Sequence::by_name(name, [1920, 1080]).and_then(|z| PixelSampler::new(z, 64, Seed(seed))) {
        Ok(s) => s.sample_2d([x, y], index, dim)[0],
        Err(_) => -1.0,
    }
}

/// Stochastic pmj02 by index.
#[unsafe(no_mangle)]
pub extern "C" fn strata_pmj02(index: u32, seed: u64) -> f32 {
    Pmj02Stochastic::point(index, Seed(seed))[0]
}

/// Scrambled Halton by index, dimension and seed.
#[unsafe(no_mangle)]
pub extern "C" fn strata_halton(index: u64, dim: u32, seed: u64) -> f32 {
    halton::scrambled_radical_inverse(index, dim % halton::MAX_DIMENSIONS, Seed(seed)).unwrap_or(0.0)
}

/// Hashing, Kensler's permutation and float conversion.
#[unsafe(no_mangle)]
pub extern "C" fn strata_hash(i: u32, len: u32, key: u64) -> f32 {
    let p = hash::permute(i % len.max(1), len.max(1), hash::hash32(i, key as u32));
    float::unit_f32_from_u32(strata::scramble::owen_scramble(p, hash::mix64(key) as u32))
}

/// Jittered sampling, a classic sampler (stateful; no allocation for a square `count`): the x
/// of point `index` of the first set of `count`.
#[unsafe(no_mangle)]
pub extern "C" fn strata_jittered(count: u64, index: u32, seed: u64) -> f32 {
    match Jittered::new(count, Seed(seed)) {
        Ok(mut s) => {
            for _ in 0..index {
                s.next_sample();
            }
            s.next_sample()[0]
        }
        Err(_) => -1.0,
    }
}
