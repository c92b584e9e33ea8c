//! `measure`: measure point sets made by anything (ours, UTK's, scipy's, yours).
//!
//! ```text
//! cargo run --release --example measure -- FILE... [--out DIR]
//! ```
//! See `docs/cli.md` (the command-line contract) and `--help` for the definitions.

mod common;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use common::{CliError, cli_error};
use rayon::prelude::*;
use strata_lab::analysis::discrepancy;
use strata_lab::pointsets::{self, PointSet};
use strata_lab::{io, spectrum};

/// The most work, `n^2 d`, of the O(n^2 d) discrepancies of one set.
const MAX_PAIRWISE_WORK: u128 = 1 << 33;

/// The pairwise work of a file from which `measure` says what it does (about a second).
const LONG_PAIRWISE_WORK: u128 = 1 << 28;

/// Whether the O(n^2 d) sums of a set of `n` points in `d` dimensions are within the bound.
fn pairwise_allowed(n: usize, d: u32) -> bool {
    (n as u128) * (n as u128) * (d as u128) <= MAX_PAIRWISE_WORK
}

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "measure: read point sets and print their discrepancies, spacing and \
spectral measures.";

/// The files it reads and the columns it prints (the end of `--help`).
const DETAILS: &str = "\
Files: CSV (one point per line, comma-separated, optional header), UTK text (space-separated,
sets separated by lines starting with '#'), or UTK binary (.bin: magic UTK!, data type f32 or
f64, counts of sets, points and dimensions, then the values). The format is read from the
content. Coordinates must lie in [0, 1).

Columns (one row per set, then the mean of each file's sets):
  n, d        points and dimensions
  l2_star     L2-star discrepancy (Warnock): sqrt(3^-d - 2^(1-d)/n sum_i prod_k (1 - x_ik^2)
              + n^-2 sum_ij prod_k (1 - max(x_ik, x_jk))); equals scipy.stats.qmc.discrepancy
              (method='L2-star'), which also takes the root
  wd2         wrap-around L2 discrepancy, squared (Hickernell): -(4/3)^d + n^-2 sum_ij
              prod_k (3/2 - |x_ik - x_jk| + |x_ik - x_jk|^2); equals scipy's 'WD' (squared)
  cd2         centered L2 discrepancy, squared (Hickernell), with a_ik = |x_ik - 1/2|:
              (13/12)^d - 2/n sum_i prod_k (1 + a_ik/2 - a_ik^2/2) + n^-2 sum_ij prod_k
              (1 + a_ik/2 + a_jk/2 - |x_ik - x_jk|/2); equals scipy's 'CD' (squared)
  md2         mixture discrepancy, squared (Zhou, Fang, Ning 2013): (19/12)^d - 2/n sum_i
              prod_k (5/3 - a_ik/4 - a_ik^2/4) + n^-2 sum_ij prod_k (15/8 - a_ik/4 - a_jk/4
              - 3|x_ik - x_jk|/4 + |x_ik - x_jk|^2/2); equals scipy's 'MD' (squared)
  star        exact star discrepancy (2D sets of at most 16384 points)
  t           t-value as a base-2 (t,m,2)-net (2D sets of 2^m points): 0 for a (0,m,2)-net
  min_nn      minimum toroidal nearest-neighbour distance / r_max (2D), r_max(n) =
              sqrt(2 / (sqrt(3) n)), the spacing of the densest packing
  mean_nn     mean nearest-neighbour distance / r_max (2D)
  nu_eff      effective Nyquist frequency / sqrt(n), and
  osc         oscillations: the PSA spectral measures (Heck et al. 2013), 2D sets of at most
              65536 points

The pairwise sums are O(n^2 d): sets with n^2 d above 2^33 (65536 points in 2D, 2930 in 1000
dimensions) show '-' for them; sets near that bound take tens of seconds each, and a file whose
sums are that long says so on stderr when it starts and when it is done. Each file is
labelled by its name without the extension; files whose names would give the same label keep
their extension, then a number ('pts.csv', 'pts-2.csv').";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them).
#[derive(clap::Parser)]
#[command(name = "measure", about = ABOUT, after_help = DETAILS)]
struct Args {
    /// point-set files (CSV, UTK text or UTK binary)
    #[arg(value_name = "FILE", required = true)]
    files: Vec<PathBuf>,
    /// also write, per file whose sets are 2D and of one size, the expected spectrum over its
    /// sets as `spectrum` does: FILE-spectrum.png/.exr, FILE-radial.csv/.png, FILE-points.png;
    /// and measures.csv with the table
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// spectrum grid, frequencies |u|, |v| <= K/2 (even)
    #[arg(long, value_name = "K", default_value_t = 128,
          value_parser = common::value_parser(resolution))]
    resolution: u32,
}

/// `--resolution K`: an even grid the spectrum takes.
fn resolution(v: &str) -> Result<u32, CliError> {
    let k = common::parse_int("--resolution", v, 2, u64::from(spectrum::MAX_RESOLUTION))? as u32;
    spectrum::check_resolution(k)?;
    Ok(k)
}

fn parse() -> Result<Option<Args>, CliError> {
    use clap::{CommandFactory, FromArgMatches};
    let Some(matches) = common::clap_matches(Args::command())? else {
        return Ok(None);
    };
    let args = Args::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?;
    if let Some(dir) = &args.out {
        common::check_output_dir("--out", dir)?;
    }
    Ok(Some(args))
}

/// The measures of one set; `None` where a measure does not apply.
#[derive(Clone, Default)]
struct Row {
    n: usize,
    d: u32,
    values: [Option<f64>; COLUMNS.len()],
}

/// The measured columns after `n` and `d`.
const COLUMNS: [&str; 10] = [
    "l2_star", "wd2", "cd2", "md2", "star", "t", "min_nn", "mean_nn", "nu_eff", "osc",
];

fn measure(set: &PointSet) -> Result<Row, strata_lab::Error> {
    let (n, d) = (set.len(), set.dims);
    let mut v: [Option<f64>; COLUMNS.len()] = Default::default();
    let c = &set.coords;
    if pairwise_allowed(n, d) {
        v[0] = Some(discrepancy::l2_star(c, d)?);
        v[1] = Some(discrepancy::wrap_around_squared(c, d)?);
        v[2] = Some(discrepancy::centered_squared(c, d)?);
        v[3] = Some(discrepancy::mixture_squared(c, d)?);
    }
    if let Some(points) = set.points_2d() {
        if n <= discrepancy::MAX_EXACT_STAR {
            v[4] = Some(discrepancy::star_2d(c)?);
        }
        v[5] = discrepancy::net_t_value(c)?.map(f64::from);
        if n >= 2 {
            let m = spectrum::point_set_measures(&[points])?;
            v[6] = m.global_min_distance;
            v[7] = m.average_min_distance;
            v[8] = m.effective_nyquist;
            v[9] = m.oscillations;
        }
    }
    Ok(Row { n, d, values: v })
}

/// A file of this many sets states its cost before the work whatever the estimate.
const MANY_SETS: usize = 100;

/// How often a long file reports how far it got.
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_secs(2);

/// The rows of every set of a file, in parallel. The first set is measured alone and timed:
/// a file whose sets would take a second or more in all (or of 100 sets or more) says so first,
/// with the estimate
/// (a 64 MiB file of 65,536 sets once ran for an hour in silence), then how far it
/// got every two seconds.
fn measure_all(label: &str, sets: &[PointSet]) -> Result<Vec<Row>, strata_lab::Error> {
    let Some((first, rest)) = sets.split_first() else {
        return Ok(Vec::new());
    };
    let started = std::time::Instant::now();
    let head = measure(first)?;
    let each = started.elapsed().as_secs_f64();
    let threads = rayon::current_num_threads().max(1) as f64;
    let estimate = each * rest.len() as f64 / threads.min(rest.len().max(1) as f64);
    if estimate >= 1.0 || sets.len() >= MANY_SETS {
        eprintln!(
            "measure: {label}: {} sets, about {} in all ({:.1} ms for the first, {} threads)",
            sets.len(),
            duration_text(estimate),
            each * 1e3,
            threads
        );
    }
    let done = std::sync::atomic::AtomicUsize::new(1);
    let last = std::sync::Mutex::new(std::time::Instant::now());
    let mut rows = vec![head];
    rows.extend(
        rest.par_iter()
            .map(|s| {
                let row = measure(s);
                let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                if let Ok(mut at) = last.try_lock()
                    && at.elapsed() >= PROGRESS_EVERY
                {
                    *at = std::time::Instant::now();
                    let spent = started.elapsed().as_secs_f64();
                    let left = spent / k as f64 * (sets.len() - k) as f64;
                    eprintln!(
                        "measure: {label}: {k} of {} sets in {}, about {} left",
                        sets.len(),
                        duration_text(spent),
                        duration_text(left)
                    );
                }
                row
            })
            .collect::<Result<Vec<Row>, strata_lab::Error>>()?,
    );
    Ok(rows)
}

/// Seconds as "12 s", "3.4 min" or "1.2 h".
fn duration_text(s: f64) -> String {
    if s < 120.0 {
        format!("{s:.0} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

/// The mean of each column over the rows that have it (`None` if some row lacks it).
fn mean(rows: &[Row]) -> Row {
    let mut out = Row {
        n: rows[0].n,
        d: rows[0].d,
        values: Default::default(),
    };
    for (k, slot) in out.values.iter_mut().enumerate() {
        let vals: Option<Vec<f64>> = rows.iter().map(|r| r.values[k]).collect();
        *slot = vals.map(|v| v.iter().sum::<f64>() / v.len() as f64);
    }
    out
}

fn cell(v: Option<f64>) -> String {
    match v {
        Some(x) if x.fract() == 0.0 && x.abs() < 1e6 => format!("{x}"),
        Some(x) => format!("{x:.6e}"),
        None => "-".into(),
    }
}

/// A file name as text: its UTF-8 as it is, every other byte as `%XX` (so two names that differ
/// only in bytes that are not UTF-8 keep different labels).
fn name_text(s: &std::ffi::OsStr) -> String {
    let mut out = String::new();
    for chunk in s.as_encoded_bytes().utf8_chunks() {
        out.push_str(chunk.valid());
        for b in chunk.invalid() {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// A label per file, unique among all of them (they name the output files): the name without
/// its extension, or with it where two files would share a label; then, where labels still
/// meet, a number before the extension (`pts-2.csv`), never one that another file's label
/// takes.
fn file_labels(paths: &[PathBuf]) -> Vec<String> {
    let stem = |p: &Path| {
        p.file_stem()
            .map_or_else(|| name_text(p.as_os_str()), name_text)
    };
    let name = |p: &Path| {
        p.file_name()
            .map_or_else(|| name_text(p.as_os_str()), name_text)
    };
    let stems: Vec<String> = paths.iter().map(|p| stem(p)).collect();
    let bases: Vec<String> = paths
        .iter()
        .zip(&stems)
        .map(|(p, s)| {
            if stems.iter().filter(|t| *t == s).count() > 1 {
                name(p)
            } else {
                s.clone()
            }
        })
        .collect();
    let mut taken = std::collections::HashSet::new();
    bases
        .iter()
        .map(|base| {
            let numbered = |k: usize| match base.rsplit_once('.') {
                Some((a, b)) if !a.is_empty() => format!("{a}-{k}.{b}"),
                _ => format!("{base}-{k}"),
            };
            let mut label = base.clone();
            let mut k = 1;
            // a number that is free now and is no other file's own label
            while taken.contains(&label) || (k > 1 && bases.contains(&label)) {
                k += 1;
                label = numbered(k);
            }
            taken.insert(label.clone());
            label
        })
        .collect()
}

fn main() -> ExitCode {
    common::run("measure", || {
        let Some(args) = parse()? else { return Ok(()) };
        let mut table = format!("| file | set | n | d | {} |\n", COLUMNS.join(" | "));
        table.push_str(&format!("|{}\n", "---|".repeat(COLUMNS.len() + 4)));
        let mut csv = format!("file,set,n,d,{}\n", COLUMNS.join(","));
        let labels = file_labels(&args.files);
        for (path, label) in args.files.iter().zip(labels) {
            let sets = pointsets::read_file(path)?;
            let rows = measure_file(&label, &sets)?;
            let same_shape = rows.iter().all(|r| (r.n, r.d) == (rows[0].n, rows[0].d));
            let mut lines: Vec<(String, &Row)> = rows
                .iter()
                .enumerate()
                .map(|(i, r)| (i.to_string(), r))
                .collect();
            let average = same_shape.then(|| mean(&rows));
            if let Some(m) = &average {
                lines.push(("mean".into(), m));
            }
            for (set, r) in lines {
                let cells: Vec<String> = r.values.iter().map(|&v| cell(v)).collect();
                let (n, d) = (r.n, r.d);
                let cells = (cells.join(" | "), cells.join(","));
                table.push_str(&format!("| {label} | {set} | {n} | {d} | {} |\n", cells.0));
                csv.push_str(&format!("{label},{set},{n},{d},{}\n", cells.1));
            }
            if let Some(dir) = &args.out {
                write_spectrum(dir, path, &label, &sets, same_shape, args.resolution)?;
            }
        }
        common::out(&table)?;
        if let Some(dir) = &args.out {
            io::write_text(dir.join("measures.csv"), &csv)?;
        }
        Ok(())
    })
}

/// The rows of a file's sets, a long file saying what it does on stderr (not a minute in
/// silence), and a note when some sets are too large for the pairwise sums.
fn measure_file(label: &str, sets: &[PointSet]) -> Result<Vec<Row>, CliError> {
    let work: u128 = sets
        .iter()
        .filter(|s| pairwise_allowed(s.len(), s.dims))
        .map(|s| s.len() as u128 * s.len() as u128 * s.dims as u128)
        .sum();
    let started = std::time::Instant::now();
    let long = work >= LONG_PAIRWISE_WORK;
    if long {
        eprintln!(
            "measure: {label}: {} set(s), pairwise sums of n^2 d = {work} terms in all ...",
            sets.len()
        );
    }
    let rows = measure_all(label, sets)?;
    if long {
        eprintln!(
            "measure: {label}: measured in {:.1} s",
            started.elapsed().as_secs_f64()
        );
    }
    if let Some(r) = rows.iter().find(|r| !pairwise_allowed(r.n, r.d)) {
        eprintln!(
            "measure: {label}: n^2 d = {} for n = {}, d = {} is above {MAX_PAIRWISE_WORK}; the \
             discrepancies are shown as '-'",
            r.n as u128 * r.n as u128 * r.d as u128,
            r.n,
            r.d
        );
    }
    Ok(rows)
}

/// `--out DIR`: the expected spectrum over a file's sets, when they are 2D and of one size.
fn write_spectrum(
    dir: &std::path::Path,
    path: &std::path::Path,
    label: &str,
    sets: &[PointSet],
    same_shape: bool,
    resolution: u32,
) -> Result<(), CliError> {
    let points: Option<Vec<_>> = sets.iter().map(PointSet::points_2d).collect();
    match points {
        Some(points) if same_shape => {
            let spec = spectrum::expected_spectrum_of_sets(&points, resolution)?;
            io::write_spectrum_files(dir, label, &spec, points.len(), &points[0], &[])?;
        }
        _ => eprintln!(
            "measure: {}: no spectrum (it needs 2D sets of one size)",
            path.display()
        ),
    }
    Ok(())
}
