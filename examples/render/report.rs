//! The numbers: `render.csv` and the Markdown tables (every render, the RMSE per count with
//! the fitted slope, the renderer's trade), `convergence.png`, `pareto.png`, and the
//! `--markdown` section.

use std::path::Path;

use strata_lab::analysis::study;
use strata_lab::io::{self, LinePlot, Marker, Rgb, Series};

use crate::args::{Args, markdown_section};
use crate::common::{self, CliError};
use crate::method::Method;
use crate::sweep::Row;

/// `render.csv` and its Markdown table: one row per sampler and count, the masked figures
/// after the others.
pub fn results(rows: &[Row]) -> (String, String) {
    let mut csv = String::from(
        "sampler,spp,rmse,rel_rmse,ms,blur1_rmse,blur2_rmse,lowband,masked_rmse,\
         masked_blur1_rmse,masked_blur2_rmse,masked_lowband\n",
    );
    let mut full = String::from(
        "| sampler | spp | rmse | rel_rmse | ms | blur1_rmse | blur2_rmse | lowband | masked: rmse | blur1_rmse | blur2_rmse | lowband |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let m = &r.masked;
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r.name,
            r.spp,
            r.rmse,
            r.rel_rmse,
            r.ms,
            r.blur1,
            r.blur2,
            r.lowband,
            m.rmse,
            m.blur1,
            m.blur2,
            m.lowband
        ));
        full.push_str(&format!(
            "| {} | {} | {:.5} | {:.4} | {:.1} | {:.5} | {:.5} | {:.4} | {:.5} | {:.5} | {:.5} | {:.4} |\n",
            r.name, r.spp, r.rmse, r.rel_rmse, r.ms, r.blur1, r.blur2, r.lowband, m.rmse,
            m.blur1, m.blur2, m.lowband
        ));
    }
    (csv, full)
}

/// The baseline of [`ratios`].
const BASELINE: &str = "sobol";

/// Every render's figures as ratios to `sobol`'s at the same count in the same run (`None`
/// without `sobol` or with nothing beside it): per-pixel RMSE and the low-band share of the error, over all pixels and
/// without those that see an emitter, and (with `--interactions`, at the smallest count) the
/// interaction part's low band.
pub fn ratios(rows: &[Row]) -> Option<String> {
    let base = |spp: u32| rows.iter().find(|r| r.name == BASELINE && r.spp == spp);
    let others = rows.iter().any(|r| r.name != BASELINE);
    (others && rows.iter().any(|r| r.name == BASELINE)).then_some(())?;
    let mut t = format!(
        "Ratios to `{BASELINE}` at the same count, same run (below 1: better; the low-band \
         share below 1 is bluer); s.e.: the masked low band's ratio's standard error over the \
         seeds (delta method, the same seeds paired).\n\n| sampler | spp | rmse | masked rmse \
         | lowband | masked lowband | interaction lowband | s.e. |\n\
         |---|---|---|---|---|---|---|---|\n"
    );
    let ratio = |a: f64, b: f64| {
        if b > 0.0 && a.is_finite() {
            format!("{:.3}", a / b)
        } else {
            "-".to_string()
        }
    };
    for r in rows.iter().filter(|r| r.name != BASELINE) {
        let Some(b) = base(r.spp) else { continue };
        let interaction = match (&r.split, &b.split) {
            (Some([_, mine]), Some([_, theirs])) => ratio(mine.lowband, theirs.lowband),
            _ => "-".to_string(),
        };
        let se = study::ratio_of_means(&r.masked.lowbands, &b.masked.lowbands)
            .map_or("-".to_string(), |(_, e)| format!("{e:.3}"));
        t.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {interaction} | {se} |\n",
            r.name,
            r.spp,
            ratio(r.rmse, b.rmse),
            ratio(r.masked.rmse, b.masked.rmse),
            ratio(r.lowband, b.lowband),
            ratio(r.masked.lowband, b.masked.lowband),
        ));
    }
    Some(t)
}

/// The RMSE per sampler (rows) and count (columns) with the fitted slope, as a Markdown
/// table, and the plot of RMSE against spp (`convergence.png`) with the slope per sampler.
pub fn convergence(
    args: &Args,
    sequences: &[(String, Method)],
    rows: &[Row],
) -> (String, LinePlot) {
    // RMSE against spp, with the fitted slope per sampler
    let mut plot = LinePlot::new(
        format!(
            "RMSE against samples per pixel ({} scene)",
            args.scene.name()
        ),
        "samples per pixel",
        "RMSE against the reference",
    );
    plot.log_x = true;
    plot.log_y = true;
    // RMSE per sampler (rows) and count (columns), with the fitted slope
    let mut table = format!(
        "| sampler | {} | slope |\n|---|{}---|\n",
        args.spp
            .iter()
            .map(|n| format!("{n} spp"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(args.spp.len())
    );
    for (k, (name, _)) in sequences.iter().enumerate() {
        let mine: Vec<&Row> = rows.iter().filter(|r| &r.name == name).collect();
        let pts: Vec<(f64, f64)> = mine.iter().map(|r| (r.spp as f64, r.rmse)).collect();
        let fitted = study::fit_slope(&pts);
        table.push_str(&format!(
            "| {name} | {} | {} |\n",
            mine.iter()
                .map(|r| format!("{:.4}", r.rmse))
                .collect::<Vec<_>>()
                .join(" | "),
            fitted.map_or("-".to_string(), |s| format!("{s:.2}"))
        ));
        let label = match fitted {
            Some(s) => format!("{name} (slope {s:.2})"),
            None => name.clone(),
        };
        plot.series
            .push(Series::new(label, pts, io::PALETTE[k % io::PALETTE.len()]));
    }
    (table, plot)
}

/// The tables of the `--markdown` section: the RMSE table, the table of every render, the
/// renderer's trade and (with `--interactions`) the error split; `masked` is how many pixels
/// the masked figures leave out.
pub struct Tables<'a> {
    pub table: &'a str,
    pub full: &'a str,
    pub trade: &'a str,
    pub split: Option<&'a str>,
    pub frames: Option<&'a str>,
    pub adaptive: Option<&'a str>,
    pub ratios: Option<&'a str>,
    pub masked: usize,
}

/// Writes the `--markdown` section `render-SCENE-COUNTS` into `path`: the [`Tables`], each
/// introduced.
pub fn write_markdown(path: &Path, args: &Args, ref_spp: u32, t: &Tables) -> Result<(), CliError> {
    let (table, full, trade) = (t.table, t.full, t.trade);
    let size = args.size;
    common::write_markdown_section(
        path,
        &markdown_section(args),
        &format!(
            "RMSE of linear radiance against the reference ({} scene, {}x{}, reference: \
             Sobol' at {ref_spp} spp), root of the mean over pixels, channels and {} \
             seeds; slope of log RMSE against log spp.\n\n{table}\nThe error image \
             (signed luminance error): its RMSE after a Gaussian blur of sigma 1 and 2 \
             pixels, and the share of its power below 1/8 cycle per pixel (white \
             error: about 0.05); 'masked': the same without the {} pixels that see \
             an emitter, directly or in a mirror.\n\n{full}\n{trade}{}{}{}{}",
            args.scene.name(),
            size.0,
            size.1,
            args.seeds,
            t.masked,
            t.split.map_or(String::new(), |s| format!("\n{s}")),
            t.frames.map_or(String::new(), |s| format!("\n{s}")),
            t.adaptive.map_or(String::new(), |s| format!("\n{s}")),
            t.ratios.map_or(String::new(), |s| format!("\n{s}"))
        ),
    )
}

/// One sequence's line of the trade table: its render time per sample per pixel, and per
/// target the count, the time and whether they are extrapolated.
struct Line {
    name: String,
    ms_per_spp: f64,
    cells: Vec<Option<(f64, f64, bool)>>,
}

/// The renderer's trade: per sequence, the render time and the time to reach each target RMSE
/// (power laws of RMSE and time against spp, fitted over the measured counts; `*`: outside
/// them). The targets are the median RMSE over the sequences at each count but the smallest
/// (the error a typical sequence reaches there). Writes `pareto.png` (RMSE against render
/// time, sequences on the Pareto front bold) and returns the Markdown table (with one count,
/// a sentence: a power law needs two).
pub fn write_trade(
    args: &Args,
    sequences: &[(String, Method)],
    rows: &[Row],
) -> Result<String, CliError> {
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.ms, r.rmse)).collect();
    if args.spp.len() < 2 {
        // a power law needs two counts: no time to an error to fit
        write_pareto(
            args,
            sequences,
            rows,
            &points,
            &study::pareto_front(&points),
        )?;
        return Ok(
            "The renderer's trade (the time to reach an error) needs two or more \
                   counts (`--spp`); this run has one.\n"
                .to_string(),
        );
    }
    let targets = trade_targets(args, rows);
    let front = study::pareto_front(&points);
    let lines = trade_lines(args, sequences, rows, &targets);
    let table = trade_table(args, &targets, &lines, rows, &front);
    write_pareto(args, sequences, rows, &points, &front)?;
    Ok(table)
}

/// The trade's target RMSEs: the median over the sequences at each count but the smallest
/// (two or more counts).
fn trade_targets(args: &Args, rows: &[Row]) -> Vec<f64> {
    args.spp
        .iter()
        .skip(1)
        .map(|&spp| {
            let mut v: Vec<f64> = rows
                .iter()
                .filter(|r| r.spp == spp)
                .map(|r| r.rmse)
                .collect();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        })
        .collect()
}

/// Whether sequence `name` has a render on the Pareto front `front` (indices into `rows`).
fn on_front(rows: &[Row], front: &[usize], name: &str) -> bool {
    front.iter().any(|&i| rows[i].name == name)
}

/// The trade table's lines, one per sequence, cheapest first at the last (smallest) target.
fn trade_lines(
    args: &Args,
    sequences: &[(String, Method)],
    rows: &[Row],
    targets: &[f64],
) -> Vec<Line> {
    let mut lines: Vec<Line> = sequences
        .iter()
        .map(|(name, _)| {
            let mine: Vec<&Row> = rows.iter().filter(|r| &r.name == name).collect();
            let err: Vec<(f64, f64)> = mine.iter().map(|r| (r.spp as f64, r.rmse)).collect();
            let time: Vec<(f64, f64)> = mine.iter().map(|r| (r.spp as f64, r.ms)).collect();
            let (lo, hi) = (
                args.spp[0] as f64,
                *args.spp.last().expect("a count") as f64,
            );
            let cells = targets
                .iter()
                .map(|&t| {
                    let spp = study::count_to_reach(&err, t)?.ceil();
                    let ms = study::power_law_at(&time, spp)?;
                    Some((spp, ms, spp < lo || spp > hi))
                })
                .collect();
            let last = mine.last().expect("a count");
            Line {
                name: name.clone(),
                ms_per_spp: last.ms / f64::from(last.spp),
                cells,
            }
        })
        .collect();
    let key = |l: &Line| {
        l.cells
            .last()
            .copied()
            .flatten()
            .map_or(f64::INFINITY, |c| c.1)
    };
    lines.sort_by(|a, b| key(a).total_cmp(&key(b)));
    lines
}

/// The trade as a Markdown table, introduced; sequences on the Pareto front bold.
fn trade_table(
    args: &Args,
    targets: &[f64],
    lines: &[Line],
    rows: &[Row],
    front: &[usize],
) -> String {
    let mut table = format!(
        "The renderer's trade: render time (all cores, one image) to reach each RMSE, cheapest \
         first at the smallest RMSE; the targets are the median RMSE over the sequences at \
         {} spp; `*`: extrapolated beyond the measured counts; bold: on the Pareto front of \
         (time, RMSE) over all renders.\n\n| sequence | ms per spp | {} |\n|---|---|{}\n",
        args.spp
            .iter()
            .skip(1)
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        targets
            .iter()
            .map(|t| format!("RMSE {t:.4}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(targets.len())
    );
    for l in lines {
        let name = if on_front(rows, front, &l.name) {
            format!("**{}**", l.name)
        } else {
            l.name.clone()
        };
        let cells: Vec<String> = l
            .cells
            .iter()
            .map(|c| match c {
                Some((spp, ms, x)) => {
                    format!("{ms:.0} ms ({spp} spp{})", if *x { "*" } else { "" })
                }
                None => "-".into(),
            })
            .collect();
        table.push_str(&format!(
            "| {name} | {:.2} | {} |\n",
            l.ms_per_spp,
            cells.join(" | ")
        ));
    }
    table
}

/// pareto.png: RMSE against render time for every render, the Pareto front drawn, the
/// sequences with a render on it bold and the rest faint.
fn write_pareto(
    args: &Args,
    sequences: &[(String, Method)],
    rows: &[Row],
    points: &[(f64, f64)],
    front: &[usize],
) -> Result<(), CliError> {
    let mut plot = LinePlot::new(
        "render: RMSE against render time (bold: Pareto front)",
        "render time (ms, all cores)",
        "RMSE against the reference",
    );
    plot.log_x = true;
    plot.log_y = true;
    plot.legend_outside = true;
    let mut line = Series::reference(
        "Pareto front",
        front.iter().map(|&i| points[i]).collect(),
        Rgb::grey(60),
    );
    line.width = 1;
    plot.series.push(line);
    for (k, (name, _)) in sequences.iter().enumerate() {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| &r.name == name)
            .map(|r| (r.ms, r.rmse))
            .collect();
        let bold = on_front(rows, front, name);
        let mut s = Series::new(
            if bold {
                format!("{name} *")
            } else {
                name.clone()
            },
            pts,
            io::PALETTE[k % io::PALETTE.len()],
        );
        s.marker = Marker::ALL[k % Marker::ALL.len()];
        s.width = if bold { 3 } else { 1 };
        s.faint = !bold;
        plot.series.push(s);
    }
    io::write_png(args.out.join("pareto.png"), &plot.render(820, 500))?;
    Ok(())
}
