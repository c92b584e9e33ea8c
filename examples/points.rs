//! `points`: print a sample set as CSV (or UTK's text or binary format), or draw it.
//!
//! ```text
//! cargo run --release --example points -- --sampler NAME -n N [--seed S] [--dims D]
//!         [--pixel X,Y] [--NAME X for a sampler parameter] [--png FILE] [--list]
//!         [--format csv|utk|bin]
//! ```
//! See `docs/cli.md` (the command-line contract).

mod common;

use std::io::Write;
use std::process::ExitCode;

use common::{CliError, MAX_CLI_COUNT, cli_error, parse_int, parse_pair, string_value};
use strata::SamplerNd;
use strata::pixel::{PixelSampler, Sequence};
use strata_lab::pointsets::{self, Format};
use strata_lab::registry::{self, Built, Params, Strictness};

/// The most values (`N x D`) one run prints.
const MAX_VALUES: u64 = 1 << 27;

/// The most dimensions `--png` draws (every 2D projection: `D^2` tiles).
const MAX_PNG_DIMS: usize = 64;

/// Runs of at least this many values print a line on stderr before and after making them.
const LONG_RUN_VALUES: u64 = 1 << 22;
/// The count from which an expensive sampler (a relaxation, an optimisation) says what it does.
const LONG_RUN_EXPENSIVE: u64 = 1 << 12;

const USAGE: &str = "points --sampler NAME -n N [--seed S] [--dims D] [--pixel X,Y] \
[--radius|--iterations|... X (a sampler parameter; see --help)] [--resolution WxH] [--png FILE] \
[--format csv|utk|bin] [--no-header] [--list]";

const HELP: &str = "\
points: print a sample set as CSV (header, then one row per sample in sequence order), or draw it.

Usage:
  cargo run --release --example points -- --sampler NAME -n N [options]

Options:
  --sampler NAME     the sampler (see --list)
  -n N               number of samples, 1 to 67108864 (2^26)
  --seed S           seed of everything (u64, default 1); same arguments, same bytes
  --dims D           dimensions per sample (default 2)
  --pixel X,Y        the values the path-tracer adapter gives pixel (X,Y); --sampler is then
                     a sequence: {SEQUENCES}
  --resolution WxH   the image of the Z-ordered adapter sequences {Z_SEQUENCES}
                     (with --pixel; default 256x256; the others ignore it)
{PARAMETERS}  --png FILE         also draw the points (with the strata grid) into FILE
  --format F         csv (default), utk (UTK text: space-separated, no header) or bin (UTK
                     binary: the magic UTK!, data type 4 = f32, counts, then the values)
  --no-header        omit the CSV header line
  --list             print every registered sampler with a one-line description
  -h, --help         this text

Fixed-count samplers print their first set of N; progressive samplers the first N points of
their endless sequence.";

struct Args {
    sampler: Option<String>,
    n: Option<u64>,
    params: Params,
    dims: u64,
    pixel: Option<(u64, u64)>,
    resolution: Option<[u32; 2]>,
    png: Option<std::path::PathBuf>,
    header: bool,
    format: Format,
}

fn parse() -> Result<Option<Args>, CliError> {
    use lexopt::prelude::*;
    let mut args = Args {
        sampler: None,
        n: None,
        params: Params::new(1),
        dims: 2,
        pixel: None,
        resolution: None,
        png: None,
        header: true,
        format: Format::Csv,
    };
    let mut parser = lexopt::Parser::from_env();
    while let Some(arg) = parser.next()? {
        match arg {
            Long("sampler") => args.sampler = Some(string_value("--sampler", parser.value()?)?),
            Short('n') => {
                let v = string_value("-n", parser.value()?)?;
                args.n = Some(parse_int("-n", &v, 1, MAX_CLI_COUNT)?);
            }
            Long("seed") => {
                let v = string_value("--seed", parser.value()?)?;
                args.params.seed = parse_int("--seed", &v, 0, u64::MAX)?;
            }
            Long("dims") => {
                let v = string_value("--dims", parser.value()?)?;
                args.dims = parse_int("--dims", &v, 1, 1 << 16)?;
            }
            Long("pixel") => {
                let v = string_value("--pixel", parser.value()?)?;
                args.pixel = Some(parse_pair("--pixel", &v, u32::MAX as u64)?);
            }
            Long(flag) if common::is_sampler_param(flag) => {
                let flag = flag.to_owned(); // the argument borrows the parser
                common::sampler_param(&flag, &mut parser, &mut args.params)?
            }
            Long("png") => args.png = Some(parser.value()?.into()),
            Long("resolution") => {
                let v = string_value("--resolution", parser.value()?)?;
                let bad = || {
                    cli_error(format!(
                        "--resolution {v:?} is not WxH; allowed: two whole numbers 1 to 65536, e.g. 256x256"
                    ))
                };
                let (w, h) = v.split_once(['x', 'X']).ok_or_else(bad)?;
                args.resolution = Some([
                    parse_int("--resolution", w, 1, 65536)? as u32,
                    parse_int("--resolution", h, 1, 65536)? as u32,
                ]);
            }
            Long("no-header") => args.header = false,
            Long("format") => {
                let v = string_value("--format", parser.value()?)?;
                args.format = Format::by_name(&v)?;
            }
            Long("list") => {
                for e in registry::entries() {
                    let kind = if e.progressive {
                        "progressive"
                    } else {
                        "fixed-count"
                    };
                    outln!(
                        "{:<16} {:<12} {:<16} {}",
                        e.name,
                        kind,
                        e.counts.to_string(),
                        e.description
                    )?;
                }
                return Ok(None);
            }
            Short('h') | Long("help") => {
                outln!(
                    "{}",
                    HELP.replace("{PARAMETERS}", &common::parameter_help())
                        .replace("{SEQUENCES}", &common::sequence_help(false, 33, 21, 95))
                        .replace("{Z_SEQUENCES}", &common::sequence_help(true, 64, 21, 95))
                )?;
                return Ok(None);
            }
            other => return Err(common::unexpected(other, USAGE)),
        }
    }
    Ok(Some(args))
}

fn main() -> ExitCode {
    common::run("points", || {
        let Some(args) = parse()? else { return Ok(()) };
        let name = args.sampler.ok_or_else(|| {
            cli_error(format!(
                "--sampler NAME is required (see --list); usage: {USAGE}"
            ))
        })?;
        let n = args.n.ok_or_else(|| {
            cli_error(format!(
                "-n N is required (1 to {MAX_CLI_COUNT}); usage: {USAGE}"
            ))
        })?;
        // options that would be ignored are refused
        if args.resolution.is_some() && args.pixel.is_none() {
            return Err(cli_error(
                "--resolution is the image of the Z-ordered sequences and needs --pixel X,Y; \
                 allowed without --pixel: a sampler's own parameters (see --help)",
            ));
        }
        if !args.header && args.format != Format::Csv {
            return Err(cli_error(
                "--no-header applies to --format csv only; UTK's formats have no header line",
            ));
        }
        // the adapter's sequences (with --pixel) include ones that are not registered samplers
        let entry = if args.pixel.is_some() {
            if let Some((p, _)) = args.params.given().next() {
                return Err(cli_error(format!(
                    "--{} is a sampler parameter; with --pixel the path-tracer sequences take \
                     none (allowed with --pixel: --seed, --dims, --resolution)",
                    p
                )));
            }
            None
        } else {
            Some(registry::find(&name)?)
        };
        if let Some(e) = entry {
            // the suggestions of the count message stay within this program's limit
            e.counts.check_within(e.name, n, MAX_CLI_COUNT)?;
        }
        let mut params = args.params.clone();
        params.count = n;
        let dims = args.dims as usize;
        // bounded before anything is allocated: the values, and the picture's canvas
        if n as u128 * dims as u128 > MAX_VALUES as u128 {
            return Err(cli_error(format!(
                "-n {n} x --dims {dims} = {} values is too many; allowed: at most {MAX_VALUES} \
                 (2^27, 512 MB)",
                n as u128 * dims as u128
            )));
        }
        if args.png.is_some() && dims > MAX_PNG_DIMS {
            return Err(cli_error(format!(
                "--png draws every 2D projection of the {dims} dimensions ({} of them); \
                 allowed: --dims at most {MAX_PNG_DIMS} with --png",
                dims * dims
            )));
        }
        if let Some(path) = &args.png
            && path.as_os_str().is_empty()
        {
            return Err(cli_error("--png: an empty file name"));
        }
        // everything is checked (the build refuses what the sampler cannot make) before a long
        // run says what it is doing, on stderr (stdout holds the values); relaxations and
        // optimisations are long from a few thousand points on
        enum Source {
            Pixel(Box<PixelSampler>),
            Built(Built),
        }
        let source = if args.pixel.is_some() {
            let resolution = args.resolution.unwrap_or([256, 256]);
            let sequence = Sequence::by_name(&name, resolution)?;
            let spp = u32::try_from(n)
                .map_err(|_| cli_error("-n must fit the samples per pixel (u32)"))?;
            Source::Pixel(Box::new(PixelSampler::new(
                sequence,
                spp,
                strata::Seed(args.params.seed),
            )?))
        } else {
            // one build for any --dims: a 2D sampler (with its strata grids) at 2
            let params = params.dims(args.dims as u32);
            Source::Built(
                entry
                    .expect("no --pixel")
                    .make(&params, Strictness::Strict)?,
            )
        };
        let started = std::time::Instant::now();
        let long_run = n * dims as u64 >= LONG_RUN_VALUES
            || (entry.is_some_and(|e| e.expensive) && n >= LONG_RUN_EXPENSIVE);
        if long_run {
            eprintln!("points: {n} points of {name} in {dims} dimensions ...");
        }
        // rows of `dims` values, point-major
        let mut values = vec![0f32; n as usize * dims];
        let mut grids = Vec::new();
        let mut projection_grids = Vec::new();
        match source {
            Source::Pixel(mut sampler) => {
                let [px, py] = args
                    .pixel
                    .map(|(x, y)| [x as u32, y as u32])
                    .expect("--pixel");
                for (index, row) in values.chunks_exact_mut(dims).enumerate() {
                    sampler.fill_sample([px, py], index as u64, 0, row);
                }
            }
            Source::Built(Built::Two(mut sampler)) => {
                let mut points = vec![[0.0f32; 2]; n as usize];
                strata::Sampler::fill(&mut sampler, &mut points);
                for (row, p) in values.chunks_exact_mut(2).zip(&points) {
                    row[0] = p[0];
                    row[1] = p[1];
                }
                grids = strata::Sampler::strata(&sampler, n);
            }
            Source::Built(mut sampler) => {
                sampler.fill(&mut values);
                // the grid of each 2D projection, row y, column x (only for the picture)
                if args.png.is_some() {
                    projection_grids = (0..dims * dims)
                        .map(|k| sampler.projection_strata((k % dims) as u32, (k / dims) as u32))
                        .collect();
                }
            }
        }

        if long_run {
            eprintln!(
                "points: made in {:.1} s; writing",
                started.elapsed().as_secs_f64()
            );
        }
        if let Some(path) = &args.png {
            let canvas = if dims > 2 {
                // the matrix of all 2D projections
                let tile = (900 / dims as u32).clamp(48, 200);
                strata_lab::io::draw_projections(&values, dims, tile, &projection_grids)
            } else {
                // the points (the first dimension twice for D = 1)
                let points: Vec<[f32; 2]> = values
                    .chunks_exact(dims)
                    .map(|r| [r[0], r[dims - 1]])
                    .collect();
                strata_lab::io::draw_points(&points, &grids, 640)
            };
            strata_lab::io::write_png(path, &canvas)?;
        }

        let stdout = std::io::stdout();
        let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
        if args.format != Format::Csv {
            let written =
                pointsets::write_f32(&mut out, args.format, dims, &values).and_then(|()| {
                    out.flush()
                        .map_err(|e| strata_lab::Error::io("<stdout>", e))
                });
            return match written {
                Err(strata_lab::Error::Io { source, .. })
                    if source
                        .downcast_ref::<std::io::Error>()
                        .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe) =>
                {
                    Err(CliError::BrokenPipe)
                }
                other => other.map_err(Into::into),
            };
        }
        let result = (|| -> std::io::Result<()> {
            if args.header {
                if dims == 2 {
                    writeln!(out, "x,y")?;
                } else {
                    let names: Vec<String> = (0..dims).map(|d| format!("x{d}")).collect();
                    writeln!(out, "{}", names.join(","))?;
                }
            }
            let mut line = String::new();
            for row in values.chunks_exact(dims) {
                line.clear();
                for (d, v) in row.iter().enumerate() {
                    if d > 0 {
                        line.push(',');
                    }
                    // the f32 widened: its shortest f64 form reads back exactly as f32 or f64
                    line.push_str(&f64::from(*v).to_string());
                }
                writeln!(out, "{line}")?;
            }
            out.flush()
        })();
        // a closed pipe (`points ... | head`) ends quietly (status 141); a full disk says so
        result.map_err(common::stdout_error)
    })
}
