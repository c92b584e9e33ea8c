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
fn the_pixel_docs_name_every_sequence() {
    // the "Sequences" section of the adapter's module docs describes each of
    // `Sequence::NAMES` (a new sequence must be described there; issue 27 item 5 would
    // generate this list as the sampler table is generated)
    let text = read("src/pixel/mod.rs");
    let heading = "//! # Sequences\n";
    let start = text
        .find(heading)
        .expect("src/pixel/mod.rs has # Sequences");
    let rest = &text[start + heading.len()..];
    let section = &rest[..rest.find("//! # ").unwrap_or(rest.len())];
    for name in strata::Sequence::NAMES {
        assert!(
            section.contains(&format!("`{name}`")),
            "the Sequences section of src/pixel/mod.rs does not describe `{name}`"
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
