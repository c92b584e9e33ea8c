//! Point sets from and to files: CSV and the two formats of UTK (the Unified Toolkit for
//! sampling, Heitz et al.), so that sets made by other tools can be measured with this crate's
//! tools and ours read by theirs.
//!
//! * **CSV**: one point per line, coordinates separated by commas, an optional header line
//!   (any line whose first field is not a number, before the first point), blank lines ignored,
//!   comment lines starting with `#` before the first point (numpy's `savetxt` header). One set
//!   per file: a `#` line after a point is refused (sets separated by `#` lines are UTK text).
//!   This is what `points` prints.
//! * **UTK text**: one point per line, coordinates separated by spaces, no header; sets
//!   separated by lines that start with `#` (UTK writes `#` between sets, none after the last).
//! * **UTK binary** (`.bin`), little-endian: the magic `0x214B5455` (the bytes `UTK!`), a
//!   data-type byte (0 `i32`, 1 `i64`, 2 `u32`, 3 `u64`, 4 `f32`, 5 `f64`) and three reserved
//!   bytes, then `u32` counts: sets, points per set, dimensions; then the coordinates, point
//!   after point, set after set. Only `f32` and `f64` data are point coordinates here.
//!
//! Text lines end in LF or CR LF; a carriage return alone (classic Mac OS) is refused with the
//! line it ends. Every coordinate must lie in `[0, 1)` and every set must hold at least one point of the
//! same dimension; a file holds at most [`MAX_SETS`] sets (a bound on the memory of many small
//! sets, checked before they are read). Malformed input is an [`strata::Error::InvalidInput`] that names the line (text) or
//! the byte offset (binary) and what is allowed; nothing panics, and nothing is allocated
//! beyond the size of the input (the binary reader checks the header's counts against the
//! file length before reading).

use std::io::Write;
use std::path::Path;

use crate::{Error, Result};
use strata::Point2;

/// Who reports the errors.
const CONTEXT: &str = "pointsets";

/// The most sets a file may hold (`2^16`). Each set costs its coordinates plus a fixed overhead
/// in every tool that reads it (a row of `measure`'s tables, about 0.5 KiB), so a file of
/// millions of one-point sets would take a hundred times its size: the readers refuse more sets
/// than this before reading them (UTK binary: from the header; text: at the first set past it).
pub const MAX_SETS: usize = 1 << 16;

/// The error for a file of more than [`MAX_SETS`] sets.
fn too_many_sets(what: String) -> Error {
    Error::input(
        CONTEXT,
        format!("{what}: at most {MAX_SETS} sets per file (split it, or merge its sets)"),
    )
}

/// The UTK binary magic number, `UTK!` as little-endian bytes.
pub const UTK_MAGIC: u32 = 0x214B_5455;

/// Bytes of a UTK binary header.
pub const UTK_HEADER_BYTES: usize = 20;

/// One point set: `dims` coordinates per point, point after point.
#[derive(Clone, Debug, PartialEq)]
pub struct PointSet {
    /// Coordinates per point (at least 1).
    pub dims: u32,
    /// The coordinates, point-major (`coords[i * dims + k]` is coordinate `k` of point `i`).
    pub coords: Vec<f64>,
}

impl PointSet {
    /// A set from point-major coordinates; checks the shape and that every coordinate is in
    /// `[0, 1)`.
    pub fn new(coords: Vec<f64>, dims: u32) -> Result<Self> {
        let width = dims as usize;
        if dims == 0 || coords.is_empty() || !coords.len().is_multiple_of(width) {
            return Err(Error::input(
                CONTEXT,
                format!(
                    "{} coordinates do not make points of {dims} dimensions; a set needs at \
                     least one point and at least one dimension",
                    coords.len()
                ),
            ));
        }
        if let Some((i, v)) = coords.iter().enumerate().find(|(_, v)| !in_unit(**v)) {
            return Err(Error::input(
                CONTEXT,
                format!(
                    "point {}, coordinate {}: {v} is outside [0, 1)",
                    i / width,
                    i % width
                ),
            ));
        }
        Ok(PointSet { dims, coords })
    }

    /// A 2D set from `f32` points.
    pub fn from_points(points: &[Point2]) -> Self {
        PointSet {
            dims: 2,
            coords: points
                .iter()
                .flat_map(|p| [p[0] as f64, p[1] as f64])
                .collect(),
        }
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.coords.len() / self.width().max(1)
    }

    /// True when the set has no points (never for a set built by [`PointSet::new`] or read).
    pub fn is_empty(&self) -> bool {
        self.coords.is_empty()
    }

    /// Point `i`'s coordinates.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.coords[i * self.width()..(i + 1) * self.width()]
    }

    /// [`dims`](Self::dims) as an index width.
    fn width(&self) -> usize {
        self.dims as usize
    }

    /// The points as [`Point2`] (rounded to `f32` toward zero, so they stay below 1), for a 2D
    /// set; `None` otherwise.
    pub fn points_2d(&self) -> Option<Vec<Point2>> {
        (self.dims == 2).then(|| {
            self.coords
                .chunks_exact(2)
                .map(|c| {
                    [
                        strata::float::unit_f32_from_f64(c[0]),
                        strata::float::unit_f32_from_f64(c[1]),
                    ]
                })
                .collect()
        })
    }
}

fn in_unit(v: f64) -> bool {
    (0.0..1.0).contains(&v)
}

/// A point-set file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Format {
    /// Comma-separated values, optional header.
    Csv,
    /// UTK's text format.
    UtkText,
    /// UTK's binary format.
    UtkBin,
}

impl Format {
    /// The names `points --format` takes.
    pub const NAMES: [&'static str; 3] = ["csv", "utk", "bin"];

    /// The format named `csv`, `utk` or `bin`.
    pub fn by_name(name: &str) -> Result<Self> {
        match name {
            "csv" => Ok(Format::Csv),
            "utk" => Ok(Format::UtkText),
            "bin" => Ok(Format::UtkBin),
            other => Err(Error::parameter(
                CONTEXT,
                "format",
                other,
                "csv, utk (UTK text) or bin (UTK binary)",
            )),
        }
    }

    /// The format of a file: binary when it starts with the UTK magic; CSV when its first
    /// non-blank line has a comma or starts with something other than a number (a header:
    /// UTK text has none); UTK text otherwise.
    pub fn detect(bytes: &[u8]) -> Self {
        if bytes.len() >= 4
            && u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]) == UTK_MAGIC
        {
            return Format::UtkBin;
        }
        let text = String::from_utf8_lossy(&bytes[..bytes.len().min(4096)]);
        let first = text
            .lines()
            .map(str::trim)
            .find(|l| !l.is_empty() && !l.starts_with('#'));
        match first {
            Some(l)
                if l.contains(',')
                    || l.split_whitespace()
                        .next()
                        .is_some_and(|t| t.parse::<f64>().is_err()) =>
            {
                Format::Csv
            }
            _ => Format::UtkText,
        }
    }
}

/// The largest point file [`read_file`] reads: 512 MiB.
pub const MAX_FILE_BYTES: u64 = 512 << 20;

/// Reads every point set of a file, in the format its content shows ([`Format::detect`]).
///
/// At most [`MAX_FILE_BYTES`] are read: a larger file, or a device or pipe that gives more (such
/// as `/dev/zero`), is an error, never an unbounded read.
pub fn read_file(path: impl AsRef<Path>) -> Result<Vec<PointSet>> {
    use std::io::Read;
    let path = path.as_ref();
    let too_large = || {
        Error::io(
            path.display().to_string(),
            format!("more than {MAX_FILE_BYTES} bytes, the most a point file may hold"),
        )
    };
    let file = std::fs::File::open(path).map_err(|e| Error::io(path.display().to_string(), e))?;
    if file
        .metadata()
        .is_ok_and(|m| m.is_file() && m.len() > MAX_FILE_BYTES)
    {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Error::io(path.display().to_string(), e))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large());
    }
    parse(&bytes).map_err(|e| match e {
        Error::Strata(strata::Error::InvalidInput { message, .. }) => {
            Error::input(CONTEXT, format!("{}: {message}", path.display()))
        }
        other => other,
    })
}

/// Parses point sets in the format the bytes show.
pub fn parse(bytes: &[u8]) -> Result<Vec<PointSet>> {
    // a UTF-8 byte-order mark before text
    let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    match Format::detect(bytes) {
        Format::UtkBin => parse_utk_bin(bytes),
        format => {
            let text = std::str::from_utf8(bytes).map_err(|e| {
                Error::input(
                    CONTEXT,
                    format!(
                        "byte {}: not UTF-8 text (and not a UTK binary file: no UTK! magic)",
                        e.valid_up_to()
                    ),
                )
            })?;
            if format == Format::Csv {
                parse_csv(text).map(|s| vec![s])
            } else {
                parse_utk_text(text)
            }
        }
    }
}

/// Parses one number of a text line (`line` counts from 1).
fn number(token: &str, line: usize, column: usize) -> Result<f64> {
    let v: f64 = token.trim().parse().map_err(|_| {
        Error::input(
            CONTEXT,
            format!(
                "line {line}, column {column}: '{}' is not a number",
                token.trim()
            ),
        )
    })?;
    if !in_unit(v) {
        // the text as written, and the number it reads as when that differs (0.99999999999999999
        // is 1 as a double)
        let text = token.trim();
        let read = if text.parse::<f64>().ok().map(|x| x.to_string()) == Some(text.to_string()) {
            String::new()
        } else {
            format!(" (read as {v})")
        };
        return Err(Error::input(
            CONTEXT,
            format!("line {line}, column {column}: '{text}'{read} is outside [0, 1)"),
        ));
    }
    Ok(v)
}

/// Collects the rows of a text format into sets: `rows` yields (line number, fields) for data
/// lines and `None` for set separators.
fn collect_sets<'a>(
    rows: impl Iterator<Item = (usize, Option<Vec<&'a str>>)>,
) -> Result<Vec<PointSet>> {
    let mut sets = Vec::new();
    let mut current: Option<(usize, usize, Vec<f64>)> = None; // (dims, first line, coords)
    let finish = |sets: &mut Vec<PointSet>, current: &mut Option<(usize, usize, Vec<f64>)>| {
        if let Some((dims, _, coords)) = current.take() {
            // the row's field count was checked to fit a `u32` where the set started
            sets.push(PointSet {
                dims: dims as u32,
                coords,
            });
        }
    };
    for (line, row) in rows {
        let Some(fields) = row else {
            finish(&mut sets, &mut current);
            continue;
        };
        if current.is_none() && sets.len() >= MAX_SETS {
            return Err(too_many_sets(format!(
                "line {line} starts set {}",
                sets.len() + 1
            )));
        }
        if current.is_none() && u32::try_from(fields.len()).is_err() {
            return Err(Error::input(
                CONTEXT,
                format!(
                    "line {line}: {} values per point; at most {} dimensions",
                    fields.len(),
                    u32::MAX
                ),
            ));
        }
        let (dims, first, coords) = current.get_or_insert((fields.len(), line, Vec::new()));
        if fields.len() != *dims {
            return Err(Error::input(
                CONTEXT,
                format!(
                    "line {line}: {} values, but the set that starts on line {first} has {dims} \
                     per point",
                    fields.len()
                ),
            ));
        }
        for (c, f) in fields.iter().enumerate() {
            coords.push(number(f, line, c + 1)?);
        }
    }
    finish(&mut sets, &mut current);
    if sets.is_empty() {
        return Err(Error::input(CONTEXT, "no points: the input holds no set"));
    }
    Ok(sets)
}

/// Refuses a carriage return that does not end a line with a line feed: lines would run
/// together (`0.1,0.2\r0.3,0.4` reads as one line).
fn check_line_ends(text: &str) -> Result<()> {
    let bytes = text.as_bytes();
    match bytes
        .iter()
        .enumerate()
        .find(|&(i, &b)| b == b'\r' && bytes.get(i + 1) != Some(&b'\n'))
    {
        Some((i, _)) => Err(Error::input(
            CONTEXT,
            format!(
                "line {} ends with a carriage return alone (classic Mac OS line ends); allowed: \
                 lines ending in LF or CR LF",
                bytes[..i].iter().filter(|&&b| b == b'\n').count() + 1
            ),
        )),
        None => Ok(()),
    }
}

/// Parses a CSV point set: `#` comment lines and at most one header line (the first other
/// non-empty line, when none of its fields is a number) before the first point, then one point
/// per line. A UTF-8 byte-order mark at the start is skipped. A later line that is not all
/// numbers is an error that names its line and column; so is a later `#` line (CSV holds one
/// set; `#`-separated sets are UTK text).
pub fn parse_csv(text: &str) -> Result<PointSet> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    check_line_ends(text)?;
    let mut first = true;
    let mut points = false;
    let mut late_comment = None;
    let rows = text.lines().enumerate().filter_map(|(i, l)| {
        let l = l.trim();
        if l.is_empty() || late_comment.is_some() {
            return None;
        }
        if l.starts_with('#') {
            if points {
                late_comment = Some(i + 1);
            }
            return None;
        }
        let fields: Vec<&str> = l.split(',').map(str::trim).collect();
        let header = first && fields.iter().all(|f| f.parse::<f64>().is_err());
        first = false;
        if header {
            return None;
        }
        points = true;
        Some((i + 1, Some(fields)))
    });
    let mut sets = collect_sets(rows)?;
    if let Some(line) = late_comment {
        return Err(Error::input(
            CONTEXT,
            format!(
                "line {line}: a '#' line after the first point; a CSV file holds one set, with \
                 '#' comments only before its first point (sets separated by '#' lines are UTK \
                 text: coordinates separated by spaces)"
            ),
        ));
    }
    Ok(sets.remove(0))
}

/// Parses UTK text: points as lines of space-separated coordinates, sets separated by lines
/// starting with `#`. Blank lines are skipped (UTK's own reader would misread them).
pub fn parse_utk_text(text: &str) -> Result<Vec<PointSet>> {
    check_line_ends(text)?;
    let rows = text.lines().enumerate().filter_map(|(i, l)| {
        let l = l.trim();
        if l.is_empty() {
            None
        } else if l.starts_with('#') {
            Some((i + 1, None))
        } else {
            Some((i + 1, Some(l.split_whitespace().collect())))
        }
    });
    collect_sets(rows)
}

/// Parses UTK binary data (see the [module docs](self)).
pub fn parse_utk_bin(bytes: &[u8]) -> Result<Vec<PointSet>> {
    let bad = |message: String| Error::input(CONTEXT, format!("UTK binary: {message}"));
    if bytes.len() < UTK_HEADER_BYTES {
        return Err(bad(format!(
            "{} bytes, but the header alone takes {UTK_HEADER_BYTES}",
            bytes.len()
        )));
    }
    let u32_at =
        |o: usize| u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
    if u32_at(0) != UTK_MAGIC {
        return Err(bad(format!(
            "bytes 0-3 are {:02x?}, not the magic 'UTK!' (55 54 4b 21)",
            &bytes[..4]
        )));
    }
    let width = match bytes[4] {
        4 => 4usize,
        5 => 8,
        t @ 0..=3 => {
            return Err(bad(format!(
                "byte 4: data type {t} is an integer type; point coordinates must be f32 (4) or \
                 f64 (5)"
            )));
        }
        t => {
            return Err(bad(format!(
                "byte 4: data type {t} is not one of UTK's (0-5); coordinates must be f32 (4) or \
                 f64 (5)"
            )));
        }
    };
    let (sets, points, dims) = (u32_at(8) as u64, u32_at(12) as u64, u32_at(16) as u64);
    if sets == 0 || points == 0 || dims == 0 {
        return Err(bad(format!(
            "bytes 8-19: {sets} sets of {points} points of {dims} dimensions; each count must \
             be at least 1"
        )));
    }
    let data = bytes.len() - UTK_HEADER_BYTES;
    let expected = sets
        .checked_mul(points)
        .and_then(|v| v.checked_mul(dims))
        .and_then(|v| v.checked_mul(width as u64));
    if expected != Some(data as u64) {
        return Err(bad(format!(
            "the header (bytes 8-19) announces {sets} sets x {points} points x {dims} \
             dimensions x {width} bytes = {} bytes of data, but {data} bytes follow it",
            expected.map_or("more than 2^64".to_string(), |e| e.to_string())
        )));
    }
    if sets > MAX_SETS as u64 {
        return Err(too_many_sets(format!(
            "UTK binary: the header (bytes 8-11) announces {sets} sets"
        )));
    }
    let (points, dims) = (points as usize, dims as usize);
    let values = bytes[UTK_HEADER_BYTES..].chunks_exact(width).map(|c| {
        if width == 4 {
            f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64
        } else {
            f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]])
        }
    });
    let mut out: Vec<PointSet> = Vec::with_capacity(sets as usize);
    let per_set = points * dims;
    let mut coords = Vec::with_capacity(per_set);
    for (i, v) in values.enumerate() {
        if !in_unit(v) {
            return Err(bad(format!(
                "byte {}: set {}, point {}, coordinate {}: {v} is outside [0, 1)",
                UTK_HEADER_BYTES + i * width,
                i / per_set,
                i % per_set / dims,
                i % dims
            )));
        }
        coords.push(v);
        if coords.len() == per_set {
            out.push(PointSet {
                dims: dims as u32, // read from the header's 32 bits
                coords: std::mem::replace(&mut coords, Vec::with_capacity(per_set)),
            });
        }
    }
    Ok(out)
}

/// Checks that all sets have the same shape (UTK binary needs it) and returns it.
fn common_shape(sets: &[PointSet]) -> Result<(usize, usize)> {
    let Some(first) = sets.first() else {
        return Err(Error::input(CONTEXT, "nothing to write: no set"));
    };
    let shape = (first.len(), first.width());
    if let Some((i, s)) = sets
        .iter()
        .enumerate()
        .find(|(_, s)| (s.len(), s.width()) != shape)
    {
        return Err(Error::input(
            CONTEXT,
            format!(
                "set {i} has {} points of {} dimensions, set 0 has {} of {}: a UTK binary file \
                 holds sets of one shape",
                s.len(),
                s.dims,
                shape.0,
                shape.1
            ),
        ));
    }
    Ok(shape)
}

fn write_err(e: std::io::Error) -> Error {
    Error::io("<output>", e)
}

/// Writes sets in `format`: CSV takes one set (with a header `x,y` or `x0,x1,...`); UTK text
/// separates sets with `#`; UTK binary writes `f64` coordinates. Numbers in the text formats
/// use Rust's shortest round-trip form, so reading them back gives the same values.
pub fn write(sets: &[PointSet], format: Format, out: &mut impl Write) -> Result<()> {
    if format == Format::Csv && sets.len() != 1 {
        return Err(Error::input(
            CONTEXT,
            format!("CSV holds one set, not {}", sets.len()),
        ));
    }
    if format == Format::UtkBin {
        common_shape(sets)?;
    }
    let views: Vec<(usize, &[f64])> = sets.iter().map(|s| (s.width(), &s.coords[..])).collect();
    write_values(out, format, &views)
}

/// Writes one set of `f32` coordinates (`dims` per point) in `format`, as `points` does: the
/// text formats print each value as the shortest decimal that reads back as the same `f64`
/// (the `f32` widened, so that a reader parsing `f64`, this module's or numpy's, gets the
/// generated value exactly: the shortest `f32` form can read back as an `f64` just beside it,
/// across a dyadic cell edge); UTK binary stores `f32` (data type 4).
pub fn write_f32(values: &[f32], dims: u32, format: Format, out: &mut impl Write) -> Result<()> {
    if dims == 0 || values.is_empty() || !values.len().is_multiple_of(dims as usize) {
        return Err(Error::input(
            CONTEXT,
            format!(
                "{} values do not make points of {dims} dimensions",
                values.len()
            ),
        ));
    }
    if format == Format::UtkBin {
        return write_values(out, format, &[(dims as usize, values)]);
    }
    let wide: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
    write_values(out, format, &[(dims as usize, &wide[..])])
}

/// The writers' common part: sets as (dims, point-major values) of any number type.
fn write_values<T: Copy + std::fmt::Display + Bytes>(
    out: &mut impl Write,
    format: Format,
    sets: &[(usize, &[T])],
) -> Result<()> {
    let rows = |out: &mut dyn Write, dims: usize, values: &[T], sep: &str| -> Result<()> {
        let mut line = String::new();
        for p in values.chunks_exact(dims) {
            line.clear();
            for (k, v) in p.iter().enumerate() {
                if k > 0 {
                    line.push_str(sep);
                }
                line.push_str(&v.to_string());
            }
            line.push('\n');
            out.write_all(line.as_bytes()).map_err(write_err)?;
        }
        Ok(())
    };
    match format {
        Format::Csv => {
            for &(dims, values) in sets {
                let header = if dims == 2 {
                    "x,y".to_string()
                } else {
                    (0..dims)
                        .map(|d| format!("x{d}"))
                        .collect::<Vec<_>>()
                        .join(",")
                };
                writeln!(out, "{header}").map_err(write_err)?;
                rows(out, dims, values, ",")?;
            }
        }
        Format::UtkText => {
            for (i, &(dims, values)) in sets.iter().enumerate() {
                if i > 0 {
                    writeln!(out, "#").map_err(write_err)?;
                }
                rows(out, dims, values, " ")?;
            }
        }
        Format::UtkBin => {
            let (dims, first) = sets[0];
            let count = |v: usize, what: &str| {
                u32::try_from(v).map_err(|_| {
                    Error::input(CONTEXT, format!("{v} {what}: UTK binary counts are 32-bit"))
                })
            };
            let mut header = Vec::with_capacity(UTK_HEADER_BYTES);
            header.extend_from_slice(&UTK_MAGIC.to_le_bytes());
            header.extend_from_slice(&[T::UTK_TYPE, 0, 0, 0]);
            header.extend_from_slice(&count(sets.len(), "sets")?.to_le_bytes());
            header.extend_from_slice(&count(first.len() / dims, "points")?.to_le_bytes());
            header.extend_from_slice(&count(dims, "dimensions")?.to_le_bytes());
            out.write_all(&header).map_err(write_err)?;
            let mut buf = Vec::new();
            for &(_, values) in sets {
                buf.clear();
                for v in values {
                    v.extend_le(&mut buf);
                }
                out.write_all(&buf).map_err(write_err)?;
            }
        }
    }
    Ok(())
}

/// A coordinate type of UTK binary files.
trait Bytes {
    /// UTK's data-type byte.
    const UTK_TYPE: u8;
    /// Appends the little-endian bytes.
    fn extend_le(&self, out: &mut Vec<u8>);
}

impl Bytes for f32 {
    const UTK_TYPE: u8 = 4;
    fn extend_le(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

impl Bytes for f64 {
    const UTK_TYPE: u8 = 5;
    fn extend_le(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sets() -> Vec<PointSet> {
        vec![
            PointSet::new(vec![0.1, 0.2, 0.6, 0.7, 0.3, 0.9], 2).unwrap(),
            PointSet::new(vec![0.25, 0.5, 0.75, 0.0, 0.5, 0.999_999_999], 2).unwrap(),
        ]
    }

    fn written(format: Format, sets: &[PointSet]) -> Vec<u8> {
        let mut out = Vec::new();
        write(sets, format, &mut out).unwrap();
        out
    }

    #[test]
    fn every_format_reads_back_what_it_wrote() {
        let s = sets();
        for format in [Format::UtkText, Format::UtkBin] {
            let bytes = written(format, &s);
            assert_eq!(Format::detect(&bytes), format);
            assert_eq!(parse(&bytes).unwrap(), s, "{format:?}");
        }
        let bytes = written(Format::Csv, &s[..1]);
        assert_eq!(Format::detect(&bytes), Format::Csv);
        assert_eq!(parse(&bytes).unwrap(), s[..1]);
    }

    #[test]
    fn utk_text_is_as_utk_writes_it() {
        // '#' between sets, none after the last; UTK's own fixed-point digits parse too
        let text = "0.10000000000000001 0.20000000000000001\n0.59999999999999998 \
                    0.69999999999999996\n#\n0.25000000000000000 0.50000000000000000\n";
        let s = parse_utk_text(text).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].coords, vec![0.1, 0.2, 0.6, 0.7]);
        assert_eq!(s[1].len(), 1);
        assert_eq!(
            String::from_utf8(written(Format::UtkText, &sets())).unwrap(),
            "0.1 0.2\n0.6 0.7\n0.3 0.9\n#\n0.25 0.5\n0.75 0\n0.5 0.999999999\n"
        );
    }

    #[test]
    fn utk_binary_header_is_byte_exact() {
        let b = written(Format::UtkBin, &sets());
        assert_eq!(&b[..4], b"UTK!");
        assert_eq!(b[4], 5);
        assert_eq!(&b[8..20], &[2, 0, 0, 0, 3, 0, 0, 0, 2, 0, 0, 0]);
        assert_eq!(b.len(), 20 + 2 * 3 * 2 * 8);
        assert_eq!(f64::from_le_bytes(b[20..28].try_into().unwrap()), 0.1);
    }

    #[test]
    fn csv_takes_a_header_or_none() {
        let with = parse_csv("x,y\n0.5,0.25\n\n0.125,0.75\n").unwrap();
        let without = parse_csv("0.5, 0.25\n0.125,0.75").unwrap();
        assert_eq!(with, without);
        assert_eq!(with.dims, 2);
    }

    fn message(r: Result<impl std::fmt::Debug>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn comments_before_the_points_and_line_ends_that_end_lines() {
        // '#' lines and CR-only line ends once got messages that named neither
        let plain = parse_csv("0.5,0.25\n0.125,0.75\n").unwrap();
        assert_eq!(
            parse_csv("# made by numpy\n#x,y\nx,y\n0.5,0.25\r\n0.125,0.75\n").unwrap(),
            plain
        );
        let m = message(parse_csv("0.5,0.25\n# set 2\n0.125,0.75\n"));
        assert!(
            m.contains("line 2") && m.contains("'#'") && m.contains("UTK"),
            "{m}"
        );
        let m = message(parse_csv("x,y\n0.5,0.25\n#\n"));
        assert!(m.contains("line 3") && m.contains("'#'"), "{m}");
        for text in ["0.5,0.25\r0.125,0.75\r", "x,y\n0.5,0.25\r0.125,0.75"] {
            let m = message(parse_csv(text));
            assert!(m.contains("carriage return alone"), "{m}");
        }
        let m = message(parse_utk_text("0.5 0.25\n0.1 0.2\r0.125 0.75\r"));
        assert!(
            m.contains("line 2 ends with a carriage return alone"),
            "{m}"
        );
        let m = message(parse(b"0.5,0.25\r0.125,0.75\r"));
        assert!(m.contains("carriage return alone"), "{m}");
    }

    #[test]
    fn malformed_text_names_the_line() {
        let m = message(parse_csv("x,y\n0.1,0.2\n0.3\n"));
        assert!(m.contains("line 3") && m.contains("1 values"), "{m}");
        let m = message(parse_csv("0.1,0.2\n0.3,abc\n"));
        assert!(
            m.contains("line 2, column 2") && m.contains("not a number"),
            "{m}"
        );
        let m = message(parse_utk_text("0.1 0.2\n0.3 1.0\n"));
        assert!(
            m.contains("line 2, column 2") && m.contains("outside [0, 1)"),
            "{m}"
        );
        let m = message(parse_utk_text("0.1 -0.2\n"));
        assert!(m.contains("outside"), "{m}");
        let m = message(parse_utk_text("# nothing\n\n#\n"));
        assert!(m.contains("no points"), "{m}");
        let m = message(parse_csv("x,y\n"));
        assert!(m.contains("no points"), "{m}");
        let m = message(parse_utk_text("0.1 0.2\n0.1 0.2 0.3\n"));
        assert!(
            m.contains("line 2") && m.contains("starts on line 1"),
            "{m}"
        );
        // each UTK set takes its dimension from its first line
        let dims: Vec<u32> = parse_utk_text("0.1 0.2\n#\n0.1 0.2 0.3\n")
            .unwrap()
            .iter()
            .map(|s| s.dims)
            .collect();
        assert_eq!(dims, [2, 3]);
        let m = message(parse(b"\xff\xfe0.1 0.2"));
        assert!(m.contains("byte 0") && m.contains("UTF-8"), "{m}");
        let m = message(parse_csv("0.1,NaN\n"));
        assert!(m.contains("line 1, column 2"), "{m}");
    }

    #[test]
    fn malformed_binary_names_the_bytes() {
        let good = written(Format::UtkBin, &sets());
        let m = message(parse_utk_bin(&good[..12]));
        assert!(m.contains("12 bytes") && m.contains("header"), "{m}");
        let m = message(parse_utk_bin(&good[..good.len() - 3]));
        assert!(
            m.contains("announces") && m.contains("93 bytes follow"),
            "{m}"
        );
        let mut b = good.clone();
        b[4] = 9;
        assert!(message(parse_utk_bin(&b)).contains("byte 4: data type 9"));
        b[4] = 2;
        assert!(message(parse_utk_bin(&b)).contains("integer"));
        let mut b = good.clone();
        b[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(message(parse_utk_bin(&b)).contains("announces"));
        let mut b = good.clone();
        b[8..12].copy_from_slice(&0u32.to_le_bytes());
        assert!(message(parse_utk_bin(&b)).contains("at least 1"));
        let mut b = good.clone();
        b[28..36].copy_from_slice(&1.5f64.to_le_bytes());
        let m = message(parse_utk_bin(&b));
        assert!(
            m.contains("byte 28") && m.contains("point 0, coordinate 1"),
            "{m}"
        );
        let mut b = good;
        b[0] = b'X';
        assert!(message(parse_utk_bin(&b)).contains("magic"));
    }

    #[test]
    fn f32_sets_keep_their_exact_values_in_every_format() {
        let values = [0.1f32, 0.7, 0.333_333_34, 0.999_999_94];
        for format in [Format::Csv, Format::UtkText, Format::UtkBin] {
            let mut out = Vec::new();
            write_f32(&values, 2, format, &mut out).unwrap();
            let back = parse(&out).unwrap();
            let got: Vec<f32> = back[0].coords.iter().map(|&v| v as f32).collect();
            assert_eq!(got, values, "{format:?}");
        }
        let mut out = Vec::new();
        write_f32(&values, 2, Format::UtkBin, &mut out).unwrap();
        assert_eq!(out[4], 4);
        assert_eq!(out.len(), 20 + 4 * 4);
    }

    #[test]
    fn writers_refuse_what_their_format_cannot_hold() {
        let mut s = sets();
        assert!(write(&s, Format::Csv, &mut Vec::new()).is_err());
        s[1] = PointSet::new(vec![0.5; 3], 3).unwrap();
        let m = write(&s, Format::UtkBin, &mut Vec::new())
            .unwrap_err()
            .to_string();
        assert!(m.contains("one shape"), "{m}");
        assert!(write(&[], Format::UtkBin, &mut Vec::new()).is_err());
        assert!(PointSet::new(vec![0.5; 3], 2).is_err());
        assert!(PointSet::new(vec![0.5, 1.0], 2).is_err());
    }
}
