//! `spectrum`: expected power spectra, radial means, anisotropy and PSA measures of the
//! registered samplers; the crate's main job.
//!
//! ```text
//! cargo run --release --example spectrum -- [--sampler NAME|all] [-n N] [--realizations R]
//!         [--seed S] [--resolution K] [--out DIR]
//! ```
//! See `docs/cli.md` (the command-line contract).

mod common;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, MAX_CLI_COUNT, cli_error, parse_int, string_value};
use glam::Vec2;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use strata::io::{self, Canvas, Rgb};
use strata::registry::{self, Entry, Params};
use strata::spectrum::{self, PointSetMeasures, RadialBin, Spectrum};

const USAGE: &str = "spectrum [--sampler NAME|all] [-n N] [--realizations R] [--seed S] [--resolution K] [--out DIR] [--markdown FILE]";

const HELP: &str = "\
spectrum: expected power spectra of sample patterns, their radial means, anisotropy and PSA
measures, written as pictures and files.

Usage:
  cargo run --release --example spectrum -- [options]

Options:
  --sampler NAME|all  one sampler, or every registered one (default all)
  -n N                points per realization (default 1024; with 'all', each sampler uses its
                      allowed count nearest to N)
  --realizations R    realizations averaged (default 64; 16 for slow samplers)
  --seed S            realization r uses seed S + r (default 1), exactly the points that
                      `points --sampler NAME -n N --seed S+r` prints
  --resolution K      frequencies |u|, |v| <= K/2 (even, default 256)
  --out DIR           output directory (default out), created when missing
  --radius, --iterations, --strength, --candidates, --capacity   passed to the samplers that take them
  --no-overview       skip out/overview.png
  --markdown FILE     also write the table into FILE, as its section 'spectrum'
  -h, --help          this text

For each sampler NAME it writes DIR/NAME-spectrum.png (log scale, DC centred), NAME-spectrum.exr
(the values, channel Y, f32), NAME-radial.csv (frequency,power,anisotropy), NAME-radial.png and
NAME-points.png, then DIR/overview.png and a table on stdout. ms/set is the time to generate
one set on one core (construction and points; one-time tables, built by a warm-up before
timing, are not counted).";

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
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut a = Args {
        sampler: "all".into(),
        n: None,
        realizations: None,
        seed: 1,
        resolution: 256,
        out: PathBuf::from("out"),
        params: Params::new(1),
        overview: true,
        markdown: None,
    };
    let mut p = lexopt::Parser::from_env();
    while let Some(arg) = p.next()? {
        match arg {
            Long("sampler") => a.sampler = string_value("--sampler", p.value()?)?,
            Short('n') => {
                // two points at least: the spacing measures need a neighbour
                a.n = Some(parse_int(
                    "-n",
                    &string_value("-n", p.value()?)?,
                    2,
                    MAX_CLI_COUNT,
                )?)
            }
            Long("realizations") => {
                let v = string_value("--realizations", p.value()?)?;
                a.realizations = Some(parse_int("--realizations", &v, 1, 100_000)? as u32);
            }
            Long("seed") => {
                a.seed = parse_int("--seed", &string_value("--seed", p.value()?)?, 0, u64::MAX)?
            }
            Long("resolution") => {
                let v = string_value("--resolution", p.value()?)?;
                let k = parse_int("--resolution", &v, 2, spectrum::MAX_RESOLUTION as u64)? as u32;
                spectrum::check_resolution(k)?;
                a.resolution = k;
            }
            Long("out") => a.out = p.value()?.into(),
            Long(flag @ ("radius" | "iterations" | "strength" | "candidates" | "capacity")) => {
                let flag = flag.to_owned(); // the argument borrows the parser
                common::sampler_param(&flag, &mut p, &mut a.params)?
            }
            Long("no-overview") => a.overview = false,
            Long("markdown") => a.markdown = Some(p.value()?.into()),
            Short('h') | Long("help") => {
                outln!("{HELP}")?;
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    common::check_output_dir(&a.out)?;
    if let Some(m) = &a.markdown {
        common::check_markdown(m, "spectrum")?;
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
    points: Vec<Vec2>,
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
    let mut params = args.params.clone();
    params.count = count;
    // Only pass the optional parameters this sampler takes (with 'all', the others are for
    // other samplers).
    let takes = |p| entry.takes(p);
    if !takes(registry::Parameter::Radius) {
        params.radius = None;
    }
    if !takes(registry::Parameter::Iterations) {
        params.iterations = None;
    }
    if !takes(registry::Parameter::Strength) {
        params.strength = None;
    }
    if !takes(registry::Parameter::Capacity) {
        params.capacity = None;
    }
    if !takes(registry::Parameter::Candidates) {
        params.candidates = None;
    }
    let generate = |r: u32| -> Result<Vec<Vec2>, strata::Error> {
        let mut s = entry.build(&params.clone().seed(args.seed.wrapping_add(r as u64)))?;
        let mut v = vec![Vec2::ZERO; count as usize];
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
    let sets: Vec<Vec<Vec2>> = (0..kept)
        .into_par_iter()
        .map(generate)
        .collect::<Result<_, strata::Error>>()?;
    let measures = spectrum::point_set_measures(&sets)?;
    bar.inc(realizations as u64);

    let name = entry.name;
    let grids = entry.build(&params.clone().seed(args.seed))?.strata(count);
    io::write_spectrum_files(
        &args.out,
        name,
        &spectrum,
        realizations as usize,
        &sets[0],
        &grids,
    )?;

    // Mean power over the low band 0 < |w| < sqrt(N)/2: what smooth integrands see.
    let band = ((count as f64).sqrt() / 2.0).max(1.0);
    let low: Vec<f64> = radial
        .iter()
        .filter(|b| (b.frequency as f64) < band)
        .map(|b| b.power)
        .collect();
    let low_power = if low.is_empty() {
        f64::NAN
    } else {
        low.iter().sum::<f64>() / low.len() as f64
    };
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
            format!("min dist {:.3}", m.global_min_distance),
            format!("avg min dist {:.3}", m.average_min_distance),
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
        let all = args.sampler == "all";
        let entries: Vec<&Entry> = if all {
            registry::entries().iter().collect()
        } else {
            vec![registry::find(&args.sampler)?]
        };
        // a parameter that no chosen sampler takes is refused, as `points` refuses it (with
        // 'all', each sampler gets the parameters it takes)
        for (p, _) in args.params.given() {
            if !entries.iter().any(|e| e.takes(p)) {
                let takers: Vec<&str> = registry::entries()
                    .iter()
                    .filter(|e| e.takes(p))
                    .map(|e| e.name)
                    .collect();
                return Err(cli_error(format!(
                    "--{} is not a parameter of {}; samplers that take it: {}",
                    p.name(),
                    args.sampler,
                    takers.join(", ")
                )));
            }
        }
        let n = args.n.unwrap_or(1024);
        let mut plan = Vec::new();
        for e in &entries {
            let count = if all {
                e.counts.nearest(n)
            } else {
                if !e.counts.allows(n) {
                    return Err(cli_error(format!(
                        "{} cannot make {n} samples: allowed counts are {} (nearest: {})",
                        e.name,
                        e.counts,
                        e.counts.nearest(n)
                    )));
                }
                n
            };
            let r = args
                .realizations
                .unwrap_or(if e.expensive { 16 } else { 64 });
            plan.push((*e, count, r));
        }
        let total: u64 = plan.iter().map(|&(_, _, r)| 2 * r as u64).sum();
        let bar = ProgressBar::new(total);
        bar.set_style(
            ProgressStyle::with_template("{msg:>16} [{bar:40}] {pos}/{len} {elapsed_precise}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        let started = Instant::now();
        let mut outcomes = Vec::new();
        let planned = plan.len();
        for (k, (e, count, r)) in plan.into_iter().enumerate() {
            bar.set_message(e.name);
            outcomes.push(run_one(e, count, r, &args, &bar)?);
            common::progress_line(format!(
                "spectrum: {} done ({}/{planned}, {:.0} s)",
                e.name,
                k + 1,
                started.elapsed().as_secs_f64()
            ));
        }
        bar.finish_and_clear();
        if args.overview && outcomes.len() > 1 {
            io::write_png(args.out.join("overview.png"), &overview(&outcomes))?;
        }
        let mut table = String::from(
            "| sampler | N | sets | ms/set | low-band power | min dist | avg min dist | nu_eff | oscillations |\n|---|---|---|---|---|---|---|---|---|\n",
        );
        for o in &outcomes {
            let m = &o.measures;
            table.push_str(&format!(
                "| {} | {} | {} | {:.3} | {:.4} | {:.3} | {:.3} | {} | {} |\n",
                o.name,
                o.count,
                o.realizations,
                o.ms_per_set,
                o.low_power,
                m.global_min_distance,
                m.average_min_distance,
                fmt_opt(m.effective_nyquist),
                fmt_opt(m.oscillations)
            ));
        }
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
        outln!(
            "\nwrote {} sampler(s) into {} in {:.1} s",
            outcomes.len(),
            args.out.display(),
            started.elapsed().as_secs_f64()
        )?;
        Ok(())
    })
}
