//! The plots: per integrand, one panel per family, `convergence-F.png` (variance against N,
//! with the published rates) and `tradeoff-F.png` (RMSE against the time of a set, with the
//! Pareto front).

use strata_lab::analysis::Integrand;
use strata_lab::analysis::study::{self, Row, Slope};
use strata_lab::io::{self, Canvas, LinePlot, Marker, PALETTE, Rgb, Series};
use strata_lab::registry::{Entry, Family};

use crate::args::Args;

/// The samplers of `rows` on the Pareto front of (set time, RMSE) for integrand `f`: those
/// with a point that no other sampler's point beats on both axes; and the front itself.
fn pareto(rows: &[Row], f: Integrand) -> (Vec<&'static str>, Vec<(f64, f64)>) {
    let mine: Vec<&Row> = rows
        .iter()
        .filter(|r| r.integrand == f && r.rmse > 0.0)
        .collect();
    let pts: Vec<(f64, f64)> = mine.iter().map(|r| (r.set_ns / 1e3, r.rmse)).collect();
    let front = study::pareto_front(&pts);
    let mut names: Vec<&'static str> = front.iter().map(|&i| mine[i].sampler).collect();
    names.sort_unstable();
    names.dedup();
    (names, front.iter().map(|&i| pts[i]).collect())
}

/// One panel per family: `convergence-F.png` (variance against N, with the published rates)
/// and `tradeoff-F.png` (RMSE against the time of a set; samplers on the Pareto front bold,
/// the front dashed, the rest faint).
pub fn plots(rows: &[Row], slopes: &[Slope], args: &Args) -> Result<(), strata_lab::Error> {
    for &f in &args.integrands {
        if !args.samplers.iter().any(|e| !of(rows, f, e).is_empty()) {
            continue;
        }
        let (conv_panels, time_panels) = panels(rows, slopes, args, f);
        io::write_png(
            args.out.join(format!("convergence-{}.png", f.name())),
            &io::panel_grid(&conv_panels, 2),
        )?;
        io::write_png(
            args.out.join(format!("tradeoff-{}.png", f.name())),
            &io::panel_grid(&time_panels, 2),
        )?;
    }
    Ok(())
}

/// The rows of sampler `e` on integrand `f` with a positive variance.
fn of<'a>(rows: &'a [Row], f: Integrand, e: &Entry) -> Vec<&'a Row> {
    rows.iter()
        .filter(|r| r.integrand == f && r.sampler == e.name && r.variance > 0.0)
        .collect()
}

/// The panels of integrand `f`, one per family with rows: the convergence plots and the
/// time plots.
fn panels(rows: &[Row], slopes: &[Slope], args: &Args, f: Integrand) -> (Vec<Canvas>, Vec<Canvas>) {
    let (front_names, front) = pareto(rows, f);
    let anchor = anchor(rows, f);
    let (mut conv_panels, mut time_panels) = (Vec::new(), Vec::new());
    for family in Family::ALL {
        let members: Vec<&&Entry> = args
            .samplers
            .iter()
            .filter(|e| e.family == family && !of(rows, f, e).is_empty())
            .collect();
        if members.is_empty() {
            continue;
        }
        let mut conv = convergence_plot(rows, f, family, anchor, args.max_n);
        let mut time = time_plot(rows, f, family, &front);
        for (k, e) in members.iter().enumerate() {
            let rs = of(rows, f, e);
            let (colour, marker) = (
                PALETTE[k % PALETTE.len()],
                Marker::ALL[k % Marker::ALL.len()],
            );
            let mut c = Series::new(
                slope_label(slopes, e, f),
                rs.iter().map(|r| (r.n as f64, r.variance)).collect(),
                colour,
            );
            c.marker = marker;
            conv.series.push(c);
            let on_front = front_names.contains(&e.name);
            time.series
                .push(time_series(e, &rs, (colour, marker), on_front));
        }
        conv_panels.push(conv.render(640, 420));
        time_panels.push(time.render(640, 420));
    }
    (conv_panels, time_panels)
}

/// Where the published rates start: the smallest count of `random` on `f` (of another sampler
/// when random has no row), with its variance.
fn anchor(rows: &[Row], f: Integrand) -> Option<(f64, f64)> {
    rows.iter()
        .filter(|r| r.integrand == f && r.variance > 0.0)
        .min_by(|a, b| {
            (a.sampler != "random")
                .cmp(&(b.sampler != "random"))
                .then(a.n.cmp(&b.n))
        })
        .map(|r| (r.n as f64, r.variance))
}

/// The range of `pick` over the rows of `f` (its positive, finite values), widened by 1.5 each
/// way: axes shared by the panels, so that they compare at a glance.
fn range(rows: &[Row], f: Integrand, pick: &dyn Fn(&Row) -> f64) -> (f64, f64) {
    let v: Vec<f64> = rows
        .iter()
        .filter(|r| r.integrand == f)
        .map(pick)
        .filter(|v| *v > 0.0 && v.is_finite())
        .collect();
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(0.0, f64::max);
    (lo / 1.5, hi * 1.5)
}

/// The convergence panel of `family` on `f`, with the published rates N^-1 to N^-3 drawn from
/// `anchor` to `max_n`; no samplers yet.
fn convergence_plot(
    rows: &[Row],
    f: Integrand,
    family: Family,
    anchor: Option<(f64, f64)>,
    max_n: u64,
) -> LinePlot {
    let mut conv = LinePlot::new(
        format!("{}: {}", f.name(), family.name()),
        "N (samples)",
        "variance of the estimate",
    );
    conv.log_x = true;
    conv.log_y = true;
    conv.legend_outside = true;
    conv.x_range = Some(range(rows, f, &|r| r.n as f64));
    conv.y_range = Some(range(rows, f, &|r| r.variance));
    if let Some((n0, v0)) = anchor {
        let n1 = max_n as f64;
        for (rate, grey) in [(-1.0, 110u8), (-1.5, 150), (-2.0, 175), (-3.0, 200)] {
            conv.series.push(Series::reference(
                format!("N^{rate}"),
                vec![(n0, v0), (n1, v0 * (n1 / n0).powf(rate))],
                Rgb::grey(grey),
            ));
        }
    }
    conv
}

/// The time panel of `family` on `f`, with the Pareto front `front` drawn; no samplers yet.
fn time_plot(rows: &[Row], f: Integrand, family: Family, front: &[(f64, f64)]) -> LinePlot {
    let mut time = LinePlot::new(
        format!("{}: {} (bold: Pareto front)", f.name(), family.name()),
        "time of a set (us, one core)",
        "RMSE",
    );
    time.log_x = true;
    time.log_y = true;
    time.legend_outside = true;
    time.x_range = Some(range(rows, f, &|r| r.set_ns / 1e3));
    time.y_range = Some(range(rows, f, &|r| r.rmse));
    let mut line = Series::reference("Pareto front", front.to_vec(), Rgb::grey(60));
    line.width = 1;
    time.series.push(line);
    time
}

/// A sampler's name in the convergence legend, with its fitted slope on `f` when it has one.
fn slope_label(slopes: &[Slope], e: &Entry, f: Integrand) -> String {
    match slopes
        .iter()
        .find(|s| s.sampler == e.name && s.integrand == f)
        .and_then(|s| s.slope)
    {
        Some(s) => format!("{} ({s:.2})", e.name),
        None => e.name.to_string(),
    }
}

/// A sampler's RMSE against the time of a set: bold and starred when it is on the Pareto
/// front, faint otherwise.
fn time_series(e: &Entry, rs: &[&Row], (colour, marker): (Rgb, Marker), on_front: bool) -> Series {
    let mut t = Series::new(
        if on_front {
            format!("{} *", e.name)
        } else {
            e.name.to_string()
        },
        rs.iter().map(|r| (r.set_ns / 1e3, r.rmse)).collect(),
        colour,
    );
    t.marker = marker;
    t.width = if on_front { 3 } else { 1 };
    t.faint = !on_front;
    t
}
