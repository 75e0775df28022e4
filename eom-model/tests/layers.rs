//! The modules of eom-model form one-way layers: a module uses only modules of its own layer
//! or of the layers below it (CONTRIBUTING.md, "Layers inside eom-model"). Checked on the
//! source: every `crate::module` a module's non-test code names.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The layers, bottom first.
const LAYERS: &[&[&str]] = &[
    &["error", "warning"],
    &["geometry"],
    &["eliminate", "canonical"],
    &["assemble"],
    &["items"],
    &["model", "fields", "validate"],
    &["reduce", "robust", "preloads"],
    &["compiled", "sensitivity"],
    &["aero", "linearize"],
    &["file", "tutorials"],
];

fn layer(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("src is readable") {
        let p = e.expect("entry").path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The modules named as `crate::NAME` in the code before the first `#[cfg(test)]`, comments
/// left out (`crate::Model` is the `model` module's).
fn uses(text: &str) -> BTreeSet<String> {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut out = BTreeSet::new();
    for line in code.lines() {
        let line = line.split("//").next().unwrap_or("");
        for part in line.split("crate::").skip(1) {
            let name: String = part
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            out.insert(if name == "Model" {
                "model".into()
            } else {
                name
            });
        }
    }
    out
}

#[test]
fn every_module_uses_only_its_layer_and_those_below() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut wrong = Vec::new();
    let mut unknown = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).expect("below src");
        let top = rel.iter().next().expect("a name").to_string_lossy();
        let module = top.trim_end_matches(".rs");
        if module == "lib" {
            continue;
        }
        let Some(own) = layer(module) else {
            unknown.push(module.to_string());
            continue;
        };
        let text = std::fs::read_to_string(f).expect("readable");
        for used in uses(&text) {
            if let Some(l) = layer(&used)
                && l > own
            {
                wrong.push(format!("{} uses crate::{used}", rel.display()));
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "modules missing from LAYERS: {unknown:?}"
    );
    assert!(
        wrong.is_empty(),
        "imports against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_check_sees_an_import_against_the_layers() {
    let text =
        "use crate::items::Body;\n// crate::file in a comment\n#[cfg(test)]\nuse crate::file;";
    assert_eq!(uses(text), BTreeSet::from(["items".to_string()]));
}
