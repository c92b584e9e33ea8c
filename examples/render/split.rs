//! The figures beyond the whole image: which pixels see an emitter (left out of the masked
//! figures), and the split of the error into its one-draw and interaction parts.

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use strata::pixel::{DimensionLayout, PixelSampler, Sequence};

use crate::method::{ByCopy, Method, PixelDraws, Stateless, Visit, with_sampler};
use strata::pixel::frames::SeedPermutation;
use strata_lab::io::{self, Rgb};
use strata_lab::spectrum::ErrorImage;

use crate::args::Args;
use crate::common::CliError;
use crate::picture::{luminance, to_canvas};
use crate::scene::{Material, Scene, SceneKind};
use crate::trace::{Draws, MAX_BOUNCES, radiance};

/// The pixels kept in the masked figures, and the draws the interaction split integrates out
/// one by one.
pub struct Emitters {
    /// Per pixel, row-major: `true` where the pixel does not see an emitter.
    pub keep: Vec<bool>,
    /// How many pixels are kept.
    pub kept: usize,
    /// The first dimensions of the draws of the camera and the first bounce: the film, the
    /// lens (and the shutter time of the spheres), the lobe, the light choice, the light point.
    pub draws: Vec<u32>,
    /// Their names, in that order.
    pub names: Vec<&'static str>,
}

/// A row's figures over the pixels that do not see an emitter: the RMSE of linear radiance
/// (or of a part's luminance error), the blurred RMSEs and the low-band share of the luminance
/// error image ([`spectrum::error_image_masked`]), over the seeds as the unmasked ones.
#[derive(Default)]
pub struct Masked {
    pub rmse: f64,
    pub blur1: f64,
    pub blur2: f64,
    pub lowband: f64,
    /// Each seed's low-band share, in the order of the seeds (for the standard error of a
    /// ratio, `analysis::fit::ratio_of_means`).
    pub lowbands: Vec<f64>,
}

impl Masked {
    /// Adds one seed's error image `m` (of `seeds`): squares of the RMSEs, the low band.
    pub fn add(&mut self, m: &ErrorImage, seeds: f64) {
        self.blur1 += m.blur1_rmse.powi(2) / seeds;
        self.blur2 += m.blur2_rmse.powi(2) / seeds;
        self.lowband += m.lowband / seeds;
        self.lowbands.push(m.lowband);
    }

    /// The means over the seeds: the roots of the mean squares.
    pub fn finish(&self) -> Masked {
        Masked {
            rmse: self.rmse.sqrt(),
            blur1: self.blur1.sqrt(),
            blur2: self.blur2.sqrt(),
            lowband: self.lowband,
            lowbands: self.lowbands.clone(),
        }
    }
}

/// The emitter mask of the scene ([`emitter_mask`]), reported on stderr and drawn into
/// `emitter-mask.png` (the reference with those pixels in magenta), and the split's draws.
pub fn emitters(args: &Args, scene: &Scene, reference: &[Vec3]) -> Result<Emitters, CliError> {
    let size = args.size;
    let keep = emitter_mask(scene, size);
    let kept = keep.iter().filter(|&&k| k).count();
    let mut canvas = to_canvas(reference, size);
    for (i, _) in keep.iter().enumerate().filter(|(_, k)| !**k) {
        let (x, y) = ((i as u32 % size.0) as i64, (i as u32 / size.0) as i64);
        canvas.set(x, y, Rgb::new(255, 0, 255));
    }
    io::write_png(args.out.join("emitter-mask.png"), &canvas)?;
    eprintln!(
        "{} of {} pixels see an emitter (left out of the masked figures)",
        keep.len() - kept,
        keep.len()
    );
    let time = args.scene == SceneKind::Spheres;
    let draws = scene.layout.split_draws(time);
    let mut names = vec!["film", "lens"];
    if time {
        names.push("time");
    }
    names.extend(["lobe", "light choice", "light point"]);
    debug_assert_eq!(names.len(), draws.len());
    Ok(Emitters {
        keep,
        kept,
        draws,
        names,
    })
}

/// Which pixels do not see an emitter (`true`: kept in the masked figures). A pixel sees one
/// when any of 144 camera rays through it (4 x 4 film positions, 3 x 3 lens positions, three
/// times of the shutter) meets a light's emitting side, directly or along a chain of mirror
/// lobes: its error is then the emitter's edge and the light-or-mirror choice, not the
/// sampler's distribution of the lighting integral.
fn emitter_mask(scene: &Scene, size: (u32, u32)) -> Vec<bool> {
    (0..size.0 * size.1)
        .into_par_iter()
        .map(|i| !(0..144u32).any(|k| sees_emitter(scene, size, [i % size.0, i / size.0], k)))
        .collect()
}

/// Whether camera ray `k` of [`emitter_mask`] through `pixel` meets an emitter.
fn sees_emitter(scene: &Scene, size: (u32, u32), pixel: [u32; 2], k: u32) -> bool {
    let film = Vec2::new((k % 4) as f32 + 0.5, (k / 4 % 4) as f32 + 0.5) / 4.0;
    let lens = Vec2::new((k / 16 % 3) as f32 + 0.5, (k / 48) as f32 + 0.5) / 3.0;
    let time = if scene.kind == SceneKind::Spheres {
        ((k % 3) as f32 + 0.5) / 3.0
    } else {
        0.0
    };
    let (mut origin, mut dir) = scene.camera.ray(pixel[0], pixel[1], size, film, lens);
    for _ in 0..MAX_BOUNCES {
        let Some(hit) = scene.intersect(origin, dir, time) else {
            return false;
        };
        match hit.material {
            Material::Light { .. } => return hit.normal.dot(dir) < 0.0,
            Material::Surface { mirror, .. } if mirror > 0.0 => {
                let n = if hit.normal.dot(dir) < 0.0 {
                    hit.normal
                } else {
                    -hit.normal
                };
                dir -= 2.0 * dir.dot(n) * n;
                origin = hit.point + n * 1e-4;
            }
            // a glossy lobe's highlight is a lighting integral: not masked
            Material::Surface { .. } | Material::Glossy { .. } => return false,
        }
    }
    false
}

/// A path's draws with one draw (the one starting at dimension `keep`) from the sampler under
/// test, at sample `index`, and every other draw from an independent Owen-scrambled Sobol'
/// sampler at sample `inner`: averaged over a block of `inner` samples, the path's radiance
/// with that draw fixed and the others integrated out (the draw's main effect).
pub struct Mixed<'a> {
    tested: &'a dyn Stateless,
    others: &'a PixelSampler,
    pixel: [u32; 2],
    index: u64,
    inner: u64,
    keep: u32,
    dim: u32,
}

impl Draws for Mixed<'_> {
    fn get_pixel_2d(&mut self) -> Vec2 {
        self.get_2d()
    }
    fn get_2d(&mut self) -> Vec2 {
        let d = self.dim;
        self.dim += 2;
        if d == self.keep {
            self.tested.sample_2d(self.pixel, self.index, d)
        } else {
            self.others.sample_2d(self.pixel, self.inner, d).into()
        }
    }
    fn get_1d(&mut self) -> f32 {
        let d = self.dim;
        self.dim += 1;
        if d == self.keep {
            self.tested.sample_1d(self.pixel, self.index, d)
        } else {
            self.others.sample_1d(self.pixel, self.inner, d)
        }
    }
    fn start_bounce(&mut self, k: u32) {
        self.dim = DimensionLayout::default().bounce_start(k);
    }
    fn dimension(&self) -> u32 {
        self.dim
    }
    fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }
}

/// The inner samples per draw and pixel sample of the interaction split (a power of two: each
/// block a net of the inner Sobol' sampler).
const INNER: u64 = 64;

/// The main effects of `draws` (their first dimensions) in a render's luminance error, one
/// image (row-major) per draw: per pixel, the mean over its samples of the draw's
/// `E[L | that draw] - I`, with the expectation over the other draws estimated by [`INNER`]
/// Sobol' points and `I` the reference. Their sum is the one-draw part of the error; the rest
/// (the render's minus the sum) is the draws' interactions (and, for pixels whose camera ray
/// meets the mirror, the later bounces' draws).
pub fn one_draw_errors(
    scene: &Scene,
    tested: &dyn Stateless,
    spp: u32,
    size: (u32, u32),
    reference: &[Vec3],
    draws: &[u32],
) -> Vec<Vec<f64>> {
    let others = PixelSampler::new(Sequence::sobol(), 1, strata::Seed(0x1a7e_5eed))
        .expect("sobol takes any count");
    let per_pixel: Vec<Vec<f64>> = (0..size.0 * size.1)
        .into_par_iter()
        .map(|p| {
            let pixel = [p % size.0, p / size.0];
            let truth = luminance(reference[p as usize]) as f64;
            let mut sums = vec![0.0; draws.len()];
            for i in 0..spp as u64 {
                for (sum, &keep) in sums.iter_mut().zip(draws) {
                    let mut mean = 0.0;
                    for m in 0..INNER {
                        let mut s = Mixed {
                            tested,
                            others: &others,
                            pixel,
                            index: i,
                            inner: i * INNER + m,
                            keep,
                            dim: 0,
                        };
                        mean += luminance(radiance(pixel[0], pixel[1], size, &mut s, scene)) as f64;
                    }
                    *sum += mean / INNER as f64 - truth;
                }
            }
            sums.iter().map(|s| s / spp as f64).collect()
        })
        .collect();
    (0..draws.len())
        .map(|d| per_pixel.iter().map(|p| p[d]).collect())
        .collect()
}

/// The one-draw part of the error: the sum of the draws' main effects, pixel by pixel.
pub fn one_draw_sum(per_draw: &[Vec<f64>]) -> Vec<f64> {
    let n = per_draw.first().map_or(0, Vec::len);
    (0..n)
        .map(|p| per_draw.iter().map(|d| d[p]).sum())
        .collect()
}

/// With `--interactions`: the one-draw and the interaction parts of the error at the smallest
/// count, emitters masked (Markdown), or `None` when no row has them.
pub fn interaction_table(rows: &[crate::sweep::Row], names: &[&str]) -> Option<String> {
    let mut t = String::from(
        "The error split at the smallest count, without the pixels that see an emitter: the \
         one-draw part (per pixel, the sum over the camera's and the first bounce's draws of \
         each draw's main effect, the other draws integrated out by 64 Owen-scrambled Sobol' \
         points) and the interaction part (the rest); RMSE, RMSE after a blur of sigma 2, \
         low-band share.\n\n| sampler | spp | one-draw rmse | blur2_rmse | lowband | \
         interaction rmse | blur2_rmse | lowband |\n|---|---|---|---|---|---|---|---|\n",
    );
    let mut any = false;
    for r in rows {
        if let Some([one, rest]) = &r.split {
            any = true;
            t.push_str(&format!(
                "| {} | {} | {:.5} | {:.5} | {:.4} | {:.5} | {:.5} | {:.4} |\n",
                r.name,
                r.spp,
                one.rmse,
                one.blur2,
                one.lowband,
                rest.rmse,
                rest.blur2,
                rest.lowband
            ));
        }
    }
    t.push_str(&format!(
        "\nEach draw's main effect alone (the one-draw part is their sum): the low-band share of \
         its error image, without the pixels that see an emitter, over the seeds (a draw that \
         changes nothing in this scene has the error of the others integrated out: the same \
         figure for every sampler).\n\n| sampler | spp | {} |\n|---|---|{}\n",
        names.join(" | "),
        "---|".repeat(names.len())
    ));
    for r in rows.iter().filter(|r| r.split.is_some()) {
        let cells: Vec<String> = r
            .per_draw
            .iter()
            .map(|m| format!("{:.4}", m.lowband))
            .collect();
        t.push_str(&format!(
            "| {} | {} | {} |\n",
            r.name,
            r.spp,
            cells.join(" | ")
        ));
    }
    any.then_some(t)
}

/// A sampler whose pixels take the draws of the pixels a [`SeedPermutation`] gives them.
struct Remapped<'a> {
    inner: Box<dyn Stateless + 'a>,
    seeds: Option<&'a SeedPermutation>,
}

impl Stateless for Remapped<'_> {
    fn sample_1d(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32 {
        let from = self.seeds.map_or(pixel, |p| p.source(pixel));
        self.inner.sample_1d(from, index, dim)
    }
    fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec2 {
        let from = self.seeds.map_or(pixel, |p| p.source(pixel));
        self.inner.sample_2d(from, index, dim)
    }
}

/// [`one_draw_errors`] of the sampler of `method` at `spp` for `seed` (the crate's sequences
/// with `--padding`), each pixel taking the draws of the pixel `seeds` gives it (its own
/// without), as `render` draws them.
#[allow(clippy::too_many_arguments)]
pub fn one_draw_with(
    args: &Args,
    scene: &Scene,
    method: &Method,
    spp: u32,
    seed: u64,
    reference: &[Vec3],
    draws: &[u32],
    seeds: Option<&SeedPermutation>,
) -> Result<Vec<Vec<f64>>, CliError> {
    /// The one-draw errors with whichever sampler the method is.
    struct OneDraw<'a> {
        scene: &'a Scene,
        spp: u32,
        size: (u32, u32),
        reference: &'a [Vec3],
        draws: &'a [u32],
        seeds: Option<&'a SeedPermutation>,
    }
    impl Visit<Vec<Vec<f64>>> for OneDraw<'_> {
        fn visit<S: PixelDraws + 'static>(self, s: S) -> Vec<Vec<f64>> {
            // the crate's sampler has stateless draws of its own; the others are copied
            let inner: Box<dyn Stateless> =
                match (&s as &dyn std::any::Any).downcast_ref::<strata::PixelSampler>() {
                    Some(p) => Box::new(p.clone()),
                    None => Box::new(ByCopy(s)),
                };
            let tested = Remapped {
                inner,
                seeds: self.seeds,
            };
            one_draw_errors(
                self.scene,
                &tested,
                self.spp,
                self.size,
                self.reference,
                self.draws,
            )
        }
    }
    let go = OneDraw {
        scene,
        spp,
        size: args.size,
        reference,
        draws,
        seeds,
    };
    Ok(with_sampler(
        method,
        spp,
        args.size,
        seed,
        args.padding,
        go,
    )?)
}
