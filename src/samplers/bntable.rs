//! The tables of the renderer crate's progressive blue-noise sequences
//! ([`strata::pixel::BlueNoiseTable`], the sequence `sobolbn`): per pixel of a toroidal tile, a
//! key (an Owen scramble) and a rank (an XOR of the sample index), arranged so that
//! neighbouring pixels' errors cancel at every power of two from 1 to `2^levels` samples. The
//! built-in table is [`optimise`]`(&`[`BUILTIN`]`)`, written into
//! `strata/src/pixel/bluenoise/sobol_128.rs` by the `bntable` program.
//!
//! The method is OpenQMC's (Framestore, `src/tools/lib/optimise.cpp`, after Heitz, Belcour et
//! al. 2019 and Belcour and Heitz 2021), rewritten over this crate's draws:
//!
//! 1. **Keys.** Random keys (ranks random above their low `levels` bits, 0 below) are permuted
//!    over the tile so that the errors of the *whole* count, `2^levels` samples, are blue.
//! 2. **Ranks, from the top down.** At each count `2^l` below it, every pixel chooses which half
//!    of its `2^(l+1)` samples comes first (bit `l` of its rank): the sets of the larger counts
//!    stay, the error at `2^l` becomes blue.
//! 3. **Every count at once** (our step): each pixel's rank (which of its blocks comes first at
//!    every count) is chosen anew against its neighbours, sweep after sweep, then whole entries
//!    are swapped between pixels (the *polish*), against the errors of every count, each count
//!    weighted by the inverse of its mean squared error.
//!
//! "Blue" is measured by the energy `sum_p sum_q w(p - q) <e_p, e_q>`: `e_p` the pixel's errors
//! over a set of test integrands of the draw's 2D domain, `w` a Gaussian of 2.1 pixels over a
//! 13 x 13 window (0 at the centre); low energy means neighbouring errors of opposite signs,
//! little power at low frequencies. The integrands: edges of random position and orientation
//! (two in five, as OpenQMC's oriented Heavisides), steps along the first coordinate (three in
//! ten: a renderer's 1D draws, a light or a lobe choice, read the first coordinate), along the
//! second (one in ten), Gaussian bumps of random centre and width (the rest), each seen through
//! a random digital shift, as the draws see them (each draw XORs its values with a shift per
//! seed and dimension). The figures are over another draw of the same kinds (held out). Each
//! step makes single moves (swaps, rank choices), the energy's change computed from a
//! low-passed field of the errors that each accepted move updates (as the lab's tile study
//! does).
//!
//! What it reaches, and what it cannot: a pixel's sets at the counts are blocks of its own
//! scrambled sequence, independent of its neighbours', so the arrangement chooses among them
//! but cannot make a neighbourhood's union a finer net as a Z order told the count does: the
//! low-band share falls most at 1 and 2 samples and less at each larger count (the table's
//! header has the figures).

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
    /// (held-out integrands, mean over them) of the random start and of the table.
    pub lowband: Vec<LevelFigures>,
}

/// The low-band shares at one count (see [`Table::lowband`]; white noise is about 0.049).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelFigures {
    /// Samples per pixel.
    pub count: u32,
    /// The random entries before the optimisation.
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
                let w = (-((dx * dx + dy * dy) as f64) / (2.0 * SIGMA * SIGMA)).exp() as f32;
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

    /// The energy's change if pixels `a` and `b` swapped their errors.
    fn swap_delta(&self, a: usize, b: usize) -> f64 {
        let (ra, rb) = (self.row(a), self.row(b));
        let (ea, eb, sa, sb) = (
            &self.e[ra.clone()],
            &self.e[rb.clone()],
            &self.s[ra],
            &self.s[rb],
        );
        let (mut dot, mut dd) = (0.0f64, 0.0f64);
        for j in 0..self.f {
            let d = (eb[j] - ea[j]) as f64;
            dot += d * (sa[j] - sb[j]) as f64;
            dd += d * d;
        }
        2.0 * dot - 2.0 * self.weight(a, b) as f64 * dd
    }

    /// Adds `sign * d` to pixel `p`'s errors' contribution to its neighbours' fields.
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

    fn swap(&mut self, a: usize, b: usize) {
        let d: Vec<f32> = (0..self.f)
            .map(|j| self.e[b * self.f + j] - self.e[a * self.f + j])
            .collect();
        self.spread(a, &d);
        let minus: Vec<f32> = d.iter().map(|x| -x).collect();
        self.spread(b, &minus);
        for j in 0..self.f {
            self.e.swap(a * self.f + j, b * self.f + j);
        }
    }

    /// The energy's change if pixel `a`'s errors became `new`.
    fn replace_delta(&self, a: usize, new: &[f32]) -> f64 {
        let r = self.row(a);
        let (ea, sa) = (&self.e[r.clone()], &self.s[r]);
        (0..self.f)
            .map(|j| 2.0 * (new[j] - ea[j]) as f64 * sa[j] as f64)
            .sum()
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

/// Anneals swaps of `field`'s pixels (`moves` proposals, most within 4 pixels), swapping
/// `entries` alike.
fn anneal_swaps(field: &mut Field, entries: &mut [[u32; 2]], moves: u64, rng: &mut Pcg32) {
    let side = field.side;
    let n = side * side;
    let propose = |rng: &mut Pcg32| {
        let a = below(rng, n);
        let b = if below(rng, 5) < 4 {
            let (dx, dy) = (below(rng, 9) as i32 - 4, below(rng, 9) as i32 - 4);
            torus(side, a, dx, dy)
        } else {
            below(rng, n)
        };
        (a, b)
    };
    // the temperature: from a twentieth of the mean change of a proposal down to a thousandth
    // of that
    let sample = 2000;
    let mean = (0..sample)
        .map(|_| {
            let (a, b) = propose(rng);
            field.swap_delta(a, b).abs()
        })
        .sum::<f64>()
        / sample as f64;
    let (t0, t1) = (0.05 * mean, 0.05e-3 * mean);
    for it in 0..moves {
        let (a, b) = propose(rng);
        if a == b {
            continue;
        }
        let t = t0 * (t1 / t0).powf(it as f64 / moves as f64);
        let delta = field.swap_delta(a, b);
        if delta < 0.0 || uniform(rng) < (-delta / t).exp() {
            field.swap(a, b);
            entries.swap(a, b);
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
    // random keys; ranks random above the arranged bits, 0 below
    let high = MAX_RANK >> levels;
    // distinct keys, so that no two entries are alike
    let mut keys = std::collections::HashSet::with_capacity(n);
    let mut entries: Vec<[u32; 2]> = Vec::with_capacity(n);
    while entries.len() < n {
        let key = rng.next_u32();
        let rank = ((rng.next_u32() as u64 * high as u64) >> 32) as u32 * (1 << levels);
        if keys.insert(key) {
            entries.push([key, rank]);
        }
    }
    drop(keys);
    let start = entries.clone();
    let all_errors = |entries: &[[u32; 2]], tests: &[Shifted]| {
        let f = (levels as usize + 1) * tests.len();
        let mut e = vec![0.0f32; entries.len() * f];
        for (p, out) in e.chunks_mut(f).enumerate() {
            entry_errors(entries[p][0], entries[p][1], tests, levels, out);
        }
        e
    };
    let level_of = |all: &[f32], l: usize, kk: usize| -> Vec<f32> {
        let f = (levels as usize + 1) * kk;
        all.chunks(f)
            .flat_map(|row| row[l * kk..(l + 1) * kk].iter().copied())
            .collect()
    };
    let moves = o.effort as u64 * n as u64;

    // 1. keys: the whole count's errors blue
    {
        let top = level_of(&all_errors(&entries, &tests), levels as usize, k);
        let mut field = Field::new(side, k, top);
        anneal_swaps(&mut field, &mut entries, moves, &mut rng);
    }

    // 2. ranks, from the top down: bit l chooses the half of the 2^(l+1) samples that comes
    // first
    for l in (0..levels).rev() {
        let mut hold = vec![0.0f32; (levels as usize + 1) * k];
        let mut flip = hold.clone();
        let mut e_hold = Vec::with_capacity(n * k);
        let mut e_flip = Vec::with_capacity(n * k);
        for &[key, rank] in &entries {
            entry_errors(key, rank, &tests, l + 1, &mut hold[..(l as usize + 2) * k]);
            entry_errors(
                key,
                rank ^ (1 << l),
                &tests,
                l + 1,
                &mut flip[..(l as usize + 2) * k],
            );
            e_hold.extend_from_slice(&hold[l as usize * k..(l as usize + 1) * k]);
            e_flip.extend_from_slice(&flip[l as usize * k..(l as usize + 1) * k]);
        }
        let mut field = Field::new(side, k, e_hold.clone());
        let mut flipped = vec![false; n];
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
            for _ in 0..n {
                let p = below(&mut rng, n);
                let other = if flipped[p] { &e_hold } else { &e_flip };
                let new = &other[p * k..(p + 1) * k];
                let delta = field.replace_delta(p, new);
                if delta < 0.0
                    || (t > 0.0 && uniform(&mut rng) < (-delta / (0.05 * t * scale)).exp())
                {
                    field.replace(p, new);
                    flipped[p] = !flipped[p];
                    changed = true;
                }
            }
            if !changed && t == 0.0 {
                break;
            }
        }
        for (e, f) in entries.iter_mut().zip(&flipped) {
            if *f {
                e[1] ^= 1 << l;
            }
        }
    }

    // 3. every count at once, each weighted by the inverse of its mean squared error: each
    // pixel's rank (its low `levels` bits: which of its blocks comes first at every count)
    // chosen anew against its neighbours, sweep after sweep; then, if asked, whole entries
    // swapped between pixels
    let f = (levels as usize + 1) * k;
    let mut all = all_errors(&entries, &tests);
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
    let mut candidate = vec![0.0f32; f];
    for _ in 0..sweeps {
        let mut changed = 0;
        for _ in 0..n {
            let p = below(&mut rng, n);
            let [key, rank] = entries[p];
            let sums = block_sums(key, rank & !((1 << levels) - 1), &tests, levels);
            let mut best = (0.0f64, rank);
            for low in 0..1u32 << levels {
                let r = (rank & !((1 << levels) - 1)) | low;
                if r == rank {
                    continue;
                }
                rank_features(&sums, &tests, levels, low, &scales, &mut candidate);
                let delta = field.replace_delta(p, &candidate);
                if delta < best.0 {
                    best = (delta, r);
                }
            }
            if best.1 != rank {
                rank_features(
                    &sums,
                    &tests,
                    levels,
                    best.1 & ((1 << levels) - 1),
                    &scales,
                    &mut candidate,
                );
                field.replace(p, &candidate);
                entries[p][1] = best.1;
                changed += 1;
            }
        }
        if changed == 0 {
            break;
        }
    }
    if o.polish {
        anneal_swaps(&mut field, &mut entries, moves, &mut rng);
    }

    drop(field);
    // a table the renderer's crate takes (the keys are distinct)
    BlueNoiseTable::new(o.side, &entries)?;
    let lowband = figures(o.side, levels, &held_out, &start, &entries)?;
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

/// The low-band shares per count of the start and of the table, over `tests`.
fn figures(
    side: u32,
    levels: u32,
    tests: &[Shifted],
    start: &[[u32; 2]],
    table: &[[u32; 2]],
) -> Result<Vec<LevelFigures>> {
    let a = lowband_per_count(side, levels, tests, start)?;
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

    #[test]
    fn a_small_table_is_bluer_than_its_random_start_at_every_count() {
        let o = TableOptions {
            side: 32,
            levels: 3,
            integrands: 16,
            effort: 40,
            polish: true,
            seed: Seed(3),
        };
        let t = optimise(&o).unwrap();
        BlueNoiseTable::new(32, &t.entries).unwrap();
        // much bluer at the smallest counts, bluer at every count
        for f in &t.lowband {
            let bound = if f.count <= 2 { 0.6 } else { 0.9 };
            assert!(f.table < bound * f.random, "{f:?}");
        }
        assert_eq!(optimise(&o).unwrap(), t, "deterministic");
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
