//! `eom analyze --matrices FILE`: the numeric A, B, C, D and the state, input and output names
//! written as NumPy `.npz` and MATLAB `.mat`, read back by NumPy (`numpy.load`) and SciPy
//! (`scipy.io.loadmat`) and compared with the JSON's `matrices` (the same numbers, bit for
//! bit, and the same names).
//!
//! Python comes from `EOM_PYTHON` (default `python3`). Without NumPy (or SciPy, for the `.mat`
//! part) that part is skipped with a message, unless `EOM_REQUIRE_SCIPY` is set (CI sets it,
//! after installing both), which makes the absence a failure.

mod common;
use common::{eom, eom_json};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn python() -> String {
    std::env::var("EOM_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// Whether `python -c "import MODULE"` works; a missing module fails the test when
/// `EOM_REQUIRE_SCIPY` is set.
fn has_module(module: &str) -> bool {
    let ok = Command::new(python())
        .args(["-c", &format!("import {module}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var_os("EOM_REQUIRE_SCIPY").is_none(),
            "EOM_REQUIRE_SCIPY is set but `{} -c 'import {module}'` fails",
            python()
        );
        eprintln!("skipped: {module} is not available to {}", python());
    }
    ok
}

/// The file read back by Python, as JSON: every matrix as rows of numbers (`repr` of each
/// float, exact), every name list as a list of strings.
const READER: &str = r#"
import json, sys
path = sys.argv[1]
if path.endswith('.npz'):
    import numpy as np
    z = np.load(path)
    out = {k: (z[k].tolist() if z[k].dtype.kind == 'f' else [str(s) for s in z[k]]) for k in z.files}
    out['_dtypes'] = {k: z[k].dtype.str for k in z.files}
    out['_shapes'] = {k: list(z[k].shape) for k in z.files}
else:
    import scipy.io as sio
    m = sio.loadmat(path)
    out = {}
    for k, v in m.items():
        if k.startswith('__'):
            continue
        if v.dtype.kind == 'f':
            out[k] = v.tolist()
        else:
            out[k] = [str(c[0]) if c.size else '' for c in v.ravel()]
    out['_shapes'] = {k: list(v.shape) for k, v in m.items() if not k.startswith('__')}
print(json.dumps(out))
"#;

fn read_back(path: &Path) -> Value {
    let out = Command::new(python())
        .args(["-c", READER, path.to_str().expect("UTF-8")])
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "reading {}: {}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON from the reader")
}

fn scratch() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("matrices");
    std::fs::create_dir_all(&d).expect("a directory");
    d
}

/// The file's matrices and names equal the JSON's, and the shapes are those of the model.
fn assert_same(file: &Value, json: &Value, what: &str) {
    let m = &json["matrices"];
    let (n, ni, no) = (
        m["states"].as_array().expect("states").len(),
        m["inputs"].as_array().expect("inputs").len(),
        m["outputs"].as_array().expect("outputs").len(),
    );
    for (name, shape) in [
        ("A", [n, n]),
        ("B", [n, ni]),
        ("C", [no, n]),
        ("D", [no, ni]),
    ] {
        let got: Vec<usize> = file["_shapes"][name]
            .as_array()
            .expect("a shape")
            .iter()
            .map(|x| x.as_u64().expect("a size") as usize)
            .collect();
        assert_eq!(got, shape, "{what}: shape of {name}");
        // Empty matrices read back as [] (no rows) or [[], …]: compare the numbers.
        let numbers = |v: &Value| -> Vec<f64> {
            v.as_array()
                .into_iter()
                .flatten()
                .flat_map(|r| r.as_array().expect("a row").clone())
                .map(|x| x.as_f64().expect("a number"))
                .collect()
        };
        let (a, b) = (numbers(&file[name]), numbers(&m[name]));
        assert_eq!(a.len(), shape[0] * shape[1], "{what}: {name}");
        assert!(
            a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
            "{what}: {name} differs: {a:?} vs {b:?}"
        );
    }
    for names in ["states", "inputs", "outputs"] {
        assert_eq!(file[names], m[names], "{what}: {names}");
    }
}

#[test]
fn the_json_has_the_matrices_with_their_names() {
    // The quarter car: 4 states, the road input, three sensors; A's rows are the equations of
    // the two masses (m z̈ = forces): the sprung mass's row is (ks, −ks, cs, −cs)/ms around
    // its own coordinates.
    let j = eom_json(&["analyze", "quarter_car", "--format", "json"]);
    let m = &j["matrices"];
    assert_eq!(m["states"], j["state_names"]);
    assert_eq!(
        m["inputs"],
        serde_json::json!(["z_g"]),
        "{}",
        serde_json::to_string(m).unwrap()
    );
    let a = &m["A"];
    let (ks, cs, ms) = (18000.0, 1500.0, 500.0);
    // Row of sprung.vz: ∂/∂(unsprung.z, sprung.z, unsprung.vz, sprung.vz).
    let row: Vec<f64> = a[3]
        .as_array()
        .expect("a row")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect();
    let want = [ks / ms, -ks / ms, cs / ms, -cs / ms];
    for (g, w) in row.iter().zip(want) {
        assert!((g - w).abs() <= 1e-12 * w.abs(), "{row:?} vs {want:?}");
    }
}

#[test]
fn npz_and_mat_files_read_back_with_numpy_and_scipy() {
    let dir = scratch();
    // A model without inputs and outputs: B, C, D empty, the name lists too.
    let bare = dir.join("bare.toml");
    std::fs::write(
        &bare,
        "[[body]]\nname = \"block\"\nmass = 2\n\n[[rigid_point]]\nname = \"slider\"\n\
         between = [\"block\", \"ground\"]\nforces = 2\nmoments = 3\naxis = [0, 0, 1]\n\n\
         [[flex_point]]\nname = \"spring\"\nbetween = [\"block\", \"ground\"]\nforces = 1\n\
         axis = [0, 0, 1]\nstiffness = [8, 0]\n",
    )
    .expect("the model file");
    let bare = bare.to_str().expect("UTF-8").to_string();
    for model in ["quarter_car", "bicycle", bare.as_str()] {
        let json = eom_json(&["analyze", model, "--format", "json"]);
        for (ext, module) in [("npz", "numpy"), ("mat", "scipy")] {
            if !has_module(module) {
                continue;
            }
            let stem = Path::new(model).file_stem().expect("a name");
            let path = dir.join(format!("{}.{ext}", stem.to_string_lossy()));
            let _ = std::fs::remove_file(&path);
            let r = eom(&[
                "analyze",
                model,
                "--matrices",
                path.to_str().expect("UTF-8"),
            ]);
            assert_eq!(r.code, 0, "{}", r.stderr);
            assert!(r.stderr.contains("wrote"), "{}", r.stderr);
            let file = read_back(&path);
            assert_same(&file, &json, &format!("{model}.{ext}"));
            if ext == "npz" {
                // Names as Unicode arrays (loaded without pickles), numbers as float64.
                assert!(
                    file["_dtypes"]["states"]
                        .as_str()
                        .unwrap()
                        .starts_with("<U")
                );
                assert_eq!(file["_dtypes"]["A"], "<f8");
            }
        }
    }
}

#[test]
fn a_matrices_file_of_another_kind_is_refused_before_the_work() {
    let r = eom(&["analyze", "smd", "--matrices", "out.csv"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("--matrices out.csv") && r.stderr.contains(".npz or .mat"),
        "{}",
        r.stderr
    );
}

#[test]
fn eom_reduce_writes_the_reduced_matrices() {
    // The reduced quarter car (3 of 4 states): the file holds the JSON's reduced A, B, C, D.
    let dir = scratch();
    let args = ["reduce", "quarter_car", "--order", "3"];
    let json = eom_json(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(json["matrices"]["states"].as_array().unwrap().len(), 3);
    for (ext, module) in [("npz", "numpy"), ("mat", "scipy")] {
        if !has_module(module) {
            continue;
        }
        let path = dir.join(format!("reduced.{ext}"));
        let _ = std::fs::remove_file(&path);
        let path_arg = path.to_str().expect("UTF-8");
        let r = eom(&[&args[..], &["--matrices", path_arg]].concat());
        assert_eq!(r.code, 0, "{}", r.stderr);
        assert_same(&read_back(&path), &json, &format!("reduced.{ext}"));
    }
}
