//! The conformance suite: a statistical battery that any path-tracer sequence can be run
//! through, so that a renderer knows its draws are unbiased, independent and stratified before
//! it renders with them.
//!
//! A renderer combines, in one integrand, the values of different draws of one pixel sample:
//! the film position, the lens, the light, the next bounce. If two draws are tied together (the
//! value of one a function of the other's), the pixel's estimate converges to a wrong value,
//! and no amount of samples helps. Averaging a signed statistic over many pixels hides this
//! (a correlation of +0.9 in one pixel cancels -0.9 in the next), so every test here is run
//! **per case** (per pixel, seed and pair of dimensions) on the **magnitude** of its statistic,
//! and the suite fails if any single case fails. This follows the shape of OpenQMC's test
//! battery: the same hypothesis tests for every sampler and every pair of dimensions.
//!
//! # What is tested
//!
//! The source gives values by `(seed, pixel, sample index, dimension)`; dimensions `2k` and
//! `2k + 1` form the `k`-th 2D draw (as `points --pixel` prints them). For each seed and pixel
//! (an *instance*), `n` = [`Suite::spp`] samples of dimensions `0..D` are drawn, and:
//!
//! * **integrands**: for every pair of dimensions, inside a draw and across draws, the
//!   estimate of a quarter disk, a Gaussian and four oriented Heavisides (half-planes at four
//!   angles): `|z| = |estimate - exact| / (sigma / sqrt n)`, with `sigma^2` the integrand's
//!   variance under uniform sampling. A sequence passes if no case errs more than independent
//!   uniform sampling plausibly would;
//! * **products**: the same for `x_a x_b` (exact 1/4): the estimate of `E[x_a x_b]` per pixel
//!   within `max(6, z*)` sigma of an independent estimate's, `z*` the Bonferroni bound below;
//! * **chi-square**: Pearson's statistic of the pair's counts on a `P x P` grid, upper tail,
//!   `P^2 - 1` degrees of freedom. `P` is prime, so that no dyadic or triadic stratification
//!   aligns with the cells: 31 (the grid of OpenQMC's battery) from 3844 samples on, below that
//!   the largest prime with at least 4 expected points per cell (13 at 1024, 5 at 128, 2 at
//!   16), where Pearson's statistic is still close to its chi-square law;
//! * **t-test over seeds** (with two or more seeds): per pixel, pair and integrand (products
//!   included), Student's t of the errors over the seeds, two-sided, `seeds - 1` degrees of
//!   freedom: unbiasedness over the randomization. (The errors' spread gets a floor of `1/n`,
//!   the resolution of an estimate from `n` values, so that a stratified set meeting a step
//!   the same way under every seed does not divide by zero.);
//! * **variance over seeds**: per pixel, pair and integrand, `sum_seeds z^2`, chi-square with
//!   `seeds` degrees of freedom: an error larger than independent sampling's, seed after seed;
//! * **across pixels** and **across seeds**: products and chi-square between the same
//!   dimension of two pixels (every pair of [`Suite::pixels`]) and of two seeds (consecutive
//!   [`Suite::seeds`]);
//! * **stratification**: the grids each draw promises ([`Source::promised_strata`]) counted
//!   cell by cell at every count `n' <= n` where a promise is made: every cell must hold
//!   exactly `n' / cells` points.
//!
//! # False alarms
//!
//! Each statistic's null hypothesis is that the sequence is no worse than independent uniform
//! sampling (its error has mean zero and a variance at most `sigma^2 / n`, close to normal; its
//! counts are uniform). Stratified and low-discrepancy sequences do much better than that on
//! these integrands, so a correct sequence sits far inside every bound. The family-wise false
//! alarm rate is [`Suite::false_alarm`] (default `1e-6`), split evenly over the rows of the
//! report and, within a row, over its cases (Bonferroni): a correct sequence fails a run with
//! probability at most about `1e-6`, and a run is deterministic (fixed seeds), so it either
//! always passes or always fails.
//!
//! # Use on a renderer's own values
//!
//! ```
//! use strata_lab::conformance::Suite;
//! use strata::{PixelSampler, Seed, Sequence};
//! let suite = Suite {
//!     spp: 256,
//!     dimensions: 6,
//!     pixels: vec![[0, 0], [1, 0], [7, 3]],
//!     seeds: [1, 2, 3, 4].map(Seed).to_vec(),
//!     ..Suite::default()
//! };
//! // the renderer's sampler behind a closure (pixel, index, dimension, seed) -> value
//! let report = suite.run(&|pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
//!     let s = PixelSampler::new(Sequence::sobol(), 256, seed).unwrap();
//!     s.sample_2d(pixel, index, dim & !1)[(dim & 1) as usize]
//! })?;
//! assert!(report.passed(), "{report}");
//! # Ok::<(), strata_lab::Error>(())
//! ```

mod pairs;

use std::fmt;

pub use pairs::{PairReport, PairStudy, Shuffle};

use crate::analysis::Integrand;
use crate::stats;
use crate::{Error, Result};
use strata::Seed;
use strata::StrataGrid;
use strata::pixel::{Padding, PixelSampler, Sequence};

/// What the suite draws values from.
///
/// Closures `Fn(pixel, index, dim, seed) -> f32` implement it; for a [`Sequence`] use
/// [`SequenceSource`] (which also states the sequence's promised stratification).
pub trait Source: Sync {
    /// Dimension `dim` of sample `index` of `pixel`, under `seed`, in `[0, 1)`. Dimensions
    /// `2k` and `2k + 1` are the `k`-th 2D draw.
    fn value(&self, pixel: [u32; 2], index: u64, dim: u32, seed: Seed) -> f32;

    /// Writes samples `0..spp`, dimensions `0..dims` of `pixel` under `seed` into `out`,
    /// sample-major (`out[i * dims + d]`). The default calls [`value`](Source::value).
    fn fill(&self, pixel: [u32; 2], spp: u32, dims: u32, seed: Seed, out: &mut [f32]) {
        for (i, row) in out
            .chunks_exact_mut(dims as usize)
            .take(spp as usize)
            .enumerate()
        {
            for (d, v) in row.iter_mut().enumerate() {
                *v = self.value(pixel, i as u64, d as u32, seed);
            }
        }
    }

    /// The grids on which the first `n` samples of every 2D draw lie, every cell holding the
    /// same number of points; empty (the default) where nothing is promised.
    fn promised_strata(&self, n: u64) -> Vec<StrataGrid> {
        let _ = n;
        Vec::new()
    }
}

impl<F: Fn([u32; 2], u64, u32, Seed) -> f32 + Sync> Source for F {
    fn value(&self, pixel: [u32; 2], index: u64, dim: u32, seed: Seed) -> f32 {
        self(pixel, index, dim, seed)
    }
}

/// A [`Sequence`] as a [`Source`]: the values of a [`PixelSampler`] with the given
/// samples per pixel, laid out by [`PixelSampler::fill_sample`] as `points --pixel` prints them
/// (dimensions `2k, 2k+1` from `get_2d` at dimension `2k`, a last odd one from `get_1d`), with
/// the stratification the sequence promises.
#[derive(Clone, Debug)]
pub struct SequenceSource {
    sampler: PixelSampler,
}

impl SequenceSource {
    /// The source for `sequence` at `spp` samples per pixel (checked as
    /// [`PixelSampler::new`] checks it).
    pub fn new(sequence: Sequence, spp: u32) -> Result<Self> {
        Ok(SequenceSource {
            sampler: PixelSampler::new(sequence, spp, Seed(0))?,
        })
    }

    /// The same source with another [`Padding`] (the adapter's default without this).
    pub fn with_padding(mut self, padding: Padding) -> Self {
        self.sampler = self.sampler.with_padding(padding);
        self
    }

    fn seeded(&self, seed: Seed) -> PixelSampler {
        PixelSampler::new(
            self.sampler.sequence().clone(),
            self.sampler.samples_per_pixel(),
            seed,
        )
        .expect("checked in new")
        .with_padding(self.sampler.padding())
    }
}

impl Source for SequenceSource {
    fn value(&self, pixel: [u32; 2], index: u64, dim: u32, seed: Seed) -> f32 {
        self.seeded(seed).sample_2d(pixel, index, dim & !1)[(dim & 1) as usize]
    }

    fn fill(&self, pixel: [u32; 2], spp: u32, dims: u32, seed: Seed, out: &mut [f32]) {
        let mut s = self.seeded(seed);
        for (i, row) in out
            .chunks_exact_mut(dims as usize)
            .take(spp as usize)
            .enumerate()
        {
            s.fill_sample(pixel, i as u64, 0, row);
        }
    }

    fn promised_strata(&self, n: u64) -> Vec<StrataGrid> {
        self.sampler.promised_strata(n)
    }
}

/// The configuration of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Suite {
    /// Samples per pixel (`n`), 16 to [`Suite::MAX_SPP`].
    pub spp: u32,
    /// Dimensions per sample (`D`), 2 to 64: `D / 2` 2D draws (and a 1D one if `D` is odd).
    pub dimensions: u32,
    /// The pixels tested (at least one; every pair of them is tested for independence).
    pub pixels: Vec<[u32; 2]>,
    /// The seeds (at least one; the tests over seeds need two or more).
    pub seeds: Vec<Seed>,
    /// The family-wise false-alarm rate, in `(0, 0.5]`.
    pub false_alarm: f64,
}

impl Default for Suite {
    /// 4096 samples per pixel, 8 dimensions (4 draws), 8 pixels (neighbours and distant
    /// ones), 16 seeds, a false-alarm rate of `1e-6`: about 4 million values.
    fn default() -> Self {
        Suite {
            spp: 4096,
            dimensions: 8,
            pixels: vec![
                [0, 0],
                [1, 0],
                [0, 1],
                [3, 5],
                [10, 11],
                [100, 7],
                [1919, 1079],
                [123_456, 654_321],
            ],
            seeds: (1..=16).map(Seed).collect(),
            false_alarm: 1e-6,
        }
    }
}

/// One row of a [`Report`]: one test over all its cases.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Row {
    /// The test (`integrands`, `products`, `chi-square`, ...).
    pub test: &'static str,
    /// Where it looks: `within draws`, `across draws`, `across pixels`, `across seeds`,
    /// `per draw`.
    pub scope: &'static str,
    /// The statistic (`|z|`, `|t|`, `chi2`, `points off`).
    pub statistic: &'static str,
    /// How many cases were tested (0: not run, see [`note`](Row::note)).
    pub cases: usize,
    /// How many cases failed.
    pub failures: usize,
    /// The worst case's statistic.
    pub worst: f64,
    /// The worst case's p-value (NaN for counts).
    pub worst_p: f64,
    /// The statistic's critical value (the bound a case must not exceed).
    pub threshold: f64,
    /// Where the worst case is (seed, pixel, dimensions, integrand).
    pub worst_case: String,
    /// Why a row was not run, or what its threshold means.
    pub note: &'static str,
}

impl Row {
    /// True when no case failed.
    pub fn passed(&self) -> bool {
        self.failures == 0
    }
}

/// The result of a run: one [`Row`] per test and scope.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Report {
    /// The rows, in a fixed order.
    pub rows: Vec<Row>,
    /// Samples per pixel of the run.
    pub spp: u32,
    /// Dimensions of the run.
    pub dimensions: u32,
    /// Number of (seed, pixel) instances.
    pub instances: usize,
    /// The side `P` of the chi-square grid (`P x P` cells).
    pub chi_square_side: u32,
    /// The family-wise false-alarm rate.
    pub false_alarm: f64,
}

impl Report {
    /// True when every row passed.
    pub fn passed(&self) -> bool {
        self.rows.iter().all(Row::passed)
    }

    /// The row of `test` in `scope`.
    pub fn row(&self, test: &str, scope: &str) -> Option<&Row> {
        self.rows
            .iter()
            .find(|r| r.test == test && r.scope == scope)
    }

    /// The rows that failed.
    pub fn failures(&self) -> impl Iterator<Item = &Row> {
        self.rows.iter().filter(|r| !r.passed())
    }
}

impl fmt::Display for Report {
    /// A Markdown table, one line per row, then the verdict.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "| test | scope | cases | statistic | worst | p | bound | worst case | verdict |"
        )?;
        writeln!(f, "|---|---|---|---|---|---|---|---|---|")?;
        for r in &self.rows {
            if r.cases == 0 {
                writeln!(
                    f,
                    "| {} | {} | 0 | {} | - | - | - | {} | not run |",
                    r.test, r.scope, r.statistic, r.note
                )?;
                continue;
            }
            let p = if r.worst_p.is_nan() {
                "-".to_string()
            } else {
                format!("{:.2e}", r.worst_p)
            };
            writeln!(
                f,
                "| {} | {} | {} | {} | {:.3} | {} | {:.3} | {} | {} |",
                r.test,
                r.scope,
                r.cases,
                r.statistic,
                r.worst,
                p,
                r.threshold,
                r.worst_case,
                if r.passed() {
                    "pass".to_string()
                } else {
                    format!("FAIL ({} cases)", r.failures)
                }
            )?;
        }
        write!(
            f,
            "\n{}: {} samples per pixel, {} dimensions, {} instances, chi-square on {}x{} cells, \
             family-wise false-alarm rate {:e}",
            if self.passed() { "PASS" } else { "FAIL" },
            self.spp,
            self.dimensions,
            self.instances,
            self.chi_square_side,
            self.chi_square_side,
            self.false_alarm
        )
    }
}

/// The oriented Heavisides: `1` where `cos(a) (x - 1/2) + sin(a) (y - 1/2) < t`.
const HEAVISIDES: [(f64, f64); 4] = [(0.35, 0.07), (1.2, -0.11), (2.1, 0.03), (2.8, -0.05)];

/// The area of the part of the unit square where `n . (p - (1/2, 1/2)) < t`, by clipping the
/// square's polygon with the half-plane (Sutherland-Hodgman) and the shoelace formula.
fn half_plane_area(angle: f64, t: f64) -> f64 {
    let (c, s) = (angle.cos(), angle.sin());
    let side = |p: [f64; 2]| c * (p[0] - 0.5) + s * (p[1] - 0.5) - t;
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut poly: Vec<[f64; 2]> = Vec::new();
    for k in 0..4 {
        let (a, b) = (square[k], square[(k + 1) % 4]);
        let (fa, fb) = (side(a), side(b));
        if fa < 0.0 {
            poly.push(a);
        }
        if (fa < 0.0) != (fb < 0.0) {
            let u = fa / (fa - fb);
            poly.push([a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])]);
        }
    }
    let mut area = 0.0;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        area += a[0] * b[1] - b[0] * a[1];
    }
    0.5 * area.abs()
}

/// A test function of two coordinates with its exact integral and variance.
#[derive(Clone, Copy, Debug)]
enum Function {
    Known(Integrand),
    Heaviside(f64, f64),
}

impl Function {
    fn name(&self) -> String {
        match self {
            Function::Known(i) => i.name().to_string(),
            Function::Heaviside(a, t) => format!("heaviside({a},{t})"),
        }
    }

    #[inline]
    fn eval(&self, x: f32, y: f32) -> f64 {
        match *self {
            Function::Known(i) => i.eval(&[x, y]),
            Function::Heaviside(a, t) => {
                f64::from(a.cos() * (x as f64 - 0.5) + a.sin() * (y as f64 - 0.5) < t)
            }
        }
    }

    /// `(exact integral, variance of one uniform sample)`.
    fn moments(&self) -> (f64, f64) {
        match *self {
            Function::Known(i) => (i.exact(), i.variance()),
            Function::Heaviside(a, t) => {
                let area = half_plane_area(a, t);
                (area, area * (1.0 - area))
            }
        }
    }
}

/// The functions of the `integrands` rows, then the product (the `products` rows) last.
fn functions() -> Vec<Function> {
    let mut f = vec![
        Function::Known(Integrand::Disk),
        Function::Known(Integrand::Gaussian),
    ];
    f.extend(HEAVISIDES.iter().map(|&(a, t)| Function::Heaviside(a, t)));
    f.push(Function::Known(Integrand::Bilinear));
    f
}

/// The side of the chi-square grid for `n` points: 31, or the largest prime below it with at
/// least 4 expected points per cell (at least 2).
fn grid_side(n: usize) -> usize {
    const PRIMES: [usize; 11] = [31, 29, 23, 19, 17, 13, 11, 7, 5, 3, 2];
    PRIMES
        .iter()
        .copied()
        .find(|&p| n >= 4 * p * p)
        .unwrap_or(2)
}

/// Pearson's chi-square of the pairs `(a[i], b[i])` on a `side x side` grid.
fn chi_square(n: usize, side: usize, a: impl Fn(usize) -> f32, b: impl Fn(usize) -> f32) -> f64 {
    let mut counts = [0u32; 31 * 31];
    for i in 0..n {
        let cx = ((a(i) as f64 * side as f64) as usize).min(side - 1);
        let cy = ((b(i) as f64 * side as f64) as usize).min(side - 1);
        counts[cy * side + cx] += 1;
    }
    let e = n as f64 / (side * side) as f64;
    counts[..side * side]
        .iter()
        .map(|&c| (c as f64 - e).powi(2) / e)
        .sum()
}

/// One tested case: its statistic, p-value and where it is.
#[derive(Clone, Debug)]
struct Case {
    statistic: f64,
    p: f64,
    place: String,
}

/// The cases of one row, before the Bonferroni bound is known.
struct Family {
    test: &'static str,
    scope: &'static str,
    statistic: &'static str,
    cases: Vec<Case>,
    /// The statistic's critical value at a per-case level `alpha`.
    critical: Box<dyn Fn(f64) -> f64>,
    /// A floor under the critical value (the products' 6 sigma).
    floor: f64,
    note: &'static str,
}

/// Runs `f` over `items` on the machine's threads, results in item order.
fn parallel_map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(items.len().max(1));
    let chunk = items.len().div_ceil(threads).max(1);
    std::thread::scope(|scope| {
        let f = &f;
        let handles: Vec<_> = items
            .chunks(chunk)
            .map(|part| scope.spawn(move || part.iter().map(f).collect::<Vec<R>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a conformance worker panicked"))
            .collect()
    })
}

impl Suite {
    /// The largest samples-per-pixel count.
    pub const MAX_SPP: u32 = 1 << 20;
    /// The largest number of values a run may draw (`spp x dimensions x pixels x seeds`):
    /// `2^25`, 128 MB of `f32`, a few minutes on one core.
    pub const MAX_VALUES: u64 = 1 << 25;

    /// Checks the configuration; the error says what is allowed.
    pub fn check(&self) -> Result<()> {
        let ctx = "Suite::check";
        if !(16..=Self::MAX_SPP).contains(&self.spp) {
            return Err(Error::parameter(
                ctx,
                "spp",
                self.spp,
                format!("16 to {} samples per pixel", Self::MAX_SPP),
            ));
        }
        if !(2..=64).contains(&self.dimensions) {
            return Err(Error::parameter(
                ctx,
                "dimensions",
                self.dimensions,
                "2 to 64",
            ));
        }
        if self.pixels.is_empty() || self.pixels.len() > 256 {
            return Err(Error::parameter(
                ctx,
                "pixels",
                self.pixels.len(),
                "1 to 256 pixels",
            ));
        }
        if self.seeds.is_empty() || self.seeds.len() > 1024 {
            return Err(Error::parameter(
                ctx,
                "seeds",
                self.seeds.len(),
                "1 to 1024 seeds",
            ));
        }
        if !(self.false_alarm > 0.0 && self.false_alarm <= 0.5) {
            return Err(Error::parameter(
                ctx,
                "false_alarm",
                self.false_alarm,
                "a probability in (0, 0.5]",
            ));
        }
        let values = self.spp as u64
            * self.dimensions as u64
            * self.pixels.len() as u64
            * self.seeds.len() as u64;
        if values > Self::MAX_VALUES {
            return Err(Error::input(
                ctx,
                format!(
                    "{} samples x {} dimensions x {} pixels x {} seeds = {values} values is too \
                     many (at most {}, a few minutes); lower one of them",
                    self.spp,
                    self.dimensions,
                    self.pixels.len(),
                    self.seeds.len(),
                    Self::MAX_VALUES
                ),
            ));
        }
        Ok(())
    }

    /// Runs a [`Sequence`] through the suite, at [`Suite::spp`] samples per pixel.
    pub fn run_sequence(&self, sequence: Sequence) -> Result<Report> {
        self.run(&SequenceSource::new(sequence, self.spp)?)
    }

    /// Runs the suite on `source`: draws every instance's values, then each family of tests
    /// in the order of the report's rows.
    pub fn run(&self, source: &(impl Source + ?Sized)) -> Result<Report> {
        self.check()?;
        let instances: Vec<(Seed, [u32; 2])> = self
            .seeds
            .iter()
            .flat_map(|&s| self.pixels.iter().map(move |&p| (s, p)))
            .collect();
        let values = self.draw(source, &instances)?;
        let run = Run::new(self, &instances, &values);
        let per_instance = run.per_instance();
        let mut families = run.instance_families(&per_instance);
        families.extend(run.seed_families(&per_instance));
        families.extend(run.cross_families());
        let mut rows = rows(families, self.false_alarm);
        rows.push(run.stratification(source));
        Ok(Report {
            rows,
            spp: self.spp,
            dimensions: self.dimensions,
            instances: instances.len(),
            chi_square_side: run.side as u32,
            false_alarm: self.false_alarm,
        })
    }

    /// The values of every instance (seed, pixel): `spp x dimensions`, sample-major, each
    /// checked to lie in `[0, 1)`.
    fn draw(
        &self,
        source: &(impl Source + ?Sized),
        instances: &[(Seed, [u32; 2])],
    ) -> Result<Vec<Vec<f32>>> {
        let (n, dims) = (self.spp as usize, self.dimensions as usize);
        let values: Vec<Vec<f32>> = parallel_map(instances, |&(seed, pixel)| {
            let mut v = vec![0.0f32; n * dims];
            source.fill(pixel, self.spp, self.dimensions, seed, &mut v);
            v
        });
        if let Some((k, bad)) = values
            .iter()
            .enumerate()
            .find_map(|(k, v)| v.iter().find(|x| !(0.0..1.0).contains(*x)).map(|x| (k, *x)))
        {
            let (seed, pixel) = instances[k];
            return Err(Error::input(
                "Suite::run",
                format!("seed {} pixel {pixel:?} gave {bad}, outside [0, 1)", seed.0),
            ));
        }
        Ok(values)
    }
}

/// The rows of `families`, in their order: the false-alarm rate split evenly over the rows
/// run (the stratification row included), and within a row over its cases.
fn rows(families: Vec<Family>, false_alarm: f64) -> Vec<Row> {
    let rows_run = families.iter().filter(|f| !f.cases.is_empty()).count() + 1;
    let alpha_row = false_alarm / rows_run as f64;
    families.into_iter().map(|f| f.row(alpha_row)).collect()
}

impl Family {
    /// A family of `|z|` cases (two-sided normal critical value, at least `floor`).
    fn z(
        test: &'static str,
        scope: &'static str,
        cases: Vec<Case>,
        floor: f64,
        note: &'static str,
    ) -> Self {
        Family {
            test,
            scope,
            statistic: "|z|",
            cases,
            critical: normal_critical(),
            floor,
            note,
        }
    }

    /// The row of these cases at the row's false-alarm rate `alpha_row` (Bonferroni over the
    /// cases).
    fn row(self, alpha_row: f64) -> Row {
        let mut row = Row {
            test: self.test,
            scope: self.scope,
            statistic: self.statistic,
            cases: self.cases.len(),
            failures: 0,
            worst: f64::NAN,
            worst_p: f64::NAN,
            threshold: f64::NAN,
            worst_case: String::new(),
            note: self.note,
        };
        if self.cases.is_empty() {
            return row;
        }
        let threshold = (self.critical)(alpha_row / self.cases.len() as f64).max(self.floor);
        row.threshold = threshold;
        row.failures = self
            .cases
            .iter()
            .filter(|c| c.statistic.is_nan() || c.statistic > threshold)
            .count();
        let worst = self
            .cases
            .iter()
            .max_by(|x, y| x.statistic.total_cmp(&y.statistic))
            .expect("non-empty");
        row.worst = worst.statistic;
        row.worst_p = worst.p;
        row.worst_case = worst.place.clone();
        row
    }
}

/// The two-sided normal critical value, as a family's `critical`.
fn normal_critical() -> Box<dyn Fn(f64) -> f64> {
    Box::new(|alpha| stats::critical_value(alpha, stats::normal_two_sided))
}

/// The case of a signed `z`: its magnitude, two-sided.
fn z_case(z: f64, place: String) -> Case {
    Case {
        statistic: z.abs(),
        p: stats::normal_two_sided(z),
        place,
    }
}

/// The z-scores of one (pixel, pair, function) over the seeds: the variance case
/// (`sum z^2`, chi-square with `seeds` degrees of freedom) and, with two or more seeds, the
/// t-test case; `variance` is the function's variance under uniform sampling, `n` the count.
fn seed_cases(zs: &[f64], variance: f64, n: usize, place: String) -> (Case, Option<Case>) {
    let r = zs.len();
    let sum_sq: f64 = zs.iter().map(|z| z * z).sum();
    let v_case = Case {
        statistic: sum_sq,
        p: stats::chi_square_upper(sum_sq, r as f64),
        place: place.clone(),
    };
    if r < 2 {
        return (v_case, None);
    }
    let mean = zs.iter().sum::<f64>() / r as f64;
    let var = zs.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / (r - 1) as f64;
    // an estimate of n values resolves 1/n: that floor keeps equal errors over all seeds (a
    // stratified set meeting a step the same way) from a zero spread and an infinite t
    let floor = (variance / n as f64).sqrt().recip() / n as f64;
    let t = mean / (var / r as f64 + floor * floor).sqrt();
    let t_case = Case {
        statistic: t.abs(),
        p: stats::student_t_two_sided(t, (r - 1) as f64),
        place,
    };
    (v_case, Some(t_case))
}

/// Which 2D draw dimension `d` belongs to, of `draws` 2D draws (an odd last dimension is a
/// 1D draw of its own).
fn draw_of(d: usize, draws: usize) -> usize {
    if d < 2 * draws { d / 2 } else { usize::MAX - d }
}

/// The largest difference between a cell's count and `m / cells` when the first `m`
/// samples of `draw` (dimensions `2 draw, 2 draw + 1` of `v`, `dims` per sample) are counted
/// on `g`; `u64::MAX` when `m` is not a multiple of the cells (a promise it cannot keep).
fn points_off(v: &[f32], dims: usize, draw: usize, m: usize, g: &StrataGrid) -> u64 {
    let cells = g.columns as usize * g.rows as usize;
    if !m.is_multiple_of(cells) {
        return u64::MAX;
    }
    let mut counts = vec![0u32; cells];
    for i in 0..m {
        let (x, y) = (v[i * dims + 2 * draw], v[i * dims + 2 * draw + 1]);
        let cx = (x as f64 * g.columns as f64) as usize;
        let cy = (y as f64 * g.rows as f64) as usize;
        counts[cy * g.columns as usize + cx] += 1;
    }
    let expect = (m / cells) as u64;
    counts
        .iter()
        .map(|&c| (c as u64).abs_diff(expect))
        .max()
        .unwrap_or(0)
}

/// One run's values with what every family of tests reads: the sizes, the functions and
/// their moments, the pairs of dimensions, the chi-square grid.
struct Run<'a> {
    suite: &'a Suite,
    instances: &'a [(Seed, [u32; 2])],
    /// Per instance, `n x dims` values, sample-major.
    values: &'a [Vec<f32>],
    n: usize,
    dims: usize,
    side: usize,
    chi_df: f64,
    /// The functions of the `integrands` rows, then the product (index `products`).
    functions: Vec<Function>,
    moments: Vec<(f64, f64)>,
    products: usize,
    pairs: Vec<(usize, usize)>,
}

/// Per instance: the z of every (pair, function), pair-major, and the chi-square of every
/// pair.
type InstanceStats = (Vec<f64>, Vec<f64>);

impl<'a> Run<'a> {
    fn new(suite: &'a Suite, instances: &'a [(Seed, [u32; 2])], values: &'a [Vec<f32>]) -> Self {
        let (n, dims) = (suite.spp as usize, suite.dimensions as usize);
        let side = grid_side(n);
        let functions = functions();
        Run {
            suite,
            instances,
            values,
            n,
            dims,
            side,
            chi_df: (side * side - 1) as f64,
            products: functions.len() - 1,
            moments: functions.iter().map(Function::moments).collect(),
            functions,
            pairs: (0..dims)
                .flat_map(|a| (a + 1..dims).map(move |b| (a, b)))
                .collect(),
        }
    }

    /// Whether the two dimensions of `pair` belong to one draw.
    fn within(&self, &(a, b): &(usize, usize)) -> bool {
        let draws = self.dims / 2;
        draw_of(a, draws) == draw_of(b, draws)
    }

    /// Instance `k` as the report names it.
    fn name(&self, k: usize) -> String {
        let (seed, pixel) = self.instances[k];
        format!("seed {} pixel {},{}", seed.0, pixel[0], pixel[1])
    }

    /// The case of a chi-square statistic, upper tail.
    fn chi_case(&self, c: f64, place: String) -> Case {
        Case {
            statistic: c,
            p: stats::chi_square_upper(c, self.chi_df),
            place,
        }
    }

    /// The chi-square critical value, as a family's `critical`.
    fn chi_critical(&self) -> Box<dyn Fn(f64) -> f64> {
        let chi_df = self.chi_df;
        Box::new(move |alpha| stats::critical_value(alpha, |x| stats::chi_square_upper(x, chi_df)))
    }

    /// The z of every (instance, pair, function), and the chi-square of every (instance,
    /// pair).
    fn per_instance(&self) -> Vec<InstanceStats> {
        let (n, dims, side) = (self.n, self.dims, self.side);
        parallel_map(self.values, |v| {
            let mut z = Vec::with_capacity(self.pairs.len() * self.functions.len());
            let mut chi = Vec::with_capacity(self.pairs.len());
            for &(a, b) in &self.pairs {
                for (f, &(exact, var)) in self.functions.iter().zip(&self.moments) {
                    let sum: f64 = (0..n)
                        .map(|i| f.eval(v[i * dims + a], v[i * dims + b]))
                        .sum();
                    z.push((sum / n as f64 - exact) / (var / n as f64).sqrt());
                }
                chi.push(chi_square(
                    n,
                    side,
                    |i| v[i * dims + a],
                    |i| v[i * dims + b],
                ));
            }
            (z, chi)
        })
    }

    /// Integrands, products and chi-square per instance, within draws then across draws.
    fn instance_families(&self, per_instance: &[InstanceStats]) -> Vec<Family> {
        let mut families = Vec::new();
        for (scope, inside) in [("within draws", true), ("across draws", false)] {
            let (mut integrands, mut prods, mut chis) = (Vec::new(), Vec::new(), Vec::new());
            for (k, (z, chi)) in per_instance.iter().enumerate() {
                for (pi, pair) in self.pairs.iter().enumerate() {
                    if self.within(pair) != inside {
                        continue;
                    }
                    for (fi, f) in self.functions.iter().enumerate() {
                        let place =
                            format!("{} dims {},{} {}", self.name(k), pair.0, pair.1, f.name());
                        let case = z_case(z[pi * self.functions.len() + fi], place);
                        if fi == self.products {
                            prods.push(case);
                        } else {
                            integrands.push(case);
                        }
                    }
                    let place = format!("{} dims {},{}", self.name(k), pair.0, pair.1);
                    chis.push(self.chi_case(chi[pi], place));
                }
            }
            let note = "no pair of dimensions in this scope";
            families.extend([
                Family::z("integrands", scope, integrands, 0.0, note),
                Family::z("products", scope, prods, 6.0, note),
                self.chi_family(scope, chis, note),
            ]);
        }
        families
    }

    /// The t-test and the variance over seeds per pixel, pair and function, within draws
    /// then across draws.
    fn seed_families(&self, per_instance: &[InstanceStats]) -> Vec<Family> {
        let (r, np, nf) = (
            self.suite.seeds.len(),
            self.suite.pixels.len(),
            self.functions.len(),
        );
        let mut families = Vec::new();
        for (scope, inside) in [("within draws", true), ("across draws", false)] {
            let (mut t_cases, mut v_cases) = (Vec::new(), Vec::new());
            for (pix, pixel) in self.suite.pixels.iter().enumerate() {
                for (pi, pair) in self.pairs.iter().enumerate() {
                    if self.within(pair) != inside {
                        continue;
                    }
                    for (fi, f) in self.functions.iter().enumerate() {
                        let zs: Vec<f64> = (0..r)
                            .map(|s| per_instance[s * np + pix].0[pi * nf + fi])
                            .collect();
                        let place = format!(
                            "pixel {},{} dims {},{} {}",
                            pixel[0],
                            pixel[1],
                            pair.0,
                            pair.1,
                            f.name()
                        );
                        let (v, t) = seed_cases(&zs, self.moments[fi].1, self.n, place);
                        v_cases.push(v);
                        t_cases.extend(t);
                    }
                }
            }
            let (df, rf) = ((r.max(2) - 1) as f64, r as f64);
            families.push(Family {
                test: "t-test over seeds",
                scope,
                statistic: "|t|",
                cases: t_cases,
                critical: Box::new(move |alpha| {
                    stats::critical_value(alpha, |t| stats::student_t_two_sided(t, df))
                }),
                floor: 0.0,
                note: "needs two or more seeds",
            });
            families.push(Family {
                test: "variance over seeds",
                scope,
                statistic: "sum z^2",
                cases: v_cases,
                critical: Box::new(move |alpha| {
                    stats::critical_value(alpha, |x| stats::chi_square_upper(x, rf))
                }),
                floor: 0.0,
                note: "no pair of dimensions in this scope",
            });
        }
        families
    }

    /// The pairs of instances compared dimension by dimension: every two pixels under one
    /// seed (`across pixels`), then one pixel under consecutive seeds (`across seeds`).
    fn cross_pairs(&self) -> Vec<(usize, usize, &'static str)> {
        let (r, np) = (self.suite.seeds.len(), self.suite.pixels.len());
        let mut cross = Vec::new();
        for s in 0..r {
            for p in 0..np {
                for q in p + 1..np {
                    cross.push((s * np + p, s * np + q, "across pixels"));
                }
            }
        }
        for s in 1..r {
            for p in 0..np {
                cross.push(((s - 1) * np + p, s * np + p, "across seeds"));
            }
        }
        cross
    }

    /// Products and chi-square between the same dimension of two instances, across pixels
    /// then across seeds.
    fn cross_families(&self) -> Vec<Family> {
        let (n, dims, side) = (self.n, self.dims, self.side);
        let cross = self.cross_pairs();
        let (prod_exact, prod_var) = self.moments[self.products];
        let cross_stats: Vec<Vec<(f64, f64)>> = parallel_map(&cross, |(a, b, _)| {
            let (va, vb) = (&self.values[*a], &self.values[*b]);
            (0..dims)
                .map(|d| {
                    let sum: f64 = (0..n)
                        .map(|i| va[i * dims + d] as f64 * vb[i * dims + d] as f64)
                        .sum();
                    let z = (sum / n as f64 - prod_exact) / (prod_var / n as f64).sqrt();
                    let chi = chi_square(n, side, |i| va[i * dims + d], |i| vb[i * dims + d]);
                    (z, chi)
                })
                .collect()
        });
        let mut families = Vec::new();
        for (scope, note) in [
            ("across pixels", "needs two or more pixels"),
            ("across seeds", "needs two or more seeds"),
        ] {
            let (mut prods, mut chis) = (Vec::new(), Vec::new());
            for ((a, b, _), st) in cross.iter().zip(&cross_stats).filter(|(c, _)| c.2 == scope) {
                for (d, &(z, chi)) in st.iter().enumerate() {
                    let place = format!("{} / {} dim {d}", self.name(*a), self.name(*b));
                    prods.push(z_case(z, place.clone()));
                    chis.push(self.chi_case(chi, place));
                }
            }
            families.push(Family::z("products", scope, prods, 6.0, note));
            families.push(self.chi_family(scope, chis, note));
        }
        families
    }

    /// The chi-square row of `scope`.
    fn chi_family(&self, scope: &'static str, cases: Vec<Case>, note: &'static str) -> Family {
        Family {
            test: "chi-square",
            scope,
            statistic: "chi2",
            cases,
            critical: self.chi_critical(),
            floor: 0.0,
            note,
        }
    }

    /// The stratification row: every promised grid of every 2D draw of every instance, at
    /// every count that has a promise, counted cell by cell.
    fn stratification(&self, source: &(impl Source + ?Sized)) -> Row {
        let dims = self.dims;
        let promises: Vec<(usize, Vec<StrataGrid>)> = (1..=self.suite.spp as usize)
            .map(|m| (m, source.promised_strata(m as u64)))
            .filter(|(_, g)| !g.is_empty())
            .collect();
        let mut row = Row {
            test: "stratification",
            scope: "per draw",
            statistic: "points off",
            cases: 0,
            failures: 0,
            worst: 0.0,
            worst_p: f64::NAN,
            threshold: 0.0,
            worst_case: String::new(),
            note: "the source promises no stratification",
        };
        let results: Vec<Vec<(u64, String)>> = parallel_map(self.values, |v| {
            let mut out = Vec::new();
            for draw in 0..dims / 2 {
                for (m, grids) in &promises {
                    for g in grids {
                        let (c, r) = (g.columns, g.rows);
                        let (a, b) = (2 * draw, 2 * draw + 1);
                        let place = format!("draw {draw} (dims {a},{b}) first {m} on {c}x{r}");
                        out.push((points_off(v, dims, draw, *m, g), place));
                    }
                }
            }
            out
        });
        for (k, cases) in results.iter().enumerate() {
            for (off, place) in cases {
                row.cases += 1;
                if *off > 0 {
                    row.failures += 1;
                }
                if *off as f64 > row.worst || row.worst_case.is_empty() {
                    row.worst = *off as f64;
                    row.worst_case = format!("{} {place}", self.name(k));
                }
            }
        }
        row
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_plane_areas_match_a_fine_grid() {
        for &(a, t) in HEAVISIDES
            .iter()
            .chain(&[(0.0, 0.0), (0.785, 0.2), (3.0, 0.6)])
        {
            let m = 2000;
            let mut inside = 0u64;
            for i in 0..m {
                for j in 0..m {
                    let (x, y) = ((i as f64 + 0.5) / m as f64, (j as f64 + 0.5) / m as f64);
                    if a.cos() * (x - 0.5) + a.sin() * (y - 0.5) < t {
                        inside += 1;
                    }
                }
            }
            let grid = inside as f64 / (m * m) as f64;
            assert!((half_plane_area(a, t) - grid).abs() < 2e-3, "{a} {t}");
        }
        assert!((half_plane_area(0.0, 0.0) - 0.5).abs() < 1e-15);
        assert!((half_plane_area(0.0, 0.6) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn bad_configurations_are_refused() {
        let ok = Suite::default();
        assert!(ok.check().is_ok());
        for bad in [
            Suite {
                spp: 0,
                ..ok.clone()
            },
            Suite {
                dimensions: 1,
                ..ok.clone()
            },
            Suite {
                pixels: vec![],
                ..ok.clone()
            },
            Suite {
                seeds: vec![],
                ..ok.clone()
            },
            Suite {
                false_alarm: 0.0,
                ..ok.clone()
            },
            Suite {
                false_alarm: f64::NAN,
                ..ok.clone()
            },
            Suite {
                spp: 1 << 20,
                seeds: (0..64).map(Seed).collect(),
                ..ok.clone()
            },
        ] {
            let e = bad.check().unwrap_err().to_string();
            assert!(e.contains("Suite::check"), "{e}");
        }
    }
}
