//! The one piece of machinery every fixed-count sampler shares: a stream of independent sets
//! of `N` points, block after block.
//!
//! A fixed-count sampler's construction implements [`Blocks`]: how to set up a block from its
//! key, and point `i` of the current block. [`Fixed`] owns the position in the stream (which
//! block, which sample) once for all of them and is the [`Sampler`] (the first two
//! coordinates) and the [`SamplerNd`] (all of them); block `b` is keyed by
//! `stream_seed(b, seed)`. Constructions computed point by point (jittered, multi-jittered,
//! orthogonal arrays) answer [`Blocks::point`] on demand; those that build a whole set at once
//! (Poisson disk, relaxation, in the lab) keep the set of the current block.

use crate::Result;
use crate::hash::stream_seed;
use crate::prelude::*;
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};

/// Where a fixed-count sampler is in its stream: which block, which sample inside it.
#[derive(Clone, Debug)]
struct BlockCursor {
    seed: u64,
    count: u32,
    block: u64,
    index: u32,
}

impl BlockCursor {
    /// The start of the stream of blocks of `count` samples seeded by `seed`.
    fn new(count: u32, seed: Seed) -> Self {
        BlockCursor {
            seed: seed.0,
            count,
            block: 0,
            index: 0,
        }
    }

    /// The key of the current block.
    fn block_key(&self) -> u64 {
        stream_seed(self.block, self.seed)
    }

    /// The key of the current block if the next sample is its first (the block must then be
    /// set up).
    fn starting_block(&self) -> Option<u64> {
        (self.index == 0).then(|| self.block_key())
    }

    /// The index of the next sample inside its block, and how many remain in the block.
    fn position(&self) -> (u32, u32) {
        (self.index, self.count - self.index)
    }

    /// Moves `k` samples on (`k` at most the number remaining in the block).
    fn advance(&mut self, k: u32) {
        self.index += k;
        if self.index == self.count {
            self.index = 0;
            self.block = self.block.wrapping_add(1);
        }
    }
}

/// The construction of a fixed-count sampler: sets of [`set_len`](Blocks::set_len) points, each
/// computed from its block's key. [`Fixed`] streams them.
pub trait Blocks: Clone + Send {
    /// The registered name.
    const NAME: &'static str;

    /// Points per set.
    fn set_len(&self) -> u32;

    /// Coordinates per point (2 unless the sampler is D-dimensional).
    fn set_dims(&self) -> u32 {
        2
    }

    /// Sets up the block keyed by `key` (a well-mixed seed).
    fn begin_block(&mut self, key: u64);

    /// The first two coordinates of point `i` of the current block, `i` below
    /// [`set_len`](Blocks::set_len) (all that [`Fixed`] asks; past it a construction may answer
    /// anything, a point outside the unit square or a panic in a debug build). A D-dimensional
    /// construction writes [`point_into`](Blocks::point_into) and answers this from it.
    fn point(&self, i: u32) -> Point2;

    /// Point `i` of the current block (`i` below [`set_len`](Blocks::set_len), as for
    /// [`point`](Blocks::point)): its first `out.len()` coordinates (at most
    /// [`set_dims`](Blocks::set_dims)). The default, for a 2D construction, copies
    /// [`point`](Blocks::point).
    #[inline]
    fn point_into(&self, i: u32, out: &mut [f32]) {
        let p = self.point(i);
        for (o, v) in out.iter_mut().zip(p) {
            *o = v;
        }
    }

    /// Points `start..start + out.len()` of the current block (a sampler may compute several
    /// at once; the values are those of [`point`](Blocks::point)).
    #[inline]
    fn fill_run(&self, start: u32, out: &mut [Point2]) {
        for (p, i) in out.iter_mut().zip(start..) {
            *p = self.point(i);
        }
    }

    /// The grids a complete set is stratified in, in its first two dimensions.
    fn grids(&self) -> Vec<StrataGrid> {
        Vec::new()
    }

    /// The grid on which the projection onto dimensions `x` and `y` of a complete set is
    /// stratified (`x != y`, both below `set_dims`).
    fn pair_strata(&self, x: u32, y: u32) -> Option<StrataGrid> {
        let _ = (x, y);
        None
    }
}

/// A fixed-count sampler: the stream of sets of its construction `B`, block after block (block
/// `b` keyed by `stream_seed(b, seed)`), as a [`Sampler`] and a [`SamplerNd`]. It dereferences
/// to the construction (`Jittered::new(16, seed)?.count()`).
#[derive(Clone, Debug)]
pub struct Fixed<B: Blocks> {
    blocks: B,
    cursor: BlockCursor,
}

impl<B: Blocks> Fixed<B> {
    /// The stream of the sets of `blocks`, seeded by `seed`; an error if a set has no points
    /// (`set_len() == 0`: a stream of empty sets has no next sample).
    pub fn new(blocks: B, seed: Seed) -> Result<Self> {
        if blocks.set_len() == 0 {
            return Err(crate::Error::input(
                B::NAME,
                "a set of 0 points: a fixed-count sampler needs at least one point per set",
            ));
        }
        let cursor = BlockCursor::new(blocks.set_len(), seed);
        Ok(Fixed { blocks, cursor })
    }
}

impl<B: Blocks> core::ops::Deref for Fixed<B> {
    type Target = B;

    fn deref(&self) -> &B {
        &self.blocks
    }
}

impl<B: Blocks> Sampler for Fixed<B> {
    fn name(&self) -> &'static str {
        B::NAME
    }

    fn progression(&self) -> Progression {
        Progression::FixedCount {
            count: self.blocks.set_len() as u64,
        }
    }

    #[inline]
    fn next_sample(&mut self) -> Point2 {
        if let Some(key) = self.cursor.starting_block() {
            self.blocks.begin_block(key);
        }
        let i = self.cursor.position().0;
        let p = self.blocks.point(i);
        self.cursor.advance(1);
        p
    }

    fn fill(&mut self, mut out: &mut [Point2]) {
        while !out.is_empty() {
            if let Some(key) = self.cursor.starting_block() {
                self.blocks.begin_block(key);
            }
            let (start, remaining) = self.cursor.position();
            let k = remaining.min(u32::try_from(out.len()).unwrap_or(u32::MAX));
            let (head, tail) = out.split_at_mut(k as usize);
            self.blocks.fill_run(start, head);
            self.cursor.advance(k);
            out = tail;
        }
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        if n == self.blocks.set_len() as u64 {
            let mut grids = self.blocks.grids();
            grids.retain(StrataGrid::resolvable);
            grids
        } else {
            Vec::new()
        }
    }
}

impl<B: Blocks> SamplerNd for Fixed<B> {
    fn name(&self) -> &'static str {
        B::NAME
    }

    fn dimensions(&self) -> u32 {
        self.blocks.set_dims()
    }

    fn progression(&self) -> Progression {
        Progression::FixedCount {
            count: self.blocks.set_len() as u64,
        }
    }

    fn next_point(&mut self, out: &mut [f32]) {
        if let Some(key) = self.cursor.starting_block() {
            self.blocks.begin_block(key);
        }
        let i = self.cursor.position().0;
        let d = (self.blocks.set_dims() as usize).min(out.len());
        self.blocks.point_into(i, &mut out[..d]);
        self.cursor.advance(1);
    }

    fn projection_strata(&self, x: u32, y: u32) -> Option<StrataGrid> {
        if x == y || x >= self.blocks.set_dims() || y >= self.blocks.set_dims() {
            return None;
        }
        self.blocks.pair_strata(x, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A construction whose sets have no points.
    #[derive(Clone)]
    struct Empty;

    impl Blocks for Empty {
        const NAME: &'static str = "empty";
        fn set_len(&self) -> u32 {
            0
        }
        fn begin_block(&mut self, _: u64) {}
        fn point(&self, _: u32) -> Point2 {
            [0.0; 2]
        }
    }

    #[test]
    fn a_set_of_no_points_is_refused() {
        // (was: accepted, then `fill` looped forever and a second sample wrapped the index)
        let e = Fixed::new(Empty, Seed(1)).err().expect("refused");
        assert!(e.to_string().contains("0 points"), "{e}");
    }
}
