//! What `eom analyze bicycle` prints, on every reduction path, against the published
//! eigenvalues of the Whipple bicycle benchmark (Meijaard et al. 2007, Table 2; the digits are
//! good to about 1e-13, docs/references.md §A), with the heading and lateral position reported
//! as exact structural zeros.

mod common;
use common::{complex, eom_json};
use num_complex::Complex64;
use tests::references::{Sidecar, sidecar};

/// (v, the four lean/steer eigenvalues) for v = 1…10: Table 2(b) as printed, the table the
/// bicycle's sidecar names.
fn table(refs: &Sidecar) -> Vec<(f64, Vec<Complex64>)> {
    refs.table("tests/data/bicycle_table2.csv", &[]).rows()
}

/// `eom analyze bicycle --set v=V --method METHOD --format json`.
fn analyze(v: f64, method: &str) -> serde_json::Value {
    eom_json(&[
        "analyze",
        "bicycle",
        "--set",
        &format!("v={v}"),
        "--method",
        method,
        "--format",
        "json",
    ])
}

fn printed(v: f64, method: &str) -> (Vec<(f64, f64)>, usize) {
    let j = analyze(v, method);
    let e: Vec<(f64, f64)> = j["eigenvalues"]
        .as_array()
        .expect("eigenvalues")
        .iter()
        .map(complex)
        .collect();
    let zeros = j["structural_zeros"]
        .as_array()
        .expect("structural_zeros")
        .len();
    (e, zeros)
}

#[test]
fn printed_eigenvalues_equal_the_published_table_on_every_path() {
    let refs = sidecar("bicycle");
    let table = table(&refs);
    assert_eq!(table.len(), 10);
    for method in ["numeric", "symbolic", "robust"] {
        for (v, want) in &table {
            let (e, zeros) = printed(*v, method);
            assert_eq!(zeros, 2, "{method} v = {v}: heading and lateral position");
            let exact_zeros = e.iter().filter(|z| **z == (0.0, 0.0)).count();
            assert_eq!(exact_zeros, 2, "{method} v = {v}: {e:?}");
            let rest: Vec<(f64, f64)> = e.into_iter().filter(|z| *z != (0.0, 0.0)).collect();
            assert_eq!(want.len(), 4, "v = {v}: weave pair, capsize, castor");
            for w in want {
                let d = rest
                    .iter()
                    .map(|g| (g.0 - w.re).hypot(g.1 - w.im))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 1e-12,
                    "{method} v = {v}: {w} missing (nearest {d:e}) in {rest:?}"
                );
            }
        }
        // v = 0: four real roots (the sidecar's Table 2(b) entry at rest).
        let at_rest = refs.eigenvalues_at(&[("v", 0.0)]).expected();
        assert_eq!(at_rest.len(), 4);
        let (e, _) = printed(0.0, method);
        for w in at_rest {
            assert!(
                e.iter().any(|g| (g.0 - w.re).abs() < 1e-12 && g.1 == w.im),
                "{method} v = 0: {w} in {e:?}"
            );
        }
    }
}

#[test]
fn stability_is_decided_alike_by_analyze_and_sweep() {
    // Self-stable between the weave and capsize speeds (4.292…, 6.024…).
    for (v, stable) in [(4.0, false), (5.0, true), (6.0, true), (6.1, false)] {
        for method in ["numeric", "symbolic", "robust"] {
            let j = analyze(v, method);
            assert_eq!(j["stable"].as_bool(), Some(stable), "{method} v = {v}");
        }
    }
}

/// Away from the benchmark's values, where the numeric elimination leaves rounding residues in
/// place of the exact zeros: at 12 random points (every parameter within ±20 % of the
/// benchmark's, speed 1…10 m/s), every path still finds the two structural zeros, and the
/// paths (numeric and robust elimination, the symbolic reduction evaluated) agree on every
/// other eigenvalue to 1e-10 relative to the largest — the capsize root included, which the
/// split zero pair used to move by 3e-7.
#[test]
fn structural_zeros_are_found_at_random_points_on_every_path() {
    use rand::{Rng, SeedableRng};
    let names = [
        "w", "c", "lambda", "rR", "mR", "IRxx", "IRyy", "xB", "zB", "mB", "IBxx", "IByy", "IBzz",
        "IBxz", "xH", "zH", "mH", "IHxx", "IHyy", "IHzz", "IHxz", "rF", "mF", "IFxx", "IFyy",
    ];
    let nominal = [
        1.02, 0.08, 0.314159, 0.3, 2.0, 0.0603, 0.12, 0.3, -0.9, 85.0, 9.2, 11.0, 2.8, 2.4, 0.9,
        -0.7, 4.0, 0.05892, 0.06, 0.00708, -0.00756, 0.35, 3.0, 0.1405, 0.28,
    ];
    let mut rng = rand::rngs::StdRng::seed_from_u64(19);
    for _ in 0..12 {
        let mut args = vec!["analyze".to_string(), "bicycle".to_string()];
        for (n, v) in names.iter().zip(nominal) {
            let x = v * (0.8 + 0.4 * rng.random::<f64>());
            args.extend(["--set".into(), format!("{n}={x:e}")]);
        }
        let v = 1.0 + 9.0 * rng.random::<f64>();
        args.extend(["--set".into(), format!("v={v}")]);
        let mut per_path = Vec::new();
        for method in ["symbolic", "numeric", "robust"] {
            let mut a = args.clone();
            a.extend(["--method", method, "--format", "json"].map(String::from));
            let a: Vec<&str> = a.iter().map(String::as_str).collect();
            let j = eom_json(&a);
            let zeros = j["structural_zeros"].as_array().map_or(0, Vec::len);
            assert_eq!(zeros, 2, "{method} at {args:?}");
            let mut e: Vec<(f64, f64)> = j["eigenvalues"]
                .as_array()
                .expect("eigenvalues")
                .iter()
                .map(complex)
                .filter(|z| *z != (0.0, 0.0))
                .collect();
            e.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            per_path.push((method, e));
        }
        let (_, reference) = &per_path[0];
        let scale = reference.iter().fold(0.0f64, |m, z| m.max(z.0.hypot(z.1)));
        for (method, e) in &per_path[1..] {
            assert_eq!(e.len(), reference.len(), "{method}: {e:?} vs {reference:?}");
            for (g, w) in e.iter().zip(reference) {
                let d = (g.0 - w.0).hypot(g.1 - w.1);
                assert!(d <= 1e-10 * scale, "{method}: {g:?} vs {w:?} at {args:?}");
            }
        }
    }
}

/// The steady-state gains `eom analyze bicycle` prints for both published inputs: a constant
/// f = [T_phi, T_delta] holds q = (g K0 + v² K2)⁻¹ f, with the benchmark's K0 and K2
/// (Meijaard et al. 2007, Appendix A, the values for Table 1 to 14 decimals;
/// docs/references.md §A), on every path, at speeds where the bicycle is stable and not.
#[test]
#[allow(clippy::excessive_precision)]
fn printed_gains_are_the_published_static_compliance() {
    let k0 = [
        [-80.95, -2.59951685249872],
        [-2.59951685249872, -0.80329488458618],
    ];
    let k2 = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]];
    let g = 9.81;
    for v in [2.0, 5.0, 8.0] {
        let k = |i: usize, j: usize| g * k0[i][j] + v * v * k2[i][j];
        let det = k(0, 0) * k(1, 1) - k(0, 1) * k(1, 0);
        // Rows [phi, delta], columns [T_phi, T_delta].
        let want = [
            [k(1, 1) / det, -k(0, 1) / det],
            [-k(1, 0) / det, k(0, 0) / det],
        ];
        for method in ["symbolic", "numeric", "robust"] {
            let j = analyze(v, method);
            let gains = j["steady_state_gain"].as_array().expect("gains");
            assert_eq!(gains.len(), 4, "{method} v = {v}: {gains:?}");
            for (r, out) in ["phi", "delta"].iter().enumerate() {
                for (c, inp) in ["T_phi", "T_delta"].iter().enumerate() {
                    let got = gains
                        .iter()
                        .find(|x| x["output"] == *out && x["input"] == *inp)
                        .unwrap_or_else(|| panic!("no gain {out} / {inp}: {gains:?}"))["value"]
                        .as_f64()
                        .expect("a number");
                    let err = (got - want[r][c]).abs() / want[r][c].abs();
                    assert!(
                        err < 1e-9,
                        "{method} v = {v}: {out} / {inp} = {got} vs {} ({err:e})",
                        want[r][c]
                    );
                }
            }
        }
    }
}
