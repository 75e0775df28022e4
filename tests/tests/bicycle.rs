//! The Whipple bicycle benchmark (Meijaard, Papadopoulos, Ruina & Schwab 2007, Proc. R. Soc. A
//! 463:1955–1982): eigenvalues at v = 0…10 m/s against the published Table 2, by the robust
//! numeric path, the numeric elimination and the symbolic path evaluated at each speed, to
//! 1e-12 absolute; the 126-speed table of 17-digit values; and the double-double path, which
//! reproduces the exact values to ~1e-16 and shows the one published entry that is off.

use eom_model::{Linearizer, Method, assemble, reduce};
use eom_num::minreal::{MinrealOptions, minimal_realization};
use eom_sym::Dd;
use eom_sym::dd::refine_eigenvalue;
use eom_sym::rational::Rational;
use eom_sym::scalar::Scalar;
use num_complex::Complex64;
use tests::{max_abs_error, read_csv};

/// Published Table 2(b) (`tests/data/bicycle_table2.csv`): v, Re weave, Im weave, capsize,
/// castor for v = 1…10 m/s (v = 0, where all four roots are real, is [`at_rest`]).
fn published() -> Vec<[f64; 5]> {
    table(include_str!("../data/bicycle_table2.csv"))
}

/// The rows of a table of v, Re weave, Im weave, capsize, castor (a header line first).
fn table(text: &str) -> Vec<[f64; 5]> {
    text.lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().expect("a number")).collect();
            [v[0], v[1], v[2], v[3], v[4]]
        })
        .collect()
}

/// The same quantities computed exactly (mpmath, 60 digits) and printed to 17 digits
/// (`tests/data/bicycle_exact.csv`; docs/references.md §A, computed for this project in
/// 60-digit arithmetic).
fn exact() -> Vec<[f64; 5]> {
    table(include_str!("../data/bicycle_exact.csv"))
}

fn expected(row: &[f64; 5]) -> Vec<Complex64> {
    vec![
        Complex64::new(row[1], row[2]),
        Complex64::new(row[1], -row[2]),
        Complex64::new(row[3], 0.0),
        Complex64::new(row[4], 0.0),
    ]
}

/// Published Table 2(b) at v = 0: four real roots, from the bicycle's sidecar
/// (`models/bicycle.ref.toml`).
fn at_rest() -> Vec<Complex64> {
    let refs = tests::references::sidecar("bicycle");
    let roots = refs.eigenvalues_at(&[("v", 0.0)]).expected();
    assert!(
        roots.len() == 4 && roots.iter().all(|z| z.im == 0.0),
        "{roots:?}"
    );
    roots
}

/// The four lean/steer eigenvalues: the eigenvalues of the minimal realization from the steer
/// torque to the steer and roll angles. The two other modes — heading and lateral position, a
/// Jordan block at zero that no sensor sees — are removed by the orthogonal observability
/// staircase, and reported: the test checks that exactly they were removed. (Computing the
/// lean/steer roots from the 6-state matrix directly is ill-conditioned near the capsize
/// speed, where the capsize root approaches that Jordan block: κ ≈ 1/λ², e.g. 6e4 at 6 m/s.)
fn lean_steer(ss: &eom_num::StateSpace<f64>) -> Vec<Complex64> {
    assert_eq!(ss.states(), 6, "six states: {:?}", ss.names.states);
    let (mr, rep) = minimal_realization(ss, &MinrealOptions::default()).unwrap();
    assert_eq!(mr.states(), 4, "{rep:?}");
    assert_eq!(rep.removed.len(), 2);
    for m in &rep.removed {
        assert!(
            m.eigenvalue.norm() < 1e-6,
            "removed mode {:?} is not a structural zero",
            m.eigenvalue
        );
    }
    eom_num::modes::eigenvalues(&mr.a).unwrap()
}

#[test]
fn published_table_by_three_paths() {
    let model = models::build("bicycle", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let mut worst = [0.0f64; 3];
    let cases: Vec<(f64, Vec<Complex64>)> = std::iter::once((0.0, at_rest()))
        .chain(published().iter().map(|r| (r[0], expected(r))))
        .collect();
    for (v, exp) in &cases {
        let values = model.scope.values_with(&[("v", *v)]).unwrap();
        let paths = [
            sym.evaluate(&values).unwrap(),
            Linearizer::new(&model)
                .at(&[("v", *v)])
                .method(Method::Numeric)
                .run()
                .unwrap()
                .state_space,
            Linearizer::new(&model)
                .at(&[("v", *v)])
                .method(Method::Robust)
                .run()
                .unwrap()
                .state_space,
        ];
        for (k, ss) in paths.iter().enumerate() {
            let err = max_abs_error(&lean_steer(ss), exp);
            worst[k] = worst[k].max(err);
            assert!(err <= 1e-12, "v = {v}, path {k}: abs error {err:e}");
        }
    }
    eprintln!(
        "bicycle vs published Table 2: worst abs error symbolic {:.1e}, numeric {:.1e}, robust {:.1e}",
        worst[0], worst[1], worst[2]
    );
}

#[test]
fn one_hundred_twenty_six_speeds() {
    let model = models::build("bicycle", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let rows = read_csv(include_str!("../data/bicycle_eigs_126_speeds.csv"));
    assert_eq!(rows.len(), 126);
    let mut worst = 0.0f64;
    for r in rows {
        let exp: Vec<Complex64> = (0..4)
            .map(|k| Complex64::new(r[1 + 2 * k], r[2 + 2 * k]))
            .collect();
        let ss = sym
            .evaluate(&model.scope.values_with(&[("v", r[0])]).unwrap())
            .unwrap();
        let got = lean_steer(&ss);
        // Near v_d = 0.684 m/s two real roots coalesce into the weave pair: there the
        // eigenvalues are ill-conditioned (a double root), so compare the symmetric functions
        // of the close pair instead of the roots themselves.
        let err = max_abs_error(&got, &exp);
        let near_double_root = (r[0] - 0.684).abs() < 0.05;
        if near_double_root {
            let (s, p) = pair_sum_product(&got);
            let (se, pe) = pair_sum_product(&exp);
            assert!(
                (s - se).abs() < 1e-11 && (p - pe).abs() < 1e-10,
                "v = {}: sum {s} vs {se}, product {p} vs {pe}",
                r[0]
            );
        } else {
            worst = worst.max(err);
            assert!(err <= 1e-12, "v = {}: abs error {err:e}", r[0]);
        }
    }
    eprintln!("bicycle 126 speeds: worst abs error {worst:.1e}");
}

/// The small-matrix kernel that sweeps use (`eom_num::small_eigen`, structural zeros deflated
/// exactly, then Francis QR on the stack) on the full 6-state matrix of the symbolic path: two
/// exact zeros and the four lean/steer roots at the 126 speeds, to 1e-12 absolute (the
/// coalescing pair near 0.684 m/s by its sum and product), as accurate as faer's solver.
#[test]
fn small_kernel_at_one_hundred_twenty_six_speeds() {
    let model = models::build("bicycle", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let rows = read_csv(include_str!("../data/bicycle_eigs_126_speeds.csv"));
    let (mut worst, mut worst_faer) = (0.0f64, 0.0f64);
    let mut ws = eom_num::modes::EigenvaluesWorkspace::new(6);
    for r in rows {
        let exp: Vec<Complex64> = (0..4)
            .map(|k| Complex64::new(r[1 + 2 * k], r[2 + 2 * k]))
            .collect();
        let a = sym
            .evaluate(&model.scope.values_with(&[("v", r[0])]).unwrap())
            .unwrap()
            .a;
        let mut all = vec![Complex64::new(0.0, 0.0); 6];
        let zeros = eom_num::small_eigen::eigenvalues_small(a.as_slice(), 6, &mut all).unwrap();
        assert_eq!(zeros, 2, "v = {}: {all:?}", r[0]);
        let got: Vec<Complex64> = all.iter().copied().filter(|z| z.norm() != 0.0).collect();
        assert_eq!(got.len(), 4, "v = {}: {all:?}", r[0]);
        let mut faer = vec![Complex64::new(0.0, 0.0); 6];
        eom_num::modes::eigenvalues_faer_in(&a, &mut ws, &mut faer).unwrap();
        let faer: Vec<Complex64> = faer.into_iter().filter(|z| z.norm() != 0.0).collect();
        if (r[0] - 0.684).abs() < 0.05 {
            let (s, p) = pair_sum_product(&got);
            let (se, pe) = pair_sum_product(&exp);
            assert!(
                (s - se).abs() < 1e-11 && (p - pe).abs() < 1e-10,
                "v = {}: sum {s} vs {se}, product {p} vs {pe}",
                r[0]
            );
        } else {
            let err = max_abs_error(&got, &exp);
            worst = worst.max(err);
            worst_faer = worst_faer.max(max_abs_error(&faer, &exp));
            assert!(err <= 1e-12, "v = {}: abs error {err:e}", r[0]);
        }
    }
    eprintln!(
        "bicycle 126 speeds, small kernel: worst abs error {worst:.1e} (faer {worst_faer:.1e})"
    );
    assert!(
        worst <= 4.0 * worst_faer.max(1e-15),
        "{worst:e} vs faer's {worst_faer:e}"
    );
}

/// Sum and product of the two eigenvalues closest to each other (the coalescing pair).
fn pair_sum_product(e: &[Complex64]) -> (f64, f64) {
    let mut best = (0, 1, f64::INFINITY);
    for i in 0..e.len() {
        for j in i + 1..e.len() {
            let d = (e[i] - e[j]).norm();
            if d < best.2 {
                best = (i, j, d);
            }
        }
    }
    let (a, b) = (e[best.0], e[best.1]);
    ((a + b).re, (a * b).re)
}

fn exact_dd(x: f64) -> Dd {
    // The benchmark's parameters are short decimals: take the decimal, not the nearest double.
    Dd::from_rational(&Rational::from_decimal(&format!("{x}")).expect("decimal"))
}

/// The double-double path: the model evaluated, assembled and reduced in double-double, then
/// each eigenvalue refined by Newton's method in double-double. It reproduces the exact values
/// to ~1e-16, and therefore the published table to its printed accuracy — except one entry
/// (v = 7, castor), which is off by 6.0e-13 in the publication (docs/references.md §A).
#[test]
fn double_double_reproduces_exact_and_published_digits() {
    let model = models::build("bicycle", &[]).unwrap();
    let names = model.scope.names();
    let mut worst_exact = 0.0f64;
    for (row, publ) in exact().iter().zip(published().iter()) {
        let values: Vec<Dd> = names
            .iter()
            .zip(model.scope.nominal_values())
            .map(|(n, x)| match n.as_str() {
                "lambda" => Dd::PI / Dd::from_f64(10.0),
                "v" => exact_dd(row[0]),
                _ => exact_dd(x),
            })
            .collect();
        let m = model.evaluate_in::<Dd>(&values).unwrap();
        let red = reduce(&assemble(&m).unwrap(), None).unwrap();
        let a = &red.state_space.a;
        let rows: Vec<Vec<Dd>> = (0..a.nrows())
            .map(|i| (0..a.ncols()).map(|j| a[(i, j)]).collect())
            .collect();
        let approx = eom_num::modes::eigenvalues(&a.map(|x| x.nominal())).unwrap();
        let refined: Vec<(Dd, Dd)> = approx
            .iter()
            .filter(|z| z.norm() > 1e-5)
            .map(|z| refine_eigenvalue(&rows, (z.re, z.im)).expect("simple eigenvalue converges"))
            .collect();
        assert_eq!(refined.len(), 4);
        let got: Vec<Complex64> = refined
            .iter()
            .map(|(r, i)| Complex64::new(r.to_f64(), i.to_f64()))
            .collect();
        let err = max_abs_error(&got, &expected(row));
        worst_exact = worst_exact.max(err);
        assert!(
            err <= 1e-15 * 25.0,
            "v = {}: double-double vs exact {err:e}",
            row[0]
        );
        // Against the published digits: within their printed accuracy (~1e-13, docs/references.md §A) …
        for (g, e) in tests::match_eigenvalues(&got, &expected(publ)) {
            // Per component, as the table prints real and imaginary parts separately.
            let d = (g.re - e.re).abs().max((g.im - e.im).abs());
            if row[0] == 7.0 && e.re == publ[4] {
                // … except the castor root at 7 m/s, misprinted by 6.0e-13.
                assert!(
                    (d - 6.0e-13).abs() < 0.1e-13,
                    "v = 7 castor: |published − exact| = {d:e}"
                );
            } else {
                assert!(d < 1e-13, "v = {}: |{g} − published {e}| = {d:e}", row[0]);
            }
        }
    }
    eprintln!("bicycle double-double vs exact: worst abs error {worst_exact:.1e}");
}

#[test]
fn structure_is_reported() {
    let model = models::build("bicycle", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let rep = &sym.reduction.report;
    assert_eq!(rep.coordinates, 24);
    assert_eq!(rep.pinned, vec!["rear frame.x".to_string()]);
    assert_eq!((rep.position_states, rep.velocity_states), (4, 2));
    assert!(rep.redundant.is_empty(), "{:?}", rep.redundant);
    let ss = sym.state_space();
    let roots: Vec<eom_sym::Expr> =
        ss.a.iter()
            .chain(ss.b.iter())
            .chain(ss.c.iter())
            .chain(ss.d.iter())
            .copied()
            .collect();
    let ops = eom_sym::Expr::op_count(&roots).total();
    // PyDy needs 734 operations after common-subexpression elimination (bench/pydy/README.md).
    assert!(ops < 734, "{ops} operations");
    let _ = Dd::zero();
}
