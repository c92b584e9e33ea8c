//! The public surface, pinned: every public item of the library with every feature (modules,
//! types, functions with their parameter names, fields, variants, constants, trait
//! implementations), one per line, in `docs/public-api.txt`. The list is generated from the
//! code by rustdoc's JSON output, so a change of the surface fails this test until the list is
//! regenerated (`STRATA_BLESS=1 cargo test --release --test public_api -- --ignored`) and the
//! growth is a reviewed diff.
//!
//! rustdoc's JSON output is unstable: it runs on the stable toolchain with `RUSTC_BOOTSTRAP=1`
//! (this test sets it for its own rustdoc run only). It takes about a minute, so it is
//! `#[ignore]`d in `cargo test` and run by `.ci/run`.

use std::collections::{BTreeSet, HashSet};
use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// The crate's rustdoc JSON, built into its own target directory.
fn rustdoc_json() -> Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target = root.join("target").join("public-api");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .current_dir(root)
        .env("RUSTC_BOOTSTRAP", "1")
        .env("CARGO_TARGET_DIR", &target)
        .env_remove("RUSTDOCFLAGS")
        .args([
            "rustdoc",
            "--lib",
            "--all-features",
            "--quiet",
            "--",
            "-Z",
            "unstable-options",
            "--output-format",
            "json",
        ])
        .status()
        .expect("cargo rustdoc runs");
    assert!(
        status.success(),
        "cargo rustdoc --output-format json failed"
    );
    let text = std::fs::read_to_string(target.join("doc").join("strata.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

struct Walk<'a> {
    index: &'a serde_json::Map<String, Value>,
    lines: BTreeSet<String>,
    /// Items whose members (fields, variants, methods, impls) were listed already: a type
    /// re-exported at two paths lists its members once, under the first path walked.
    expanded: HashSet<String>,
}

fn kind(item: &Value) -> &str {
    item["inner"]
        .as_object()
        .and_then(|o| o.keys().next())
        .map_or("?", String::as_str)
}

fn public(item: &Value) -> bool {
    item["visibility"] == "public"
}

impl Walk<'_> {
    fn item(&self, id: &Value) -> Option<&Value> {
        self.index.get(&id.to_string())
    }

    fn module(&mut self, id: &Value, prefix: &str) {
        let Some(m) = self.item(id) else { return };
        let items: Vec<Value> = m["inner"]["module"]["items"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        for child in items {
            let Some(item) = self.item(&child).cloned() else {
                continue;
            };
            if !public(&item) {
                continue;
            }
            if kind(&item) == "use" {
                let u = &item["inner"]["use"];
                let Some(target) = self.item(&u["id"]).cloned() else {
                    // a re-export of another crate's item: its path is the surface
                    self.lines.insert(format!(
                        "use {prefix}::{} = {}",
                        u["name"].as_str().unwrap_or("?"),
                        u["source"].as_str().unwrap_or("?")
                    ));
                    continue;
                };
                if u["is_glob"] == true {
                    self.module(&u["id"], prefix);
                } else {
                    let name = u["name"].as_str().unwrap_or("?");
                    self.named(&u["id"], &target, &format!("{prefix}::{name}"));
                }
                continue;
            }
            let name = item["name"].as_str().unwrap_or("?").to_string();
            self.named(&child, &item, &format!("{prefix}::{name}"));
        }
    }

    fn named(&mut self, id: &Value, item: &Value, path: &str) {
        let k = kind(item);
        let line = match k {
            "function" => format!("fn {path}({})", params(item)),
            _ => format!("{k} {path}"),
        };
        self.lines.insert(line);
        if k == "module" {
            self.module(id, path);
            return;
        }
        if !self.expanded.insert(id.to_string()) {
            return;
        }
        let inner = &item["inner"][k];
        match k {
            "struct" => {
                if let Some(fields) = inner["kind"]["plain"]["fields"].as_array() {
                    for f in fields {
                        if let Some(fi) = self.item(f)
                            && public(fi)
                        {
                            self.lines
                                .insert(format!("field {path}.{}", fi["name"].as_str().unwrap()));
                        }
                    }
                }
                if inner["kind"]["plain"]["has_stripped_fields"] == false {
                    self.lines.insert(format!("exhaustive {path}"));
                }
                self.impls(inner, path);
            }
            "enum" => {
                for v in inner["variants"].as_array().into_iter().flatten() {
                    if let Some(vi) = self.item(v) {
                        self.lines
                            .insert(format!("variant {path}::{}", vi["name"].as_str().unwrap()));
                    }
                }
                self.impls(inner, path);
            }
            "trait" => {
                for t in inner["items"].as_array().into_iter().flatten() {
                    if let Some(ti) = self.item(t).cloned() {
                        self.member(&ti, path);
                    }
                }
            }
            _ => {}
        }
        if item["attrs"]
            .as_array()
            .into_iter()
            .flatten()
            .any(|a| a.to_string().contains("non_exhaustive"))
        {
            self.lines.insert(format!("non_exhaustive {path}"));
        }
    }

    fn member(&mut self, item: &Value, path: &str) {
        let name = item["name"].as_str().unwrap_or("?");
        let line = match kind(item) {
            "function" => format!("fn {path}::{name}({})", params(item)),
            k => format!("{k} {path}::{name}"),
        };
        self.lines.insert(line);
    }

    fn impls(&mut self, inner: &Value, path: &str) {
        for i in inner["impls"].as_array().into_iter().flatten() {
            let Some(imp) = self.item(i).cloned() else {
                continue;
            };
            let imp_inner = &imp["inner"]["impl"];
            if imp_inner["is_synthetic"] == true || !imp_inner["blanket_impl"].is_null() {
                continue;
            }
            if imp_inner["trait"].is_null() {
                for m in imp_inner["items"].as_array().into_iter().flatten() {
                    if let Some(mi) = self.item(m).cloned()
                        && public(&mi)
                    {
                        self.member(&mi, path);
                    }
                }
            } else {
                let t = &imp_inner["trait"];
                let name = t["path"].as_str().or(t["name"].as_str()).unwrap_or("?");
                self.lines.insert(format!("impl {name} for {path}"));
            }
        }
    }
}

/// A function's parameter names, so that a change of arity or a renamed parameter shows.
fn params(item: &Value) -> String {
    item["inner"]["function"]["sig"]["inputs"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|p| p.get(0).and_then(Value::as_str))
        .collect::<Vec<_>>()
        .join(", ")
}

#[test]
#[ignore = "about a minute: runs rustdoc; .ci/run runs it"]
fn the_public_surface_is_the_reviewed_list() {
    let doc = rustdoc_json();
    let index = doc["index"].as_object().unwrap();
    let mut walk = Walk {
        index,
        lines: BTreeSet::new(),
        expanded: HashSet::new(),
    };
    walk.module(&doc["root"], "strata");
    let got: String = walk.lines.iter().map(|l| format!("{l}\n")).collect();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/public-api.txt");
    let header = "# The public items of the `strata` library with every feature, generated by\n\
                  # `STRATA_BLESS=1 cargo test --release --test public_api -- --ignored`.\n";
    if std::env::var_os("STRATA_BLESS").is_some() {
        std::fs::write(&file, format!("{header}{got}")).unwrap();
        return;
    }
    let want = std::fs::read_to_string(&file).unwrap_or_default();
    let want: BTreeSet<&str> = want.lines().filter(|l| !l.starts_with('#')).collect();
    let got: BTreeSet<&str> = got.lines().collect();
    let added: Vec<_> = got.difference(&want).collect();
    let removed: Vec<_> = want.difference(&got).collect();
    assert!(
        added.is_empty() && removed.is_empty(),
        "the public surface changed; review, then regenerate docs/public-api.txt with \
         STRATA_BLESS=1.\nadded ({}):\n  {}\nremoved ({}):\n  {}",
        added.len(),
        added
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join("\n  "),
        removed.len(),
        removed
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join("\n  ")
    );
}
