//! Model files: the built-in models are the files under `models/`, embedded as they are; the
//! files of the families (`chain10`, `chainp10`) give the state space the families build; a
//! model written by the exporter loads back into the same model; mutated files are rejected
//! with a position or load into exactly what they say, never a panic.

use eom_model::{Linearizer, Method, Model, file};
use num_complex::Complex64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::path::PathBuf;

/// Every catalogue entry by a name it builds under: the families at size 4.
fn builtins() -> Vec<String> {
    models::catalogue().iter().map(|m| m.name_at(4)).collect()
}

fn path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../models")
        .join(format!("{name}.toml"))
}

fn eigenvalues(m: &Model, at: &[(&str, f64)]) -> Vec<Complex64> {
    let ss = Linearizer::new(m)
        .at(at)
        .method(Method::Numeric)
        .run()
        .unwrap_or_else(|e| panic!("{}: {e}", m.name))
        .state_space;
    let mut e = eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues");
    e.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    e
}

fn assert_same(a: &[Complex64], b: &[Complex64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: {a:?} vs {b:?}");
    let pairs = tests::match_eigenvalues(a, b);
    let scale = b.iter().fold(1e-300f64, |m, x| m.max(x.norm()));
    for (x, y) in pairs {
        // Structural zero pairs split by √ε on every path alike; compare away from them.
        let tol = if y.norm() < 1e-6 * scale {
            1e-6 * scale
        } else {
            1e-12 * y.norm().max(1e-3 * scale)
        };
        assert!((x - y).norm() <= tol, "{what}: {x} vs {y}");
    }
}

/// A random point: every parameter scaled by a factor in [0.8, 1.2].
fn random_point(m: &Model, rng: &mut StdRng) -> Vec<(String, f64)> {
    m.scope
        .names()
        .into_iter()
        .zip(m.scope.nominal_values())
        .map(|(n, v)| (n, v * (0.8 + 0.4 * rng.random::<f64>())))
        .collect()
}

/// The families are built in Rust; the files `models/chain10.toml` and `models/chainp10.toml`
/// show what they build and must stay what the family builds (eigenvalues to 1e-12 at the
/// defaults and at 20 random points).
#[test]
fn the_family_files_equal_their_families() {
    let mut rng = StdRng::seed_from_u64(16);
    for name in ["chain10", "chainp10"] {
        let family = models::build(name, &[]).expect("family");
        let loaded = file::load(&path(name), &[]).unwrap_or_else(|e| panic!("{e}"));
        let f = &loaded.model;
        assert_eq!(f.scope.names(), family.scope.names(), "{name}: parameters");
        assert_same(&eigenvalues(f, &[]), &eigenvalues(&family, &[]), name);
        for _ in 0..20 {
            let p = random_point(&family, &mut rng);
            let at: Vec<(&str, f64)> = p.iter().map(|(k, v)| (k.as_str(), *v)).collect();
            assert_same(&eigenvalues(f, &at), &eigenvalues(&family, &at), name);
        }
    }
}

#[test]
fn exported_models_load_back_into_the_same_model() {
    for name in builtins() {
        let name = name.as_str();
        let builder = models::build(name, &[]).expect("builder");
        let text = file::to_toml(&builder);
        let back = file::from_str(&text, name, &[]).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_same(&eigenvalues(&back, &[]), &eigenvalues(&builder, &[]), name);
        // A second round trip gives the same text.
        assert_eq!(file::to_toml(&back), text, "{name}");
    }
}

#[test]
fn errors_name_the_line_the_item_and_the_field() {
    let good = std::fs::read_to_string(path("shimmy")).expect("shimmy.toml");
    let cases = [
        (
            "stiffness = [\"k\", 0]",
            "stifness = [\"k\", 0]",
            "unknown key `stifness` (did you mean `stiffness`?)",
        ),
        (
            "stiffness = [\"k\", 0]",
            "stiffness = [\"kk\", 0]",
            "flex_point `spring`, field `stiffness`",
        ),
        (
            "between = [\"chassis\", \"ground\"]\nat = [\"b\"",
            "between = [\"chasis\", \"ground\"]\nat = [\"b\"",
            "no body called `chasis`",
        ),
        (
            "forces = 1\naxis = [0, 1, 0]\nstiffness",
            "forces = 4\naxis = [0, 1, 0]\nstiffness",
            "expected an integer from 0 to 3",
        ),
        (
            "b = { value = \"l - x*l\"",
            "b = { value = \"a + l\"",
            "cycle",
        ),
        ("m = { value = 5,", "m = { value = -5,", "outside its range"),
        (
            "name = \"tyre\"",
            "name = \"spring\"",
            "already called `spring`",
        ),
    ];
    for (from, to, want) in cases {
        assert!(good.contains(from), "{from}");
        let mut bad = good.replacen(from, to, 1);
        if want == "cycle" {
            bad = bad.replacen("a = { value = \"x*l\"", "a = { value = \"b*x\"", 1);
        }
        let e = file::from_str(&bad, "shimmy.toml", &[])
            .expect_err(to)
            .to_string();
        assert!(e.contains(want), "{to}: {e}");
        // file:line:column
        let line = good[..good.find(from).expect("present")]
            .matches('\n')
            .count()
            + 1;
        assert!(
            e.starts_with(&format!("shimmy.toml:{line}:"))
                || want == "cycle"
                || want == "outside its range",
            "{to}: {e}"
        );
    }
}

/// Random edits of a valid file: each is rejected with an error (never a panic), or loads into
/// a model that its own export reproduces (so the model is what the file says).
#[test]
fn mutated_files_never_panic_and_never_load_something_else() {
    let good = std::fs::read_to_string(path("shimmy")).expect("shimmy.toml");
    let cases: usize = std::env::var("EOM_FILE_MUTATIONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    let mut rng = StdRng::seed_from_u64(2026);
    let alphabet: Vec<char> = "abcxyz019.-+*/^()[]{}=,\"' \n#_".chars().collect();
    let (mut accepted, mut rejected) = (0, 0);
    for _ in 0..cases {
        let mut t: Vec<char> = good.chars().collect();
        for _ in 0..rng.random_range(1..4) {
            let at = rng.random_range(0..t.len());
            match rng.random_range(0..3) {
                0 => {
                    t.remove(at);
                }
                1 => t.insert(at, alphabet[rng.random_range(0..alphabet.len())]),
                _ => t[at] = alphabet[rng.random_range(0..alphabet.len())],
            }
        }
        let text: String = t.into_iter().collect();
        let r = std::panic::catch_unwind(|| file::from_str(&text, "m.toml", &[]));
        match r {
            Err(_) => panic!("panic on:\n{text}"),
            Ok(Err(e)) => {
                rejected += 1;
                assert!(e.to_string().starts_with("m.toml"), "{e}");
            }
            Ok(Ok(model)) => {
                accepted += 1;
                let again =
                    file::from_str(&file::to_toml(&model), "again", &[]).expect("export loads");
                assert_eq!(file::to_toml(&again), file::to_toml(&model));
            }
        }
    }
    assert!(
        accepted > 0 && rejected > 0,
        "{accepted} accepted, {rejected} rejected"
    );
}

/// The README's model-file example is the spring-mass-damper: it loads, and gives the built-in
/// smd's eigenvalues.
#[test]
fn the_readmes_model_file_is_the_smd() {
    let readme = include_str!("../../README.md");
    let section = &readme[readme.find("## A model file").expect("section")..];
    let start = section.find("```toml\n").expect("a toml block") + 8;
    let text = &section[start..start + section[start..].find("```").expect("closed")];
    let m = file::from_str(text, "README.md", &[]).unwrap_or_else(|e| panic!("{e}"));
    let builtin = models::build("smd", &[]).expect("smd");
    assert_same(&eigenvalues(&m, &[]), &eigenvalues(&builtin, &[]), "README");
}
