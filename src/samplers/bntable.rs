//! The tables of the renderer crate's progressive blue-noise sequences
//! ([`strata::pixel::BlueNoiseTable`], the sequence `sobolbn`): per pixel of a toroidal tile, a
//! key (an Owen scramble) and a rank (an XOR of the sample index), arranged so that
//! neighbouring pixels' errors cancel at every power of two from 1 to `2^levels` samples. The
//! built-in table is [`optimise`]`(&`[`BUILTIN`]`)`, written into
//! `strata/src/pixel/bluenoise/sobol_128.rs` by the `bntable` program.
//!
//! **The structure.** The tile is cut into 4 x 4 blocks. The sixteen pixels of a block share
//! the bits of their key that scramble the leading `levels + 4` digits (the rest of the key is
//! the pixel's own), and each XORs the block's base rank with a pattern, a sum of the
//! [`GENERATORS`] chosen by its place in the block and the block's layout. So at every count `2^k` the union of a
//! block's (or of a 2 x 2 sub-block's) first `2^k` samples per pixel is the scrambled Sobol'
//! points at a subspace of indices: a net of 16 (or 4) times as many points, with the small
//! t-values the generators were searched for, while each pixel's own samples stay the aligned
//! blocks of its sequence (nets) at every count. It is the Z order of Ahmed and Wonka ("Screen-
//! Space Blue-Noise Diffusion of Monte Carlo Sampling Error via Hierarchical Ordering of
//! Pixels", SIGGRAPH Asia 2020; pbrt-v4's `ZSobolSampler`) for two levels, made progressive:
//! that order makes the union a net at the one count it is told; a rank XOR by a fixed pattern
//! cannot make it an aligned block at every count (the block of one count holds the first
//! sample of the others), so the generators are the subspaces that come closest.
//!
//! **The arrangement** (OpenQMC's method, Framestore, `src/tools/lib/optimise.cpp`, after
//! Heitz, Belcour et al. 2019 and Belcour and Heitz 2021, rewritten over whole blocks):
//!
//! 1. **Keys.** Blocks of random keys and base ranks (random above their low `levels` bits, 0
//!    below) are permuted over the tile so that the errors of the *whole* count, `2^levels`
//!    samples, are blue.
//! 2. **Ranks, from the top down.** At each count `2^l` below it, every block chooses which half
//!    of its pixels' `2^(l+1)` samples comes first (bit `l` of its base rank): the sets of the
//!    larger counts stay, the error at `2^l` becomes blue.
//! 3. **Every count at once** (our step): each block's base rank's low bits, then its layout
//!    (which pixel holds which pattern: 576 maps that keep the sub-blocks'
//!    and the block's unions, 32 of them tried per block and sweep) are chosen anew against its
//!    neighbours, sweep after sweep, then whole blocks are swapped (the *polish*), against the
//!    errors of every count, each count weighted by the inverse of its mean squared error.
//!
//! "Blue" is measured by the energy `sum_p sum_q w(p - q) <e_p, e_q>`: `e_p` the pixel's errors
//! over a set of test integrands of the draw's 2D domain, `w` a Gaussian of 2.1 pixels over a
//! 13 x 13 window (0 at the centre), six times as heavy on the pixel's row and column; low
//! energy means neighbouring errors of opposite signs, little power at low frequencies. The
//! row and the column weigh more because an edge of the image along a row meets the same
//! integrand in every pixel of that row alone: a tile whose error is blue as a whole can still
//! have rows of one sign (the blocks' fixed layout did, at 4 samples), and then the edge's error
//! is red. The integrands: edges of random position and orientation
//! (two in five, as OpenQMC's oriented Heavisides), steps along the first coordinate (three in
//! ten: a renderer's 1D draws, a light or a lobe choice, read the first coordinate), along the
//! second (one in ten), Gaussian bumps of random centre and width (the rest), each seen through
//! a random digital shift, as the draws see them (each draw XORs its values with a shift per
//! seed and dimension). The figures are over another draw of the same kinds (held out). Each
//! step makes moves of whole blocks (swaps, rank choices), the energy's change computed from a
//! low-passed field of the errors that each accepted move updates (as the lab's tile study
//! does).
//!
//! **The limit.** Past `2^12` samples two pixels of a block can draw the same block of indices
//! (their points then agree in the leading `levels + 4` digits and differ below them), and
//! past `2^(levels + 2)` samples the unions are nets only down to those digits: the table's
//! arrangement fades out there, as the optimiser's counts end.

use std::fmt::Write as _;

use rand::Rng;
use rand_pcg::Pcg32;
use strata::Seed;
use strata::pixel::BlueNoiseTable;
use strata::pixel::bluenoise::{MAX_RANK, MAX_SIDE};

use crate::rng::{below, pcg, streams, uniform};
use crate::spectrum::error_image;
use crate::{Error, Result};

/// What [`optimise`] makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableOptions {
    /// The side of the tile: a power of two from 16 to [`MAX_SIDE`].
    pub side: u32,
    /// The counts arranged: `1, 2, ..., 2^levels` samples (`levels` from 1 to 10).
    pub levels: u32,
    /// Test integrands the optimiser sees (1 to 1024).
    pub integrands: u32,
    /// Proposed moves per pixel and step (1 to 10 000): the run time grows with it.
    pub effort: u32,
    /// Whether step 3 (the polish) runs.
    pub polish: bool,
    /// The seed of the keys, the ranks' high bits, the test integrands and the annealing.
    pub seed: Seed,
}

/// The options of the renderer crate's built-in table.
pub const BUILTIN: TableOptions = TableOptions {
    side: 128,
    levels: 6,
    integrands: 512,
    effort: 100,
    polish: true,
    seed: Seed(0x626e_7462),
};

/// A table and what it achieves.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The options that made it.
    pub options: TableOptions,
    /// `(key, rank)` row-major, as [`BlueNoiseTable::new`] takes them.
    pub entries: Vec<[u32; 2]>,
    /// Per count `2^l`, `l = 0..=levels`: the low-band share of the error image over the tile
    /// (held-out integrands, mean over them) of random entries and of the table.
    pub lowband: Vec<LevelFigures>,
}

/// The low-band shares at one count (see [`Table::lowband`]; white noise is about 0.049).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelFigures {
    /// Samples per pixel.
    pub count: u32,
    /// Random entries (distinct random keys, random ranks): white noise.
    pub random: f64,
    /// The table.
    pub table: f64,
}

/// The number of held-out integrands of the figures.
const HELD_OUT: u32 = 64;

/// A test integrand over `[0, 1)^2` seen through a random digital shift (the draws XOR their
/// values with a shift per seed and dimension, which keeps the integral), with its exact
/// integral.
#[derive(Clone, Copy, Debug)]
struct Shifted {
    test: Test,
    shift: [u32; 2],
}

impl Shifted {
    fn draw(rng: &mut Pcg32) -> Shifted {
        Shifted {
            test: Test::draw(rng),
            shift: [rng.next_u32(), rng.next_u32()],
        }
    }

    /// The integrand at the 32-bit fixed-point point `p`.
    #[inline]
    fn eval(&self, p: [u32; 2]) -> f64 {
        let unit = |v: u32| v as f64 / 4_294_967_296.0;
        self.test
            .eval([unit(p[0] ^ self.shift[0]), unit(p[1] ^ self.shift[1])])
    }

    fn integral(&self) -> f64 {
        self.test.integral()
    }
}

/// A test integrand over `[0, 1)^2`, with its exact integral.
#[derive(Clone, Copy, Debug)]
enum Test {
    /// 1 where `(x - c) . n > 0`.
    Edge {
        c: [f64; 2],
        n: [f64; 2],
        integral: f64,
    },
    /// `exp(-|x - c|^2 / (2 s^2))`, stored as `k = 1 / (2 s^2)`.
    Bump { c: [f64; 2], k: f64, integral: f64 },
}

impl Test {
    /// A random integrand: an edge of random orientation (two times in five), a step along the
    /// first coordinate (three in ten: a 1D draw's choice, which reads the first coordinate),
    /// one along the second (one in ten), else a bump.
    fn draw(rng: &mut Pcg32) -> Test {
        let c = [uniform(rng), uniform(rng)];
        let kind = below(rng, 10);
        if kind < 8 {
            let a = 2.0 * std::f64::consts::PI * uniform(rng);
            let n = match kind {
                0..4 => [a.cos(), a.sin()],
                4..7 => [if a < std::f64::consts::PI { 1.0 } else { -1.0 }, 0.0],
                _ => [0.0, if a < std::f64::consts::PI { 1.0 } else { -1.0 }],
            };
            Test::Edge {
                c,
                n,
                integral: half_plane_area(c, n),
            }
        } else {
            let s = 0.05 + 0.2 * uniform(rng);
            let axis = |c: f64| {
                let r = s * std::f64::consts::SQRT_2;
                s * (std::f64::consts::PI / 2.0).sqrt() * (erf((1.0 - c) / r) + erf(c / r))
            };
            Test::Bump {
                c,
                k: 1.0 / (2.0 * s * s),
                integral: axis(c[0]) * axis(c[1]),
            }
        }
    }

    #[inline]
    fn eval(&self, x: [f64; 2]) -> f64 {
        match *self {
            Test::Edge { c, n, .. } => {
                ((x[0] - c[0]) * n[0] + (x[1] - c[1]) * n[1] > 0.0) as u8 as f64
            }
            Test::Bump { c, k, .. } => {
                let (dx, dy) = (x[0] - c[0], x[1] - c[1]);
                (-(dx * dx + dy * dy) * k).exp()
            }
        }
    }

    fn integral(&self) -> f64 {
        match *self {
            Test::Edge { integral, .. } | Test::Bump { integral, .. } => integral,
        }
    }
}

/// The area of `{x in [0,1]^2 : (x - c) . n > 0}`: the unit square clipped by the half-plane
/// (Sutherland and Hodgman), by the shoelace formula.
fn half_plane_area(c: [f64; 2], n: [f64; 2]) -> f64 {
    let side = |p: [f64; 2]| (p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1];
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut poly: Vec<[f64; 2]> = Vec::with_capacity(5);
    for k in 0..4 {
        let (p, q) = (square[k], square[(k + 1) % 4]);
        let (sp, sq) = (side(p), side(q));
        if sp > 0.0 {
            poly.push(p);
        }
        if (sp > 0.0) != (sq > 0.0) {
            let t = sp / (sp - sq);
            poly.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
        }
    }
    let mut area = 0.0;
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        area += p[0] * q[1] - q[0] * p[1];
    }
    (area / 2.0).abs()
}

/// The error function (Abramowitz and Stegun 7.1.26, absolute error below `1.5e-7`).
fn erf(x: f64) -> f64 {
    let t = 1.0 / (1.0 + 0.327_591_1 * x.abs());
    let poly = t
        * (0.254_829_592
            + t * (-0.284_496_736
                + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    let y = 1.0 - poly * (-x * x).exp();
    if x < 0.0 { -y } else { y }
}

/// The errors of entry `(key, rank)` at every count `2^l`, `l = 0..=levels`, over `tests`:
/// `out[l * tests.len() + k]`.
fn entry_errors(key: u32, rank: u32, tests: &[Shifted], levels: u32, out: &mut [f32]) {
    let k = tests.len();
    let mut sums = vec![0.0f64; k];
    let mut next = 1u32;
    let mut level = 0;
    for i in 0..1u32 << levels {
        let p = BlueNoiseTable::point_u32(i, rank, key);
        for (s, t) in sums.iter_mut().zip(tests) {
            *s += t.eval(p);
        }
        if i + 1 == next {
            for (j, t) in tests.iter().enumerate() {
                out[level * k + j] = (sums[j] / next as f64 - t.integral()) as f32;
            }
            level += 1;
            next <<= 1;
        }
    }
}

/// The radius of the energy's window.
const RADIUS: i32 = 6;
/// The Gaussian's standard deviation, pixels.
const SIGMA: f64 = 2.1;
/// The extra weight of the pairs of one row or one column (times the Gaussian).
const LINE: f64 = 5.0;

/// The errors of every pixel of the tile (`f` features each) and their low-passed field
/// `s_p = sum_{q != p} w(p - q) e_q`.
struct Field {
    side: usize,
    f: usize,
    e: Vec<f32>,
    s: Vec<f32>,
    /// The window's offsets and weights (centre excluded).
    offsets: Vec<(i32, i32, f32)>,
    /// The weight of every offset of the window, row-major over `[-R, R]^2`.
    weights: Vec<f32>,
}

impl Field {
    fn new(side: usize, f: usize, e: Vec<f32>) -> Field {
        let width = (2 * RADIUS + 1) as usize;
        let mut offsets = Vec::new();
        let mut weights = vec![0.0f32; width * width];
        for dy in -RADIUS..=RADIUS {
            for dx in -RADIUS..=RADIUS {
                if dx == 0 && dy == 0 {
                    continue;
                }
                let g = |d2: i32| (-(d2 as f64) / (2.0 * SIGMA * SIGMA)).exp();
                // pixels on one row or column weigh more: an edge of the image along a row
                // meets one integrand in every pixel of it, and its error is that row's alone
                let line = if dx == 0 || dy == 0 { LINE } else { 0.0 };
                let w = (g(dx * dx + dy * dy) * (1.0 + line)) as f32;
                offsets.push((dx, dy, w));
                weights[((dy + RADIUS) as usize) * width + (dx + RADIUS) as usize] = w;
            }
        }
        let mut field = Field {
            side,
            f,
            s: vec![0.0; e.len()],
            e,
            offsets,
            weights,
        };
        for p in 0..side * side {
            for k in 0..field.offsets.len() {
                let (dx, dy, w) = field.offsets[k];
                let q = field.at(p, dx, dy);
                for j in 0..f {
                    field.s[q * f + j] += w * field.e[p * f + j];
                }
            }
        }
        field
    }

    /// The pixel at `(dx, dy)` from `p`, toroidally.
    #[inline]
    fn at(&self, p: usize, dx: i32, dy: i32) -> usize {
        torus(self.side, p, dx, dy)
    }

    /// The weight between pixels `a` and `b` (0 outside the window).
    fn weight(&self, a: usize, b: usize) -> f32 {
        let n = self.side as i32;
        let wrap = |d: i32| {
            let d = d.rem_euclid(n);
            if d > n / 2 { d - n } else { d }
        };
        let dx = wrap((b % self.side) as i32 - (a % self.side) as i32);
        let dy = wrap((b / self.side) as i32 - (a / self.side) as i32);
        if dx.abs() > RADIUS || dy.abs() > RADIUS {
            return 0.0;
        }
        let width = (2 * RADIUS + 1) as usize;
        self.weights[((dy + RADIUS) as usize) * width + (dx + RADIUS) as usize]
    }

    fn row(&self, p: usize) -> core::ops::Range<usize> {
        p * self.f..(p + 1) * self.f
    }

    /// Adds `d` to pixel `p`'s errors' contribution to its neighbours' fields.
    fn spread(&mut self, p: usize, d: &[f32]) {
        for k in 0..self.offsets.len() {
            let (dx, dy, w) = self.offsets[k];
            let q = self.at(p, dx, dy);
            let s = &mut self.s[q * self.f..(q + 1) * self.f];
            for (s, d) in s.iter_mut().zip(d) {
                *s += w * d;
            }
        }
    }

    /// The energy's change if the distinct pixels `pix` took the errors `new` (`f` each, in
    /// the order of `pix`); `d` is scratch.
    fn set_delta(&self, pix: &[usize], new: &[f32], d: &mut Vec<f32>) -> f64 {
        let f = self.f;
        d.clear();
        let mut total = 0.0f64;
        for (i, &p) in pix.iter().enumerate() {
            let (e, s, n) = (
                &self.e[self.row(p)],
                &self.s[self.row(p)],
                &new[i * f..][..f],
            );
            let mut dot = 0.0f64;
            for j in 0..f {
                let dj = n[j] - e[j];
                d.push(dj);
                dot += dj as f64 * s[j] as f64;
            }
            total += 2.0 * dot;
        }
        for i in 0..pix.len() {
            for i2 in i + 1..pix.len() {
                let w = self.weight(pix[i], pix[i2]);
                if w != 0.0 {
                    let (a, b) = (&d[i * f..][..f], &d[i2 * f..][..f]);
                    let dot: f64 = a.iter().zip(b).map(|(x, y)| *x as f64 * *y as f64).sum();
                    total += 2.0 * w as f64 * dot;
                }
            }
        }
        total
    }

    /// Gives the pixels `pix` the errors `new` (as [`set_delta`](Self::set_delta) takes them).
    fn set_replace(&mut self, pix: &[usize], new: &[f32]) {
        let f = self.f;
        for (i, &p) in pix.iter().enumerate() {
            self.replace(p, &new[i * f..][..f]);
        }
    }

    fn replace(&mut self, a: usize, new: &[f32]) {
        let d: Vec<f32> = (0..self.f)
            .map(|j| new[j] - self.e[a * self.f + j])
            .collect();
        self.spread(a, &d);
        self.e[a * self.f..(a + 1) * self.f].copy_from_slice(new);
    }
}

/// The pixel at `(dx, dy)` from `p` on the torus of side `side` (a power of two).
#[inline]
fn torus(side: usize, p: usize, dx: i32, dy: i32) -> usize {
    let m = side as i32 - 1;
    let (x, y) = ((p % side) as i32, (p / side) as i32);
    (((y + dy) & m) as usize) * side + ((x + dx) & m) as usize
}

/// The generators of the ranks' patterns, two per level of a block's hierarchy: under the
/// identity layout, the pixel at `(x, y)` of a 4 x 4 block XORs the block's base rank with `a`
/// if `x & 1`, `b` if `y & 1`, `c` if `x & 2`, `d` if `y & 2` (a block's layout permutes the
/// places, keeping the sub-blocks). With the same scramble, the union of the first `2^k`
/// samples of a 2 x 2 sub-block is the Sobol' points at the indices `span(e_0, ..., e_(k-1), a,
/// b)` (shifted): a (t, k+2, 2)-net with t = 0, 0, 0, 0, 1, 2, 0 at 1 to 64 samples; of the
/// `3 * 2^15` pairs whose bits `k` and `k + 1` are independent at every `k` below 15, the pair
/// is one of those with the least sum of t-values over `k = 0..=8` (an exhaustive search). The
/// whole block's union is `span(e_0, ..., e_(k-1), a, b, c, d)`, with t = 0, 0, 0, 1, 1, 1, 1,
/// and bits `k` to `k + 3` of the four are independent at every `k` below 13: of the 18,160
/// pairs `(c, d)` with that property among `2 * 10^8` random ones, the three with the least sum
/// of t-values at 1 to 64 samples were arranged at random over a 64 x 64 tile, and this one's
/// low band was the lowest from 2 to 16 samples (8 draws of 64 test integrands). So up to
/// `2^12` samples the sixteen pixels draw sixteen different blocks of their sequence, whose
/// union is stratified along the first coordinate into 16 times as many intervals (test
/// `the_generators_make_the_nets_they_promise`).
pub const GENERATORS: [u32; 4] = [0x6aab, 0xd556, 0xadd8, 0x311f];

/// The side of a block: its pixels share the scramble of the leading digits.
const BLOCK: usize = 4;

/// The pattern of the pixel at `(x, y)` of a block (see [`GENERATORS`]).
fn pattern(x: usize, y: usize) -> u32 {
    let bit = |v: usize, k: usize| if v >> k & 1 == 1 { u32::MAX } else { 0 };
    (GENERATORS[0] & bit(x, 0))
        ^ (GENERATORS[1] & bit(y, 0))
        ^ (GENERATORS[2] & bit(x, 1))
        ^ (GENERATORS[3] & bit(y, 1))
}

/// The number of layouts of a block (see `layout_pattern`).
const LAYOUTS: u16 = 6 * 6 * 16;
/// The layouts step 3 tries per block and sweep.
const LAYOUT_TRIES: u32 = 32;

/// The pattern of the pixel at `(x, y)` of a block under layout `layout`: the place XOR-ed
/// with `(u, v)`, then each level's two bits (`x & 1, y & 1` and `x >> 1, y >> 1`) mapped by
/// one of the six invertible 2 x 2 matrices over GF(2) (`m0`, `m1`). Every layout gives each
/// 2 x 2 sub-block the same four patterns up to a common XOR (so its union stays the same
/// net) and the block its sixteen; they differ in which patterns neighbours on a row or a
/// column hold.
fn layout_pattern(layout: u16, x: usize, y: usize) -> u32 {
    const GL2: [[u8; 4]; 6] = [
        [1, 0, 0, 1],
        [0, 1, 1, 0],
        [1, 1, 0, 1],
        [1, 0, 1, 1],
        [0, 1, 1, 1],
        [1, 1, 1, 0],
    ];
    let (m0, m1, uv) = (layout % 6, layout / 6 % 6, layout / 36);
    let (x, y) = (x ^ (uv & 3) as usize, y ^ (uv >> 2) as usize);
    let map = |m: u16, a: usize, b: usize| {
        let g = GL2[m as usize];
        (
            (g[0] as usize & a) ^ (g[1] as usize & b),
            (g[2] as usize & a) ^ (g[3] as usize & b),
        )
    };
    let (x0, y0) = map(m0, x & 1, y & 1);
    let (x1, y1) = map(m1, x >> 1, y >> 1);
    pattern(x0 | x1 << 1, y0 | y1 << 1)
}

/// The blocks' state: per 4 x 4 block of the tile a shared key, a base rank and a layout; per
/// pixel the bits of its key the block does not share.
struct Blocks {
    side: usize,
    key: Vec<u32>,
    base: Vec<u32>,
    layout: Vec<u16>,
    deep: Vec<u32>,
    shared: u32,
}

/// The pixels of a block.
const PIXELS: usize = BLOCK * BLOCK;

impl Blocks {
    /// The pixels of block `b`, row-major within it.
    fn pixels(&self, b: usize) -> [usize; PIXELS] {
        Blocks::pixels_of(self.side, b)
    }

    /// The pixels of block `b` of a tile of side `side`, row-major within it.
    fn pixels_of(side: usize, b: usize) -> [usize; PIXELS] {
        let per_row = side / BLOCK;
        let (bx, by) = (b % per_row, b / per_row);
        core::array::from_fn(|j| (BLOCK * by + j / BLOCK) * side + BLOCK * bx + j % BLOCK)
    }

    /// The entry of the `j`-th pixel of block `b` with base rank `base` and layout `layout`.
    fn entry(&self, b: usize, j: usize, base: u32, layout: u16) -> [u32; 2] {
        let p = self.pixels(b)[j];
        [
            (self.key[b] & self.shared) | self.deep[p],
            base ^ layout_pattern(layout, j % BLOCK, j / BLOCK),
        ]
    }

    fn entries(&self) -> Vec<[u32; 2]> {
        let mut out = vec![[0u32; 2]; self.side * self.side];
        for b in 0..self.key.len() {
            for (j, p) in self.pixels(b).into_iter().enumerate() {
                out[p] = self.entry(b, j, self.base[b], self.layout[b]);
            }
        }
        out
    }

    /// Swaps what blocks `a` and `b` hold (their pixels' deep bits too).
    fn swap(&mut self, a: usize, b: usize) {
        self.key.swap(a, b);
        self.base.swap(a, b);
        self.layout.swap(a, b);
        let (pa, pb) = (self.pixels(a), self.pixels(b));
        for j in 0..PIXELS {
            self.deep.swap(pa[j], pb[j]);
        }
    }
}

/// Anneals swaps of whole blocks (`moves` proposals, most within 4 blocks) in `field`, a field
/// over the pixels, swapping `blocks` alike.
fn anneal_block_swaps(field: &mut Field, blocks: &mut Blocks, moves: u64, rng: &mut Pcg32) {
    let half = blocks.side / BLOCK;
    let nb = half * half;
    let f = field.f;
    let propose = |rng: &mut Pcg32| {
        let a = below(rng, nb);
        let b = if below(rng, 5) < 4 {
            let (dx, dy) = (below(rng, 9) as i32 - 4, below(rng, 9) as i32 - 4);
            torus(half, a, dx, dy)
        } else {
            below(rng, nb)
        };
        (a, b)
    };
    let mut new = vec![0.0f32; 2 * PIXELS * f];
    let mut d = Vec::with_capacity(2 * PIXELS * f);
    let mut delta_of = |field: &Field, blocks: &Blocks, a: usize, b: usize, new: &mut [f32]| {
        let (pa, pb) = (blocks.pixels(a), blocks.pixels(b));
        let mut pix = [0usize; 2 * PIXELS];
        for j in 0..PIXELS {
            pix[j] = pa[j];
            pix[PIXELS + j] = pb[j];
            new[j * f..][..f].copy_from_slice(&field.e[field.row(pb[j])]);
            new[(PIXELS + j) * f..][..f].copy_from_slice(&field.e[field.row(pa[j])]);
        }
        (pix, field.set_delta(&pix, new, &mut d))
    };
    // the temperature: from a twentieth of the mean change of a proposal down to a thousandth
    // of that
    let sample = 2000;
    let mut mean = 0.0;
    for _ in 0..sample {
        let (a, b) = propose(rng);
        if a != b {
            mean += delta_of(field, blocks, a, b, &mut new).1.abs();
        }
    }
    mean /= sample as f64;
    let (t0, t1) = (0.05 * mean, 0.05e-3 * mean);
    for it in 0..moves {
        let (a, b) = propose(rng);
        if a == b {
            continue;
        }
        let t = t0 * (t1 / t0).powf(it as f64 / moves as f64);
        let (pix, delta) = delta_of(field, blocks, a, b, &mut new);
        if delta < 0.0 || uniform(rng) < (-delta / t).exp() {
            field.set_replace(&pix, &new);
            blocks.swap(a, b);
        }
    }
}

/// Checks the options.
fn check(o: &TableOptions) -> Result<()> {
    let context = "samplers::bntable::optimise";
    if !o.side.is_power_of_two() || !(16..=MAX_SIDE).contains(&o.side) {
        return Err(Error::parameter(
            context,
            "side",
            o.side,
            format!("a power of two from 16 to {MAX_SIDE}"),
        ));
    }
    for (name, v, lo, hi) in [
        ("levels", o.levels, 1, 10),
        ("integrands", o.integrands, 1, 1024),
        ("effort", o.effort, 1, 10_000),
    ] {
        if !(lo..=hi).contains(&v) {
            return Err(Error::parameter(context, name, v, format!("{lo} to {hi}")));
        }
    }
    // the errors of every pixel at every count over every integrand, twice (the field and its
    // low-passed copy), in f32
    let numbers = (o.side as u64).pow(2) * (o.levels as u64 + 1) * o.integrands as u64;
    if numbers > MAX_FIELD {
        return Err(Error::input(
            context,
            format!(
                "side^2 (levels + 1) integrands = {numbers} errors per field: at most {MAX_FIELD} \
                 (2 GiB of memory for the two fields); take a smaller side, fewer levels or \
                 fewer integrands"
            ),
        ));
    }
    Ok(())
}

/// The most errors of one field [`optimise`] keeps (`side^2 (levels + 1) integrands`, `f32`):
/// 2^28, 1 GiB per field.
pub const MAX_FIELD: u64 = 1 << 28;

/// Makes a table (see the [module docs](self)); deterministic for given options.
pub fn optimise(o: &TableOptions) -> Result<Table> {
    check(o)?;
    let side = o.side as usize;
    let n = side * side;
    let levels = o.levels;
    let mut rng = pcg(o.seed.0, streams::BNTABLE);
    let tests: Vec<Shifted> = (0..o.integrands).map(|_| Shifted::draw(&mut rng)).collect();
    let held_out: Vec<Shifted> = (0..HELD_OUT).map(|_| Shifted::draw(&mut rng)).collect();
    let k = tests.len();
    let nb = n / PIXELS;
    let mask = (1u32 << levels) - 1;
    // per block a key, distinct, of which the pixels share the bits that scramble the digits
    // of the arranged counts' unions (the bits below `16 + levels + 2`: see `SHARED_DIGITS`);
    // base ranks random above the arranged bits, 0 below
    let shared = ((1u64 << (16 + levels + 4)) - 1) as u32;
    let high = MAX_RANK >> levels;
    let mut seen = std::collections::HashSet::with_capacity(nb);
    let mut key = Vec::with_capacity(nb);
    while key.len() < nb {
        let kk = rng.next_u32() & shared;
        if seen.insert(kk) {
            key.push(kk);
        }
    }
    drop(seen);
    let base = (0..nb)
        .map(|_| ((rng.next_u32() as u64 * high as u64) >> 32) as u32 * (1 << levels))
        .collect();
    // the pixels' own bits, distinct within each block (so that two pixels of a block never
    // draw the same samples)
    let mut deep = vec![0u32; n];
    for b in 0..nb {
        let pixels = Blocks::pixels_of(side, b);
        for (j, &p) in pixels.iter().enumerate() {
            deep[p] = loop {
                let d = rng.next_u32() & !shared;
                if pixels[..j].iter().all(|&q| deep[q] != d) {
                    break d;
                }
            };
        }
    }
    let mut blocks = Blocks {
        side,
        key,
        base,
        layout: (0..nb)
            .map(|_| below(&mut rng, LAYOUTS as usize) as u16)
            .collect(),
        deep,
        shared,
    };
    let errors_at = |entries: &[[u32; 2]], l: u32, flip: u32| -> Vec<f32> {
        let mut out = vec![0.0f32; (l as usize + 1) * k];
        let mut e = Vec::with_capacity(entries.len() * k);
        for &[key, rank] in entries {
            entry_errors(key, rank ^ flip, &tests, l, &mut out);
            e.extend_from_slice(&out[l as usize * k..]);
        }
        e
    };
    let moves = o.effort as u64 * nb as u64;

    // 1. blocks: the whole count's errors blue
    {
        let mut field = Field::new(side, k, errors_at(&blocks.entries(), levels, 0));
        anneal_block_swaps(&mut field, &mut blocks, moves, &mut rng);
    }

    // 2. base ranks, from the top down: bit l chooses the half of each pixel's 2^(l+1) samples
    // that comes first, for the four pixels of a block at once
    let mut new = vec![0.0f32; PIXELS * k];
    let mut scratch = Vec::new();
    for l in (0..levels).rev() {
        let entries = blocks.entries();
        let e_hold = errors_at(&entries, l, 0);
        let e_flip = errors_at(&entries, l, 1 << l);
        let mut field = Field::new(side, k, e_hold.clone());
        let mut flipped = vec![false; nb];
        let sweeps = (o.effort / 10).max(4);
        for s in 0..sweeps {
            // anneal for the first half of the sweeps, then descend
            let t = if s < sweeps / 2 {
                1.0 - s as f64 / (sweeps / 2) as f64
            } else {
                0.0
            };
            let scale = field_scale(&field);
            let mut changed = false;
            for _ in 0..nb {
                let b = below(&mut rng, nb);
                let other = if flipped[b] { &e_hold } else { &e_flip };
                let pix = blocks.pixels(b);
                for (j, &p) in pix.iter().enumerate() {
                    new[j * k..][..k].copy_from_slice(&other[p * k..][..k]);
                }
                let delta = field.set_delta(&pix, &new, &mut scratch);
                if delta < 0.0
                    || (t > 0.0 && uniform(&mut rng) < (-delta / (0.05 * t * scale)).exp())
                {
                    field.set_replace(&pix, &new);
                    flipped[b] = !flipped[b];
                    changed = true;
                }
            }
            if !changed && t == 0.0 {
                break;
            }
        }
        for (base, f) in blocks.base.iter_mut().zip(&flipped) {
            if *f {
                *base ^= 1 << l;
            }
        }
    }

    // 3. every count at once, each weighted by the inverse of its mean squared error: each
    // block's base rank's low `levels` bits (which of its pixels' blocks comes first at every
    // count), then the order of its patterns over its pixels, chosen anew against its
    // neighbours, sweep after sweep; then, if asked, whole blocks swapped
    let f = (levels as usize + 1) * k;
    let mut all = vec![0.0f32; n * f];
    for (p, &[key, rank]) in blocks.entries().iter().enumerate() {
        entry_errors(key, rank, &tests, levels, &mut all[p * f..][..f]);
    }
    let scales: Vec<f32> = (0..=levels as usize)
        .map(|l| {
            let ms: f64 = all
                .chunks(f)
                .flat_map(|row| row[l * k..(l + 1) * k].iter())
                .map(|&x| (x as f64) * (x as f64))
                .sum::<f64>()
                / (n * k) as f64;
            (1.0 / ms.max(1e-30)).sqrt() as f32
        })
        .collect();
    for row in all.chunks_mut(f) {
        for (l, s) in scales.iter().enumerate() {
            for x in &mut row[l * k..(l + 1) * k] {
                *x *= s;
            }
        }
    }
    let mut field = Field::new(side, f, all);
    let sweeps = (o.effort / 20).max(2);
    let mut candidate = vec![0.0f32; PIXELS * f];
    let mut best_new = vec![0.0f32; PIXELS * f];
    let scale_row = |row: &mut [f32]| {
        for (l, s) in scales.iter().enumerate() {
            for x in &mut row[l * k..(l + 1) * k] {
                *x *= s;
            }
        }
    };
    for _ in 0..sweeps {
        let mut changed = 0;
        for _ in 0..nb {
            let b = below(&mut rng, nb);
            let pix = blocks.pixels(b);
            let (base, layout) = (blocks.base[b], blocks.layout[b]);
            // the base rank's low bits: the tree of block sums of every pixel
            let sums: Vec<Vec<f64>> = (0..PIXELS)
                .map(|j| {
                    let [key, rank] = blocks.entry(b, j, base, layout);
                    block_sums(key, rank & !mask, &tests, levels)
                })
                .collect();
            let mut best = (0.0f64, base & mask);
            for low in 0..=mask {
                if low == base & mask {
                    continue;
                }
                for (j, sums) in sums.iter().enumerate() {
                    let rank_low = (low ^ layout_pattern(layout, j % BLOCK, j / BLOCK)) & mask;
                    let out = &mut candidate[j * f..][..f];
                    rank_features(sums, &tests, levels, rank_low, &scales, out);
                }
                let delta = field.set_delta(&pix, &candidate, &mut scratch);
                if delta < best.0 {
                    best = (delta, low);
                    best_new.copy_from_slice(&candidate);
                }
            }
            if best.0 < 0.0 {
                field.set_replace(&pix, &best_new);
                blocks.base[b] = (base & !mask) | best.1;
                changed += 1;
            }
            // the layout: the sums of each of the sixteen patterns under the first pixel's
            // key (the pixels' keys differ in digits past those the errors see), some layouts
            // tried, the best one's errors computed exactly
            let base = blocks.base[b];
            let key0 = blocks.entry(b, 0, base, layout)[0];
            let patterns: Vec<u32> = (0..PIXELS)
                .map(|j| layout_pattern(0, j % BLOCK, j / BLOCK))
                .collect();
            let pattern_sums: Vec<Vec<f64>> = patterns
                .iter()
                .map(|&pat| block_sums(key0, (base ^ pat) & !mask, &tests, levels))
                .collect();
            let mut best = (0.0f64, layout);
            for _ in 0..LAYOUT_TRIES {
                let l = below(&mut rng, LAYOUTS as usize) as u16;
                if l == layout {
                    continue;
                }
                for j in 0..PIXELS {
                    let pat = layout_pattern(l, j % BLOCK, j / BLOCK);
                    let q = patterns.iter().position(|&p| p == pat).unwrap_or(0);
                    let out = &mut candidate[j * f..][..f];
                    rank_features(
                        &pattern_sums[q],
                        &tests,
                        levels,
                        (base ^ pat) & mask,
                        &scales,
                        out,
                    );
                }
                let delta = field.set_delta(&pix, &candidate, &mut scratch);
                if delta < best.0 {
                    best = (delta, l);
                }
            }
            if best.0 < 0.0 {
                for j in 0..PIXELS {
                    let [key, rank] = blocks.entry(b, j, base, best.1);
                    let out = &mut candidate[j * f..][..f];
                    entry_errors(key, rank, &tests, levels, out);
                    scale_row(out);
                }
                field.set_replace(&pix, &candidate);
                blocks.layout[b] = best.1;
                changed += 1;
            }
        }
        if changed == 0 {
            break;
        }
    }
    if o.polish {
        anneal_block_swaps(&mut field, &mut blocks, moves, &mut rng);
    }

    drop(field);
    let entries = blocks.entries();
    // a table the renderer's crate takes (the keys are distinct)
    BlueNoiseTable::new(o.side, &entries)?;
    let lowband = figures(o.side, levels, &held_out, &random_entries(o), &entries)?;
    Ok(Table {
        options: *o,
        entries,
        lowband,
    })
}

/// The sums of every test over every aligned block of the first `2^levels` samples of the
/// entry `(key, base)` (`base` a rank with its low `levels` bits 0): block `b` of `2^l` samples
/// at `[(2^(levels - l) - 1 + b) * tests.len() ..]`, a binary tree whose root is the whole set.
fn block_sums(key: u32, base: u32, tests: &[Shifted], levels: u32) -> Vec<f64> {
    let k = tests.len();
    let leaves = 1usize << levels;
    let mut sums = vec![0.0f64; (2 * leaves - 1) * k];
    for i in 0..leaves {
        let p = BlueNoiseTable::point_u32(i as u32, base, key);
        let row = &mut sums[(leaves - 1 + i) * k..(leaves + i) * k];
        for (s, t) in row.iter_mut().zip(tests) {
            *s = t.eval(p);
        }
    }
    for node in (0..leaves - 1).rev() {
        for j in 0..k {
            sums[node * k + j] = sums[(2 * node + 1) * k + j] + sums[(2 * node + 2) * k + j];
        }
    }
    sums
}

/// The scaled errors of every count of the entry whose rank's low bits are `low`, from its
/// [`block_sums`]: at count `2^l` the block `low >> l` of the tree's level `levels - l`.
fn rank_features(
    sums: &[f64],
    tests: &[Shifted],
    levels: u32,
    low: u32,
    scales: &[f32],
    out: &mut [f32],
) {
    let k = tests.len();
    for l in 0..=levels {
        let node = (1usize << (levels - l)) - 1 + (low >> l) as usize;
        let count = (1u32 << l) as f64;
        for (j, t) in tests.iter().enumerate() {
            out[l as usize * k + j] =
                ((sums[node * k + j] / count - t.integral()) as f32) * scales[l as usize];
        }
    }
}

/// The mean squared value of a field's errors (the annealing's scale).
fn field_scale(field: &Field) -> f64 {
    let e = &field.e;
    let mean_sq = e.iter().map(|&x| (x as f64) * (x as f64)).sum::<f64>() / e.len() as f64;
    mean_sq * field.offsets.len() as f64 * field.f as f64 / 10.0
}

/// Entries with distinct random keys and random ranks (white noise), drawn by `o.seed`.
fn random_entries(o: &TableOptions) -> Vec<[u32; 2]> {
    let mut rng = pcg(o.seed.0, streams::BNTABLE_RANDOM);
    let n = (o.side * o.side) as usize;
    let mut keys = std::collections::HashSet::with_capacity(n);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let key = rng.next_u32();
        if keys.insert(key) {
            out.push([
                key,
                ((rng.next_u32() as u64 * MAX_RANK as u64) >> 32) as u32,
            ]);
        }
    }
    out
}

/// The low-band shares per count of random entries and of the table, over `tests`.
fn figures(
    side: u32,
    levels: u32,
    tests: &[Shifted],
    random: &[[u32; 2]],
    table: &[[u32; 2]],
) -> Result<Vec<LevelFigures>> {
    let a = lowband_per_count(side, levels, tests, random)?;
    let b = lowband_per_count(side, levels, tests, table)?;
    Ok((0..=levels)
        .map(|l| LevelFigures {
            count: 1 << l,
            random: a[l as usize],
            table: b[l as usize],
        })
        .collect())
}

/// Per count `2^l`, the mean over `tests` of the low-band share of the error image of the
/// tile `entries` (`side x side`).
fn lowband_per_count(
    side: u32,
    levels: u32,
    tests: &[Shifted],
    entries: &[[u32; 2]],
) -> Result<Vec<f64>> {
    let k = tests.len();
    let f = (levels as usize + 1) * k;
    let mut all = vec![0.0f32; entries.len() * f];
    for (p, out) in all.chunks_mut(f).enumerate() {
        entry_errors(entries[p][0], entries[p][1], tests, levels, out);
    }
    let mut out = Vec::new();
    for l in 0..=levels as usize {
        let mut sum = 0.0;
        for j in 0..k {
            let image: Vec<f64> = all.chunks(f).map(|row| row[l * k + j] as f64).collect();
            sum += error_image(&image, side, side)?.lowband;
        }
        out.push(sum / k as f64);
    }
    Ok(out)
}

/// The low-band share per count `1, 2, ..., 2^levels` of the error image over a table's
/// tile (`side x side` entries `(key, rank)`), mean over 64 test integrands drawn by `seed` (the
/// kinds [`optimise`] arranges for): how blue a table is, 0.049 for white noise.
pub fn table_lowband(side: u32, entries: &[[u32; 2]], levels: u32, seed: Seed) -> Result<Vec<f64>> {
    BlueNoiseTable::new(side, entries)?;
    if !(1..=10).contains(&levels) {
        return Err(Error::parameter(
            "samplers::bntable::table_lowband",
            "levels",
            levels,
            "1 to 10",
        ));
    }
    let mut rng = pcg(seed.0, streams::BNTABLE_TESTS);
    let tests: Vec<Shifted> = (0..HELD_OUT).map(|_| Shifted::draw(&mut rng)).collect();
    lowband_per_count(side, levels, &tests, entries)
}

/// The Rust source of `table` for the renderer's crate: a header naming the options, `command`
/// and the run time, then `SIDE` and `ENTRIES`.
pub fn rust_table(table: &Table, command: &str, seconds: f64) -> String {
    let o = &table.options;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "//! {which} table of `sobolbn`: {side} x {side} entries `[key, rank]`, made by the \
         lab's\n\
         //! `bntable` program (`strata_lab::samplers::bntable::optimise`: side {side}, levels \
         {levels},\n\
         //! integrands {integrands}, effort {effort}, polish {polish}, seed {seed:#x}) in \
         {seconds:.0} s on one core:\n\
         //! `{command}`.\n\
         //! The low-band share of the error over the tile per count (held-out integrands; white\n\
         //! noise 0.049):",
        side = o.side,
        levels = o.levels,
        integrands = o.integrands,
        effort = o.effort,
        polish = o.polish,
        seed = o.seed.0,
        which = if *o == BUILTIN { "The built-in" } else { "A" },
    );
    for f in &table.lowband {
        let _ = writeln!(
            s,
            "//! {} spp: {:.4} (random entries: {:.4})",
            f.count, f.table, f.random
        );
    }
    let _ = writeln!(
        s,
        "\n/// The side of the tile.\npub(super) const SIDE: u32 = {};\n\n/// The entries `[key, \
         rank]`, row-major (four to a line).\n#[rustfmt::skip]\npub(super) static ENTRIES: [[u32; 2]; {}] = [",
        o.side,
        table.entries.len()
    );
    for row in table.entries.chunks(4) {
        let line: Vec<String> = row
            .iter()
            .map(|[k, r]| format!("[0x{k:08x}, 0x{r:04x}],"))
            .collect();
        let _ = writeln!(s, "    {}", line.join(" "));
    }
    s.push_str("];\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_test_integrals_are_exact() {
        // against a fine grid of midpoints
        let mut rng = pcg(5, streams::BNTABLE);
        for _ in 0..40 {
            let t = Test::draw(&mut rng);
            let g = 400;
            let mut sum = 0.0;
            for i in 0..g {
                for j in 0..g {
                    sum += t.eval([(i as f64 + 0.5) / g as f64, (j as f64 + 0.5) / g as f64]);
                }
            }
            let grid = sum / (g * g) as f64;
            assert!((grid - t.integral()).abs() < 4e-3, "{t:?}: grid {grid}");
        }
    }

    /// A small table: side 32, counts 1 to 8.
    fn small() -> TableOptions {
        TableOptions {
            side: 32,
            levels: 3,
            integrands: 16,
            effort: 40,
            polish: true,
            seed: Seed(3),
        }
    }

    #[test]
    fn a_small_table_is_much_bluer_than_random_entries_at_every_count() {
        let o = small();
        let t = optimise(&o).unwrap();
        BlueNoiseTable::new(32, &t.entries).unwrap();
        for f in &t.lowband {
            assert!(f.table < 0.5 * f.random, "{f:?}");
        }
        assert_eq!(optimise(&o).unwrap(), t, "deterministic");
    }

    /// Whether `points` (`2^m` of them) are a (t, m, 2)-net: every elementary interval of area
    /// `2^(t - m)` holds `2^t` points.
    fn is_net(points: &[[u32; 2]], t: u32) -> bool {
        let m = points.len().trailing_zeros();
        let q = m - t;
        (0..=q).all(|d1| {
            let d2 = q - d1;
            let mut cells = vec![0u32; 1 << q];
            for p in points {
                let (x, y) = (p[0].checked_shr(32 - d1), p[1].checked_shr(32 - d2));
                cells[((x.unwrap_or(0) << d2) | y.unwrap_or(0)) as usize] += 1;
            }
            cells.iter().all(|&c| c == 1 << t)
        })
    }

    #[test]
    fn the_union_of_a_block_s_samples_is_the_net_its_generators_promise_at_every_count() {
        // the first 2^k samples of every 2 x 2 sub-block: (0, k+2, 2)-nets at 1 to 8 samples;
        // of every 4 x 4 block: (t, k+4, 2) with t = 0, 0, 0, 1 at 1 to 8 samples; and along
        // the first coordinate, one point per interval of 2^-(k+4)
        let o = small();
        let t = optimise(&o).unwrap();
        let side = o.side as usize;
        let union = |x0: usize, y0: usize, w: usize, k: u32| -> Vec<[u32; 2]> {
            let mut out = Vec::new();
            for y in y0..y0 + w {
                for x in x0..x0 + w {
                    let [key, rank] = t.entries[y * side + x];
                    for i in 0..1u32 << k {
                        out.push(BlueNoiseTable::point_u32(i, rank, key));
                    }
                }
            }
            out
        };
        let mut checked = 0;
        for k in 0..=o.levels {
            for by in (0..side).step_by(4) {
                for bx in (0..side).step_by(4) {
                    let mut keys: Vec<u32> = (0..16)
                        .map(|j| t.entries[(by + j / 4) * side + bx + j % 4][0])
                        .collect();
                    keys.sort_unstable();
                    keys.dedup();
                    assert_eq!(keys.len(), 16, "block ({bx}, {by}): two pixels share a key");
                    let whole = union(bx, by, 4, k);
                    let tv = [0, 0, 0, 1][k as usize];
                    assert!(
                        is_net(&whole, tv),
                        "block ({bx}, {by}) at 2^{k}: not a t = {tv} net"
                    );
                    let mut xs: Vec<u32> = whole.iter().map(|p| p[0] >> (32 - (k + 4))).collect();
                    xs.sort_unstable();
                    xs.dedup();
                    assert_eq!(xs.len(), whole.len(), "block ({bx}, {by}) at 2^{k}: x");
                    for (dx, dy) in [(0, 0), (2, 0), (0, 2), (2, 2)] {
                        let sub = union(bx + dx, by + dy, 2, k);
                        assert!(
                            is_net(&sub, 0),
                            "sub-block ({}, {}) at 2^{k}",
                            bx + dx,
                            by + dy
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 4 * 64 * 4);
    }

    /// The low-band share (below 1/8 cycle per pixel, white: 0.25) of the errors along the
    /// rows (`along_rows`) or the columns of the tile `entries` at `n` samples, for steps along
    /// coordinate `axis` seen through random digital shifts, mean over 16 steps and every line.
    fn line_lowband(
        entries: &[[u32; 2]],
        side: usize,
        n: u32,
        along_rows: bool,
        axis: usize,
    ) -> f64 {
        let mut rng = pcg(9, streams::BNTABLE_TESTS);
        let (mut low, mut all) = (0.0, 0.0);
        for _ in 0..16 {
            let (t, shift) = (rng.next_u32(), rng.next_u32());
            let errors: Vec<f64> = entries
                .iter()
                .map(|&[key, rank]| {
                    let inside = (0..n)
                        .filter(|&i| BlueNoiseTable::point_u32(i, rank, key)[axis] ^ shift < t)
                        .count();
                    inside as f64 / n as f64 - t as f64 / 4_294_967_296.0
                })
                .collect();
            for line in 0..side {
                let at = |i: usize| {
                    if along_rows {
                        errors[line * side + i]
                    } else {
                        errors[i * side + line]
                    }
                };
                for f in 1..side {
                    let (mut re, mut im) = (0.0, 0.0);
                    for i in 0..side {
                        let a = 2.0 * std::f64::consts::PI * (f * i) as f64 / side as f64;
                        re += at(i) * a.cos();
                        im += at(i) * a.sin();
                    }
                    let power = re * re + im * im;
                    all += power;
                    if f.min(side - f) * 8 <= side {
                        low += power;
                    }
                }
            }
        }
        low / all
    }

    #[test]
    fn a_small_table_is_blue_along_its_rows_and_its_columns() {
        // an edge of the image along a row meets the same step in every pixel of it: the
        // error along the row alone must be blue, not only the tile's (a layout that gives the
        // neighbours on a row patterns whose sets share their strata makes it red)
        let o = small();
        let t = optimise(&o).unwrap();
        let random = random_entries(&o);
        for n in [1, 2, 4, 8] {
            for along_rows in [true, false] {
                for axis in 0..2 {
                    let table = line_lowband(&t.entries, 32, n, along_rows, axis);
                    let white = line_lowband(&random, 32, n, along_rows, axis);
                    assert!(
                        table < 0.85 * white,
                        "{n} spp, rows {along_rows}, axis {axis}: {table:.3} against {white:.3}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_generators_make_the_nets_they_promise() {
        let [a, b, c, d] = GENERATORS;
        let union = |k: u32, gens: &[u32]| -> Vec<[u32; 2]> {
            let mut out = Vec::new();
            for m in 0..1u32 << gens.len() {
                let offset = (0..gens.len())
                    .filter(|&g| m >> g & 1 == 1)
                    .fold(0, |acc, g| acc ^ gens[g]);
                for i in 0..1u32 << k {
                    out.push(BlueNoiseTable::point_u32(i, offset, 0x2545_f491));
                }
            }
            out
        };
        for (k, (t2, t4)) in [(0, 0), (0, 0), (0, 0), (0, 1), (1, 1), (2, 1), (0, 1)]
            .into_iter()
            .enumerate()
        {
            let k = k as u32;
            assert!(is_net(&union(k, &[a, b]), t2), "sub-block at 2^{k}");
            assert!(
                t2 == 0 || !is_net(&union(k, &[a, b]), t2 - 1),
                "sub-block's t at 2^{k}"
            );
            assert!(is_net(&union(k, &[a, b, c, d]), t4), "block at 2^{k}");
            assert!(
                t4 == 0 || !is_net(&union(k, &[a, b, c, d]), t4 - 1),
                "block's t at 2^{k}"
            );
        }
        let independent = |gens: &[u32], k: u32| {
            let w = gens.len() as u32;
            // the span of the generators' bits k..k+w has 2^w elements
            let mut seen = std::collections::HashSet::new();
            for m in 0..1u32 << w {
                let v = (0..w as usize)
                    .filter(|&g| m >> g & 1 == 1)
                    .fold(0, |acc, g| acc ^ gens[g]);
                seen.insert((v >> k) & ((1 << w) - 1));
            }
            seen.len() == 1 << w
        };
        assert!((0..15).all(|k| independent(&[a, b], k)));
        assert!((0..13).all(|k| independent(&[a, b, c, d], k)));
        assert!(!independent(&[a, b, c, d], 13), "16 bits hold no more");
    }

    #[test]
    fn the_net_checker_refuses_a_set_that_is_not_one() {
        // the first four Sobol' points are a (0,2,2)-net; the four of one column are not
        let good: Vec<[u32; 2]> = (0..4).map(|i| BlueNoiseTable::point_u32(i, 0, 0)).collect();
        assert!(is_net(&good, 0));
        let bad: Vec<[u32; 2]> = (0..4)
            .map(|i| BlueNoiseTable::point_u32(4 * i, 0, 0))
            .collect();
        assert!(!is_net(&bad, 0));
    }

    #[test]
    fn bad_options_are_refused() {
        for o in [
            TableOptions { side: 8, ..BUILTIN },
            TableOptions {
                side: 100,
                ..BUILTIN
            },
            TableOptions {
                levels: 0,
                ..BUILTIN
            },
            TableOptions {
                levels: 11,
                ..BUILTIN
            },
            TableOptions {
                integrands: 0,
                ..BUILTIN
            },
            TableOptions {
                effort: 0,
                ..BUILTIN
            },
        ] {
            assert!(optimise(&o).is_err(), "{o:?}");
        }
    }
}
