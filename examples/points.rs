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

use common::{CliError, MAX_CLI_COUNT, cli_error, parse_int, parse_pair};
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

/// The short usage, in the messages of a missing option.
const USAGE: &str = "points --sampler NAME -n N [options] (see --help)";

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "points: print a sample set as CSV (header, then one row per sample in \
sequence order), or draw it.";

/// The end of `--help`.
const NOTES: &str = "Fixed-count samplers print their first set of N; progressive samplers the \
first N points of their endless sequence.";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them);
/// the sampler parameters are added from the registry ([`common::with_sampler_params`]).
#[derive(clap::Parser)]
#[command(name = "points", about = ABOUT, after_help = NOTES)]
struct Cli {
    /// the sampler (see --list)
    #[arg(long, value_name = "NAME", value_parser = clap::builder::NonEmptyStringValueParser::new())]
    sampler: Option<String>,
    /// number of samples, 1 to 67108864 (2^26)
    #[arg(short = 'n', value_name = "N", value_parser = common::whole::<u64>("-n", 1, MAX_CLI_COUNT))]
    n: Option<u64>,
    /// seed of everything; same arguments, same bytes
    #[arg(long, value_name = "S", default_value_t = 1,
          value_parser = common::whole::<u64>("--seed", 0, u64::MAX))]
    seed: u64,
    /// dimensions per sample
    #[arg(long, value_name = "D", default_value_t = 2,
          value_parser = common::whole::<u64>("--dims", 1, 1 << 16))]
    dims: u64,
    /// the values the path-tracer adapter gives pixel (X,Y); --sampler is then a sequence (the
    /// list is added at run time)
    #[arg(long, value_name = "X,Y", value_parser = common::value_parser(pixel))]
    pixel: Option<Pixel>,
    /// the image of the Z-ordered adapter sequences (the list is added at run time)
    #[arg(long, value_name = "WxH", value_parser = common::value_parser(resolution))]
    resolution: Option<Resolution>,
    /// also draw the points (with the strata grid) into FILE
    #[arg(long, value_name = "FILE")]
    png: Option<std::path::PathBuf>,
    /// csv, utk (UTK text: space-separated, no header) or bin (UTK binary: the magic UTK!, data
    /// type 4 = f32, counts, then the values)
    #[arg(long, value_name = "F", default_value = "csv", value_parser = common::value_parser(format))]
    format: FormatArg,
    /// omit the CSV header line
    #[arg(long)]
    no_header: bool,
    /// print every registered sampler with a one-line description
    #[arg(long)]
    list: bool,
}

/// `--pixel X,Y`.
#[derive(Clone)]
struct Pixel(u64, u64);

/// `--resolution WxH`.
#[derive(Clone)]
struct Resolution([u32; 2]);

/// `--format`.
#[derive(Clone)]
struct FormatArg(Format);

/// `--pixel X,Y`: two whole numbers up to `u32::MAX`.
fn pixel(v: &str) -> Result<Pixel, CliError> {
    let (x, y) = parse_pair("--pixel", v, u32::MAX as u64)?;
    Ok(Pixel(x, y))
}

/// `--resolution WxH`: each side 1 to 65536.
fn resolution(v: &str) -> Result<Resolution, CliError> {
    let bad = || {
        cli_error(format!(
            "--resolution {v:?} is not WxH; allowed: two whole numbers 1 to 65536, e.g. 256x256"
        ))
    };
    let (w, h) = v.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok(Resolution([
        parse_int("--resolution", w, 1, 65536)? as u32,
        parse_int("--resolution", h, 1, 65536)? as u32,
    ]))
}

/// `--format`: csv, utk or bin.
fn format(v: &str) -> Result<FormatArg, CliError> {
    Ok(FormatArg(Format::by_name(v)?))
}

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
    use clap::{CommandFactory, FromArgMatches};
    let sequences = format!(
        "the values the path-tracer adapter gives pixel (X,Y); --sampler is then a sequence: {}",
        common::sequence_help(false, 0, 0, usize::MAX)
    );
    let z = format!(
        "the image of the Z-ordered adapter sequences {} (with --pixel; default 256x256; the \
         others ignore it)",
        common::sequence_help(true, 0, 0, usize::MAX)
    );
    let command = common::with_sampler_params(Cli::command())
        .mut_arg("pixel", |a| a.help(sequences))
        .mut_arg("resolution", |a| a.help(z));
    let Some(matches) = common::clap_matches(command)? else {
        return Ok(None);
    };
    let c = Cli::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?;
    if c.list {
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
    let mut params = Params::new(1).seed(strata::Seed(c.seed));
    common::read_sampler_params(&matches, &mut params)?;
    Ok(Some(Args {
        sampler: c.sampler,
        n: c.n,
        params,
        dims: c.dims,
        pixel: c.pixel.map(|p| (p.0, p.1)),
        resolution: c.resolution.map(|r| r.0),
        png: c.png,
        header: !c.no_header,
        format: c.format.0,
    }))
}

fn main() -> ExitCode {
    common::run("points", || {
        let Some(args) = parse()? else { return Ok(()) };
        let job = check(&args)?;
        let started = std::time::Instant::now();
        let made = make(&args, &job)?;
        if job.long_run {
            let s = started.elapsed().as_secs_f64();
            eprintln!("points: made in {s:.1} s; writing");
        }
        if let Some(path) = &args.png {
            draw(path, &made, job.dims)?;
        }
        print(&args, &made.values, job.dims)
    })
}

/// A run's checked request: what to make and how much of it.
struct Job {
    name: String,
    n: u64,
    dims: usize,
    /// The registered sampler (`None` with `--pixel`: an adapter sequence).
    entry: Option<&'static registry::Entry>,
    /// Long enough to say so on stderr.
    long_run: bool,
}

/// Every check before any work: the options required and those that would be ignored, the
/// count the sampler takes, the values and the picture bounded before anything is allocated.
fn check(args: &Args) -> Result<Job, CliError> {
    let name = args.sampler.clone().ok_or_else(|| {
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
                "--{p} is a sampler parameter; with --pixel the path-tracer sequences take \
                 none (allowed with --pixel: --seed, --dims, --resolution)"
            )));
        }
        None
    } else {
        let e = registry::find(&name)?;
        // the suggestions of the count message stay within this program's limit
        e.counts.check_within(e.name, n, MAX_CLI_COUNT)?;
        Some(e)
    };
    let dims = args.dims as usize;
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
    // relaxations and optimisations are long from a few thousand points on
    let long_run = n * dims as u64 >= LONG_RUN_VALUES
        || (entry.is_some_and(|e| e.expensive) && n >= LONG_RUN_EXPENSIVE);
    Ok(Job {
        name,
        n,
        dims,
        entry,
        long_run,
    })
}

/// The values made (rows of `dims`, point-major) and the strata grids the picture draws.
struct Made {
    values: Vec<f32>,
    /// The 2D sampler's grids.
    grids: Vec<strata::StrataGrid>,
    /// The grid of each 2D projection, row y, column x (a D-dimensional sampler, with --png).
    projection_grids: Vec<Option<strata::StrataGrid>>,
}

/// Builds the sampler (which refuses what it cannot make), then, a long run saying so on
/// stderr (stdout holds the values), makes the values.
fn make(args: &Args, job: &Job) -> Result<Made, CliError> {
    let (n, dims) = (job.n, job.dims);
    let say = || {
        if job.long_run {
            let name = &job.name;
            eprintln!("points: {n} points of {name} in {dims} dimensions ...");
        }
    };
    let mut made = Made {
        values: vec![0f32; n as usize * dims],
        grids: Vec::new(),
        projection_grids: Vec::new(),
    };
    let Some(entry) = job.entry else {
        let resolution = args.resolution.unwrap_or([256, 256]);
        let sequence = Sequence::by_name(&job.name, resolution)?;
        let spp =
            u32::try_from(n).map_err(|_| cli_error("-n must fit the samples per pixel (u32)"))?;
        let seed = args.params.seed;
        let mut sampler = PixelSampler::new(sequence, spp, seed)?;
        say();
        let (x, y) = args.pixel.expect("--pixel");
        for (index, row) in made.values.chunks_exact_mut(dims).enumerate() {
            sampler.fill_sample([x as u32, y as u32], index as u64, 0, row);
        }
        return Ok(made);
    };
    // one build for any --dims: a 2D sampler (with its strata grids) at 2
    let mut params = args.params.clone();
    params.count = n;
    let params = params.dims(args.dims as u32);
    let built = entry.make(&params, Strictness::Strict)?;
    say();
    match built {
        Built::Two(mut sampler) => {
            let mut points = vec![[0.0f32; 2]; n as usize];
            strata::Sampler::fill(&mut sampler, &mut points);
            for (row, p) in made.values.chunks_exact_mut(2).zip(&points) {
                row.copy_from_slice(p);
            }
            made.grids = strata::Sampler::strata(&sampler, n);
        }
        mut sampler => {
            sampler.fill(&mut made.values);
            if args.png.is_some() {
                made.projection_grids = (0..dims * dims)
                    .map(|k| sampler.projection_strata((k % dims) as u32, (k / dims) as u32))
                    .collect();
            }
        }
    }
    Ok(made)
}

/// The picture: the points with their grids, or the matrix of all 2D projections.
fn draw(path: &std::path::Path, made: &Made, dims: usize) -> Result<(), CliError> {
    let values = &made.values;
    let canvas = if dims > 2 {
        let tile = (900 / dims as u32).clamp(48, 200);
        strata_lab::io::draw_projections(values, dims as u32, tile, &made.projection_grids)
    } else {
        // the points (the first dimension twice for D = 1)
        let points: Vec<[f32; 2]> = values
            .chunks_exact(dims)
            .map(|r| [r[0], r[dims - 1]])
            .collect();
        strata_lab::io::draw_points(&points, &made.grids, 640)
    };
    strata_lab::io::write_png(path, &canvas)?;
    Ok(())
}

/// The values on stdout, in the format asked for.
fn print(args: &Args, values: &[f32], dims: usize) -> Result<(), CliError> {
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, stdout.lock());
    if args.format != Format::Csv {
        let written =
            pointsets::write_f32(values, dims as u32, args.format, &mut out).and_then(|()| {
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
}
