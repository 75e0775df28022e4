//! The tape (`Tape::new`, exact rounding) against the recursive evaluator
//! (`eval_generic::<f64>`) bit for bit, sign of zero included, on random expressions at
//! points made of signed zeros and small integers, where `x·0`, `0 − x`, `x − x`, `−(x − y)`
//! and negated zeros show which sign each evaluation gives a zero.

mod common;

use common::{build, params, recipe};
use eom_sym::{Expr, Tape, eval_generic};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// Inputs where a sign of zero is decided: ±0 and values whose sums and products give zeros.
fn zeroish() -> impl Strategy<Value = [f64; 4]> {
    let v = prop::sample::select(vec![0.0, -0.0, 1.0, -1.0, 2.0, -2.0, 0.5]);
    [v.clone(), v.clone(), v.clone(), v]
}

/// The first output whose bits differ (NaNs of any payload count as equal).
fn first_difference(roots: &[Expr], p: &[Expr], x: &[f64]) -> Option<(usize, f64, f64)> {
    let tape = Tape::new(roots, p).expect("tape of a valid expression");
    let mut out = vec![0.0; tape.n_outputs()];
    let mut work = vec![0.0; tape.work_len()];
    // Non-finite outputs are reported as errors after the values are written.
    let _ = tape.eval_into(x, &mut out, &mut work);
    let value = |i: u32| {
        p.iter()
            .position(|q| q.param_index() == Some(i))
            .map(|k| x[k])
    };
    let want = eval_generic::<f64>(roots, value).expect("every parameter has a value");
    out.iter()
        .zip(&want)
        .enumerate()
        .find(|(_, (t, w))| t.to_bits() != w.to_bits() && !(t.is_nan() && w.is_nan()))
        .map(|(k, (t, w))| (k, *t, *w))
}

#[test]
fn tape_and_recursive_evaluator_agree_on_signed_zeros() {
    let p = params();
    let mut runner = TestRunner::new(Config {
        cases: 4096,
        failure_persistence: None,
        ..Config::default()
    });
    let res = runner.run(&(recipe(), zeroish()), |(r, x)| {
        let e = build(&r, &p);
        if e.check().is_err() {
            return Ok(());
        }
        if let Some((k, t, w)) = first_difference(&[e, -e], &p, &x) {
            prop_assert!(
                false,
                "output {k}: tape {t:?}, eval_generic {w:?} for {e} at {x:?}"
            );
        }
        Ok(())
    });
    if let Err(e) = res {
        panic!("{e}");
    }
}

/// Random DAGs with heavy sharing (every node a root), at points of signed zeros and small
/// integers.
#[test]
fn tape_and_recursive_evaluator_agree_on_signed_zeros_in_shared_dags() {
    let p = params();
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    };
    let values = [0.0, -0.0, 1.0, -1.0, 2.0, -2.0, 0.5];
    for _ in 0..200 {
        let mut pool: Vec<Expr> = p.clone();
        pool.extend([Expr::int(1), Expr::int(-1), Expr::int(2)]);
        for _ in 0..60 {
            let n = pool.len();
            let a = pool[next(n)];
            let b = pool[n - 1 - next(n.min(8))];
            let e = match next(11) {
                0 | 1 => a + b,
                2 | 3 => a - b,
                4 | 5 => a * b,
                6 => -a,
                7 => a.sin(),
                8 => a.powi(2 + next(2) as i64),
                9 => -(a - b),
                _ => a * b - b * a + a,
            };
            if e.check().is_ok() && !e.is_number() {
                pool.push(e);
            }
        }
        let roots: Vec<Expr> = pool[p.len()..].to_vec();
        for _ in 0..20 {
            let x: Vec<f64> = (0..p.len()).map(|_| values[next(values.len())]).collect();
            if let Some((k, t, w)) = first_difference(&roots, &p, &x) {
                panic!(
                    "output {k}: tape {t:?}, eval_generic {w:?} for {} at {x:?}",
                    roots[k]
                );
            }
        }
    }
}
