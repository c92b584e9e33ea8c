//! The command line: the usage and help texts, the options, their parsing with one-line
//! errors that say what is allowed, and the checks made before any work.

use std::path::PathBuf;

use strata::pixel::{Padding, Sequence};

use crate::common::{self, CliError, cli_error, parse_int};
use crate::scene::SceneKind;
use crate::trace::Layout;

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "render: a small path tracer rendered with each sampler at one or more \
sample counts and compared with a converged reference.";

/// What a run writes and prints (the end of `--help`).
const WRITES: &str = "\
Writes, into DIR: render.csv (sampler,spp,rmse,rel_rmse,ms,blur1_rmse,blur2_rmse,lowband, \
masked_rmse,masked_blur1_rmse,masked_blur2_rmse,masked_lowband: one row per sampler and count; \
rmse over all pixels and channels of linear radiance, rel_rmse of |I - R| / (R + 0.02) on \
luminance, ms the render time on all cores; blur1_rmse, blur2_rmse and lowband describe the \
signed luminance error image: its RMSE after a Gaussian blur of sigma 1 and 2 pixels, and the \
share of its power (mean error excluded) below 1/8 cycle per pixel, about 0.05 for white \
error; the masked_ columns are rmse and those three without the pixels that see an emitter, \
directly or in a mirror, whose error is the emitter's edge), emitter-mask.png (the reference with \
those pixels in magenta), NAME.png and NAME-error.png (the largest count; the error map is the per-pixel \
relative error, colour-mapped from 0 to 0.5), NAME-SPP.png and NAME-SPP-error-spectrum.png \
(the signed error image beside its periodogram) for each count, reference.png, compare.png \
(one row per sampler), blue-noise.png (every sampler's error image and periodogram at 1, 4 and \
16 spp, those rendered, else at the smallest count) and blue-noise-masked.png (the same without the pixels that see an emitter), convergence.png (RMSE against spp with the fitted slope per sampler) and \
pareto.png (RMSE against render time, the sequences on the Pareto front bold); prints the \
tables, the slopes and the renderer's trade: per sequence the render time to reach the RMSE \
that the median sequence reaches at each count but the smallest (power laws of RMSE and \
time against spp fitted over the counts; '*' where extrapolated).";

/// The options as the command line declares them: each one's help, default and allowed
/// values, written once (clap makes `--help`, the usage and the errors from them).
#[derive(clap::Parser)]
#[command(name = "render", about = ABOUT, after_help = WRITES)]
struct Cli {
    /// path-tracer sequences, or all (the default); the list is added at run time
    #[arg(long, value_name = "a,b,..|all", default_value = "all",
          value_parser = common::value_parser(samplers))]
    samplers: Names,
    /// samples per pixel, one to eight counts, each 1 to 65536 (jittered needs squares)
    #[arg(long, value_name = "N[,N,..]", default_value = "4,16,64,256",
          value_parser = common::value_parser(spp))]
    spp: Counts,
    /// image size, each side 8 to 1024; every sequence and count keeps its images until the
    /// pictures are drawn: a run whose estimate passes 4 GiB is refused before any work (see
    /// docs/cli.md)
    #[arg(long, value_name = "WxH", default_value = "128x128",
          value_parser = common::value_parser(size))]
    size: Size,
    /// the scene
    #[arg(long, value_enum, value_name = "NAME", default_value_t = SceneKind::Cornell)]
    scene: SceneKind,
    /// how two draws' samples meet (strata::Padding)
    #[arg(long, value_enum, default_value_t = PaddingArg::Shells)]
    padding: PaddingArg,
    /// where a path's draws go
    #[arg(long, value_enum, default_value_t = Layout::Bounce)]
    layout: Layout,
    /// also a sequence of F frames (2 to 64) of the static camera per sampler, count and seed,
    /// whose pixels exchange their draws within tiles between frames so that the error
    /// follows a blue-noise mask (Heitz and Belcour 2019; strata::pixel::frames), measured over
    /// frames 2 to F beside frame 1: a table on stdout and in --markdown (with --interactions,
    /// the interaction part's low band too)
    #[arg(long, value_name = "F", value_parser = common::whole::<u32>("--frames", 2, 64))]
    frames: Option<u32>,
    /// also an adaptive image per sampler and seed: each pixel stops at its own count, from 1
    /// to MAX (2 to 4096), varying smoothly over the image (a random field over cells of 16
    /// pixels hashed from the seed, the same for every sampler; a Z-ordered sequence is told
    /// MAX); measured as the other renders, emitters masked: a table on stdout and in
    /// --markdown, and adaptive.csv
    #[arg(long, value_name = "MAX", value_parser = common::whole::<u32>("--adaptive", 2, 4096))]
    adaptive: Option<u32>,
    /// the tiles' side of --frames, 1 to 64
    #[arg(long, value_name = "T", default_value_t = 4,
          value_parser = common::whole::<u32>("--frame-tile", 1, strata::pixel::frames::MAX_TILE as u64))]
    frame_tile: u32,
    /// samples per pixel of the reference (default 16 x the largest count, at least 1024, at
    /// most 65536; never below the largest count)
    #[arg(long, value_name = "N", value_parser = common::whole::<u32>("--reference-spp", 1, 65536))]
    reference_spp: Option<u32>,
    /// seed of the samplers (the reference has its own)
    #[arg(long, value_name = "S", default_value_t = 1,
          value_parser = common::whole::<u64>("--seed", 0, u64::MAX))]
    seed: u64,
    /// renders per sampler and count, seeds S to S+K-1, 1 to 1024: rmse and rel_rmse are over
    /// all of them (the root of the mean squared error), ms is the mean time, s.e. the
    /// standard error of a ratio over them; the pictures show seed S
    #[arg(long, value_name = "K", default_value_t = 4,
          value_parser = common::whole::<u32>("--seeds", 1, 1024))]
    seeds: u32,
    /// output directory
    #[arg(long, value_name = "DIR", default_value = "out/render")]
    out: PathBuf,
    /// at the smallest count, also split the error (emitters masked) into its one-draw part
    /// (each draw's main effect, the other draws integrated out by 64 Sobol' points) and the
    /// interaction part (the rest), and print their RMSE, blurred RMSE and low-band share
    /// (direct-lighting scenes only: spheres, cornell-direct, studio-direct)
    #[arg(long)]
    interactions: bool,
    /// also write the tables into FILE, as its section 'render-SCENE-COUNTS' (e.g.
    /// render-cornell-4,16,64,256), followed by -interacting, -frames, -adaptive, -nested or
    /// -uniform with those options
    #[arg(long, value_name = "FILE")]
    markdown: Option<PathBuf>,
}

/// `--samplers`: the names, each once in the order given.
#[derive(Clone)]
struct Names(Vec<String>);

/// `--spp`: the counts, sorted, each once.
#[derive(Clone)]
struct Counts(Vec<u32>);

/// `--size WxH`.
#[derive(Clone)]
struct Size(u32, u32);

/// `--padding`, as the command line names them.
#[derive(Clone, Copy, clap::ValueEnum)]
enum PaddingArg {
    /// each dyadic shell [2^j, 2^(j+1)) of the index reordered per draw by a sharply
    /// 2-transitive map, every power-of-two prefix a net
    Shells,
    /// the nested index shuffle alone, every prefix a net
    Nested,
    /// each block of spp samples reordered per draw, only whole blocks nets
    Uniform,
}

/// The options of a run.
pub struct Args {
    pub samplers: Vec<String>,
    pub spp: Vec<u32>,
    pub size: (u32, u32),
    pub scene: SceneKind,
    pub padding: Padding,
    /// Where the draws of a path go.
    pub layout: Layout,
    /// `--frames F`: the frames of the a-posteriori permutation study (0: none).
    pub frames: u32,
    /// `--frame-tile T`: its tiles' side.
    pub frame_tile: u32,
    /// `--adaptive MAX`: the largest stopping count of the adaptive images.
    pub adaptive: Option<u32>,
    pub reference_spp: Option<u32>,
    pub seed: u64,
    pub seeds: u32,
    pub out: PathBuf,
    pub markdown: Option<PathBuf>,
    /// Split the error at the smallest count into one-draw and interaction parts.
    pub interactions: bool,
}

/// The options from the command line (`None` after `--help`), checked: the reference at
/// least the largest count, the output directory and the Markdown file writable.
pub fn parse() -> Result<Option<Args>, CliError> {
    use clap::{CommandFactory, FromArgMatches};
    let sequences = format!(
        "path-tracer sequences (default all; the Z-ordered ones for the image size): {}; also \
         references written in this program, not in all: pbrt-padded (pbrt-v4's \
         PaddedSobolSampler, FastOwen), pbrt-zsobol (its ZSobolSampler; powers of two) and \
         pbrt-zsobol-seeded (the same with the seed in its pixel order's hash, which pbrt keys \
         by the dimension alone: a new order per seed, as the crate's Z-ordered sequences), \
         openqmc-sobolbn (OpenQMC's SobolBnSampler: progressive blue noise from its 256 x 256 \
         table; the seed is its frame, times 65536), and experiments on a sequence SEQ, not in all: SEQ+permute (each draw reads its samples \
         through a random permutation of the pixel's 0..spp, pbrt's pairing; powers of two) and \
         SEQ+shells (a random permutation inside each shell [2^j, 2^(j+1)) of the index: every \
         power-of-two prefix keeps its samples)",
        common::sequence_help(false, 0, 0, usize::MAX)
    );
    let command = Cli::command().mut_arg("samplers", |a| a.help(sequences));
    let Some(matches) = common::clap_matches(command)? else {
        return Ok(None);
    };
    let c = Cli::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?;
    let a = Args {
        samplers: c.samplers.0,
        spp: c.spp.0,
        size: (c.size.0, c.size.1),
        scene: c.scene,
        padding: match c.padding {
            PaddingArg::Shells => Padding::Shells,
            PaddingArg::Nested => Padding::Nested,
            PaddingArg::Uniform => Padding::Uniform,
        },
        layout: c.layout,
        frames: c.frames.unwrap_or(0),
        frame_tile: c.frame_tile,
        adaptive: c.adaptive,
        reference_spp: c.reference_spp,
        seed: c.seed,
        seeds: c.seeds,
        out: c.out,
        markdown: c.markdown,
        interactions: c.interactions,
    };
    check(&a)?;
    Ok(Some(a))
}

/// Every adapter sequence: the default of `--samplers`, and `--samplers all`.
fn every_sequence() -> Vec<String> {
    Sequence::NAMES.iter().map(|s| s.to_string()).collect()
}

/// `--samplers`: the names, or `all`.
fn samplers(v: &str) -> Result<Names, CliError> {
    if v == "all" {
        return Ok(Names(every_sequence()));
    }
    // each name once, in the order given (a repeated name rendered twice before)
    let mut names: Vec<String> = Vec::new();
    for name in v.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        if !names.iter().any(|n| n == name) {
            names.push(name.to_string());
        }
    }
    if names.is_empty() {
        return Err(cli_error("--samplers needs at least one name (or all)"));
    }
    Ok(Names(names))
}

/// `--spp`: the counts, sorted, each once, at most [`MAX_COUNTS`] of them.
fn spp(v: &str) -> Result<Counts, CliError> {
    let mut spp: Vec<u32> = v
        .split(',')
        .map(|s| parse_int("--spp", s, 1, 65536).map(|n| n as u32))
        .collect::<Result<_, _>>()?;
    spp.sort_unstable();
    spp.dedup();
    if spp.len() > MAX_COUNTS {
        return Err(cli_error(format!(
            "--spp lists {} counts; allowed: at most {MAX_COUNTS}",
            spp.len()
        )));
    }
    Ok(Counts(spp))
}

/// `--size WxH`: each side 8 to [`MAX_SIDE`].
fn size(v: &str) -> Result<Size, CliError> {
    let bad = || {
        cli_error(format!(
            "--size {v:?} is not WxH; allowed: two whole numbers 8 to {MAX_SIDE}, e.g. 128x128"
        ))
    };
    let (w, h) = v.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok(Size(
        parse_int("--size", w, 8, MAX_SIDE)? as u32,
        parse_int("--size", h, 8, MAX_SIDE)? as u32,
    ))
}

/// The checks after the flags, before any work: `--reference-spp` at least the largest count,
/// `--interactions` only in direct lighting, the output directory writable, the Markdown file
/// (if any) one that can be rewritten.
fn check(a: &Args) -> Result<(), CliError> {
    let largest = *a.spp.last().expect("at least one count");
    if let Some(r) = a.reference_spp
        && r < largest
    {
        return Err(cli_error(format!(
            "--reference-spp {r} is below the largest --spp {largest}: the error would be \
                 measured against a noisier image; allowed: {largest} to 65536"
        )));
    }
    if a.seed.checked_add(a.seeds as u64 - 1).is_none() {
        return Err(cli_error(format!(
            "--seed {} with --seeds {}: the seeds S to S+K-1 pass 2^64-1; allowed: --seed at \
             most {}",
            a.seed,
            a.seeds,
            u64::MAX - (a.seeds as u64 - 1)
        )));
    }
    let need = memory_estimate(a);
    if need > MAX_MEMORY {
        let renders = a.samplers.len() * a.spp.len();
        return Err(cli_error(format!(
            "--size {}x{} with {renders} renders ({} sequences x {} counts) needs about {} MiB \
             ({BYTES_PER_RENDER_PIXEL} bytes per pixel per render, kept for the pictures); \
             allowed: at most {} MiB: fewer sequences, counts or pixels",
            a.size.0,
            a.size.1,
            a.samplers.len(),
            a.spp.len(),
            need >> 20,
            MAX_MEMORY >> 20
        )));
    }
    if a.interactions && matches!(a.scene, SceneKind::Cornell | SceneKind::Studio) {
        return Err(cli_error(
            "--interactions splits the error of a direct-lighting render; allowed with --scene \
             spheres, cornell-direct or studio-direct (every bounce has too many draws to \
             integrate each out)",
        ));
    }
    common::check_output_dir("--out", &a.out)?;
    if let Some(m) = &a.markdown {
        common::check_markdown(m, &markdown_section(a))?;
    }
    Ok(())
}

/// The name of the `--markdown` section a run writes: `render-SCENE-COUNTS`, then
/// `-interacting`, `-frames`, `-nested` or `-uniform` for a run with that layout, frames or
/// padding.
pub fn markdown_section(args: &Args) -> String {
    let counts: Vec<String> = args.spp.iter().map(|n| n.to_string()).collect();
    let layout = match args.layout {
        Layout::Bounce => "",
        Layout::Interacting => "-interacting",
    };
    let frames = if args.frames > 0 { "-frames" } else { "" };
    let adaptive = if args.adaptive.is_some() {
        "-adaptive"
    } else {
        ""
    };
    let padding = match args.padding {
        Padding::Nested => "-nested",
        Padding::Uniform => "-uniform",
        _ => "",
    };
    format!(
        "render-{}-{}{layout}{frames}{adaptive}{padding}",
        args.scene.name(),
        counts.join(",")
    )
}

/// The largest image side.
const MAX_SIDE: u64 = 1024;

/// Bytes per pixel that every render (a sequence at a count) keeps until the pictures are
/// drawn: its image, its error image and their spectra, with and without the emitters, and its
/// tile of `compare.png`. Measured 53-63 (peak resident memory over 1 and 8 renders at 256^2
/// and 512^2); the allowance covers the allocator.
const BYTES_PER_RENDER_PIXEL: u64 = 72;

/// Bytes per pixel that a run keeps once (the reference, the emitter mask, the image being
/// rendered): measured 70.
const BYTES_PER_PIXEL: u64 = 96;

/// Bytes per pixel that `--frames` adds (its frames' estimates and the permutation of the
/// pixels' draws): about 60 measured.
const BYTES_PER_FRAMES_PIXEL: u64 = 64;

/// Bytes per pixel that `--interactions` adds (the split's one-draw and interaction images):
/// about 35 measured.
const BYTES_PER_SPLIT_PIXEL: u64 = 40;

/// What a run needs whatever its size (the program, its threads, the scene): measured 4 MiB.
const BASE_BYTES: u64 = 32 << 20;

/// The most memory a run may need by [`memory_estimate`]: 4 GiB.
pub const MAX_MEMORY: u64 = 4 << 30;

/// The memory a run needs, at most (the test `render_memory_stays_within_its_estimate`
/// compares it with the peak measured): refused before any work above [`MAX_MEMORY`]
/// (1024^2 with every sequence at eight counts once took 5.1 GB against a documented
/// "under 4 GB").
pub fn memory_estimate(a: &Args) -> u64 {
    let renders = (a.samplers.len() * a.spp.len()) as u64;
    let pixels = a.size.0 as u64 * a.size.1 as u64;
    let frames = if a.frames > 0 {
        BYTES_PER_FRAMES_PIXEL
    } else {
        0
    };
    let split = if a.interactions {
        BYTES_PER_SPLIT_PIXEL
    } else {
        0
    };
    BASE_BYTES + pixels * (BYTES_PER_PIXEL + renders * BYTES_PER_RENDER_PIXEL + frames + split)
}

/// Says on stderr the run's peak memory beside its estimate (where the system tells it).
pub fn report_memory(a: &Args) {
    if let Some(peak) = common::peak_memory() {
        let estimate = memory_estimate(a) >> 20;
        eprintln!(
            "render: peak memory {} MiB (estimated at most {estimate} MiB)",
            peak >> 20
        );
    }
}

/// The most sample counts in `--spp`.
const MAX_COUNTS: usize = 8;
