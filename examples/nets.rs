//! `nets`: the stratification of the jointly Z-ordered sequences' groups, counted exactly.
//!
//! ```text
//! cargo run --release --example nets -- [--sequence zjoint|zquad] [--group G] [--max-m M]
//!     [--markdown FILE]
//! ```

mod common;

use std::process::ExitCode;

use common::{CliError, cli_error, parse_int};
use strata::samplers::sobol;

/// What the program does (the first lines of `--help`).
const ABOUT: &str = "\
nets: the t-values of the projections that `zjoint` or `zquad` draws read, from the generator \
matrices (exact, by the rank criterion of digital nets). A pixel's 2^m samples of a group \
are an aligned block of 2^m points of the multi-dimensional sequence (Sobol' for zjoint, the \
base-4 Faure sequence in binary form for zquad), nested-shuffled and Owen-scrambled, which \
keeps every elementary interval: each pair of the group's dimensions is a (t, m, 2)-net and \
each set of four a (t, m, 4)-net with the t printed here (t = 0 is the best possible; an \
independent pair, as two draws of zsobol are, has no such guarantee). Prints, for m = 2, 4, \
..., M (2^m points, 4^(m/2) for even m), the t-value of every pair of dimensions of one group, \
the largest and the mean t over every set of four, and the t of dimensions 0-3 as a base-4 \
net of 4^(m/2) points.";

/// The options, each declared once (clap makes `--help`, the usage and the errors from them).
#[derive(clap::Parser)]
#[command(name = "nets", about = ABOUT)]
struct Args {
    /// zjoint, or zquad (groups of 4, and the fifth matrix its 2D draws at a group's last
    /// dimension read)
    #[arg(long, value_enum, default_value_t = SequenceArg::Zjoint)]
    sequence: SequenceArg,
    /// zjoint's dimensions of a group: a power of two from 2 to 16 (zquad: 4)
    #[arg(long, value_name = "G", default_value_t = 8,
          value_parser = common::value_parser(group))]
    group: u32,
    /// the largest m, an even number from 2 to 24
    #[arg(long, value_name = "M", default_value_t = 16,
          value_parser = common::value_parser(max_m))]
    max_m: u32,
    /// also write the tables into FILE, as its section 'nets-zjoint-G' or 'nets-zquad'
    #[arg(long, value_name = "FILE")]
    markdown: Option<std::path::PathBuf>,
}

/// `--sequence`.
#[derive(Clone, Copy, PartialEq, clap::ValueEnum)]
enum SequenceArg {
    /// Sobol' matrices, groups of G dimensions
    Zjoint,
    /// the base-4 Faure matrices in binary form, groups of 4
    Zquad,
}

impl Args {
    /// The sampler whose matrices are read: `sobol` (zjoint) or `faure4` (zquad).
    fn sampler(&self) -> &'static str {
        match self.sequence {
            SequenceArg::Zjoint => "sobol",
            SequenceArg::Zquad => "faure4",
        }
    }
}

/// `--group G`: a power of two from 2 to 16.
fn group(v: &str) -> Result<u32, CliError> {
    let g = parse_int("--group", v, 2, 16)? as u32;
    if !g.is_power_of_two() {
        return Err(cli_error(format!(
            "--group {g}: a power of two from 2 to 16 is needed"
        )));
    }
    Ok(g)
}

/// `--max-m M`: an even number from 2 to 24.
fn max_m(v: &str) -> Result<u32, CliError> {
    let m = parse_int("--max-m", v, 2, 24)? as u32;
    if !m.is_multiple_of(2) {
        return Err(cli_error(format!(
            "--max-m {m}: an even number from 2 to 24 is needed"
        )));
    }
    Ok(m)
}

fn parse() -> Result<Option<Args>, CliError> {
    use clap::{CommandFactory, FromArgMatches};
    let Some(matches) = common::clap_matches(Args::command())? else {
        return Ok(None);
    };
    let mut args = Args::from_arg_matches(&matches).map_err(|e| cli_error(e.to_string()))?;
    if args.sequence == SequenceArg::Zquad {
        let given = matches.value_source("group") == Some(clap::parser::ValueSource::CommandLine);
        if given && args.group != 4 {
            return Err(cli_error(format!(
                "--group {}: zquad's groups have 4 dimensions",
                args.group
            )));
        }
        args.group = 4;
    }
    if let Some(m) = &args.markdown {
        common::check_markdown(m, &section(&args))?;
    }
    Ok(Some(args))
}

fn section(args: &Args) -> String {
    if args.sequence == SequenceArg::Zquad {
        String::from("nets-zquad")
    } else {
        format!("nets-zjoint-{}", args.group)
    }
}

/// Every `k`-subset of `0..n`, in lexicographic order.
fn subsets(n: u32, k: usize) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    let mut pick = Vec::with_capacity(k);
    fn go(start: u32, n: u32, k: usize, pick: &mut Vec<u32>, out: &mut Vec<Vec<u32>>) {
        if pick.len() == k {
            out.push(pick.clone());
            return;
        }
        for d in start..n {
            pick.push(d);
            go(d + 1, n, k, pick, out);
            pick.pop();
        }
    }
    go(0, n, k, &mut pick, &mut out);
    out
}

fn tables(args: &Args) -> Result<String, CliError> {
    let ms: Vec<u32> = (2..=args.max_m).step_by(2).collect();
    let header = |first: &str| {
        format!(
            "| {first} | {} |\n|---|{}\n",
            ms.iter()
                .map(|m| format!("m = {m}"))
                .collect::<Vec<_>>()
                .join(" | "),
            "---|".repeat(ms.len())
        )
    };
    let t_of =
        |dims: &[u32], m: u32, base: u32| sobol::projection_t_value(args.sampler(), dims, m, base);
    let quad = args.sequence == SequenceArg::Zquad;
    // zquad: the four dimensions and the fifth matrix a 2D draw at dimension 3 pairs with
    let dims = if quad { 5 } else { args.group };
    let mut text = if quad {
        String::from(
            "t-values of the projections of one `zquad` group (dimensions 0-3: Faure's \
             (0,4)-sequence in base 4, binary form; dimension 4: the fifth matrix, Sobol' \
             dimension 4, read only by a 2D draw at the group's last dimension) as base-2 \
             nets of `2^m` points; 0 is a perfect net, `m` no stratification at all. The \
             draws at dimensions 0 and 2 read the pairs (0, 1) and (2, 3), both \
             (0, 2)-sequences; an independent pair of draws has no t-value guarantee.\n\n",
        )
    } else {
        format!(
            "t-values of the projections of one `zjoint` group of {} dimensions (Sobol' \
             dimensions 0 to {}: the draw at dimension `d` of a group reads `d` and `d + 1`) \
             as base-2 nets of `2^m` points; 0 is a perfect net, `m` no stratification at \
             all. The first draw's pair (0, 1) is a (0, 2)-sequence; an independent pair of \
             draws (any two of `zsobol`, or of two groups) has no t-value guarantee.\n\n",
            args.group,
            args.group - 1
        )
    };
    text += "Every pair of dimensions:\n\n";
    text += &header("dimensions");
    for pair in subsets(dims, 2) {
        let row: Vec<String> = ms
            .iter()
            .map(|&m| t_of(&pair, m, 2).map(|t| t.to_string()))
            .collect::<Result<_, _>>()?;
        text += &format!("| {}, {} | {} |\n", pair[0], pair[1], row.join(" | "));
    }
    if args.group >= 4 {
        let quads = subsets(dims, 4);
        text += &format!(
            "\nEvery set of four dimensions ({} sets): the largest t, the mean t, and the \
             first draw pair with the second, dimensions 0-3; then dimensions 0-3 as a \
             base-4 net of `4^(m/2)` points (boxes of sides `4^-a`; 0 for a (0,4)-sequence \
             in base 4):\n\n",
            quads.len()
        );
        text += &header("sets of four");
        let mut worst = Vec::new();
        let mut mean = Vec::new();
        let mut first = Vec::new();
        let mut base4 = Vec::new();
        for &m in &ms {
            let ts: Vec<u32> = quads
                .iter()
                .map(|q| t_of(q, m, 2))
                .collect::<Result<_, _>>()?;
            worst.push(ts.iter().max().copied().unwrap_or(0).to_string());
            mean.push(format!(
                "{:.2}",
                ts.iter().sum::<u32>() as f64 / ts.len() as f64
            ));
            first.push(t_of(&[0, 1, 2, 3], m, 2)?.to_string());
            base4.push(t_of(&[0, 1, 2, 3], m / 2, 4)?.to_string());
        }
        text += &format!("| largest | {} |\n", worst.join(" | "));
        text += &format!("| mean | {} |\n", mean.join(" | "));
        text += &format!("| 0, 1, 2, 3 | {} |\n", first.join(" | "));
        text += &format!("| 0, 1, 2, 3 in base 4 | {} |\n", base4.join(" | "));
    }
    Ok(text)
}

fn main() -> ExitCode {
    common::run("nets", || {
        let Some(args) = parse()? else {
            return Ok(());
        };
        let text = tables(&args)?;
        outln!("{text}")?;
        if let Some(m) = &args.markdown {
            common::write_markdown_section(m, &section(&args), &text)?;
        }
        Ok(())
    })
}
