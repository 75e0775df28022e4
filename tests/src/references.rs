//! The built-in models' reference answers: the sidecars `models/NAME.ref.toml` beside the model
//! files (format: docs/model-files.md, "Reference answers"), read for every test that needs a
//! model's reference numbers — `eom-cli/tests/references.rs` checks each entry through the
//! command line, and the other tests take the numbers they compare with from here (the
//! bicycle's Table 2, the shimmy's cubic, the stability boundaries) instead of typing them
//! again, so that each reference number has one home.
//!
//! A sidecar that does not parse, or an entry without its source, tolerance or reason, is a
//! defect of the repository: the readers panic with the file and the entry.

use num_complex::Complex64;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The repository's root folder (the data files' paths are relative to it).
pub fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The parameter values of an entry (`set = { NAME = VALUE, ... }`); the others keep their
/// defaults.
pub type Set = toml::Table;

/// A sidecar `models/NAME.ref.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sidecar {
    /// Why the model has no independent reference (then no reference is given).
    pub none: Option<String>,
    /// Eigenvalues at one point each.
    #[serde(default)]
    pub eigenvalues: Vec<Eigenvalues>,
    /// Eigenvalues at each row of a table.
    #[serde(default)]
    pub eigenvalue_table: Vec<EigenvalueTable>,
    /// Steady-state gains.
    #[serde(default)]
    pub gain: Vec<Gain>,
    /// Stability boundaries in a parameter.
    #[serde(default)]
    pub boundary: Vec<Boundary>,
    /// Static forces and moments items carry.
    #[serde(default)]
    pub preload: Vec<Preload>,
}

/// The eigenvalues at one point.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Eigenvalues {
    /// Where the numbers come from.
    pub source: String,
    /// The parameter values.
    #[serde(default)]
    pub set: Set,
    /// A JSON file (from the repository root) that string entries of `values` point into.
    pub data: Option<String>,
    /// The values: numbers, `[re, im]` or JSON pointers into `data`.
    pub values: Vec<toml::Value>,
    /// Each complex value also stands for its conjugate.
    #[serde(default)]
    pub pairs: bool,
    /// How many of the other eigenvalues are zero (|λ| ≤ 1e-6); all of them unless
    /// `partial`.
    #[serde(default)]
    pub zeros: usize,
    /// The reference gives only some of the eigenvalues (the rest are not checked).
    #[serde(default)]
    pub partial: bool,
    /// Tolerance relative to max(1, |λ|).
    pub tolerance: f64,
    /// Why that tolerance.
    pub why: String,
}

/// Eigenvalues at each row of a CSV table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EigenvalueTable {
    /// Where the numbers come from.
    pub source: String,
    /// The CSV file, from the repository root.
    pub file: String,
    /// The other parameters' values (the rest keep their defaults).
    #[serde(default)]
    pub set: Set,
    /// The parameter the table's first column sets.
    pub param: String,
    /// Each eigenvalue: a column name (real) or two (real and imaginary parts).
    pub columns: Vec<toml::Value>,
    /// Each complex value also stands for its conjugate.
    #[serde(default)]
    pub pairs: bool,
    /// A row gives only some of the eigenvalues.
    #[serde(default)]
    pub partial: bool,
    /// Tolerance relative to max(1, |λ|).
    pub tolerance: f64,
    /// Why that tolerance.
    pub why: String,
}

/// A steady-state gain.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Gain {
    /// Where the number comes from.
    pub source: String,
    /// The parameter values.
    #[serde(default)]
    pub set: Set,
    /// A JSON file that a string `value` points into.
    pub data: Option<String>,
    /// The output, as the model names it.
    pub output: String,
    /// The input, as the model names it.
    pub input: String,
    /// The gain: a number or a JSON pointer into `data`.
    pub value: toml::Value,
    /// Tolerance relative to max(1, |gain|).
    pub tolerance: f64,
    /// Why that tolerance.
    pub why: String,
}

/// The stability boundaries in one parameter.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Boundary {
    /// Where the numbers come from.
    pub source: String,
    /// The other parameters' values.
    #[serde(default)]
    pub set: Set,
    /// A JSON file that string entries of `values` and `frequencies` point into.
    pub data: Option<String>,
    /// The sweep's `--param`, NAME=START:STOP:COUNT.
    pub param: String,
    /// The parameter values where stability changes, in increasing order.
    pub values: Vec<toml::Value>,
    /// |Im λ| at each boundary (a flutter frequency; 0 for a real crossing), if given.
    #[serde(default)]
    pub frequencies: Vec<toml::Value>,
    /// Tolerance relative to max(1, |value|).
    pub tolerance: f64,
    /// Why that tolerance.
    pub why: String,
}

/// The static force (and moment) an item carries at the equilibrium, on the body it names, in
/// ground axes.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Preload {
    /// Where the numbers come from.
    pub source: String,
    /// The parameter values.
    #[serde(default)]
    pub set: Set,
    /// The item as the output names it, e.g. "flex point `tail gear`".
    pub item: String,
    /// The force.
    pub force: [f64; 3],
    /// The moment.
    #[serde(default)]
    pub moment: [f64; 3],
    /// Tolerance relative to max(1, |force|) and max(1, |moment|).
    pub tolerance: f64,
    /// Why that tolerance.
    pub why: String,
}

/// The model files under `models/` (but the crate's manifest and the sidecars), sorted.
pub fn model_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join("models"))
        .expect("the models folder")
        .map(|e| e.expect("an entry").path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.ends_with(".toml") && name != "Cargo.toml" && !name.ends_with(".ref.toml")
        })
        .collect();
    files.sort();
    files
}

/// The sidecar of the model file `models/NAME.toml`.
pub fn sidecar(name: &str) -> Sidecar {
    sidecar_of(&repo().join("models").join(format!("{name}.toml")))
}

/// The sidecar of a model file, parsed and checked: references or a reason for none, and every
/// reference with its source, its tolerance (0 < tol < 0.1) and why.
pub fn sidecar_of(file: &Path) -> Sidecar {
    let path = file.with_extension("ref.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: a model needs its sidecar ({e})", path.display()));
    let s: Sidecar = toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let texts: Vec<(&String, &String, f64)> = s
        .eigenvalues
        .iter()
        .map(|r| (&r.source, &r.why, r.tolerance))
        .chain(
            s.eigenvalue_table
                .iter()
                .map(|r| (&r.source, &r.why, r.tolerance)),
        )
        .chain(s.gain.iter().map(|r| (&r.source, &r.why, r.tolerance)))
        .chain(s.boundary.iter().map(|r| (&r.source, &r.why, r.tolerance)))
        .chain(s.preload.iter().map(|r| (&r.source, &r.why, r.tolerance)))
        .collect();
    match &s.none {
        Some(why) => assert!(
            texts.is_empty() && why.len() > 20,
            "{}: `none` with references, or without a reason",
            path.display()
        ),
        None => assert!(
            !texts.is_empty(),
            "{}: no reference and no `none`",
            path.display()
        ),
    }
    for (source, why, tol) in texts {
        assert!(
            !source.trim().is_empty() && !why.trim().is_empty() && tol > 0.0 && tol < 0.1,
            "{}: every reference names its source, its tolerance (0 < tol < 0.1) and why",
            path.display()
        );
    }
    s
}

impl Sidecar {
    /// The `[[eigenvalues]]` entry at exactly the parameter values `set` (an empty `set`: the
    /// defaults).
    pub fn eigenvalues_at(&self, set: &[(&str, f64)]) -> &Eigenvalues {
        self.eigenvalues
            .iter()
            .find(|r| same_set(&r.set, set))
            .unwrap_or_else(|| panic!("no [[eigenvalues]] at {set:?} in the sidecar"))
    }

    /// The `[[eigenvalue_table]]` entry of the CSV file `file` at exactly the other parameter
    /// values `set`.
    pub fn table(&self, file: &str, set: &[(&str, f64)]) -> &EigenvalueTable {
        self.eigenvalue_table
            .iter()
            .find(|r| r.file == file && same_set(&r.set, set))
            .unwrap_or_else(|| panic!("no [[eigenvalue_table]] of {file} at {set:?}"))
    }

    /// The `[[boundary]]` entry in the parameter `name` at exactly the other parameter values
    /// `set`.
    pub fn boundary_in(&self, name: &str, set: &[(&str, f64)]) -> &Boundary {
        self.boundary
            .iter()
            .find(|r| r.param_name() == name && same_set(&r.set, set))
            .unwrap_or_else(|| panic!("no [[boundary]] in {name} at {set:?}"))
    }
}

/// Whether an entry's `set` gives exactly the values `want` (in any order).
fn same_set(set: &Set, want: &[(&str, f64)]) -> bool {
    set.len() == want.len()
        && want
            .iter()
            .all(|(k, v)| set.get(*k).is_some_and(|x| toml_number(x, "set") == *v))
}

impl Eigenvalues {
    /// The reference eigenvalues, each complex value of a `pairs` entry followed by its
    /// conjugate's place at the end.
    pub fn expected(&self) -> Vec<Complex64> {
        let what = format!("eigenvalues at {} ({})", shown(&self.set), self.source);
        let data = data_file(&self.data);
        let want = values(&self.values, &data, Kind::Complex, &what);
        with_conjugates(want, self.pairs)
    }
}

impl EigenvalueTable {
    /// Each row's parameter value and reference eigenvalues (with the conjugates of a
    /// `pairs` entry).
    pub fn rows(&self) -> Vec<(f64, Vec<Complex64>)> {
        let text = std::fs::read_to_string(repo().join(&self.file))
            .unwrap_or_else(|e| panic!("{}: {e}", self.file));
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
        let col = |name: &str| {
            header
                .iter()
                .position(|h| h.trim() == name)
                .unwrap_or_else(|| panic!("{}: no column `{name}`", self.file))
        };
        let name = |v: &toml::Value| {
            v.as_str()
                .unwrap_or_else(|| panic!("{}: a column is a name or two", self.file))
                .to_string()
        };
        let first = col(header[0].trim());
        let mut out = Vec::new();
        for line in lines.filter(|l| !l.trim().is_empty()) {
            let row: Vec<f64> = line
                .split(',')
                .map(|x| x.trim().parse().expect("a number"))
                .collect();
            let want = self
                .columns
                .iter()
                .map(|c| match c {
                    toml::Value::Array(p) if p.len() == 2 => {
                        Complex64::new(row[col(&name(&p[0]))], row[col(&name(&p[1]))])
                    }
                    _ => Complex64::new(row[col(&name(c))], 0.0),
                })
                .collect();
            out.push((row[first], with_conjugates(want, self.pairs)));
        }
        out
    }

    /// The reference eigenvalues of the row at the parameter value `at`.
    pub fn row(&self, at: f64) -> Vec<Complex64> {
        self.rows()
            .into_iter()
            .find(|r| r.0 == at)
            .unwrap_or_else(|| panic!("{}: no row at {} = {at}", self.file, self.param))
            .1
    }
}

impl Gain {
    /// What the gain is, for messages: output, input, point and source.
    pub fn describe(&self) -> String {
        format!(
            "gain {}/{} at {} ({})",
            self.output,
            self.input,
            shown(&self.set),
            self.source
        )
    }

    /// The reference gain.
    pub fn expected(&self) -> f64 {
        let what = self.describe();
        let data = data_file(&self.data);
        values(std::slice::from_ref(&self.value), &data, Kind::Real, &what)[0].re
    }
}

impl Boundary {
    /// The swept parameter's name (`v` of `v=3:8:11`).
    pub fn param_name(&self) -> &str {
        self.param.split('=').next().unwrap_or("").trim()
    }

    /// The parameter values of the boundaries, in increasing order.
    pub fn expected(&self) -> Vec<f64> {
        self.numbers(&self.values)
    }

    /// |Im λ| at each boundary, where the reference gives it.
    pub fn frequencies(&self) -> Vec<f64> {
        self.numbers(&self.frequencies)
    }

    fn numbers(&self, vals: &[toml::Value]) -> Vec<f64> {
        let what = format!(
            "boundaries in {} at {} ({})",
            self.param,
            shown(&self.set),
            self.source
        );
        let data = data_file(&self.data);
        values(vals, &data, Kind::Real, &what)
            .into_iter()
            .map(|z| z.re)
            .collect()
    }
}

/// The values followed by the conjugates of the complex ones, where `pairs`.
fn with_conjugates(mut want: Vec<Complex64>, pairs: bool) -> Vec<Complex64> {
    if pairs {
        let conj: Vec<Complex64> = want
            .iter()
            .filter(|z| z.im != 0.0)
            .map(|z| z.conj())
            .collect();
        want.extend(conj);
    }
    want
}

/// Whether the numbers read are complex (eigenvalues: a pair of numbers is `[re, im]`) or
/// real (gains, boundaries: a list of numbers is that many values).
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Complex,
    Real,
}

/// A number read from a JSON value: a number or a string of digits.
fn json_number(v: &serde_json::Value, what: &str) -> f64 {
    match v {
        serde_json::Value::Number(n) => n.as_f64().expect("a finite number"),
        serde_json::Value::String(s) => s.parse().unwrap_or_else(|e| panic!("{what}: `{s}` ({e})")),
        _ => panic!("{what}: not a number: {v}"),
    }
}

/// The numbers a JSON value holds: a number, `{re, im}`, `[re, im]` (complex), or a list of
/// those.
fn json_values(v: &serde_json::Value, kind: Kind, what: &str, out: &mut Vec<Complex64>) {
    match v {
        serde_json::Value::Object(o) => out.push(Complex64::new(
            json_number(&o["re"], what),
            json_number(&o["im"], what),
        )),
        serde_json::Value::Array(a)
            if kind == Kind::Complex
                && a.len() == 2
                && a.iter().all(|x| !x.is_array() && !x.is_object()) =>
        {
            out.push(Complex64::new(
                json_number(&a[0], what),
                json_number(&a[1], what),
            ))
        }
        serde_json::Value::Array(a) => a.iter().for_each(|x| json_values(x, kind, what, out)),
        _ => out.push(Complex64::new(json_number(v, what), 0.0)),
    }
}

/// Reads the JSON data file a reference points into.
fn data_file(data: &Option<String>) -> Option<serde_json::Value> {
    data.as_ref().map(|f| {
        let text = std::fs::read_to_string(repo().join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{f}: {e}"))
    })
}

/// The numbers a sidecar entry gives: a number, `[re, im]`, or a JSON pointer (a string) into
/// `data`.
fn values(
    vals: &[toml::Value],
    data: &Option<serde_json::Value>,
    kind: Kind,
    what: &str,
) -> Vec<Complex64> {
    let mut out = Vec::new();
    for v in vals {
        match v {
            toml::Value::String(ptr) => {
                let d = data
                    .as_ref()
                    .unwrap_or_else(|| panic!("{what}: `{ptr}` without `data`"));
                let x = d
                    .pointer(ptr)
                    .unwrap_or_else(|| panic!("{what}: no `{ptr}` in the data"));
                json_values(x, kind, what, &mut out);
            }
            toml::Value::Array(a) if kind == Kind::Complex && a.len() == 2 => out.push(
                Complex64::new(toml_number(&a[0], what), toml_number(&a[1], what)),
            ),
            _ => out.push(Complex64::new(toml_number(v, what), 0.0)),
        }
    }
    out
}

fn toml_number(v: &toml::Value, what: &str) -> f64 {
    match v {
        toml::Value::Float(x) => *x,
        toml::Value::Integer(i) => *i as f64,
        _ => panic!("{what}: not a number: {v}"),
    }
}

/// `NAME=VALUE, ...` for messages (`the defaults` when empty).
pub fn shown(set: &Set) -> String {
    if set.is_empty() {
        return "the defaults".into();
    }
    let v: Vec<String> = set.iter().map(|(k, v)| format!("{k}={v}")).collect();
    v.join(", ")
}

/// The parameter values of a `set`, as numbers.
pub fn set_values(set: &Set) -> Vec<(String, f64)> {
    set.iter()
        .map(|(k, v)| (k.clone(), toml_number(v, &format!("set {k}"))))
        .collect()
}
