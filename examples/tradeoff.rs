//! `tradeoff`: speed against accuracy. Convergence of every sampler on test integrands, the
//! fitted rates against the published ones, the variance predicted from the spectrum, and the
//! error against generation time.
//!
//! ```text
//! cargo run --release --example tradeoff -- [--samplers a,b,..|all] [--integrands a,b,..|all]
//!         [--min-n N] [--max-n N] [--seeds K] [--out DIR]
//! ```

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int, string_value};
use indicatif::{ProgressBar, ProgressStyle};
use strata::analysis::Integrand;
use strata::analysis::study::{self, Config, Row, Slope};
use strata::io::{self, LinePlot, PALETTE, Rgb, Series};
use strata::registry::{self, Entry};

const USAGE: &str = "tradeoff [--samplers a,b,..|all] [--integrands a,b,..|all] [--min-n N] [--max-n N] [--seeds K] [--out DIR] [--markdown FILE]";

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
  --seeds K                 estimates per count (default 32; at least 2)
  --no-predict              skip the variance predicted from the spectrum
  --out DIR                 output directory (default out/tradeoff)
  --markdown FILE           also write the slopes table into FILE, as its section 'tradeoff'
  -h, --help                this text

Each sampler runs at its allowed counts nearest to the powers of two in [min-n, max-n]. Writes
DIR/tradeoff.csv (sampler,integrand,n,seeds,mean,variance,rmse,ns_per_sample,predicted_variance),
DIR/slopes.csv (sampler,integrand,slope,expected), DIR/convergence-INTEGRAND.png (variance
against N, log-log, with reference slopes) and DIR/tradeoff-INTEGRAND.png (RMSE against the
generation time of a set), and prints the slopes as a Markdown table.

predicted_variance = (1/N) sum_{w != 0} |f^(w)|^2 E[P(w)] from the integrand's Fourier
coefficients and the sampler's measured expected spectrum (Subr and Kautz 2013; Pilleboue et
al. 2015): exact for random sampling, an approximation for patterns that are not
shift-invariant (stratified ones).";

struct Args {
    samplers: Vec<&'static Entry>,
    integrands: Vec<Integrand>,
    min_n: u64,
    max_n: u64,
    seeds: u32,
    predict: bool,
    out: PathBuf,
    markdown: Option<PathBuf>,
}

fn list<T>(
    value: &str,
    all: impl Fn() -> Vec<T>,
    one: impl Fn(&str) -> Result<T, strata::Error>,
) -> Result<Vec<T>, CliError> {
    if value == "all" {
        return Ok(all());
    }
    let items: Vec<T> = value
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(one)
        .collect::<Result<_, _>>()?;
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
        seeds: 32,
        predict: true,
        out: PathBuf::from("out/tradeoff"),
        markdown: None,
    };
    let mut p = lexopt::Parser::from_env();
    while let Some(arg) = p.next()? {
        match arg {
            Long("samplers") => {
                let v = string_value("--samplers", p.value()?)?;
                a.samplers = list(&v, || registry::entries().iter().collect(), registry::find)?;
            }
            Long("integrands") => {
                let v = string_value("--integrands", p.value()?)?;
                a.integrands = list(&v, || Integrand::ALL.to_vec(), Integrand::by_name)?;
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
                a.seeds = parse_int(
                    "--seeds",
                    &string_value("--seeds", p.value()?)?,
                    2,
                    study::MAX_SEEDS as u64,
                )? as u32
            }
            Long("no-predict") => a.predict = false,
            Long("out") => a.out = p.value()?.into(),
            Long("markdown") => a.markdown = Some(p.value()?.into()),
            Short('h') | Long("help") => {
                println!("{HELP}");
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    Ok(Some(a))
}

fn fmt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x}"))
}

fn plots(rows: &[Row], slopes: &[Slope], args: &Args) -> Result<(), strata::Error> {
    let names: Vec<&str> = args.samplers.iter().map(|e| e.name).collect();
    for &f in &args.integrands {
        let mut by: BTreeMap<usize, Vec<&Row>> = BTreeMap::new();
        for r in rows.iter().filter(|r| r.integrand == f && r.variance > 0.0) {
            by.entry(names.iter().position(|&n| n == r.sampler).unwrap_or(0))
                .or_default()
                .push(r);
        }
        if by.is_empty() {
            continue;
        }
        let colour = |k: usize| PALETTE[k % PALETTE.len()];
        let mut conv = LinePlot::new(
            format!("{}: variance against N", f.name()),
            "N (samples)",
            "variance of the estimate",
        );
        conv.log_x = true;
        conv.log_y = true;
        let mut time = LinePlot::new(
            format!("{}: error against time", f.name()),
            "time to generate a set (us, one core)",
            "RMSE",
        );
        time.log_x = true;
        time.log_y = true;
        for (k, (idx, rs)) in by.iter().enumerate() {
            let name = names[*idx];
            let label = match slopes
                .iter()
                .find(|s| s.sampler == name && s.integrand == f)
                .and_then(|s| s.slope)
            {
                Some(s) => format!("{name} ({s:.2})"),
                None => name.to_string(),
            };
            conv.series.push(Series::new(
                label.clone(),
                rs.iter().map(|r| (r.n as f64, r.variance)).collect(),
                colour(k),
            ));
            time.series.push(Series::new(
                name,
                rs.iter()
                    .map(|r| (r.ns_per_sample * r.n as f64 / 1e3, r.rmse))
                    .collect(),
                colour(k),
            ));
        }
        // reference slopes through the first point of random sampling (or the first line)
        let anchor = rows
            .iter()
            .filter(|r| r.integrand == f && r.variance > 0.0)
            .min_by(|a, b| {
                (a.sampler != "random")
                    .cmp(&(b.sampler != "random"))
                    .then(a.n.cmp(&b.n))
            })
            .map(|r| (r.n as f64, r.variance));
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
        io::write_png(
            args.out.join(format!("convergence-{}.png", f.name())),
            &conv.render(1000, 700),
        )?;
        io::write_png(
            args.out.join(format!("tradeoff-{}.png", f.name())),
            &time.render(1000, 700),
        )?;
    }
    Ok(())
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
            "sampler,integrand,n,seeds,mean,variance,rmse,ns_per_sample,predicted_variance\n",
        );
        for r in &rows {
            csv.push_str(&format!(
                "{},{},{},{},{},{},{},{},{}\n",
                r.sampler,
                r.integrand.name(),
                r.n,
                r.seeds,
                r.mean,
                r.variance,
                r.rmse,
                r.ns_per_sample,
                fmt(r.predicted_variance)
            ));
        }
        io::write_text(args.out.join("tradeoff.csv"), &csv)?;
        let mut csv = String::from("sampler,integrand,slope,expected\n");
        for s in &slopes {
            csv.push_str(&format!(
                "{},{},{},{}\n",
                s.sampler,
                s.integrand.name(),
                fmt(s.slope),
                fmt(s.expected)
            ));
        }
        io::write_text(args.out.join("slopes.csv"), &csv)?;
        plots(&rows, &slopes, &args)?;

        // the slopes as a table: samplers down, integrands across
        let header: Vec<&str> = args.integrands.iter().map(|f| f.name()).collect();
        let mut table = format!(
            "| sampler | {} |\n|---|{}\n",
            header.join(" | "),
            "---|".repeat(header.len())
        );
        for e in &args.samplers {
            let cells: Vec<String> = args
                .integrands
                .iter()
                .map(|&f| {
                    match slopes
                        .iter()
                        .find(|s| s.sampler == e.name && s.integrand == f)
                    {
                        Some(Slope {
                            slope: Some(s),
                            expected: Some(x),
                            ..
                        }) => format!("{s:.2} ({x})"),
                        Some(Slope { slope: Some(s), .. }) => format!("{s:.2}"),
                        _ => "-".into(),
                    }
                })
                .collect();
            table.push_str(&format!("| {} | {} |\n", e.name, cells.join(" | ")));
        }
        print!("{table}");
        if let Some(path) = &args.markdown {
            common::write_markdown_section(
                path,
                "tradeoff",
                &format!(
                    "Slope of log variance against log N (the published rate in parentheses), \
                     N = {}..{}, {} seeds.\n\n{table}",
                    args.min_n, args.max_n, args.seeds
                ),
            )?;
        }
        println!(
            "\nslope of log variance against log N (published rate in parentheses); N = {}..{}, {} seeds; {:.1} s; files in {}",
            args.min_n,
            args.max_n,
            args.seeds,
            start.elapsed().as_secs_f64(),
            args.out.display()
        );
        Ok(())
    })
}
