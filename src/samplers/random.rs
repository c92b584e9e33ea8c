//! Independent uniform random points: the baseline every other pattern is measured against.
//!
//! Each coordinate is 24 random bits from PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast
//! Space-Efficient Statistically Good Algorithms for Random Number Generation"). The expected
//! power spectrum is flat (1 at every frequency but DC) and the integration variance falls as
//! `N^-1` whatever the integrand: no stratification, but trivially progressive and free of
//! correlation between dimensions.

use crate::entry::{Built, CountRule, Entry, Family, Rates};
use crate::float::unit_f32_from_u32;
use crate::hash::stream_seed;
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed};

/// The registry entry of `random`.
pub(crate) const ENTRY: Entry = Entry {
    name: "random",
    description: "independent uniform points (PCG32); progressive",
    paper: "-",
    family: Family::Classic,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[],
    promise: "nothing (i.i.d. uniform)",
    rates: Rates::RANDOM,
    expensive: false,
    blue_noise: None,
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Random::new(p.sampler_seed())),
            d => Built::nd(RandomNd::new(d, p.sampler_seed())?),
        })
    },
};

/// The generator of a seed.
fn pcg(seed: Seed) -> Pcg32 {
    Pcg32::new(stream_seed(seed.0, 0), stream_seed(seed.0, 1))
}

/// PCG32 (XSH RR 64/32: a 64-bit LCG with a xorshift-and-rotate output), seeded as `rand_pcg`'s
/// `Pcg32::new(state, stream)` and giving its `next_u32` bits; written out here so that the
/// sampler needs neither `std` nor a dependency beyond `rand` and `glam`.
#[derive(Clone, Debug)]
struct Pcg32 {
    state: u64,
    increment: u64,
}

impl Pcg32 {
    const MULTIPLIER: u64 = 6_364_136_223_846_793_005;

    fn new(state: u64, stream: u64) -> Self {
        // the increment must be odd: the stream's top bit is dropped
        let increment = (stream << 1) | 1;
        let mut pcg = Pcg32 {
            state: state.wrapping_add(increment),
            increment,
        };
        pcg.step();
        pcg
    }

    #[inline]
    fn step(&mut self) {
        self.state = self
            .state
            .wrapping_mul(Self::MULTIPLIER)
            .wrapping_add(self.increment);
    }

    #[inline]
    fn next_u32(&mut self) -> u32 {
        let state = self.state;
        self.step();
        // xorshift the high bits down, then rotate by the top 5 bits
        let xsh = (((state >> 18) ^ state) >> 27) as u32;
        xsh.rotate_right((state >> 59) as u32)
    }
}

/// Independent uniform points in `[0,1)^2` (progressive: every prefix is an i.i.d. sample).
///
/// ```
/// use strata::{Sampler, Seed, samplers::Random};
/// let mut s = Random::new(Seed(42));
/// let p = s.next_sample();
/// assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
/// ```
#[derive(Clone, Debug)]
pub struct Random {
    rng: Pcg32,
}

impl Random {
    /// A stream seeded by `seed`.
    pub fn new(seed: Seed) -> Self {
        Random { rng: pcg(seed) }
    }
}

impl Sampler for Random {
    fn name(&self) -> &'static str {
        ENTRY.name
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    #[inline]
    fn next_sample(&mut self) -> Point2 {
        let x = unit_f32_from_u32(self.rng.next_u32());
        let y = unit_f32_from_u32(self.rng.next_u32());
        Point2::new(x, y)
    }

    fn fill(&mut self, out: &mut [Point2]) {
        for p in out {
            *p = self.next_sample();
        }
    }
}

/// Independent uniform points in `[0,1)^D` (progressive).
#[derive(Clone, Debug)]
pub struct RandomNd {
    dims: u32,
    rng: Pcg32,
}

impl RandomNd {
    /// `dims >= 1` dimensions seeded by `seed` (the first two coordinates of each point are
    /// those of [`Random`] with the same seed only for `dims = 2`).
    pub fn new(dims: u32, seed: Seed) -> crate::Result<Self> {
        super::check_dims(ENTRY.name, dims, super::MAX_DIMENSIONS, "")?;
        Ok(RandomNd {
            dims,
            rng: pcg(seed),
        })
    }
}

impl SamplerNd for RandomNd {
    fn name(&self) -> &'static str {
        ENTRY.name
    }

    fn dimensions(&self) -> u32 {
        self.dims
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_point(&mut self, out: &mut [f32]) {
        for o in out.iter_mut().take(self.dims as usize) {
            *o = unit_f32_from_u32(self.rng.next_u32());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[cfg(feature = "std")] // the reference, `rand_pcg`, is a dependency of `std` only
    fn pcg32_gives_the_bits_of_rand_pcg() {
        use rand::Rng;
        let mut seeds = vec![
            (0, 0),
            (1, 2),
            (u64::MAX, u64::MAX),
            (0xcafe_f00d_d15e_a5e5, 0),
        ];
        seeds.extend((0..64).map(|s| (stream_seed(s, 0), stream_seed(s, 1))));
        for (state, stream) in seeds {
            let mut ours = Pcg32::new(state, stream);
            let mut theirs = rand_pcg::Pcg32::new(state, stream);
            for i in 0..4096 {
                assert_eq!(
                    ours.next_u32(),
                    theirs.next_u32(),
                    "{state:x} {stream:x}: draw {i}"
                );
            }
        }
    }
}
