//! Pictures and files: PNG drawings of point sets and spectra, EXR and
//! CSV files, and plots with axes and labels.
//!
//! Raster pictures come from a small software rasterizer on an RGB8 [`Canvas`]; plots are drawn
//! by `plotters` into the same kind of buffer with a bundled font (DejaVu Sans), so nothing here
//! needs a system library and the output is reproducible byte for byte.

mod canvas;
pub mod markdown;
mod plot;

pub use canvas::{Canvas, Rgb};
pub use plot::{
    LinePlot, Marker, PALETTE, Series, label, overview_row_label, panel_grid, radial_plot,
};

use std::io::Write;
use std::path::Path;

use crate::spectrum::{RadialBin, Spectrum};
use crate::{Error, Result};
use strata::{Point2, StrataGrid};

/// Writes `canvas` as an 8-bit RGB PNG (the `png` crate: balanced compression, adaptive
/// filters), as [`write_file`] writes: never half written, every byte checked.
pub fn write_png(path: impl AsRef<Path>, canvas: &Canvas) -> Result<()> {
    let path = path.as_ref();
    let fail = |e: png::EncodingError| crate::Error::io(path.display().to_string(), e);
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, canvas.width(), canvas.height());
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Balanced);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(fail)?;
    writer.write_image_data(canvas.data()).map_err(fail)?;
    writer.finish().map_err(fail)?;
    write_file(path, &bytes)
}

/// Writes `bytes` to `path` so that a failure never leaves a truncated file, and says every
/// failure: the file named and the operating system's reason.
///
/// A regular file, or a path where nothing exists yet, is written to a temporary file in the
/// same directory, flushed to the disk and renamed over the target, so that a full disk or a
/// crash in mid-write leaves the old file whole (a symbolic link is followed: its target is
/// replaced, the link kept, and a link to nothing yet makes its target; the old file's
/// permissions are kept). On Linux the temporary file
/// has no name while it is written (`O_TMPFILE`), so an interrupted program (Ctrl-C, a kill)
/// leaves nothing behind: a new file is linked under its own name when complete, and one that
/// replaces a file is named (`.strata-PID-N.tmp`, short whatever the target's name) only for
/// the instant between being linked into the directory and renamed over the target.
/// Where `/proc` is not mounted (a chroot, a build sandbox) and the process may not link a
/// descriptor directly, the temporary file is named from the start. A program's signal handler
/// removes a named temporary file on an interrupt with [`remove_pending_temporaries`]. A file
/// with several hard links becomes a new file under the name given (as with any rename): the
/// other names keep the old contents.
/// A target the user could not write is refused, not replaced: a read-only file (no write
/// permission bit) or one that cannot be opened for writing. Anything else (a device such as
/// `/dev/stdout` or `/dev/full`, a pipe) is written in place and flushed, and a failed write is
/// an error. A missing parent directory is created.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("strata-doc-{}", std::process::id()));
/// let path = dir.join("a.txt");
/// strata_lab::io::write_file(&path, b"hello")?;
/// assert_eq!(std::fs::read(&path).unwrap(), b"hello");
/// # std::fs::remove_dir_all(&dir).unwrap();
/// // a full device: an error, not a silent truncated file
/// # #[cfg(target_os = "linux")]
/// assert!(strata_lab::io::write_file("/dev/full", b"hello").is_err());
/// # Ok::<(), strata_lab::Error>(())
/// ```
pub fn write_file(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    let fail = |e: std::io::Error| Error::io(path.display().to_string(), e);
    let meta = std::fs::metadata(path);
    match refusal(path, meta.as_ref().ok())? {
        WriteMode::InPlace => return write_in_place(path, bytes),
        WriteMode::Replaced | WriteMode::New => {}
    }
    let target = write_target(path)?;
    create_parent(&target)?;
    let dir = directory_of(&target);
    if target.file_name().is_none() {
        return Err(Error::io(path.display().to_string(), "not a file name"));
    }
    static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!(".strata-{}-{n}.tmp", std::process::id()));
    let fill = |mut f: std::fs::File| -> std::io::Result<std::fs::File> {
        f.write_all(bytes)?;
        f.flush()?;
        f.sync_all()?;
        if let Ok(m) = &meta {
            f.set_permissions(m.permissions())?;
        }
        Ok(f)
    };
    let result = (|| {
        if let Some(f) = temporary::unnamed(&dir) {
            let f = fill(f)?;
            // a new file is linked under its own name at once (nothing named is ever left);
            // one that exists is replaced through the short-lived temporary name
            if meta.is_err() {
                match temporary::link(&f, &target) {
                    Ok(()) => return Ok(()),
                    Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
                    // no way to name an unnamed file here (no `/proc`, no privilege): the
                    // named temporary file below
                    Err(_) => return write_named(&tmp, &target, fill),
                }
            }
            let _armed = pending::arm(&tmp);
            return match temporary::link(&f, &tmp) {
                Ok(()) => std::fs::rename(&tmp, &target).inspect_err(|_| {
                    let _ = std::fs::remove_file(&tmp);
                }),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Err(e),
                Err(_) => write_named(&tmp, &target, fill),
            };
        }
        write_named(&tmp, &target, fill)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        fail(e)
    })
}

/// The named path of [`write_file`]: `tmp` created, filled by `fill` and renamed over
/// `target`, its name registered for [`remove_pending_temporaries`] meanwhile.
fn write_named(
    tmp: &Path,
    target: &Path,
    fill: impl Fn(std::fs::File) -> std::io::Result<std::fs::File>,
) -> std::io::Result<()> {
    let _armed = pending::arm(tmp);
    let result = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(tmp)
        .and_then(fill)
        .and_then(|_| std::fs::rename(tmp, target));
    if result.is_err() {
        // removed while the name is still registered (an interrupt now leaves nothing)
        let _ = std::fs::remove_file(tmp);
    }
    result
}

/// What [`write_file`] does with a path, from its metadata (`None`: nothing there).
enum WriteMode {
    /// Not a regular file (a device, a pipe): written in place.
    InPlace,
    /// A regular file the user may write: replaced.
    Replaced,
    /// Nothing yet: made.
    New,
}

/// The error [`write_file`] gives `path` before writing anything (an empty name, a directory,
/// a file the user could not write), or what it will do.
fn refusal(path: &Path, meta: Option<&std::fs::Metadata>) -> Result<WriteMode> {
    let refuse = |why: &str| Err(Error::io(path.display().to_string(), why));
    if path.as_os_str().is_empty() {
        return refuse("an empty file name");
    }
    match meta {
        None => Ok(WriteMode::New),
        Some(m) if m.is_dir() => refuse("a directory, not a file"),
        Some(m) if !m.is_file() => Ok(WriteMode::InPlace),
        Some(m) => {
            // what the user could not write by redirection is not replaced behind their back
            // (renaming needs only the directory's permission)
            let writable = !m.permissions().readonly()
                && std::fs::OpenOptions::new().write(true).open(path).is_ok();
            if writable {
                Ok(WriteMode::Replaced)
            } else {
                refuse(
                    "the file is read-only (or not writable by you), so it was not replaced: \
                     make it writable or write elsewhere",
                )
            }
        }
    }
}

/// The file [`write_file`] writes for `path`: `path` itself, with every symbolic link on the
/// way followed, also a link whose target does not exist yet (the file is then made where it
/// points, the link kept, as a shell's redirection does). Programs that let writers of one
/// file take turns lock this file's directory, so that a writer through a link and a writer of
/// the file itself take the same lock.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("strata-doc-target-{}", std::process::id()));
/// std::fs::create_dir_all(dir.join("a")).unwrap();
/// std::fs::create_dir_all(dir.join("b")).unwrap();
/// # #[cfg(target_os = "linux")]
/// # {
/// // a/r.md -> ../b/r.md, which does not exist yet: the file will be made in b
/// std::os::unix::fs::symlink("../b/r.md", dir.join("a/r.md")).unwrap();
/// let target = strata_lab::io::write_target(dir.join("a/r.md"))?;
/// assert_eq!(target, dir.join("b").canonicalize().unwrap().join("r.md"));
/// # }
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), strata_lab::Error>(())
/// ```
pub fn write_target(path: impl AsRef<Path>) -> Result<std::path::PathBuf> {
    let path = path.as_ref();
    let fail = |e: std::io::Error| Error::io(path.display().to_string(), e);
    let at = if std::fs::metadata(path).is_ok() {
        std::fs::canonicalize(path).map_err(fail)?
    } else {
        dangling_target(path).map_err(fail)?
    };
    // the directory's own links resolved too (the file itself does not exist yet)
    match (at.parent(), at.file_name()) {
        (Some(dir), Some(name)) if !dir.as_os_str().is_empty() => match dir.canonicalize() {
            Ok(dir) => Ok(dir.join(name)),
            Err(_) => Ok(at),
        },
        _ => Ok(at),
    }
}

/// Checks, before any work, that [`write_file`] will be able to write `path`: the refusals it
/// would give (an empty name, a directory, a file the user cannot write), and in the
/// directory it writes into (created when missing) a new file can be made. The probe on Linux
/// is a file without a name (`O_TMPFILE`), so an interrupted check leaves nothing behind;
/// elsewhere a named file, removed at once.
pub fn check_writable(path: impl AsRef<Path>) -> Result<()> {
    let path = path.as_ref();
    let meta = std::fs::metadata(path);
    if let WriteMode::InPlace = refusal(path, meta.as_ref().ok())? {
        // a device or a pipe: its permission bits only (opening a pipe would wait for a
        // reader, or end a waiting reader's input)
        return match &meta {
            Ok(m) if m.permissions().readonly() => Err(Error::io(
                path.display().to_string(),
                "not writable (no write permission)",
            )),
            _ => Ok(()),
        };
    }
    let target = write_target(path)?;
    check_writable_dir(directory_of(&target))
}

/// Checks, before any work, that files can be written into the directory `dir` (created when
/// missing): a probe file is made there, without a name on Linux (nothing is left behind even
/// if the program is interrupted), elsewhere named and removed at once.
pub fn check_writable_dir(dir: impl AsRef<Path>) -> Result<()> {
    let dir = dir.as_ref();
    let fail = |e: std::io::Error| Error::io(dir.display().to_string(), e);
    std::fs::create_dir_all(dir).map_err(fail)?;
    if temporary::unnamed(dir).is_some() {
        return Ok(());
    }
    let probe = dir.join(format!(".strata-probe-{}", std::process::id()));
    let _armed = pending::arm(&probe);
    std::fs::write(&probe, b"")
        .and_then(|()| std::fs::remove_file(&probe))
        .map_err(fail)
}

/// The directory a file is written into (`.` for a bare name).
fn directory_of(path: &Path) -> std::path::PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    }
}

/// Removes the temporary files that writes in progress have named, for a program's handler of
/// `SIGINT` or `SIGTERM` (then nothing named `.strata-*` is left by an interrupt). It only
/// reads static buffers and calls `unlink`, which a signal handler may do. A write has a named
/// temporary file only in the instant it replaces an existing file (between linking its
/// unnamed file and renaming it over the old one) or where files cannot be unnamed. On Linux
/// only: elsewhere no name is registered and this does nothing. Call it from a handler that
/// ends the process: a name it removed is never registered again.
pub fn remove_pending_temporaries() {
    pending::remove_all();
}

/// The named temporary files of writes in progress, in static buffers that a signal handler
/// reads ([`remove_pending_temporaries`]): a few slots, each a path and its state.
mod pending {
    use std::path::Path;

    /// The registration of one path, released when dropped.
    pub(super) struct Armed(#[cfg(target_os = "linux")] Option<&'static linux::Slot>);

    /// Registers `path` until the returned value is dropped (not at all when every slot is
    /// taken, the path is too long, or the system is not Linux: then an interrupt may leave
    /// it).
    pub(super) fn arm(path: &Path) -> Armed {
        #[cfg(target_os = "linux")]
        {
            Armed(linux::arm(path))
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = path;
            Armed()
        }
    }

    /// Unlinks every armed path (Linux; nothing elsewhere).
    pub(super) fn remove_all() {
        #[cfg(target_os = "linux")]
        linux::remove_all();
    }

    #[cfg(target_os = "linux")]
    impl Drop for Armed {
        fn drop(&mut self) {
            if let Some(slot) = self.0 {
                linux::release(slot);
            }
        }
    }

    #[cfg(target_os = "linux")]
    mod linux {
        use core::cell::UnsafeCell;
        use core::sync::atomic::{AtomicU8, Ordering};
        use std::path::Path;

        /// The longest path kept (with its NUL); longer ones are not registered.
        const LEN: usize = 4096;

        /// Free: a writer may take the slot.
        const FREE: u8 = 0;
        /// Being written by the writer that took it.
        const WRITING: u8 = 1;
        /// Holds a path that a handler may remove.
        const ARMED: u8 = 2;
        /// Taken by a handler, which reads the path; never freed again (the process ends).
        const CLAIMED: u8 = 3;

        /// One registered path and its state.
        pub(super) struct Slot {
            state: AtomicU8,
            path: UnsafeCell<[u8; LEN]>,
        }

        // SAFETY: `path` is written only by the writer that moved `state` from FREE to WRITING,
        // until it stores ARMED (release); it is read only by the handler that moved `state`
        // from ARMED to CLAIMED (acquire), after which no one writes it again: a slot leaves
        // CLAIMED never. So no read overlaps a write.
        unsafe impl Sync for Slot {}

        static SLOTS: [Slot; 8] = [const {
            Slot {
                state: AtomicU8::new(FREE),
                path: UnsafeCell::new([0; LEN]),
            }
        }; 8];

        pub(super) fn arm(path: &Path) -> Option<&'static Slot> {
            use std::os::unix::ffi::OsStrExt;
            let bytes = path.as_os_str().as_bytes();
            if bytes.len() >= LEN || bytes.contains(&0) {
                return None;
            }
            let slot = SLOTS.iter().find(|slot| {
                slot.state
                    .compare_exchange(FREE, WRITING, Ordering::Acquire, Ordering::Relaxed)
                    .is_ok()
            })?;
            // SAFETY: this thread owns the slot (WRITING) until it stores ARMED
            let buf = unsafe { &mut *slot.path.get() };
            buf[..bytes.len()].copy_from_slice(bytes);
            buf[bytes.len()] = 0;
            slot.state.store(ARMED, Ordering::Release);
            Some(slot)
        }

        /// Frees the slot, unless a handler has claimed it.
        pub(super) fn release(slot: &Slot) {
            let _ = slot
                .state
                .compare_exchange(ARMED, FREE, Ordering::Release, Ordering::Relaxed);
        }

        pub(super) fn remove_all() {
            for slot in &SLOTS {
                if slot
                    .state
                    .compare_exchange(ARMED, CLAIMED, Ordering::Acquire, Ordering::Relaxed)
                    .is_ok()
                {
                    // SAFETY: a claimed slot holds a NUL-terminated path that no one writes
                    // again; unlink is async-signal-safe
                    unsafe { libc::unlink(slot.path.get().cast::<libc::c_char>()) };
                }
            }
        }
    }
}

/// Where `path` leads when it does not exist: itself, or for a symbolic link (a chain of them)
/// whose target does not exist, that target (relative targets from the link's directory).
fn dangling_target(path: &Path) -> std::io::Result<std::path::PathBuf> {
    let mut at = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&at) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&at)?;
                at = match at.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            _ => return Ok(at),
        }
    }
    Err(std::io::Error::other(
        "too many levels of symbolic links (more than 40)",
    ))
}

/// The temporary file of [`write_file`]: unnamed on Linux, linked under its name when it is
/// complete; named from the start elsewhere (and where the file system has no unnamed files).
mod temporary {
    use std::fs::File;
    use std::path::Path;

    /// A new file without a name in `dir` (Linux's `O_TMPFILE`), or `None` where the system or
    /// the file system has none.
    pub(super) fn unnamed(dir: &Path) -> Option<File> {
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::fs::OpenOptionsExt;
            std::fs::OpenOptions::new()
                .write(true)
                .custom_flags(libc::O_TMPFILE)
                .mode(0o666)
                .open(dir)
                .ok()
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = dir;
            None
        }
    }

    /// Links the unnamed `file` into its directory as `name`: through `/proc/self/fd`, which
    /// needs no privilege, or where `/proc` is not mounted by the descriptor itself
    /// (`AT_EMPTY_PATH`, which needs `CAP_DAC_READ_SEARCH`); fails if `name` exists, or if
    /// neither way is open.
    pub(super) fn link(file: &File, name: &Path) -> std::io::Result<()> {
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::ffi::OsStrExt;
            use std::os::unix::io::AsRawFd;
            let from = std::ffi::CString::new(format!("/proc/self/fd/{}", file.as_raw_fd()))?;
            let to = std::ffi::CString::new(name.as_os_str().as_bytes())?;
            // SAFETY: both are valid NUL-terminated paths for the duration of the call.
            let rc = unsafe {
                libc::linkat(
                    libc::AT_FDCWD,
                    from.as_ptr(),
                    libc::AT_FDCWD,
                    to.as_ptr(),
                    libc::AT_SYMLINK_FOLLOW,
                )
            };
            if rc == 0 {
                return Ok(());
            }
            let first = std::io::Error::last_os_error();
            if first.kind() == std::io::ErrorKind::AlreadyExists {
                return Err(first);
            }
            // SAFETY: an open descriptor, an empty NUL-terminated path and a valid target path
            let rc = unsafe {
                libc::linkat(
                    file.as_raw_fd(),
                    c"".as_ptr(),
                    libc::AT_FDCWD,
                    to.as_ptr(),
                    libc::AT_EMPTY_PATH,
                )
            };
            if rc != 0 {
                let second = std::io::Error::last_os_error();
                if second.kind() == std::io::ErrorKind::AlreadyExists {
                    return Err(second);
                }
                return Err(first);
            }
            Ok(())
        }
        #[cfg(not(target_os = "linux"))]
        {
            let _ = (file, name);
            Err(std::io::Error::other("unnamed files exist only on Linux"))
        }
    }
}

/// Writes into something that is not a regular file (a device, a pipe), checking every write.
fn write_in_place(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut f = std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(|e| Error::io(path.display().to_string(), e))?;
    f.write_all(bytes)
        .and_then(|()| f.flush())
        .map_err(|e| Error::io(path.display().to_string(), e))
}

/// Creates the directory `path` will be written into, if it has one and it is missing.
pub(crate) fn create_parent(path: &Path) -> Result<()> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => {
            std::fs::create_dir_all(dir).map_err(|e| Error::io(dir.display().to_string(), e))
        }
        _ => Ok(()),
    }
}

/// Draws a point set on a white square of `size` pixels: strata grids as light lines (each
/// only when its cells are at least 3 pixels wide; the first, coarsest, grid darker), then the
/// points as dark dots whose radius shrinks with the number of points. `y` points up, as in the
/// papers' figures.
pub fn draw_points(points: &[Point2], grids: &[StrataGrid], size: u32) -> Canvas {
    let mut canvas = Canvas::new(size, size, Rgb::WHITE);
    let s = size as f32;
    for (level, grid) in grids.iter().enumerate().rev() {
        draw_grid(
            &mut canvas,
            grid,
            Rgb::grey(if level == 0 { 190 } else { 225 }),
        );
    }
    let radius = (s / (points.len().max(1) as f32).sqrt() * 0.18).clamp(0.9, 5.0);
    for p in points {
        canvas.disc(p[0] * s, (1.0 - p[1]) * s, radius, Rgb::new(20, 40, 120));
    }
    canvas.frame(Rgb::grey(120));
    canvas
}

/// Draws the cell boundaries of `grid` over the whole (square) canvas, unless the cells would be
/// 3 pixels or narrower.
fn draw_grid(canvas: &mut Canvas, grid: &StrataGrid, colour: Rgb) {
    let size = canvas.width();
    for (cells, vertical) in [(grid.columns, true), (grid.rows, false)] {
        if cells < 2 || size as f32 / cells as f32 <= 3.0 {
            continue;
        }
        for k in 1..cells {
            let t = (k as f64 / cells as f64 * size as f64).round() as i64;
            if vertical {
                canvas.vline(t, colour);
            } else {
                canvas.hline(size as i64 - 1 - t, colour);
            }
        }
    }
}

/// Draws the 2D projections of a `dims`-dimensional point set (`values` point-major) as a
/// `dims x dims` matrix of `tile`-pixel scatter plots: tile (row `i`, column `j`) plots
/// dimension `j` across against dimension `i` up; the diagonal shows each 1D projection as
/// ticks along a line. `strata[y * dims + x]`, when given, is the grid the projection onto
/// dimensions `x` (across) and `y` (up) is stratified on, drawn under the points (an empty
/// slice draws none).
pub fn draw_projections(
    values: &[f32],
    dims: u32,
    tile: u32,
    strata: &[Option<StrataGrid>],
) -> Canvas {
    let gap = 4u32;
    let side = dims * (tile + gap) + gap;
    let dims = dims as usize;
    let mut canvas = Canvas::new(side, side, Rgb::grey(235));
    let n = values.len() / dims.max(1);
    let radius = (tile as f32 / (n.max(1) as f32).sqrt() * 0.16).clamp(0.7, 3.0);
    for i in 0..dims {
        for j in 0..dims {
            let mut t = Canvas::new(tile, tile, Rgb::WHITE);
            if let Some(Some(grid)) = strata.get(i * dims + j) {
                draw_grid(&mut t, grid, Rgb::grey(205));
            }
            let s = tile as f32;
            for p in values.chunks_exact(dims) {
                if i == j {
                    let x = (p[j] * s) as i64;
                    for y in (tile as i64 / 2 - 6)..(tile as i64 / 2 + 6) {
                        t.blend(x, y, Rgb::new(20, 40, 120), 0.35);
                    }
                } else {
                    t.disc(p[j] * s, (1.0 - p[i]) * s, radius, Rgb::new(20, 40, 120));
                }
            }
            t.frame(Rgb::grey(150));
            let x0 = (gap + j as u32 * (tile + gap)) as i64;
            let y0 = (gap + i as u32 * (tile + gap)) as i64;
            canvas.paste(&t, x0, y0);
        }
    }
    canvas
}

/// The log-scale range of [`draw_spectrum`]: `P` from `10^LOW` (black) to `10^HIGH` (white), so
/// white noise (`P = 1`) is a mid grey and every picture shares one scale.
pub const SPECTRUM_LOG_RANGE: (f64, f64) = (-2.0, 1.0);

/// Draws a spectrum as a grey-scale image, log-scaled over [`SPECTRUM_LOG_RANGE`], DC in the
/// centre (drawn white), `v` pointing up, each frequency a square of `scale` pixels.
pub fn draw_spectrum(spectrum: &Spectrum, scale: u32) -> Canvas {
    let side = spectrum.side() as u32;
    let scale = scale.max(1);
    let mut canvas = Canvas::new(side * scale, side * scale, Rgb::BLACK);
    let h = (side / 2) as i32;
    let (lo, hi) = SPECTRUM_LOG_RANGE;
    for v in -h..=h {
        for u in -h..=h {
            let p = spectrum.get(u, v).expect("inside");
            let t = if u == 0 && v == 0 {
                1.0
            } else if p > 0.0 {
                ((p.log10() - lo) / (hi - lo)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let c = Rgb::grey((t * 255.0).round() as u8);
            let (x0, y0) = ((u + h) as u32 * scale, (h - v) as u32 * scale);
            for y in y0..y0 + scale {
                for x in x0..x0 + scale {
                    canvas.set(x as i64, y as i64, c);
                }
            }
        }
    }
    canvas
}

/// Writes a spectrum as a single-channel (`Y`), 32-bit float OpenEXR image, unscaled, in the
/// orientation of [`draw_spectrum`] (row 0 is `v = +K/2`, column 0 is `u = -K/2`).
pub fn write_spectrum_exr(path: impl AsRef<Path>, spectrum: &Spectrum) -> Result<()> {
    use exr::prelude::*;
    let path = path.as_ref();
    let side = spectrum.side();
    let mut values = Vec::with_capacity(side * side);
    for row in (0..side).rev() {
        values.extend(
            spectrum.values()[row * side..(row + 1) * side]
                .iter()
                .map(|&v| v as f32),
        );
    }
    let channel = AnyChannel::new("Y", FlatSamples::F32(values));
    let layer = Layer::new(
        (side, side),
        LayerAttributes::named("power spectrum"),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(vec![channel].into()),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| crate::Error::io(path.display().to_string(), e))?;
    write_file(path, &bytes.into_inner())
}

/// Reads a single-channel `Y` f32 EXR written by [`write_spectrum_exr`]: `(width, height,
/// values row-major from the top row)`.
pub fn read_exr_y(path: impl AsRef<Path>) -> Result<(usize, usize, Vec<f32>)> {
    use exr::prelude::*;
    let path = path.as_ref();
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| crate::Error::io(path.display().to_string(), e))?;
    let layer = &image.layer_data;
    let size = layer.size;
    let channel = layer
        .channel_data
        .list
        .iter()
        .find(|c| c.name.eq("Y"))
        .ok_or_else(|| crate::Error::io(path.display().to_string(), "no channel named Y"))?;
    let values = channel.sample_data.values_as_f32().collect();
    Ok((size.width(), size.height(), values))
}

/// Writes the radial mean as CSV: `frequency,power,anisotropy`, one row per bin.
pub fn write_radial_csv(path: impl AsRef<Path>, bins: &[RadialBin]) -> Result<()> {
    let mut text = String::from("frequency,power,anisotropy\n");
    for b in bins {
        text.push_str(&format!("{},{},{}\n", b.frequency, b.power, b.anisotropy));
    }
    write_text(path, &text)
}

/// Writes `text` to `path` as [`write_file`] writes: never half written, every byte checked.
pub fn write_text(path: impl AsRef<Path>, text: &str) -> Result<()> {
    write_file(path, text.as_bytes())
}

/// Writes the files of one pattern's expected spectrum into `dir`, as the `spectrum` and
/// `measure` programs do: `NAME-spectrum.png` (log-scaled), `NAME-spectrum.exr` (the values),
/// `NAME-radial.csv` and `NAME-radial.png` (the radial mean), and `NAME-points.png` (`points`,
/// one realization, with `grids`).
pub fn write_spectrum_files(
    dir: impl AsRef<Path>,
    name: &str,
    spectrum: &Spectrum,
    realizations: usize,
    points: &[Point2],
    grids: &[StrataGrid],
) -> Result<()> {
    let dir = dir.as_ref();
    let radial = spectrum.radial();
    let count = points.len();
    let scale = 512u32.div_ceil(spectrum.side() as u32).max(1);
    write_png(
        dir.join(format!("{name}-spectrum.png")),
        &draw_spectrum(spectrum, scale),
    )?;
    write_spectrum_exr(dir.join(format!("{name}-spectrum.exr")), spectrum)?;
    write_radial_csv(dir.join(format!("{name}-radial.csv")), &radial)?;
    let title = format!("{name}: radial mean, N = {count}, {realizations} realizations");
    write_png(
        dir.join(format!("{name}-radial.png")),
        &radial_plot(&radial, &title, count, 640, 400),
    )?;
    write_png(
        dir.join(format!("{name}-points.png")),
        &draw_points(points, grids, 512),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("strata-io-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    #[cfg(target_os = "linux")]
    fn an_armed_temporary_name_is_removed_by_the_handler_s_call() {
        // A10: an interrupt between naming the temporary file and renaming it left it behind
        let dir = scratch("pending");
        let tmp = dir.join(".strata-test.tmp");
        std::fs::write(&tmp, b"x").unwrap();
        // a released name is left alone (it may be the renamed file's old name, reused)
        drop(pending::arm(&tmp));
        remove_pending_temporaries();
        assert!(tmp.exists());
        // an armed one is removed (its slot then stays claimed: the process would be ending)
        let armed = pending::arm(&tmp);
        remove_pending_temporaries();
        assert!(!tmp.exists());
        drop(armed);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn the_write_probe_leaves_nothing_behind() {
        // A10: the probe was a named file, left by an interrupt in its instant
        let dir = scratch("probe");
        check_writable_dir(&dir).unwrap();
        check_writable(dir.join("r.md")).unwrap();
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        assert!(check_writable(&dir).is_err(), "a directory is no file");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
