//! The documents that state facts about the samplers agree with the registry, which each
//! sampler's own file declares: the table in `docs/samplers.md` (included in the crate docs)
//! and in the README. `STRATA_BLESS=1 cargo test --test docs` rewrites `docs/samplers.md`.

use std::path::Path;

use strata::registry;

fn read(path: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn the_sampler_tables_are_the_registry() {
    let table = registry::table();
    if std::env::var_os("STRATA_BLESS").is_some() {
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/samplers.md");
        std::fs::write(p, &table).unwrap();
    }
    assert_eq!(
        read("docs/samplers.md"),
        table,
        "docs/samplers.md is stale (STRATA_BLESS=1)"
    );
    assert!(
        read("README.md").contains(&table),
        "the README's sampler table differs from registry::table():\n{table}"
    );
    // every registered sampler has a row, and no row names an unregistered one
    let rows: Vec<&str> = table.lines().skip(2).collect();
    assert_eq!(rows.len(), registry::entries().len());
    for (row, e) in rows.iter().zip(registry::entries()) {
        assert!(row.starts_with(&format!("| `{}` |", e.name)), "{row}");
    }
}

#[test]
fn nothing_refers_outside_the_repository() {
    for f in [
        "README.md",
        "docs/results.md",
        "src/lib.rs",
        "examples/points.rs",
        "examples/spectrum.rs",
        "tests/cli.rs",
    ] {
        let text = read(f);
        assert!(
            !text.contains("../shared"),
            "{f} refers outside the repository"
        );
    }
}

#[test]
fn the_sequence_table_is_generated_and_names_every_sequence() {
    // the pixel module docs include docs/sequences.md, which `Sequence::summary_table` writes
    let table = strata::Sequence::summary_table();
    if std::env::var_os("STRATA_BLESS").is_some() {
        let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/sequences.md");
        std::fs::write(p, &table).unwrap();
    }
    assert_eq!(
        read("docs/sequences.md"),
        table,
        "docs/sequences.md is stale (STRATA_BLESS=1)"
    );
    assert!(
        read("src/pixel/mod.rs").contains("include_str!(\"../../docs/sequences.md\")"),
        "the pixel module docs no longer include the sequence table"
    );
    // one row per sequence the adapter knows by name, in the order of `Sequence::NAMES`
    let rows: Vec<&str> = table.lines().skip(2).collect();
    assert_eq!(rows.len(), strata::Sequence::NAMES.len());
    for (row, name) in rows.iter().zip(strata::Sequence::NAMES) {
        assert!(row.starts_with(&format!("| `{name}` |")), "{row}");
        // and the row's GPU column says what `gpu_parameters` does
        let spp = if name == "jittered" { 16 } else { 8 };
        let seq = strata::Sequence::by_name_at(name, [8, 8]).unwrap();
        let s = strata::PixelSampler::new(seq, spp, strata::Seed(1)).unwrap();
        let gpu = s
            .gpu_parameters()
            .map(|g| format!("sequence {}", g.sequence));
        assert!(
            row.contains(&format!("| {} |", gpu.as_deref().unwrap_or("CPU only"))),
            "{row}"
        );
    }
}

#[test]
fn no_merge_conflict_markers_are_left_in_the_sources_or_the_docs() {
    // (a merge once committed its markers into CHANGELOG.md and docs/cli.md unnoticed)
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let markers = [format!("{} ", "<".repeat(7)), format!("{} ", ">".repeat(7))];
    let mut stack: Vec<std::path::PathBuf> =
        ["src", "docs", "examples", "tests", "benches", "shaders"]
            .iter()
            .map(|d| root.join(d))
            .chain(
                ["README.md", "CHANGELOG.md", "CONTRIBUTING.md", "Cargo.toml"]
                    .map(|f| root.join(f)),
            )
            .collect();
    let mut files = 0;
    while let Some(p) = stack.pop() {
        if p.is_dir() {
            for e in std::fs::read_dir(&p).unwrap() {
                stack.push(e.unwrap().path());
            }
            continue;
        }
        let Ok(text) = std::fs::read_to_string(&p) else {
            continue; // pictures and other binary files
        };
        files += 1;
        for (n, line) in text.lines().enumerate() {
            assert!(
                !markers.iter().any(|m| line.starts_with(m.as_str())),
                "{}:{}: a merge conflict marker",
                p.display(),
                n + 1
            );
        }
    }
    assert!(files > 50, "only {files} files read");
}
