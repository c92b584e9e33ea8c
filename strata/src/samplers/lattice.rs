//! Rank-1 lattices: every point a multiple of one generating vector, modulo 1.
//!
//! * [`Lattice`] / [`LatticeNd`]: the extensible lattice sequence in base 2,
//!   `x_i = frac(phi_2(i) z + shift)`, with `phi_2` the van der Corput radical inverse: the
//!   first `2^m` points of the sequence are the rank-1 lattice of `2^m` points with generating
//!   vector `z`, at every `m`, so the sequence is progressive. `z` is the embedded vector of
//!   Cools, Kuo and Nuyens, "Constructing embedded lattice rules for multivariate integration"
//!   (SIAM J. Sci. Comput. 28, 2006), file `lattice-32001-1024-1048576.3600` on Frances Kuo's
//!   page (order-2 weights, embedded for `2^10 <= N <= 2^20`): its first 100 components.
//!   In fixed point, `phi_2(i) 2^32` is the bit reversal of `i`, so a coordinate is one
//!   wrapping multiply and add.
//! * [`Fibonacci`]: the 2D Fibonacci lattice, `N = F_k` points with `z = (1, F_{k-1})`
//!   (Korobov form with the best 2D figure of merit, Niederreiter 1992), a fixed count.
//!
//! Randomization: a toroidal shift per seed (Cranley and Patterson 1976), which keeps a
//! lattice a lattice: unbiased, and every 1D projection of `N = 2^m` (or `F_k`) points has one
//! point per `1/N` stratum. Belcour and Heitz ("Lessons Learned and Improvements when Building
//! Screen-Space Samplers with Blue-Noise Error Distribution", 2021) report lattices on par
//! with Owen-scrambled Sobol' for rendering once padded: `render` measures it.

use super::{Blocks, Epochs, Fixed, check_dims};
use crate::counts::{CountRule, fibonacci_numbers};
use crate::error::Result;
use crate::float::unit_f32_from_u32;
use crate::hash::{hash_u64, stream_seed};
use crate::prelude::*;
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};
use crate::scramble::Pair;

/// The name of the Fibonacci lattice sampler.
const FIBONACCI: &str = "fibonacci";

/// The first 100 components of Cools, Kuo and Nuyens' embedded base-2 generating vector
/// (`lattice-32001-1024-1048576.3600`); all odd.
pub(crate) const GENERATOR: [u32; 100] = [
    1, 182667, 469891, 498753, 110745, 446247, 250185, 118627, 245333, 283199, 408519, 391023,
    246327, 126539, 399185, 461527, 300343, 69681, 516695, 436179, 106383, 238523, 413283, 70841,
    47719, 300129, 113029, 123925, 410745, 211325, 17489, 511893, 40767, 186077, 519471, 255369,
    101819, 243573, 66189, 152143, 503455, 113217, 132603, 463967, 297717, 157383, 224015, 502917,
    36237, 94049, 170665, 79397, 123963, 223451, 323871, 303633, 98567, 318855, 494245, 477137,
    177975, 64483, 26695, 88779, 94497, 239429, 381007, 110205, 339157, 73397, 407559, 181791,
    442675, 301397, 32569, 147737, 189949, 138655, 350241, 63371, 511925, 515861, 434045, 383435,
    249187, 492723, 479195, 84589, 99703, 239831, 269423, 182241, 61063, 130789, 143095, 471209,
    139019, 172565, 487045, 304803,
];

/// The registered name of the lattice.
const LATTICE_NAME: &str = "lattice";

/// Dimensions 0 and 1 of the lattice point whose radical inverse is `r` (in 32-bit fixed point
/// `phi_2(i) 2^32` is the bit reversal of `i`), shifted on the torus by `shift`: the point
/// function of [`Lattice`] and of the path-tracer adapter's `lattice`.
#[inline(always)]
pub(crate) fn point_lanes<P: Pair>(r: u32, shift: P) -> P {
    P::splat(r)
        .mul(P::new([GENERATOR[0], GENERATOR[1]]))
        .add(shift)
}

/// The toroidal shift of dimension `d` for a key (32-bit fixed point).
#[inline]
fn shift(key: u64, d: u32) -> u32 {
    (hash_u64(d as u64, key) >> 32) as u32
}

/// The extensible rank-1 lattice in 2D (dimensions 0-1 of [`LatticeNd`]), progressive.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Lattice};
/// let mut s = Lattice::new(Seed(1));
/// let mut xs: Vec<u32> = (0..16).map(|_| (s.next_sample()[0] * 16.0) as u32).collect();
/// xs.sort();
/// assert_eq!(xs, (0..16).collect::<Vec<_>>()); // one point per 1/16 in x
/// ```
#[derive(Clone, Debug)]
pub struct Lattice {
    epochs: Epochs,
    key: u64,
}

impl Lattice {
    /// The lattice sequence shifted by `seed`.
    pub fn new(seed: Seed) -> Self {
        let epochs = Epochs::new(1 << 32, seed);
        Lattice {
            key: epochs.key(0),
            epochs,
        }
    }

    /// Point `index`, without changing the stream position.
    pub fn sample(&self, index: u32) -> Point2 {
        let shifts = [shift(self.key, 0), shift(self.key, 1)];
        let [x, y] = point_lanes(index.reverse_bits(), shifts).unit_f32();
        [x, y]
    }
}

impl Sampler for Lattice {
    fn name(&self) -> &'static str {
        LATTICE_NAME
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let (i, new_epoch) = self.epochs.advance();
        if let Some(key) = new_epoch {
            self.key = key;
        }
        self.sample(i as u32)
    }

    /// Constant time: the epoch and the index, re-keyed when the epoch changes.
    fn skip(&mut self, n: u64) -> bool {
        if let Some(e) = self.epochs.skip(n) {
            self.key = self.epochs.key(e);
        }
        true
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        if n.is_power_of_two() && n <= 1 << 31 {
            StrataGrid::axes(n as u32)
        } else {
            Vec::new()
        }
    }
}

/// The extensible rank-1 lattice in `D` dimensions (1 to 100), progressive.
#[derive(Clone, Debug)]
pub struct LatticeNd {
    epochs: Epochs,
    key: u64,
    dims: u32,
}

impl LatticeNd {
    /// `dims` dimensions (1 to 100), shifted by `seed`.
    pub fn new(dims: u32, seed: Seed) -> Result<Self> {
        check_dims(
            LATTICE_NAME,
            dims,
            GENERATOR.len() as u32,
            " (the published generating vector's components)",
        )?;
        let epochs = Epochs::new(1 << 32, seed);
        Ok(LatticeNd {
            key: epochs.key(0),
            epochs,
            dims,
        })
    }
}

impl SamplerNd for LatticeNd {
    fn name(&self) -> &'static str {
        LATTICE_NAME
    }

    fn dimensions(&self) -> u32 {
        self.dims
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_point(&mut self, out: &mut [f32]) {
        let (i, new_epoch) = self.epochs.advance();
        if let Some(key) = new_epoch {
            self.key = key;
        }
        let r = (i as u32).reverse_bits();
        for (d, (o, z)) in out
            .iter_mut()
            .zip(GENERATOR)
            .take(self.dims as usize)
            .enumerate()
        {
            *o = unit_f32_from_u32(r.wrapping_mul(z).wrapping_add(shift(self.key, d as u32)));
        }
    }
}

/// The Fibonacci lattice: `N = F_k` points `(i / N, frac(i F_(k-1) / N))` shifted per set.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Fibonacci};
/// let mut s = Fibonacci::new(89, Seed(2)).unwrap();
/// let p = s.next_sample();
/// assert!(p[0] < 1.0 && p[1] < 1.0);
/// assert!(Fibonacci::new(90, Seed(2)).is_err()); // 89 or 144
/// ```
#[derive(Clone, Debug)]
pub struct Fibonacci {
    n: u32,
    z: u32,
    shift: [u64; 2],
}

impl Fibonacci {
    /// Sets of `count` points, a Fibonacci number (1, 2, 3, 5, 8, ..., at most `2^31`).
    pub fn new(count: u64, seed: Seed) -> Result<Fixed<Self>> {
        let n = CountRule::Fibonacci.check(FIBONACCI, count)?;
        let z = fibonacci_numbers()
            .take_while(|&f| f < n as u64)
            .last()
            .unwrap_or(1) as u32;
        Fixed::new(
            Fibonacci {
                n,
                z,
                shift: [0, 0],
            },
            seed,
        )
    }
}

impl Blocks for Fibonacci {
    const NAME: &'static str = FIBONACCI;

    fn set_len(&self) -> u32 {
        self.n
    }

    fn begin_block(&mut self, key: u64) {
        self.shift = [stream_seed(0, key) >> 32, stream_seed(1, key) >> 32];
    }

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        // (i z mod N) / N + shift, in 32-bit fixed point: the stratum index times 2^32 / N,
        // exact to a unit of 2^-32, plus the shift
        let n = self.n as u64;
        let coord = |k: u64, s: u64| {
            let v = ((k << 32) / n + s) & 0xffff_ffff;
            unit_f32_from_u32(v as u32)
        };
        let y = (i as u64 * self.z as u64) % n;
        [coord(i as u64, self.shift[0]), coord(y, self.shift[1])]
    }

    fn grids(&self) -> Vec<StrataGrid> {
        StrataGrid::axes(self.n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generator_is_odd_and_the_prefixes_are_lattices() {
        assert!(GENERATOR.iter().all(|z| z % 2 == 1));
        // the first 2^m points of every dimension are the multiples of z / 2^m, i.e. a
        // permutation of the 2^m strata (z odd)
        let mut s = LatticeNd::new(8, Seed(3)).unwrap();
        let m = 10;
        let mut pts = vec![0.0f32; 8 << m];
        s.fill(&mut pts);
        for d in 0..8 {
            let mut seen = vec![false; 1 << m];
            for i in 0..1 << m {
                let cell = (pts[i * 8 + d] as f64 * (1 << m) as f64) as usize;
                assert!(!seen[cell], "dimension {d}: stratum {cell} twice");
                seen[cell] = true;
            }
        }
    }

    #[test]
    fn fibonacci_counts_and_strata() {
        let f: Vec<u64> = fibonacci_numbers().take(10).collect();
        assert_eq!(f, [1, 2, 3, 5, 8, 13, 21, 34, 55, 89]);
        let mut s = Fibonacci::new(144, Seed(1)).unwrap();
        assert_eq!(s.z, 89);
        let mut cols = vec![0; 144];
        let mut rows = vec![0; 144];
        for _ in 0..144 {
            let p = s.next_sample();
            cols[(p[0] as f64 * 144.0) as usize] += 1;
            rows[(p[1] as f64 * 144.0) as usize] += 1;
        }
        assert!(cols.iter().chain(&rows).all(|&c| c == 1));
    }
}
