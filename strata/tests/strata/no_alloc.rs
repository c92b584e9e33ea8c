//! Nothing allocates after construction: the path-tracer adapter's draws for every sequence, and
//! the stateless core (Sobol' and Z-ordered Sobol' by index, dimension and seed, stochastic
//! pmj02 by index, Halton, hashing, Kensler's permutation, float conversion). A counting global
//! allocator watches, counting per thread so that the test harness's own allocations on other
//! threads do not count (this file is its own test binary: the allocator is global).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::hint::black_box;

use strata::samplers::{Pmj02Stochastic, halton, sobol};
use strata::{PixelSampler, Seed, Sequence, float, hash};

struct Counting;

thread_local! {
    // const-initialised, no destructor: touching it never allocates
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards to the system allocator unchanged; only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        // SAFETY: the caller's contract is passed through.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed through.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn the_counter_sees_an_allocation() {
    // the tests below can fail: a Vec is counted
    assert!(allocations(|| drop(black_box(vec![1u8; 10]))) >= 1);
}

#[test]
fn the_render_loop_allocates_nothing() {
    for name in Sequence::NAMES {
        let s =
            PixelSampler::new(Sequence::by_name(name, [256, 256]).unwrap(), 16, Seed(9)).unwrap();
        let mut t = black_box(s.clone());
        let mut acc = 0.0f32;
        let n = allocations(|| {
            for y in 0..16u32 {
                for x in 0..16u32 {
                    for i in 0..16u64 {
                        t.start_pixel_sample([x, y], i, 0);
                        acc += t.get_pixel_2d()[0] + t.get_2d()[1] + t.get_1d() + t.get_4d()[3];
                        acc += t.sample_1d([x, y], i + (1 << 32), 3);
                        acc += t.sample_2d([x, y], i * 70_001, 5)[0];
                    }
                }
            }
        });
        assert_eq!(n, 0, "{name} allocated {n} times in the render loop");
        assert!(acc.is_finite());
    }
}

#[test]
fn the_stateless_core_allocates_nothing() {
    // (the tables are built at compile time, or when a sampler is made)
    black_box(sobol::owen_scrambled(0, 5, strata::Seed(1)));
    let zsobol = PixelSampler::new(Sequence::zsobol(64, 64).unwrap(), 16, Seed(2)).unwrap();
    let n = allocations(|| {
        for i in 0..4096u32 {
            for dim in 0..8 {
                black_box(sobol::owen_scrambled(i, dim, strata::Seed(7)));
                black_box(halton::scrambled_radical_inverse(
                    i as u64,
                    dim,
                    strata::Seed(7),
                ));
                black_box(zsobol.sample_2d([i % 64, i / 64 % 64], i as u64 % 16, dim));
            }
            black_box(Pmj02Stochastic::point(i, Seed(7)));
            black_box(hash::permute(i % 1000, 1000, i));
            black_box(float::unit_f32_from_u32(strata::scramble::owen_scramble(
                i, 9,
            )));
            black_box(float::f32_in_stratum(i as u64 % 3, 3, 0.5));
        }
    });
    assert_eq!(n, 0, "{n} allocations");
}
