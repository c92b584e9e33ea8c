//! Plots with axes and labels, drawn by `plotters` into a [`Canvas`] with the bundled font.

use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::{Canvas, Rgb};
use crate::spectrum::RadialBin;

/// The bundled font (DejaVu Sans; see `assets/README.md`).
static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers the bundled font as plotters' `sans-serif` (once per process).
fn ensure_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The bytes are a valid TrueType font, checked by the tests; if registration ever failed,
        // text would be missing from the pictures, not the program.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c.0[0], c.0[1], c.0[2])
}

/// The marker drawn at each point of a [`Series`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle.
    Triangle,
    /// A cross.
    Cross,
    /// A hollow circle.
    Ring,
    /// A filled diamond.
    Diamond,
}

impl Marker {
    /// Every marker, for cycling through with colours.
    pub const ALL: [Marker; 6] = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Cross,
        Marker::Ring,
        Marker::Diamond,
    ];
}

/// One line of a [`LinePlot`].
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend entry (empty for none).
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line colour.
    pub colour: Rgb,
    /// Dashed (for reference lines) or solid.
    pub dashed: bool,
    /// Draw a marker at every point.
    pub markers: bool,
    /// The marker's shape.
    pub marker: Marker,
    /// Line width in pixels.
    pub width: u32,
    /// Drawn pale (mixed with white), for context behind the highlighted lines.
    pub faint: bool,
}

impl Series {
    /// A solid line with markers.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, colour: Rgb) -> Self {
        Series {
            name: name.into(),
            points,
            colour,
            dashed: false,
            markers: true,
            marker: Marker::Circle,
            width: 2,
            faint: false,
        }
    }

    /// A dashed reference line without markers.
    pub fn reference(name: impl Into<String>, points: Vec<(f64, f64)>, colour: Rgb) -> Self {
        Series {
            name: name.into(),
            points,
            colour,
            dashed: true,
            markers: false,
            marker: Marker::Circle,
            width: 2,
            faint: false,
        }
    }
}

/// A line plot with axes, labels and a legend, linear or logarithmic on each axis.
#[derive(Clone, Debug)]
pub struct LinePlot {
    /// Title above the plot.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// X range (`None`: from the data).
    pub x_range: Option<(f64, f64)>,
    /// Y range (`None`: from the data).
    pub y_range: Option<(f64, f64)>,
    /// The lines.
    pub series: Vec<Series>,
    /// Draw the legend in a column right of the data instead of over it.
    pub legend_outside: bool,
}

/// A palette of distinguishable colours (Okabe-Ito, then darker tones), for plots with many lines.
pub const PALETTE: [Rgb; 12] = [
    Rgb::new(0, 114, 178),
    Rgb::new(213, 94, 0),
    Rgb::new(0, 158, 115),
    Rgb::new(204, 121, 167),
    Rgb::new(230, 159, 0),
    Rgb::new(86, 180, 233),
    Rgb::new(120, 120, 120),
    Rgb::new(0, 0, 0),
    Rgb::new(140, 40, 40),
    Rgb::new(40, 90, 40),
    Rgb::new(90, 40, 140),
    Rgb::new(150, 110, 20),
];

impl LinePlot {
    /// An empty plot.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        LinePlot {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            log_x: false,
            log_y: false,
            x_range: None,
            y_range: None,
            series: Vec::new(),
            legend_outside: false,
        }
    }

    fn data_range(&self, pick: impl Fn(&(f64, f64)) -> f64, log: bool) -> (f64, f64) {
        let vals = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(&pick))
            .filter(|v| v.is_finite() && (!log || *v > 0.0));
        let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        if !lo.is_finite() {
            return if log { (0.1, 10.0) } else { (0.0, 1.0) };
        }
        if log {
            let (lo, hi) = if lo == hi {
                (lo / 2.0, hi * 2.0)
            } else {
                (lo, hi)
            };
            (lo / 1.3, hi * 1.3)
        } else {
            let pad = if hi > lo { 0.05 * (hi - lo) } else { 0.5 };
            (lo - pad, hi + pad)
        }
    }

    /// Renders the plot into a `width x height` canvas.
    pub fn render(&self, width: u32, height: u32) -> Canvas {
        ensure_font();
        let mut canvas = Canvas::new(width, height, Rgb::WHITE);
        let x = self
            .x_range
            .unwrap_or_else(|| self.data_range(|p| p.0, self.log_x));
        let y = self
            .y_range
            .unwrap_or_else(|| self.data_range(|p| p.1, self.log_y));
        {
            let full =
                BitMapBackend::with_buffer(canvas.data_mut(), (width, height)).into_drawing_area();
            let legend_width = if self.legend_outside {
                self.legend_width()
            } else {
                0
            };
            let (root, side) = full.split_horizontally(width.saturating_sub(legend_width));
            if self.legend_outside {
                self.draw_legend(&side);
            }
            // Drawing into memory cannot fail except on invalid ranges, which `data_range`
            // rules out; a failed plot leaves a blank canvas rather than an error.
            let _ = match (self.log_x, self.log_y) {
                (false, false) => self.draw(&root, x.0..x.1, y.0..y.1),
                (true, false) => self.draw(&root, (x.0..x.1).log_scale(), y.0..y.1),
                (false, true) => self.draw(&root, x.0..x.1, (y.0..y.1).log_scale()),
                (true, true) => self.draw(&root, (x.0..x.1).log_scale(), (y.0..y.1).log_scale()),
            };
            let _ = full.present();
        }
        canvas
    }

    /// The width of the outside legend column: the longest name at about 7 pixels a character.
    fn legend_width(&self) -> u32 {
        let longest = self
            .series
            .iter()
            .map(|s| s.name.chars().count())
            .max()
            .unwrap_or(0) as u32;
        if longest == 0 { 0 } else { 44 + 7 * longest }
    }

    /// The legend in its own column: a line sample with the marker, and the name.
    fn draw_legend<DB: DrawingBackend>(&self, area: &DrawingArea<DB, plotters::coord::Shift>) {
        let mut y = 40;
        for s in self.series.iter().filter(|s| !s.name.is_empty()) {
            let colour = rgb(shade(s));
            let style = ShapeStyle::from(&colour).stroke_width(s.width);
            let _ = area.draw(&PathElement::new(vec![(6, y), (30, y)], style));
            if s.markers {
                let _ = draw_marker(area, s.marker, (18, y), colour);
            }
            let _ = area.draw(&Text::new(
                s.name.clone(),
                (36, y - 7),
                ("sans-serif", 12).into_font().color(&BLACK),
            ));
            y += 18;
        }
    }

    fn draw<DB, X, Y>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
        x: X,
        y: Y,
    ) -> Result<(), String>
    where
        DB: DrawingBackend,
        X: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
        Y: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
        X::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
        Y::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
    {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(55)
            .build_cartesian_2d(x, y)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style(("sans-serif", 12))
            .axis_desc_style(("sans-serif", 14))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(215, 215, 215))
            .draw()
            .map_err(e)?;
        let mut any_legend = false;
        // faint lines first, so that the highlighted ones are drawn over them
        let order = self
            .series
            .iter()
            .filter(|s| s.faint)
            .chain(self.series.iter().filter(|s| !s.faint));
        for s in order {
            let colour = rgb(shade(s));
            let style = ShapeStyle::from(&colour).stroke_width(s.width);
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            let anno = if s.dashed {
                chart
                    .draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))
                    .map_err(e)?
            } else {
                chart
                    .draw_series(LineSeries::new(pts.clone(), style))
                    .map_err(e)?
            };
            if !s.name.is_empty() && !self.legend_outside {
                any_legend = true;
                anno.label(s.name.clone()).legend(move |(lx, ly)| {
                    PathElement::new(
                        vec![(lx, ly), (lx + 18, ly)],
                        ShapeStyle::from(&colour).stroke_width(2),
                    )
                });
            }
            if s.markers {
                // the root area starts at the canvas's origin, so backend pixels are its own
                let area = chart.plotting_area();
                for &p in &pts {
                    draw_marker(root, s.marker, area.map_coordinate(&p), colour).map_err(e)?;
                }
            }
        }
        if any_legend {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(180, 180, 180))
                .label_font(("sans-serif", 12))
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(e)?;
        }
        Ok(())
    }
}

/// A series' drawing colour: its own, or mixed 60% toward white when faint.
fn shade(s: &Series) -> Rgb {
    if s.faint {
        s.colour.mix(Rgb::WHITE, 0.6)
    } else {
        s.colour
    }
}

/// Draws `marker` centred at pixel `at`.
fn draw_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    marker: Marker,
    at: (i32, i32),
    colour: RGBColor,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (x, y) = at;
    let r = 4;
    match marker {
        Marker::Circle => area.draw(&Circle::new(at, r, colour.filled())),
        Marker::Ring => area.draw(&Circle::new(at, r, colour.stroke_width(2))),
        Marker::Square => area.draw(&Rectangle::new(
            [(x - r + 1, y - r + 1), (x + r - 1, y + r - 1)],
            colour.filled(),
        )),
        Marker::Triangle => area.draw(&Polygon::new(
            vec![(x, y - r - 1), (x - r, y + r - 1), (x + r, y + r - 1)],
            colour.filled(),
        )),
        Marker::Diamond => area.draw(&Polygon::new(
            vec![(x, y - r - 1), (x + r, y), (x, y + r + 1), (x - r, y)],
            colour.filled(),
        )),
        Marker::Cross => {
            let style = colour.stroke_width(2);
            area.draw(&PathElement::new(
                vec![(x - r, y - r), (x + r, y + r)],
                style,
            ))?;
            area.draw(&PathElement::new(
                vec![(x - r, y + r), (x + r, y - r)],
                style,
            ))
        }
    }
}

/// Panels of equal size in a grid of `columns` columns, row by row, on a white canvas.
pub fn panel_grid(panels: &[Canvas], columns: usize) -> Canvas {
    let columns = columns.max(1);
    let (w, h) = panels
        .iter()
        .fold((1, 1), |(w, h), p| (w.max(p.width()), h.max(p.height())));
    let rows = panels.len().div_ceil(columns).max(1);
    let mut out = Canvas::new(w * columns as u32, h * rows as u32, Rgb::WHITE);
    for (k, p) in panels.iter().enumerate() {
        let (cx, cy) = ((k % columns) as u32 * w, (k / columns) as u32 * h);
        out.paste(p, i64::from(cx), i64::from(cy));
    }
    out
}

/// An axis tick label: integers without decimals, small and large values in scientific form,
/// the rest with at most three decimals.
fn tick(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.0e}")
    } else if (v - v.round()).abs() < 1e-9 * a.max(1.0) {
        format!("{v:.0}")
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// The radial mean of a spectrum as a plot: power against frequency `|w|`, with white noise
/// (`P = 1`) dashed and `sqrt(N)` (the typical blue-noise ring) marked.
pub fn radial_plot(
    bins: &[RadialBin],
    title: &str,
    n_points: usize,
    width: u32,
    height: u32,
) -> Canvas {
    let pts: Vec<(f64, f64)> = bins.iter().map(|b| (b.frequency as f64, b.power)).collect();
    let x_max = bins.last().map_or(1.0, |b| b.frequency as f64);
    let y_max = pts
        .iter()
        .map(|p| p.1)
        .fold(0.0f64, f64::max)
        .clamp(1.5, 4.0)
        * 1.05;
    let mut plot = LinePlot::new(title, "frequency |w|", "radial mean power");
    plot.x_range = Some((0.0, x_max));
    plot.y_range = Some((0.0, y_max));
    plot.series.push(Series::reference(
        "",
        vec![(0.0, 1.0), (x_max, 1.0)],
        Rgb::grey(140),
    ));
    let root_n = (n_points as f64).sqrt();
    if root_n < x_max {
        plot.series.push(Series::reference(
            "sqrt(N)",
            vec![(root_n, 0.0), (root_n, y_max)],
            Rgb::new(213, 94, 0),
        ));
    }
    let mut line = Series::new("", pts, Rgb::new(0, 114, 178));
    line.markers = false;
    plot.series.push(line);
    plot.render(width, height)
}

/// Draws `text` onto `canvas` with its top-left corner at `(x, y)`, in the bundled font.
pub fn label(canvas: &mut Canvas, text: &str, x: i32, y: i32, size: u32) {
    ensure_font();
    let (w, h) = (canvas.width(), canvas.height());
    let root = BitMapBackend::with_buffer(canvas.data_mut(), (w, h)).into_drawing_area();
    let _ = root.draw(&Text::new(
        text.to_string(),
        (x, y),
        ("sans-serif", size).into_font().color(&BLACK),
    ));
    let _ = root.present();
}

/// The label column of an overview row: the sampler's name and a few lines of figures.
pub fn overview_row_label(title: &str, lines: &[String], width: u32, height: u32) -> Canvas {
    let mut c = Canvas::new(width, height, Rgb::WHITE);
    label(&mut c, title, 8, 10, 20);
    for (i, l) in lines.iter().enumerate() {
        label(&mut c, l, 8, 40 + 18 * i as i32, 13);
    }
    c
}
