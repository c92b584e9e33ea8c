//! Shared command-line plumbing of the example programs: parsing numbers with messages that say
//! what is allowed, and one-line errors with a non-zero exit status.

#![allow(dead_code)]

use std::fmt::Display;
use std::process::ExitCode;

/// The largest count the example programs accept (the library itself may go further).
pub const MAX_CLI_COUNT: u64 = 1 << 26;

/// A command-line failure: a one-line message for stderr (exit status 2), or standard output
/// closed under the program (a pipe whose reader left: exit quietly with status 141, as a
/// process ended by `SIGPIPE` appears to the shell).
#[derive(Debug)]
pub enum CliError {
    /// What went wrong, for stderr.
    Message(String),
    /// Standard output is a closed pipe.
    BrokenPipe,
}

impl<E: std::error::Error> From<E> for CliError {
    fn from(e: E) -> Self {
        CliError::Message(e.to_string())
    }
}

/// Shorthand for a `CliError` from anything printable.
pub fn cli_error(msg: impl Display) -> CliError {
    CliError::Message(msg.to_string())
}

/// Runs `body`, printing its error as one line on stderr (exit status 2); standard output is
/// flushed and checked at the end, and a closed pipe ends the program quietly (status 141).
pub fn run(program: &str, body: impl FnOnce() -> Result<(), CliError>) -> ExitCode {
    remove_temporaries_on_interrupt();
    let result = body().and_then(|()| {
        use std::io::Write;
        std::io::stdout().flush().map_err(stdout_error)
    });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::BrokenPipe) => ExitCode::from(141),
        Err(CliError::Message(msg)) => {
            let one_line = msg.replace('\n', " ");
            eprintln!("{program}: error: {one_line}");
            ExitCode::from(2)
        }
    }
}

/// On `SIGINT`, `SIGTERM` and `SIGHUP`: the temporary files of writes in progress removed
/// ([`strata_lab::io::remove_pending_temporaries`]), then the signal's default action (the
/// program ends as it would have).
fn remove_temporaries_on_interrupt() {
    #[cfg(target_os = "linux")]
    {
        extern "C" fn on_signal(sig: libc::c_int) {
            strata_lab::io::remove_pending_temporaries();
            // SAFETY: signal and raise are async-signal-safe; the default action ends the
            // program as the signal would have
            unsafe {
                libc::signal(sig, libc::SIG_DFL);
                libc::raise(sig);
            }
        }
        for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            // SAFETY: installs a handler that calls only async-signal-safe functions; a
            // signal the parent ignored (nohup) stays ignored
            unsafe {
                let mut old: libc::sigaction = core::mem::zeroed();
                if libc::sigaction(sig, core::ptr::null(), &mut old) == 0
                    && old.sa_sigaction == libc::SIG_IGN
                {
                    continue;
                }
                let mut action: libc::sigaction = core::mem::zeroed();
                action.sa_sigaction = on_signal as extern "C" fn(libc::c_int) as usize;
                // no second signal interrupts the handler halfway through its removals
                libc::sigemptyset(&mut action.sa_mask);
                for other in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
                    libc::sigaddset(&mut action.sa_mask, other);
                }
                libc::sigaction(sig, &action, core::ptr::null_mut());
            }
        }
    }
}

/// A failed write to standard output: a closed pipe, or another error (a full device...).
pub fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::BrokenPipe
    } else {
        cli_error(format!("writing to standard output: {e}"))
    }
}

/// Writes `text` to standard output, flushed, every failure said (see [`stdout_error`]).
pub fn out(text: impl Display) -> Result<(), CliError> {
    use std::io::Write;
    let mut o = std::io::stdout().lock();
    write!(o, "{text}")
        .and_then(|()| o.flush())
        .map_err(stdout_error)
}

/// `println!` that fails instead of panicking: [`out`] with a newline; use with `?`.
#[macro_export]
macro_rules! outln {
    () => {
        $crate::common::out("\n")
    };
    ($($arg:tt)*) => {
        $crate::common::out(format_args!("{}\n", format_args!($($arg)*)))
    };
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
    if b.contains(',') {
        // three or more numbers: the whole value is named, not its tail (N23)
        return Err(bad());
    }
    Ok((parse_int(flag, a, 0, max)?, parse_int(flag, b, 0, max)?))
}

/// Parses the command line by `command` (a clap declaration: the options, their help, defaults
/// and allowed values, written once): the matches, or `None` after `--help` (the help printed
/// on stdout), or a one-line error (clap's message, its lines joined, the usage and the tip of
/// a close flag kept). Repeated flags: the last one wins.
pub fn clap_matches(command: clap::Command) -> Result<Option<clap::ArgMatches>, CliError> {
    clap_matches_from(command, std::env::args_os())
}

/// [`clap_matches`] on the given arguments (the first is the program).
pub fn clap_matches_from(
    command: clap::Command,
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> Result<Option<clap::ArgMatches>, CliError> {
    let command = command
        .args_override_self(true)
        .allow_negative_numbers(true)
        .disable_version_flag(true)
        // the same text on every terminal (docs/cli.md holds it)
        .term_width(HELP_WIDTH)
        .max_term_width(HELP_WIDTH)
        .help_template(HELP_TEMPLATE);
    match command.try_get_matches_from(args) {
        Ok(m) => Ok(Some(m)),
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelp => {
            out(format!("{}\n", e.render().to_string().trim_end()))?;
            Ok(None)
        }
        Err(e) => Err(cli_error(one_line(&e.render().to_string()))),
    }
}

/// The width of every program's help.
const HELP_WIDTH: usize = 96;

/// The help's layout for every program: what it does, the usage, the options, then notes.
const HELP_TEMPLATE: &str = "{about-with-newline}\nUsage: {usage}\n\n{all-args}{after-help}";

/// A clap message on one line: its lines joined, without the `error: ` prefix and the closing
/// pointer to `--help`.
fn one_line(message: &str) -> String {
    let mut out = String::new();
    for line in message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("For more information"))
    {
        if !out.is_empty() {
            out.push_str(if out.ends_with(':') { " " } else { "; " });
        }
        out.push_str(line.trim_start_matches("error: "));
    }
    out
}

/// A clap value parser of a whole number from `min` to `max` (which must fit `T`), with
/// [`parse_int`]'s message: "--FLAG V is out of range; allowed: MIN to MAX".
pub fn whole<T>(
    flag: &'static str,
    min: u64,
    max: u64,
) -> impl clap::builder::TypedValueParser<Value = T>
where
    T: TryFrom<u64> + Clone + Send + Sync + 'static,
{
    move |v: &str| -> Result<T, String> {
        let n = parse_int(flag, v, min, max).map_err(|e| match e {
            CliError::Message(m) => m,
            CliError::BrokenPipe => String::new(),
        })?;
        T::try_from(n).map_err(|_| format!("{flag} {n}: too large for this option"))
    }
}

/// A clap value parser from a function giving one-line messages (`Err` of a [`CliError`]
/// message, which clap shows after "invalid value 'V' for '--FLAG'").
pub fn value_parser<T: Clone + Send + Sync + 'static>(
    f: fn(&str) -> Result<T, CliError>,
) -> impl clap::builder::TypedValueParser<Value = T> {
    move |v: &str| match f(v) {
        Ok(t) => Ok(t),
        Err(CliError::Message(m)) => Err(m),
        Err(CliError::BrokenPipe) => Err("standard output is closed".to_string()),
    }
}

/// The sampler parameters as options of `command`, one per name some sampler declares (from
/// the registry: each sampler's help, range and default), under their own heading.
pub fn with_sampler_params(mut command: clap::Command) -> clap::Command {
    use strata_lab::registry;
    for name in registry::parameter_names() {
        let kind = registry::parameter_kind(name).map_or("", |k| k.name());
        let mut help = format!("a {kind}, for the samplers that take it:");
        for (e, p) in registry::parameters().filter(|(_, p)| p.is_named(name)) {
            let alias = if p.name == name {
                String::new()
            } else {
                format!(" [an alias of its --{}]", p.name)
            };
            help.push_str(&format!(
                "\n- {}: {} ({}, default {}){alias}",
                e.name,
                p.help,
                p.allowed(),
                p.default
            ));
        }
        command = command.arg(
            clap::Arg::new(name)
                .long(name)
                .value_name("X")
                .help(help)
                .help_heading("Sampler parameters"),
        );
    }
    command
}

/// The sampler parameters given on the command line ([`with_sampler_params`]) into `params`,
/// each parsed by its kind within the widest range a sampler declares for it.
pub fn read_sampler_params(
    matches: &clap::ArgMatches,
    params: &mut strata_lab::registry::Params,
) -> Result<(), CliError> {
    for name in strata_lab::registry::parameter_names() {
        if let Some(v) = matches.get_one::<String>(name) {
            sampler_param(name, v, params)?;
        }
    }
    Ok(())
}

/// Reads the value `v` of the sampler parameter `--flag` into `params`, parsed by the
/// kind its declaration gives and within the widest range any sampler declares for it (each
/// sampler's own range is checked when it is built).
fn sampler_param(
    flag: &str,
    v: &str,
    params: &mut strata_lab::registry::Params,
) -> Result<(), CliError> {
    use strata_lab::registry::{self, Bound, Kind};
    let dashed = format!("--{flag}");
    let specs: Vec<_> = registry::parameters()
        .filter(|(_, p)| p.is_named(flag))
        .map(|(_, p)| p)
        .collect();
    let Some(first) = specs.first() else {
        return Err(cli_error(format!("--{flag} is not a sampler parameter")));
    };
    let end = |b: &Bound| match *b {
        Bound::Closed(v) | Bound::Open(v) => v,
        _ => f64::NAN,
    };
    let lo = specs
        .iter()
        .map(|p| end(&p.min))
        .fold(f64::INFINITY, f64::min);
    let hi = specs
        .iter()
        .map(|p| end(&p.max))
        .fold(f64::NEG_INFINITY, f64::max);
    let value = match first.kind {
        Kind::Whole => parse_int(&dashed, v, lo as u64, hi as u64)? as f64,
        _ => parse_open_float(&dashed, v, lo, hi)?,
    };
    params.set(flag, value);
    Ok(())
}

/// The path-tracer sequences for `--help`, from their declarations (`Sequence::NAMES`): every
/// name, and the Z-ordered ones (those that take the image's resolution), comma-separated and
/// wrapped to `width` columns after an indent of `indent` spaces (the first line starts at
/// column `first`).
pub fn sequence_help(z_only: bool, first: usize, indent: usize, width: usize) -> String {
    use strata::Sequence;
    let names: Vec<String> = Sequence::NAMES
        .iter()
        .filter(|n| !z_only || Sequence::by_name(n, [1, 1]).is_ok_and(|s| s.resolution().is_some()))
        .map(|n| {
            if *n == "zjoint" && !z_only {
                "zjoint, zjoint-G (groups of G dimensions)".to_string()
            } else {
                n.to_string()
            }
        })
        .collect();
    let text = names.join(", ");
    let mut out = String::new();
    let mut column = first;
    for (i, word) in text.split(' ').enumerate() {
        if i > 0 && column + 1 + word.len() > width {
            out.push('\n');
            out.push_str(&" ".repeat(indent));
            column = indent;
        } else if i > 0 {
            out.push(' ');
            column += 1;
        }
        out.push_str(word);
        column += word.len();
    }
    out
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
    // the arguments as the shell takes them back (any bytes, UTF-8 or not), and never a
    // marker: `<`, `>` and `!` are always escaped
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| shell_quote(&a))
        .collect();
    let program = std::env::args_os()
        .next()
        .and_then(|p| std::path::Path::new(&p).file_stem().map(shell_quote))
        .unwrap_or_default();
    let section = format!(
        "{begin}\n<!-- written by `cargo run --release --example {program} -- {}` -->\n\n{}\n\n{end}",
        args.join(" "),
        body.trim_end()
    );
    // programs run side by side into one file take turns: the read, the splice and the
    // rename under one lock, or the last writer's copy would drop the others' sections
    let _turn = DirectoryLock::take(path)?;
    let old = read_markdown(path)?;
    let new = splice_section(path, &old, name, &section)?;
    strata_lab::io::write_text(path, &new)?;
    Ok(())
}

/// An exclusive advisory lock (`flock`) on the directory of the file a write lands in (the
/// target of a symbolic link: writers through a link and writers of its target take the same
/// lock), held until dropped: the file itself cannot carry it, since each writer renames a new
/// file over it. On systems other than Linux, no lock (concurrent `--markdown` runs into one
/// file may lose sections).
struct DirectoryLock {
    #[cfg(target_os = "linux")]
    _dir: std::fs::File,
}

impl DirectoryLock {
    /// The directory whose lock guards `path`, opened (an error naming it when it cannot be:
    /// the lock needs it readable).
    #[cfg(target_os = "linux")]
    fn open(path: &std::path::Path) -> Result<(std::path::PathBuf, std::fs::File), CliError> {
        let target = strata_lab::io::write_target(path)?;
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => std::path::PathBuf::from("."),
        };
        let f = std::fs::create_dir_all(&dir)
            .and_then(|()| std::fs::File::open(&dir))
            .map_err(|e| {
                cli_error(format!(
                    "--markdown {}: its directory {} cannot be opened to take turns with other \
                     writers ({e}); it must be readable",
                    path.display(),
                    dir.display()
                ))
            })?;
        Ok((dir, f))
    }

    fn take(path: &std::path::Path) -> Result<Self, CliError> {
        #[cfg(target_os = "linux")]
        {
            use std::os::fd::AsRawFd;
            let (dir, f) = Self::open(path)?;
            let lock = |how| {
                // SAFETY: flock on a file descriptor this function owns, open for its lifetime
                if unsafe { libc::flock(f.as_raw_fd(), how) } == 0 {
                    Ok(())
                } else {
                    Err(std::io::Error::last_os_error())
                }
            };
            match lock(libc::LOCK_EX | libc::LOCK_NB) {
                Ok(()) => {}
                Err(e) if e.raw_os_error() == Some(libc::EWOULDBLOCK) => {
                    // another writer has it: say so, and who, then wait
                    eprintln!(
                        "--markdown {}: waiting for another writer of {} ({}) to finish",
                        path.display(),
                        dir.display(),
                        lock_holder(&f).unwrap_or_else(|| "its process is unknown".into())
                    );
                    lock(libc::LOCK_EX).map_err(|e| {
                        cli_error(format!(
                            "{}: cannot lock the directory for --markdown: {e}",
                            dir.display()
                        ))
                    })?;
                }
                Err(e) => {
                    return Err(cli_error(format!(
                        "{}: cannot lock the directory for --markdown: {e}",
                        dir.display()
                    )));
                }
            }
            Ok(DirectoryLock { _dir: f })
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = path;
            Ok(DirectoryLock {})
        }
    }
}

/// The process holding a `flock` on the open directory `f`, from `/proc/locks` (its lines
/// `N: FLOCK ADVISORY WRITE PID MAJ:MIN:INODE 0 EOF`): "process PID: its command line".
#[cfg(target_os = "linux")]
fn lock_holder(f: &std::fs::File) -> Option<String> {
    use std::os::unix::fs::MetadataExt;
    let meta = f.metadata().ok()?;
    let dev = meta.dev();
    // the file as /proc/locks names it: MAJOR:MINOR (hexadecimal) and the inode
    let (major, minor) = (libc::major(dev), libc::minor(dev));
    let locks = std::fs::read_to_string("/proc/locks").ok()?;
    let pid = locks.lines().find_map(|line| {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let at = fields.iter().position(|&w| w == "FLOCK")?;
        let (pid, file) = (fields.get(at + 3)?, fields.get(at + 4)?);
        let mut parts = file.split(':');
        let maj = u32::from_str_radix(parts.next()?, 16).ok()?;
        let min = u32::from_str_radix(parts.next()?, 16).ok()?;
        let ino: u64 = parts.next()?.parse().ok()?;
        (maj == major && min == minor && ino == meta.ino()).then(|| pid.to_string())
    })?;
    let cmdline = std::fs::read(format!("/proc/{pid}/cmdline")).unwrap_or_default();
    let words: Vec<String> = cmdline
        .split(|&b| b == 0)
        .filter(|w| !w.is_empty())
        .map(|w| {
            use std::os::unix::ffi::OsStrExt;
            shell_quote(std::ffi::OsStr::from_bytes(w))
        })
        .collect();
    Some(format!("process {pid}: {}", words.join(" ")))
}

/// `arg` as a shell word: as it is when it holds only letters, digits and `_ . / , = : + - @ %`,
/// else in bash's `$'...'` quoting with every other byte as `\xNN` (so a recorded command line
/// can be pasted back, whatever its bytes, and never holds `<`, `>` or `!`, which could close
/// or open a Markdown comment or a section marker).
pub fn shell_quote(arg: &std::ffi::OsStr) -> String {
    let bytes = arg.as_encoded_bytes();
    let plain = |b: u8| b.is_ascii_alphanumeric() || b"_./,=:+-@%".contains(&b);
    if !bytes.is_empty() && bytes.iter().all(|&b| plain(b)) {
        return String::from_utf8_lossy(bytes).into_owned();
    }
    let mut q = String::from("$'");
    for &b in bytes {
        if plain(b) || b == b' ' {
            q.push(b as char);
        } else {
            q.push_str(&format!("\\x{b:02x}"));
        }
    }
    q.push('\'');
    q
}

/// `old` with section `name` set to `section` (the library's rules,
/// `strata_lab::io::markdown`), or an error naming `path` and saying it was left untouched.
fn splice_section(
    path: &std::path::Path,
    old: &str,
    name: &str,
    section: &str,
) -> Result<String, CliError> {
    strata_lab::io::markdown::splice_section(old, name, section).map_err(|e| {
        cli_error(format!(
            "{}: {}; the file was left untouched",
            path.display(),
            e.to_string().trim_start_matches("markdown: ")
        ))
    })
}

/// Checks, before any work, that `--markdown FILE` can be rewritten: an error now rather than
/// after the work when it is not a regular UTF-8 file, when the file or its directory cannot be
/// written, or when the directory cannot be opened for the lock writers take turns with. A
/// file with other hard links gets a note: the rewrite gives this name a new file.
pub fn check_markdown(path: &std::path::Path, name: &str) -> Result<(), CliError> {
    let flag = format!("--markdown {}", path.display());
    let (begin, end) = strata_lab::io::markdown::markers(name);
    splice_section(path, &read_markdown(path)?, name, &format!("{begin}{end}"))?;
    strata_lab::io::check_writable(path).map_err(|e| cli_error(format!("--markdown: {e}")))?;
    #[cfg(target_os = "linux")]
    DirectoryLock::open(path)?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let Ok(m) = std::fs::metadata(path)
            && m.nlink() > 1
        {
            eprintln!(
                "{flag}: the file has {} other hard link(s); the rewrite gives this name a new \
                 file and the other names keep the old text",
                m.nlink() - 1
            );
        }
    }
    Ok(())
}

/// The largest Markdown file `--markdown` rewrites.
const MAX_MARKDOWN_BYTES: u64 = 16 << 20;

/// The current text of a Markdown file that `--markdown` rewrites: empty when it does not exist
/// yet; an error (and nothing written) when it is not a regular file, cannot be read, is larger
/// than 16 MiB, or is not UTF-8.
fn read_markdown(path: &std::path::Path) -> Result<String, CliError> {
    use std::io::Read;
    let untouched = |why: String| {
        cli_error(format!(
            "{}: {why}; --markdown rewrites a regular UTF-8 Markdown file, which was left \
             untouched",
            path.display()
        ))
    };
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(String::new()),
        Err(e) => return Err(untouched(format!("cannot be read ({e})"))),
    };
    if !meta.is_file() {
        return Err(untouched("not a regular file".to_string()));
    }
    if meta.len() > MAX_MARKDOWN_BYTES {
        return Err(untouched(format!(
            "{} bytes, more than {MAX_MARKDOWN_BYTES}",
            meta.len()
        )));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_MARKDOWN_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| untouched(format!("cannot be read ({e})")))?;
    String::from_utf8(bytes).map_err(|e| {
        untouched(format!(
            "not UTF-8 text (an invalid byte at offset {})",
            e.utf8_error().valid_up_to()
        ))
    })
}

/// A progress line on stderr when it is not a terminal (where the progress bar is hidden):
/// logs and CI see how far a long run got.
pub fn progress_line(text: impl Display) {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        eprintln!("{text}");
    }
}

/// Checks, before any work, that the output directory `dir` of flag `flag` (`--out`) can be
/// written: created when missing, and a probe file made in it (without a name on Linux, so
/// an interrupt leaves nothing). An empty path, a path that is a file, or a directory that
/// cannot be written is an error that names the flag and the directory.
pub fn check_output_dir(flag: &str, dir: &std::path::Path) -> Result<(), CliError> {
    if dir.as_os_str().is_empty() {
        return Err(cli_error(format!(
            "{flag}: an empty directory name; give a directory, e.g. {flag} out"
        )));
    }
    if dir.exists() && !dir.is_dir() {
        return Err(cli_error(format!(
            "{flag} {}: exists and is not a directory",
            dir.display()
        )));
    }
    strata_lab::io::check_writable_dir(dir)
        .map_err(|e| cli_error(format!("{flag} {}: cannot be written ({e})", dir.display())))
}

/// The peak resident memory of this process in bytes (`VmHWM` of `/proc/self/status`), where
/// the system reports it (Linux).
pub fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib << 10)
}
