//! The generated stability verdict (`eom codegen --stability`, modules `stab::MODEL`):
//!
//! * its rounding-error bounds hold: every coefficient and Liénard–Chipart condition the
//!   code computes is within its bound of the same formula evaluated in double-double;
//! * where it decides, its verdict is the eigenvalues' (faer's solver on the tape's A, the
//!   structural zeros deflated exactly, a point stable when every other eigenvalue has a
//!   negative real part), and it leaves few points undecided;
//! * the bicycle: the published speeds' stability (Meijaard et al. 2007: weave speed 4.29 m/s,
//!   capsize speed 6.02 m/s), and the spring–mass–damper's polynomial `m s² + c s + k`.

use super::*;
use eom_sym::Dd;
use eom_sym::closed::{ClosedForms, hurwitz_minor};
use eom_sym::tape::eval_generic;
use rand::{Rng, SeedableRng, rngs::StdRng};

/// Values and their rounding-error bounds.
type WithBounds = (Vec<f64>, Vec<f64>);

/// Whether a point's a-priori bounds apply, its values and bounds.
type Quick = (bool, WithBounds);

/// One generated module's stability functions (`f64` in and out).
struct Stab {
    model: &'static str,
    /// The verdict: `-1`, `0`, `1`, or `None` on an error.
    verdict: fn(&[f64]) -> Option<i8>,
    /// `stability_conditions`: whether normalised, values, bounds.
    conditions: fn(&[f64]) -> (bool, WithBounds),
    /// `characteristic_polynomial`: values, bounds.
    polynomial: fn(&[f64]) -> WithBounds,
    /// `stability_conditions_quick`: whether the bounds apply, values, a-priori bounds.
    quick: fn(&[f64]) -> (bool, WithBounds),
    /// `stability_many`: the verdicts of many points (`None` on an error).
    many: fn(&[Vec<f64>]) -> Vec<Option<i8>>,
    /// `stability_conditions_quick_lanes` on consecutive blocks of points (a trailing
    /// partial block left out): per point whether the bounds apply, values, bounds.
    quick_lanes: fn(&[Vec<f64>]) -> Vec<Quick>,
    degrees: &'static [usize],
    zero_roots: usize,
}

macro_rules! stab {
    ($model:expr, $m:path) => {{
        use $m as g;
        fn arr(p: &[f64]) -> [f64; g::N_PARAMS] {
            p.try_into().expect("parameter count")
        }
        fn verdict(p: &[f64]) -> Option<i8> {
            g::stability(&arr(p)).ok().map(|v| v as i8)
        }
        fn conditions(p: &[f64]) -> (bool, WithBounds) {
            let (mut c, mut e) = ([0.0; g::N_CONDITIONS], [0.0; g::N_CONDITIONS]);
            let ok = g::stability_conditions(&arr(p), &mut c, &mut e);
            (ok, (c.to_vec(), e.to_vec()))
        }
        fn polynomial(p: &[f64]) -> WithBounds {
            let (mut c, mut e) = ([0.0; g::POLY_DEGREE + 1], [0.0; g::POLY_DEGREE + 1]);
            g::characteristic_polynomial(&arr(p), &mut c, &mut e);
            (c.to_vec(), e.to_vec())
        }
        fn quick(p: &[f64]) -> (bool, WithBounds) {
            let (mut c, mut e) = ([0.0; g::N_CONDITIONS], [0.0; g::N_CONDITIONS]);
            let ok = g::stability_conditions_quick(&arr(p), &mut c, &mut e);
            (ok, (c.to_vec(), e.to_vec()))
        }
        fn many(points: &[Vec<f64>]) -> Vec<Option<i8>> {
            let points: Vec<[f64; g::N_PARAMS]> = points.iter().map(|p| arr(p)).collect();
            let mut out = vec![Ok(g::Verdict::Undecided); points.len()];
            assert_eq!(g::stability_many(&points, &mut out), points.len());
            out.into_iter().map(|v| v.ok().map(|v| v as i8)).collect()
        }
        fn quick_lanes(points: &[Vec<f64>]) -> Vec<Quick> {
            let mut out = Vec::new();
            for block in points.chunks_exact(g::LANES) {
                let p: [[f64; g::N_PARAMS]; g::LANES] = core::array::from_fn(|l| arr(&block[l]));
                let (mut c, mut e) = (
                    [[0.0; g::LANES]; g::N_CONDITIONS],
                    [[0.0; g::LANES]; g::N_CONDITIONS],
                );
                let ok = g::stability_conditions_quick_lanes(&p, &mut c, &mut e);
                for (l, &applies) in ok.iter().enumerate() {
                    let col =
                        |m: &[[f64; g::LANES]; g::N_CONDITIONS]| m.iter().map(|r| r[l]).collect();
                    out.push((applies, (col(&c), col(&e))));
                }
            }
            out
        }
        Stab {
            model: $model,
            verdict,
            conditions,
            polynomial,
            quick,
            many,
            quick_lanes,
            degrees: &g::CONDITION_DEGREES,
            zero_roots: g::ZERO_ROOTS,
        }
    }};
}

/// Every model that `build.rs` generates with the stability verdict (its `STABILITY`).
fn all() -> Vec<Stab> {
    include!(concat!(env!("OUT_DIR"), "/all_stab.rs"))
}

/// The conditions' formulas as the generator forms them: the pencil's characteristic
/// polynomial, then the Hurwitz determinants `Δ_{d−1}, Δ_{d−3}, …`.
fn condition_exprs(sym: &SymbolicStateSpace) -> (Vec<eom_sym::Expr>, usize) {
    let (e, f) = sym.pencil();
    let p = ClosedForms::default()
        .with_max_states(16)
        .pencil_polynomial(Some(&e), &f)
        .expect("closed form");
    let a = p.polynomial.coefficients.clone();
    let d = a.len() - 1;
    let mut out = a.clone();
    let mut k = d.saturating_sub(1);
    while k >= 2 {
        out.push(hurwitz_minor(&a, k));
        k -= 2;
    }
    (out, p.zero_roots)
}

/// The eigenvalues' verdict: whether every eigenvalue that is not a structural zero (faer,
/// after the exact deflation) has a negative real part; `None` when the largest real part
/// is within rounding (1e-9 of the spectral radius) of zero, where the eigenvalues cannot
/// tell (an undamped model's ±iω).
fn eigen_stable(a: &DMatrix<f64>) -> Option<bool> {
    let n = a.nrows();
    let mut e = vec![Complex64::new(0.0, 0.0); n];
    let mut ws = eom_num::modes::EigenvaluesWorkspace::new(n);
    eom_num::modes::eigenvalues_faer_in(a, &mut ws, &mut e).expect("eigenvalues");
    let nonzero = e.iter().filter(|z| **z != Complex64::new(0.0, 0.0));
    let radius = nonzero.clone().fold(0.0f64, |m, z| m.max(z.norm()));
    let top = nonzero.fold(f64::NEG_INFINITY, |m, z| m.max(z.re));
    if top.abs() <= 1e-9 * radius {
        None
    } else {
        Some(top < 0.0)
    }
}

fn random_point(rng: &mut StdRng, nominal: &[f64], spread: f64) -> Vec<f64> {
    nominal
        .iter()
        .map(|&x| {
            let f = rng.random_range(1.0 - spread..1.0 + spread);
            if x == 0.0 { f - 1.0 } else { x * f }
        })
        .collect()
}

#[test]
fn bounds_hold_against_double_double() {
    for g in all() {
        let r = reference(g.model);
        let (exprs, zero_roots) = condition_exprs(&r.sym);
        assert_eq!(zero_roots, g.zero_roots, "{}", g.model);
        let pos: std::collections::HashMap<u32, usize> = r
            .sym
            .params
            .iter()
            .enumerate()
            .map(|(k, p)| (p.param_index().expect("a parameter"), k))
            .collect();
        let nominal = r.model.scope.nominal_values();
        let mut rng = StdRng::seed_from_u64(31);
        let mut worst = 0.0f64;
        let mut drawn = Vec::new();
        for _ in 0..200 {
            let values = random_point(&mut rng, &nominal, 0.3);
            let exact =
                eval_generic::<Dd>(&exprs, |i| pos.get(&i).map(|&k| Dd::from_f64(values[k])))
                    .expect("double-double");
            drawn.push((values.clone(), exact.clone()));
            let (coef, coef_err) = (g.polynomial)(&values);
            let (ok, (cond, cond_err)) = (g.conditions)(&values);
            // The first stage's a-priori bounds, where they apply.
            let (applies, (quick, quick_err)) = (g.quick)(&values);
            let checked = if applies { exact.len() } else { 0 };
            for k in 0..checked {
                let err = (Dd::from_f64(quick[k]) - exact[k]).to_f64().abs();
                assert!(
                    err <= quick_err[k],
                    "{} condition {k}, first stage: {:e} vs exact {:e}: error {err:e} above its bound {:e}",
                    g.model,
                    quick[k],
                    exact[k].to_f64(),
                    quick_err[k]
                );
                // Never tighter than it can be: at least the rounding of the value itself
                // (a zero bound only for an exact value).
                assert!(
                    quick_err[k] > 0.0 || err == 0.0,
                    "{} condition {k}",
                    g.model
                );
            }
            let d = coef.len() - 1;
            let sign = if exact[d].to_f64() < 0.0 { -1.0 } else { 1.0 };
            for k in 0..exact.len() {
                let want = exact[k].to_f64();
                let (got, bound) = if k <= d {
                    (coef[k], coef_err[k])
                } else {
                    (cond[k], cond_err[k])
                };
                let err = (Dd::from_f64(got) - exact[k]).to_f64().abs();
                assert!(
                    err <= bound,
                    "{} condition {k}: {got:e} vs exact {want:e}: error {err:e} above its bound {bound:e} at {values:?}",
                    g.model
                );
                if bound > 0.0 {
                    worst = worst.max(err / bound);
                }
                // Normalised by the leading coefficient's sign where it is decided.
                if ok {
                    let s = if g.degrees[k] % 2 == 1 { sign } else { 1.0 };
                    let err = (Dd::from_f64(cond[k]) - exact[k] * Dd::from_f64(s))
                        .to_f64()
                        .abs();
                    assert!(err <= cond_err[k], "{} normalised condition {k}", g.model);
                }
            }
        }
        // The batch's first stage (one magnitude per block of points) at the same points.
        let points: Vec<Vec<f64>> = drawn.iter().map(|(v, _)| v.clone()).collect();
        let lanes = (g.quick_lanes)(&points);
        assert!(lanes.len() + 4 > points.len(), "{}: every block", g.model);
        let mut applied = 0;
        for ((applies, (c, e)), (values, exact)) in lanes.iter().zip(&drawn) {
            if !applies {
                continue;
            }
            applied += 1;
            let (_, (_, quick_err)) = (g.quick)(values);
            for k in 0..exact.len() {
                let err = (Dd::from_f64(c[k]) - exact[k]).to_f64().abs();
                assert!(
                    err <= e[k] && e[k] >= quick_err[k],
                    "{} condition {k}, batch first stage: {:e} vs exact {:e}: error {err:e}, bound {:e} (one point alone {:e})",
                    g.model,
                    c[k],
                    exact[k].to_f64(),
                    e[k],
                    quick_err[k]
                );
            }
        }
        assert!(
            applied * 10 >= lanes.len() * 9,
            "{}: the batch bounds apply at {applied} of {} points",
            g.model,
            lanes.len()
        );
        eprintln!(
            "{}: the largest rounding error is {worst:.2} of its bound",
            g.model
        );
    }
}

#[test]
fn verdict_is_the_eigenvalues_where_decided() {
    let mut report = String::new();
    for g in all() {
        let r = reference(g.model);
        let nominal = r.model.scope.nominal_values();
        let mut rng = StdRng::seed_from_u64(20261121);
        let (mut undecided, mut stable, mut marginal, mut points) = (0, 0, 0, 0);
        // Points whose every condition is clear of its first-stage (a-priori) bound.
        let mut clear = 0;
        let mut drawn = Vec::new();
        for _ in 0..2000 {
            let values = random_point(&mut rng, &nominal, 0.3);
            let Ok(ss) = r.sym.evaluate(&values) else {
                continue;
            };
            points += 1;
            let verdict = (g.verdict)(&values).expect("inside the validity region");
            drawn.push((values.clone(), Some(verdict)));
            let (applies, (q, qe)) = (g.quick)(&values);
            clear += usize::from(applies && q.iter().zip(&qe).all(|(x, e)| x.abs() > *e));
            let Some(want) = eigen_stable(&ss.a) else {
                // Marginal: not asymptotically stable, whatever the verdict decides.
                assert_ne!(verdict, 1, "{}: a marginal point called stable", g.model);
                marginal += 1;
                continue;
            };
            match verdict {
                0 => undecided += 1,
                v => {
                    assert_eq!(
                        v == 1,
                        want,
                        "{}: verdict {v}, eigenvalues {} at {values:?}",
                        g.model,
                        if want { "stable" } else { "not stable" }
                    );
                    stable += usize::from(want);
                }
            }
        }
        // The batch verdict (first stage in lanes) is the one-point verdict, point by point
        // (an odd count, so that the remainder after the lanes is used too).
        drawn.truncate(drawn.len() / 2 * 2 - 1);
        let (points_only, want): (Vec<Vec<f64>>, Vec<Option<i8>>) = drawn.into_iter().unzip();
        assert_eq!((g.many)(&points_only), want, "{}: stability_many", g.model);
        report.push_str(&format!(
            "{}: {points} points, {stable} stable, {marginal} marginal, {undecided} undecided, \
             {clear} clear of the first stage's bounds\n",
            g.model
        ));
        assert!(points >= 1000, "{}: {points} points evaluated", g.model);
        assert!(
            undecided * 100 <= points,
            "{}: {undecided} of {points} undecided",
            g.model
        );
    }
    eprint!("{report}");
}

#[test]
fn bicycle_at_the_published_speeds() {
    use stab::bicycle as g;
    let model = models::build("bicycle", &[]).expect("bicycle");
    let names = model.scope.names();
    let at = |v: f64| -> [f64; g::N_PARAMS] {
        let values = model.scope.values_with(&[("v", v)]).expect("values");
        let mut p = g::NOMINAL;
        for (k, name) in g::PARAM_NAMES.iter().enumerate() {
            let i = names.iter().position(|n| n == name).expect("a parameter");
            p[k] = values[i];
        }
        p
    };
    // Meijaard et al. (2007): weave speed 4.292 m/s, capsize speed 6.024 m/s; stable between.
    for (v, stable) in [
        (1.0, false),
        (4.0, false),
        (4.28, false),
        (4.30, true),
        (5.0, true),
        (6.0, true),
        (6.02, true),
        (6.03, false),
        (7.0, false),
        (10.0, false),
    ] {
        let want = if stable {
            g::Verdict::Stable
        } else {
            g::Verdict::Unstable
        };
        assert_eq!(g::stability(&at(v)), Ok(want), "v = {v}");
    }
    // Zero roots: heading and lateral position; the rest a quartic.
    assert_eq!((g::ZERO_ROOTS, g::POLY_DEGREE), (2, 4));
}

/// At the weave speed the bicycle's verdict changes; at the two neighbouring speeds (adjacent
/// doubles) where the computed condition changes sign, the condition is within its rounding
/// bound of zero: the verdict is undecided, in one call and in the batch, and the first
/// stage's bound does not decide it either.
#[test]
fn bicycle_undecided_at_the_weave_speed() {
    use stab::bicycle as g;
    let iv = g::PARAM_NAMES
        .iter()
        .position(|n| *n == "v")
        .expect("speed");
    let at = |v: f64| {
        let mut p = g::NOMINAL;
        p[iv] = v;
        p
    };
    let stable = |v: f64| g::stability(&at(v)) == Ok(g::Verdict::Stable);
    let (mut lo, mut hi) = (4.28, 4.30);
    assert!(!stable(lo) && stable(hi));
    // Bisect on the running-bound conditions: the last condition that fails at `lo`.
    let failing = |v: f64| {
        let (mut c, mut e) = ([0.0; g::N_CONDITIONS], [0.0; g::N_CONDITIONS]);
        assert!(g::stability_conditions(&at(v), &mut c, &mut e));
        c.iter().position(|&x| x <= 0.0)
    };
    let k = failing(lo).expect("a failing condition below the weave speed");
    while hi - lo > 0.0 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if failing(mid) == Some(k) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut undecided = 0;
    for v in [lo, hi] {
        let p = at(v);
        let (mut c, mut e) = ([0.0; g::N_CONDITIONS], [0.0; g::N_CONDITIONS]);
        assert!(g::stability_conditions(&p, &mut c, &mut e));
        if c[k].abs() <= e[k] {
            undecided += 1;
            assert_eq!(g::stability(&p), Ok(g::Verdict::Undecided), "v = {v}");
            let mut out = [Ok(g::Verdict::Stable); 5];
            g::stability_many(&[p; 5], &mut out);
            assert!(out.iter().all(|v| *v == Ok(g::Verdict::Undecided)));
            let (mut q, mut qe) = ([0.0; g::N_CONDITIONS], [0.0; g::N_CONDITIONS]);
            if g::stability_conditions_quick(&p, &mut q, &mut qe) {
                assert!(q[k].abs() <= qe[k], "the first stage decides v = {v}");
            }
        }
    }
    assert!(undecided >= 1, "condition {k} at {lo}, {hi}: both decided");
}

#[test]
fn spring_mass_damper_polynomial() {
    use stab::smd as g;
    let (m, c, k) = (2.0, 0.3, 50.0);
    let mut p = g::NOMINAL;
    for (i, name) in g::PARAM_NAMES.iter().enumerate() {
        p[i] = match *name {
            "m" => m,
            "c" => c,
            "k" => k,
            _ => p[i],
        };
    }
    let (mut a, mut e) = ([0.0; g::POLY_DEGREE + 1], [0.0; g::POLY_DEGREE + 1]);
    g::characteristic_polynomial(&p, &mut a, &mut e);
    // p(s) ∝ m s² + c s + k.
    assert_eq!(g::POLY_DEGREE, 2);
    let scale = a[2] / m;
    assert!((a[1] / scale - c).abs() <= 1e-15 * c && (a[0] / scale - k).abs() <= 1e-15 * k);
    assert_eq!(g::stability(&p), Ok(g::Verdict::Stable));
    let mut undamped = p;
    for (i, name) in g::PARAM_NAMES.iter().enumerate() {
        if *name == "c" {
            undamped[i] = 0.0;
        }
    }
    // No damping: marginal, which is not asymptotically stable: the condition `c > 0` is
    // exactly 0 here (computed without rounding, bound 0).
    assert_eq!(g::stability(&undamped), Ok(g::Verdict::Unstable));
    for (i, name) in g::PARAM_NAMES.iter().enumerate() {
        if *name == "c" {
            undamped[i] = -0.1;
        }
    }
    assert_eq!(g::stability(&undamped), Ok(g::Verdict::Unstable));
}

/// The batch verdict decides each point as the one-point verdict does, also at points that
/// take the first stage's other ways out: a parameter NaN, infinite, zero, huge or tiny, or
/// negated (which can flip the sign of the leading coefficient, so that the lanes'
/// normalisation is used), mixed in blocks with ordinary points.
#[test]
fn batch_verdict_is_the_one_point_verdict_at_hostile_points() {
    let mut report = String::new();
    let (mut flipped, mut not_finite) = (0, 0);
    for g in all() {
        let r = reference(g.model);
        let nominal = r.model.scope.nominal_values();
        let lead = g.degrees.iter().take_while(|&&d| d == 1).count() - 1;
        let mut points = vec![nominal.clone()];
        for k in 0..nominal.len() {
            for x in [f64::NAN, f64::INFINITY, 0.0, 1e300, 1e-300, -nominal[k]] {
                let mut p = nominal.clone();
                p[k] = x;
                points.push(p);
            }
        }
        points.push(nominal.iter().map(|x| -x).collect());
        let mut rng = StdRng::seed_from_u64(20261129);
        for _ in 0..points.len() {
            points.push(random_point(&mut rng, &nominal, 0.3));
        }
        // Hostile and ordinary points interleaved, so that every block mixes them.
        let half = points.len() / 2;
        let mixed: Vec<Vec<f64>> = (0..half)
            .flat_map(|i| [points[i].clone(), points[half + i].clone()])
            .collect();
        let want: Vec<Option<i8>> = mixed.iter().map(|p| (g.verdict)(p)).collect();
        assert_eq!((g.many)(&mixed), want, "{}: stability_many", g.model);
        for p in &mixed {
            let (applies, (c, e)) = (g.quick)(p);
            flipped += usize::from(applies && c[lead] < -e[lead]);
            not_finite += usize::from(c.iter().chain(&e).any(|x| !x.is_finite()));
        }
        report.push_str(&format!("{}: {} points\n", g.model, mixed.len()));
    }
    eprintln!("{report}{flipped} with a negative leading coefficient, {not_finite} not finite");
    assert!(
        flipped > 0,
        "no point used the normalisation by the leading coefficient's sign"
    );
    assert!(not_finite > 0, "no point with a value or bound not finite");
}
