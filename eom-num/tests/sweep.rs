//! Parameter sweeps against closed forms: the shimmy cubic (Routh–Hurwitz gives the stable
//! interval 0.3 < x < 0.7 exactly), a vehicle-like model with neutral rigid-body modes, branches
//! that cross in real part, a real root crossing zero, and error propagation.

mod analysis_support;

use analysis_support::{eig_nalgebra, mat, rand_orth, rng};
use eom_num::NumError;
use eom_num::modes::{Stability, eigenvalues_with_errors, stability_of};
use eom_num::sweep::{Crossing, PointStability, Sweep, SweepError, screen_bound};
use nalgebra::DMatrix;
use num_complex::Complex64;

/// Companion matrix of the shimmy characteristic cubic
/// (Iz + m a²) s³ + m a u s² + k l² s + k l u with a = x·l, m = 5, l = 1, Iz = 1.05, k = 1.5,
/// u = 10. Routh–Hurwitz: stable iff (m a u)(k l²) > (Iz + m a²)(k l u), i.e.
/// x² − x + 0.21 < 0, i.e. 0.3 < x < 0.7; on the boundary s² = k l²/(Iz + m a²).
fn shimmy(x: f64) -> Result<DMatrix<f64>, std::convert::Infallible> {
    let (m, l, iz, k, u) = (5.0, 1.0, 1.05, 1.5, 10.0);
    let a = x * l;
    let c3 = iz + m * a * a;
    let (c2, c1, c0) = (m * a * u, k * l * l, k * l * u);
    Ok(mat(&[
        &[0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0],
        &[-c0 / c3, -c1 / c3, -c2 / c3],
    ]))
}

#[test]
fn shimmy_stable_interval_is_found_to_1e_9() {
    for count in [37, 101] {
        let res = Sweep::linspace(0.0, 1.0, count)
            .with_param_name("x")
            .run(shimmy)
            .unwrap();
        assert_eq!(res.param, "x");
        assert_eq!(res.points.len(), count);
        assert_eq!(res.stable_intervals.len(), 1, "{:?}", res.stable_intervals);
        let iv = res.stable_intervals[0];
        assert!((iv.lo - 0.3).abs() < 1e-9, "lo = {}", iv.lo);
        assert!((iv.hi - 0.7).abs() < 1e-9, "hi = {}", iv.hi);
        assert_eq!(res.boundaries.len(), 2, "{:?}", res.boundaries);
        let (b0, b1) = (&res.boundaries[0], &res.boundaries[1]);
        assert!(b0.converged && b1.converged);
        assert_eq!(b0.crossing, Crossing::Stabilizing);
        assert_eq!(b1.crossing, Crossing::Destabilizing);
        assert!(
            (b0.eigenvalue - Complex64::new(0.0, 1.0)).norm() < 1e-9,
            "{b0:?}"
        );
        let w = (3.0f64 / 7.0).sqrt();
        assert!(
            (b1.eigenvalue - Complex64::new(0.0, w)).norm() < 1e-9,
            "{b1:?}"
        );
        // No neutral branch; the stability classes agree with Routh–Hurwitz off the
        // boundaries.
        assert!(res.branches.iter().all(|b| !b.neutral));
        for p in &res.points {
            let x = p.value;
            if (x - 0.3).abs() > 1e-6 && (x - 0.7).abs() > 1e-6 {
                let want = if x > 0.3 && x < 0.7 {
                    PointStability::Stable
                } else {
                    PointStability::Unstable
                };
                assert_eq!(p.stability, want, "x = {x}");
            }
        }
    }
}

#[test]
fn branch_values_match_independent_eigenvalues_and_are_continuous() {
    let res = Sweep::linspace(0.0, 1.0, 51).run(shimmy).unwrap();
    for p in &res.points {
        let mut got = p.eigenvalues.clone();
        got.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        let want = eig_nalgebra(&shimmy(p.value).unwrap());
        for (g, w) in got.iter().zip(&want) {
            assert!(
                (g - w).norm() < 1e-10,
                "x = {}: {got:?} vs {want:?}",
                p.value
            );
        }
    }
    // The real root stays on one branch and the pair on the other two, as exact conjugates
    // with a fixed sign of the imaginary part.
    let first = &res.points[0].eigenvalues;
    let real = (0..3).find(|&j| first[j].im == 0.0).unwrap();
    let (up, down) = if first[(real + 1) % 3].im > 0.0 {
        ((real + 1) % 3, (real + 2) % 3)
    } else {
        ((real + 2) % 3, (real + 1) % 3)
    };
    for p in &res.points {
        let e = &p.eigenvalues;
        assert_eq!(e[real].im, 0.0, "x = {}", p.value);
        assert!(e[up].im > 0.0 && e[down] == e[up].conj(), "x = {}", p.value);
    }
}

/// Yaw-plane-like vehicle: lateral position y and heading ψ integrate (a double zero
/// eigenvalue with a Jordan chain, y' = u ψ + v), and a lateral/yaw pair σ(x) ± iω with
/// σ = x − 0.5 crossing at x = 0.5. Mixed by a fixed orthogonal basis.
fn vehicle(x: f64) -> Result<DMatrix<f64>, String> {
    let (u, w) = (10.0, 2.0);
    let s = x - 0.5;
    let a = mat(&[
        &[0.0, u, 1.0, 0.3],
        &[0.0, 0.0, 0.0, 1.0],
        &[0.0, 0.0, s, w],
        &[0.0, 0.0, -w, s],
    ]);
    let q = rand_orth(&mut rng(3), 4);
    Ok(q.transpose() * a * q)
}

#[test]
fn neutral_branches_are_reported_and_excluded() {
    let res = Sweep::linspace(0.0, 1.0, 41).run(vehicle).unwrap();
    let neutral = res.branches.iter().filter(|b| b.neutral).count();
    assert_eq!(neutral, 2, "{:?}", res.branches);
    assert_eq!(res.boundaries.len(), 1, "{:?}", res.boundaries);
    let b = &res.boundaries[0];
    assert!((b.value - 0.5).abs() < 1e-10, "{b:?}");
    assert!((b.eigenvalue - Complex64::new(0.0, 2.0)).norm() < 1e-9);
    assert_eq!(b.crossing, Crossing::Destabilizing);
    assert_eq!(res.stable_intervals.len(), 1);
    assert_eq!(res.stable_intervals[0].lo, 0.0);
    assert!((res.stable_intervals[0].hi - 0.5).abs() < 1e-10);
    // max_real ignores the neutral branches: it is σ(x) = x − 0.5.
    for p in &res.points {
        let m = p.max_real.unwrap();
        assert!((m - (p.value - 0.5)).abs() < 1e-12, "{m} at {}", p.value);
    }
    // Without the neutral classification (threshold 0) the rounding noise of the double
    // zero decides stability: no point is stable any more.
    let strict = Sweep::linspace(0.0, 1.0, 41)
        .with_neutral_rtol(0.0)
        .run(vehicle)
        .unwrap();
    assert!(strict.branches.iter().all(|b| !b.neutral));
    assert!(
        strict
            .points
            .iter()
            .all(|p| p.stability != PointStability::Stable)
    );
}

/// Two oscillatory pairs whose real parts cross at x = 0.5: σ₁ = x − 1 with ω₁ = 1 and
/// σ₂ = −x with ω₂ = 3 (mixed by a fixed orthogonal basis). Sorting by real part would swap
/// them at 0.5; tracked branches keep their |Im|.
fn crossing_pairs(x: f64) -> Result<DMatrix<f64>, String> {
    let (s1, s2) = (x - 1.0, -x);
    let a = mat(&[
        &[s1, 1.0, 0.0, 0.0],
        &[-1.0, s1, 0.0, 0.0],
        &[0.0, 0.0, s2, 3.0],
        &[0.0, 0.0, -3.0, s2],
    ]);
    let q = rand_orth(&mut rng(4), 4);
    Ok(q.transpose() * a * q)
}

#[test]
fn branches_crossing_in_real_part_keep_their_identity() {
    let res = Sweep::linspace(-0.5, 1.5, 41).run(crossing_pairs).unwrap();
    for j in 0..4 {
        let w0 = res.points[0].eigenvalues[j].im;
        for p in &res.points {
            let z = p.eigenvalues[j];
            assert!(
                (z.im - w0).abs() < 1e-10,
                "branch {j} jumps at {}: {z}",
                p.value
            );
        }
        // Real part linear in x along the branch: σ₁ or σ₂.
        let slope = res.points[1].eigenvalues[j].re - res.points[0].eigenvalues[j].re;
        assert!((slope.abs() - 0.05).abs() < 1e-10);
    }
    // Boundaries: σ₂ = 0 at x = 0 (stabilizing, 3i), σ₁ = 0 at x = 1 (destabilizing, 1i).
    assert_eq!(res.boundaries.len(), 2, "{:?}", res.boundaries);
    assert!(res.boundaries[0].value.abs() < 1e-10);
    assert!((res.boundaries[0].eigenvalue - Complex64::new(0.0, 3.0)).norm() < 1e-9);
    assert_eq!(res.boundaries[0].crossing, Crossing::Stabilizing);
    assert!((res.boundaries[1].value - 1.0).abs() < 1e-10);
    assert!((res.boundaries[1].eigenvalue - Complex64::new(0.0, 1.0)).norm() < 1e-9);
    assert_eq!(res.stable_intervals.len(), 1);
    let iv = res.stable_intervals[0];
    assert!(iv.lo.abs() < 1e-10 && (iv.hi - 1.0).abs() < 1e-10, "{iv:?}");
}

#[test]
fn real_branches_crossing_each_other_are_followed_through() {
    // λ₁ = −2 + x and λ₂ = −x (real) meet at x = 1; a third λ₃ = −3 stays.
    let f = |x: f64| -> Result<DMatrix<f64>, String> {
        let a = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![-2.0 + x, -x, -3.0]));
        let q = rand_orth(&mut rng(5), 3);
        Ok(q.transpose() * a * q)
    };
    let res = Sweep::linspace(0.05, 1.95, 20).run(f).unwrap();
    let first = &res.points[0].eigenvalues;
    let j1 = (0..3)
        .find(|&j| (first[j].re - (-1.95)).abs() < 1e-12)
        .unwrap();
    for p in &res.points {
        assert!((p.eigenvalues[j1].re - (-2.0 + p.value)).abs() < 1e-12);
    }
}

#[test]
fn a_real_root_crossing_zero_is_located() {
    // Capsize-like: a real eigenvalue x² − 0.16 (zero at x = 0.4) next to a stable pair
    // −1 ± 2i, with non-normal coupling, in a fixed orthogonal basis.
    let f = |x: f64| -> Result<DMatrix<f64>, String> {
        let a = mat(&[
            &[x * x - 0.16, 1.0, 0.5],
            &[0.0, -1.0, 2.0],
            &[0.0, -2.0, -1.0],
        ]);
        let q = rand_orth(&mut rng(6), 3);
        Ok(q.transpose() * a * q)
    };
    let res = Sweep::linspace(0.0, 1.0, 23).run(f).unwrap();
    assert_eq!(res.boundaries.len(), 1);
    let b = &res.boundaries[0];
    assert!((b.value - 0.4).abs() < 1e-10, "{b:?}");
    assert!(b.eigenvalue.norm() < 1e-9);
    assert_eq!(b.crossing, Crossing::Destabilizing);
    assert_eq!(res.stable_intervals.len(), 1);
    assert_eq!(res.stable_intervals[0].lo, 0.0);
    assert!((res.stable_intervals[0].hi - 0.4).abs() < 1e-10);
    // A user tolerance is honoured (looser tolerance, fewer evaluations).
    let loose = Sweep::linspace(0.0, 1.0, 23)
        .with_tolerance(1e-4)
        .run(f)
        .unwrap();
    assert!((loose.boundaries[0].value - 0.4).abs() < 1e-4);
    assert!(loose.boundaries[0].evaluations <= b.evaluations);
}

#[test]
fn a_real_root_crossing_next_to_a_neutral_zero() {
    // A heading-like integrator (exact zero eigenvalue) next to a real root 0.4 − x that
    // crosses zero. With the coupling `k` ≠ 0 (heading driven by the crossing state, as
    // ψ' = r) the two form a defective double zero at x = 0.4: each eigenvalue is then only
    // known to √ε ≈ 1.5e-8, and locating the root from the branch alone misses by ~1e-8. The
    // sum of the neutral and the crossing eigenvalue stays accurate, and the sweep uses it.
    for k in [0.0, 1.0] {
        let f = move |x: f64| -> Result<DMatrix<f64>, String> {
            let a = mat(&[
                &[0.0, k, 0.0, 0.0],
                &[0.0, 0.4 - x, 0.7, 0.0],
                &[0.0, 0.0, -1.0, 3.0],
                &[0.0, 0.0, -3.0, -1.0],
            ]);
            let q = rand_orth(&mut rng(12), 4);
            Ok(q.transpose() * a * q)
        };
        let res = Sweep::linspace(0.0, 1.0, 17).run(f).unwrap();
        assert_eq!(res.branches.iter().filter(|b| b.neutral).count(), 1);
        assert_eq!(res.boundaries.len(), 1, "{:?}", res.boundaries);
        let b = &res.boundaries[0];
        assert!((b.value - 0.4).abs() < 1e-10, "k = {k}: {b:?}");
        assert!(b.eigenvalue.re.abs() < 1e-10, "k = {k}: {b:?}");
        assert_eq!(b.crossing, Crossing::Stabilizing);
        assert_eq!(res.stable_intervals.len(), 1);
        assert!((res.stable_intervals[0].lo - 0.4).abs() < 1e-10);
        assert_eq!(res.stable_intervals[0].hi, 1.0);
    }
}

#[test]
fn decreasing_sweeps_give_the_same_intervals() {
    let res = Sweep::linspace(1.0, 0.0, 41).run(shimmy).unwrap();
    let iv = res.stable_intervals[0];
    assert!((iv.lo - 0.3).abs() < 1e-9 && (iv.hi - 0.7).abs() < 1e-9);
    // Directions are stated for an increasing parameter.
    assert_eq!(res.boundaries[0].crossing, Crossing::Stabilizing);
    assert_eq!(res.boundaries[1].crossing, Crossing::Destabilizing);
}

#[test]
fn model_errors_pass_through_with_the_parameter_value() {
    #[derive(Debug, PartialEq)]
    struct Broken(f64);
    // Fails on the grid: the first failing value in sweep order is reported.
    let f = |x: f64| {
        if x > 0.55 {
            Err(Broken(x))
        } else {
            Ok(shimmy(x).unwrap())
        }
    };
    match Sweep::linspace(0.0, 1.0, 11).with_param_name("a/l").run(f) {
        Err(SweepError::Model {
            param,
            value,
            source,
        }) => {
            assert_eq!(param, "a/l");
            assert!((value - 0.6).abs() < 1e-12);
            assert_eq!(source, Broken(value));
        }
        other => panic!("{other:?}"),
    }
    // Fails only between grid points, while a boundary is being located.
    let g = |x: f64| {
        if x > 0.26 && x < 0.34 {
            Err(Broken(x))
        } else {
            Ok(shimmy(x).unwrap())
        }
    };
    match Sweep::linspace(0.0, 1.0, 6).run(g) {
        Err(SweepError::Model { value, .. }) => assert!(value > 0.26 && value < 0.34),
        other => panic!("{other:?}"),
    }
    // Numeric trouble names the value too.
    let h = |x: f64| -> Result<DMatrix<f64>, String> {
        if x == 0.5 {
            Ok(DMatrix::from_element(3, 3, f64::NAN))
        } else {
            Ok(shimmy(x).unwrap())
        }
    };
    match Sweep::new(vec![0.0, 0.5, 1.0]).run(h) {
        Err(SweepError::Numeric { value, source, .. }) => {
            assert_eq!(value, 0.5);
            assert!(matches!(source, NumError::NonFinite(_)));
        }
        other => panic!("{other:?}"),
    }
    let size = |x: f64| -> Result<DMatrix<f64>, String> {
        Ok(DMatrix::identity(if x < 0.5 { 2 } else { 3 }, 3))
    };
    assert!(matches!(
        Sweep::new(vec![0.0, 1.0]).run(size),
        Err(SweepError::Numeric { value, .. }) if value == 0.0
    ));
    let grow = |x: f64| -> Result<DMatrix<f64>, String> {
        let n = if x < 0.5 { 2 } else { 3 };
        Ok(DMatrix::identity(n, n))
    };
    assert!(matches!(
        Sweep::new(vec![0.0, 1.0]).run(grow),
        Err(SweepError::Numeric { value, .. }) if value == 1.0
    ));
    // The error displays with the parameter.
    let e = Sweep::new(vec![1.0])
        .with_param_name("u")
        .run(|_| Err::<DMatrix<f64>, _>(std::fmt::Error))
        .unwrap_err();
    assert!(e.to_string().contains("u = 1"), "{e}");
}

#[test]
fn invalid_sweeps_are_rejected() {
    let bad = [
        Sweep::new(vec![]),
        Sweep::new(vec![0.0, 1.0, 0.5]),
        Sweep::new(vec![0.0, f64::NAN]),
        Sweep::new(vec![0.0, 1.0]).with_tolerance(0.0),
        Sweep::new(vec![0.0, 1.0]).with_neutral_rtol(-1.0),
        Sweep::new(vec![0.0, 1.0]).with_max_evaluations(0),
    ];
    for s in bad {
        assert!(
            matches!(
                s.run(shimmy),
                Err(SweepError::Setup(NumError::InvalidOption(_)))
            ),
            "{s:?}"
        );
    }
}

#[test]
fn json_has_the_keys_the_cli_prints() {
    let res = Sweep::linspace(0.0, 1.0, 21)
        .with_param_name("x")
        .run(shimmy)
        .unwrap();
    let v = serde_json::to_value(&res).unwrap();
    assert_eq!(v["param"], "x");
    assert!(v["points"][0]["value"].is_number());
    assert!(v["points"][0]["eigenvalues"][0]["re"].is_number());
    assert!(v["points"][0]["eigenvalues"][0]["im"].is_number());
    let iv = v["stable_intervals"][0].as_array().unwrap();
    assert_eq!(iv.len(), 2);
    assert!((iv[0].as_f64().unwrap() - 0.3).abs() < 1e-9);
    assert!(v["boundaries"][0]["value"].is_number());
    assert!(v["boundaries"][0]["eigenvalue"]["im"].is_number());
}

#[test]
fn linspace_and_single_points() {
    let s = Sweep::linspace(2.0, 3.0, 5);
    assert_eq!(s.values(), &[2.0, 2.25, 2.5, 2.75, 3.0]);
    assert_eq!(Sweep::linspace(2.0, 3.0, 1).values(), &[2.0]);
    let res = Sweep::new(vec![0.5]).run(shimmy).unwrap();
    assert_eq!(res.points.len(), 1);
    assert_eq!(res.stable_intervals.len(), 1);
    assert_eq!(res.stable_intervals[0].lo, 0.5);
    assert!(res.boundaries.is_empty());
}

#[test]
fn grid_only_mode_reports_grid_intervals() {
    let res = Sweep::linspace(0.0, 1.0, 11)
        .with_boundaries(false)
        .run(shimmy)
        .unwrap();
    assert!(res.boundaries.is_empty());
    assert_eq!(res.stable_intervals.len(), 1);
    let iv = res.stable_intervals[0];
    // Stable grid points are 0.4, 0.5, 0.6 (0.3 and 0.7 are on the boundaries).
    assert!(
        (iv.lo - 0.4).abs() < 1e-12 && (iv.hi - 0.6).abs() < 1e-12,
        "{iv:?}"
    );
}

/// The point verdict the rule gives with every eigenvalue's error estimate computed at that
/// point (no neutral branches): unstable when one is, marginal when one is within its
/// estimate, stable otherwise.
fn verdict_with_estimates(a: &DMatrix<f64>) -> PointStability {
    let judged: Vec<Stability> = eigenvalues_with_errors(a)
        .unwrap()
        .iter()
        .map(|(z, tol)| stability_of(z.re, *tol))
        .collect();
    if judged.contains(&Stability::Unstable) {
        PointStability::Unstable
    } else if judged.contains(&Stability::Marginal) {
        PointStability::Marginal
    } else {
        PointStability::Stable
    }
}

/// Non-normal: eigenvalues −x and −2x with condition number ≈ 1e6/x (a triangular matrix
/// turned by a fixed rotation, so that balancing cannot undo it), so that their error
/// estimates exceed |Re λ| for small x: marginal there, though the real parts are negative.
fn non_normal(x: f64) -> Result<DMatrix<f64>, String> {
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let r = mat(&[&[c, -s], &[s, c]]);
    Ok(r.transpose() * mat(&[&[-x, 1e6], &[0.0, -2.0 * x]]) * r)
}

/// A family `A(x)` of a test.
type Family = Box<dyn Fn(f64) -> DMatrix<f64> + Sync>;

/// The estimates are computed only where a verdict could depend on them (some |Re λ| within
/// `screen_bound`); every point's verdict is still the rule's with all estimates, and the
/// points that state no tolerance are those beyond the bound.
#[test]
fn estimates_only_where_a_verdict_could_change_with_the_same_verdicts() {
    let cases: [(&str, Family, f64, f64); 3] = [
        ("shimmy", Box::new(|x| shimmy(x).unwrap()), 0.0, 1.0),
        (
            "crossing pairs",
            Box::new(|x| crossing_pairs(x).unwrap()),
            0.0,
            2.0,
        ),
        (
            "non-normal",
            Box::new(|x| non_normal(x).unwrap()),
            1e-3,
            200.0,
        ),
    ];
    for (name, f, lo, hi) in cases {
        let res = Sweep::linspace(lo, hi, 201)
            .run(|x| Ok::<_, String>(f(x)))
            .unwrap();
        let (mut with, mut without) = (0, 0);
        for p in &res.points {
            let a = f(p.value);
            assert_eq!(
                p.stability,
                verdict_with_estimates(&a),
                "{name} at {}",
                p.value
            );
            let bound = screen_bound(a.nrows(), a.norm());
            let near = p.eigenvalues.iter().any(|z| z.re.abs() <= bound);
            assert_eq!(p.tolerance.is_some(), near, "{name} at {}: {p:?}", p.value);
            if near { with += 1 } else { without += 1 }
        }
        // Each family has points of both kinds.
        assert!(
            with > 0 && without > 0,
            "{name}: {with} with, {without} without"
        );
    }
    // The non-normal family is marginal where its estimates exceed its real parts.
    let res = Sweep::linspace(1e-3, 200.0, 201).run(non_normal).unwrap();
    assert_eq!(res.points[0].stability, PointStability::Marginal);
}

/// A divergence (real root +0.2, whatever x) beside a defective double zero (a heading ψ and
/// a lateral position y with y' = u ψ, as an aircraft pair's free heading): the zero pair's
/// error estimates are large (√ε-sensitive, its eigenvectors nearly parallel), the root's own
/// is tiny. Each point must be unstable with the root's own tolerance, as `eom analyze`
/// judges the eigenvalue, not marginal by the neutral branches' estimates.
#[test]
fn a_divergence_beside_a_defective_zero_is_unstable() {
    let f = |x: f64| -> Result<DMatrix<f64>, String> {
        let a = mat(&[
            &[0.0, 40.0, 1.0, 0.3, 0.0],
            &[0.0, 0.0, 0.5, 1.0, 0.0],
            &[0.0, 0.0, 0.2, 0.0, 0.7],
            &[0.0, 0.0, 0.0, -1.0 - x, 2.0],
            &[0.0, 0.0, 0.0, -2.0, -1.0],
        ]);
        let q = rand_orth(&mut rng(21), 5);
        Ok(q.transpose() * a * q)
    };
    let res = Sweep::linspace(0.0, 1.0, 5).run(f).unwrap();
    assert_eq!(res.branches.iter().filter(|b| b.neutral).count(), 2);
    for p in &res.points {
        let a = f(p.value).unwrap();
        let ve = eigenvalues_with_errors(&a).unwrap();
        let &(root, err) = ve.iter().max_by(|x, y| x.0.re.total_cmp(&y.0.re)).unwrap();
        assert!((root.re - 0.2).abs() < 1e-12, "{ve:?}");
        assert_eq!(stability_of(root.re, err), Stability::Unstable);
        assert_eq!(p.stability, PointStability::Unstable, "{p:?}");
        assert!((p.max_real.unwrap() - 0.2).abs() < 1e-9, "{p:?}");
        assert!(p.tolerance.unwrap_or(0.0) < 1e-6, "{p:?}");
    }
}
