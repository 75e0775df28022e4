//! Property tests of evaluation on random expressions (`common::recipe`): the tape, the
//! recursive evaluator in `f64` and in double-double, batches, and the double-double
//! reference itself; and of the canonical forms. Tolerances: see `common/bound.rs`.

mod common;

use common::bound::*;
use common::{Recipe, build, params, recipe};
use eom_sym::{Dd, Expr, SymError, Tape, eval_generic};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// Tape = `eval_generic::<f64>` = `eval_generic::<Dd>` (rounded), within the running bound.
#[test]
fn tape_recursive_and_double_double_evaluation_agree() {
    let p = params();
    let st = Stats::default();
    run((recipe(), point()), |(r, x)| {
        Stats::bump(&st.cases);
        let e = build(&r, &p);
        if e.check().is_err() {
            Stats::bump(&st.invalid);
            return Ok(());
        }
        let pt = Point { p: &p, x };
        let reference = dd_eval(e, |i| pt.dd_of(i));
        let w = walk(&[e], &|i| pt.val_of(i));
        let bound = w.at(e).err;
        if !finite(reference) || !bound.is_finite() {
            Stats::bump(&st.undefined);
            return Ok(());
        }
        // The independent walker and eval_generic::<Dd> agree at double-double level.
        let walked = w.at(e).v;
        let dd_tol = DD_RATIO * bound + TINY;
        prop_assert!(
            (walked - reference).to_f64().abs() <= dd_tol,
            "walker {walked} vs eval_generic::<Dd> {reference} (tol {dd_tol:e}) for {e}"
        );
        let g = eval_generic::<f64>(&[e], |i| pt.f64_of(i)).unwrap()[0];
        let tol = 2.0 * bound + TINY;
        let rf = reference.to_f64();
        // The exact tape and the reassociating one (other rounding, same bound).
        for tape in [Tape::new(&[e], &p), Tape::new_reassociating(&[e], &p)] {
            let tape = tape.expect("tape of a valid expression");
            match tape.eval_vec(&x) {
                Ok(t) => prop_assert!(
                    (Dd::from_f64(t[0]) - reference).to_f64().abs() <= tol,
                    "tape {} vs reference {reference}: error {:e} > tol {tol:e} for {e}",
                    t[0],
                    (t[0] - rf).abs()
                ),
                Err(err) => prop_assert!(
                    false,
                    "tape failed ({err}) where the reference is {reference}"
                ),
            }
        }
        prop_assert!(
            g.is_finite() && (Dd::from_f64(g) - reference).to_f64().abs() <= tol,
            "eval_generic::<f64> {g} vs reference {reference}: tol {tol:e} for {e}"
        );
        Stats::bump(&st.compared);
        if bound <= 1e-12 * rf.abs() {
            Stats::bump(&st.sharp);
        }
        Ok(())
    });
    st.assert_coverage("evaluation", 0.7, 0.5);
}

/// `eval_batch` (chunks of points in structure-of-arrays form) gives exactly the results of
/// `eval_into` point by point (the same operations per lane), and on a non-finite output
/// names the same first (point, output) pair. Batch sizes 0–39 cover full and partial chunks
/// and the point-by-point remainder.
#[test]
fn batch_evaluation_equals_pointwise_evaluation() {
    let p = params();
    run(
        (recipe(), prop::collection::vec(point(), 0..40)),
        |(r, pts)| {
            let e = build(&r, &p);
            if e.check().is_err() {
                return Ok(());
            }
            let roots = [e, e + p[0]];
            let tape = Tape::new(&roots, &p).expect("tape of a valid expression");
            let mut want = Vec::new();
            let mut first_bad = None;
            let mut work = vec![0.0; tape.work_len()];
            for (k, x) in pts.iter().enumerate() {
                let mut o = [0.0; 2];
                tape.eval_into(x, &mut o, &mut work).unwrap();
                if let (None, Some(j)) = (&first_bad, o.iter().position(|v| !v.is_finite())) {
                    first_bad = Some(format!("output {j} at point {k}"));
                }
                want.extend_from_slice(&o);
            }
            let flat: Vec<f64> = pts.iter().flatten().copied().collect();
            let mut got = vec![0.0; 2 * pts.len()];
            let res = tape.eval_batch(&flat, &mut got, &mut eom_sym::TapeWorkspace::default());
            match (res, first_bad) {
                (Ok(()), None) => {
                    for (g, w) in got.iter().zip(&want) {
                        prop_assert_eq!(
                            g.to_bits(),
                            w.to_bits(),
                            "batch {} vs pointwise {} for {}",
                            g,
                            w,
                            e
                        );
                    }
                }
                (Err(SymError::EvalNonFinite { what, .. }), Some(bad)) => {
                    prop_assert_eq!(what, bad)
                }
                (res, bad) => {
                    prop_assert!(false, "batch {res:?}, pointwise first non-finite {bad:?}")
                }
            }
            Ok(())
        },
    );
}

/// The double-double reference itself (every tolerance above relies on it): exact identities
/// hold to ~10⁻³⁰ — `exp(x)·exp(−x) = 1`, `ln(exp x) = x`, `sin²x + cos²x = 1`,
/// `atan2(sin x, cos x) = x − 2πk`, `(√y)² = y`, `(1/y)·y = 1` — for |x| < 30.
#[test]
fn double_double_functions_satisfy_identities() {
    run(-30.0f64..30.0, |x| {
        let d = Dd::from_f64(x);
        let tol = 1e-30;
        let check = |what: &str, err: Dd, scale: f64| -> Result<(), TestCaseError> {
            let e = err.to_f64().abs();
            prop_assert!(e <= tol * scale, "{what} at x = {x}: error {e:e}");
            Ok(())
        };
        check("exp(x)·exp(−x) − 1", d.exp() * (-d).exp() - Dd::ONE, 1.0)?;
        check("ln(exp x) − x", d.exp().ln() - d, x.abs().max(1.0))?;
        let (sn, cs) = (d.sin(), d.cos());
        check("sin² + cos² − 1", sn * sn + cs * cs - Dd::ONE, 1.0)?;
        let k = (x / (2.0 * std::f64::consts::PI)).round();
        let reduced = d - Dd::PI * Dd::from_f64(2.0 * k);
        check(
            "atan2(sin x, cos x) − (x − 2πk)",
            sn.atan2(cs) - reduced,
            x.abs().max(1.0),
        )?;
        let y = d.abs() + Dd::from_f64(0.5);
        check("(√y)² − y", y.sqrt() * y.sqrt() - y, y.to_f64())?;
        check("(1/y)·y − 1", Dd::ONE / y * y - Dd::ONE, 1.0)?;
        Ok(())
    });
}

// ================================================================== (b) derivatives

// ================================================================== (d) hash-consing

/// Unique non-numeric nodes the smart constructors may add for one recipe step (see the
/// derivation in [`dag_size_is_bounded_by_the_recipe`]).
fn new_nodes(r: &Recipe) -> usize {
    use Recipe::*;
    let own = match r {
        Param(_) => 1,
        Int(_) | Rat(..) | Float(_) => 0,
        Add(..) | Sub(..) => 3,
        Mul(..) | Div(..) | Neg(_) | Powi(..) | Atan2(..) => 1,
        Sqrt(_) | Ln(_) => 4,
        Sin(_) => 3,
        Cos(_) | Exp(_) | Abs(_) => 2,
    };
    let kids: usize = match r {
        Param(_) | Int(_) | Rat(..) | Float(_) => 0,
        Add(a, b) | Sub(a, b) | Mul(a, b) | Div(a, b) | Atan2(a, b) => new_nodes(a) + new_nodes(b),
        Neg(a) | Powi(a, _) | Sqrt(a) | Sin(a) | Cos(a) | Exp(a) | Ln(a) | Abs(a) => new_nodes(a),
    };
    own + kids
}

/// Unique reachable nodes that are not numbers.
fn non_numeric(e: Expr) -> usize {
    reachable(&[e]).iter().filter(|n| !n.is_number()).count()
}

/// The recipe with every float constant replaced by a nearby exact rational (k/8).
fn exact(r: &Recipe) -> Recipe {
    use Recipe::*;
    let b = |x: &Recipe| Box::new(exact(x));
    match r {
        Float(x) => Rat((x * 8.0).round() as i64, 8),
        Param(_) | Int(_) | Rat(..) => r.clone(),
        Add(x, y) => Add(b(x), b(y)),
        Sub(x, y) => Sub(b(x), b(y)),
        Mul(x, y) => Mul(b(x), b(y)),
        Div(x, y) => Div(b(x), b(y)),
        Atan2(x, y) => Atan2(b(x), b(y)),
        Neg(x) => Neg(b(x)),
        Powi(x, n) => Powi(b(x), *n),
        Sqrt(x) => Sqrt(b(x)),
        Sin(x) => Sin(b(x)),
        Cos(x) => Cos(b(x)),
        Exp(x) => Exp(b(x)),
        Ln(x) => Ln(b(x)),
        Abs(x) => Abs(b(x)),
    }
}

/// `x` and `y` are the same node, or both invalid with the same error (invalid nodes carry
/// their own error and are not hash-consed).
fn same(x: Expr, y: Expr) -> Result<(), TestCaseError> {
    match (x.check(), y.check()) {
        (Ok(_), Ok(_)) => prop_assert_eq!(x, y),
        (Err(ex), Err(ey)) => prop_assert_eq!(ex, ey),
        (ex, ey) => prop_assert!(false, "one side invalid: {:?} vs {:?}", ex, ey),
    }
    Ok(())
}

/// Building a recipe twice gives the same node, and shared structure is stored once.
#[test]
fn building_twice_gives_the_same_node() {
    let p = params();
    run(recipe(), |r| {
        let a = build(&r, &p);
        let b = build(&r, &p);
        if a.check().is_err() {
            // Invalid nodes each carry their own error: not hash-consed, but both invalid.
            prop_assert!(b.is_invalid());
            return Ok(());
        }
        prop_assert_eq!(a, b);
        // Twice the same subexpression is stored once: a + a and a·a add at most one
        // non-numeric node (and new coefficients or exponents).
        // (A large float constant may overflow: then both sides are the same error.)
        let n = non_numeric(a);
        let twice = a + a;
        same(twice, Expr::int(2) * a)?;
        if twice.check().is_ok() {
            prop_assert!(non_numeric(twice) <= n + 1, "{a} + {a}");
        }
        let sq = a * a;
        same(sq, a.powi(2))?;
        if sq.check().is_ok() {
            prop_assert!(non_numeric(sq) <= n + 1, "{a}·{a}");
        }
        prop_assert_eq!(a - a, Expr::zero());
        prop_assert_eq!(a + Expr::zero(), a);
        prop_assert_eq!(a * Expr::one(), a);
        Ok(())
    });
}

/// `dag_size` counts unique reachable nodes (checked against a DFS here), and the non-numeric
/// ones are bounded by the recipe: each recipe step adds its result node plus at most a fixed
/// number of auxiliary nodes — a unit product for each operand of a sum that carries a
/// coefficient (≤ 2, so `+`/`−` ≤ 3); the positive form of a negated argument and the negated
/// result of an odd function (`sin` ≤ 3); `abs` of a negated argument (≤ 2), then for `sqrt` the
/// `abs` of a base with an even power (`sqrt` ≤ 4); `ln(|a| + 1/2)` ≤ 4 (abs ≤ 2, a unit
/// product, the sum, the ln). Everything else that is built along the way (intermediate
/// powers, `−b` inside `a − b`) is flattened into the result and no longer reachable. Numbers
/// (coefficients, exponents, constants) are counted separately.
#[test]
fn dag_size_is_bounded_by_the_recipe() {
    let p = params();
    run(recipe(), |r| {
        let e = build(&r, &p);
        if e.check().is_err() {
            return Ok(());
        }
        let nodes = reachable(&[e]);
        prop_assert_eq!(Expr::dag_size(&[e]), nodes.len());
        let count = non_numeric(e);
        let bound = new_nodes(&r);
        prop_assert!(count <= bound, "{e}: {count} non-numeric nodes > {bound}");
        Ok(())
    });
}

/// Canonical forms do not depend on the order of operations: `a + b = b + a`, `a·b = b·a`,
/// and, with the float constants replaced by exact ones (float arithmetic is not associative:
/// a folded coefficient depends on the order), `(a + b) + c = a + (b + c)` and
/// `(a·b)·c = a·(b·c)`; the latter only
/// when no operand or partial product is a number (a number times a sum is distributed, a
/// number times a product is not: `(2·s)·x ≠ 2·(s·x)` for a sum `s`, a known limitation).
#[test]
fn canonical_forms_are_order_independent() {
    let p = params();
    let st = Stats::default();
    run((recipe(), recipe(), recipe()), |(ra, rb, rc)| {
        Stats::bump(&st.cases);
        let (a, b, c) = (build(&ra, &p), build(&rb, &p), build(&rc, &p));
        if a.check().is_err() || b.check().is_err() || c.check().is_err() {
            Stats::bump(&st.invalid);
            return Ok(());
        }
        same(a + b, b + a)?;
        same(a * b, b * a)?;
        // Associativity on the exact versions of the recipes.
        let (a, b, c) = (
            build(&exact(&ra), &p),
            build(&exact(&rb), &p),
            build(&exact(&rc), &p),
        );
        if a.check().is_err() || b.check().is_err() || c.check().is_err() {
            Stats::bump(&st.skipped);
            return Ok(());
        }
        same((a + b) + c, a + (b + c))?;
        same(Expr::sum([a, b, c]), (c + a) + b)?;
        let numeric = [a, b, c, a * b, b * c].iter().any(|x| x.is_number());
        if !numeric {
            same((a * b) * c, a * (b * c))?;
            Stats::bump(&st.compared);
        }
        Ok(())
    });
    st.report("canonical");
}
