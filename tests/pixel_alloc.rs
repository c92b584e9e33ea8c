//! The render loop allocates nothing: a counting global allocator watches `get_*` calls after
//! construction (its own test binary, because the allocator is global).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use strata::pixel::{PixelSampler, Sequence};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn no_allocation_after_construction() {
    for name in Sequence::NAMES {
        let mut s =
            PixelSampler::new(Sequence::by_name(name).unwrap(), 16, strata::Seed(9)).unwrap();
        // first use builds the shared tables (pmj02, Sobol'): outside the measured loop
        s.start_pixel_sample([0, 0], 0, 0);
        let _ = (s.get_pixel_2d(), s.get_2d(), s.get_1d());
        let mut t = s.clone();
        let before = ALLOCATIONS.load(Ordering::Relaxed);
        let mut acc = 0.0f32;
        for y in 0..16u32 {
            for x in 0..16u32 {
                for i in 0..16u64 {
                    t.start_pixel_sample([x, y], i, 0);
                    acc += t.get_pixel_2d().x + t.get_2d().y + t.get_1d() + t.get_2d().x;
                    acc += t.sample([x, y], i + (1 << 32), 3);
                }
            }
        }
        let after = ALLOCATIONS.load(Ordering::Relaxed);
        assert_eq!(
            after,
            before,
            "{name} allocated {} times in the render loop",
            after - before
        );
        assert!(acc.is_finite());
    }
}
