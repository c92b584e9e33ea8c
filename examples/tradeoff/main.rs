//! `tradeoff`: speed against accuracy. Convergence of every sampler on test integrands, the
//! fitted rates with bootstrap intervals against the published ones, the variance predicted
//! from the spectrum, the error against generation time with its Pareto front, and the time
//! each sampler needs to reach an error.
//!
//! ```text
//! cargo run --release --example tradeoff -- [--samplers a,b,..|all] [--integrands a,b,..|all]
//!         [--min-n N] [--max-n N] [--seeds K] [--targets e,e,..] [--out DIR]
//! ```
//!
//! The program's parts: [`args`] (the command line), [`files`] (the CSV files), [`plots`]
//! (the convergence and time panels) and [`tables`] (the printed tables and the Markdown
//! sections); the study itself is `strata_lab::analysis::study`.

#[path = "../common/mod.rs"]
mod common;

mod args;
mod files;
mod plots;
mod tables;

use std::process::ExitCode;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use strata_lab::analysis::study::{self, Config};

use crate::args::Args;

/// Runs the study, then writes the CSV files and the plots and prints the tables (see
/// `--help`).
fn main() -> ExitCode {
    common::run("tradeoff", || {
        let Some(args) = args::parse()? else {
            return Ok(());
        };
        let config = config(&args);
        study::check(&config)?;
        let bar = progress_bar(&config, &args);
        let start = Instant::now();
        let (rows, slopes) = study::run(&config, &|name, n| {
            bar.set_message(format!("{name} N={n}"));
            bar.inc(1);
            common::progress_line(format!("tradeoff: {name} N={n}"));
        })?;
        bar.finish_and_clear();

        files::write_rows(&args, &rows)?;
        files::write_slopes(&args, &slopes)?;
        let tte = study::time_to_error(&rows, &args.samplers, &args.targets);
        files::write_time_to_error(&args, &tte)?;
        plots::plots(&rows, &slopes, &args)?;

        let table = tables::slopes(&args, &rows, &slopes);
        common::out(&table)?;
        common::out(tables::times(&args, &tte))?;
        if let Some(path) = &args.markdown {
            tables::write_markdown(path, &args, &table, &tte)?;
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

/// The study's configuration from the options.
fn config(args: &Args) -> Config {
    Config {
        samplers: args.samplers.clone(),
        integrands: args.integrands.clone(),
        min_n: args.min_n,
        max_n: args.max_n,
        seeds: args.seeds,
        predict: args.predict,
    }
}

/// The progress bar of the study: one step per sampler and count.
fn progress_bar(config: &Config, args: &Args) -> ProgressBar {
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
    bar
}
