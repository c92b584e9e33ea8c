//! Pictures and the numbers of a pixel: tone mapping, luminance and the relative error, the
//! colour maps, and the canvases of an image, its error map and its signed error image.

use glam::Vec3;
use strata_lab::io::{self, Canvas, Rgb};
use strata_lab::spectrum::ErrorImage;

/// A pixel value's display byte: Reinhard tone mapping, then display gamma.
fn tone(v: f32) -> u8 {
    let v = v.max(0.0);
    let mapped = (v / (1.0 + v)).powf(1.0 / 2.2); // Reinhard, then display gamma
    (mapped * 255.0).round().clamp(0.0, 255.0) as u8
}

/// The image `img` (linear radiance, row-major, `size`) tone-mapped.
pub fn to_canvas(img: &[Vec3], size: (u32, u32)) -> Canvas {
    let mut c = Canvas::new(size.0, size.1, Rgb::BLACK);
    for (i, v) in img.iter().enumerate() {
        c.set(
            (i as u32 % size.0) as i64,
            (i as u32 / size.0) as i64,
            Rgb::new(tone(v.x), tone(v.y), tone(v.z)),
        );
    }
    c
}

/// The luminance of a linear RGB value (Rec. 709 weights).
pub fn luminance(v: Vec3) -> f32 {
    0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z
}

/// Relative error of a pixel: |I - R| / (R + 0.02) on luminance.
pub fn relative_error(a: Vec3, r: Vec3) -> f32 {
    (luminance(a) - luminance(r)).abs() / (luminance(r) + 0.02)
}

/// A perceptual colour map (black - purple - orange - yellow), `t` in [0, 1].
fn colormap(t: f32) -> Rgb {
    const STOPS: [(f32, [u8; 3]); 5] = [
        (0.0, [0, 0, 4]),
        (0.25, [87, 16, 110]),
        (0.5, [188, 55, 84]),
        (0.75, [249, 142, 9]),
        (1.0, [252, 255, 164]),
    ];
    let t = t.clamp(0.0, 1.0);
    for w in STOPS.windows(2) {
        let ((t0, c0), (t1, c1)) = (w[0], w[1]);
        if t <= t1 {
            let u = (t - t0) / (t1 - t0);
            let mix = |a: u8, b: u8| (a as f32 + (b as f32 - a as f32) * u).round() as u8;
            return Rgb::new(mix(c0[0], c1[0]), mix(c0[1], c1[1]), mix(c0[2], c1[2]));
        }
    }
    Rgb::new(252, 255, 164)
}

/// The relative error at the top of the error map's colour scale.
const ERROR_SCALE: f32 = 0.5;

/// The error map of `img` against `reference`: the per-pixel relative error, colour-mapped
/// from 0 to [`ERROR_SCALE`], with the scale beside it.
pub fn error_canvas(img: &[Vec3], reference: &[Vec3], size: (u32, u32)) -> Canvas {
    let bar = 56;
    let mut c = Canvas::new(size.0 + bar, size.1, Rgb::WHITE);
    for (i, (a, r)) in img.iter().zip(reference).enumerate() {
        let e = relative_error(*a, *r) / ERROR_SCALE;
        c.set(
            (i as u32 % size.0) as i64,
            (i as u32 / size.0) as i64,
            colormap(e),
        );
    }
    // the scale: a vertical bar from 0 (bottom) to ERROR_SCALE (top), with labels
    let (x0, top, bottom) = (size.0 as i64 + 6, 14i64, size.1 as i64 - 14);
    for y in top..=bottom {
        let t = (bottom - y) as f32 / (bottom - top) as f32;
        for x in x0..x0 + 12 {
            c.set(x, y, colormap(t));
        }
    }
    io::label(
        &mut c,
        &format!("{ERROR_SCALE}"),
        (x0 + 14) as i32,
        (top - 6) as i32,
        11,
    );
    io::label(&mut c, "0", (x0 + 14) as i32, (bottom - 6) as i32, 11);
    io::label(
        &mut c,
        "rel.",
        (x0 + 14) as i32,
        (size.1 as i64 / 2 - 6) as i32,
        11,
    );
    c
}

/// The signed luminance error of every pixel.
pub fn luminance_errors(image: &[Vec3], reference: &[Vec3]) -> Vec<f64> {
    image
        .iter()
        .zip(reference)
        .map(|(a, r)| luminance(*a) as f64 - luminance(*r) as f64)
        .collect()
}

/// A diverging colour map for signed values in [-1, 1]: blue, white, red.
fn diverging(t: f32) -> Rgb {
    let t = t.clamp(-1.0, 1.0);
    let mix = |a: f32, b: f32, u: f32| (a + (b - a) * u).round() as u8;
    if t < 0.0 {
        let u = -t;
        Rgb::new(
            mix(255.0, 33.0, u),
            mix(255.0, 102.0, u),
            mix(255.0, 172.0, u),
        )
    } else {
        Rgb::new(
            mix(255.0, 178.0, t),
            mix(255.0, 24.0, t),
            mix(255.0, 43.0, t),
        )
    }
}

/// The signed error image (scaled to `scale`) beside its periodogram (log scale, DC centred).
pub fn error_image_canvas(e: &ErrorImage, errors: &[f64], scale: f64) -> Canvas {
    let (w, h) = (e.width, e.height);
    let mut c = Canvas::new(2 * w + 8, h, Rgb::WHITE);
    for (i, v) in errors.iter().enumerate() {
        c.set(
            (i as u32 % w) as i64,
            (i as u32 / w) as i64,
            diverging((v / scale) as f32),
        );
    }
    // the periodogram over 3 decades below its largest value
    let top = e.spectrum.iter().cloned().fold(f64::MIN_POSITIVE, f64::max);
    for (i, p) in e.spectrum.iter().enumerate() {
        let t = ((p / top).max(1e-3).log10() + 3.0) / 3.0;
        let g = (t.clamp(0.0, 1.0) * 255.0) as u8;
        c.set(
            (w + 8 + i as u32 % w) as i64,
            (i as u32 / w) as i64,
            Rgb::new(g, g, g),
        );
    }
    c
}

/// A label's width in pixels at `size` (the bundled font averages about 0.55 em per glyph).
pub fn label_width(text: &str, size: u32) -> u32 {
    (text.chars().count() as f32 * size as f32 * 0.56).ceil() as u32
}
