//! `eom symbolic` against closed forms: the JSON expressions are read back with eom's parser
//! and evaluated at random points against the references of docs/references.md.

mod common;
use common::{eom, eom_json};
use eom_sym::{Expr, Scope, Tape};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A scope with the given parameters (nominal values irrelevant) and the expressions parsed.
fn parse_all(names: &[&str], texts: &[&str]) -> (Vec<Expr>, Vec<Expr>) {
    let mut scope = Scope::new();
    let params: Vec<Expr> = names
        .iter()
        .map(|n| scope.declare(n, 1.0).expect("declare"))
        .collect();
    let exprs = texts
        .iter()
        .map(|t| eom_sym::parse(t, &scope).unwrap_or_else(|e| panic!("`{t}` does not parse: {e}")))
        .collect();
    (params, exprs)
}

fn strings(v: &serde_json::Value) -> Vec<String> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_str().expect("a string").to_string())
        .collect()
}

#[test]
fn shimmy_polynomial_and_stability_read_back_from_json() {
    let j = eom_json(&["symbolic", "shimmy", "--solve-for", "x", "--format", "json"]);
    let names = ["m", "I", "k", "l", "x", "u"];
    let coeffs = strings(&j["characteristic_polynomial"]["coefficients"]);
    let scale = j["characteristic_polynomial"]["scale"]
        .as_str()
        .expect("scale");
    let conds: Vec<String> = j["stability"]
        .as_array()
        .expect("conditions")
        .iter()
        .map(|c| c["expression"].as_str().expect("expression").to_string())
        .collect();
    let mut texts: Vec<&str> = coeffs.iter().map(String::as_str).collect();
    texts.push(scale);
    texts.extend(conds.iter().map(String::as_str));
    let (params, exprs) = parse_all(&names, &texts);
    let tape = Tape::new(&exprs, &params).expect("tape");
    let mut rng = StdRng::seed_from_u64(1);
    for _ in 0..1000 {
        let v: Vec<f64> = (0..6).map(|_| 0.2 + 2.0 * rng.random::<f64>()).collect();
        let (m, i, k, l, x, u) = (v[0], v[1], v[2], v[3], v[4], v[5]);
        let a = x * l;
        let want = [k * l * u, k * l * l, m * a * u, i + m * a * a];
        let got = tape.eval_vec(&v).expect("finite");
        // p(s) is the reference cubic up to a common factor; det(sI − A) = p/scale is monic.
        for (g, w) in got[..4].iter().zip(&want) {
            assert!((g - w).abs() <= 1e-12 * w.abs().max(1.0), "{g} vs {w}");
        }
        assert!(
            (got[4] - want[3]).abs() <= 1e-12 * want[3],
            "scale {} vs {}",
            got[4],
            want[3]
        );
        // Stable ⇔ m a (l − a) > I (with u, x > 0): the printed conditions say the same.
        let stable = m * a * (l - a) > i;
        let margin = (m * a * (l - a) - i).abs();
        if margin > 1e-9 {
            assert_eq!(
                got[5..].iter().all(|&c| c > 0.0),
                stable,
                "at {v:?}: {conds:?}"
            );
        }
    }
    // The boundary of the Hurwitz condition: x = 1/2 ∓ √(1/4 − I/(m l²)).
    let b = j["stability"]
        .as_array()
        .expect("conditions")
        .iter()
        .find_map(|c| c["boundary"].as_array().filter(|r| r.len() == 2).cloned())
        .expect("a quadratic boundary");
    let roots: Vec<&str> = b.iter().map(|r| r.as_str().expect("root")).collect();
    let (params, exprs) = parse_all(&names, &roots);
    let tape = Tape::new(&exprs, &params).expect("tape");
    let got = tape
        .eval_vec(&[5.0, 1.05, 1.5, 1.0, 0.5, 10.0])
        .expect("finite");
    assert!(
        (got[0] - 0.3).abs() < 1e-15 && (got[1] - 0.7).abs() < 1e-15,
        "{got:?}"
    );
}

#[test]
fn spring_mass_damper_modal_closed_form() {
    let j = eom_json(&["symbolic", "smd", "--format", "json", "--transfer"]);
    let so = &j["second_order"];
    let (params, exprs) = parse_all(
        &["m", "k", "c"],
        &[
            so["natural_frequency"].as_str().expect("wn"),
            so["damping_ratio"].as_str().expect("zeta"),
        ],
    );
    let tape = Tape::new(&exprs, &params).expect("tape");
    for (m, k, c) in [(1.0, 10.0, 0.1), (2.5, 40.0, 3.0), (0.3, 0.7, 0.05)] {
        let got = tape.eval_vec(&[m, k, c]).expect("finite");
        let wn = f64::sqrt(k / m);
        assert!((got[0] - wn).abs() < 1e-14 * wn);
        assert!((got[1] - c / (2.0 * (k * m).sqrt())).abs() < 1e-15);
    }
    // z/F = 1/(m s² + c s + k): the first transfer function.
    let tf = &j["transfer_functions"][0];
    let num = strings(&tf["numerator"]);
    let den = strings(&tf["denominator"]);
    let mut texts: Vec<&str> = num.iter().map(String::as_str).collect();
    texts.extend(den.iter().map(String::as_str));
    let (params, exprs) = parse_all(&["m", "k", "c"], &texts);
    let v = Tape::new(&exprs, &params)
        .expect("tape")
        .eval_vec(&[2.0, 8.0, 0.5])
        .expect("finite");
    let (n, d) = v.split_at(num.len());
    assert_eq!(n.len(), 1, "numerator degree 0: {num:?}");
    let lead = n[0];
    assert!(
        ((d[2] / lead) - 2.0).abs() < 1e-14
            && ((d[1] / lead) - 0.5).abs() < 1e-14
            && ((d[0] / lead) - 8.0).abs() < 1e-14,
        "{d:?} / {lead}"
    );
}

#[test]
fn substituted_values_are_exact_and_large_models_get_a_note() {
    let r = eom(&["symbolic", "shimmy", "--set", "u=10", "--set", "I=0.21"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout.contains("substituted: u = 10, I = 21/100"),
        "{}",
        r.stdout
    );
    assert!(r.stdout.contains("s^3: m*l^2*x^2 + 21/100"), "{}", r.stdout);
    let big = eom(&["symbolic", "chain10"]);
    assert_eq!(big.code, 0, "{}", big.stderr);
    assert!(big.stdout.contains("--max-states"), "{}", big.stdout);
    let bad = eom(&["symbolic", "shimmy", "--solve-for", "q"]);
    assert_eq!(bad.code, 2);
    assert!(
        bad.stderr.contains("q") && bad.stderr.contains("x"),
        "{}",
        bad.stderr
    );
}
