//! `mask`: a blue-noise dither mask by void and cluster, written as the Rust table the
//! renderer's crate includes (its built-in mask is this program's default output).
//!
//! ```text
//! cargo run --release --example mask -- [--side N] [--seed S] [--out FILE] [--png FILE]
//! ```

mod common;

use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int};
use strata::pixel::frames::MAX_MASK_SIDE;
use strata_lab::io::{Canvas, Rgb};
use strata_lab::samplers::mask::{BUILTIN_SEED, BUILTIN_SIDE, rust_table, void_and_cluster};

/// Where the renderer's crate reads its built-in mask, from the repository's root.
const BUILTIN_TABLE: &str = "strata/src/pixel/frames/blue_noise_64.rs";

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "mask: a blue-noise dither mask of side x side pixels by void and cluster \
(Ulichney 1993; strata_lab::samplers::mask), written as a Rust table of its ranks (row-major, \
u16) under a header naming the options that made it. The renderer's crate reads its built-in \
mask (strata::pixel::frames::BlueNoiseMask::builtin) from the default output, and the lab's \
tests check that file against the function.";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them).
#[derive(clap::Parser)]
#[command(name = "mask", about = ABOUT)]
struct Args {
    /// a power of two from 4 to 256
    #[arg(long, value_name = "N", default_value_t = BUILTIN_SIDE,
          value_parser = common::value_parser(side))]
    side: u32,
    /// the seed that breaks the fill's ties (the default is the built-in's)
    #[arg(long, value_name = "S", default_value_t = BUILTIN_SEED.0,
          value_parser = common::whole::<u64>("--seed", 0, u64::MAX))]
    seed: u64,
    /// the Rust table (the default is the built-in's, from the repository's root)
    #[arg(long, value_name = "FILE", default_value = BUILTIN_TABLE)]
    out: std::path::PathBuf,
    /// also the mask as a grey picture, one pixel per rank (black: rank 0)
    #[arg(long, value_name = "FILE")]
    png: Option<std::path::PathBuf>,
}

/// `--side N`: a power of two from 4 to [`MAX_MASK_SIDE`].
fn side(v: &str) -> Result<u32, CliError> {
    let side = parse_int("--side", v, 4, MAX_MASK_SIDE as u64)? as u32;
    if !side.is_power_of_two() {
        return Err(cli_error(format!(
            "--side {side}: a power of two from 4 to {MAX_MASK_SIDE} is needed"
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
    common::run("mask", || {
        let Some(args) = parse()? else {
            return Ok(());
        };
        // both outputs checked before the work
        strata_lab::io::check_writable(&args.out)?;
        if let Some(png) = &args.png {
            strata_lab::io::check_writable(png)?;
        }
        let start = Instant::now();
        let table = rust_table(args.side, strata::Seed(args.seed))?;
        strata_lab::io::write_text(&args.out, &table)?;
        if let Some(png) = &args.png {
            let ranks = void_and_cluster(args.side, strata::Seed(args.seed))?;
            let n = (args.side * args.side) as f32;
            let mut canvas = Canvas::new(args.side, args.side, Rgb([0, 0, 0]));
            for (i, &r) in ranks.iter().enumerate() {
                let g = (r as f32 * 256.0 / n) as u8;
                let (x, y) = (i as u32 % args.side, i as u32 / args.side);
                canvas.set(x as i64, y as i64, Rgb([g, g, g]));
            }
            strata_lab::io::write_png(png, &canvas)?;
        }
        outln!(
            "wrote {} ({} x {} ranks, seed {}) in {:.2} s",
            args.out.display(),
            args.side,
            args.side,
            args.seed,
            start.elapsed().as_secs_f64()
        )?;
        Ok(())
    })
}
