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
//! * the objective is a sum over the prefixes `2^k`, `k = 4 .. m`, of a repulsion energy
//!   `sum (1 - d^2 / c_k^2)^4` over the pairs closer than `c_k = sqrt(8) sigma_k`, with
//!   `sigma_k = SIGMA r_max(2^k)` (`SIGMA = 0.4`; the kernel is the Gaussian of width `sigma_k`
//!   to second order, with compact support), each prefix weighted by `2^-k` (energy per
//!   point), so no prefix is sacrificed for the last one;
//! * coordinate descent: each flag at depths `1 ..= m` (depth 0 is a half-period translation,
//!   which does not change toroidal distances), coarse to fine, in x and in y, is flipped when
//!   that lowers the objective, exactly (the moved points' energies are recomputed against a
//!   neighbour grid of every prefix); sweeps repeat until none keeps a flip or `--sweeps`
//!   sweeps have run (default 2);
//! * each prefix's grid has the elementary intervals `2^-ceil(k/2) x 2^-floor(k/2)` as cells:
//!   since the prefix is a (0,k,2)-net under every scrambling, every cell holds exactly one
//!   point, so the grid is a flat array of positions (padded by two wrapped columns per row),
//!   a point's neighbours are the 5 x 5 (or 5 x 3) cells around it, and a flip's update is
//!   writing the moved points into their new cells;
//! * deeper flags (finer than the optimised count) stay random, so the sequence continues past
//!   `2^m` as an Owen-scrambled (0,2)-sequence.
//!
//! Ahmed and Wonka (2021) note that (0,2)-sequences are much less optimisable than nets, since
//! a coarse choice serves every later prefix. Choosing flags across all prefixes at once is what
//! makes it work: with 32 seeds, mean nearest-neighbour distances over `r_max` are 0.754, 0.728,
//! 0.708, 0.703 and 0.702 at 64, 256, 1024, 4096 and 16384 points, 1.16-1.24x those of `pmj02`
//! (0.61), where best candidate inside the single valid stratum left by `pmj02` reached
//! 0.99-1.06x; the `pmj` crate's best-candidate pmj02bn (99 retries) reaches 0.60 at 4096.
//!
//! Guaranteed: the (0,2)-sequence property above (tested on every prefix and aligned block).
//! Cost: the optimisation, once per sequence, is `O(N log N)` for the intended count `N`
//! (4096 points: 0.70 G instructions, 4.1x the `pmj` crate's best candidate, and 4.3x its
//! time in interleaved runs, about 40 ms on a quiet core; `tools/pmj-peer`); counts above [`MAX_OPTIMIZED_LOG2`] are optimised up to `2^16`); each sample is
//! then computed from the flags in `O(32)`.

use super::{MAX_SEQUENCE_LEN, pmj_grids};
use crate::entry::{BlueNoise, Built, CountRule, Entry, Family, ParameterSpec, Rates};
use crate::error::{Error, Result};
use crate::float::unit_f32_from_u32;
use crate::grid::relative_radius_max;
use crate::hash::{hash_u64, stream_seed};
use crate::sampler::{Point2, Progression, Sampler, Seed, StrataGrid};
use crate::samplers::{Epochs, sobol};

/// The kernel width relative to `r_max` of each prefix.
pub(crate) const SIGMA: f64 = 0.4;

/// The kernel's support relative to `SIGMA r_max`: `(1 - d^2/c^2)^4` is `exp(-4 d^2/c^2)` to
/// second order, the Gaussian of width `sigma` when `c = sqrt(8) sigma`.
pub(crate) const CUTOFF: f64 = 2.828_427_124_746_19;

/// The smallest prefix `2^k` in the objective.
pub(crate) const FIRST_PREFIX_LOG2: u32 = 4;

/// The default cap on the sweeps over all flags (they usually stop earlier).
pub const DEFAULT_SWEEPS: u32 = 2;

/// The most sweeps accepted.
pub const MAX_SWEEPS: u32 = 1000;

/// The largest optimised prefix, `2^16` points.
pub const MAX_OPTIMIZED_LOG2: u32 = 16;

/// The registry entry of `pmj02bn`.
pub(crate) const ENTRY: Entry = Entry {
    name: "pmj02bn",
    description: "a (0,2)-sequence whose Owen-scrambling flags are chosen for blue noise at every power-of-two prefix up to N (--sweeps K caps them, default 2)",
    paper: "Christensen et al. 2018; Doignies et al. 2024",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[ParameterSpec::whole(
        "sweeps",
        0,
        MAX_SWEEPS,
        DEFAULT_SWEEPS,
        "the most sweeps over the scrambling flags (they stop earlier when a sweep keeps no flip)",
    )
    .with_alias("iterations")],
    promise: "(0,m,2)-net at every `2^m` prefix and aligned block, blue noise up to `N`",
    rates: Rates::NETS,
    expensive: false,
    blue_noise: Some(BlueNoise::published(
        "none found (Christensen et al. 2018 could not be checked here)",
    )),
    any_dims: false,
    build: |p| {
        let k = ENTRY.parameters[0].read_whole(p);
        Ok(Built::two(Pmj02Bn::new(p.sampler_seed(), p.count, k)?))
    },
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
                "sweeps",
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
    pub fn sample_u32(&self, index: u32) -> [u32; 2] {
        let x = sobol::sobol_u32(index, 0).unwrap_or(0);
        let y = sobol::sobol_u32(index, 1).unwrap_or(0);
        [self.flags.scramble(0, x), self.flags.scramble(1, y)]
    }

    /// Sample `index`.
    pub fn sample(&self, index: u32) -> Point2 {
        let p = self.sample_u32(index);
        Point2::new(unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1]))
    }

    /// The old name of [`sample_u32`](Self::sample_u32).
    #[deprecated(
        since = "0.1.0",
        note = "renamed `sample_u32` (the `_u32` suffix for 32-bit fixed point)"
    )]
    pub fn sample_fixed(&self, index: u32) -> [u32; 2] {
        self.sample_u32(index)
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
///
/// The cells are the elementary intervals `2^-tx x 2^-ty` with `tx + ty = k` and `tx` the
/// larger: every prefix `2^k` of the sequence is a (0,k,2)-net under every Owen scrambling, so
/// each cell holds exactly one point, before and after any flip. The grid is therefore a flat
/// array of positions, and a flip only overwrites the cells of the moved points.
struct Prefix {
    len: usize,
    tx: u32,
    ty: u32,
    /// The position of the point in each cell, row-major, each row of `2^tx` cells padded with
    /// [`PAD`] cells of wrapped columns on both sides (so `stride = 2^tx + 2 PAD`).
    slots: Vec<[u32; 2]>,
    stride: usize,
    /// Whether the rows are wide enough to scan `2 PAD + 1` padded columns without repeats.
    fast: bool,
    /// The columns (then rows) to scan around a point's cell, relative and wrapped.
    span_x: Vec<u32>,
    span_y: Vec<u32>,
    /// `1 / cutoff^2` in units of `2^-64` (squared fixed-point distances).
    inv_cutoff2: f32,
    weight: f64,
}

impl Prefix {
    fn new(k: u32, pos: &[[u32; 2]]) -> Self {
        let len = 1usize << k;
        let cutoff = CUTOFF * SIGMA * relative_radius_max(len);
        let tx = k.div_ceil(2);
        let ty = k - tx;
        // the offsets that reach `cutoff` (each cell at most once on a small grid)
        let span = |t: u32| -> Vec<u32> {
            let res = 1u32 << t;
            let reach = (cutoff * f64::from(res)).ceil() as u32;
            if 2 * reach + 1 >= res {
                (0..res).collect()
            } else {
                (0..=2 * reach).map(|d| (d + res - reach) % res).collect()
            }
        };
        let stride = (1usize << tx) + 2 * PAD;
        let span_x = span(tx);
        let fast = span_x.len() <= 2 * PAD + 1 && 1usize << tx > 2 * PAD + 1;
        let mut p = Prefix {
            len,
            tx,
            ty,
            slots: vec![[0, 0]; stride << ty],
            stride,
            fast,
            span_x,
            span_y: span(ty),
            inv_cutoff2: (1.0 / (cutoff * cutoff * FIXED2)) as f32,
            weight: 1.0 / len as f64,
        };
        for q in &pos[..len] {
            p.put(*q);
        }
        p
    }

    /// Writes `q` into its cell (and the cell's padding copy, if any).
    fn put(&mut self, q: [u32; 2]) {
        let (x, y) = self.cell_xy(q);
        let (x, row) = (x as usize, y as usize * self.stride);
        let res = 1usize << self.tx;
        self.slots[row + x + PAD] = q;
        if x < PAD {
            self.slots[row + x + PAD + res] = q;
        } else if x + PAD >= res {
            self.slots[row + x + PAD - res] = q;
        }
    }

    fn cell_xy(&self, q: [u32; 2]) -> (u32, u32) {
        // (a shift by 32 is not defined for u32: tx, ty < 32, and ty = 0 is one row)
        let f = |v: u32, t: u32| if t == 0 { 0 } else { v >> (32 - t) };
        (f(q[0], self.tx), f(q[1], self.ty))
    }
}

/// The columns of padding on each side of a grid row: the kernel reaches at most two cells.
const PAD: usize = 2;

/// `2^64`: a squared distance in units of `2^-64` over this is the distance in the unit torus.
const FIXED2: f64 = 18_446_744_073_709_551_616.0;

/// The squared toroidal distance in units of `2^-64` (at most `2^63`, so it fits).
#[cfg(test)]
fn torus_d2_fixed(a: [u32; 2], b: [u32; 2]) -> u64 {
    // a wrapping difference read as signed is the shorter way round
    let d = |u: u32, v: u32| u64::from((u.wrapping_sub(v) as i32).unsigned_abs());
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
        .map(|k| Prefix::new(k, &pos))
        .collect();
    for _ in 0..sweeps {
        let mut kept = 0usize;
        for l in 1..depth {
            let per = n >> l;
            for (ax, by_ax) in order.iter().enumerate() {
                for u in 0..1u32 << l {
                    let s = &by_ax[u as usize * per..(u as usize + 1) * per];
                    let before = energy(s, &pos, ax, l, &prefixes);
                    flip(s, ax, l, &mut pos, &mut prefixes);
                    let after = energy(s, &pos, ax, l, &prefixes);
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

/// The objective's part that involves the points `s` of one node of depth `l` in coordinate
/// `ax` (each pair inside `s` once).
///
/// A point `q` is in the node of `i` when the first `l` digits of their coordinates `ax` agree
/// (the flags above depth `l` map the nodes of depth `l` one to one), and is `i` itself when
/// they are at distance 0 (the points of a (0,2)-sequence have distinct coordinates).
fn energy(s: &[u32], pos: &[[u32; 2]], ax: usize, l: u32, prefixes: &[Prefix]) -> f64 {
    let mut total = 0.0;
    // the first `l` digits of coordinate `ax`
    let mask = !(u32::MAX >> l);
    let node_mask = if ax == 0 { [mask, 0] } else { [0, mask] };
    for p in prefixes {
        let mut outer = 0.0;
        let my = (1u32 << p.ty) - 1;
        let res_x = 1u32 << p.tx;
        for &i in s {
            let i = i as usize;
            if i >= p.len {
                continue;
            }
            let pi = pos[i];
            let (cx, cy) = p.cell_xy(pi);
            // each pair's kernel, halved inside the node (the point itself adds a constant)
            let pair = |q: [u32; 2]| {
                let d = |a: u32, b: u32| (a.wrapping_sub(b) as i32) as f32;
                let (dx, dy) = (d(pi[0], q[0]), d(pi[1], q[1]));
                let t = (1.0 - (dx * dx + dy * dy) * p.inv_cutoff2).max(0.0);
                let t2 = t * t;
                let same = ((pi[0] ^ q[0]) & node_mask[0]) | ((pi[1] ^ q[1]) & node_mask[1]);
                let w = if same == 0 { 0.5 } else { 1.0 };
                w * t2 * t2
            };
            for &dy in &p.span_y {
                let row = ((cy + dy) & my) as usize * p.stride;
                if p.fast {
                    let start = row + cx as usize;
                    let c = &p.slots[start..start + 2 * PAD + 1];
                    outer +=
                        f64::from(pair(c[0]) + pair(c[1]) + pair(c[2]) + pair(c[3]) + pair(c[4]));
                } else {
                    for &dx in &p.span_x {
                        outer += f64::from(pair(p.slots[row + PAD + ((cx + dx) % res_x) as usize]));
                    }
                }
            }
        }
        total += p.weight * outer;
    }
    total
}

/// Flips digit `l + 1` of coordinate `ax` of the points `s` (the effect of one flag), keeping
/// the grids current. Its own inverse.
///
/// The moved points leave and fill the same set of cells (one point per cell before and
/// after), so writing each new position into its cell is the whole update.
fn flip(s: &[u32], ax: usize, l: u32, pos: &mut [[u32; 2]], prefixes: &mut [Prefix]) {
    for &i in s {
        let i = i as usize;
        pos[i][ax] ^= 0x8000_0000 >> l;
        let q = pos[i];
        for p in prefixes.iter_mut().filter(|p| i < p.len) {
            p.put(q);
        }
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
            (0..256).map(|i| a.sample_u32(i)).collect::<Vec<_>>(),
            (0..256).map(|i| b.sample_u32(i)).collect::<Vec<_>>()
        );
        assert!(Pmj02Bn::new(Seed(1), 256, MAX_SWEEPS + 1).is_err());
    }

    #[test]
    fn toroidal_distance_takes_the_short_way() {
        let d = torus_d2_fixed([0, 0], [u32::MAX, 1 << 31]) as f64 / FIXED2;
        assert!((d - 0.25).abs() < 1e-9, "{d}");
    }
}
