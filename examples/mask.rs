//! `mask`: a blue-noise dither mask by void and cluster, written as the Rust table the
//! renderer's crate includes (its built-in mask is this program's default output).
//!
//! ```text
//! cargo run --release --example mask -- [--side N] [--seed S] [--out FILE] [--png FILE]
//! ```

mod common;

use std::process::ExitCode;
use std::time::Instant;

use common::{CliError, cli_error, parse_int, string_value};
use strata::pixel::frames::MAX_MASK_SIDE;
use strata_lab::io::{Canvas, Rgb};
use strata_lab::samplers::mask::{BUILTIN_SEED, BUILTIN_SIDE, rust_table, void_and_cluster};

const USAGE: &str = "mask [--side N] [--seed S] [--out FILE] [--png FILE]";

/// Where the renderer's crate reads its built-in mask, from the repository's root.
const BUILTIN_TABLE: &str = "strata/src/pixel/frames/blue_noise_64.rs";

struct Args {
    side: u32,
    seed: u64,
    out: std::path::PathBuf,
    png: Option<std::path::PathBuf>,
}

fn help() -> String {
    format!(
        "\
mask: a blue-noise dither mask of side x side pixels by void and cluster (Ulichney 1993;
strata_lab::samplers::mask), written as a Rust table of its ranks (row-major, u16) under a
header naming the options that made it. The renderer's crate reads its built-in mask
(strata::pixel::frames::BlueNoiseMask::builtin) from the default output, and the lab's tests
check that file against the function.

Usage:
  cargo run --release --example mask -- [options]

Options:
  --side N      a power of two from 4 to {MAX_MASK_SIDE} (default {BUILTIN_SIDE})
  --seed S      the seed that breaks the fill's ties (default {BUILTIN_SEED}, the built-in's)
  --out FILE    the Rust table (default {BUILTIN_TABLE}, the built-in's, from the repository's
                root)
  --png FILE    also the mask as a grey picture, one pixel per rank (black: rank 0)
  -h, --help    this text"
    )
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut args = Args {
        side: BUILTIN_SIDE,
        seed: BUILTIN_SEED,
        out: BUILTIN_TABLE.into(),
        png: None,
    };
    let mut parser = lexopt::Parser::from_env();
    while let Some(arg) = parser.next()? {
        match arg {
            Long("side") => {
                let v = string_value("--side", parser.value()?)?;
                let side = parse_int("--side", &v, 4, MAX_MASK_SIDE as u64)? as u32;
                if !side.is_power_of_two() {
                    return Err(cli_error(format!(
                        "--side {side}: a power of two from 4 to {MAX_MASK_SIDE} is needed"
                    )));
                }
                args.side = side;
            }
            Long("seed") => {
                let v = string_value("--seed", parser.value()?)?;
                args.seed = parse_int("--seed", &v, 0, u64::MAX)?;
            }
            Long("out") => args.out = parser.value()?.into(),
            Long("png") => args.png = Some(parser.value()?.into()),
            Short('h') | Long("help") => {
                common::out(help())?;
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    Ok(Some(args))
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
        let table = rust_table(args.side, args.seed)?;
        strata_lab::io::write_text(&args.out, &table)?;
        if let Some(png) = &args.png {
            let ranks = void_and_cluster(args.side, args.seed)?;
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
