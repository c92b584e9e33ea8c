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
//!   neighbour grid of every prefix, the energy after the flip only until it exceeds the energy
//!   before); sweeps repeat until none keeps a flip or `--sweeps` sweeps have run (default
//!   2), the second and later ones over the depths past `m/2` only (the coarse flags keep
//!   their first choice: revisiting depths below `m/2` changed the spacing by under 0.002,
//!   and depth `m/2` gained about 0.005 at 4096 points for about 5% more time; 64 seeds);
//! * each prefix's grid has the elementary intervals `2^-ceil(k/2) x 2^-floor(k/2)` as cells:
//!   since the prefix is a (0,k,2)-net under every scrambling, every cell holds exactly one
//!   point, so the grid is a flat array of positions, and a flip's update is writing the moved
//!   points into their new cells. It is stored by columns (padded with wrapped copies), so the
//!   cells a point's kernel reaches are runs of 4 consecutive cells in 3 to 6 consecutive
//!   columns, evaluated in four `f32` lanes (SSE2 on x86-64; the same operations in the same
//!   order elsewhere, so the same bits: a test compares both);
//! * deeper flags (finer than the optimised count) are random, flipped by the crate's nested
//!   hash ([`owen_scramble`]), so the sequence continues past `2^m` as an Owen-scrambled
//!   (0,2)-sequence.
//!
//! Ahmed and Wonka (2021) note that (0,2)-sequences are much less optimisable than nets, since
//! a coarse choice serves every later prefix. Choosing flags across all prefixes at once is what
//! makes it work: its spacing (mean nearest-neighbour distance) is well above `pmj02`'s at every
//! prefix, where best candidate inside the single valid stratum left by `pmj02` barely moves
//! it; the repository's `docs/results.md` has the measured figures (`spectrum
//! --blue-noise-table`) and `tools/pmj-peer` times it against the `pmj` crate.
//!
//! Guaranteed: the (0,2)-sequence property above (tested on every prefix and aligned block).
//! Cost: the optimisation, once per sequence, is `O(N log N)` for the intended count `N`;
//! counts above [`MAX_OPTIMIZED_LOG2`] are optimised up to `2^16`; each sample is then computed
//! from the flags in `O(m)` and one hash.

use crate::Result;
use crate::counts::CountRule;
use crate::entry::{BlueNoise, Built, Entry, Family, ParameterSpec, Rates};
use crate::grid::relative_radius_max;
use crate::rng::streams;
use strata::float::unit_f32_from_u32;
use strata::hash::{hash_u64, stream_seed};
use strata::samplers::MAX_SEQUENCE_LEN;
use strata::samplers::{Epochs, sobol};
use strata::scramble::owen_scramble;
use strata::{Point2, Progression, Sampler, Seed, StrataGrid};

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

/// `--sweeps`: the cap on the sweeps over the flags.
const SWEEPS: ParameterSpec = ParameterSpec::whole(
    "sweeps",
    0,
    MAX_SWEEPS,
    DEFAULT_SWEEPS,
    "the most sweeps over the scrambling flags (they stop earlier when a sweep keeps no flip)",
)
.with_alias("iterations");

/// The registry entry of `pmj02bn`.
pub(crate) const ENTRY: Entry = Entry {
    name: "pmj02bn",
    description: "a (0,2)-sequence whose Owen-scrambling flags are chosen for blue noise at every power-of-two prefix up to N (--sweeps K caps them, default 2)",
    paper: "Christensen et al. 2018; Doignies et al. 2024",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[SWEEPS],
    promise: "(0,m,2)-net at every `2^m` prefix and aligned block, blue noise up to `N`",
    rates: Rates::NETS,
    blue_noise: Some(BlueNoise::published(
        "none found (Christensen et al. 2018 could not be checked here)",
    )),
    build: |p| {
        let k = ENTRY.parameters[0].read_whole(p);
        Ok(Built::two(Pmj02Bn::new(p.count, k, p.seed)?))
    },
    ..Entry::DEFAULT
};

/// The scrambling flags of both coordinates: explicit up to a depth, hashed below it (the
/// crate's nested hash, [`owen_scramble`], whose flip of each digit is a function of the digits
/// above it: an Owen scrambling there too).
#[derive(Clone, Debug)]
struct Flags {
    /// Depths `0 .. depth` are stored, node `u` of depth `l` at bit `2^l - 1 + u`.
    depth: u32,
    bits: [Vec<u64>; 2],
    /// The seeds of the hashed flags below `depth`.
    deep: [u32; 2],
}

impl Flags {
    /// Random flags (each a hash of the key, the depth and the node), stored to `depth`.
    fn random(key: u64, depth: u32) -> Self {
        let keys = streams::PMJBN.map(|s| stream_seed(s, key));
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
        let deep = streams::PMJBN_DEEP.map(|s| stream_seed(s, key) as u32);
        Flags { depth, bits, deep }
    }

    fn hashed(key: u64, l: u32, node: u32) -> bool {
        hash_u64((u64::from(l) << 32) | u64::from(node), key) & 1 == 1
    }

    fn flip(&mut self, ax: usize, l: u32, node: u32) {
        let i = (1usize << l) - 1 + node as usize;
        self.bits[ax][i >> 6] ^= 1 << (i & 63);
    }

    /// Coordinate `ax` of a point of the plain sequence, scrambled.
    fn scramble(&self, ax: usize, v: u32) -> u32 {
        // digits depth + 1 .. 32 flipped by the nested hash (depth <= 17)
        let mut out = v ^ ((owen_scramble(v, self.deep[ax]) ^ v) & (u32::MAX >> self.depth));
        for l in 0..self.depth {
            let node = if l == 0 { 0 } else { v >> (32 - l) };
            let i = (1usize << l) - 1 + node as usize;
            if self.bits[ax][i >> 6] >> (i & 63) & 1 == 1 {
                out ^= 0x8000_0000 >> l;
            }
        }
        out
    }
}

/// The blue-noise (0,2)-sequence (progressive).
///
/// ```
/// use strata::{Sampler, Seed};
/// use strata_lab::samplers::Pmj02Bn;
/// let mut s = Pmj02Bn::new(256, 4, Seed(3))?;
/// let pts: Vec<_> = (0..16).map(|_| s.next_sample()).collect();
/// let mut cells = [0; 16]; // a (0,4,2)-net: one point in each 4 x 4 cell
/// for p in &pts {
///     cells[(p[1] * 4.0) as usize * 4 + (p[0] * 4.0) as usize] += 1;
/// }
/// assert!(cells.iter().all(|&c| c == 1));
/// # Ok::<(), strata_lab::Error>(())
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
    pub fn new(count: u64, sweeps: u32, seed: Seed) -> Result<Self> {
        SWEEPS.check(ENTRY.name, sweeps as f64)?;
        // (a count past 2^63 has no next power of two in u64: it optimises the longest prefix)
        let log2 = count
            .max(1)
            .checked_next_power_of_two()
            .map_or(64, u64::trailing_zeros)
            .clamp(FIRST_PREFIX_LOG2, MAX_OPTIMIZED_LOG2);
        let epochs = Epochs::new(MAX_SEQUENCE_LEN, seed);
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
        [unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1])]
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
        StrataGrid::net(n, true)
    }
}

/// One prefix's neighbour grid and kernel.
///
/// The cells are the elementary intervals `2^-tx x 2^-ty` with `tx + ty = k` and `tx` the
/// larger: every prefix `2^k` of the sequence is a (0,k,2)-net under every Owen scrambling, so
/// each cell holds exactly one point, before and after any flip. The grid is therefore a flat
/// array of coordinates, and a flip only overwrites the cells of the moved points.
///
/// The grid is stored by columns: each column is its `2^ty` cells' x coordinates followed by
/// copies of the first [`WRAP_CELLS`] (wrapped), then the same for y; the `2^tx` columns are
/// followed by copies of the first [`WRAP_COLUMNS`]. The cells that the kernel of a point
/// reaches are then one run of [`LANES`] values of each coordinate in each of 3 to 6
/// consecutive columns (the kernel's diameter is under `LANES - 1` cell heights and
/// `WRAP_COLUMNS` cell widths).
struct Prefix {
    tx: u32,
    /// `32 - tx` and `32 - ty`: a coordinate's cell is its top `tx` (`ty`) bits.
    shift: [u32; 2],
    /// `2^tx - 1`.
    last: u32,
    /// The columns, `2 * stride` values each.
    cells: Vec<u32>,
    /// `2^ty + WRAP_CELLS`: the offset of a column's y coordinates from its x coordinates.
    stride: usize,
    /// The kernel's reach in units of `2^-32`, rounded up (so that every pair it misses is
    /// beyond the cutoff).
    reach: u32,
    /// `1 / cutoff^2` in units of `2^-64` (squared fixed-point distances).
    inv_cutoff2: f32,
    /// `2^-k` (energy per point; exact in `f32`).
    weight: f32,
}

/// The cells of a column read at once: a point's kernel reaches at most this many.
const LANES: usize = 4;

/// The cells copied after each column (its first ones, wrapped).
const WRAP_CELLS: usize = LANES - 1;

/// The columns copied after the grid: a point's kernel reaches at most one more.
const WRAP_COLUMNS: usize = 5;

impl Prefix {
    fn new(k: u32, pos: &[[u32; 2]]) -> Self {
        let len = 1usize << k;
        let cutoff = CUTOFF * SIGMA * relative_radius_max(len);
        let tx = k.div_ceil(2);
        let ty = k - tx;
        let reach = (cutoff * 4_294_967_296.0).ceil() as u32 + 1;
        // a column's run of LANES cells covers the kernel's diameter, and the columns it
        // reaches are distinct and at most WRAP_COLUMNS + 1 (cell sizes in units of 2^-32)
        let (h, w) = (1u64 << (32 - ty), 1u64 << (32 - tx));
        let columns = 2 * u64::from(reach) / w + 2;
        assert!(ty >= 2 && 2 * u64::from(reach) < (LANES as u64 - 1) * h);
        assert!(columns <= 1 << tx && columns <= WRAP_COLUMNS as u64 + 1);
        let stride = (1usize << ty) + WRAP_CELLS;
        let mut p = Prefix {
            tx,
            shift: [32 - tx, 32 - ty],
            last: (1 << tx) - 1,
            cells: vec![0; 2 * stride * ((1 << tx) + WRAP_COLUMNS)],
            stride,
            reach,
            inv_cutoff2: (1.0 / (cutoff * cutoff * FIXED2)) as f32,
            weight: 1.0 / len as f32,
        };
        for q in &pos[..len] {
            p.put(*q);
        }
        p
    }

    /// Writes `q` into its cell (and the cell's copies, if any).
    #[inline(always)]
    fn put(&mut self, q: [u32; 2]) {
        // (tx >= ty >= 2: the shifts are defined)
        let (cx, cy) = (
            (q[0] >> self.shift[0]) as usize,
            (q[1] >> self.shift[1]) as usize,
        );
        let stride = self.stride;
        let column = 2 * stride;
        let copies = 1 + usize::from(cx < WRAP_COLUMNS);
        let mut at = cx * column + cy;
        // cx < 2^tx, cy < 2^ty = stride - WRAP_CELLS, and a copy is of a column
        // cx < WRAP_COLUMNS: every index is below column (2^tx + WRAP_COLUMNS) = cells.len()
        debug_assert!(self.cells.len() == column * ((1 << self.tx) + WRAP_COLUMNS));
        debug_assert!(cy + WRAP_CELLS < stride);
        for _ in 0..copies {
            self.cells[at] = q[0];
            self.cells[at + stride] = q[1];
            if cy < WRAP_CELLS {
                let wrapped = at + stride - WRAP_CELLS;
                self.cells[wrapped] = q[0];
                self.cells[wrapped + stride] = q[1];
            }
            at += column << self.tx;
        }
    }

    /// Adds `2^-k` times the kernel summed over the points near `q` (`q` itself included),
    /// halved for those whose coordinate `AX` agrees with `q`'s on the bits of `mask` (the
    /// node of `q`), to the lanes `acc`.
    #[inline]
    fn add_energy<const AX: usize>(&self, q: [u32; 2], mask: u32, acc: &mut [f32; LANES]) {
        let x0 = q[0].wrapping_sub(self.reach) >> self.shift[0];
        let x1 = q[0].wrapping_add(self.reach) >> self.shift[0];
        let columns = (x1.wrapping_sub(x0) & self.last) as usize + 1;
        let y0 = (q[1].wrapping_sub(self.reach) >> self.shift[1]) as usize;
        let kernel = Kernel {
            q,
            node: q[AX] & mask,
            mask,
            inv_cutoff2: self.inv_cutoff2,
        };
        let column = 2 * self.stride;
        let start = x0 as usize * column + y0;
        // the runs of the columns (of the copies past the last)
        let runs = &self.cells[start..start + (columns - 1) * column + self.stride + LANES];
        kernel.add::<AX>(runs, columns, self.stride, self.weight, acc);
    }
}

/// One point's kernel, evaluated against runs of [`LANES`] cells.
struct Kernel {
    q: [u32; 2],
    /// The bits of `mask` of the point's coordinate `AX` (its node).
    node: u32,
    mask: u32,
    inv_cutoff2: f32,
}

impl Kernel {
    /// Adds `weight` times the kernel of the cells of `columns` runs, halved inside the
    /// node, to the lanes `acc`: run `c` is the `LANES` x coordinates at `runs[2 c stride..]`
    /// and the y coordinates `stride` later.
    ///
    /// Evaluated in `f32` lanes, one per cell of a run, in a fixed order: in SSE2 on x86-64
    /// ([`add_sse2`](Kernel::add_sse2)), in plain arrays elsewhere
    /// ([`add_portable`](Kernel::add_portable)), the same bits (tested).
    #[inline(always)]
    fn add<const AX: usize>(
        &self,
        runs: &[u32],
        columns: usize,
        stride: usize,
        weight: f32,
        acc: &mut [f32; LANES],
    ) {
        #[cfg(target_arch = "x86_64")]
        self.add_sse2::<AX>(runs, columns, stride, weight, acc);
        #[cfg(not(target_arch = "x86_64"))]
        self.add_portable::<AX>(runs, columns, stride, weight, acc);
    }

    /// [`add`](Kernel::add) in plain arrays, lane by lane (also built on x86-64 for the test
    /// that both ways give the same bits).
    #[cfg(any(test, not(target_arch = "x86_64")))]
    #[inline(always)]
    fn add_portable<const AX: usize>(
        &self,
        runs: &[u32],
        columns: usize,
        stride: usize,
        weight: f32,
        acc: &mut [f32; LANES],
    ) {
        let mut sum = [0f32; LANES];
        for c in 0..columns {
            let xs = &runs[2 * c * stride..][..LANES];
            let ys = &runs[2 * c * stride + stride..][..LANES];
            for j in 0..LANES {
                // a wrapping difference read as signed is the shorter way round
                let dx = self.q[0].wrapping_sub(xs[j]) as i32 as f32;
                let dy = self.q[1].wrapping_sub(ys[j]) as i32 as f32;
                let t = 1.0 - (dx * dx + dy * dy) * self.inv_cutoff2;
                let t = if t > 0.0 { t } else { 0.0 };
                let t2 = t * t;
                let same = if AX == 0 { xs[j] } else { ys[j] };
                let w = if same & self.mask == self.node {
                    0.5
                } else {
                    1.0
                };
                sum[j] += w * (t2 * t2);
            }
        }
        for j in 0..LANES {
            acc[j] += sum[j] * weight;
        }
    }

    /// [`add`](Kernel::add) in SSE2 (part of the x86-64 baseline): the same operations in
    /// the same order as [`add_portable`](Kernel::add_portable), so the same values.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    fn add_sse2<const AX: usize>(
        &self,
        runs: &[u32],
        columns: usize,
        stride: usize,
        weight: f32,
        acc: &mut [f32; LANES],
    ) {
        use core::arch::x86_64::*;
        assert!(columns >= 1 && runs.len() >= 2 * (columns - 1) * stride + stride + LANES);
        // SAFETY: SSE2 is part of the x86-64 baseline, so every intrinsic is available; the
        // loads read LANES values at 2 c stride and at 2 c stride + stride, c < columns,
        // inside `runs` (checked above), and `acc`, which the store writes.
        unsafe {
            let qx = _mm_set1_epi32(self.q[0] as i32);
            let qy = _mm_set1_epi32(self.q[1] as i32);
            let inv = _mm_set1_ps(self.inv_cutoff2);
            let mask = _mm_set1_epi32(self.mask as i32);
            let node = _mm_set1_epi32(self.node as i32);
            let (one, half) = (_mm_set1_ps(1.0), _mm_set1_ps(0.5));
            let mut sum = _mm_setzero_ps();
            let mut at = runs.as_ptr();
            for _ in 0..columns {
                let xv = _mm_loadu_si128(at.cast());
                let yv = _mm_loadu_si128(at.add(stride).cast());
                at = at.wrapping_add(2 * stride);
                let dx = _mm_cvtepi32_ps(_mm_sub_epi32(qx, xv));
                let dy = _mm_cvtepi32_ps(_mm_sub_epi32(qy, yv));
                let d2 = _mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy));
                // max(t, 0) is t where t > 0, else 0, as the portable code
                let t = _mm_max_ps(_mm_sub_ps(one, _mm_mul_ps(d2, inv)), _mm_setzero_ps());
                let t2 = _mm_mul_ps(t, t);
                let same = if AX == 0 { xv } else { yv };
                let inside = _mm_cmpeq_epi32(_mm_and_si128(same, mask), node);
                // 1 - 0.5 inside the node, 1 - 0 outside (both exact)
                let w = _mm_sub_ps(one, _mm_and_ps(_mm_castsi128_ps(inside), half));
                sum = _mm_add_ps(sum, _mm_mul_ps(w, _mm_mul_ps(t2, t2)));
            }
            let total = _mm_add_ps(
                _mm_loadu_ps(acc.as_ptr()),
                _mm_mul_ps(sum, _mm_set1_ps(weight)),
            );
            _mm_storeu_ps(acc.as_mut_ptr(), total);
        }
    }
}

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

/// The index in `prefixes` (prefix `2^k` at `k - FIRST_PREFIX_LOG2`) of the smallest prefix
/// that holds point `i`.
fn first_prefix(i: usize) -> usize {
    ((usize::BITS - i.leading_zeros()) as usize).saturating_sub(FIRST_PREFIX_LOG2 as usize)
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
    // (m >= FIRST_PREFIX_LOG2)
    let mut prefixes: Vec<Prefix> = (FIRST_PREFIX_LOG2..=m)
        .map(|k| Prefix::new(k, &pos))
        .collect();
    for sweep in 0..sweeps {
        let mut kept = 0usize;
        // the later sweeps revisit the depths past m/2 only (the coarse flags keep their first
        // choice: revisiting depth m/2 too gained 0.005 in spacing at 4096, 64 seeds, for 5%
        // more time)
        let first = if sweep == 0 { 1 } else { m / 2 + 1 };
        for l in first..depth {
            let per = n >> l;
            for (ax, by_ax) in order.iter().enumerate() {
                for u in 0..1u32 << l {
                    let s = &by_ax[u as usize * per..(u as usize + 1) * per];
                    let before = energy(s, &pos, ax, l, &prefixes, f64::INFINITY);
                    flip(s, ax, l, &mut pos, &mut prefixes);
                    let after = energy(s, &pos, ax, l, &prefixes, before);
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
/// `ax` (each pair inside `s` once), or a partial sum over `bound` once it is over (the terms
/// are not negative, so the whole is over too).
///
/// A point `q` is in the node of `i` when the first `l` digits of their coordinates `ax` agree
/// (the flags above depth `l` map the nodes of depth `l` one to one); the pair of `i` with
/// itself adds a constant.
fn energy(s: &[u32], pos: &[[u32; 2]], ax: usize, l: u32, prefixes: &[Prefix], bound: f64) -> f64 {
    if ax == 0 {
        energy_in::<0>(s, pos, l, prefixes, bound)
    } else {
        energy_in::<1>(s, pos, l, prefixes, bound)
    }
}

/// [`energy`] for coordinate `AX`.
fn energy_in<const AX: usize>(
    s: &[u32],
    pos: &[[u32; 2]],
    l: u32,
    prefixes: &[Prefix],
    bound: f64,
) -> f64 {
    // the first `l` digits of coordinate `AX`
    let mask = !(u32::MAX >> l);
    let mut total = 0.0;
    for &i in s {
        let i = i as usize;
        let q = pos[i];
        let mut acc = [0f32; LANES];
        for p in &prefixes[first_prefix(i)..] {
            p.add_energy::<AX>(q, mask, &mut acc);
        }
        total += f64::from((acc[0] + acc[1]) + (acc[2] + acc[3]));
        if total > bound {
            break;
        }
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
        for p in &mut prefixes[first_prefix(i)..] {
            p.put(q);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_sweeps_is_a_random_owen_scrambling_and_sweeps_change_it() {
        let a = Pmj02Bn::new(256, 0, Seed(1)).unwrap();
        let b = Pmj02Bn::new(256, 2, Seed(1)).unwrap();
        assert_ne!(
            (0..256).map(|i| a.sample_u32(i)).collect::<Vec<_>>(),
            (0..256).map(|i| b.sample_u32(i)).collect::<Vec<_>>()
        );
        assert!(Pmj02Bn::new(256, MAX_SWEEPS + 1, Seed(1)).is_err());
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_kernel_gives_the_same_bits_in_sse2_and_in_plain_arrays() {
        let word = |i: u64| strata::hash::hash_u64(i, 0x6b65_726e) as u32;
        let (columns, stride) = (6, 16);
        let runs: Vec<u32> = (0..(2 * (columns - 1) * stride + stride + LANES) as u64)
            .map(|i| {
                // coordinates near the kernel's point, so that most lanes fall inside it
                let near = word(i) >> 4;
                if i % 3 == 0 { word(i) } else { near }
            })
            .collect();
        let mut inside = 0;
        for case in 0..200u64 {
            let kernel = Kernel {
                q: [word(1000 + case) >> 4, word(2000 + case) >> 4],
                node: word(3000 + case) & 0xf000_0000,
                mask: 0xf000_0000,
                inv_cutoff2: 1.0 / (word(4000 + case) >> 2) as f32 / (1u64 << 31) as f32,
            };
            let weight = 0.25 + (case as f32) / 64.0;
            let (mut a, mut b) = ([0.125f32; LANES], [0.125f32; LANES]);
            kernel.add_sse2::<0>(&runs, columns, stride, weight, &mut a);
            kernel.add_portable::<0>(&runs, columns, stride, weight, &mut b);
            kernel.add_sse2::<1>(&runs, columns, stride, weight, &mut a);
            kernel.add_portable::<1>(&runs, columns, stride, weight, &mut b);
            assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits), "case {case}");
            inside += a.iter().filter(|v| **v != 0.125).count();
        }
        // the kernel was evaluated inside its cutoff, not only outside it
        assert!(inside > 200, "{inside}");
    }

    #[test]
    fn toroidal_distance_takes_the_short_way() {
        let d = torus_d2_fixed([0, 0], [u32::MAX, 1 << 31]) as f64 / FIXED2;
        assert!((d - 0.25).abs() < 1e-9, "{d}");
    }
}
