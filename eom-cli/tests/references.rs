//! Every model's reference answers, as the user sees them: for each model file under
//! `models/` (found by reading the folder, never a typed list) its sidecar `NAME.ref.toml`
//! (format: docs/model-files.md, "Reference answers") is read, and each reference is checked
//! against the `eom` command line's JSON output (`eom analyze --format json`: eigenvalues,
//! steady-state gains, preloads; `eom sweep --format json`: stability boundaries) at the parameter values it names, within the tolerance it states. A model
//! without an independent reference says so in its sidecar, with the reason; those are
//! counted and printed. Every entry of the catalogue (`models::names()`) must have a file
//! there, so a new built-in model cannot come without its sidecar.

mod common;
use common::eom_json;
use serde::Deserialize;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A sidecar `models/NAME.ref.toml`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Sidecar {
    /// Why the model has no independent reference (then no reference is given).
    none: Option<String>,
    #[serde(default)]
    eigenvalues: Vec<Eigenvalues>,
    #[serde(default)]
    eigenvalue_table: Vec<EigenvalueTable>,
    #[serde(default)]
    gain: Vec<Gain>,
    #[serde(default)]
    boundary: Vec<Boundary>,
    #[serde(default)]
    preload: Vec<Preload>,
}

/// The static force (and moment) an item carries at the equilibrium (`eom analyze`'s
/// `preloads`), on the body it names, in ground axes.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Preload {
    source: String,
    #[serde(default)]
    set: toml::Table,
    /// The item as the output names it, e.g. "flex point `tail gear`".
    item: String,
    force: [f64; 3],
    #[serde(default)]
    moment: [f64; 3],
    tolerance: f64,
    why: String,
}

/// The eigenvalues of `eom analyze` at one point.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Eigenvalues {
    source: String,
    #[serde(default)]
    set: toml::Table,
    /// A JSON file (from the repository root) that string entries of `values` point into.
    data: Option<String>,
    values: Vec<toml::Value>,
    /// Each complex value also stands for its conjugate.
    #[serde(default)]
    pairs: bool,
    /// How many of the other eigenvalues are zero (|λ| ≤ 1e-6); all of them unless
    /// `partial`.
    #[serde(default)]
    zeros: usize,
    /// The reference gives only some of the eigenvalues (the rest are not checked).
    #[serde(default)]
    partial: bool,
    tolerance: f64,
    why: String,
}

/// Eigenvalues at each row of a CSV table, one `eom analyze` per row.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EigenvalueTable {
    source: String,
    file: String,
    /// The other parameters' values (the rest keep their defaults).
    #[serde(default)]
    set: toml::Table,
    /// The parameter the table's first column sets.
    param: String,
    /// Each eigenvalue: a column name (real) or two (real and imaginary parts).
    columns: Vec<toml::Value>,
    #[serde(default)]
    pairs: bool,
    #[serde(default)]
    partial: bool,
    tolerance: f64,
    why: String,
}

/// A steady-state gain of `eom analyze`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Gain {
    source: String,
    #[serde(default)]
    set: toml::Table,
    data: Option<String>,
    output: String,
    input: String,
    value: toml::Value,
    tolerance: f64,
    why: String,
}

/// The stability boundaries `eom sweep` locates on a grid.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Boundary {
    source: String,
    #[serde(default)]
    set: toml::Table,
    data: Option<String>,
    /// The sweep's `--param`, NAME=START:STOP:COUNT.
    param: String,
    /// The parameter values where stability changes, in increasing order.
    values: Vec<toml::Value>,
    /// |Im λ| at each boundary (a flutter frequency; 0 for a real crossing), if given.
    #[serde(default)]
    frequencies: Vec<toml::Value>,
    tolerance: f64,
    why: String,
}

/// A number read from a JSON value: a number or a string of digits.
fn json_number(v: &serde_json::Value, what: &str) -> f64 {
    match v {
        serde_json::Value::Number(n) => n.as_f64().expect("a finite number"),
        serde_json::Value::String(s) => s.parse().unwrap_or_else(|e| panic!("{what}: `{s}` ({e})")),
        _ => panic!("{what}: not a number: {v}"),
    }
}

/// Whether the numbers read are complex (eigenvalues: a pair of numbers is `[re, im]`) or
/// real (gains, boundaries: a list of numbers is that many values).
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Complex,
    Real,
}

/// The numbers a JSON value holds: a number, `{re, im}`, `[re, im]` (complex), or a list of
/// those.
fn json_values(v: &serde_json::Value, kind: Kind, what: &str, out: &mut Vec<(f64, f64)>) {
    match v {
        serde_json::Value::Object(o) => {
            out.push((json_number(&o["re"], what), json_number(&o["im"], what)))
        }
        serde_json::Value::Array(a)
            if kind == Kind::Complex
                && a.len() == 2
                && a.iter().all(|x| !x.is_array() && !x.is_object()) =>
        {
            out.push((json_number(&a[0], what), json_number(&a[1], what)))
        }
        serde_json::Value::Array(a) => a.iter().for_each(|x| json_values(x, kind, what, out)),
        _ => out.push((json_number(v, what), 0.0)),
    }
}

/// Reads the JSON data file a reference points into.
fn data_file(data: &Option<String>) -> Option<serde_json::Value> {
    data.as_ref().map(|f| {
        let text = std::fs::read_to_string(repo().join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{f}: {e}"))
    })
}

/// The complex numbers a sidecar entry gives: a number, `[re, im]`, or a JSON pointer (a
/// string) into `data`.
fn values(
    vals: &[toml::Value],
    data: &Option<serde_json::Value>,
    kind: Kind,
    what: &str,
) -> Vec<(f64, f64)> {
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
            toml::Value::Array(a) if kind == Kind::Complex && a.len() == 2 => {
                out.push((toml_number(&a[0], what), toml_number(&a[1], what)))
            }
            _ => out.push((toml_number(v, what), 0.0)),
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

/// `NAME=VALUE, ...` for messages (`defaults` when empty).
fn shown(set: &toml::Table) -> String {
    if set.is_empty() {
        return "the defaults".into();
    }
    let v: Vec<String> = set.iter().map(|(k, v)| format!("{k}={v}")).collect();
    v.join(", ")
}

/// `--set NAME=VALUE` arguments.
fn set_args(set: &toml::Table, what: &str) -> Vec<String> {
    set.iter()
        .flat_map(|(k, v)| {
            [
                "--set".to_string(),
                format!("{k}={:?}", toml_number(v, what)),
            ]
        })
        .collect()
}

fn run(args: Vec<String>) -> serde_json::Value {
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    eom_json(&a)
}

fn analyze(model: &str, set: &[String]) -> serde_json::Value {
    let mut a = vec![
        "analyze".to_string(),
        model.into(),
        "--format".into(),
        "json".into(),
    ];
    a.extend(set.iter().cloned());
    run(a)
}

/// The deviation of `got` from `want` relative to max(1, |want|).
fn deviation(got: (f64, f64), want: (f64, f64)) -> f64 {
    (got.0 - want.0).hypot(got.1 - want.1) / want.0.hypot(want.1).max(1.0)
}

/// The size of an eigenvalue counted as zero.
const ZERO: f64 = 1e-6;

/// Matches each reference eigenvalue with the nearest unmatched one of `got`; the largest
/// deviation. The others must be `zeros` zero eigenvalues (all of them unless `partial`).
fn match_eigenvalues(
    got: &[(f64, f64)],
    want: &[(f64, f64)],
    zeros: usize,
    partial: bool,
    what: &str,
) -> f64 {
    let mut free: Vec<(f64, f64)> = got.to_vec();
    let mut worst = 0.0f64;
    for &w in want {
        // A zero of the reference (a multiple zero computed in floating point splits by about
        // ε^(1/k)) is any eigenvalue within the zero tolerance.
        if w.0.hypot(w.1) <= ZERO {
            let k = free
                .iter()
                .position(|g| g.0.hypot(g.1) <= ZERO)
                .unwrap_or_else(|| panic!("{what}: no zero eigenvalue left in {free:?}"));
            free.swap_remove(k);
            continue;
        }
        let (k, d) = free
            .iter()
            .enumerate()
            .map(|(k, &g)| (k, deviation(g, w)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or_else(|| panic!("{what}: more reference values than eigenvalues {got:?}"));
        worst = worst.max(d);
        free.swap_remove(k);
    }
    let zero = free.iter().filter(|z| z.0.hypot(z.1) <= ZERO).count();
    assert!(
        zero >= zeros && (partial || free.len() == zeros),
        "{what}: {zeros} zero eigenvalues expected besides the reference, left {free:?}"
    );
    worst
}

/// What one model's references gave: (what, deviation, tolerance) per reference.
type Checked = Vec<(String, f64, f64)>;

/// One model file's outcome: its references checked and its `none`, or why the check failed.
type Outcome = Result<(Checked, Option<String>), String>;

fn check_eigenvalues(model: &str, r: &Eigenvalues, out: &mut Checked) {
    let what = format!("{model} eigenvalues at {} ({})", shown(&r.set), r.source);
    let data = data_file(&r.data);
    let mut want = values(&r.values, &data, Kind::Complex, &what);
    if r.pairs {
        let conj: Vec<_> = want
            .iter()
            .filter(|z| z.1 != 0.0)
            .map(|z| (z.0, -z.1))
            .collect();
        want.extend(conj);
    }
    let got = common::eigenvalues(&analyze(model, &set_args(&r.set, &what)));
    let d = match_eigenvalues(&got, &want, r.zeros, r.partial, &what);
    out.push((what, d, r.tolerance));
}

fn check_table(model: &str, r: &EigenvalueTable, out: &mut Checked) {
    let text = std::fs::read_to_string(repo().join(&r.file)).expect("the table");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h.trim() == name)
            .unwrap_or_else(|| panic!("{}: no column `{name}`", r.file))
    };
    let first = header[0].trim();
    let mut worst = 0.0f64;
    let mut rows = 0;
    for line in lines.filter(|l| !l.trim().is_empty()) {
        let row: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse().expect("a number"))
            .collect();
        let at = row[col(first)];
        let what = format!("{model} eigenvalues at {}={at} ({})", r.param, r.source);
        let mut want = Vec::new();
        for c in &r.columns {
            match c {
                toml::Value::String(re) => want.push((row[col(re)], 0.0)),
                toml::Value::Array(p) => {
                    let name = |v: &toml::Value| v.as_str().expect("a column name").to_string();
                    want.push((row[col(&name(&p[0]))], row[col(&name(&p[1]))]));
                }
                _ => panic!("{}: a column is a name or two", r.file),
            }
        }
        if r.pairs {
            let conj: Vec<_> = want
                .iter()
                .filter(|z| z.1 != 0.0)
                .map(|z| (z.0, -z.1))
                .collect();
            want.extend(conj);
        }
        let mut set = set_args(&r.set, &what);
        set.extend(["--set".into(), format!("{}={at:?}", r.param)]);
        let got = common::eigenvalues(&analyze(model, &set));
        worst = worst.max(match_eigenvalues(&got, &want, 0, r.partial, &what));
        rows += 1;
    }
    let what = format!(
        "{model} eigenvalues at {rows} rows of {} and {} ({})",
        r.file,
        shown(&r.set),
        r.source
    );
    out.push((what, worst, r.tolerance));
}

fn check_gain(model: &str, r: &Gain, out: &mut Checked) {
    let what = format!(
        "{model} gain {}/{} at {} ({})",
        r.output,
        r.input,
        shown(&r.set),
        r.source
    );
    let data = data_file(&r.data);
    let want = values(std::slice::from_ref(&r.value), &data, Kind::Real, &what)[0].0;
    let a = analyze(model, &set_args(&r.set, &what));
    let g = a["steady_state_gain"]
        .as_array()
        .expect("gains")
        .iter()
        .find(|g| g["output"] == r.output.as_str() && g["input"] == r.input.as_str())
        .unwrap_or_else(|| panic!("{what}: no such gain in {}", a["steady_state_gain"]));
    let got = g["value"]
        .as_f64()
        .unwrap_or_else(|| panic!("{what}: no finite gain: {g}"));
    out.push((what, deviation((got, 0.0), (want, 0.0)), r.tolerance));
}

fn check_boundary(model: &str, r: &Boundary, out: &mut Checked) {
    let what = format!(
        "{model} boundaries in {} at {} ({})",
        r.param,
        shown(&r.set),
        r.source
    );
    let data = data_file(&r.data);
    let want = values(&r.values, &data, Kind::Real, &what);
    let freqs = values(&r.frequencies, &data, Kind::Real, &what);
    let mut a = vec![
        "sweep".to_string(),
        model.into(),
        "--param".into(),
        r.param.clone(),
        "--format".into(),
        "json".into(),
        "--quiet".into(),
    ];
    a.extend(set_args(&r.set, &what));
    let s = run(a);
    let got: Vec<(f64, f64)> = s["boundaries"]
        .as_array()
        .expect("boundaries")
        .iter()
        .map(|b| {
            (
                b["value"].as_f64().expect("a value"),
                b["eigenvalue"]["im"].as_f64().expect("an eigenvalue").abs(),
            )
        })
        .collect();
    assert_eq!(got.len(), want.len(), "{what}: the sweep's {got:?}");
    let mut worst = 0.0f64;
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        worst = worst.max(deviation((g.0, 0.0), (w.0, 0.0)));
        if let Some(f) = freqs.get(k) {
            worst = worst.max(deviation((g.1, 0.0), (f.0, 0.0)));
        }
    }
    out.push((what, worst, r.tolerance));
}

fn check_preload(model: &str, r: &Preload, out: &mut Checked) {
    let what = format!(
        "{model} preload of {} at {} ({})",
        r.item,
        shown(&r.set),
        r.source
    );
    let a = analyze(model, &set_args(&r.set, &what));
    let p = a["preloads"]["items"]
        .as_array()
        .expect("preloads")
        .iter()
        .find(|p| p["item"] == r.item.as_str())
        .unwrap_or_else(|| panic!("{what}: no such item in {}", a["preloads"]));
    let vector = |key: &str| -> Vec<f64> {
        p[key]
            .as_array()
            .unwrap_or_else(|| panic!("{what}: no {key}: {p}"))
            .iter()
            .map(|x| x.as_f64().expect("a number"))
            .collect()
    };
    let mut worst = 0.0f64;
    for (got, want) in [(vector("force"), r.force), (vector("moment"), r.moment)] {
        let scale = want.iter().map(|x| x * x).sum::<f64>().sqrt().max(1.0);
        for (g, w) in got.iter().zip(want) {
            worst = worst.max((g - w).abs() / scale);
        }
    }
    out.push((what, worst, r.tolerance));
}

/// The message of a caught panic.
fn panic_text(e: &(dyn std::any::Any + Send)) -> String {
    e.downcast_ref::<String>()
        .cloned()
        .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "a panic".into())
}

/// The model files under `models/` (but the crate's manifest and the sidecars).
fn model_files() -> Vec<PathBuf> {
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

/// The sidecar of a model file, parsed.
fn sidecar(file: &Path) -> Sidecar {
    let path = file.with_extension("ref.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: a model needs its sidecar ({e})", path.display()));
    let s: Sidecar = toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let refs = s.eigenvalues.len()
        + s.eigenvalue_table.len()
        + s.gain.len()
        + s.boundary.len()
        + s.preload.len();
    match &s.none {
        Some(why) => assert!(
            refs == 0 && why.len() > 20,
            "{}: `none` with references, or without a reason",
            path.display()
        ),
        None => assert!(refs > 0, "{}: no reference and no `none`", path.display()),
    }
    let texts = s
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
        .chain(s.preload.iter().map(|r| (&r.source, &r.why, r.tolerance)));
    for (source, why, tol) in texts {
        assert!(
            !source.trim().is_empty() && !why.trim().is_empty() && tol > 0.0 && tol < 0.1,
            "{}: every reference names its source, its tolerance (0 < tol < 0.1) and why",
            path.display()
        );
    }
    s
}

/// How the command line names a model file: its catalogue name where the catalogue has it
/// (what users type), and the file itself too where the catalogue builds it another way (a
/// family: `chain10` is built in Rust, `models/chain10.toml` read from the file).
fn invocations(file: &Path) -> Vec<String> {
    let stem = file
        .file_stem()
        .expect("a name")
        .to_string_lossy()
        .into_owned();
    // Relative to the package folder, where cargo runs the test (shorter messages).
    let name = file.file_name().expect("a name").to_string_lossy();
    let path = format!("../models/{name}");
    if models::file_text(&stem).is_some() {
        vec![stem]
    } else if models::find(&stem).is_ok() {
        vec![stem, path]
    } else {
        vec![path]
    }
}

fn check_model(file: &Path) -> (Checked, Option<String>) {
    let s = sidecar(file);
    let mut out = Checked::new();
    for model in invocations(file) {
        s.eigenvalues
            .iter()
            .for_each(|r| check_eigenvalues(&model, r, &mut out));
        s.eigenvalue_table
            .iter()
            .for_each(|r| check_table(&model, r, &mut out));
        s.gain.iter().for_each(|r| check_gain(&model, r, &mut out));
        s.boundary
            .iter()
            .for_each(|r| check_boundary(&model, r, &mut out));
        s.preload
            .iter()
            .for_each(|r| check_preload(&model, r, &mut out));
    }
    (out, s.none)
}

#[test]
fn every_model_meets_its_reference_answers() {
    let files = model_files();
    // Every catalogue entry has its file (a family, `chainN`, at size 10) and so its sidecar.
    for info in models::catalogue() {
        let (name, stem) = (info.name, info.name_at(10));
        assert!(
            files
                .iter()
                .any(|f| f.file_stem().is_some_and(|s| s == stem.as_str())),
            "the catalogue's `{name}` has no models/{stem}.toml"
        );
    }
    // Each sidecar belongs to a model file.
    for e in std::fs::read_dir(repo().join("models")).expect("the folder") {
        let p = e.expect("an entry").path();
        if let Some(stem) = p.to_str().and_then(|s| s.strip_suffix(".ref.toml")) {
            let model = PathBuf::from(format!("{stem}.toml"));
            assert!(files.contains(&model), "{}: no model file", p.display());
        }
    }

    // Two workers: the CI machine's cores.
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results: Vec<(PathBuf, Outcome)> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..2)
            .map(|_| {
                s.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(f) = files.get(k) else { break };
                        // A model whose check panics is reported with the others.
                        let r = std::panic::catch_unwind(|| check_model(f))
                            .map_err(|e| panic_text(e.as_ref()));
                        done.push((f.clone(), r));
                    }
                    done
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("a worker"))
            .collect()
    });

    let (mut failed, mut checked, mut without) = (Vec::new(), 0, Vec::new());
    for (file, result) in &results {
        let stem = file.file_stem().expect("a name").to_string_lossy();
        let (refs, none) = match result {
            Ok(r) => r,
            Err(e) => {
                failed.push(format!("{stem}: {e}"));
                continue;
            }
        };
        if let Some(why) = none {
            without.push(format!("{stem}: {why}"));
        }
        for (what, d, tol) in refs {
            checked += 1;
            println!("{d:9.2e} (tolerance {tol:e}) {what}");
            // A NaN deviation fails too.
            if d.is_nan() || d > tol {
                failed.push(format!("{what}: deviation {d:e} > {tol:e}"));
            }
        }
    }
    println!(
        "{checked} references of {} models checked; {} without an independent reference:",
        files.len(),
        without.len()
    );
    for w in &without {
        println!("  {w}");
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}
