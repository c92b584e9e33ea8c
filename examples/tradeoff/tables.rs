//! The tables: the slopes (samplers down, integrands across), the time to reach each error per
//! integrand, and the `--markdown` sections `tradeoff` and `time-to-error`.

use std::path::Path;

use strata_lab::analysis::Integrand;
use strata_lab::analysis::study::{Row, Slope, TimeToError};

use crate::args::Args;
use crate::common::{self, CliError};

/// The slopes as a table: samplers down, integrands across, with the seeds used.
pub fn slopes(args: &Args, rows: &[Row], slopes: &[Slope]) -> String {
    let header: Vec<&str> = args.integrands.iter().map(|f| f.name()).collect();
    let mut table = format!(
        "| sampler | seeds | {} |\n|---|---|{}\n",
        header.join(" | "),
        "---|".repeat(header.len())
    );
    for e in &args.samplers {
        let seeds = rows
            .iter()
            .find(|r| r.sampler == e.name)
            .map_or(String::from("-"), |r| r.seeds.to_string());
        let cells: Vec<String> = args
            .integrands
            .iter()
            .map(|&f| {
                slope_cell(
                    slopes
                        .iter()
                        .find(|s| s.sampler == e.name && s.integrand == f),
                )
            })
            .collect();
        table.push_str(&format!(
            "| {} | {seeds} | {} |\n",
            e.name,
            cells.join(" | ")
        ));
    }
    table
}

/// One cell of the slopes table: the slope, its interval and the published rate, or `-`.
fn slope_cell(slope: Option<&Slope>) -> String {
    match slope {
        Some(s @ Slope { slope: Some(v), .. }) => {
            let ci = s
                .interval
                .map_or(String::new(), |(lo, hi)| format!(" [{lo:.2}, {hi:.2}]"));
            let exp = s.expected.map_or(String::new(), |x| format!(" ({x})"));
            format!("{v:.2}{ci}{exp}")
        }
        _ => "-".into(),
    }
}

/// The time-to-error tables of every integrand, each after an empty line.
pub fn times(args: &Args, tte: &[TimeToError]) -> String {
    let mut times = String::new();
    for &f in &args.integrands {
        times.push_str(&format!("\n{}", time_table(tte, f, &args.targets)));
    }
    times
}

/// Writes the `--markdown` sections: `tradeoff` (the slopes table `table`) and
/// `time-to-error` (the time-to-error tables of disk and gaussian, where they ran).
pub fn write_markdown(
    path: &Path,
    args: &Args,
    table: &str,
    tte: &[TimeToError],
) -> Result<(), CliError> {
    common::write_markdown_section(
        path,
        "tradeoff",
        &format!(
            "Slope of log variance against log N with its 95% bootstrap interval (the \
             published rate in parentheses), N = {}..{}.\n\n{table}",
            args.min_n, args.max_n
        ),
    )?;
    let mut body = String::from(
        "The generation time each sampler needs for an RMSE relative to the integral \
         (cheapest first at the middle target; N is the count it needs, `*` where the \
         fitted power laws are extrapolated beyond the measured counts). Time of a set \
         on one core, one-time tables excluded.\n",
    );
    for f in [Integrand::Disk, Integrand::Gaussian] {
        if args.integrands.contains(&f) {
            body.push_str(&format!("\n{}", time_table(tte, f, &args.targets)));
        }
    }
    common::write_markdown_section(path, "time-to-error", &body)
}

/// A duration in nanoseconds, readable.
fn human(ns: f64) -> String {
    if ns < 1e3 {
        format!("{ns:.0} ns")
    } else if ns < 1e6 {
        format!("{:.1} us", ns / 1e3)
    } else if ns < 1e9 {
        format!("{:.1} ms", ns / 1e6)
    } else {
        format!("{:.1} s", ns / 1e9)
    }
}

/// The time-to-error table of one integrand: samplers down (cheapest at the middle target
/// first), one column per target with the time and the count (`*`: extrapolated).
fn time_table(tte: &[TimeToError], f: Integrand, targets: &[f64]) -> String {
    let mut names: Vec<&'static str> = Vec::new();
    let key = targets.get(targets.len() / 2).copied().unwrap_or(1e-3);
    let mut order: Vec<&TimeToError> = tte
        .iter()
        .filter(|t| t.integrand == f && t.target == key)
        .collect();
    order.sort_by(|a, b| a.ns.total_cmp(&b.ns));
    names.extend(order.iter().map(|t| t.sampler));
    for t in tte.iter().filter(|t| t.integrand == f) {
        if !names.contains(&t.sampler) {
            names.push(t.sampler);
        }
    }
    let mut table = format!(
        "| {} | {} |\n|---|{}\n",
        f.name(),
        targets
            .iter()
            .map(|t| format!("RMSE {t:e}"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(targets.len())
    );
    for name in names {
        let cells: Vec<String> = targets
            .iter()
            .map(|&t| {
                match tte
                    .iter()
                    .find(|x| x.integrand == f && x.target == t && x.sampler == name)
                {
                    Some(x) => format!(
                        "{} (N={}{})",
                        human(x.ns),
                        x.n,
                        if x.extrapolated { "*" } else { "" }
                    ),
                    None => "-".into(),
                }
            })
            .collect();
        table.push_str(&format!("| {name} | {} |\n", cells.join(" | ")));
    }
    table
}
