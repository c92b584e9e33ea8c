//! Counting helpers shared by the integration tests.

#![allow(dead_code)]

use strata::Sampler;

/// The next `n` points of `s`.
pub fn take(s: &mut dyn Sampler, n: usize) -> Vec<[f32; 2]> {
    let mut v = vec![[0.0f32; 2]; n];
    s.fill(&mut v);
    v
}

/// The cell of `x` among `cells` equal strata of [0,1), computed exactly in f64.
pub fn cell(x: f32, cells: u32) -> usize {
    assert!((0.0..1.0).contains(&x), "coordinate {x} outside [0,1)");
    ((x as f64) * cells as f64).floor() as usize
}

/// Points per cell of a `columns x rows` grid, row-major.
pub fn counts(points: &[[f32; 2]], columns: u32, rows: u32) -> Vec<u32> {
    let mut c = vec![0u32; columns as usize * rows as usize];
    for p in points {
        c[cell(p[1], rows) * columns as usize + cell(p[0], columns)] += 1;
    }
    c
}

/// Asserts exactly one point in every cell of the grid.
pub fn assert_one_per_cell(points: &[[f32; 2]], columns: u32, rows: u32, what: &str) {
    let c = counts(points, columns, rows);
    if let Some(bad) = c.iter().position(|&k| k != 1) {
        panic!(
            "{what}: cell ({}, {}) of {columns}x{rows} holds {} points",
            bad % columns as usize,
            bad / columns as usize,
            c[bad]
        );
    }
}

/// Asserts at most one point in every cell of the grid.
pub fn assert_at_most_one_per_cell(points: &[[f32; 2]], columns: u32, rows: u32, what: &str) {
    let c = counts(points, columns, rows);
    if let Some(bad) = c.iter().position(|&k| k > 1) {
        panic!(
            "{what}: cell {bad} of {columns}x{rows} holds {} points",
            c[bad]
        );
    }
}

/// The top `bits` bits of a 32-bit fixed-point coordinate (its cell among `2^bits`).
pub fn top(v: u32, bits: u32) -> usize {
    if bits == 0 {
        0
    } else {
        (v >> (32 - bits)) as usize
    }
}

/// Whether `pts` (2^m fixed-point points) is a (0,m,2)-net: one point in every cell of every
/// shape `2^a x 2^(m-a)`, counted with one bitset per shape (cheap enough for 2^25 points).
pub fn is_net_fixed(pts: &[[u32; 2]]) -> bool {
    let m = pts.len().trailing_zeros();
    (0..=m).all(|a| {
        let mut seen = vec![0u64; pts.len().div_ceil(64)];
        pts.iter().all(|p| {
            let i = (top(p[1], m - a) << a) | top(p[0], a);
            let fresh = seen[i >> 6] >> (i & 63) & 1 == 0;
            seen[i >> 6] |= 1 << (i & 63);
            fresh
        })
    })
}

/// Whether `pts` (2^m points) is a (0,m,2)-net: one point per cell of every shape
/// `2^a x 2^(m-a)`.
pub fn is_net(pts: &[[f32; 2]]) -> bool {
    let m = pts.len().trailing_zeros();
    pts.len().is_power_of_two()
        && (0..=m).all(|a| counts(pts, 1 << a, 1 << (m - a)).iter().all(|&c| c == 1))
}

/// The squared distance of two points on the unit torus, written here independently of the
/// crate's own.
pub fn torus_distance_squared(a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = |u: f64, v: f64| {
        let t = (u - v).abs() % 1.0;
        t.min(1.0 - t)
    };
    d(a[0], b[0]).powi(2) + d(a[1], b[1]).powi(2)
}

/// The example program `name`, built by Cargo for this test's profile (once per test binary),
/// at the path Cargo reports for it: the `executable` of its `compiler-artifact` message in
/// `cargo build --message-format=json` (Cargo sets `CARGO_BIN_EXE_*` for `[[bin]]` targets
/// only, not for examples). `None` when the build fails or reports no executable.
pub fn example_bin(name: &str) -> Option<std::path::PathBuf> {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static BUILT: OnceLock<Mutex<HashMap<String, Option<std::path::PathBuf>>>> = OnceLock::new();
    let mut built = BUILT.get_or_init(Default::default).lock().ok()?;
    if !built.contains_key(name) {
        let exe = std::env::current_exe().ok()?;
        let profile_dir = exe.parent()?.parent()?; // target/<profile>/deps -> target/<profile>
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut cmd = std::process::Command::new(cargo);
        cmd.args([
            "build",
            "--quiet",
            "--message-format=json",
            "--example",
            name,
        ]);
        if profile_dir.file_name()? == "release" {
            cmd.arg("--release");
        } else {
            cmd.args(["--profile", "test"]);
        }
        cmd.stderr(std::process::Stdio::inherit());
        let path = cmd
            .output()
            .ok()
            .filter(|o| o.status.success())
            .and_then(|o| artifact_executable(&String::from_utf8_lossy(&o.stdout), name));
        built.insert(name.to_string(), path);
    }
    built[name].clone().filter(|p| p.exists())
}

/// The `executable` path of example `name` in Cargo's JSON messages (one object per line).
fn artifact_executable(messages: &str, name: &str) -> Option<std::path::PathBuf> {
    let target = format!("\"kind\":[\"example\"],\"crate_types\":[\"bin\"],\"name\":\"{name}\"");
    let line = messages
        .lines()
        .find(|l| l.contains("\"reason\":\"compiler-artifact\"") && l.contains(&target))?;
    let key = "\"executable\":\"";
    let start = line.find(key)? + key.len();
    let end = start + line[start..].find('"')?;
    Some(std::path::PathBuf::from(
        line[start..end].replace("\\\\", "\\"),
    ))
}

/// Every program under `examples/`: a file `NAME.rs` or a directory `NAME/main.rs`.
pub fn programs() -> Vec<String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            let stem = p.file_stem()?.to_str()?.to_string();
            let program = if p.is_dir() {
                p.join("main.rs").is_file()
            } else {
                p.extension().is_some_and(|x| x == "rs")
            };
            program.then_some(stem)
        })
        .collect();
    names.sort();
    names
}
