//! The command line: the usage and help texts, the options, their parsing with one-line
//! errors that say what is allowed, and the checks made before any work.

use std::path::PathBuf;

use strata_lab::analysis::Integrand;
use strata_lab::analysis::study::{self, Seeds};
use strata_lab::registry::{self, Entry};

use crate::common::{self, CliError, cli_error};

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "tradeoff: the convergence of each sampler on test integrands, speed \
against accuracy.";

/// What a run measures and writes (the end of `--help`).
const DETAILS: &str = "Each sampler runs at its allowed counts nearest to the powers of two in [min-n, max-n]. Writes DIR/tradeoff.csv (sampler,integrand,n,seeds,mean,variance,rmse,ns_per_sample,predicted_variance, set_ns,set_ns_min,set_ns_max,one_time_ns), DIR/slopes.csv (sampler,integrand,slope,expected, slope_lo,slope_hi), DIR/time_to_error.csv (integrand,target,sampler,n,ns,extrapolated), DIR/convergence-INTEGRAND.png (variance against N, one panel per family, with the published rates) and DIR/tradeoff-INTEGRAND.png (RMSE against the time of a set, one panel per family, the samplers on the Pareto front bold and the front itself dashed), and prints the tables.\n\n\
Timing: the time of a set is building the sampler with a new seed and filling N points (for relaxations the whole optimisation), on one core, after an untimed first build that pays the one-time tables (reported as one_time_ns). Sets repeat until 1 ms of work is timed; the median of 5 such measurements is set_ns, and their range set_ns_min..set_ns_max.\n\n\
Slope intervals: 95% bootstrap intervals (400 resamples of the seeds at every count).\n\n\
Time to error: the RMSE and the set time are fitted as power laws of N over the measured counts; n is the smallest allowed count whose fitted RMSE meets the target, ns the fitted time of a set of n, extrapolated = 1 when n lies outside the measured counts. Samplers whose error does not fall with N have no row.\n\n\
predicted_variance = (1/N) sum_{w != 0} |f^(w)|^2 E[P(w)] from the integrand's Fourier coefficients and the sampler's measured expected spectrum (Subr and Kautz 2013; Pilleboue et al. 2015): exact for random sampling, an approximation for patterns that are not shift-invariant (stratified ones).";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them).
#[derive(clap::Parser)]
#[command(name = "tradeoff", about = ABOUT, after_help = DETAILS)]
struct Cli {
    /// registered samplers, or all
    #[arg(long, value_name = "a,b,..|all", default_value = "all",
          value_parser = common::value_parser(samplers))]
    samplers: Samplers,
    /// disk, triangle, step, gaussian, bilinear (2D), gaussian4d, ball4d (4D, for samplers
    /// with D dimensions), or all
    #[arg(long, value_name = "a,b,..|all", default_value = "all",
          value_parser = common::value_parser(integrands))]
    integrands: Integrands,
    /// smallest count
    #[arg(long, value_name = "N", default_value_t = 16,
          value_parser = common::whole::<u64>("--min-n", 1, study::MAX_STUDY_COUNT))]
    min_n: u64,
    /// largest count
    #[arg(long, value_name = "N", default_value_t = 1024,
          value_parser = common::whole::<u64>("--max-n", 1, study::MAX_STUDY_COUNT))]
    max_n: u64,
    /// estimates per count for every sampler, 2 to 65536 (default: by cost, 256 for samplers
    /// whose set at max-n takes under 0.125 ms, down to 32 for those over 1 ms; the count is in
    /// the tables)
    #[arg(long, value_name = "K",
          value_parser = common::whole::<u32>("--seeds", 2, study::MAX_SEEDS as u64))]
    seeds: Option<u32>,
    /// RMSE targets relative to the integral, each in (0, 1)
    #[arg(long, value_name = "e,e,..", default_value = "1e-2,1e-3,1e-4",
          value_parser = common::value_parser(targets))]
    targets: Targets,
    /// skip the variance predicted from the spectrum
    #[arg(long)]
    no_predict: bool,
    /// output directory
    #[arg(long, value_name = "DIR", default_value = "out/tradeoff")]
    out: PathBuf,
    /// also write the slopes and the time-to-error tables of disk and gaussian into FILE, as
    /// its sections 'tradeoff' and 'time-to-error'
    #[arg(long, value_name = "FILE")]
    markdown: Option<PathBuf>,
}

/// `--samplers`.
#[derive(Clone)]
struct Samplers(Vec<&'static Entry>);

/// `--integrands`.
#[derive(Clone)]
struct Integrands(Vec<Integrand>);

/// `--targets`.
#[derive(Clone)]
struct Targets(Vec<f64>);

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
    use clap::{CommandFactory, FromArgMatches};
    let Some(matches) = common::clap_matches(Cli::command())? else {
        return Ok(None);
    };
    let c = Cli::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?;
    let a = Args {
        samplers: c.samplers.0,
        integrands: c.integrands.0,
        min_n: c.min_n,
        max_n: c.max_n,
        seeds: c.seeds.map_or(Seeds::DEFAULT, Seeds::Fixed),
        targets: c.targets.0,
        predict: !c.no_predict,
        out: c.out,
        markdown: c.markdown,
    };
    common::check_output_dir("--out", &a.out)?;
    if let Some(m) = &a.markdown {
        common::check_markdown(m, "tradeoff")?;
        common::check_markdown(m, "time-to-error")?;
    }
    Ok(Some(a))
}

/// `--samplers`: registered samplers, or `all`.
fn samplers(v: &str) -> Result<Samplers, CliError> {
    list(
        v,
        || registry::entries().iter().collect(),
        registry::find,
        |e| e.name,
    )
    .map(Samplers)
}

/// `--integrands`: integrand names, or `all`.
fn integrands(v: &str) -> Result<Integrands, CliError> {
    list(
        v,
        || Integrand::ALL.to_vec(),
        Integrand::by_name,
        |f| f.name(),
    )
    .map(Integrands)
}

/// `--targets`: relative errors in (0, 1), largest first, each once.
fn targets(v: &str) -> Result<Targets, CliError> {
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
    Ok(Targets(targets))
}
