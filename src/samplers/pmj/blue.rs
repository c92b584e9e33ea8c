//! `pmj02bn`: a blue-noise (0,2)-sequence, made by choosing the flags of its Owen scrambling.
//!
//! Every nested uniform (Owen) scrambling of the Sobol' (0,2)-sequence is again a
//! (0,2)-sequence: every prefix of `2^m` points, and every aligned block `[k 2^m, (k+1) 2^m)`,
//! is a (0,m,2)-net. The scrambling is a binary tree of flags per coordinate: the flag at depth
//! `l` and node `u` flips digit `l + 1` of every point whose first `l` digits are `u`. Random
//! flags give the usual Owen-scrambled Sobol' points (white noise at coarse scales); the
//! structure of the sequence is *chosen* here instead (the structural freedom of Christensen,
//! Kensler and Kilpatrick 2018's pmj02bn, in the form of the scrambling tree that Doignies,
//! Coeurjolly and Ostromoukhov 2024 optimise for nets):
//!
//! * the objective is a sum over the prefixes `2^k`, `k = 4 .. m`, of a Gaussian repulsion energy
//!   `sum exp(-d^2 / (2 sigma_k^2))` with `sigma_k = SIGMA r_max(2^k)`, each prefix weighted by
//!   `2^-k` (energy per point), so no prefix is sacrificed for the last one;
//! * coordinate descent: each flag at depths `1 ..= m` (depth 0 is a half-period translation,
//!   which does not change toroidal distances), in x and in y, is flipped when that lowers the
//!   objective, exactly (the moved points' energies are recomputed against neighbour grids of
//!   every prefix); sweeps repeat until none keeps a flip or `--iterations` sweeps have run;
//! * deeper flags (finer than the optimised count) stay random, so the sequence continues past
//!   `2^m` as an Owen-scrambled (0,2)-sequence.
//!
//! Ahmed and Wonka (2021) note that (0,2)-sequences are much less optimisable than nets, since
//! a coarse choice serves every later prefix. Choosing flags across all prefixes at once is what
//! makes it work: with 32 seeds, mean nearest-neighbour distances are 1.1-1.2x those of `pmj02`
//! at 64 to 16384 points (`docs/results.md`), where best candidate inside the single valid
//! stratum left by `pmj02` reached 0.99-1.06x.
//!
//! Guaranteed: the (0,2)-sequence property above (tested on every prefix and aligned block).
//! Cost: the optimisation, once per sequence, is `O(N log N)` for the intended count `N`
//! (about 0.1 s at 1024 points, 2 s at 16384; counts above [`MAX_OPTIMIZED_LOG2`] are optimised
//! up to `2^16`); each sample is then computed from the flags in `O(32)`.

use super::{MAX_SEQUENCE_LEN, pmj_grids};
use crate::error::{Error, Result};
use crate::float::unit_f32_from_u32;
use crate::grid::relative_radius_max;
use crate::hash::{hash_u64, stream_seed};
use crate::registry::{BlueNoise, CountRule, Entry, Family, Parameter, ParameterSpec, Rates};
use crate::sampler::{Point2, Progression, Sampler, Seed, StrataGrid};
use crate::samplers::{Epochs, sobol};

/// The kernel width relative to `r_max` of each prefix.
pub(crate) const SIGMA: f64 = 0.5;

/// The smallest prefix `2^k` in the objective.
pub(crate) const FIRST_PREFIX_LOG2: u32 = 4;

/// The default cap on the sweeps over all flags (they usually stop earlier).
pub const DEFAULT_SWEEPS: u32 = 4;

/// The most sweeps accepted.
pub const MAX_SWEEPS: u32 = 1000;

/// The largest optimised prefix, `2^16` points.
pub const MAX_OPTIMIZED_LOG2: u32 = 16;

/// The registry entry of `pmj02bn`.
pub(crate) const ENTRY: Entry = Entry {
    name: "pmj02bn",
    description: "a (0,2)-sequence whose Owen-scrambling flags are chosen for blue noise at every power-of-two prefix up to N (--iterations K caps the sweeps, default 4)",
    paper: "Christensen et al. 2018; Doignies et al. 2024",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[ParameterSpec {
        parameter: Parameter::Iterations,
        default: DEFAULT_SWEEPS as f64,
        allowed: "0 to 1000",
    }],
    promise: "(0,m,2)-net at every `2^m` prefix and aligned block, blue noise up to `N`",
    rates: Rates::NETS,
    expensive: false,
    blue_noise: Some(BlueNoise::published(
        "none found (Christensen et al. 2018 could not be checked here)",
    )),
    build: |p| {
        let k = p.iterations.unwrap_or(DEFAULT_SWEEPS);
        Ok(Box::new(Pmj02Bn::new(p.sampler_seed(), p.count, k)?))
    },
    nd: None,
};

/// The scrambling flags of both coordinates: explicit up to a depth, hashed below it.
#[derive(Clone, Debug)]
struct Flags {
    /// Depths `0 .. depth` are stored, node `u` of depth `l` at bit `2^l - 1 + u`.
    depth: u32,
    bits: [Vec<u64>; 2],
    keys: [u64; 2],
}

impl Flags {
    /// Random flags (each a hash of the key, the depth and the node), stored to `depth`.
    fn random(key: u64, depth: u32) -> Self {
        let keys = [stream_seed(key, 0x0b10), stream_seed(key, 0x0b11)];
        let len = (1usize << depth).div_ceil(64);
        let mut bits = [vec![0u64; len], vec![0u64; len]];
        for (ax, b) in bits.iter_mut().enumerate() {
            for l in 0..depth {
                for u in 0..1u32 << l {
                    if Self::hashed(keys[ax], l, u) {
                        let i = (1usize << l) - 1 + u as usize;
                        b[i >> 6] |= 1 << (i & 63);
                    }
                }
            }
        }
        Flags { depth, bits, keys }
    }

    fn hashed(key: u64, l: u32, node: u32) -> bool {
        hash_u64(key, (u64::from(l) << 32) | u64::from(node)) & 1 == 1
    }

    fn flip(&mut self, ax: usize, l: u32, node: u32) {
        let i = (1usize << l) - 1 + node as usize;
        self.bits[ax][i >> 6] ^= 1 << (i & 63);
    }

    /// Coordinate `ax` of a point of the plain sequence, scrambled.
    fn scramble(&self, ax: usize, v: u32) -> u32 {
        let mut out = v;
        for l in 0..32u32 {
            let node = if l == 0 { 0 } else { v >> (32 - l) };
            let f = if l < self.depth {
                let i = (1usize << l) - 1 + node as usize;
                self.bits[ax][i >> 6] >> (i & 63) & 1 == 1
            } else {
                Self::hashed(self.keys[ax], l, node)
            };
            if f {
                out ^= 0x8000_0000 >> l;
            }
        }
        out
    }
}

/// The blue-noise (0,2)-sequence (progressive).
///
/// ```
/// use strata::{Sampler, Seed, samplers::Pmj02Bn};
/// let mut s = Pmj02Bn::new(Seed(3), 256, 4)?;
/// let pts: Vec<_> = (0..16).map(|_| s.next_sample()).collect();
/// let mut cells = [0; 16]; // a (0,4,2)-net: one point in each 4 x 4 cell
/// for p in &pts {
///     cells[(p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize] += 1;
/// }
/// assert!(cells.iter().all(|&c| c == 1));
/// # Ok::<(), strata::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Pmj02Bn {
    epochs: Epochs,
    log2: u32,
    sweeps: u32,
    flags: Flags,
}

impl Pmj02Bn {
    /// The sequence seeded by `seed`, optimised for the prefixes up to `count` points (rounded
    /// up to a power of two, at least 16; above `2^16` the optimisation covers `2^16`), with at
    /// most `sweeps` sweeps (0 to [`MAX_SWEEPS`]; 0 leaves a random Owen scrambling).
    pub fn new(seed: Seed, count: u64, sweeps: u32) -> Result<Self> {
        if sweeps > MAX_SWEEPS {
            return Err(Error::parameter(
                ENTRY.name,
                "iterations",
                sweeps,
                format!("0 to {MAX_SWEEPS} sweeps"),
            ));
        }
        // (a count past 2^63 has no next power of two in u64: it optimises the longest prefix)
        let log2 = count
            .max(1)
            .checked_next_power_of_two()
            .map_or(64, u64::trailing_zeros)
            .clamp(FIRST_PREFIX_LOG2, MAX_OPTIMIZED_LOG2);
        let epochs = Epochs::new(seed, MAX_SEQUENCE_LEN);
        let flags = optimize(epochs.key(0), log2, sweeps);
        Ok(Pmj02Bn {
            epochs,
            log2,
            sweeps,
            flags,
        })
    }

    /// Sample `index` as 32-bit fixed point.
    pub fn sample_fixed(&self, index: u32) -> [u32; 2] {
        let x = sobol::sobol_u32(index, 0).unwrap_or(0);
        let y = sobol::sobol_u32(index, 1).unwrap_or(0);
        [self.flags.scramble(0, x), self.flags.scramble(1, y)]
    }

    /// Sample `index`.
    pub fn sample(&self, index: u32) -> Point2 {
        let p = self.sample_fixed(index);
        Point2::new(unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1]))
    }
}

impl Sampler for Pmj02Bn {
    fn name(&self) -> &'static str {
        ENTRY.name
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let (i, new_epoch) = self.epochs.advance();
        if let Some(key) = new_epoch {
            // a new, independent sequence
            self.flags = optimize(key, self.log2, self.sweeps);
        }
        self.sample(i as u32)
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        pmj_grids(n, true)
    }
}

/// One prefix's neighbour grid and kernel.
struct Prefix {
    len: usize,
    res: usize,
    cells: Vec<Vec<u32>>,
    inv_two_sigma2: f64,
    cutoff2: f64,
    weight: f64,
}

impl Prefix {
    fn cell(&self, p: [u32; 2]) -> usize {
        let c = |v: u32| ((u64::from(v) * self.res as u64) >> 32) as usize;
        c(p[1]) * self.res + c(p[0])
    }
}

fn unit(v: u32) -> f64 {
    f64::from(v) * (1.0 / 4_294_967_296.0)
}

fn torus_d2(a: [u32; 2], b: [u32; 2]) -> f64 {
    // wrapping differences are toroidal: the shorter way round is min(d, 2^32 - d)
    let d = |u: u32, v: u32| {
        let t = u.wrapping_sub(v);
        unit(t.min(t.wrapping_neg()))
    };
    let (dx, dy) = (d(a[0], b[0]), d(a[1], b[1]));
    dx * dx + dy * dy
}

/// Coordinate descent on the flags of the first `2^m` points (see the module docs).
fn optimize(key: u64, m: u32, sweeps: u32) -> Flags {
    let depth = m + 1;
    let mut flags = Flags::random(key, depth);
    if sweeps == 0 {
        return flags;
    }
    let n = 1usize << m;
    let base: Vec<[u32; 2]> = (0..n as u32)
        .map(|i| {
            [
                sobol::sobol_u32(i, 0).unwrap_or(0),
                sobol::sobol_u32(i, 1).unwrap_or(0),
            ]
        })
        .collect();
    let mut pos: Vec<[u32; 2]> = base
        .iter()
        .map(|b| [flags.scramble(0, b[0]), flags.scramble(1, b[1])])
        .collect();
    // the points in the order of each plain coordinate: a node's points are contiguous
    let order: [Vec<u32>; 2] = [0, 1].map(|ax| {
        let mut o: Vec<u32> = (0..n as u32).collect();
        o.sort_unstable_by_key(|&i| base[i as usize][ax]);
        o
    });
    let mut prefixes: Vec<Prefix> = (FIRST_PREFIX_LOG2.min(m)..=m)
        .map(|k| {
            let len = 1usize << k;
            let sigma = SIGMA * relative_radius_max(len);
            let cutoff = 3.0 * sigma;
            let res = ((1.0 / cutoff) as usize).max(1);
            let mut p = Prefix {
                len,
                res,
                cells: vec![Vec::new(); res * res],
                inv_two_sigma2: 1.0 / (2.0 * sigma * sigma),
                cutoff2: cutoff * cutoff,
                weight: 1.0 / len as f64,
            };
            for (i, q) in pos[..len].iter().enumerate() {
                let c = p.cell(*q);
                p.cells[c].push(i as u32);
            }
            p
        })
        .collect();
    for _ in 0..sweeps {
        let mut kept = 0usize;
        for l in 1..depth {
            let per = n >> l;
            for ax in 0..2 {
                for u in 0..1u32 << l {
                    let s = &order[ax][u as usize * per..(u as usize + 1) * per];
                    let inside = |j: usize| base[j][ax] >> (32 - l) == u;
                    let before = energy(s, &pos, &prefixes, &inside);
                    flip(s, ax, l, &mut pos, &mut prefixes);
                    let after = energy(s, &pos, &prefixes, &inside);
                    if after < before {
                        flags.flip(ax, l, u);
                        kept += 1;
                    } else {
                        flip(s, ax, l, &mut pos, &mut prefixes);
                    }
                }
            }
        }
        if kept == 0 {
            break;
        }
    }
    flags
}

/// The objective's part that involves the points `s` (each pair inside `s` once).
fn energy(s: &[u32], pos: &[[u32; 2]], prefixes: &[Prefix], inside: &dyn Fn(usize) -> bool) -> f64 {
    let mut total = 0.0;
    for p in prefixes {
        let (mut outer, mut inner) = (0.0, 0.0);
        let res = p.res as isize;
        let span: &[isize] = match res {
            1 => &[0],
            2 => &[0, 1],
            _ => &[-1, 0, 1],
        };
        for &i in s {
            let i = i as usize;
            if i >= p.len {
                continue;
            }
            let c = p.cell(pos[i]);
            let (cx, cy) = ((c % p.res) as isize, (c / p.res) as isize);
            for &dy in span {
                let y = (cy + dy).rem_euclid(res) as usize;
                for &dx in span {
                    let x = (cx + dx).rem_euclid(res) as usize;
                    for &j in &p.cells[y * p.res + x] {
                        let j = j as usize;
                        if j == i {
                            continue;
                        }
                        let d2 = torus_d2(pos[i], pos[j]);
                        if d2 < p.cutoff2 {
                            let e = libm::exp(-d2 * p.inv_two_sigma2);
                            if inside(j) {
                                inner += e;
                            } else {
                                outer += e;
                            }
                        }
                    }
                }
            }
        }
        total += p.weight * (outer + 0.5 * inner);
    }
    total
}

/// Flips digit `l + 1` of coordinate `ax` of the points `s` (the effect of one flag), keeping
/// the grids current. Its own inverse.
fn flip(s: &[u32], ax: usize, l: u32, pos: &mut [[u32; 2]], prefixes: &mut [Prefix]) {
    for &i in s {
        let i = i as usize;
        let mut q = pos[i];
        q[ax] ^= 0x8000_0000 >> l;
        for p in prefixes.iter_mut().filter(|p| i < p.len) {
            let (from, to) = (p.cell(pos[i]), p.cell(q));
            if from != to {
                let list = &mut p.cells[from];
                if let Some(k) = list.iter().position(|&x| x as usize == i) {
                    list.swap_remove(k);
                }
                p.cells[to].push(i as u32);
            }
        }
        pos[i] = q;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_sweeps_is_a_random_owen_scrambling_and_sweeps_change_it() {
        let a = Pmj02Bn::new(Seed(1), 256, 0).unwrap();
        let b = Pmj02Bn::new(Seed(1), 256, 2).unwrap();
        assert_ne!(
            (0..256).map(|i| a.sample_fixed(i)).collect::<Vec<_>>(),
            (0..256).map(|i| b.sample_fixed(i)).collect::<Vec<_>>()
        );
        assert!(Pmj02Bn::new(Seed(1), 256, MAX_SWEEPS + 1).is_err());
    }

    #[test]
    fn toroidal_distance_takes_the_short_way() {
        let d = torus_d2([0, 0], [u32::MAX, 1 << 31]);
        assert!((d - 0.25).abs() < 1e-9, "{d}");
    }
}
