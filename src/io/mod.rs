//! Pictures and files: PNG canvases, point drawings (behind the `io` feature).
//!
//! The drawing code is a small software rasterizer on an RGB8 [`Canvas`]: it needs no system
//! library, and its output is byte-for-byte reproducible.

mod canvas;

pub use canvas::{Canvas, Rgb};

use std::path::Path;

use crate::error::{Error, Result};
use crate::sampler::{Point2, StrataGrid};

/// Writes `canvas` as an 8-bit RGB PNG, creating the parent directory when missing.
pub fn write_png(path: impl AsRef<Path>, canvas: &Canvas) -> Result<()> {
    let path = path.as_ref();
    create_parent(path)?;
    let file = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
    let mut encoder = png::Encoder::new(
        std::io::BufWriter::new(file),
        canvas.width(),
        canvas.height(),
    );
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().map_err(|e| Error::io(path, e))?;
    writer
        .write_image_data(canvas.data())
        .map_err(|e| Error::io(path, e))?;
    writer.finish().map_err(|e| Error::io(path, e))
}

/// Creates the directory `path` will be written into, if it has one and it is missing.
pub fn create_parent(path: &Path) -> Result<()> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => {
            std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))
        }
        _ => Ok(()),
    }
}

/// Draws a point set on a white square of `size` pixels: strata grids as light lines (finest
/// first, each only when its cells are at least 3 pixels wide), then the points as dark dots
/// whose radius shrinks with the number of points. `y` points up, as in the papers' figures.
pub fn draw_points(points: &[Point2], grids: &[StrataGrid], size: u32) -> Canvas {
    let mut canvas = Canvas::new(size, size, Rgb::WHITE);
    let s = size as f32;
    // Finest grid lightest, coarsest darkest and drawn last.
    for (level, grid) in grids.iter().enumerate().rev() {
        let shade = if level == 0 { 190 } else { 225 };
        let colour = Rgb::grey(shade);
        for (cells, vertical) in [(grid.columns, true), (grid.rows, false)] {
            if cells < 2 || s / cells as f32 <= 3.0 {
                continue;
            }
            for k in 1..cells {
                let t = (k as f64 / cells as f64 * size as f64).round() as i64;
                if vertical {
                    canvas.vline(t, colour);
                } else {
                    canvas.hline(size as i64 - 1 - t, colour);
                }
            }
        }
    }
    let radius = (s / (points.len().max(1) as f32).sqrt() * 0.18).clamp(0.9, 5.0);
    for p in points {
        canvas.disc(p.x * s, (1.0 - p.y) * s, radius, Rgb::new(20, 40, 120));
    }
    canvas.frame(Rgb::grey(120));
    canvas
}
