//! The public surface, from rustdoc's JSON output: every public item with its signature
//! (functions with their parameters' names and types and their return type, constants with
//! their type and value, fields with their type, variants, trait implementations), one per
//! line. Two uses: the surface is pinned in a reviewed list (`docs/public-api.txt` of each
//! crate), and the renderer crate's features are shown additive (what a caller can name without
//! features is named the same with every feature). rustdoc's JSON output is unstable: it runs on
//! the stable toolchain with `RUSTC_BOOTSTRAP=1` (for its own rustdoc run only). It takes about
//! a minute, so the tests that use it are `#[ignore]`d in `cargo test` and run by `.ci/run`.
//! The renderer's tests (`public_api.rs`) and the lab's include this file.

#![allow(dead_code)]

use std::collections::{BTreeSet, HashSet};
use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// The public surface of the library of the package in `dir` (its `[lib] name` is `lib`),
/// built with `features` (cargo's flags: `--all-features`, `--no-default-features`, ...) into
/// its own target directory, as lines.
pub fn surface(dir: &Path, lib: &str, features: &[&str]) -> BTreeSet<String> {
    // the workspace's target directory: this test's executable is target/<profile>/deps/NAME
    let exe = std::env::current_exe().unwrap();
    let target = exe
        .ancestors()
        .nth(3)
        .unwrap()
        .join(format!("public-api{}", features.join("")));
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .current_dir(dir)
        .env("RUSTC_BOOTSTRAP", "1")
        .env("CARGO_TARGET_DIR", &target)
        .env_remove("RUSTDOCFLAGS")
        .args(["rustdoc", "--lib", "--quiet"])
        .args(features)
        .args(["--", "-Z", "unstable-options", "--output-format", "json"])
        .status()
        .expect("cargo rustdoc runs");
    assert!(
        status.success(),
        "cargo rustdoc --output-format json failed"
    );
    let text = std::fs::read_to_string(target.join("doc").join(format!("{lib}.json"))).unwrap();
    let doc: Value = serde_json::from_str(&text).unwrap();
    let index = doc["index"].as_object().unwrap();
    let mut walk = Walk {
        index,
        lines: BTreeSet::new(),
        expanded: HashSet::new(),
    };
    walk.module(&doc["root"], lib);
    walk.lines
}

/// Checks `got` against the reviewed list in `file` (`STRATA_BLESS=1` rewrites it).
pub fn check_pinned(got: &BTreeSet<String>, file: &Path, header: &str) {
    if std::env::var_os("STRATA_BLESS").is_some() {
        let text: String = got.iter().map(|l| format!("{l}\n")).collect();
        std::fs::write(file, format!("{header}{text}")).unwrap();
        return;
    }
    let want = std::fs::read_to_string(file).unwrap_or_default();
    let want: BTreeSet<String> = want
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(String::from)
        .collect();
    let added: Vec<_> = got.difference(&want).cloned().collect();
    let removed: Vec<_> = want.difference(got).cloned().collect();
    assert!(
        added.is_empty() && removed.is_empty(),
        "the public surface changed; review, then regenerate {} with STRATA_BLESS=1.\n\
         added ({}):\n  {}\nremoved ({}):\n  {}",
        file.display(),
        added.len(),
        added.join("\n  "),
        removed.len(),
        removed.join("\n  ")
    );
}

pub struct Walk<'a> {
    index: &'a serde_json::Map<String, Value>,
    lines: BTreeSet<String>,
    /// Items whose members (fields, variants, methods, impls) were listed already: a type
    /// re-exported at two paths lists its members once, under the first path walked.
    expanded: HashSet<String>,
}

pub fn kind(item: &Value) -> &str {
    item["inner"]
        .as_object()
        .and_then(|o| o.keys().next())
        .map_or("?", String::as_str)
}

pub fn public(item: &Value) -> bool {
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
            "function" => format!("fn {path}{}", signature(item)),
            "constant" => format!(
                "const {path}: {} = {}",
                ty(&item["inner"]["constant"]["type"]),
                value(&item["inner"]["constant"]["const"]["expr"])
            ),
            "static" => format!("static {path}: {}", ty(&item["inner"]["static"]["type"])),
            "type_alias" => format!("type {path} = {}", ty(&item["inner"]["type_alias"]["type"])),
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
                            self.lines.insert(format!(
                                "field {path}.{}: {}",
                                fi["name"].as_str().unwrap(),
                                ty(&fi["inner"]["struct_field"])
                            ));
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
            "function" => format!("fn {path}::{name}{}", signature(item)),
            "assoc_const" => format!(
                "const {path}::{name}: {} = {}",
                ty(&item["inner"]["assoc_const"]["type"]),
                value(&item["inner"]["assoc_const"]["value"])
            ),
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

/// A function's signature: its parameters (names and types) and its return type, so that a
/// change of arity, of a type or a renamed parameter shows.
fn signature(item: &Value) -> String {
    let sig = &item["inner"]["function"]["sig"];
    let inputs: Vec<String> = sig["inputs"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|p| format!("{}: {}", p[0].as_str().unwrap_or("?"), ty(&p[1])))
        .collect();
    let output = if sig["output"].is_null() {
        String::new()
    } else {
        format!(" -> {}", ty(&sig["output"]))
    };
    format!("({}){output}", inputs.join(", "))
}

/// A constant's value as rustdoc writes it, or for a long one (a shader's text) its length and
/// a digest, so that any change shows in one line.
fn value(v: &Value) -> String {
    let text = v.as_str().unwrap_or("?");
    if text.len() <= 60 {
        return text.to_string();
    }
    let digest = text.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    });
    format!("<{} bytes, FNV-1a {digest:016x}>", text.len())
}

/// A type of rustdoc's JSON as text, by its path (never by the item ids, which differ from one
/// build to another).
fn ty(t: &Value) -> String {
    let Some((k, v)) = t.as_object().and_then(|o| o.iter().next()) else {
        return t.to_string();
    };
    match k.as_str() {
        "primitive" | "generic" => v.as_str().unwrap_or("?").to_string(),
        "resolved_path" => {
            let name = v["path"].as_str().unwrap_or("?");
            let args = &v["args"]["angle_bracketed"]["args"];
            let args: Vec<String> = args
                .as_array()
                .into_iter()
                .flatten()
                .map(|a| match a.get("type") {
                    Some(t) => ty(t),
                    None => a.to_string(),
                })
                .collect();
            if args.is_empty() {
                name.to_string()
            } else {
                format!("{name}<{}>", args.join(", "))
            }
        }
        "borrowed_ref" => format!(
            "&{}{}",
            if v["is_mutable"] == true { "mut " } else { "" },
            ty(&v["type"])
        ),
        "slice" => format!("[{}]", ty(v)),
        "array" => format!("[{}; {}]", ty(&v["type"]), v["len"].as_str().unwrap_or("?")),
        "tuple" => format!(
            "({})",
            v.as_array()
                .into_iter()
                .flatten()
                .map(ty)
                .collect::<Vec<_>>()
                .join(", ")
        ),
        _ => {
            // anything else (impl Trait, dyn Trait, fn pointers): its JSON without item ids
            let mut v = t.clone();
            strip_ids(&mut v);
            v.to_string()
        }
    }
}

fn strip_ids(v: &mut Value) {
    match v {
        Value::Object(o) => {
            o.remove("id");
            o.values_mut().for_each(strip_ids);
        }
        Value::Array(a) => a.iter_mut().for_each(strip_ids),
        _ => {}
    }
}
