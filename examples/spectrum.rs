//! `spectrum`: expected power spectra, radial means, anisotropy and PSA measures of the
//! registered samplers; the crate's main job.
//!
//! ```text
//! cargo run --release --example spectrum -- [--sampler NAME|all] [-n N] [--realizations R]
//!         [--seed S] [--resolution K] [--out DIR]
//! cargo run --release --example spectrum -- --blue-noise-table [-n N] [--realizations R]
//!         [--seed S] [--resolution K] [--markdown FILE]
//! ```
//! See `docs/cli.md` (the command-line contract).

mod common;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, MAX_CLI_COUNT, cli_error, parse_int};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use strata_lab::io::{self, Canvas, Rgb};
use strata_lab::registry::{self, Entry, Params};
use strata_lab::spectrum::{self, PointSetMeasures, RadialBin, Spectrum};

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "spectrum: expected power spectra of sample patterns, their radial means, \
anisotropy and PSA measures, written as pictures and files.";

/// What a run writes, and the blue-noise table (the end of `--help`).
const DETAILS: &str = "For each sampler NAME it writes DIR/NAME-spectrum.png (log scale, DC centred), NAME-spectrum.exr (the values, channel Y, f32), NAME-radial.csv (frequency,power,anisotropy), NAME-radial.png and NAME-points.png, then DIR/overview.png and a table on stdout. ms/set is the time to generate one set on one core (construction and points; one-time tables, built by a warm-up before timing, are not counted).\n\n\
--blue-noise-table: one row per blue-noise sampler of the registry and count (N = 1024 and 4096, each sampler's allowed count nearest to it; -n N for one count, at most 16384), from R seeds (default 8; seed S + r as above), at each sampler's default parameters: rho (the smallest toroidal distance between two points of a set relative to r_max(N) = sqrt(2 / (sqrt(3) N)), Lagae and Dutre 2008; mean over the seeds), the mean nearest-neighbour distance relative to r_max(N) (mean over the seeds), the low-band power of the expected spectrum (the mean of its radial bins b = 1, 2, ... below sqrt(N)/2, bin b averaging P over w != 0 with round(|w|) == b, as in the main table), the median time per set over the seeds (one thread, measured now), and the figure the sampler's paper reports, with the reference. A row whose first set takes so long that its R sets would take more than 60 s is skipped after that set, and says so. Writes no files but --markdown FILE (section 'blue-noise-table').";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them);
/// the sampler parameters are added from the registry ([`common::with_sampler_params`]).
#[derive(clap::Parser)]
#[command(name = "spectrum", about = ABOUT, after_help = DETAILS)]
struct Cli {
    /// one sampler, or every registered one
    #[arg(long, value_name = "NAME|all", default_value = "all",
          value_parser = clap::builder::NonEmptyStringValueParser::new())]
    sampler: String,
    /// points per realization (default 1024; with 'all', each sampler uses its allowed count
    /// nearest to N)
    #[arg(short = 'n', value_name = "N", value_parser = common::whole::<u64>("-n", 2, MAX_CLI_COUNT))]
    n: Option<u64>,
    /// realizations averaged (default 64; 16 for slow samplers)
    #[arg(long, value_name = "R", value_parser = common::whole::<u32>("--realizations", 1, 100_000))]
    realizations: Option<u32>,
    /// realization r uses seed S + r, exactly the points that `points --sampler NAME -n N --seed
    /// S+r` prints
    #[arg(long, value_name = "S", default_value_t = 1,
          value_parser = common::whole::<u64>("--seed", 0, u64::MAX))]
    seed: u64,
    /// frequencies |u|, |v| <= K/2 (even)
    #[arg(long, value_name = "K", default_value_t = 256, value_parser = common::value_parser(resolution))]
    resolution: u32,
    /// output directory, created when missing
    #[arg(long, value_name = "DIR", default_value = "out")]
    out: PathBuf,
    /// skip DIR/overview.png
    #[arg(long)]
    no_overview: bool,
    /// also write the table into FILE, as its section 'spectrum' ('blue-noise-table' with
    /// --blue-noise-table)
    #[arg(long, value_name = "FILE")]
    markdown: Option<PathBuf>,
    /// instead: the published-figures table of every blue-noise sampler (below)
    #[arg(long)]
    blue_noise_table: bool,
}

/// `--resolution K`: an even grid the spectrum takes.
fn resolution(v: &str) -> Result<u32, CliError> {
    let k = parse_int("--resolution", v, 2, spectrum::MAX_RESOLUTION as u64)? as u32;
    spectrum::check_resolution(k)?;
    Ok(k)
}

/// The most points per set in `--blue-noise-table` (the relaxations are quadratic or worse).
const MAX_TABLE_COUNT: u64 = 1 << 14;

/// The time a row of `--blue-noise-table` may take, estimated before it runs.
const TABLE_BUDGET_S: f64 = 60.0;

struct Args {
    sampler: String,
    n: Option<u64>,
    realizations: Option<u32>,
    seed: u64,
    resolution: u32,
    out: PathBuf,
    params: Params,
    overview: bool,
    markdown: Option<PathBuf>,
    /// `--blue-noise-table`.
    table: bool,
}

fn parse() -> Result<Option<Args>, CliError> {
    use clap::parser::ValueSource;
    use clap::{CommandFactory, FromArgMatches};
    let Some(matches) = common::clap_matches(common::with_sampler_params(Cli::command()))? else {
        return Ok(None);
    };
    let c = Cli::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?;
    let mut params = Params::new(1);
    common::read_sampler_params(&matches, &mut params)?;
    let a = Args {
        sampler: c.sampler,
        n: c.n,
        realizations: c.realizations,
        seed: c.seed,
        resolution: c.resolution,
        out: c.out,
        params,
        overview: !c.no_overview,
        markdown: c.markdown,
        table: c.blue_noise_table,
    };
    if a.table {
        // the flags the table does not take, in the order of the help
        let given = |id: &str| matches.value_source(id) == Some(ValueSource::CommandLine);
        let not_for_table = ["sampler", "out", "no_overview"]
            .into_iter()
            .chain(registry::parameter_names())
            .find(|id| given(id));
        if let Some(id) = not_for_table {
            return Err(cli_error(format!(
                "--blue-noise-table takes -n, --realizations, --seed, --resolution and \
                 --markdown, not --{} (the table covers every blue-noise sampler at its \
                 default parameters and writes no files but --markdown)",
                id.replace('_', "-")
            )));
        }
        if let Some(n) = a.n.filter(|&n| n > MAX_TABLE_COUNT) {
            return Err(cli_error(format!(
                "--blue-noise-table -n {n}: allowed 2 to {MAX_TABLE_COUNT} points per set"
            )));
        }
    } else {
        common::check_output_dir("--out", &a.out)?;
    }
    // realization r uses seed S + r: refused where that would wrap
    let most = a.realizations.unwrap_or(64) as u64;
    if a.seed.checked_add(most - 1).is_none() {
        return Err(cli_error(format!(
            "--seed {} with {most} realizations would wrap past 2^64 - 1 (realization r uses \
             seed S + r); allowed: --seed at most {}",
            a.seed,
            u64::MAX - (most - 1)
        )));
    }
    if let Some(m) = &a.markdown {
        common::check_markdown(m, if a.table { TABLE_SECTION } else { "spectrum" })?;
    }
    Ok(Some(a))
}

/// One sampler's results, for the table and the overview.
struct Outcome {
    name: &'static str,
    count: u64,
    realizations: u32,
    ms_per_set: f64,
    low_power: f64,
    measures: PointSetMeasures,
    points: Vec<[f32; 2]>,
    grids: Vec<strata::StrataGrid>,
    spectrum: Spectrum,
    radial: Vec<RadialBin>,
}

fn run_one(
    entry: &Entry,
    count: u64,
    realizations: u32,
    args: &Args,
    bar: &ProgressBar,
) -> Result<Outcome, CliError> {
    // the lenient build: only the parameters this sampler takes (with 'all', the others are
    // for other samplers)
    let mut params = args.params.kept_for(entry);
    params.count = count;
    let generate = |r: u32| -> Result<Vec<[f32; 2]>, strata_lab::Error> {
        let mut s = entry.build(&params.clone().seed(strata::Seed(args.seed + r as u64)))?;
        let mut v = vec![[0.0f32; 2]; count as usize];
        s.fill(&mut v);
        Ok(v)
    };
    // Build the one-time tables (Sobol' directions, shared sequences) with a small set first,
    // then time one set on its own (one core), then stream the realizations through the
    // spectrum (memory: one wave of sets, not all of them).
    let mut warm = params.clone();
    warm.count = entry.counts.nearest(4);
    entry.build(&warm)?.next_sample();
    let start = Instant::now();
    let first = generate(0)?;
    let ms_per_set = start.elapsed().as_secs_f64() * 1e3;
    let spectrum = spectrum::expected_spectrum(realizations, args.resolution, |r| {
        let v = if r == 0 { first.clone() } else { generate(r)? };
        bar.inc(1);
        Ok(v)
    })?;
    let radial = spectrum.radial();
    // PSA measures from the first realizations (at most 2^22 points in all)
    let kept = (realizations as u64).min(((1u64 << 22) / count).max(1)) as u32;
    let sets: Vec<Vec<[f32; 2]>> = (0..kept)
        .into_par_iter()
        .map(generate)
        .collect::<Result<_, strata_lab::Error>>()?;
    let measures = spectrum::point_set_measures(&sets)?;
    bar.inc(realizations as u64);

    let name = entry.name;
    let grids = entry
        .build(&params.clone().seed(strata::Seed(args.seed)))?
        .strata(count);
    io::write_spectrum_files(
        &args.out,
        name,
        &spectrum,
        realizations as usize,
        &sets[0],
        &grids,
    )?;

    let low_power = low_band_power(&radial, count);
    Ok(Outcome {
        name,
        count,
        realizations,
        ms_per_set,
        low_power,
        measures,
        points: sets.into_iter().next().expect("at least one realization"),
        grids,
        spectrum,
        radial,
    })
}

/// Mean power over the low band `0 < |w| < sqrt(N)/2` (what smooth integrands see): the mean of
/// the radial bins `b = 1, 2, ...` below `sqrt(N)/2` (at least bin 1).
fn low_band_power(radial: &[RadialBin], count: u64) -> f64 {
    // bin 1 always: below N = 5 the band holds no other (it once held none: NaN)
    let band = (count as f64).sqrt() / 2.0;
    let low: Vec<f64> = radial
        .iter()
        .filter(|b| b.frequency == 1 || (b.frequency >= 1 && (b.frequency as f64) < band))
        .map(|b| b.power)
        .collect();
    if low.is_empty() {
        f64::NAN
    } else {
        low.iter().sum::<f64>() / low.len() as f64
    }
}

/// The section `--blue-noise-table` writes.
const TABLE_SECTION: &str = "blue-noise-table";

/// One measured row of `--blue-noise-table`.
struct TableRow {
    rho: f64,
    mean_nn: f64,
    low_power: f64,
    ms_per_set: f64,
}

/// `seeds` sets of `entry` at `count` points (seed `seed + r`), each made on this thread and
/// timed, measured: the row of the table; `Err(seconds)`, the first set's time, when the
/// sets would take longer than [`TABLE_BUDGET_S`] (judged after the first).
fn table_row(
    entry: &Entry,
    count: u64,
    seeds: u32,
    args: &Args,
) -> Result<Result<TableRow, f64>, CliError> {
    // one-time tables (Sobol' directions, shared sequences) are built before the timing
    let mut warm = Params::new(entry.counts.nearest(4));
    warm.seed = strata::Seed(args.seed);
    entry.build(&warm)?.next_sample();
    let mut sets = Vec::with_capacity(seeds as usize);
    let mut ms = Vec::with_capacity(seeds as usize);
    for r in 0..seeds {
        let params = Params::new(count).seed(strata::Seed(args.seed + r as u64));
        let start = Instant::now();
        let mut s = entry.build(&params)?;
        let mut v = vec![[0.0f32; 2]; count as usize];
        s.fill(&mut v);
        let seconds = start.elapsed().as_secs_f64();
        if r == 0 && seconds * seeds as f64 > TABLE_BUDGET_S {
            return Ok(Err(seconds));
        }
        ms.push(seconds * 1e3);
        sets.push(v);
    }
    ms.sort_by(f64::total_cmp);
    let mid = ms.len() / 2;
    let ms_per_set = if ms.len() % 2 == 1 {
        ms[mid]
    } else {
        (ms[mid - 1] + ms[mid]) / 2.0
    };
    let r_max = spectrum::relative_radius_max(count as usize);
    let (mut rho, mut mean_nn) = (0.0, 0.0);
    for s in &sets {
        let d = spectrum::nearest_neighbour_distances(s)
            .ok_or_else(|| cli_error("a set of one point has no nearest neighbour"))?;
        rho += d.iter().copied().fold(f64::INFINITY, f64::min) / r_max;
        mean_nn += d.iter().sum::<f64>() / d.len() as f64 / r_max;
    }
    let spectrum = spectrum::expected_spectrum_of_sets(&sets, args.resolution)?;
    Ok(Ok(TableRow {
        rho: rho / seeds as f64,
        mean_nn: mean_nn / seeds as f64,
        low_power: low_band_power(&spectrum.radial(), count),
        ms_per_set,
    }))
}

/// `--blue-noise-table`: the measured and the published figures of every blue-noise sampler.
fn blue_noise_table(args: &Args) -> Result<(), CliError> {
    let seeds = args.realizations.unwrap_or(8);
    let wanted: Vec<u64> = match args.n {
        Some(n) => vec![n],
        None => vec![1024, 4096],
    };
    let started = Instant::now();
    let mut table = String::from(
        "| sampler | N | seeds | rho | mean NN | low-band power | ms/set | published (reference) |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    let entries: Vec<&Entry> = registry::blue_noise().collect();
    for e in &entries {
        for (k, &n) in wanted.iter().enumerate() {
            let count = e.counts.nearest(n);
            let published = if k == 0 {
                e.blue_noise.map_or("", |b| b.published)
            } else {
                "(as above)"
            };
            let row = match table_row(e, count, seeds, args)? {
                Ok(row) => row,
                Err(first) => {
                    table.push_str(&format!(
                        "| {} | {count} | - | skipped: the first set took {first:.1} s, about \
                         {:.0} s for {seeds}, over the {TABLE_BUDGET_S:.0} s budget | - | - | \
                         {:.0} | {published} |\n",
                        e.name,
                        first * seeds as f64,
                        first * 1e3
                    ));
                    common::progress_line(format!(
                        "spectrum: {} at {count} skipped (first set {first:.1} s)",
                        e.name
                    ));
                    continue;
                }
            };
            table.push_str(&format!(
                "| {} | {count} | {seeds} | {:.3} | {:.3} | {:.4} | {:.3} | {published} |\n",
                e.name, row.rho, row.mean_nn, row.low_power, row.ms_per_set
            ));
            common::progress_line(format!(
                "spectrum: {} at {count} done ({:.0} s)",
                e.name,
                started.elapsed().as_secs_f64()
            ));
        }
    }
    common::out(&table)?;
    if let Some(path) = &args.markdown {
        common::write_markdown_section(
            path,
            TABLE_SECTION,
            &format!(
                "The blue-noise samplers of the registry ({} of them), each at its default \
                 parameters, {seeds} seeds (seed S + r) per row, against the figures their \
                 papers report. `rho` is the smallest toroidal distance between two points of \
                 a set relative to `r_max(N) = sqrt(2 / (sqrt(3) N))` (the relative radius of \
                 Lagae and Dutré 2008), `mean NN` the mean nearest-neighbour distance relative \
                 to `r_max(N)`, both means over the seeds; the low-band power is the mean of \
                 the expected spectrum's radial bins `b = 1, 2, ...` below `sqrt(N)/2` (bin `b` \
                 averages `P(w)` over `w != 0` with `round(|w|) == b`, K = {}; 1 is white \
                 noise); ms/set is the median over the seeds of the time to make one set on \
                 one thread, measured when the table was written (construction and points). \
                 A row whose first set takes so long that its {seeds} sets would take more \
                 than {TABLE_BUDGET_S:.0} s is skipped after that set (its ms/set is that \
                 set's time). \
                 The published column gives the paper's figure with its reference and says \
                 where it was not checked against the paper; \"not reported\" where the paper \
                 has no such figure.\n\n{table}",
                entries.len(),
                args.resolution
            ),
        )?;
    }
    outln!(
        "\nmeasured {} blue-noise sampler(s) in {:.1} s",
        entries.len(),
        started.elapsed().as_secs_f64()
    )?;
    Ok(())
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{x:.3}"))
}

fn overview(outcomes: &[Outcome]) -> Canvas {
    const TILE: u32 = 256;
    const LABEL: u32 = 230;
    const PLOT: u32 = 400;
    let width = LABEL + TILE + TILE + PLOT + 4 * 8;
    let height = TILE * outcomes.len() as u32 + 8 * (outcomes.len() as u32 + 1);
    let mut c = Canvas::new(width, height, Rgb::WHITE);
    for (i, o) in outcomes.iter().enumerate() {
        let y = 8 + i as i64 * (TILE as i64 + 8);
        let m = &o.measures;
        let lines = vec![
            format!("N = {}, {} sets", o.count, o.realizations),
            format!("min dist {}", fmt_opt(m.global_min_distance)),
            format!("avg min dist {}", fmt_opt(m.average_min_distance)),
            format!("nu_eff {}", fmt_opt(m.effective_nyquist)),
            format!("oscillations {}", fmt_opt(m.oscillations)),
            format!("low-band power {:.3}", o.low_power),
        ];
        c.paste(&io::overview_row_label(o.name, &lines, LABEL, TILE), 8, y);
        c.paste(
            &io::draw_points(&o.points, &o.grids, TILE),
            8 + LABEL as i64 + 8,
            y,
        );
        let spec = io::draw_spectrum(&o.spectrum, 1);
        // Centre the (K+1)-pixel spectrum in its tile, cropping if larger.
        let off = (TILE as i64 - spec.width() as i64) / 2;
        let mut tile = Canvas::new(TILE, TILE, Rgb::BLACK);
        tile.paste(&spec, off, off);
        c.paste(&tile, 16 + LABEL as i64 + TILE as i64 + 8, y);
        let plot = io::radial_plot(&o.radial, "", o.count as usize, PLOT, TILE);
        c.paste(&plot, 24 + LABEL as i64 + 2 * TILE as i64 + 8, y);
    }
    c
}

fn main() -> ExitCode {
    common::run("spectrum", || {
        let Some(args) = parse()? else { return Ok(()) };
        if args.table {
            return blue_noise_table(&args);
        }
        let plan = plan(&args)?;
        let started = Instant::now();
        let outcomes = run_plan(plan, &args, started)?;
        if args.overview && outcomes.len() > 1 {
            io::write_png(args.out.join("overview.png"), &overview(&outcomes))?;
        }
        let table = summary_table(&outcomes);
        common::out(&table)?;
        if let Some(path) = &args.markdown {
            common::write_markdown_section(
                path,
                "spectrum",
                &format!(
                    "Expected spectra, {} realizations ({} for the slow samplers) of N points, \
                     K = {}: the mean power in the low band `0 < |w| < sqrt(N)/2`, the PSA \
                     measures (minimum distances relative to `r_max(N)`, effective Nyquist \
                     frequency, oscillations) and the time per set on one core.\n\n{table}",
                    args.realizations.unwrap_or(64),
                    args.realizations.unwrap_or(16),
                    args.resolution
                ),
            )?;
        }
        let secs = started.elapsed().as_secs_f64();
        let (k, out) = (outcomes.len(), args.out.display());
        outln!("\nwrote {k} sampler(s) into {out} in {secs:.1} s")?;
        Ok(())
    })
}

/// The samplers to measure, each with its count and realizations; a parameter no chosen
/// sampler takes is refused, as `points` refuses it (with 'all', each sampler gets the
/// parameters it takes).
fn plan(args: &Args) -> Result<Vec<(&'static Entry, u64, u32)>, CliError> {
    let all = args.sampler == "all";
    let entries: Vec<&'static Entry> = if all {
        registry::entries().iter().collect()
    } else {
        vec![registry::find(&args.sampler)?]
    };
    for (p, _) in args.params.given() {
        if !entries.iter().any(|e| e.takes(p)) {
            let takers: Vec<&str> = registry::entries()
                .iter()
                .filter(|e| e.takes(p))
                .map(|e| e.name)
                .collect();
            return Err(cli_error(format!(
                "--{} is not a parameter of {}; samplers that take it: {}",
                p,
                args.sampler,
                takers.join(", ")
            )));
        }
    }
    let n = args.n.unwrap_or(1024);
    let mut plan = Vec::new();
    for e in entries {
        let count = if all {
            e.counts.nearest_within(n, MAX_CLI_COUNT)
        } else {
            e.counts.check_within(e.name, n, MAX_CLI_COUNT)?;
            n
        };
        let r = args
            .realizations
            .unwrap_or(if e.expensive { 16 } else { 64 });
        plan.push((e, count, r));
    }
    Ok(plan)
}

/// Runs the plan with a progress bar and a line per sampler.
fn run_plan(
    plan: Vec<(&'static Entry, u64, u32)>,
    args: &Args,
    started: Instant,
) -> Result<Vec<Outcome>, CliError> {
    let total: u64 = plan.iter().map(|&(_, _, r)| 2 * r as u64).sum();
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{msg:>16} [{bar:40}] {pos}/{len} {elapsed_precise}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    let mut outcomes = Vec::new();
    let planned = plan.len();
    for (k, (e, count, r)) in plan.into_iter().enumerate() {
        bar.set_message(e.name);
        outcomes.push(run_one(e, count, r, args, &bar)?);
        common::progress_line(format!(
            "spectrum: {} done ({}/{planned}, {:.0} s)",
            e.name,
            k + 1,
            started.elapsed().as_secs_f64()
        ));
    }
    bar.finish_and_clear();
    Ok(outcomes)
}

/// The table on stdout (and in `--markdown`): a row per sampler.
fn summary_table(outcomes: &[Outcome]) -> String {
    let mut table = String::from(
        "| sampler | N | sets | ms/set | low-band power | min dist | avg min dist | nu_eff | oscillations |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for o in outcomes {
        let m = &o.measures;
        table.push_str(&format!(
            "| {} | {} | {} | {:.3} | {:.4} | {} | {} | {} | {} |\n",
            o.name,
            o.count,
            o.realizations,
            o.ms_per_set,
            o.low_power,
            fmt_opt(m.global_min_distance),
            fmt_opt(m.average_min_distance),
            fmt_opt(m.effective_nyquist),
            fmt_opt(m.oscillations)
        ));
    }
    table
}
