//! The hand-typed model lists in the documentation name exactly the catalogue's models: the
//! crate table of README.md and the model table of this crate's docs (`models/src/lib.rs`).
//! Adding a model to the catalogue without documenting it, or documenting one that is not in
//! it, fails here.

use std::collections::BTreeSet;

/// The catalogue's names, families as patterns (`chainN`).
fn catalogue_names() -> BTreeSet<String> {
    models::catalogue()
        .iter()
        .map(|m| m.name.to_string())
        .collect()
}

/// The words between backticks in `text`.
fn backticked(text: &str) -> Vec<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// Fails naming what one list lacks and what it has beyond the catalogue.
fn assert_lists_catalogue(listed: &[String], place: &str) {
    let catalogue = catalogue_names();
    let listed_set: BTreeSet<String> = listed.iter().cloned().collect();
    assert_eq!(
        listed.len(),
        listed_set.len(),
        "{place} lists a model twice: {listed:?}"
    );
    let missing: Vec<_> = catalogue.difference(&listed_set).collect();
    let unknown: Vec<_> = listed_set.difference(&catalogue).collect();
    assert!(
        missing.is_empty() && unknown.is_empty(),
        "{place}: catalogue models not listed: {missing:?}; listed names that are no catalogue \
         model: {unknown:?}"
    );
}

#[test]
fn readme_crate_table_lists_every_catalogue_model() {
    let readme = include_str!("../../README.md");
    let row = readme
        .lines()
        .find(|l| l.starts_with("| `models` |"))
        .expect("README.md has a crate-table row for `models`");
    // The first backticked word is the crate's name; the rest are models.
    let names = backticked(row);
    assert_eq!(names.first().map(String::as_str), Some("models"));
    assert_lists_catalogue(&names[1..], "README.md's `models` row");
}

#[test]
fn crate_docs_model_table_lists_every_catalogue_model() {
    let lib = include_str!("../src/lib.rs");
    let rows: Vec<&str> = lib
        .lines()
        .skip_while(|l| !l.starts_with("//! | model |"))
        .skip(2)
        .take_while(|l| l.starts_with("//! | `"))
        .collect();
    assert!(
        !rows.is_empty(),
        "models/src/lib.rs has a `| model |` table"
    );
    let names: Vec<String> = rows
        .iter()
        .map(|r| {
            backticked(r)
                .into_iter()
                .next()
                .expect("a backticked model name")
        })
        .collect();
    assert_lists_catalogue(&names, "the model table of models/src/lib.rs");
}
