//! `--frames F`: a sequence of frames of a static camera with Heitz and Belcour's a-posteriori
//! permutation of pixels' draws ([`strata::pixel::frames`]): frame 1 as any render, then each
//! frame takes, in every tile, the draws of the previous frame's pixels in the order that
//! makes its error follow a blue-noise mask. Measured over frames 2 to F (the first excluded)
//! and every seed, beside frame 1 (the plain render, the same draws unpermuted).

use glam::Vec3;
use strata::pixel::frames::{BlueNoiseMask, SeedPermutation};
use strata_lab::spectrum;

use crate::args::Args;
use crate::common::CliError;
use crate::method::Method;
use crate::picture::luminance_errors;
use crate::scene::Scene;
use crate::split::Emitters;
use crate::trace::render_remapped;

/// One sequence at one count: the plain frame's and the permuted frames' figures, each a mean
/// over the seeds (and frames): RMSE of luminance and low-band share, unmasked and masked.
struct Figures {
    plain: [f64; 4],
    permuted: [f64; 4],
    /// With `--interactions`, at the smallest count: the masked low-band share of the
    /// interaction part of the plain frame's and of the permuted frames' error.
    interaction: Option<[f64; 2]>,
}

/// The luminance of an image, per pixel (the scalar the permutation ranks).
fn luminance(image: &[Vec3]) -> Vec<f32> {
    image
        .iter()
        .map(|c| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z)
        .collect()
}

/// The frames table: per sequence and count, the plain render and the permuted frames 2 to
/// `frames`: RMSE of the luminance error and its low-band share, over all pixels and without
/// those that see an emitter.
pub fn table(
    args: &Args,
    scene: &Scene,
    sequences: &[(String, Method)],
    reference: &[Vec3],
    emitters: &Emitters,
    frames: u32,
    tile: u32,
) -> Result<String, CliError> {
    // the renderer crate's built-in mask, tiled over the image
    let mask = BlueNoiseMask::builtin();
    let side = mask.side();
    let mut out = format!(
        "Frames of a static camera with the draws of pixels permuted between frames within \
         tiles of {tile}x{tile} so that the error follows a {side}x{side} blue-noise \
         mask (Heitz and Belcour 2019; `strata::pixel::frames`), {frames} frames, frame 1 \
         excluded, {} seeds; 'plain': frame 1 (no permutation). RMSE of the luminance error, \
         and the share of its power below 1/8 cycle per pixel (white: about 0.05); 'masked': \
         without the pixels that see an emitter; 'interaction': with `--interactions`, at the \
         smallest count, the masked low-band share of the error's interaction part (the error \
         less its one-draw part, as in the render's split, each pixel with the draws it took).\n\n\
         | sampler | spp | plain rmse | plain lowband | frames rmse | frames lowband | \
         masked plain rmse | masked plain lowband | masked frames rmse | masked frames lowband | \
         plain interaction lowband | frames interaction lowband |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
        args.seeds
    );
    for (name, method) in sequences {
        for &spp in &args.spp {
            let f = measure(
                args, scene, method, spp, reference, emitters, frames, tile, &mask,
            )?;
            let cell = |v: f64| format!("{v:.5}");
            let share = |v: f64| format!("{v:.4}");
            out.push_str(&format!(
                "| {name} | {spp} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                cell(f.plain[0]),
                share(f.plain[1]),
                cell(f.permuted[0]),
                share(f.permuted[1]),
                cell(f.plain[2]),
                share(f.plain[3]),
                cell(f.permuted[2]),
                share(f.permuted[3]),
                f.interaction.map_or("-".into(), |i| share(i[0])),
                f.interaction.map_or("-".into(), |i| share(i[1])),
            ));
            eprintln!("frames: {name} at {spp} spp done");
        }
    }
    Ok(out)
}

/// The figures of one sequence at one count over the seeds.
#[allow(clippy::too_many_arguments)]
fn measure(
    args: &Args,
    scene: &Scene,
    method: &Method,
    spp: u32,
    reference: &[Vec3],
    emitters: &Emitters,
    frames: u32,
    tile: u32,
    mask: &BlueNoiseMask,
) -> Result<Figures, CliError> {
    let (w, h) = args.size;
    let mut plain = [0.0f64; 4];
    let mut permuted = [0.0f64; 4];
    let seeds = args.seeds as f64;
    let later = (frames - 1) as f64 * seeds;
    let split = args.interactions && spp == args.spp[0] && emitters.kept > 0;
    let mut interaction = [0.0f64; 2];
    for k in 0..args.seeds as u64 {
        let mut seeds_of = SeedPermutation::new(w, h, tile)?;
        for frame in 0..frames {
            let image = render_remapped(
                scene,
                method,
                spp,
                args.size,
                args.seed.wrapping_add(k),
                args.padding,
                Some(&seeds_of),
            )?;
            let lum = luminance_errors(&image, reference);
            let e = spectrum::error_image(&lum, w, h)?;
            let masked = (emitters.kept > 0)
                .then(|| spectrum::error_image_masked(&lum, &emitters.keep, w, h))
                .transpose()?;
            let figures = [
                e.rmse.powi(2),
                e.lowband,
                masked.as_ref().map_or(0.0, |m| m.rmse.powi(2)),
                masked.as_ref().map_or(0.0, |m| m.lowband),
            ];
            let (into, n) = if frame == 0 {
                (&mut plain, seeds)
            } else {
                (&mut permuted, later)
            };
            if split {
                let one = crate::split::one_draw_sum(&crate::split::one_draw_with(
                    args,
                    scene,
                    method,
                    spp,
                    args.seed.wrapping_add(k),
                    reference,
                    &emitters.draws,
                    Some(&seeds_of),
                )?);
                let rest: Vec<f64> = lum.iter().zip(&one).map(|(e, o)| e - o).collect();
                let part = spectrum::error_image_masked(&rest, &emitters.keep, w, h)?;
                interaction[(frame > 0) as usize] += part.lowband / n;
            }
            for (a, b) in into.iter_mut().zip(figures) {
                *a += b / n;
            }
            seeds_of.update(&luminance(&image), mask)?;
        }
    }
    for f in [&mut plain, &mut permuted] {
        f[0] = f[0].sqrt();
        f[2] = f[2].sqrt();
    }
    Ok(Figures {
        plain,
        permuted,
        interaction: split.then_some(interaction),
    })
}
