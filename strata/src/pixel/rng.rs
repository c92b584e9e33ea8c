//! A bridge for renderers written against `rand`: successive dimensions of a pixel sample as
//! `rand::Rng` words.

use core::convert::Infallible;

use rand_core::TryRng;

use super::PixelSampler;

/// `rand::Rng` over the current pixel sample of a [`PixelSampler`]: every `next_u32` or
/// `next_u64` is the next dimension ([`PixelSampler::get_1d`]).
///
/// The sequence's value, rounded down to a multiple of `2^-24`, fills the top 24 bits of the
/// word (so `random::<f32>()` returns `get_1d()` to 24 bits: exactly for the nets, whose
/// values are 24-bit fixed point; jittered and Halton values carry finer bits near 0, which
/// the word drops); the bits below are hashed from the pixel, sample and dimension, so that
/// every word is uniform. `fill_bytes` takes one dimension per
/// 8 bytes. Which `rand` calls keep their dimension, and which to replace by mappings of 2D
/// draws, is in the [module docs](super#dimensions-in-a-renderer-that-bounces).
///
/// ```
/// use rand::RngExt;
/// use strata::{PixelSampler, Seed, Sequence};
/// let mut sampler = PixelSampler::new(Sequence::sobol(), 16, Seed(1))?;
/// sampler.start_pixel_sample([3, 4], 0, 2);
/// let u: f32 = sampler.rng().random(); // dimension 2
/// assert_eq!(u, sampler.sample_1d([3, 4], 0, 2));
/// assert_eq!(sampler.dimension(), 3);
/// # Ok::<(), strata::Error>(())
/// ```
#[derive(Debug)]
pub struct PixelRng<'a> {
    sampler: &'a mut PixelSampler,
}

impl<'a> PixelRng<'a> {
    /// The bridge over `sampler`'s current pixel sample.
    pub(crate) fn new(sampler: &'a mut PixelSampler) -> Self {
        PixelRng { sampler }
    }

    /// The next dimension as a 64-bit word: the value's 24 bits on top, 40 hashed bits below.
    #[inline]
    fn next_word(&mut self) -> u64 {
        let low = self.sampler.low_bits() >> 24;
        let value = (self.sampler.get_1d() * 16_777_216.0) as u64; // exact: 24-bit values
        (value << 40) | low
    }
}

impl TryRng for PixelRng<'_> {
    type Error = Infallible;

    #[inline]
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.next_word() >> 32) as u32)
    }

    #[inline]
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        Ok(self.next_word())
    }

    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(8) {
            let word = self.next_word().to_le_bytes();
            chunk.copy_from_slice(&word[..chunk.len()]);
        }
        Ok(())
    }
}
