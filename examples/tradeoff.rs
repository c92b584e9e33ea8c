//! `tradeoff`: speed against accuracy. Convergence of every sampler on test integrands, the
//! fitted rates with bootstrap intervals against the published ones, the variance predicted
//! from the spectrum, the error against generation time with its Pareto front, and the time
//! each sampler needs to reach an error.
//!
//! ```text
//! cargo run --release --example tradeoff -- [--samplers a,b,..|all] [--integrands a,b,..|all]
//!         [--min-n N] [--max-n N] [--seeds K] [--targets e,e,..] [--out DIR]
//! ```

mod common;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int, string_value};
use indicatif::{ProgressBar, ProgressStyle};
use strata::analysis::Integrand;
use strata::analysis::study::{self, Config, Row, Seeds, Slope, TimeToError};
use strata::io::{self, LinePlot, Marker, PALETTE, Rgb, Series};
use strata::registry::{self, Entry, Family};

const USAGE: &str = "tradeoff [--samplers a,b,..|all] [--integrands a,b,..|all] [--min-n N] [--max-n N] [--seeds K] [--targets e,e,..] [--out DIR] [--markdown FILE]";

const HELP: &str = "\
tradeoff: the convergence of each sampler on test integrands, speed against accuracy.

Usage:
  cargo run --release --example tradeoff -- [options]

Options:
  --samplers a,b,..|all     registered samplers (default all)
  --integrands a,b,..|all   disk, triangle, step, gaussian, bilinear (2D), gaussian4d, ball4d
                            (4D, for samplers with D dimensions) (default all)
  --min-n N                 smallest count (default 16)
  --max-n N                 largest count (default 1024; at most 1048576)
  --seeds K                 estimates per count for every sampler (default: by cost, 256 for
                            samplers whose set at max-n takes under 0.125 ms, down to 32 for
                            those over 1 ms; the count is in the tables)
  --targets e,e,..          RMSE targets relative to the integral (default 1e-2,1e-3,1e-4)
  --no-predict              skip the variance predicted from the spectrum
  --out DIR                 output directory (default out/tradeoff)
  --markdown FILE           also write the slopes and the time-to-error tables of disk and
                            gaussian into FILE, as its sections 'tradeoff' and 'time-to-error'
  -h, --help                this text

Each sampler runs at its allowed counts nearest to the powers of two in [min-n, max-n]. Writes
DIR/tradeoff.csv (sampler,integrand,n,seeds,mean,variance,rmse,ns_per_sample,predicted_variance,
set_ns,set_ns_min,set_ns_max,one_time_ns), DIR/slopes.csv (sampler,integrand,slope,expected,
slope_lo,slope_hi), DIR/time_to_error.csv (integrand,target,sampler,n,ns,extrapolated),
DIR/convergence-INTEGRAND.png (variance against N, one panel per family, with the published
rates) and DIR/tradeoff-INTEGRAND.png (RMSE against the time of a set, one panel per family,
the samplers on the Pareto front bold and the front itself dashed), and prints the tables.

Timing: the time of a set is building the sampler with a new seed and filling N points (for
relaxations the whole optimisation), on one core, after an untimed first build that pays the
one-time tables (reported as one_time_ns). Sets repeat until 1 ms of work is timed; the median
of 5 such measurements is set_ns, and their range set_ns_min..set_ns_max.

Slope intervals: 95% bootstrap intervals (400 resamples of the seeds at every count).

Time to error: the RMSE and the set time are fitted as power laws of N over the measured counts;
n is the smallest allowed count whose fitted RMSE meets the target, ns the fitted time of a set
of n, extrapolated = 1 when n lies outside the measured counts. Samplers whose error does not
fall with N have no row.

predicted_variance = (1/N) sum_{w != 0} |f^(w)|^2 E[P(w)] from the integrand's Fourier
coefficients and the sampler's measured expected spectrum (Subr and Kautz 2013; Pilleboue et
al. 2015): exact for random sampling, an approximation for patterns that are not
shift-invariant (stratified ones).";

struct Args {
    samplers: Vec<&'static Entry>,
    integrands: Vec<Integrand>,
    min_n: u64,
    max_n: u64,
    seeds: Seeds,
    targets: Vec<f64>,
    predict: bool,
    out: PathBuf,
    markdown: Option<PathBuf>,
}

/// The items named in a comma-separated list (or all of them), each once, in the order given.
fn list<T>(
    value: &str,
    all: impl Fn() -> Vec<T>,
    one: impl Fn(&str) -> Result<T, strata::Error>,
    name_of: impl Fn(&T) -> &'static str,
) -> Result<Vec<T>, CliError> {
    if value == "all" {
        return Ok(all());
    }
    let mut items: Vec<T> = Vec::new();
    for name in value.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let item = one(name)?;
        if !items.iter().any(|i| name_of(i) == name_of(&item)) {
            items.push(item);
        }
    }
    if items.is_empty() {
        return Err(cli_error(format!(
            "{value:?} names nothing; give names separated by commas, or all"
        )));
    }
    Ok(items)
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut a = Args {
        samplers: registry::entries().iter().collect(),
        integrands: Integrand::ALL.to_vec(),
        min_n: 16,
        max_n: 1024,
        seeds: Seeds::DEFAULT,
        targets: vec![1e-2, 1e-3, 1e-4],
        predict: true,
        out: PathBuf::from("out/tradeoff"),
        markdown: None,
    };
    let mut p = lexopt::Parser::from_env();
    while let Some(arg) = p.next()? {
        match arg {
            Long("samplers") => {
                let v = string_value("--samplers", p.value()?)?;
                a.samplers = list(
                    &v,
                    || registry::entries().iter().collect(),
                    registry::find,
                    |e| e.name,
                )?;
            }
            Long("integrands") => {
                let v = string_value("--integrands", p.value()?)?;
                a.integrands = list(
                    &v,
                    || Integrand::ALL.to_vec(),
                    Integrand::by_name,
                    |f| f.name(),
                )?;
            }
            Long("min-n") => {
                a.min_n = parse_int(
                    "--min-n",
                    &string_value("--min-n", p.value()?)?,
                    1,
                    study::MAX_STUDY_COUNT,
                )?
            }
            Long("max-n") => {
                a.max_n = parse_int(
                    "--max-n",
                    &string_value("--max-n", p.value()?)?,
                    1,
                    study::MAX_STUDY_COUNT,
                )?
            }
            Long("seeds") => {
                a.seeds = Seeds::Fixed(parse_int(
                    "--seeds",
                    &string_value("--seeds", p.value()?)?,
                    2,
                    study::MAX_SEEDS as u64,
                )? as u32)
            }
            Long("targets") => {
                let v = string_value("--targets", p.value()?)?;
                a.targets = v
                    .split(',')
                    .map(|t| {
                        t.trim()
                            .parse::<f64>()
                            .ok()
                            .filter(|x| *x > 0.0 && *x < 1.0)
                            .ok_or_else(|| {
                                cli_error(format!(
                                    "--targets {v:?}: {t:?} is not a relative error; allowed: numbers in (0, 1), e.g. 1e-2,1e-3"
                                ))
                            })
                    })
                    .collect::<Result<_, _>>()?;
                a.targets.sort_by(|x, y| y.total_cmp(x));
                a.targets.dedup();
            }
            Long("no-predict") => a.predict = false,
            Long("out") => a.out = p.value()?.into(),
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
        common::check_markdown(m, "tradeoff")?;
        common::check_markdown(m, "time-to-error")?;
    }
    Ok(Some(a))
}

fn fmt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x}"))
}

/// The samplers of `rows` on the Pareto front of (set time, RMSE) for integrand `f`: those
/// with a point that no other sampler's point beats on both axes; and the front itself.
fn pareto(rows: &[Row], f: Integrand) -> (Vec<&'static str>, Vec<(f64, f64)>) {
    let mine: Vec<&Row> = rows
        .iter()
        .filter(|r| r.integrand == f && r.rmse > 0.0)
        .collect();
    let pts: Vec<(f64, f64)> = mine.iter().map(|r| (r.set_ns / 1e3, r.rmse)).collect();
    let front = study::pareto_front(&pts);
    let mut names: Vec<&'static str> = front.iter().map(|&i| mine[i].sampler).collect();
    names.sort_unstable();
    names.dedup();
    (names, front.iter().map(|&i| pts[i]).collect())
}

/// One panel per family: `convergence-F.png` (variance against N, with the published rates)
/// and `tradeoff-F.png` (RMSE against the time of a set; samplers on the Pareto front bold,
/// the front dashed, the rest faint).
fn plots(rows: &[Row], slopes: &[Slope], args: &Args) -> Result<(), strata::Error> {
    for &f in &args.integrands {
        let of = |e: &Entry| -> Vec<&Row> {
            rows.iter()
                .filter(|r| r.integrand == f && r.sampler == e.name && r.variance > 0.0)
                .collect()
        };
        if !args.samplers.iter().any(|e| !of(e).is_empty()) {
            continue;
        }
        let (front_names, front) = pareto(rows, f);
        let anchor = rows
            .iter()
            .filter(|r| r.integrand == f && r.variance > 0.0)
            .min_by(|a, b| {
                (a.sampler != "random")
                    .cmp(&(b.sampler != "random"))
                    .then(a.n.cmp(&b.n))
            })
            .map(|r| (r.n as f64, r.variance));
        // shared axis ranges, so panels compare at a glance
        let range = |pick: &dyn Fn(&Row) -> f64| {
            let v: Vec<f64> = rows
                .iter()
                .filter(|r| r.integrand == f)
                .map(pick)
                .filter(|v| *v > 0.0 && v.is_finite())
                .collect();
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(0.0, f64::max);
            (lo / 1.5, hi * 1.5)
        };
        let (mut conv_panels, mut time_panels) = (Vec::new(), Vec::new());
        for family in Family::ALL {
            let members: Vec<&&Entry> = args
                .samplers
                .iter()
                .filter(|e| e.family == family && !of(e).is_empty())
                .collect();
            if members.is_empty() {
                continue;
            }
            let mut conv = LinePlot::new(
                format!("{}: {}", f.name(), family.name()),
                "N (samples)",
                "variance of the estimate",
            );
            conv.log_x = true;
            conv.log_y = true;
            conv.legend_outside = true;
            conv.x_range = Some(range(&|r| r.n as f64));
            conv.y_range = Some(range(&|r| r.variance));
            let mut time = LinePlot::new(
                format!("{}: {} (bold: Pareto front)", f.name(), family.name()),
                "time of a set (us, one core)",
                "RMSE",
            );
            time.log_x = true;
            time.log_y = true;
            time.legend_outside = true;
            time.x_range = Some(range(&|r| r.set_ns / 1e3));
            time.y_range = Some(range(&|r| r.rmse));
            if let Some((n0, v0)) = anchor {
                let n1 = args.max_n as f64;
                for (rate, grey) in [(-1.0, 110u8), (-1.5, 150), (-2.0, 175), (-3.0, 200)] {
                    conv.series.push(Series::reference(
                        format!("N^{rate}"),
                        vec![(n0, v0), (n1, v0 * (n1 / n0).powf(rate))],
                        Rgb::grey(grey),
                    ));
                }
            }
            let mut line = Series::reference("Pareto front", front.clone(), Rgb::grey(60));
            line.width = 1;
            time.series.push(line);
            for (k, e) in members.iter().enumerate() {
                let rs = of(e);
                let (colour, marker) = (
                    PALETTE[k % PALETTE.len()],
                    Marker::ALL[k % Marker::ALL.len()],
                );
                let label = match slopes
                    .iter()
                    .find(|s| s.sampler == e.name && s.integrand == f)
                    .and_then(|s| s.slope)
                {
                    Some(s) => format!("{} ({s:.2})", e.name),
                    None => e.name.to_string(),
                };
                let mut c = Series::new(
                    label,
                    rs.iter().map(|r| (r.n as f64, r.variance)).collect(),
                    colour,
                );
                c.marker = marker;
                conv.series.push(c);
                let on_front = front_names.contains(&e.name);
                let mut t = Series::new(
                    if on_front {
                        format!("{} *", e.name)
                    } else {
                        e.name.to_string()
                    },
                    rs.iter().map(|r| (r.set_ns / 1e3, r.rmse)).collect(),
                    colour,
                );
                t.marker = marker;
                t.width = if on_front { 3 } else { 1 };
                t.faint = !on_front;
                time.series.push(t);
            }
            conv_panels.push(conv.render(640, 420));
            time_panels.push(time.render(640, 420));
        }
        io::write_png(
            args.out.join(format!("convergence-{}.png", f.name())),
            &io::panel_grid(&conv_panels, 2),
        )?;
        io::write_png(
            args.out.join(format!("tradeoff-{}.png", f.name())),
            &io::panel_grid(&time_panels, 2),
        )?;
    }
    Ok(())
}

/// A duration in nanoseconds, readable.
fn human(ns: f64) -> String {
    if ns < 1e3 {
        format!("{ns:.0} ns")
    } else if ns < 1e6 {
        format!("{:.1} us", ns / 1e3)
    } else if ns < 1e9 {
        format!("{:.1} ms", ns / 1e6)
    } else {
        format!("{:.1} s", ns / 1e9)
    }
}

/// The time-to-error table of one integrand: samplers down (cheapest at the middle target
/// first), one column per target with the time and the count (`*`: extrapolated).
fn time_table(tte: &[TimeToError], f: Integrand, targets: &[f64]) -> String {
    let mut names: Vec<&'static str> = Vec::new();
    let key = targets.get(targets.len() / 2).copied().unwrap_or(1e-3);
    let mut order: Vec<&TimeToError> = tte
        .iter()
        .filter(|t| t.integrand == f && t.target == key)
        .collect();
    order.sort_by(|a, b| a.ns.total_cmp(&b.ns));
    names.extend(order.iter().map(|t| t.sampler));
    for t in tte.iter().filter(|t| t.integrand == f) {
        if !names.contains(&t.sampler) {
            names.push(t.sampler);
        }
    }
    let mut table = format!(
        "| {} | {} |\n|---|{}\n",
        f.name(),
        targets
            .iter()
            .map(|t| format!("RMSE {t:e}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(targets.len())
    );
    for name in names {
        let cells: Vec<String> = targets
            .iter()
            .map(|&t| {
                match tte
                    .iter()
                    .find(|x| x.integrand == f && x.target == t && x.sampler == name)
                {
                    Some(x) => format!(
                        "{} (N={}{})",
                        human(x.ns),
                        x.n,
                        if x.extrapolated { "*" } else { "" }
                    ),
                    None => "-".into(),
                }
            })
            .collect();
        table.push_str(&format!("| {name} | {} |\n", cells.join(" | ")));
    }
    table
}

fn main() -> ExitCode {
    common::run("tradeoff", || {
        let Some(args) = parse()? else { return Ok(()) };
        let config = Config {
            samplers: args.samplers.clone(),
            integrands: args.integrands.clone(),
            min_n: args.min_n,
            max_n: args.max_n,
            seeds: args.seeds,
            predict: args.predict,
        };
        study::check(&config)?;
        let total: usize = config
            .samplers
            .iter()
            .map(|e| study::counts_for(e.counts, args.min_n, args.max_n).len())
            .sum();
        let bar = ProgressBar::new(total as u64);
        bar.set_style(
            ProgressStyle::with_template("{msg:>24} [{bar:40}] {pos}/{len} {elapsed_precise}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        let start = Instant::now();
        let (rows, slopes) = study::run(&config, &|name, n| {
            bar.set_message(format!("{name} N={n}"));
            bar.inc(1);
            common::progress_line(format!("tradeoff: {name} N={n}"));
        })?;
        bar.finish_and_clear();

        let mut csv = String::from(
            "sampler,integrand,n,seeds,mean,variance,rmse,ns_per_sample,predicted_variance,set_ns,set_ns_min,set_ns_max,one_time_ns\n",
        );
        for r in &rows {
            csv.push_str(&format!(
                "{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                r.sampler,
                r.integrand.name(),
                r.n,
                r.seeds,
                r.mean,
                r.variance,
                r.rmse,
                r.ns_per_sample,
                fmt(r.predicted_variance),
                r.set_ns,
                r.set_ns_min,
                r.set_ns_max,
                r.one_time_ns
            ));
        }
        io::write_text(args.out.join("tradeoff.csv"), &csv)?;
        let mut csv = String::from("sampler,integrand,slope,expected,slope_lo,slope_hi\n");
        for s in &slopes {
            csv.push_str(&format!(
                "{},{},{},{},{},{}\n",
                s.sampler,
                s.integrand.name(),
                fmt(s.slope),
                fmt(s.expected),
                fmt(s.interval.map(|i| i.0)),
                fmt(s.interval.map(|i| i.1))
            ));
        }
        io::write_text(args.out.join("slopes.csv"), &csv)?;
        let tte = study::time_to_error(&rows, &args.samplers, &args.targets);
        let mut csv = String::from("integrand,target,sampler,n,ns,extrapolated\n");
        for t in &tte {
            csv.push_str(&format!(
                "{},{},{},{},{},{}\n",
                t.integrand.name(),
                t.target,
                t.sampler,
                t.n,
                t.ns,
                u8::from(t.extrapolated)
            ));
        }
        io::write_text(args.out.join("time_to_error.csv"), &csv)?;
        plots(&rows, &slopes, &args)?;

        // the slopes as a table: samplers down, integrands across, with the seeds used
        let header: Vec<&str> = args.integrands.iter().map(|f| f.name()).collect();
        let mut table = format!(
            "| sampler | seeds | {} |\n|---|---|{}\n",
            header.join(" | "),
            "---|".repeat(header.len())
        );
        for e in &args.samplers {
            let seeds = rows
                .iter()
                .find(|r| r.sampler == e.name)
                .map_or(String::from("-"), |r| r.seeds.to_string());
            let cells: Vec<String> = args
                .integrands
                .iter()
                .map(|&f| {
                    match slopes
                        .iter()
                        .find(|s| s.sampler == e.name && s.integrand == f)
                    {
                        Some(s @ Slope { slope: Some(v), .. }) => {
                            let ci = s
                                .interval
                                .map_or(String::new(), |(lo, hi)| format!(" [{lo:.2}, {hi:.2}]"));
                            let exp = s.expected.map_or(String::new(), |x| format!(" ({x})"));
                            format!("{v:.2}{ci}{exp}")
                        }
                        _ => "-".into(),
                    }
                })
                .collect();
            table.push_str(&format!(
                "| {} | {seeds} | {} |\n",
                e.name,
                cells.join(" | ")
            ));
        }
        common::out(&table)?;
        let mut times = String::new();
        for &f in &args.integrands {
            times.push_str(&format!("\n{}", time_table(&tte, f, &args.targets)));
        }
        common::out(&times)?;
        if let Some(path) = &args.markdown {
            common::write_markdown_section(
                path,
                "tradeoff",
                &format!(
                    "Slope of log variance against log N with its 95% bootstrap interval (the \
                     published rate in parentheses), N = {}..{}.\n\n{table}",
                    args.min_n, args.max_n
                ),
            )?;
            let mut body = String::from(
                "The generation time each sampler needs for an RMSE relative to the integral \
                 (cheapest first at the middle target; N is the count it needs, `*` where the \
                 fitted power laws are extrapolated beyond the measured counts). Time of a set \
                 on one core, one-time tables excluded.\n",
            );
            for f in [Integrand::Disk, Integrand::Gaussian] {
                if args.integrands.contains(&f) {
                    body.push_str(&format!("\n{}", time_table(&tte, f, &args.targets)));
                }
            }
            common::write_markdown_section(path, "time-to-error", &body)?;
        }
        outln!(
            "\nslope of log variance against log N [95% interval] (published rate); N = {}..{}; {:.1} s; files in {}",
            args.min_n,
            args.max_n,
            start.elapsed().as_secs_f64(),
            args.out.display()
        )?;
        Ok(())
    })
}
