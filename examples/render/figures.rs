//! The comparison pictures: `compare.png` (every sequence's images beside the reference) and
//! `blue-noise.png` (every sequence's signed error image above its periodogram; and
//! `blue-noise-masked.png`, the same without the pixels that see an emitter).

use strata_lab::spectrum::ErrorImage;

use glam::Vec3;
use strata_lab::io::{self, Canvas, Rgb};

use crate::args::Args;
use crate::common::CliError;
use crate::picture::{error_canvas, error_image_canvas, label_width, to_canvas};
use crate::sweep::Row;

/// blue-noise.png (or, `masked`, blue-noise-masked.png, without the pixels that see an emitter):
/// per sampler (side by side), the signed error image (one colour scale per count) above its
/// periodogram: white error against blue; one band per count of 1, 4 and 16 that was rendered
/// (the smallest count when none was).
pub fn write_blue_noise(args: &Args, rows: &[Row], masked: bool) -> Result<(), CliError> {
    let mut counts: Vec<u32> = [1, 4, 16]
        .into_iter()
        .filter(|n| args.spp.contains(n))
        .collect();
    if counts.is_empty() {
        counts.push(args.spp[0]);
    }
    // each row's error image and pixels: all of them, or without the emitters' pixels
    fn pick(r: &Row, masked: bool) -> Option<(&ErrorImage, &[f64])> {
        match (masked, &r.masked_errors) {
            (false, _) => Some((&r.errors, r.error_pixels.as_slice())),
            (true, Some((e, p))) => Some((e, p.as_slice())),
            (true, None) => None,
        }
    }
    let bands: Vec<Vec<(&Row, &ErrorImage, &[f64])>> = counts
        .iter()
        .map(|&n| {
            rows.iter()
                .filter(|r| r.spp == n)
                .filter_map(|r| pick(r, masked).map(|(e, p)| (r, e, p)))
                .collect()
        })
        .collect();
    let bands: Vec<_> = bands.into_iter().filter(|b| !b.is_empty()).collect();
    let Some(first) = bands.first().and_then(|b| b.first()) else {
        return Ok(());
    };
    let (w, h) = (first.1.width, first.1.height);
    let label_h = 34u32;
    let cell_w = w.max(150) + 12;
    let band_h = label_h + 2 * h + 24;
    let columns = bands.iter().map(Vec::len).max().unwrap_or(1) as u32;
    let mut c = Canvas::new(
        8 + cell_w * columns,
        band_h * bands.len() as u32,
        Rgb::WHITE,
    );
    for (b, band) in bands.iter().enumerate() {
        let top = b as u32 * band_h;
        let scale = 4.0 * band.iter().map(|r| r.1.rmse).fold(1e-9, f64::max);
        for (k, (r, errors, pixels)) in band.iter().enumerate() {
            let x = 8 + cell_w * k as u32;
            io::label(
                &mut c,
                &format!("{} at {} spp", r.name, r.spp),
                x as i32,
                top as i32 + 2,
                12,
            );
            io::label(
                &mut c,
                &format!(
                    "low band {:.3}, blur2 {:.4}",
                    errors.lowband, errors.blur2_rmse
                ),
                x as i32,
                top as i32 + 17,
                11,
            );
            let both = error_image_canvas(errors, pixels, scale);
            // the canvas holds the image and the spectrum side by side: stack them
            let mut image = Canvas::new(w, h, Rgb::WHITE);
            image.paste(&both, 0, 0);
            let mut spectrum = Canvas::new(w, h, Rgb::WHITE);
            spectrum.paste(&both, -((w + 8) as i64), 0);
            c.paste(&image, x as i64, (top + label_h) as i64);
            c.paste(&spectrum, x as i64, (top + label_h + h + 8) as i64);
        }
    }
    let name = if masked {
        "blue-noise-masked.png"
    } else {
        "blue-noise.png"
    };
    io::write_png(args.out.join(name), &c)?;
    Ok(())
}

/// The cells of `compare.png`: the gap between them, the height of a title, the number of
/// columns (one per count and the error map) and the width of a cell.
#[derive(Clone, Copy)]
struct Grid {
    gap: u32,
    label_h: u32,
    cols: u32,
    cell_w: u32,
}

/// compare.png: the reference, then one row per sampler: its image at each count, and the
/// error map at the largest count. Titles are clipped to their cell, so that they stay
/// legible (and apart) at any image size.
pub fn write_compare(
    args: &Args,
    rows: &[Row],
    reference: &[Vec3],
    ref_spp: u32,
) -> Result<(), CliError> {
    let size = args.size;
    let gap = 8u32;
    let label_h = 18u32;
    let names: Vec<&str> = {
        let mut v: Vec<&str> = rows.iter().map(|r| r.name.as_str()).collect();
        v.dedup();
        v
    };
    let cols = args.spp.len() as u32 + 1;
    let cell_w = size.0.max(72) + 56 + gap;
    let cell_h = label_h + size.1 + gap;
    let width = gap + cell_w * cols;
    let height = gap + cell_h * (names.len() as u32 + 1);
    let mut c = Canvas::new(width, height, Rgb::WHITE);
    put(
        &mut c,
        format!("reference ({ref_spp} spp)"),
        gap,
        gap / 2,
        cell_w * 2,
    );
    c.paste(
        &to_canvas(reference, size),
        gap as i64,
        (gap / 2 + label_h) as i64,
    );
    let grid = Grid {
        gap,
        label_h,
        cols,
        cell_w,
    };
    for (k, name) in names.iter().enumerate() {
        let y = gap / 2 + cell_h * (k as u32 + 1);
        paste_sampler(&mut c, rows, name, reference, size, y, grid);
    }
    io::write_png(args.out.join("compare.png"), &c)?;
    Ok(())
}

/// A label, shortened until it fits `room` pixels.
fn put(c: &mut Canvas, text: String, x: u32, y: u32, room: u32) {
    let mut t = text;
    let size = if room < 120 { 10 } else { 12 };
    while t.chars().count() > 3 && label_width(&t, size) > room {
        t.pop();
    }
    io::label(c, &t, x as i32, y as i32, size);
}

/// One row of `compare.png` at height `y`: sampler `name`'s image at each count, with its RMSE,
/// then its error map at the largest count.
fn paste_sampler(
    c: &mut Canvas,
    rows: &[Row],
    name: &str,
    reference: &[Vec3],
    size: (u32, u32),
    y: u32,
    grid: Grid,
) {
    let Grid {
        gap,
        label_h,
        cols,
        cell_w,
    } = grid;
    for (j, r) in rows.iter().filter(|r| r.name == name).enumerate() {
        let x = gap + cell_w * j as u32;
        put(
            c,
            format!("{} {} spp: {:.4}", r.name, r.spp, r.rmse),
            x,
            y,
            cell_w - gap,
        );
        c.paste(&to_canvas(&r.image, size), x as i64, (y + label_h) as i64);
    }
    if let Some(last) = rows.iter().rfind(|r| r.name == name) {
        let x = gap + cell_w * (cols - 1);
        put(
            c,
            format!("{} error at {} spp", last.name, last.spp),
            x,
            y,
            cell_w - gap,
        );
        c.paste(
            &error_canvas(&last.image, reference, size),
            x as i64,
            (y + label_h) as i64,
        );
    }
}
