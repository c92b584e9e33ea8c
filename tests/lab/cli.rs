//! The `points` program's command-line contract (`docs/cli.md`): CSV that parses back to
//! the library's values, `--list`, and one-line errors with a non-zero exit status.

use crate::common::example_bin;
use std::path::PathBuf;
use std::process::Command;

use strata_lab::registry::{self, Params};

fn points_bin() -> Option<PathBuf> {
    example_bin("points")
}

fn run(args: &[&str]) -> (i32, String, String) {
    let bin = points_bin().expect("the points example is built by `cargo test`");
    let out = Command::new(bin).args(args).output().expect("points runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn csv_round_trips_to_the_library_values() {
    for (name, n) in [("cmj", 37u64), ("jittered", 25), ("random", 10)] {
        let (code, out, err) = run(&["--sampler", name, "-n", &n.to_string(), "--seed", "42"]);
        assert_eq!(code, 0, "{err}");
        let mut lines = out.lines();
        assert_eq!(lines.next(), Some("x,y"));
        let mut s = registry::build(name, &Params::new(n).seed(strata::Seed(42))).unwrap();
        let mut rows = 0;
        for line in lines {
            let (x, y) = line.split_once(',').unwrap();
            let p = s.next_sample();
            assert_eq!(x.parse::<f32>().unwrap().to_bits(), p[0].to_bits());
            assert_eq!(y.parse::<f32>().unwrap().to_bits(), p[1].to_bits());
            rows += 1;
        }
        assert_eq!(rows, n);
    }
}

#[test]
fn list_names_every_sampler() {
    let (code, out, _) = run(&["--list"]);
    assert_eq!(code, 0);
    for name in registry::names() {
        assert!(
            out.lines().any(|l| l.starts_with(name)),
            "{name} missing from --list"
        );
    }
}

#[test]
fn bad_input_is_a_one_line_error() {
    let cases: &[(&[&str], &str)] = &[
        (&["--sampler", "jittered", "-n", "0"], "allowed"),
        (
            &["--sampler", "random", "-n", "100000000000000000000"],
            "is out of range",
        ),
        (
            &["--sampler", "random", "-n", "12x"],
            "is not a whole number",
        ),
        (&["--sampler", "nosuch", "-n", "4"], "known samplers"),
        (&["--sampler", "jittered", "-n", "10"], "9 or 16"),
        (&["--sampler", "regular", "-n", "99"], "81 or 100"),
        (&["--sampler", "multijittered", "-n", "2"], "1 or 4"),
        (&["--sampler", "cmj", "-n", "67108865"], "67108864"),
        (&["--sampler", "cmj", "-n", "abc"], "whole number"),
        (&["--sampler", "cmj"], "-n N is required"),
        (&["--bogus"], "unexpected argument '--bogus'"),
    ];
    for (args, needle) in cases {
        let (code, out, err) = run(args);
        assert_ne!(code, 0, "{args:?} should fail");
        assert!(out.is_empty(), "{args:?} printed {out}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn png_is_written_and_directories_are_created() {
    let dir = std::env::temp_dir().join(format!("strata-cli-{}", std::process::id()));
    let file = dir.join("nested").join("cmj.png");
    let (code, _, err) = run(&[
        "--sampler",
        "cmj",
        "-n",
        "16",
        "--png",
        file.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let bytes = std::fs::read(&file).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn dims_and_pixel_print_the_library_values() {
    // --dims D: D columns, the D-dimensional sampler's values
    let (code, out, err) = run(&[
        "--sampler",
        "sobol",
        "-n",
        "8",
        "--dims",
        "5",
        "--seed",
        "3",
    ]);
    assert_eq!(code, 0, "{err}");
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("x0,x1,x2,x3,x4"));
    let mut s = registry::build_nd("sobol", &Params::new(8).seed(strata::Seed(3)), 5).unwrap();
    let mut want = vec![0f32; 5];
    let mut rows = 0;
    for line in lines {
        s.next_point(&mut want);
        let got: Vec<f32> = line.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(got, want);
        rows += 1;
    }
    assert_eq!(rows, 8);
    // --pixel X,Y: the adapter's values, dims 0-1 get_pixel_2d, then get_2d, then get_1d
    let (code, out, err) = run(&[
        "--sampler",
        "pmj02",
        "-n",
        "4",
        "--pixel",
        "3,7",
        "--dims",
        "5",
    ]);
    assert_eq!(code, 0, "{err}");
    let sampler =
        strata::pixel::PixelSampler::new(strata::pixel::Sequence::pmj02(), 4, strata::Seed(1))
            .unwrap();
    let mut lines = out.lines();
    assert_eq!(lines.next(), Some("x0,x1,x2,x3,x4"));
    let mut rows = 0;
    for (i, line) in lines.enumerate() {
        let got: Vec<f32> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let a = sampler.sample_2d([3, 7], i as u64, 0);
        let b = sampler.sample_2d([3, 7], i as u64, 2);
        let c = sampler.sample_1d([3, 7], i as u64, 4);
        assert_eq!(got, vec![a[0], a[1], b[0], b[1], c]);
        rows += 1;
    }
    assert_eq!(rows, 4);
    // refusals name what is allowed
    let (code, _, err) = run(&["--sampler", "jittered", "-n", "4", "--dims", "3"]);
    assert_ne!(code, 0);
    assert!(err.contains("sobol"), "{err}");
    let (code, _, err) = run(&["--sampler", "cmj", "-n", "4", "--pixel", "1,1"]);
    assert_ne!(code, 0);
    assert!(err.contains("pmj02"), "{err}");
}

#[test]
fn the_main_job_and_the_study_give_the_same_bytes_with_1_and_2_threads() {
    let base = std::env::temp_dir().join(format!("strata-threads-{}", std::process::id()));
    let run = |threads: &str| {
        let out = base.join(threads);
        let bin = example_bin("spectrum").expect("spectrum example");
        let status = Command::new(bin)
            .env("RAYON_NUM_THREADS", threads)
            .args([
                "--sampler",
                "cmj",
                "-n",
                "256",
                "--realizations",
                "20",
                "--resolution",
                "64",
                "--out",
            ])
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
        let bin = example_bin("tradeoff").expect("tradeoff example");
        let status = Command::new(bin)
            .env("RAYON_NUM_THREADS", threads)
            .args([
                "--samplers",
                "jittered,sobol",
                "--integrands",
                "disk,gaussian4d",
                "--max-n",
                "64",
                "--seeds",
                "6",
                "--out",
            ])
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
        let csv = std::fs::read_to_string(out.join("tradeoff.csv")).unwrap();
        // every column but the timings (ns_per_sample, set_ns, set_ns_min, set_ns_max,
        // one_time_ns)
        let study: Vec<String> = csv
            .lines()
            .map(|l| {
                let c: Vec<&str> = l.split(',').collect();
                assert_eq!(c.len(), 13, "{l}");
                [&c[..7], &c[8..9]].concat().join(",")
            })
            .collect();
        (
            std::fs::read(out.join("cmj-spectrum.exr")).unwrap(),
            std::fs::read(out.join("cmj-radial.csv")).unwrap(),
            study,
        )
    };
    let (one, two) = (run("1"), run("2"));
    std::fs::remove_dir_all(&base).ok();
    assert!(one.0 == two.0, "the EXR differs between 1 and 2 threads");
    assert_eq!(
        one.1, two.1,
        "the radial CSV differs between 1 and 2 threads"
    );
    assert_eq!(one.2, two.2, "the study differs between 1 and 2 threads");
}

/// The rows of the Markdown table a program printed under the header line that contains
/// `header` (after its `|---|` line), up to the first line that is not a row.
fn printed_table<'a>(out: &'a str, header: &str) -> Vec<&'a str> {
    out.lines()
        .skip_while(|l| !l.contains(header))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .collect()
}

/// The numbers of a printed table row after its first two cells (sampler, count).
fn row_numbers(row: &str) -> Vec<f64> {
    row.split('|')
        .skip(3)
        .filter_map(|c| c.trim().parse().ok())
        .collect()
}

fn run_example(name: &str, args: &[&str]) -> (i32, String, String) {
    let bin = example_bin(name).unwrap_or_else(|| panic!("the {name} example is built"));
    let out = Command::new(bin)
        .args(args)
        .output()
        .expect("the example runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn conformance_passes_a_sequence_and_refuses_bad_input() {
    let (code, out, err) = run_example(
        "conformance",
        &[
            "--sampler",
            "sobol",
            "--spp",
            "256",
            "--seeds",
            "4",
            "--pixels",
            "3",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("| chi-square | across draws |"), "{out}");
    assert!(out.contains("PASS: 256 samples per pixel"), "{out}");
    for (args, says) in [
        (vec!["--sampler", "cmj"], "the sequences: random"),
        (vec!["--sampler", "sobol", "--spp", "0"], "allowed: 16 to"),
        (vec!["--spp", "64"], "--sampler is required"),
        (
            vec!["--sampler", "sobol", "--spp", "1048576", "--seeds", "1024"],
            "too many",
        ),
        (
            vec!["--sampler", "sobol", "--false-alarm", "2"],
            "out of range",
        ),
    ] {
        let (code, out, err) = run_example("conformance", &args);
        assert_eq!(code, 2, "{args:?}: {out}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

#[test]
fn render_sweeps_counts_and_refuses_bad_input() {
    let dir = std::env::temp_dir().join(format!("strata-render-{}", std::process::id()));
    let (code, out, err) = run_example(
        "render",
        &[
            "--samplers",
            "pmj02,jittered",
            "--spp",
            "4,1",
            "--size",
            "8x8",
            "--reference-spp",
            "16",
            "--seeds",
            "1",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(dir.join("render.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(
        rows[0],
        "sampler,spp,rmse,rel_rmse,ms,blur1_rmse,blur2_rmse,lowband,masked_rmse,\
         masked_blur1_rmse,masked_blur2_rmse,masked_lowband"
    );
    // one row per sampler and count, counts in increasing order
    assert_eq!(rows.len(), 5, "{csv}");
    assert!(rows[1].starts_with("pmj02,1,") && rows[2].starts_with("pmj02,4,"));
    assert!(rows[4].starts_with("jittered,4,"));
    for f in [
        "compare.png",
        "convergence.png",
        "pmj02.png",
        "pmj02-error.png",
        "pmj02-1.png",
        "emitter-mask.png",
    ] {
        assert!(dir.join(f).exists(), "{f}: {out}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    for (args, says) in [
        (vec!["--spp", "4,x"], "not a whole number"),
        (vec!["--samplers", "jittered", "--spp", "8"], "square"),
        (
            vec!["--scene", "teapot"],
            "cornell, spheres, cornell-direct",
        ),
        (vec!["--samplers", "cmj"], "the sequences: random"),
        (vec!["--interactions"], "direct-lighting"),
    ] {
        let (code, _, err) = run_example("render", &args);
        assert_eq!(code, 2, "{args:?}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

#[test]
fn render_adaptive_stops_each_pixel_at_its_own_count_for_every_sampler() {
    let dir = std::env::temp_dir().join(format!("strata-render-adaptive-{}", std::process::id()));
    let md = dir.join("results.md");
    let (code, out, err) = run_example(
        "render",
        &[
            "--scene",
            "cornell-direct",
            "--samplers",
            "sobol,zsobol,sobolbn",
            "--spp",
            "1,4",
            "--size",
            "32x32",
            "--reference-spp",
            "64",
            "--seeds",
            "2",
            "--adaptive",
            "8",
            "--out",
            dir.to_str().unwrap(),
            "--markdown",
            md.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    // a row per sampler, with the ratio to sobol's low band (1 for sobol itself) and its
    // standard error over the two seeds (none for sobol itself)
    let rows = printed_table(&out, "| sampler | masked rmse | masked blur2_rmse");
    assert_eq!(rows.len(), 3, "{out}");
    assert!(rows[0].starts_with("| sobol |") && rows[0].ends_with("| 1.000 | 1.000 | - |"));
    for row in &rows[1..] {
        let se: f64 = row
            .trim_end_matches(" |")
            .rsplit("| ")
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(se > 0.0 && se.is_finite(), "{row}");
    }
    // where the error is: the counts' shares, up to 4 (below the largest count, 8)
    assert!(
        out.contains("of the error's power") && out.contains("up to 4."),
        "{out}"
    );
    let csv = std::fs::read_to_string(dir.join("adaptive.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "sampler,max_spp,lowband,masked_rmse,masked_blur2_rmse,masked_lowband,\
         masked_scaled_lowband"
    );
    assert_eq!(lines.len(), 4, "{csv}");
    for l in &lines[1..] {
        let v: Vec<&str> = l.split(',').collect();
        assert_eq!((v.len(), v[1]), (7, "8"), "{l}");
        assert!(
            v[2..].iter().all(|x| x.parse::<f64>().unwrap() > 0.0),
            "{l}"
        );
    }
    // its own section name, with the table in it
    let text = std::fs::read_to_string(&md).unwrap();
    assert!(text.contains("<!-- begin render-cornell-direct-1,4-adaptive -->"));
    assert!(text.contains("Adaptive images: each pixel stops at its own count, from 1 to 8"));
    let (code, _, err) = run_example("render", &["--adaptive", "1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--adaptive"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn render_draws_the_pbrt_references_and_the_experiments_in_the_studio() {
    // issue 39: pbrt-v4's two samplers and the padding experiments beside a crate sequence, in
    // the scene that is not a box, with the interaction split (their stateless draws)
    let dir = std::env::temp_dir().join(format!("strata-render-pbrt-{}", std::process::id()));
    let (code, out, err) = run_example(
        "render",
        &[
            "--scene",
            "studio-direct",
            "--samplers",
            "sobol,pbrt-padded,pbrt-zsobol,pbrt-zsobol-seeded,openqmc-sobolbn,sobol+shells,\
             pmj02+permute",
            "--spp",
            "1,4",
            "--size",
            "16x16",
            "--reference-spp",
            "16",
            "--seeds",
            "1",
            "--interactions",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    // the small light is in the picture: some pixels are masked, not all
    let masked: u32 = err
        .lines()
        .find_map(|l| l.strip_suffix(" pixels see an emitter (left out of the masked figures)"))
        .and_then(|l| l.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{err}"));
    assert!(masked > 0 && masked < 256, "{err}");
    let csv = std::fs::read_to_string(dir.join("render.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|r| r.split(',').collect())
        .collect();
    let names: Vec<(&str, &str)> = rows.iter().map(|r| (r[0], r[1])).collect();
    assert_eq!(
        names,
        [
            ("sobol", "1"),
            ("sobol", "4"),
            ("pbrt-padded", "1"),
            ("pbrt-padded", "4"),
            ("pbrt-zsobol", "1"),
            ("pbrt-zsobol", "4"),
            ("pbrt-zsobol-seeded", "1"),
            ("pbrt-zsobol-seeded", "4"),
            ("openqmc-sobolbn", "1"),
            ("openqmc-sobolbn", "4"),
            ("sobol+shells", "1"),
            ("sobol+shells", "4"),
            ("pmj02+permute", "1"),
            ("pmj02+permute", "4"),
        ],
        "{csv}"
    );
    for r in &rows {
        for v in &r[2..] {
            let v: f64 = v.parse().unwrap();
            assert!(v.is_finite() && v >= 0.0, "{csv}");
        }
    }
    // the interaction split has a row per sampler at the smallest count
    let split: Vec<&str> = printed_table(&out, "one-draw rmse");
    assert_eq!(split.len(), 7, "{out}");
    assert!(split[2].starts_with("| pbrt-zsobol | 1 |"), "{out}");
    // the seeded order is another sampler: its draws differ from pbrt's at the same seed
    let row = |name: &str| {
        rows.iter()
            .find(|r| r[0] == name && r[1] == "1")
            .unwrap()
            .clone()
    };
    assert_ne!(row("pbrt-zsobol")[2], row("pbrt-zsobol-seeded")[2], "{csv}");
    let _ = std::fs::remove_dir_all(&dir);
    for (args, says) in [
        (
            vec!["--samplers", "pbrt-zsobol", "--spp", "3"],
            "powers of two",
        ),
        (
            vec!["--samplers", "sobol+permute", "--spp", "6"],
            "powers of two",
        ),
        (vec!["--samplers", "sobol+twist"], "not an experiment"),
        (
            vec!["--samplers", "pbrt"],
            "pbrt-padded, pbrt-zsobol, pbrt-zsobol-seeded, openqmc-sobolbn",
        ),
        (
            vec!["--scene", "studio", "--interactions"],
            "direct-lighting",
        ),
    ] {
        let (code, _, err) = run_example("render", &args);
        assert_eq!(code, 2, "{args:?}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

#[test]
fn render_takes_the_last_samplers_flag_even_when_it_is_all() {
    // docs/cli.md: the last flag wins; `--samplers X --samplers all` renders every sequence
    let dir = std::env::temp_dir().join(format!("strata-render-all-{}", std::process::id()));
    let (code, _, err) = run_example(
        "render",
        &[
            "--samplers",
            "sobol",
            "--samplers",
            "all",
            "--spp",
            "1",
            "--size",
            "8x8",
            "--reference-spp",
            "4",
            "--seeds",
            "1",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(dir.join("render.csv")).unwrap();
    let names: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|r| r.split(',').next().unwrap())
        .collect();
    assert_eq!(names, strata::pixel::Sequence::NAMES, "{csv}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn render_splits_the_error_into_one_draw_and_interaction_parts() {
    let dir = std::env::temp_dir().join(format!("strata-render-split-{}", std::process::id()));
    let (code, out, err) = run_example(
        "render",
        &[
            "--scene",
            "cornell-direct",
            "--samplers",
            "random,zjoint",
            "--spp",
            "1,2",
            "--size",
            "16x16",
            "--reference-spp",
            "64",
            "--seeds",
            "1",
            "--interactions",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    // one row per sampler at the smallest count, each part's figures finite
    let table: Vec<&str> = printed_table(&out, "one-draw rmse");
    assert_eq!(table.len(), 2, "{out}");
    for (row, name) in table.iter().zip(["random", "zjoint"]) {
        assert!(row.starts_with(&format!("| {name} | 1 |")), "{row}");
        let cells = row_numbers(row);
        assert_eq!(cells.len(), 6, "{row}");
        assert!(cells.iter().all(|v| v.is_finite() && *v >= 0.0), "{row}");
        // (both parts carry error at 1 spp)
        assert!(cells[0] > 0.0 && cells[3] > 0.0, "{row}");
    }
    // each draw's main effect: a row per sampler, a low band per draw of the camera and the
    // first bounce (film, lens, lobe, light choice, light point)
    let per_draw: Vec<&str> = printed_table(&out, "| sampler | spp | film | lens | lobe |");
    assert_eq!(per_draw.len(), 2, "{out}");
    for (row, name) in per_draw.iter().zip(["random", "zjoint"]) {
        assert!(row.starts_with(&format!("| {name} | 1 |")), "{row}");
        let cells = row_numbers(row);
        assert_eq!(cells.len(), 5, "{row}");
        assert!(cells.iter().all(|v| v.is_finite() && *v >= 0.0), "{row}");
    }
    for f in ["emitter-mask.png", "blue-noise-masked.png"] {
        assert!(dir.join(f).exists(), "{f}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn render_with_one_count_or_one_sampler_says_what_it_cannot_show() {
    // one count: no power law to fit for the time to an error; sobol alone: nothing to divide
    let dir = std::env::temp_dir().join(format!("strata-render-one-{}", std::process::id()));
    let (code, out, err) = run_example(
        "render",
        &[
            "--scene",
            "cornell-direct",
            "--samplers",
            "sobol",
            "--spp",
            "2",
            "--size",
            "16x16",
            "--reference-spp",
            "64",
            "--seeds",
            "1",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("needs two or more counts"), "{out}");
    assert!(!out.contains(" at  spp"), "{out}");
    assert!(!out.contains("Ratios to"), "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn render_runs_the_frames_and_the_interacting_layout() {
    // issue 39: --layout interacting and --frames with their tables, the ratios to sobol and the
    // section name of each option in --markdown
    let dir = std::env::temp_dir().join(format!("strata-render-frames-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let md = dir.join("results.md");
    let (code, out, err) = run_example(
        "render",
        &[
            "--scene",
            "cornell-direct",
            "--samplers",
            "sobol,zquad",
            "--spp",
            "1,2",
            "--size",
            "16x16",
            "--reference-spp",
            "16",
            "--seeds",
            "1",
            "--layout",
            "interacting",
            "--frames",
            "2",
            "--frame-tile",
            "4",
            "--interactions",
            "--padding",
            "nested",
            "--out",
            dir.join("out").to_str().unwrap(),
            "--markdown",
            md.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    // the frames table: a row per sampler and count, figures finite, the interaction part's low
    // band at the smallest count only
    let frames: Vec<Vec<String>> = printed_table(&out, "| plain rmse |")
        .iter()
        .map(|l| l.split('|').map(|c| c.trim().to_string()).collect())
        .collect();
    let names: Vec<(&str, &str)> = frames
        .iter()
        .map(|r| (r[1].as_str(), r[2].as_str()))
        .collect();
    assert_eq!(
        names,
        [
            ("sobol", "1"),
            ("sobol", "2"),
            ("zquad", "1"),
            ("zquad", "2")
        ],
        "{out}"
    );
    for r in &frames {
        let values: Vec<f64> = r[3..11].iter().map(|c| c.parse().unwrap()).collect();
        assert!(values.iter().all(|v| v.is_finite() && *v >= 0.0), "{r:?}");
        let split = &r[11..13];
        if r[2] == "1" {
            assert!(
                split
                    .iter()
                    .all(|c| c.parse::<f64>().is_ok_and(|v| v > 0.0)),
                "{r:?}"
            );
        } else {
            assert_eq!(split, ["-", "-"], "{r:?}");
        }
    }
    // the ratios to sobol: zquad's rows, sobol's own none
    assert!(out.contains("Ratios to `sobol`"), "{out}");
    assert!(out.lines().any(|l| l.starts_with("| zquad | 1 |")), "{out}");
    let md = std::fs::read_to_string(&md).unwrap();
    assert!(
        md.contains("<!-- begin render-cornell-direct-1,2-interacting-frames-nested -->"),
        "{md}"
    );
    let _ = std::fs::remove_dir_all(&dir);
    for (args, says) in [
        (vec!["--frames", "1"], "--frames"),
        (vec!["--frames", "65"], "--frames"),
        (vec!["--frames", "2", "--frame-tile", "0"], "--frame-tile"),
        (vec!["--layout", "sideways"], "bounce, interacting"),
        (vec!["--padding", "tight"], "shells"),
    ] {
        let (code, _, err) = run_example("render", &args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// `run_example` with raw stdout bytes.
fn run_example_bytes(name: &str, args: &[&str]) -> (i32, Vec<u8>, String) {
    let bin = example_bin(name).expect("the example is built by `cargo test`");
    let out = Command::new(bin)
        .args(args)
        .output()
        .expect("the example runs");
    (
        out.status.code().unwrap_or(-1),
        out.stdout,
        String::from_utf8(out.stderr).unwrap(),
    )
}

#[test]
fn points_writes_every_format_and_measure_reads_them_back() {
    use strata_lab::analysis::discrepancy;
    use strata_lab::pointsets;
    let dir = std::env::temp_dir().join(format!("strata-measure-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut s = registry::build("sobol", &Params::new(64).seed(strata::Seed(5))).unwrap();
    let want: Vec<f64> = (0..64)
        .flat_map(|_| {
            let p = s.next_sample();
            [p[0] as f64, p[1] as f64]
        })
        .collect();
    let mut files = Vec::new();
    for format in ["csv", "utk", "bin"] {
        let (code, out, err) = run_example_bytes(
            "points",
            &[
                "--sampler",
                "sobol",
                "-n",
                "64",
                "--seed",
                "5",
                "--format",
                format,
            ],
        );
        assert_eq!(code, 0, "{err}");
        let sets = pointsets::parse(&out).unwrap();
        assert_eq!(sets.len(), 1);
        // every format holds exactly the generated values, read as f64 (the shortest f32 text
        // would read back as an f64 beside the value, across cell edges of the nets)
        assert_eq!(sets[0].coords, want, "{format}");
        let path = dir.join(format!("sobol-{format}.{format}"));
        std::fs::write(&path, &out).unwrap();
        files.push(path);
    }
    let paths: Vec<&str> = files.iter().map(|p| p.to_str().unwrap()).collect();
    let out_dir = dir.join("out");
    let mut args = paths.clone();
    args.extend(["--out", out_dir.to_str().unwrap()]);
    let (code, out, err) = run_example("measure", &args);
    assert_eq!(code, 0, "{err}");
    // three files, each a set row and a mean row, all with the library's values
    let cd = discrepancy::centered_squared(&want, 2).unwrap();
    let rows: Vec<&str> = out
        .lines()
        .filter(|l| l.split('|').nth(2).map(str::trim) == Some("0"))
        .collect();
    assert_eq!(rows.len(), 3, "{out}");
    for row in rows {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let printed: f64 = cells[7].parse().unwrap(); // | file | set | n | d | l2 | wd2 | cd2
        assert!((printed - cd).abs() <= 1e-6 * cd, "{row}");
        assert_eq!(cells[10], "0", "a Sobol' prefix is a (0,6,2)-net: {row}");
    }
    for f in [
        "sobol-csv-spectrum.png",
        "sobol-bin-radial.csv",
        "measures.csv",
    ] {
        assert!(out_dir.join(f).exists(), "{f}");
    }
    // a damaged file: a one-line error naming the line
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "0.1 0.2\n0.3\n").unwrap();
    let (code, _, err) = run_example("measure", &[bad.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("line 2") && err.lines().count() == 1, "{err}");
    let (code, _, err) = run_example("measure", &[]);
    assert_ne!(code, 0);
    assert!(err.contains("FILE"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn mask_writes_the_built_in_table_and_refuses_bad_sides() {
    let dir = std::env::temp_dir().join(format!("strata-mask-{}", std::process::id()));
    let (table, png) = (dir.join("t/mask.rs"), dir.join("mask.png"));
    let (code, out, err) = run_example(
        "mask",
        &[
            "--out",
            table.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("64 x 64 ranks"), "{out}");
    // the defaults are the built-in's: the same bytes as the table the renderer's crate reads
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    assert_eq!(
        std::fs::read_to_string(&table).unwrap(),
        std::fs::read_to_string(root.join("strata/src/pixel/frames/blue_noise_64.rs")).unwrap()
    );
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let (code, _, _) = run_example(
        "mask",
        &[
            "--side",
            "8",
            "--seed",
            "3",
            "--out",
            table.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0);
    assert!(
        std::fs::read_to_string(&table)
            .unwrap()
            .contains("[u16; 64]")
    );
    for (bad, says) in [
        (&["--side", "12"][..], "power of two"),
        (&["--side", "512"][..], "--side"),
        (&["--seed", "-1"][..], "--seed"),
        (&["--sides", "8"][..], "--sides"),
    ] {
        let (code, _, err) = run_example("mask", bad);
        assert_eq!(code, 2, "{bad:?}");
        assert!(
            err.contains(says) && err.lines().count() == 1,
            "{bad:?}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bntable_writes_a_table_the_crate_accepts_and_refuses_bad_options() {
    let dir = std::env::temp_dir().join(format!("strata-bntable-{}", std::process::id()));
    let table = dir.join("t/table.rs");
    let (code, out, err) = run_example(
        "bntable",
        &[
            "--side",
            "16",
            "--levels",
            "2",
            "--integrands",
            "8",
            "--effort",
            "4",
            "--out",
            table.to_str().unwrap(),
        ],
    );
    assert_eq!(code, 0, "{err}");
    // a row per count with the table's and the random start's low band, then the file
    let rows: Vec<Vec<f64>> = printed_table(&out, "count")
        .iter()
        .map(|r| r.split('|').filter_map(|c| c.trim().parse().ok()).collect())
        .collect();
    assert_eq!(rows.len(), 3, "{out}");
    for (count, r) in [1.0, 2.0, 4.0].iter().zip(&rows) {
        assert_eq!((r[0], r.len()), (*count, 3), "{out}");
        assert!(r[1] > 0.0 && r[2] > 0.0, "{out}");
    }
    let text = std::fs::read_to_string(&table).unwrap();
    assert!(
        text.contains("pub(super) const SIDE: u32 = 16;") && text.contains("--side 16 --levels 2"),
        "{text}"
    );
    // the entries parse into a table the crate takes
    let entries: Vec<[u32; 2]> = text
        .lines()
        .filter(|l| l.starts_with("    ["))
        .flat_map(|l| {
            l.split("],")
                .filter(|e| e.contains("0x"))
                .collect::<Vec<_>>()
        })
        .map(|e| {
            let v: Vec<u32> = e
                .trim_matches(|c| c == ' ' || c == '[')
                .split(", ")
                .map(|h| u32::from_str_radix(h.trim_start_matches("0x"), 16).unwrap())
                .collect();
            [v[0], v[1]]
        })
        .collect();
    assert_eq!(entries.len(), 256);
    strata::pixel::BlueNoiseTable::new(16, &entries).unwrap();
    for (bad, says) in [
        (&["--side", "24"][..], "power of two"),
        (&["--side", "8"][..], "--side"),
        (&["--levels", "11"][..], "--levels"),
        (&["--integrands", "0"][..], "--integrands"),
        (&["--effort", "x"][..], "--effort"),
    ] {
        let (code, _, err) = run_example("bntable", bad);
        assert_eq!(code, 2, "{bad:?}");
        assert!(
            err.contains(says) && err.lines().count() == 1,
            "{bad:?}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn nets_tabulates_every_pair_of_a_group_and_refuses_bad_groups() {
    let (code, out, err) = run_example("nets", &["--group", "4", "--max-m", "4"]);
    assert_eq!(code, 0, "{err}");
    // the six pairs of four dimensions, each with its t at m = 2 and 4; Sobol' 0-1 is a net
    let pairs: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with("| ") && l.chars().nth(2).is_some_and(|c| c.is_ascii_digit()))
        .collect();
    // and the rows of the set 0, 1, 2, 3 in base 2 and in base 4 (Sobol' 0-3: t = 1 at 4^2)
    assert_eq!(pairs.len(), 6 + 2, "{out}");
    assert!(out.contains("| 0, 1 | 0 | 0 |"), "{out}");
    assert!(out.contains("| 0, 1, 2, 3 in base 4 | 0 | 1 |"), "{out}");
    // zquad: the ten pairs of its four dimensions and the fifth matrix; 0-1 and 2-3 nets,
    // and 0-3 a (0,4)-sequence in base 4
    let (code, out, err) = run_example("nets", &["--sequence", "zquad", "--max-m", "8"]);
    assert_eq!(code, 0, "{err}");
    for row in [
        "| 0, 1 | 0 | 0 | 0 | 0 |",
        "| 2, 3 | 0 | 0 | 0 | 0 |",
        "| 0, 1, 2, 3 in base 4 | 0 | 0 | 0 | 0 |",
        "| 3, 4 |",
    ] {
        assert!(out.contains(row), "{row}: {out}");
    }
    for bad in [
        &["--group", "3"][..],
        &["--group", "32"],
        &["--max-m", "5"],
        &["--max-m", "0"],
        &["--sequence", "zsobol"],
        &["--sequence", "zquad", "--group", "8"],
    ] {
        let (code, _, err) = run_example("nets", bad);
        assert_eq!(code, 2, "{bad:?}: {err}");
        assert!(err.contains(bad[bad.len() - 2]), "{bad:?}: {err}");
    }
}

/// The rows of the table in section `name` of the Markdown text `md`: the cells of each line
/// below the header and its separator.
fn section_rows(md: &str, name: &str) -> Vec<Vec<String>> {
    let begin = format!("<!-- begin {name} -->");
    let end = format!("<!-- end {name} -->");
    let a = md
        .find(&begin)
        .unwrap_or_else(|| panic!("no {begin} in {md}"));
    let b = md.find(&end).unwrap_or_else(|| panic!("no {end} in {md}"));
    md[a..b]
        .lines()
        .filter(|l| l.starts_with("| "))
        .skip(1) // the header; the separator starts with "|-"
        .map(|l| {
            l.trim_matches('|')
                .split(" | ")
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect()
}

#[test]
fn the_blue_noise_table_has_a_row_per_blue_noise_sampler_and_refuses_bad_input() {
    let dir = std::env::temp_dir().join(format!("strata-bn-table-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let md = dir.join("results.md");
    let before = "# Results\n\n<!-- begin spectrum -->\nkept\n<!-- end spectrum -->\n";
    std::fs::write(&md, before).unwrap();
    let md_arg = md.to_str().unwrap();

    // bad input: a one-line error, exit 2, and the Markdown file untouched
    for (args, says) in [
        (
            vec!["--blue-noise-table", "--sampler", "poisson"],
            "not --sampler",
        ),
        (
            vec!["--blue-noise-table", "-n", "100000"],
            "allowed 2 to 16384",
        ),
        (
            vec!["--blue-noise-table", "--radius", "0.5"],
            "not --radius",
        ),
        (vec!["--blue-noise-table", "--out", md_arg], "not --out"),
        (
            vec!["--blue-noise-table", "--no-overview"],
            "not --no-overview",
        ),
        (vec!["--blue-noise-table", "-n", "1"], "-n"),
        (
            vec!["--blue-noise-table", "--realizations", "0"],
            "--realizations",
        ),
    ] {
        let mut args = args;
        args.extend(["--markdown", md_arg]);
        let (code, out, err) = run_example("spectrum", &args);
        assert_eq!(code, 2, "{args:?}: {out}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert_eq!(std::fs::read_to_string(&md).unwrap(), before, "{args:?}");
    }

    let (code, out, err) = run_example(
        "spectrum",
        &[
            "--blue-noise-table",
            "-n",
            "64",
            "--realizations",
            "2",
            "--resolution",
            "32",
            "--markdown",
            md_arg,
        ],
    );
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&md).unwrap();
    assert!(text.contains("<!-- begin spectrum -->\nkept\n<!-- end spectrum -->"));
    assert!(
        text.contains(
            "<!-- written by `cargo run --release --example spectrum -- --blue-noise-table -n 64"
        ),
        "{text}"
    );
    let rows = section_rows(&text, "blue-noise-table");
    let names: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    let registered: Vec<&str> = registry::blue_noise().map(|e| e.name).collect();
    // one row per blue-noise sampler of the registry, in its order: a sampler dropped from
    // the table fails here ...
    assert_eq!(names, registered, "{text}");
    // ... and one dropped from the registry's blue-noise list fails here
    let known = vec![
        "pmjbn",
        "pmj02bn",
        "net02bn",
        "poisson",
        "bridson",
        "best-candidate",
        "ccvt",
        "bnot",
        "lloyd",
    ];
    for name in known {
        assert!(
            registered.contains(&name),
            "{name} is not in {registered:?}"
        );
    }
    for (row, e) in rows.iter().zip(registry::blue_noise()) {
        assert_eq!(row.len(), 8, "{row:?}");
        assert_eq!(row[1], "64", "{row:?}");
        assert_eq!(row[2], "2", "{row:?}");
        let num = |i: usize| -> f64 {
            row[i]
                .parse()
                .unwrap_or_else(|_| panic!("{}: column {i}: {row:?}", e.name))
        };
        let (rho, nn, low, ms) = (num(3), num(4), num(5), num(6));
        assert!(rho > 0.0 && rho <= nn && nn < 1.2, "{row:?}");
        assert!(low > 0.0 && low < 1.0, "{row:?}");
        assert!(ms >= 0.0, "{row:?}");
        assert_eq!(
            row[7],
            e.blue_noise.expect("a blue-noise sampler").published,
            "{row:?}"
        );
    }
    // the table is printed too
    assert!(out.contains("| sampler | N | seeds | rho |"), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_option_of_every_program_refuses_an_empty_value_and_a_misspelling_by_name() {
    // the options as each program's --help lists them (its one declaration): an empty value is
    // refused naming the option, and the option misspelt (a letter more) names it as the
    // closest one; each on one line, before any work
    let mut checked = 0;
    for name in crate::common::programs() {
        let (code, help, _) = run_example(&name, &["--help"]);
        assert_eq!(code, 0, "{name} --help");
        let options: Vec<(String, bool)> = help
            .lines()
            .filter_map(|l| {
                let l = l.trim_start().trim_start_matches("-h, ");
                let rest = l.strip_prefix("--")?;
                let flag: String = rest
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                    .collect();
                let takes_value = rest[flag.len()..].starts_with(" <");
                (flag != "help" && !flag.is_empty()).then_some((flag, takes_value))
            })
            .collect();
        assert!(!options.is_empty(), "{name}: no options in its help");
        for (flag, takes_value) in options {
            let dashed = format!("--{flag}");
            if takes_value {
                let (code, out, err) = run_example(&name, &[&dashed, ""]);
                assert_eq!(code, 2, "{name} {dashed} '': {out}{err}");
                assert_eq!(err.lines().count(), 1, "{name} {dashed} '': {err}");
                assert!(err.contains(&dashed), "{name} {dashed} '': {err}");
            }
            let typo = format!("{dashed}x");
            let (code, _, err) = run_example(&name, &[&typo]);
            assert_eq!(code, 2, "{name} {typo}");
            assert_eq!(err.lines().count(), 1, "{name} {typo}: {err}");
            assert!(
                err.contains(&format!("similar argument exists: '{dashed}'")),
                "{name} {typo}: {err}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 60, "{checked} options");
}
