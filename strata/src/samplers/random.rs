//! Independent uniform random points: the baseline every other pattern is measured against.
//!
//! Each coordinate is 24 random bits from PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast
//! Space-Efficient Statistically Good Algorithms for Random Number Generation"). The expected
//! power spectrum is flat (1 at every frequency but DC) and the integration variance falls as
//! `N^-1` whatever the integrand: no stratification, but trivially progressive and free of
//! correlation between dimensions. The generator is `rand_pcg`'s `Pcg32`.

use rand_core::Rng;
use rand_pcg::Pcg32;

use crate::float::unit_f32_from_u32;
use crate::hash::stream_seed;
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed};

/// The name of the sampler.
const NAME: &str = "random";

/// The generator of a seed.
fn pcg(seed: Seed) -> Pcg32 {
    Pcg32::new(stream_seed(0, seed.0), stream_seed(1, seed.0))
}

/// Independent uniform points in `[0,1)^2` (progressive: every prefix is an i.i.d. sample).
///
/// ```
/// use strata::{Sampler, Seed, samplers::Random};
/// let mut s = Random::new(Seed(42));
/// let p = s.next_sample();
/// assert!(p.iter().all(|v| (0.0..1.0).contains(v)));
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
        NAME
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    #[inline]
    fn next_sample(&mut self) -> Point2 {
        let x = unit_f32_from_u32(self.rng.next_u32());
        let y = unit_f32_from_u32(self.rng.next_u32());
        [x, y]
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
        super::check_dims(NAME, dims, super::MAX_DIMENSIONS, "")?;
        Ok(RandomNd {
            dims,
            rng: pcg(seed),
        })
    }
}

impl SamplerNd for RandomNd {
    fn name(&self) -> &'static str {
        NAME
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
