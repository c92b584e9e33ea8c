//! The command line: the usage and help texts, the options, their parsing with one-line
//! errors that say what is allowed, and the checks made before any work.

use std::path::PathBuf;

use strata_lab::analysis::Integrand;
use strata_lab::analysis::study::{self, Seeds};
use strata_lab::registry::{self, Entry};

use crate::common::{self, CliError, cli_error, parse_int, string_value};
use crate::outln;

/// The one-line usage, in the message of an unknown flag.
const USAGE: &str = "tradeoff [--samplers a,b,..|all] [--integrands a,b,..|all] [--min-n N] [--max-n N] [--seeds K] [--targets e,e,..] [--out DIR] [--markdown FILE]";

/// The text of `--help`.
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

/// The options of a run.
pub struct Args {
    pub samplers: Vec<&'static Entry>,
    pub integrands: Vec<Integrand>,
    pub min_n: u64,
    pub max_n: u64,
    pub seeds: Seeds,
    pub targets: Vec<f64>,
    pub predict: bool,
    pub out: PathBuf,
    pub markdown: Option<PathBuf>,
}

/// The items named in a comma-separated list (or all of them), each once, in the order given.
fn list<T>(
    value: &str,
    all: impl Fn() -> Vec<T>,
    one: impl Fn(&str) -> Result<T, strata_lab::Error>,
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

/// The options from the command line (`None` after `--help`), checked: the output directory
/// and the Markdown file writable.
pub fn parse() -> Result<Option<Args>, CliError> {
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
            Long("samplers") => a.samplers = samplers(&string_value("--samplers", p.value()?)?)?,
            Long("integrands") => {
                a.integrands = integrands(&string_value("--integrands", p.value()?)?)?
            }
            Long("min-n") => a.min_n = count("--min-n", &string_value("--min-n", p.value()?)?)?,
            Long("max-n") => a.max_n = count("--max-n", &string_value("--max-n", p.value()?)?)?,
            Long("seeds") => a.seeds = seeds(&string_value("--seeds", p.value()?)?)?,
            Long("targets") => a.targets = targets(&string_value("--targets", p.value()?)?)?,
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
    common::check_output_dir("--out", &a.out)?;
    if let Some(m) = &a.markdown {
        common::check_markdown(m, "tradeoff")?;
        common::check_markdown(m, "time-to-error")?;
    }
    Ok(Some(a))
}

/// `--samplers`: registered samplers, or `all`.
fn samplers(v: &str) -> Result<Vec<&'static Entry>, CliError> {
    list(
        v,
        || registry::entries().iter().collect(),
        registry::find,
        |e| e.name,
    )
}

/// `--integrands`: integrand names, or `all`.
fn integrands(v: &str) -> Result<Vec<Integrand>, CliError> {
    list(
        v,
        || Integrand::ALL.to_vec(),
        Integrand::by_name,
        |f| f.name(),
    )
}

/// `--min-n` and `--max-n`: a count, 1 to the study's largest.
fn count(flag: &str, v: &str) -> Result<u64, CliError> {
    parse_int(flag, v, 1, study::MAX_STUDY_COUNT)
}

/// `--seeds`: a fixed number of estimates per count, 2 to the study's most.
fn seeds(v: &str) -> Result<Seeds, CliError> {
    Ok(Seeds::Fixed(
        parse_int("--seeds", v, 2, study::MAX_SEEDS as u64)? as u32,
    ))
}

/// `--targets`: relative errors in (0, 1), largest first, each once.
fn targets(v: &str) -> Result<Vec<f64>, CliError> {
    let mut targets: Vec<f64> = v
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
    targets.sort_by(|x, y| y.total_cmp(x));
    targets.dedup();
    Ok(targets)
}
