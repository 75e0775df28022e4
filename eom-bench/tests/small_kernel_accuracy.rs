//! The small-matrix eigenvalue kernel on the bicycle at 256 random points (±20 % of nominal),
//! against the eigenvalues of the same rounded A refined in double-double: every eigenvalue
//! within the first-order bound n·ε·‖Ã‖_F·κ of a backward-stable solver (the bound the verdicts
//! use, without its safety factor), and the kernel as accurate as faer's solver in
//! distribution. The work-precision chart's worst bicycle error (a relative error of 5e-13 on
//! a capsize root of 5e-3, docs/work-precision.md) is this floor: an absolute error of
//! 0.2 ε‖A‖_F (‖A‖_F ≈ 49), which faer meets at other points.

use eom_bench::compare::match_eigenvalues;
use eom_bench::work_precision::{points, reference::ReferenceModel};
use eom_model::Linearizer;
use eom_sym::Dd;
use eom_sym::dd::refine_eigenvalue;
use nalgebra::DMatrix;
use num_complex::Complex64;

/// The eigenvalues of `a` as given, refined in double-double on `a` itself (so that only the
/// solver's error remains); `None` where Newton's method does not settle.
fn refined(a: &DMatrix<f64>, approx: &[Complex64]) -> Option<Vec<Complex64>> {
    let n = a.nrows();
    let rows: Vec<Vec<Dd>> = (0..n)
        .map(|i| (0..n).map(|j| Dd::from_f64(a[(i, j)])).collect())
        .collect();
    approx
        .iter()
        .map(|z| {
            if z.norm() == 0.0 {
                return Some(*z);
            }
            let (re, im) = refine_eigenvalue(&rows, (z.re, z.im))?;
            let r = Complex64::new(re.to_f64(), im.to_f64());
            ((r - z).norm() <= 1e-6 * z.norm()).then_some(r)
        })
        .collect()
}

fn percentile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

#[test]
fn small_kernel_is_backward_stable_on_the_bicycle() {
    let model = models::build("bicycle", &[]).expect("bicycle");
    let sym = Linearizer::new(&model).symbolic().expect("symbolic");
    let refm = ReferenceModel::new(&sym);
    let nominal = model.scope.nominal_values();
    let (mut rel_small, mut rel_faer) = (Vec::new(), Vec::new());
    let mut checked = 0;
    let mut worst_ratio = 0.0f64;
    for p in points(&nominal, 256, 0.2, 20261128) {
        let a = refm.at(&p).expect("reference").a;
        let n = a.nrows();
        let mut small = vec![Complex64::new(0.0, 0.0); n];
        eom_num::small_eigen::eigenvalues_small(a.as_slice(), n, &mut small).expect("kernel");
        let mut faer = vec![Complex64::new(0.0, 0.0); n];
        let mut ws = eom_num::modes::EigenvaluesWorkspace::new(n);
        eom_num::modes::eigenvalues_faer_in(&a, &mut ws, &mut faer).expect("faer");
        // The verdicts' estimates: 10·n·ε·‖Ã‖_F·κ (or the componentwise term) per eigenvalue.
        let est = eom_num::modes::eigenvalues_with_errors_faer(&a).expect("estimates");
        let Some(exact) = refined(&a, &faer) else {
            continue;
        };
        checked += 1;
        for (got, rel) in [(&small, &mut rel_small), (&faer, &mut rel_faer)] {
            for (g, e) in match_eigenvalues(got, &exact) {
                if e.norm() == 0.0 {
                    assert_eq!(g.norm(), 0.0, "structural zero at {p:?}");
                    continue;
                }
                let (_, tol) = est
                    .iter()
                    .min_by(|x, y| (x.0 - e).norm().total_cmp(&(y.0 - e).norm()))
                    .expect("estimates");
                assert!(
                    (g - e).norm() <= tol / 10.0,
                    "eigenvalue {e} at {p:?}: error {:e} beyond n·ε·‖Ã‖·κ = {:e}",
                    (g - e).norm(),
                    tol / 10.0
                );
                worst_ratio = worst_ratio.max((g - e).norm() / (tol / 10.0));
                rel.push((g - e).norm() / e.norm());
            }
        }
    }
    assert!(checked >= 250, "only {checked} of 256 points refined");
    let (m_s, m_f) = (
        percentile(&mut rel_small, 0.5),
        percentile(&mut rel_faer, 0.5),
    );
    let (p_s, p_f) = (
        percentile(&mut rel_small, 0.9),
        percentile(&mut rel_faer, 0.9),
    );
    let (x_s, x_f) = (
        percentile(&mut rel_small, 1.0),
        percentile(&mut rel_faer, 1.0),
    );
    println!("largest error over n·ε·‖Ã‖·κ: {worst_ratio:.3}");
    println!(
        "relative error, kernel / faer: median {m_s:.2e} / {m_f:.2e}, 90 % {p_s:.2e} / {p_f:.2e}, max {x_s:.2e} / {x_f:.2e}"
    );
    assert!(
        m_s <= 2.0 * m_f.max(f64::EPSILON),
        "median {m_s:e} against faer's {m_f:e}"
    );
    assert!(
        p_s <= 2.0 * p_f.max(f64::EPSILON),
        "90th percentile {p_s:e} against faer's {p_f:e}"
    );
}
