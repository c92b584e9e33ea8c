//! Shared command-line plumbing of the example programs: parsing numbers with messages that say
//! what is allowed, and one-line errors with a non-zero exit status.

#![allow(dead_code)]

use std::fmt::Display;
use std::process::ExitCode;

/// The largest count the example programs accept (the library itself may go further).
pub const MAX_CLI_COUNT: u64 = 1 << 26;

/// A command-line failure: a one-line message for stderr.
#[derive(Debug)]
pub struct CliError(pub String);

impl<E: std::error::Error> From<E> for CliError {
    fn from(e: E) -> Self {
        CliError(e.to_string())
    }
}

/// Shorthand for a `CliError` from anything printable.
pub fn cli_error(msg: impl Display) -> CliError {
    CliError(msg.to_string())
}

/// Runs `body`, printing its error as one line on stderr (exit status 2), or `--help` text.
pub fn run(program: &str, body: impl FnOnce() -> Result<(), CliError>) -> ExitCode {
    match body() {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError(msg)) => {
            let one_line = msg.replace('\n', " ");
            eprintln!("{program}: error: {one_line}");
            ExitCode::from(2)
        }
    }
}

/// The value of a flag as a UTF-8 string.
pub fn string_value(flag: &str, value: std::ffi::OsString) -> Result<String, CliError> {
    value
        .into_string()
        .map_err(|v| cli_error(format!("{flag}: {v:?} is not valid UTF-8")))
}

/// Parses a flag's value as an integer in `[min, max]`.
pub fn parse_int(flag: &str, value: &str, min: u64, max: u64) -> Result<u64, CliError> {
    let v: u64 = value.trim().parse().map_err(|e: std::num::ParseIntError| {
        let what = match e.kind() {
            std::num::IntErrorKind::PosOverflow => "is out of range",
            _ => "is not a whole number",
        };
        cli_error(format!("{flag} {value:?} {what}; allowed: {min} to {max}"))
    })?;
    if v < min || v > max {
        return Err(cli_error(format!(
            "{flag} {v} is out of range; allowed: {min} to {max}"
        )));
    }
    Ok(v)
}

/// Parses a flag's value as a finite float in the open interval `(lo, hi)`.
pub fn parse_open_float(flag: &str, value: &str, lo: f64, hi: f64) -> Result<f64, CliError> {
    let v: f64 = value.trim().parse().map_err(|_| {
        cli_error(format!(
            "{flag} {value:?} is not a number; allowed: {lo} < {flag} < {hi}"
        ))
    })?;
    if !(v > lo && v < hi) {
        return Err(cli_error(format!(
            "{flag} {v} is out of range; allowed: {lo} < value < {hi}"
        )));
    }
    Ok(v)
}

/// Parses `X,Y` as two integers in `[0, max]`.
pub fn parse_pair(flag: &str, value: &str, max: u64) -> Result<(u64, u64), CliError> {
    let bad = || {
        cli_error(format!(
            "{flag} {value:?} is not X,Y; allowed: two whole numbers 0 to {max}, e.g. 3,7"
        ))
    };
    let (a, b) = value.split_once(',').ok_or_else(bad)?;
    Ok((parse_int(flag, a, 0, max)?, parse_int(flag, b, 0, max)?))
}

/// Turns lexopt's complaint about an unexpected argument into a message that lists the flags.
pub fn unexpected(arg: lexopt::Arg<'_>, usage: &str) -> CliError {
    let what = match arg {
        lexopt::Arg::Short(c) => format!("unknown flag -{c}"),
        lexopt::Arg::Long(l) => format!("unknown flag --{l}"),
        lexopt::Arg::Value(v) => format!("unexpected argument {v:?}"),
    };
    cli_error(format!("{what}; usage: {usage}"))
}

/// The sampler parameters `points` and `spectrum` share: `--radius`, `--iterations`,
/// `--strength`, `--candidates`, `--capacity` (the flag's name without dashes), read from `parser` into
/// `params` with the same ranges in both programs.
pub fn sampler_param(
    flag: &str,
    parser: &mut lexopt::Parser,
    params: &mut strata::registry::Params,
) -> Result<(), CliError> {
    let dashed = format!("--{flag}");
    let v = string_value(&dashed, parser.value()?)?;
    match flag {
        "radius" => params.radius = Some(parse_open_float(&dashed, &v, 0.0, 1.0)?),
        "iterations" => params.iterations = Some(parse_int(&dashed, &v, 0, 100_000)? as u32),
        "strength" => params.strength = Some(parse_int(&dashed, &v, 0, 64)? as u32),
        "candidates" => params.candidates = Some(parse_int(&dashed, &v, 0, 1 << 16)? as u32),
        "capacity" => params.capacity = Some(parse_int(&dashed, &v, 0, 1 << 16)? as u32),
        other => return Err(cli_error(format!("--{other} is not a sampler parameter"))),
    }
    Ok(())
}

/// Writes `body` into the Markdown file `path` as section `name`, between the lines
/// `<!-- begin NAME -->` and `<!-- end NAME -->`, replacing an earlier version of the section
/// and keeping the rest of the file (a new section goes at the end; a missing file is
/// created). The section records the command that wrote it, so that every figure in
/// `docs/results.md` says which program and arguments produced it.
pub fn write_markdown_section(
    path: &std::path::Path,
    name: &str,
    body: &str,
) -> Result<(), CliError> {
    let (begin, end) = (
        format!("<!-- begin {name} -->"),
        format!("<!-- end {name} -->"),
    );
    let args: Vec<String> = std::env::args().skip(1).collect();
    let program = std::env::args()
        .next()
        .and_then(|p| {
            std::path::Path::new(&p)
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
        })
        .unwrap_or_default();
    let section = format!(
        "{begin}\n<!-- written by `cargo run --release --example {program} -- {}` -->\n\n{}\n\n{end}",
        args.join(" "),
        body.trim_end()
    );
    let old = std::fs::read_to_string(path).unwrap_or_default();
    let new = match (old.find(&begin), old.find(&end)) {
        (Some(a), Some(b)) if b > a => format!("{}{section}{}", &old[..a], &old[b + end.len()..]),
        _ if old.is_empty() => format!("{section}\n"),
        _ => format!("{}\n\n{section}\n", old.trim_end()),
    };
    strata::io::write_text(path, &new)?;
    Ok(())
}

/// A progress line on stderr when it is not a terminal (where the progress bar is hidden):
/// logs and CI see how far a long run got.
pub fn progress_line(text: impl Display) {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        eprintln!("{text}");
    }
}
