//! Every model's reference answers, as the user sees them: for each model file under
//! `models/` (found by reading the folder, never a typed list) its sidecar `NAME.ref.toml`
//! (format: docs/model-files.md, "Reference answers"; read by `tests::references`, the
//! reader every test shares) is read, and each reference is checked against the `eom` command
//! line's JSON output (`eom analyze --format json`: eigenvalues, steady-state gains, preloads;
//! `eom sweep --format json`: stability boundaries) at the parameter values it names, within
//! the tolerance it states. A model
//! without an independent reference says so in its sidecar, with the reason; those are
//! counted and printed. Every entry of the catalogue (`models::names()`) must have a file
//! there, so a new built-in model cannot come without its sidecar.

mod common;
use common::eom_json;
use num_complex::Complex64;
use std::path::{Path, PathBuf};
use tests::references::{
    Boundary, EigenvalueTable, Eigenvalues, Gain, Preload, Set, model_files, repo, set_values,
    shown, sidecar_of,
};

/// `--set NAME=VALUE` arguments.
fn set_args(set: &Set) -> Vec<String> {
    set_values(set)
        .into_iter()
        .flat_map(|(k, v)| ["--set".to_string(), format!("{k}={v:?}")])
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

/// Complex numbers as the JSON helpers hold them, (re, im).
fn pairs(z: &[Complex64]) -> Vec<(f64, f64)> {
    z.iter().map(|z| (z.re, z.im)).collect()
}

fn check_eigenvalues(model: &str, r: &Eigenvalues, out: &mut Checked) {
    let what = format!("{model} eigenvalues at {} ({})", shown(&r.set), r.source);
    let want = pairs(&r.expected());
    let got = common::eigenvalues(&analyze(model, &set_args(&r.set)));
    let d = match_eigenvalues(&got, &want, r.zeros, r.partial, &what);
    out.push((what, d, r.tolerance));
}

fn check_table(model: &str, r: &EigenvalueTable, out: &mut Checked) {
    let mut worst = 0.0f64;
    let rows = r.rows();
    for (at, want) in &rows {
        let what = format!("{model} eigenvalues at {}={at} ({})", r.param, r.source);
        let mut set = set_args(&r.set);
        set.extend(["--set".into(), format!("{}={at:?}", r.param)]);
        let got = common::eigenvalues(&analyze(model, &set));
        worst = worst.max(match_eigenvalues(&got, &pairs(want), 0, r.partial, &what));
    }
    let what = format!(
        "{model} eigenvalues at {} rows of {} and {} ({})",
        rows.len(),
        r.file,
        shown(&r.set),
        r.source
    );
    out.push((what, worst, r.tolerance));
}

fn check_gain(model: &str, r: &Gain, out: &mut Checked) {
    let what = format!("{model} {}", r.describe());
    let want = r.expected();
    let a = analyze(model, &set_args(&r.set));
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
    let (want, freqs) = (r.expected(), r.frequencies());
    let mut a = vec![
        "sweep".to_string(),
        model.into(),
        "--param".into(),
        r.param.clone(),
        "--format".into(),
        "json".into(),
        "--quiet".into(),
    ];
    a.extend(set_args(&r.set));
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
        worst = worst.max(deviation((g.0, 0.0), (*w, 0.0)));
        if let Some(f) = freqs.get(k) {
            worst = worst.max(deviation((g.1, 0.0), (*f, 0.0)));
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
    let a = analyze(model, &set_args(&r.set));
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
    let s = sidecar_of(file);
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
