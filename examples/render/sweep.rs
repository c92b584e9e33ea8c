//! The sweep: the sequences named on the command line, the converged reference, and each
//! sequence rendered at each count over the seeds and measured against the reference, with the
//! pictures of each render.

use std::time::Instant;

use glam::Vec3;
use strata::pixel::{Padding, Sequence};
use strata_lab::io;
use strata_lab::spectrum::{self, ErrorImage};

use crate::args::Args;
use crate::common::CliError;
use crate::method::Method;
use crate::picture::{
    error_canvas, error_image_canvas, luminance_errors, relative_error, to_canvas,
};
use crate::scene::Scene;
use crate::split::{Emitters, Masked};
use crate::trace::render;

/// One sequence at one count: the numbers of `render.csv` and the pictures' images.
pub struct Row {
    pub name: String,
    pub spp: u32,
    pub image: Vec<Vec3>,
    pub rmse: f64,
    pub rel_rmse: f64,
    pub ms: f64,
    pub blur1: f64,
    pub blur2: f64,
    pub lowband: f64,
    /// The error image's measures for the first seed (for the pictures), and its pixels.
    pub errors: ErrorImage,
    pub error_pixels: Vec<f64>,
    /// The figures without the pixels that see an emitter ([`Emitters`]).
    pub masked: Masked,
    /// The same error image without them (their errors at zero), when any pixel is kept.
    pub masked_errors: Option<(ErrorImage, Vec<f64>)>,
    /// With `--interactions`, at the smallest count: the one-draw and the interaction parts of
    /// the error, without the pixels that see an emitter, over the seeds.
    pub split: Option<[Masked; 2]>,
    /// With them, each draw's main effect ([`Emitters::draws`]), the same way.
    pub per_draw: Vec<Masked>,
}

/// The samplers of `--samplers` at the image size (the crate's sequences, the references,
/// the experiments), each checked against every count.
pub fn sequences(args: &Args) -> Result<Vec<(String, Method)>, CliError> {
    let sequences: Vec<(String, Method)> = args
        .samplers
        .iter()
        .map(|n| Ok((n.clone(), Method::by_name(n, args.size)?)))
        .collect::<Result<_, CliError>>()?;
    // two names of one sampler (`zjoint` and `zjoint-8`, `zjoint+permute` and
    // `zjoint-8+permute`) would render it twice
    for (k, (name, method)) in sequences.iter().enumerate() {
        if let Some((first, _)) = sequences[..k].iter().find(|(_, m)| m == method) {
            return Err(crate::common::cli_error(format!(
                "--samplers names one sampler twice: '{name}' is '{first}'; allowed: each \
                 sampler once"
            )));
        }
    }
    for (_, method) in &sequences {
        for &spp in &args.spp {
            // refused before any work: the sampler checks its count
            method.check_spp(spp)?;
        }
    }
    Ok(sequences)
}

/// The samples per pixel of the reference: `--reference-spp`, or 16 times the largest count
/// within 1024 to 65536.
pub fn reference_spp(args: &Args) -> u32 {
    let largest = *args.spp.last().expect("at least one count");
    args.reference_spp
        .unwrap_or((largest * 16).clamp(1024, 65536))
}

/// Renders the reference (scrambled Sobol' at `ref_spp`, its own seed, nested padding) with
/// progress lines, and writes `reference.png`.
pub fn reference(args: &Args, scene: &Scene, ref_spp: u32) -> Result<Vec<Vec3>, CliError> {
    let size = args.size;
    eprintln!(
        "reference: sobol at {ref_spp} spp, {}x{} ...",
        size.0, size.1
    );
    let start = Instant::now();
    let reference = render(
        scene,
        &Method::Crate(Sequence::sobol()),
        ref_spp,
        size,
        0x5eed_0000_0001,
        Some("reference"),
        Padding::Nested,
    )?;
    eprintln!("reference: {:.1} s", start.elapsed().as_secs_f64());
    io::write_png(args.out.join("reference.png"), &to_canvas(&reference, size))?;
    Ok(reference)
}

/// Every sequence at every count, measured and with its pictures written: one row each, in
/// the order of the sequences, then of the counts.
pub fn rows(
    args: &Args,
    scene: &Scene,
    sequences: &[(String, Method)],
    reference: &[Vec3],
    emitters: &Emitters,
) -> Result<Vec<Row>, CliError> {
    let mut rows = Vec::new();
    for (name, seq) in sequences {
        for &spp in &args.spp {
            let row = measure(args, scene, name, seq, spp, reference, emitters)?;
            write_pictures(args, &row, reference)?;
            rows.push(row);
        }
    }
    Ok(rows)
}

/// Renders `seq` at `spp` with each of the seeds and measures the images against the
/// reference: the root of the mean squared error (absolute and relative) over all seeds, the
/// mean render time, the error image's measures, all of them also without the pixels that
/// see an emitter ([`masked`]); the pictures show the first seed.
fn measure(
    args: &Args,
    scene: &Scene,
    name: &str,
    seq: &Method,
    spp: u32,
    reference: &[Vec3],
    emitters: &Emitters,
) -> Result<Row, CliError> {
    let size = args.size;
    let (mut sums, mut ms, mut first, mut errors) = (Sums::default(), 0.0f64, None, None);
    let mut m = MaskedSums {
        masked: Masked::default(),
        errors: None,
        split: (args.interactions && spp == args.spp[0] && emitters.kept > 0)
            .then(<[Masked; 2]>::default),
        per_draw: Vec::new(),
    };
    for k in 0..args.seeds as u64 {
        let start = Instant::now();
        let image = render(
            scene,
            seq,
            spp,
            size,
            args.seed.wrapping_add(k),
            None,
            args.padding,
        )?;
        ms += start.elapsed().as_secs_f64() * 1e3 / args.seeds as f64;
        let lum = luminance_errors(&image, reference);
        let e = spectrum::error_image(&lum, size.0, size.1)?;
        sums.add(&image, reference, &e, args.seeds);
        if emitters.kept > 0 {
            let s = Seed {
                seq,
                spp,
                seed: args.seed.wrapping_add(k),
                image: &image,
                lum: &lum,
            };
            masked(args, scene, reference, emitters, &s, &mut m)?;
        }
        errors.get_or_insert(e);
        first.get_or_insert(image);
    }
    let image = first.expect("at least one seed");
    eprintln!("{name} at {spp} spp: {ms:.0} ms");
    let errors = errors.expect("at least one seed");
    let e = luminance_errors(&image, reference);
    Ok(Row {
        name: name.to_string(),
        spp,
        image,
        rmse: sums.mse.sqrt(),
        rel_rmse: sums.rel.sqrt(),
        ms,
        blur1: sums.blur1.sqrt(),
        blur2: sums.blur2.sqrt(),
        lowband: sums.lowband,
        errors,
        error_pixels: e,
        masked: m.masked.finish(),
        masked_errors: m.errors,
        split: m.split.map(|parts| parts.map(|p| p.finish())),
        per_draw: m.per_draw.iter().map(Masked::finish).collect(),
    })
}

/// The unmasked figures of a row, summed over its seeds: mean squared (and relative squared)
/// error, the squared RMSE after each blur and the low-band share, each a mean over the seeds.
#[derive(Default)]
struct Sums {
    mse: f64,
    rel: f64,
    blur1: f64,
    blur2: f64,
    lowband: f64,
}

impl Sums {
    /// Adds one seed's image (of `seeds`), with its error image's measures `e`.
    fn add(&mut self, image: &[Vec3], reference: &[Vec3], e: &spectrum::ErrorImage, seeds: u32) {
        let n = image.len() as f64 * seeds as f64;
        let (image_mse, image_rel) = squared_errors(image, reference, n);
        self.mse += image_mse;
        self.rel += image_rel;
        let seeds = seeds as f64;
        self.blur1 += e.blur1_rmse.powi(2) / seeds;
        self.blur2 += e.blur2_rmse.powi(2) / seeds;
        self.lowband += e.lowband / seeds;
    }
}

/// One seed's render of a row: its sequence and count, its seed, the image and its
/// luminance error.
struct Seed<'a> {
    seq: &'a Method,
    spp: u32,
    seed: u64,
    image: &'a [Vec3],
    lum: &'a [f64],
}

/// A row's masked figures as the seeds add to them.
struct MaskedSums {
    masked: Masked,
    errors: Option<(ErrorImage, Vec<f64>)>,
    split: Option<[Masked; 2]>,
    per_draw: Vec<Masked>,
}

/// Adds one seed's figures without the pixels that see an emitter: the RMSE of linear
/// radiance over the kept pixels, the error image's measures (kept for the pictures at the
/// first seed) and, when asked for, the one-draw and interaction parts.
fn masked(
    args: &Args,
    scene: &Scene,
    reference: &[Vec3],
    emitters: &Emitters,
    s: &Seed,
    m: &mut MaskedSums,
) -> Result<(), CliError> {
    let (size, seeds, keep) = (args.size, args.seeds as f64, &emitters.keep);
    let e = spectrum::error_image_masked(s.lum, keep, size.0, size.1)?;
    m.masked.rmse += s
        .image
        .iter()
        .zip(reference)
        .zip(keep)
        .filter(|(_, k)| **k)
        .map(|((a, r), _)| (*a - *r).length_squared() as f64 / 3.0)
        .sum::<f64>()
        / (emitters.kept as f64 * seeds);
    m.masked.add(&e, seeds);
    if let Some(parts) = &mut m.split {
        let per_draw = crate::split::one_draw_with(
            args,
            scene,
            s.seq,
            s.spp,
            s.seed,
            reference,
            &emitters.draws,
            None,
        )?;
        m.per_draw.resize_with(per_draw.len(), Masked::default);
        for (part, errors) in m.per_draw.iter_mut().zip(&per_draw) {
            let p = spectrum::error_image_masked(errors, keep, size.0, size.1)?;
            part.rmse += p.rmse.powi(2) / seeds;
            part.add(&p, seeds);
        }
        let one = crate::split::one_draw_sum(&per_draw);
        let rest: Vec<f64> = s.lum.iter().zip(&one).map(|(e, o)| e - o).collect();
        for (part, errors) in parts.iter_mut().zip([&one, &rest]) {
            let p = spectrum::error_image_masked(errors, keep, size.0, size.1)?;
            part.rmse += p.rmse.powi(2) / seeds;
            part.add(&p, seeds);
        }
    }
    if m.errors.is_none() {
        let dropped = s
            .lum
            .iter()
            .zip(keep)
            .map(|(e, k)| if *k { *e } else { 0.0 })
            .collect();
        m.errors = Some((e, dropped));
    }
    Ok(())
}

/// The squared errors of `image` against `reference`, summed over the pixels and divided by
/// `n`: of linear radiance (the mean over the channels) and of the relative error.
fn squared_errors(image: &[Vec3], reference: &[Vec3], n: f64) -> (f64, f64) {
    let mse = image
        .iter()
        .zip(reference)
        .map(|(a, r)| (*a - *r).length_squared() as f64 / 3.0)
        .sum::<f64>()
        / n;
    let rel = image
        .iter()
        .zip(reference)
        .map(|(a, r)| (relative_error(*a, *r) as f64).powi(2))
        .sum::<f64>()
        / n;
    (mse, rel)
}

/// The pictures of one render: `NAME-SPP.png`, `NAME-SPP-error-spectrum.png` (the signed error
/// image beside its periodogram), and at the largest count `NAME.png` and `NAME-error.png`.
fn write_pictures(args: &Args, row: &Row, reference: &[Vec3]) -> Result<(), CliError> {
    let (name, spp, size) = (&row.name, row.spp, args.size);
    let largest = *args.spp.last().expect("at least one count");
    io::write_png(
        args.out.join(format!("{name}-{spp}.png")),
        &to_canvas(&row.image, size),
    )?;
    if spp == largest {
        io::write_png(
            args.out.join(format!("{name}.png")),
            &to_canvas(&row.image, size),
        )?;
        io::write_png(
            args.out.join(format!("{name}-error.png")),
            &error_canvas(&row.image, reference, size),
        )?;
    }
    let scale = 4.0 * row.errors.rmse.max(1e-9);
    io::write_png(
        args.out.join(format!("{name}-{spp}-error-spectrum.png")),
        &error_image_canvas(&row.errors, &row.error_pixels, scale),
    )?;
    Ok(())
}
