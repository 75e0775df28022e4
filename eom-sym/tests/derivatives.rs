//! Property tests of derivatives and substitution on random expressions (`common::recipe`),
//! against finite differences and evaluation in double-double. Tolerances: see
//! `common/bound.rs`.

mod common;

use common::bound::*;
use common::{N_PARAMS, build, has_float, params, recipe};
use eom_sym::{Dd, SymError};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// `diff` evaluated in double-double agrees with a fourth-order central difference
/// `D(h) = [f(x−2h) − 8f(x−h) + 8f(x+h) − f(x+2h)]/(12h)` of the double-double evaluation.
///
/// * `h = 10⁻⁴·max(|x|, 1/4)`; the shifted points `x ± kh` are exact in double-double, so only
///   the truncation error (`O(h⁴)`) and the evaluation noise (`≈ 3·DD_RATIO·E_f/h`, with `E_f`
///   the running bound of `f`) matter.
/// * Richardson check: if `|D(h) − D(h/2)| > 10⁻⁹·max|D(·)|` (plus noise) the difference is not
///   resolved at this step (a pole or a kink nearby): skipped. Otherwise the error of `D(h/2)`
///   is about `|D(h) − D(h/2)|/15 ≤ 10⁻¹⁰·|D|`.
/// * Non-smooth spots: the signs of every `abs`/`ln` argument, every base with a negative or
///   fractional exponent and the `atan2` cut must be the same (and nonzero) at all stencil
///   points, else skipped.
/// * Then `|diff − D(h/2)| ≤ 10⁻⁸·max(|diff|, |D|) + 4·noise + DD_RATIO·E_diff`, where
///   `E_diff` is the running bound of the derivative. When the recipe has float constants,
///   `diff` folds new float coefficients in `f64` (`c·c/2` in `d√|c·x|/dx`), so `2·E_diff`
///   replaces `DD_RATIO·E_diff` (as for substitution).
/// * A parameter the expression does not depend on must give a structural zero.
#[test]
fn derivative_matches_finite_differences() {
    let p = params();
    let st = Stats::default();
    run((recipe(), point(), 0..N_PARAMS), |(r, x, j)| {
        Stats::bump(&st.cases);
        let e = build(&r, &p);
        if e.check().is_err() {
            Stats::bump(&st.invalid);
            return Ok(());
        }
        // Differentiate with respect to a parameter the expression depends on (the others give
        // a structural zero).
        let deps = e.params();
        for q in &p {
            if !deps.contains(&q.param_index().unwrap()) {
                prop_assert!(e.diff(*q).unwrap().is_zero(), "d/d{q} of {e} is not 0");
            }
        }
        let on: Vec<usize> = (0..N_PARAMS)
            .filter(|&k| deps.contains(&p[k].param_index().unwrap()))
            .collect();
        if on.is_empty() {
            Stats::bump(&st.constant);
            return Ok(());
        }
        let j = on[j % on.len()];
        let d = e.diff(p[j]).expect("derivative of a valid expression");
        prop_assert!(
            d.check().is_ok(),
            "the derivative of {e} is invalid: {:?}",
            d.check()
        );
        let pj = p[j].param_index().unwrap();
        let x0 = x[j];
        let h = 1e-4 * x0.abs().max(0.25);
        let pt = Point { p: &p, x };
        let pt = &pt;
        let at = |k: f64| {
            let shifted = Dd::from_f64(x0) + Dd::from_f64(k * h);
            move |i: u32| if i == pj { Some(shifted) } else { pt.dd_of(i) }
        };
        let offsets = [-2.0, -1.0, -0.5, 0.5, 1.0, 2.0];
        let f: Vec<Dd> = offsets.iter().map(|&k| dd_eval(e, at(k))).collect();
        let w0 = walk(&[e, d], &|i| pt.val_of(i));
        let (ef, ed) = (w0.at(e).err, w0.at(d).err);
        let ds = dd_eval(d, |i| pt.dd_of(i));
        if !f.iter().all(|v| finite(*v)) || !finite(ds) || !ef.is_finite() || !ed.is_finite() {
            Stats::bump(&st.undefined);
            return Ok(());
        }
        // Same smooth piece at every stencil point.
        let sig0 = walk(&[e], &|i| pt.val_of(i)).signature;
        let smooth = !sig0.contains(&0)
            && offsets.iter().all(|&k| {
                let shifted = Dd::from_f64(x0) + Dd::from_f64(k * h);
                let shifted = Val {
                    v: shifted,
                    err: 0.0,
                };
                let wk = walk(&[e], &|i| if i == pj { shifted } else { pt.val_of(i) });
                wk.signature == sig0
            });
        if !smooth {
            Stats::bump(&st.skipped);
            return Ok(());
        }
        let d_h = (f[0] - Dd::from_f64(8.0) * f[1] + Dd::from_f64(8.0) * f[4] - f[5])
            / Dd::from_f64(12.0 * h);
        let d_h2 = (f[1] - Dd::from_f64(8.0) * f[2] + Dd::from_f64(8.0) * f[3] - f[4])
            / Dd::from_f64(6.0 * h);
        let noise = 3.0 * DD_RATIO * ef / h;
        let scale = ds.to_f64().abs().max(d_h2.to_f64().abs());
        // Resolution is judged on the differences alone, never on the value under test: with
        // `scale` here, a huge symbolic derivative made two random difference quotients of a
        // wildly oscillating function look converged (cos(27/p³) near p = −3·10⁻⁴).
        // Written so that NaN (a difference quotient that overflowed: `inf − x` is NaN in
        // double-double) counts as unresolved.
        let fd_scale = d_h.to_f64().abs().max(d_h2.to_f64().abs());
        let resolved = (d_h - d_h2).to_f64().abs() <= 1e-9 * fd_scale + 2.0 * noise;
        if !(finite(d_h) && finite(d_h2) && resolved) {
            Stats::bump(&st.skipped);
            return Ok(());
        }
        // A derivative of an expression with float constants has float coefficients folded in
        // f64 at construction (c·c/2 for d√|c·x|): allow its own f64 running bound then.
        let folded = if has_float(&r) {
            2.0 * ed
        } else {
            DD_RATIO * ed
        };
        let tol = 1e-8 * scale + 4.0 * noise + folded + TINY;
        let miss = (ds - d_h2).to_f64().abs();
        prop_assert!(
            miss <= tol,
            "d/d{} of {e} = {d}: symbolic {ds} vs finite difference {d_h2}, miss {miss:e} > {tol:e}",
            p[j]
        );
        Stats::bump(&st.compared);
        // Sharp: the tolerance is the 1e-8 relative term, not the noise allowance.
        if 4.0 * noise + folded <= 1e-10 * scale {
            Stats::bump(&st.sharp);
        }
        Ok(())
    });
    st.assert_coverage("derivative", 0.6, 0.5);
}

// ================================================================== (c) substitution

/// A substituted value: an exact dyadic (folds as rationals) or a general float (folds in
/// `f64`).
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![(-24i32..25).prop_map(|k| k as f64 / 8.0), -3.0f64..3.0]
}

/// `subs_values(p_j → v)` evaluated = the original evaluated with `p_j = v`.
///
/// `subs` rebuilds through the smart constructors, so float constants fold in `f64` at
/// construction: the two sides legitimately differ by `f64` rounding errors of the
/// original's operations, bounded by the original's running bound `E` (every folded constant
/// is computed by the same operations the bound charges, in some order — the sum and product
/// bounds hold for any order). Tolerance `2·E + DD_RATIO·E_subs`. Where the original is
/// finite (and `E` finite) the substituted expression must be valid.
#[test]
fn substituting_a_value_equals_evaluating_with_it() {
    let p = params();
    let st = Stats::default();
    run(
        (recipe(), point(), 0..N_PARAMS, value()),
        |(r, mut x, j, v)| {
            Stats::bump(&st.cases);
            let e = build(&r, &p);
            if e.check().is_err() {
                Stats::bump(&st.invalid);
                return Ok(());
            }
            x[j] = v;
            let pt = Point { p: &p, x };
            let s = e
                .subs_values(&[(p[j], v)])
                .expect("subs of a valid expression");
            let orig = dd_eval(e, |i| pt.dd_of(i));
            let bound = walk(&[e], &|i| pt.val_of(i)).at(e).err;
            if !finite(orig) || !bound.is_finite() {
                Stats::bump(&st.undefined);
                return Ok(());
            }
            match s.check() {
                Ok(_) => {}
                Err(SymError::RationalOverflow) => {
                    Stats::bump(&st.skipped);
                    return Ok(());
                }
                Err(err) => {
                    return Err(TestCaseError::fail(format!(
                        "{e} with {} = {v}: subs gave an error ({err}) where the value is {orig}",
                        p[j]
                    )));
                }
            }
            let pj = p[j].param_index().unwrap();
            prop_assert!(!s.params().contains(&pj), "{s} still depends on {}", p[j]);
            let subst = dd_eval(s, |i| pt.dd_of(i));
            let sb = walk(&[s], &|i| pt.val_of(i)).at(s).err;
            let tol = 2.0 * bound + DD_RATIO * sb + TINY;
            let miss = (subst - orig).to_f64().abs();
            prop_assert!(
                miss <= tol,
                "{e} with {} = {v} is {s} = {subst}, evaluation gives {orig}: miss {miss:e} > {tol:e}",
                p[j]
            );
            Stats::bump(&st.compared);
            if bound <= 1e-12 * orig.to_f64().abs() {
                Stats::bump(&st.sharp);
            }
            Ok(())
        },
    );
    st.assert_coverage("subs value", 0.7, 0.5);
}

/// `subs(p_j → r)` with an expression `r` (another recipe, which may itself contain `p_j`:
/// substitution is simultaneous) evaluated = the original evaluated with `p_j = r(x)`.
///
/// Without float constants everything stays symbolic except exact rational folding, so both
/// sides are double-double evaluations of the same function: tolerance `DD_RATIO·(E +
/// E_subs)`, where `E` includes the propagation of `r`'s own error. With float constants,
/// new float coefficients fold in `f64` (`3·(0.61/p0) → 1.84/p0`), so the tolerance is
/// `2·E + DD_RATIO·E_subs` as for values.
#[test]
fn substituting_an_expression_equals_evaluating_with_its_value() {
    let p = params();
    let st = Stats::default();
    run(
        (recipe(), recipe(), point(), 0..N_PARAMS),
        |(r1, r2, x, j)| {
            Stats::bump(&st.cases);
            let (e, rep) = (build(&r1, &p), build(&r2, &p));
            if e.check().is_err() || rep.check().is_err() {
                Stats::bump(&st.invalid);
                return Ok(());
            }
            let pt = Point { p: &p, x };
            let pj = p[j].param_index().unwrap();
            let rv = walk(&[rep], &|i| pt.val_of(i)).at(rep);
            let rdd = dd_eval(rep, |i| pt.dd_of(i));
            if !finite(rdd) || !rv.err.is_finite() {
                Stats::bump(&st.undefined);
                return Ok(());
            }
            let with_r = |i: u32| if i == pj { Some(rdd) } else { pt.dd_of(i) };
            let orig = dd_eval(e, with_r);
            let bound = walk(&[e], &|i| {
                if i == pj {
                    Val {
                        v: rdd,
                        err: rv.err,
                    }
                } else {
                    pt.val_of(i)
                }
            })
            .at(e)
            .err;
            if !finite(orig) || !bound.is_finite() {
                Stats::bump(&st.undefined);
                return Ok(());
            }
            let s = e.subs(&[(p[j], rep)]).expect("subs of valid expressions");
            match s.check() {
                Ok(_) => {}
                Err(SymError::RationalOverflow) => {
                    Stats::bump(&st.skipped);
                    return Ok(());
                }
                Err(err) => {
                    return Err(TestCaseError::fail(format!(
                        "{e} with {} → {rep}: subs gave an error ({err}) where the value is {orig}",
                        p[j]
                    )));
                }
            }
            let subst = dd_eval(s, |i| pt.dd_of(i));
            let sb = walk(&[s], &|i| pt.val_of(i)).at(s).err;
            let exact = !has_float(&r1) && !has_float(&r2);
            let tol = if exact { DD_RATIO * bound } else { 2.0 * bound } + DD_RATIO * sb + TINY;
            let miss = (subst - orig).to_f64().abs();
            prop_assert!(
                miss <= tol,
                "{e} with {} → {rep} is {s} = {subst}, evaluation gives {orig}: miss {miss:e} > {tol:e}",
                p[j]
            );
            Stats::bump(&st.compared);
            if exact && DD_RATIO * (bound + sb) <= 1e-20 * orig.to_f64().abs() {
                Stats::bump(&st.sharp);
            }
            Ok(())
        },
    );
    st.assert_coverage("subs expression", 0.6, 0.2);
}
