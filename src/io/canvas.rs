//! A minimal RGB8 raster with the few primitives the pictures need.

/// An 8-bit RGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgb(pub [u8; 3]);

impl Rgb {
    /// White.
    pub const WHITE: Rgb = Rgb([255, 255, 255]);
    /// Black.
    pub const BLACK: Rgb = Rgb([0, 0, 0]);

    /// A colour from its components.
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Rgb([r, g, b])
    }

    /// A grey level.
    pub const fn grey(v: u8) -> Self {
        Rgb([v, v, v])
    }

    /// `self` blended toward `other` by `t` in `[0, 1]`.
    pub fn mix(self, other: Rgb, t: f32) -> Rgb {
        let t = t.clamp(0.0, 1.0);
        let c = |a: u8, b: u8| (a as f32 + (b as f32 - a as f32) * t).round() as u8;
        Rgb([
            c(self.0[0], other.0[0]),
            c(self.0[1], other.0[1]),
            c(self.0[2], other.0[2]),
        ])
    }
}

/// An RGB8 image, row-major from the top-left corner.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Canvas {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

impl Canvas {
    /// A `width x height` canvas filled with `background`.
    pub fn new(width: u32, height: u32, background: Rgb) -> Self {
        let mut data = Vec::with_capacity(width as usize * height as usize * 3);
        for _ in 0..width as usize * height as usize {
            data.extend_from_slice(&background.0);
        }
        Canvas {
            width,
            height,
            data,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, 3 bytes each, row-major from the top-left.
    pub fn data(&self) -> &[u8] {
        &self.data
    }

    /// The pixels, mutable (for drawing libraries that render into an RGB8 buffer).
    pub fn data_mut(&mut self) -> &mut [u8] {
        &mut self.data
    }

    /// The colour at `(x, y)` (`None` outside).
    pub fn get(&self, x: u32, y: u32) -> Option<Rgb> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        Some(Rgb([self.data[i], self.data[i + 1], self.data[i + 2]]))
    }

    /// Sets `(x, y)` to `c`; pixels outside are ignored.
    pub fn set(&mut self, x: i64, y: i64, c: Rgb) {
        self.blend(x, y, c, 1.0);
    }

    /// Blends `c` over `(x, y)` with coverage `alpha`; pixels outside are ignored.
    pub fn blend(&mut self, x: i64, y: i64, c: Rgb, alpha: f32) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 || alpha <= 0.0 {
            return;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        let old = Rgb([self.data[i], self.data[i + 1], self.data[i + 2]]);
        self.data[i..i + 3].copy_from_slice(&old.mix(c, alpha).0);
    }

    /// A full-height vertical line at column `x`.
    pub fn vline(&mut self, x: i64, c: Rgb) {
        for y in 0..self.height as i64 {
            self.set(x, y, c);
        }
    }

    /// A full-width horizontal line at row `y`.
    pub fn hline(&mut self, y: i64, c: Rgb) {
        for x in 0..self.width as i64 {
            self.set(x, y, c);
        }
    }

    /// A one-pixel border.
    pub fn frame(&mut self, c: Rgb) {
        let (w, h) = (self.width as i64, self.height as i64);
        for x in 0..w {
            self.set(x, 0, c);
            self.set(x, h - 1, c);
        }
        for y in 0..h {
            self.set(0, y, c);
            self.set(w - 1, y, c);
        }
    }

    /// An anti-aliased filled disc centred at `(cx, cy)` (pixel units, `(0,0)` the top-left
    /// corner of the top-left pixel).
    pub fn disc(&mut self, cx: f32, cy: f32, r: f32, c: Rgb) {
        let (x0, x1) = ((cx - r - 1.0).floor() as i64, (cx + r + 1.0).ceil() as i64);
        let (y0, y1) = ((cy - r - 1.0).floor() as i64, (cy + r + 1.0).ceil() as i64);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let d = ((x as f32 + 0.5 - cx).powi(2) + (y as f32 + 0.5 - cy).powi(2)).sqrt();
                self.blend(x, y, c, r + 0.5 - d);
            }
        }
    }

    /// Copies `other` into this canvas with its top-left corner at `(x, y)` (clipped).
    pub fn paste(&mut self, other: &Canvas, x: i64, y: i64) {
        for j in 0..other.height {
            for i in 0..other.width {
                let c = other.get(i, j).expect("inside");
                self.set(x + i as i64, y + j as i64, c);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disc_covers_its_centre_and_not_far_pixels() {
        let mut c = Canvas::new(20, 20, Rgb::WHITE);
        c.disc(10.0, 10.0, 3.0, Rgb::BLACK);
        assert_eq!(c.get(10, 10), Some(Rgb::BLACK));
        assert_eq!(c.get(0, 0), Some(Rgb::WHITE));
        assert_eq!(c.get(10, 15), Some(Rgb::WHITE));
    }
}
