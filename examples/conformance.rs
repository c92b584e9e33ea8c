//! `conformance`: run the statistical conformance suite on a path-tracer sequence.
//!
//! ```text
//! cargo run --release --example conformance -- --sampler NAME [--spp N] [--dims D]
//!         [--pixels K] [--seeds K] [--false-alarm A]
//! ```

mod common;

use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int, parse_open_float, string_value};
use strata::conformance::Suite;
use strata::pixel::Sequence;

const USAGE: &str = "conformance --sampler NAME|all [--spp N] [--dims D] [--pixels K] [--seeds K] \
[--false-alarm A] [--markdown FILE]";

const HELP: &str = "\
conformance: run the statistical conformance suite on a path-tracer sequence: unbiased
estimates, independent draws (inside a pixel sample, across pixels, across seeds), chi-square
uniformity of every pair of dimensions, and the promised stratification counted cell by cell.
Prints a table of tests with their worst statistic, bound and verdict; exits with status 1 when
any test fails.

Usage:
  cargo run --release --example conformance -- --sampler NAME [options]

Options:
  --sampler NAME|all  the sequence: random, jittered, pmj02, sobol, halton, or all of them
  --spp N             samples per pixel, 16 to 1048576 (default 4096)
  --dims D            dimensions per sample, 2 to 64 (default 8: four 2D draws)
  --pixels K          pixels tested, 1 to 256 (default 8: neighbours and distant ones)
  --seeds K           seeds, 1 to 1024 (default 16)
  --false-alarm A     family-wise false-alarm rate, 0 < A < 0.5 (default 1e-6)
  --markdown FILE     also write a summary (one line per sequence) into FILE, as its section
                      'conformance'
  -h, --help          this text

A run draws spp x dims x pixels x seeds values, at most 2^25 (a few minutes); larger runs
are refused.";

struct Args {
    samplers: Vec<String>,
    suite: Suite,
    markdown: Option<std::path::PathBuf>,
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut samplers = None;
    let mut suite = Suite::default();
    let mut markdown = None;
    let default_pixels = suite.pixels.clone();
    let mut parser = lexopt::Parser::from_env();
    while let Some(arg) = parser.next()? {
        match arg {
            Long("sampler") => {
                let v = string_value("--sampler", parser.value()?)?;
                samplers = Some(if v == "all" {
                    Sequence::NAMES.iter().map(|s| s.to_string()).collect()
                } else {
                    vec![v]
                });
            }
            Long("spp") => {
                let v = string_value("--spp", parser.value()?)?;
                suite.spp = parse_int("--spp", &v, 16, Suite::MAX_SPP as u64)? as u32;
            }
            Long("dims") => {
                let v = string_value("--dims", parser.value()?)?;
                suite.dimensions = parse_int("--dims", &v, 2, 64)? as u32;
            }
            Long("pixels") => {
                let v = string_value("--pixels", parser.value()?)?;
                let k = parse_int("--pixels", &v, 1, 256)? as usize;
                // the default pixels first, then a diagonal of distant ones
                suite.pixels = default_pixels
                    .iter()
                    .copied()
                    .chain((0..).map(|i: u32| [37 * i + 11, 53 * i + 29]))
                    .take(k)
                    .collect();
            }
            Long("seeds") => {
                let v = string_value("--seeds", parser.value()?)?;
                suite.seeds = (1..=parse_int("--seeds", &v, 1, 1024)?).collect();
            }
            Long("false-alarm") => {
                let v = string_value("--false-alarm", parser.value()?)?;
                suite.false_alarm = parse_open_float("--false-alarm", &v, 0.0, 0.5)?;
            }
            Long("markdown") => markdown = Some(parser.value()?.into()),
            Short('h') | Long("help") => {
                println!("{HELP}");
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    let samplers =
        samplers.ok_or_else(|| cli_error(format!("--sampler is required; usage: {USAGE}")))?;
    suite.check()?;
    Ok(Some(Args {
        samplers,
        suite,
        markdown,
    }))
}

fn main() -> ExitCode {
    let mut failed = false;
    let status = common::run("conformance", || {
        let Some(args) = parse()? else { return Ok(()) };
        // every name first, so that a typo fails before any work
        let sequences = args
            .samplers
            .iter()
            .map(|n| Ok((n.clone(), Sequence::by_name(n)?)))
            .collect::<Result<Vec<_>, strata::Error>>()?;
        let mut summary = String::from(
            "| sequence | tests | cases | closest to its bound (statistic / bound) | verdict |\n|---|---|---|---|---|\n",
        );
        for (name, sequence) in sequences {
            eprintln!("conformance: {name} ...");
            let start = Instant::now();
            let report = args.suite.run_sequence(sequence)?;
            println!("## {name}\n\n{report}\n");
            eprintln!(
                "conformance: {name} took {:.1} s",
                start.elapsed().as_secs_f64()
            );
            failed |= !report.passed();
            let closest = report
                .rows
                .iter()
                .filter(|r| r.cases > 0 && r.threshold > 0.0)
                .max_by(|a, b| (a.worst / a.threshold).total_cmp(&(b.worst / b.threshold)));
            summary.push_str(&format!(
                "| {name} | {} | {} | {} | {} |\n",
                report.rows.iter().filter(|r| r.cases > 0).count(),
                report.rows.iter().map(|r| r.cases).sum::<usize>(),
                closest.map_or("-".into(), |r| format!(
                    "{} {}: {:.3} / {:.3}",
                    r.test, r.scope, r.worst, r.threshold
                )),
                if report.passed() { "pass" } else { "FAIL" }
            ));
        }
        if let Some(path) = &args.markdown {
            common::write_markdown_section(
                path,
                "conformance",
                &format!(
                    "The conformance suite ({} samples per pixel, {} dimensions, {} pixels, {} \
                     seeds, family-wise false-alarm rate {:e}).\n\n{summary}",
                    args.suite.spp,
                    args.suite.dimensions,
                    args.suite.pixels.len(),
                    args.suite.seeds.len(),
                    args.suite.false_alarm
                ),
            )?;
        }
        Ok(())
    });
    if failed { ExitCode::from(1) } else { status }
}
