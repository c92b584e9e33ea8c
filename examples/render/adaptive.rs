//! `--adaptive MAX`: an image whose pixels stop at counts of their own, as an adaptive
//! sampler's or a viewport's do, measured per sampler over the seeds: a progressive sequence
//! keeps its promises at every count, a Z-ordered one is told `MAX` and cut short.

use glam::Vec3;
use strata_lab::analysis::study;
use strata_lab::io;
use strata_lab::spectrum;

use crate::args::Args;
use crate::common::CliError;
use crate::method::Method;
use crate::picture::luminance_errors;
use crate::scene::Scene;
use crate::split::{Emitters, Masked};
use crate::trace::{Counts, render_adaptive};

/// The stream of the stopping counts' keys (per seed: every sampler stops its pixels alike).
const STOPS: u64 = 0xada9_0001;

/// The adaptive images of every sampler: the table (Markdown, on stdout and in `--markdown`);
/// `adaptive.csv` written into the output directory.
pub fn table(
    args: &Args,
    scene: &Scene,
    sequences: &[(String, Method)],
    reference: &[Vec3],
    emitters: &Emitters,
    max: u32,
) -> Result<String, CliError> {
    for (_, method) in sequences {
        method.check_spp(max)?;
    }
    let (size, seeds) = (args.size, args.seeds as f64);
    let keep: Vec<bool> = if emitters.kept > 0 {
        emitters.keep.clone()
    } else {
        vec![true; emitters.keep.len()]
    };
    let mut rows: Vec<(String, Masked, f64, f64)> = Vec::new();
    for (name, method) in sequences {
        let (mut m, mut lowband, mut normalized) = (Masked::default(), 0.0, 0.0);
        for k in 0..args.seeds as u64 {
            let seed = args.seed.wrapping_add(k);
            let counts = Counts::Adaptive {
                max,
                key: strata::hash::stream_seed(STOPS, seed),
            };
            let image = render_adaptive(scene, method, counts, size, seed, args.padding)?;
            let lum = luminance_errors(&image, reference);
            lowband += spectrum::error_image(&lum, size.0, size.1)?.lowband / seeds;
            let e = spectrum::error_image_masked(&lum, &keep, size.0, size.1)?;
            m.rmse += e.rmse.powi(2) / seeds;
            m.add(&e, seeds);
            // each pixel's error times the root of its count: the arrangement alone, without
            // the low counts' larger errors dominating the spectrum
            let scaled: Vec<f64> = (0..lum.len() as u32)
                .map(|i| {
                    let n = counts.at(i % size.0, i / size.0) as f64;
                    lum[i as usize] * n.sqrt()
                })
                .collect();
            normalized +=
                spectrum::error_image_masked(&scaled, &keep, size.0, size.1)?.lowband / seeds;
        }
        eprintln!("{name} adaptive (1 to {max} spp)");
        rows.push((name.clone(), m.finish(), lowband, normalized));
    }
    let sobol = rows
        .iter()
        .find(|r| r.0 == "sobol")
        .map(|r| (r.1.lowband, r.3, r.1.lowbands.clone()));
    let mut csv = String::from(
        "sampler,max_spp,lowband,masked_rmse,masked_blur2_rmse,masked_lowband,\
         masked_scaled_lowband\n",
    );
    let mut out = format!(
        "Adaptive images: each pixel stops at its own count, from 1 to {max}, varying smoothly \
         over the image (a random field over cells of {cell} pixels, hashed from the seed: the \
         same counts for every sampler; a Z-ordered sequence is told {max}), {} seeds; without \
         the pixels that see an emitter, the luminance error's RMSE, RMSE after a blur of sigma \
         2 and low-band share, the low-band share of the error scaled by the root of each \
         pixel's count (the arrangement alone, the low counts' larger errors not dominating), \
         and the ratios of the two shares to `sobol`'s with the same counts (below 1: \
         bluer), the first with its standard error over the seeds (s.e.). {share}\n\n\
         | sampler | masked rmse | masked blur2_rmse | masked lowband | scaled lowband | ratio to \
         sobol | scaled ratio to sobol | s.e. |\n\
         |---|---|---|---|---|---|---|---|\n",
        args.seeds,
        cell = crate::trace::COUNT_CELL,
        share = count_shares(args, max),
    );
    for (name, m, lowband, scaled) in &rows {
        let ratio = |a: f64, b: f64| format!("{:.3}", a / b);
        let (r, rs, se) =
            sobol
                .as_ref()
                .map_or(("-".into(), "-".into(), "-".into()), |(s, ss, lowbands)| {
                    let se = study::ratio_of_means(&m.lowbands, lowbands)
                        .filter(|_| name != "sobol")
                        .map_or("-".to_string(), |(_, e)| format!("{e:.3}"));
                    (ratio(m.lowband, *s), ratio(*scaled, *ss), se)
                });
        out.push_str(&format!(
            "| {name} | {:.5} | {:.5} | {:.4} | {scaled:.4} | {r} | {rs} | {se} |\n",
            m.rmse, m.blur2, m.lowband
        ));
        csv.push_str(&format!(
            "{name},{max},{lowband},{},{},{},{scaled}\n",
            m.rmse, m.blur2, m.lowband
        ));
    }
    io::write_text(args.out.join("adaptive.csv"), &csv)?;
    Ok(out)
}

/// Where the adaptive image's error is: over the seeds' count fields, the share of the pixels,
/// and of the error's power if a pixel's error variance is `1 / n` at count `n`, at counts up
/// to 4, 8, 16 and 32 (a sentence for the table's caption).
fn count_shares(args: &Args, max: u32) -> String {
    let (w, h) = args.size;
    let bounds = [4u32, 8, 16, 32];
    let (mut pixels, mut power) = ([0f64; 4], [0f64; 4]);
    let (mut all_pixels, mut all_power) = (0f64, 0f64);
    for k in 0..args.seeds as u64 {
        let counts = Counts::Adaptive {
            max,
            key: strata::hash::stream_seed(STOPS, args.seed.wrapping_add(k)),
        };
        for y in 0..h {
            for x in 0..w {
                let n = counts.at(x, y);
                all_pixels += 1.0;
                all_power += 1.0 / n as f64;
                for (j, &b) in bounds.iter().enumerate() {
                    if n <= b {
                        pixels[j] += 1.0;
                        power[j] += 1.0 / n as f64;
                    }
                }
            }
        }
    }
    let list: Vec<String> = bounds
        .iter()
        .enumerate()
        .filter(|(_, b)| **b < max)
        .map(|(j, b)| {
            format!(
                "{:.1}% and {:.1}% up to {b}",
                100.0 * pixels[j] / all_pixels,
                100.0 * power[j] / all_power
            )
        })
        .collect();
    if list.is_empty() {
        return String::new();
    }
    format!(
        "The counts' shares of the pixels and of the error's power (a pixel's error variance \
         taken as 1/n at count n): {}.",
        list.join(", ")
    )
}
