//! The CSV files: `tradeoff.csv` (one row per sampler, integrand and count), `slopes.csv` (the
//! fitted rates) and `time_to_error.csv`.

use strata_lab::analysis::study::{Row, Slope, TimeToError};
use strata_lab::io;

use crate::args::Args;
use crate::common::CliError;

/// A number as Rust prints it, or nothing when there is none.
fn fmt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x}"))
}

/// `DIR/tradeoff.csv`: one row per sampler, integrand and count.
pub fn write_rows(args: &Args, rows: &[Row]) -> Result<(), CliError> {
    let mut csv = String::from(
        "sampler,integrand,n,seeds,mean,variance,rmse,ns_per_sample,predicted_variance,set_ns,set_ns_min,set_ns_max,one_time_ns\n",
    );
    for r in rows {
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            r.sampler,
            r.integrand.name(),
            r.n,
            r.seeds,
            r.mean,
            r.variance,
            r.rmse,
            r.ns_per_sample,
            fmt(r.predicted_variance),
            r.set_ns,
            r.set_ns_min,
            r.set_ns_max,
            r.one_time_ns
        ));
    }
    io::write_text(args.out.join("tradeoff.csv"), &csv)?;
    Ok(())
}

/// `DIR/slopes.csv`: per sampler and integrand, the fitted slope, the published rate and the
/// bootstrap interval.
pub fn write_slopes(args: &Args, slopes: &[Slope]) -> Result<(), CliError> {
    let mut csv = String::from("sampler,integrand,slope,expected,slope_lo,slope_hi\n");
    for s in slopes {
        csv.push_str(&format!(
            "{},{},{},{},{},{}\n",
            s.sampler,
            s.integrand.name(),
            fmt(s.slope),
            fmt(s.expected),
            fmt(s.interval.map(|i| i.0)),
            fmt(s.interval.map(|i| i.1))
        ));
    }
    io::write_text(args.out.join("slopes.csv"), &csv)?;
    Ok(())
}

/// `DIR/time_to_error.csv`: per integrand, target and sampler, the count and the time it needs.
pub fn write_time_to_error(args: &Args, tte: &[TimeToError]) -> Result<(), CliError> {
    let mut csv = String::from("integrand,target,sampler,n,ns,extrapolated\n");
    for t in tte {
        csv.push_str(&format!(
            "{},{},{},{},{},{}\n",
            t.integrand.name(),
            t.target,
            t.sampler,
            t.n,
            t.ns,
            u8::from(t.extrapolated)
        ));
    }
    io::write_text(args.out.join("time_to_error.csv"), &csv)?;
    Ok(())
}
