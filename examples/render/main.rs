//! `render`: the samplers inside a small path tracer, against a converged reference, over a
//! sweep of sample counts.
//!
//! ```text
//! cargo run --release --example render -- [--samplers a,b,..|all] [--spp N[,N,..]]
//!         [--size WxH] [--scene cornell|spheres|cornell-direct] [--reference-spp N]
//!         [--interactions] [--out DIR]
//! ```
//!
//! Three scenes, all through the path-tracer adapter (`strata::pixel::PixelSampler`):
//!
//! * `cornell` (default): a Cornell box lit by two area lights, with a white diffuse sphere and
//!   a sphere that is half mirror, half diffuse. Up to eight bounces of diffuse
//!   interreflection, next-event estimation with a discrete choice of light (by power), a
//!   discrete choice of lobe, Russian roulette from the third bounce, and a thin-lens camera
//!   (caustics, diffuse-mirror-light paths, are left out, as in many production renderers):
//!   about 60 sample dimensions per path, each bounce at a fixed dimension budget
//!   (`start_bounce`), as a real path tracer takes them.
//! * `spheres`: direct lighting only (seven dimensions: pixel, lens, time, light).
//! * `cornell-direct`: the Cornell box in direct lighting (the first diffuse hit's next-event
//!   estimate).
//!
//! The reference is scrambled Sobol' at `--reference-spp` (default 16 times the largest count,
//! at least 1024) with another seed.
//!
//! The program's parts: [`args`] (the command line), [`scene`] (the scenes), [`trace`] (the
//! path tracer), [`split`] (the emitter mask and the interaction split), [`sweep`] (the
//! reference and every sequence at every count, measured),
//! [`picture`] (tone mapping, error maps), [`figures`] (`compare.png`, `blue-noise.png`) and
//! [`report`] (`render.csv`, the tables, the plots, the Markdown section).

#[path = "../common/mod.rs"]
mod common;

mod adaptive;
mod args;
mod figures;
mod frames;
mod method;
mod openqmc;
mod pbrt;
mod picture;
mod report;
mod scene;
mod split;
mod sweep;
mod trace;

use std::process::ExitCode;

use strata_lab::io;

/// The optional studies beside the sweep: `--frames` and `--adaptive`, each a table.
fn studies(
    args: &args::Args,
    scene: &scene::Scene,
    sequences: &[(String, method::Method)],
    reference: &[glam::Vec3],
    emitters: &split::Emitters,
) -> Result<(Option<String>, Option<String>), common::CliError> {
    let (f, tile) = (args.frames, args.frame_tile);
    let frames = (f > 0)
        .then(|| frames::table(args, scene, sequences, reference, emitters, f, tile))
        .transpose()?;
    let adaptive = (args.adaptive)
        .map(|m| adaptive::table(args, scene, sequences, reference, emitters, m))
        .transpose()?;
    Ok((frames, adaptive))
}

/// Renders the reference, every sequence at every count over the seeds, then writes the
/// pictures, `render.csv` and the tables (see `--help`).
fn main() -> ExitCode {
    common::run("render", || {
        let Some(args) = args::parse()? else {
            return Ok(());
        };
        let sequences = sweep::sequences(&args)?;
        let mut scene = scene::build(args.scene);
        scene.layout = args.layout;
        let ref_spp = sweep::reference_spp(&args);
        let reference = sweep::reference(&args, &scene, ref_spp)?;
        let emitters = split::emitters(&args, &scene, &reference)?;
        let rows = sweep::rows(&args, &scene, &sequences, &reference, &emitters)?;

        figures::write_compare(&args, &rows, &reference, ref_spp)?;
        let (csv, full) = report::results(&rows);
        common::out(&full)?;
        io::write_text(args.out.join("render.csv"), &csv)?;
        figures::write_blue_noise(&args, &rows, false)?;
        figures::write_blue_noise(&args, &rows, true)?;
        let split = split::interaction_table(&rows, &emitters.names);
        if let Some(t) = &split {
            outln!("\n{t}")?;
        }

        let (frames, adaptive) = studies(&args, &scene, &sequences, &reference, &emitters)?;
        for t in [&frames, &adaptive].into_iter().flatten() {
            outln!("\n{t}")?;
        }
        let ratios = report::ratios(&rows);
        if let Some(t) = &ratios {
            outln!("\n{t}")?;
        }
        let (table, plot) = report::convergence(&args, &sequences, &rows);
        outln!("\n{table}")?;
        let trade = report::write_trade(&args, &sequences, &rows)?;
        outln!("{trade}")?;
        if let Some(path) = &args.markdown {
            let tables = report::Tables {
                table: &table,
                full: &full,
                trade: &trade,
                split: split.as_deref(),
                frames: frames.as_deref(),
                adaptive: adaptive.as_deref(),
                ratios: ratios.as_deref(),
                masked: emitters.keep.len() - emitters.kept,
            };
            report::write_markdown(path, &args, ref_spp, &tables)?;
        }
        io::write_png(args.out.join("convergence.png"), &plot.render(720, 480))?;
        eprintln!("wrote {} renders into {}", rows.len(), args.out.display());
        args::report_memory(&args);
        Ok(())
    })
}
