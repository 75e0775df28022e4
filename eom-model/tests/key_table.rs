//! The table of keys in docs/model-files.md is the declaration's (`eom_model::items::KINDS`
//! and `BODY`): a kind or key added, renamed or removed in one and not the other fails here.

use eom_model::items::{BODY, COMMON_KEYS, KINDS, Kind};
use std::path::Path;

const BEGIN: &str = "<!-- keys: generated from eom_model::items::{BODY, KINDS} -->";
const END: &str = "<!-- end of the keys -->";

/// The table as the declarations give it.
fn table() -> String {
    let common: Vec<String> = COMMON_KEYS.iter().map(|k| format!("`{k}`")).collect();
    let mut t = format!(
        "| table | kind (in messages) | keys besides {} |\n|---|---|---|\n",
        common.join(" and ")
    );
    for k in std::iter::once(&BODY).chain(KINDS) {
        let Kind { name, key, keys } = k;
        let keys: Vec<String> = keys.iter().map(|k| format!("`{k}`")).collect();
        t.push_str(&format!("| `[[{key}]]` | {name} | {} |\n", keys.join(", ")));
    }
    t
}

#[test]
fn the_key_table_of_the_docs_is_that_of_the_declarations() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/model-files.md");
    let doc = std::fs::read_to_string(&path).expect("docs/model-files.md");
    let start = doc.find(BEGIN).expect("the table's opening marker") + BEGIN.len();
    let end = doc[start..].find(END).expect("the table's closing marker") + start;
    let want = table();
    assert_eq!(
        doc[start..end].trim(),
        want.trim(),
        "docs/model-files.md: the table of keys differs from the declarations; it should read\n{want}"
    );
}

#[test]
fn every_kind_has_one_name_and_one_file_key() {
    let mut names: Vec<&str> = KINDS.iter().map(|k| k.name).collect();
    let mut keys: Vec<&str> = KINDS.iter().map(|k| k.key).collect();
    names.sort_unstable();
    names.dedup();
    keys.sort_unstable();
    keys.dedup();
    assert_eq!(names.len(), KINDS.len());
    assert_eq!(keys.len(), KINDS.len());
    for k in KINDS {
        assert_eq!(k.key, k.name.replace(' ', "_"), "file key of {}", k.name);
    }
}
