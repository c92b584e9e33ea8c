//! `bntable`: the table of the progressive blue-noise sequence `sobolbn` (per pixel of a
//! toroidal tile, an Owen scramble key and a rank), optimised so that the error is blue at every
//! power-of-two count, written as the Rust table the renderer's crate includes (its built-in
//! table is this program's default output).
//!
//! ```text
//! cargo run --release --example bntable -- [--side N] [--levels L] [--integrands K]
//!     [--effort E] [--no-polish] [--seed S] [--out FILE]
//! ```

mod common;

use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int};
use strata_lab::samplers::bntable::{BUILTIN, TableOptions, optimise, rust_table};

/// Where the renderer's crate reads its built-in table, from the repository's root.
const BUILTIN_TABLE: &str = "strata/src/pixel/bluenoise/sobol_128.rs";

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "bntable: the table of the progressive blue-noise sequence sobolbn (per \
pixel of a side x side torus, an Owen scramble key and a rank that XORs the sample index), \
optimised so that the error of neighbouring pixels cancels at every count 1, 2, ..., 2^levels \
(strata_lab::samplers::bntable: 4 x 4 blocks of pixels sharing their scramble's leading digits, \
whose ranks XOR patterns that make the block's samples together a net at every count, arranged \
by OpenQMC's keys-then-ranks method, then a polish over every count), written as a Rust table under a header naming the options, the command and the run time, \
with the low-band share of the error per count. The renderer's crate reads its built-in table \
(strata::pixel::BlueNoiseTable::builtin) from the default output.";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them).
#[derive(clap::Parser)]
#[command(name = "bntable", about = ABOUT)]
struct Args {
    /// the tile's side, a power of two from 16 to 1024
    #[arg(long, value_name = "N", default_value_t = BUILTIN.side,
          value_parser = common::value_parser(side))]
    side: u32,
    /// the counts arranged: 1 to 2^L samples, L from 1 to 10
    #[arg(long, value_name = "L", default_value_t = BUILTIN.levels,
          value_parser = common::whole::<u32>("--levels", 1, 10))]
    levels: u32,
    /// the test integrands the optimiser sees, 1 to 1024
    #[arg(long, value_name = "K", default_value_t = BUILTIN.integrands,
          value_parser = common::whole::<u32>("--integrands", 1, 1024))]
    integrands: u32,
    /// moves proposed per pixel and step, 1 to 10000 (the run time grows with it)
    #[arg(long, value_name = "E", default_value_t = BUILTIN.effort,
          value_parser = common::whole::<u32>("--effort", 1, 10_000))]
    effort: u32,
    /// skip the last step (whole entries swapped against every count's errors)
    #[arg(long)]
    no_polish: bool,
    /// the seed of the keys, the integrands and the annealing (the default is the built-in's)
    #[arg(long, value_name = "S", default_value_t = BUILTIN.seed.0,
          value_parser = common::whole::<u64>("--seed", 0, u64::MAX))]
    seed: u64,
    /// the Rust table; the default, the built-in table's file (strata/src/pixel/bluenoise/
    /// sobol_128.rs, from the repository's root), only with the built-in's options
    #[arg(long, value_name = "FILE")]
    out: Option<std::path::PathBuf>,
}

/// `--side N`: a power of two from 16 to 1024.
fn side(v: &str) -> Result<u32, CliError> {
    let side = parse_int("--side", v, 16, strata::pixel::bluenoise::MAX_SIDE as u64)? as u32;
    if !side.is_power_of_two() {
        return Err(cli_error(format!(
            "--side {side}: a power of two from 16 to 1024 is needed"
        )));
    }
    Ok(side)
}

fn parse() -> Result<Option<Args>, CliError> {
    use clap::{CommandFactory, FromArgMatches};
    let Some(matches) = common::clap_matches(Args::command())? else {
        return Ok(None);
    };
    Ok(Some(
        Args::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?,
    ))
}

fn main() -> ExitCode {
    common::run("bntable", || {
        let Some(args) = parse()? else {
            return Ok(());
        };
        let options = TableOptions {
            side: args.side,
            levels: args.levels,
            integrands: args.integrands,
            effort: args.effort,
            polish: !args.no_polish,
            seed: strata::Seed(args.seed),
        };
        let out = match args.out {
            Some(out) => out,
            None if options == BUILTIN => BUILTIN_TABLE.into(),
            None => {
                return Err(cli_error(
                    "--out FILE is needed with options other than the built-in's (without it \
                     the program rewrites the built-in table, strata/src/pixel/bluenoise/\
                     sobol_128.rs)",
                ));
            }
        };
        strata_lab::io::check_writable(&out)?;
        let start = Instant::now();
        let table = optimise(&options)?;
        let seconds = start.elapsed().as_secs_f64();
        let command: Vec<String> = std::env::args().skip(1).collect();
        let command = format!(
            "cargo run --release --example bntable -- {}",
            command.join(" ")
        );
        strata_lab::io::write_text(&out, &rust_table(&table, command.trim_end(), seconds))?;
        outln!("| count | low band, table | low band, random entries |\n|---|---|---|")?;
        for f in &table.lowband {
            outln!("| {} | {:.4} | {:.4} |", f.count, f.table, f.random)?;
        }
        outln!("wrote {} in {seconds:.1} s", out.display())?;
        Ok(())
    })
}
