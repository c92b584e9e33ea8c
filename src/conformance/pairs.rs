//! The pair test: are two draws of a pixel paired as chance pairs them?
//!
//! Within a pixel sample, the values of different draws meet in one integrand, so the pairing
//! of sample `i` of one draw with sample `i` of another must be random. A padded sequence gets
//! that from a per-draw index shuffle, and a weak shuffle (one plain round of Burley's hash)
//! leaves a few pairs of draws in ten thousand nearly tied: their samples meet in the same
//! strata far more often than chance allows. The study takes, for every pixel and every pair of
//! its draws, the first coordinates of the two draws over the first `n` samples and counts them
//! on a `31 x 31` grid (prime, so that no dyadic stratification aligns with the cells);
//! Pearson's statistic of each pair is one case. The default, 390 pixels x 64 draws (every one
//! of the 2016 pairs of draws of each pixel) x 4096 samples, has 786,240 cases.
//!
//! # The bound
//!
//! With 4.3 expected points per cell and stratified marginals, Pearson's statistic is not
//! close to its chi-square law in the far tail, so the bound is calibrated on the ideal: an
//! exact random nested shuffle ([`Shuffle::Ideal`], a hash per node of the index's bit tree).
//! Over 32 seeds of the default study (25 million cases), the ideal's largest statistic was
//! 1317 and its median maximum per seed 1266; one plain round exceeded 1500 at every seed
//! tried. A study passes when no case exceeds [`PairStudy::BOUND`] = 1400.

use std::fmt;

use super::{Source, parallel_map};
use crate::{Error, Result};
use strata::Seed;
use strata::hash::mix64;
use strata::pixel::DrawKeys;
use strata::scramble::owen_scramble_rev;

/// The configuration of a pair study.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PairStudy {
    /// Pixels (`x = k mod 64`, `y = k / 64` for `k < pixels`), 1 to 4096.
    pub pixels: u32,
    /// 2D draws per pixel (dimensions `0, 2, ..., 2 draws - 2`; every pair of them is a case),
    /// 2 to 128.
    pub draws: u32,
    /// Samples per draw, 1024 to 65536 (the grid is `31 x 31` from 3844 on, coarser below).
    pub samples: u32,
    /// The seed.
    pub seed: Seed,
}

impl Default for PairStudy {
    /// 390 pixels, 64 draws, 4096 samples, seed 1: 786,240 pairs.
    fn default() -> Self {
        PairStudy {
            pixels: 390,
            draws: 64,
            samples: 4096,
            seed: Seed(1),
        }
    }
}

/// The result of a pair study.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PairReport {
    /// Cases (pixel, pair of draws).
    pub pairs: usize,
    /// The side of the grid.
    pub side: u32,
    /// The mean statistic.
    pub mean: f64,
    /// The largest statistic, and where (pixel, draws).
    pub max: f64,
    /// Where the largest statistic is.
    pub worst: String,
    /// How many cases exceed 1200, 1250, 1300 and 1400 (with a `31 x 31` grid).
    pub above: [(f64, usize); 4],
}

impl PairReport {
    /// True when no case exceeds [`PairStudy::BOUND`].
    pub fn passed(&self) -> bool {
        self.max <= PairStudy::BOUND
    }
}

impl fmt::Display for PairReport {
    /// One line: pairs, mean, max and where, the tail counts.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} pairs on {}x{} cells: mean {:.1}, max {:.0} ({})",
            self.pairs, self.side, self.side, self.mean, self.max, self.worst
        )?;
        for (t, n) in self.above {
            write!(f, ", > {t:.0}: {n}")?;
        }
        Ok(())
    }
}

impl PairStudy {
    /// The largest statistic a case may have (calibrated on the ideal nested shuffle: see
    /// [`Shuffle::Ideal`] and the `conformance` module docs).
    pub const BOUND: f64 = 1400.0;

    /// Checks the configuration; the error says what is allowed.
    pub fn check(&self) -> Result<()> {
        let ctx = "PairStudy::check";
        if !(1..=4096).contains(&self.pixels) {
            return Err(Error::parameter(ctx, "pixels", self.pixels, "1 to 4096"));
        }
        if !(2..=128).contains(&self.draws) {
            return Err(Error::parameter(ctx, "draws", self.draws, "2 to 128"));
        }
        if !(1024..=65536).contains(&self.samples) {
            return Err(Error::parameter(
                ctx,
                "samples",
                self.samples,
                "1024 to 65536",
            ));
        }
        Ok(())
    }

    /// Runs the study on `source` (its dimensions `2k` are the first coordinates of the draws).
    pub fn run(&self, source: &(impl Source + ?Sized)) -> Result<PairReport> {
        self.check()?;
        let (n, d) = (self.samples as usize, self.draws as usize);
        let side = super::grid_side(n);
        let pixels: Vec<u32> = (0..self.pixels).collect();
        let per_pixel: Vec<Vec<(f64, usize, usize)>> = parallel_map(&pixels, |&k| {
            let pixel = [k % 64, k / 64];
            let dims = 2 * self.draws;
            let mut values = vec![0f32; n * dims as usize];
            source.fill(pixel, self.samples, dims, self.seed, &mut values);
            let mut cells = vec![0u8; d * n];
            for (i, row) in values.chunks_exact(dims as usize).enumerate() {
                for a in 0..d {
                    let c = (row[2 * a] as f64 * side as f64) as usize;
                    cells[a * n + i] = c.min(side - 1) as u8;
                }
            }
            let e = n as f64 / (side * side) as f64;
            let mut counts = vec![0u32; side * side];
            let mut out = Vec::with_capacity(d * (d - 1) / 2);
            for a in 0..d {
                for b in a + 1..d {
                    counts.iter_mut().for_each(|c| *c = 0);
                    let (ca, cb) = (&cells[a * n..(a + 1) * n], &cells[b * n..(b + 1) * n]);
                    for (&x, &y) in ca.iter().zip(cb) {
                        counts[x as usize * side + y as usize] += 1;
                    }
                    let chi: f64 = counts.iter().map(|&c| (c as f64 - e).powi(2) / e).sum();
                    out.push((chi, a, b));
                }
            }
            out
        });
        let mut report = PairReport {
            pairs: 0,
            side: side as u32,
            mean: 0.0,
            max: f64::NEG_INFINITY,
            worst: String::new(),
            above: [(1200.0, 0), (1250.0, 0), (1300.0, 0), (1400.0, 0)],
        };
        let mut sum = 0.0;
        for (k, cases) in per_pixel.iter().enumerate() {
            for &(chi, a, b) in cases {
                report.pairs += 1;
                sum += chi;
                for (t, count) in report.above.iter_mut() {
                    *count += (chi > *t) as usize;
                }
                if chi > report.max {
                    report.max = chi;
                    report.worst = format!("pixel {},{} draws {a},{b}", k % 64, k / 64);
                }
            }
        }
        report.mean = sum / report.pairs as f64;
        Ok(report)
    }
}

/// The index shuffles the pair test compares, on Sobol' dimension 0 (van der Corput: a
/// bijection of the shuffled index, so the pairing of two draws is all the test sees), keyed
/// as the adapter keys its draws ([`strata::pixel::DrawKeys`]); the value is Owen-scrambled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Shuffle {
    /// An exact random nested shuffle: bit `j` of the index flipped by a hash of the draw's keys,
    /// `j` and the bits above it (32 hashes per value). The reference.
    Ideal,
    /// One plain round of the hash (Burley 2020; sobol_burley, pbrt-v4): the counterexample.
    PlainRound,
    /// Two plain rounds with independent keys (what the adapter shipped before).
    TwoRounds,
    /// What the adapter ships: the seeded XOR-multiply, then one round
    /// ([`strata::scramble::shuffle_rev`]).
    Shipped,
}

impl Shuffle {
    /// Every shuffle, reference first.
    pub const ALL: [Shuffle; 4] = [
        Shuffle::Ideal,
        Shuffle::PlainRound,
        Shuffle::TwoRounds,
        Shuffle::Shipped,
    ];

    /// A short name.
    pub fn name(self) -> &'static str {
        match self {
            Shuffle::Ideal => "ideal nested shuffle",
            Shuffle::PlainRound => "one plain round",
            Shuffle::TwoRounds => "two plain rounds",
            Shuffle::Shipped => "one round + seeded XOR-multiply (shipped)",
        }
    }

    /// The shuffled index (plain bit order) of `index` under draw keys `k`.
    fn apply(self, k: &DrawKeys, index: u32) -> u32 {
        let r = index.reverse_bits();
        match self {
            Shuffle::Ideal => {
                let mut out = 0u32;
                for j in 0..32u32 {
                    let above = index.checked_shr(j + 1).unwrap_or(0);
                    let node = (k.h as u64) << 32 | k.e as u64;
                    let h = mix64(node ^ mix64((j as u64) << 40 | above as u64));
                    out |= (((index >> j) & 1) ^ (h as u32 & 1)) << j;
                }
                out
            }
            Shuffle::PlainRound => owen_scramble_rev(r, k.h).reverse_bits(),
            Shuffle::TwoRounds => {
                owen_scramble_rev(owen_scramble_rev(r, k.h), k.e | 1).reverse_bits()
            }
            Shuffle::Shipped => strata::scramble::shuffle_rev(r, k.e, k.h).reverse_bits(),
        }
    }
}

impl Source for Shuffle {
    /// Dimension `2k` is the first coordinate of draw `k`: van der Corput at the shuffled
    /// index, Owen-scrambled; odd dimensions are 0.
    fn value(&self, pixel: [u32; 2], index: u64, dim: u32, seed: Seed) -> f32 {
        if dim % 2 == 1 {
            return 0.0;
        }
        self.draw(&DrawKeys::of(pixel, dim, seed), index as u32)
    }

    fn fill(&self, pixel: [u32; 2], spp: u32, dims: u32, seed: Seed, out: &mut [f32]) {
        let draws: Vec<DrawKeys> = (0..dims).map(|d| DrawKeys::of(pixel, d, seed)).collect();
        for (i, row) in out
            .chunks_exact_mut(dims as usize)
            .take(spp as usize)
            .enumerate()
        {
            for (d, v) in row.iter_mut().enumerate() {
                *v = if d % 2 == 1 {
                    0.0
                } else {
                    self.draw(&draws[d], i as u32)
                };
            }
        }
    }
}

impl Shuffle {
    /// The first coordinate of the draw with keys `k` at `index`.
    fn draw(self, k: &DrawKeys, index: u32) -> f32 {
        let i = self.apply(k, index);
        strata::float::unit_f32_from_u32(owen_scramble_rev(i, k.v[0]).reverse_bits())
    }
}
