//! Generated code of reduced and discretised models (`tests/build.rs` generates chain50
//! reduced to 10 states and the bicycle to 5, both with `eval_discrete`, and the full quarter
//! car with `eval_discrete`):
//!
//! * `eval_discrete` against the exponential of the same augmented matrix in double-double
//!   (Taylor series with scaling and squaring in `eom_sym::Dd`), across sample times and
//!   random parameter points;
//! * the reduced chain50's frequency response against the full model's (linearized anew at
//!   each point) within the bound of the nominal point, at random points near it;
//! * the reduced bicycle keeps its exact zeros at every speed, and reports a point outside the
//!   validity region as the full code does.

use eom_model::Linearizer;
use eom_num::StateSpace;
use eom_num::freq::{HessenbergForm, SolveStatus};
use eom_sym::Dd;
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::{Rng, SeedableRng};

include!(concat!(env!("OUT_DIR"), "/reduced.rs"));

/// `e^M` in double-double: Taylor series of `M/2^s` with `‖M/2^s‖₁ ≤ 1/2` to 40 terms (the
/// remainder below 1e-60), then s squarings.
fn expm_dd(m: &DMatrix<f64>) -> Vec<Vec<Dd>> {
    let n = m.nrows();
    let norm = (0..n)
        .map(|j| (0..n).map(|i| m[(i, j)].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let mut s = 0;
    while norm / 2f64.powi(s) > 0.5 {
        s += 1;
    }
    let scale = Dd::from_f64(1.0 / 2f64.powi(s));
    let x: Vec<Vec<Dd>> = (0..n)
        .map(|i| (0..n).map(|j| Dd::from_f64(m[(i, j)]) * scale).collect())
        .collect();
    let mul = |a: &Vec<Vec<Dd>>, b: &Vec<Vec<Dd>>| -> Vec<Vec<Dd>> {
        (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        let mut acc = Dd::from_f64(0.0);
                        for k in 0..n {
                            acc += a[i][k] * b[k][j];
                        }
                        acc
                    })
                    .collect()
            })
            .collect()
    };
    let mut sum: Vec<Vec<Dd>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| Dd::from_f64(if i == j { 1.0 } else { 0.0 }))
                .collect()
        })
        .collect();
    let mut term = sum.clone();
    for k in 1..=40 {
        term = mul(&term, &x);
        let f = Dd::from_f64(1.0) / Dd::from_i64(k);
        for row in term.iter_mut() {
            for v in row.iter_mut() {
                *v *= f;
            }
        }
        for i in 0..n {
            for j in 0..n {
                sum[i][j] += term[i][j];
            }
        }
    }
    for _ in 0..s {
        sum = mul(&sum, &sum);
    }
    sum
}

/// The largest error of `(ad, bd)` against the double-double exponential of
/// `M = [[A h, B h], [0, 0]]`, relative to the largest entry of the reference `[Ad, Bd]`, in
/// units of `max(1, ‖M‖₁)·ε`: the relative condition number of the exponential is at least
/// `‖M‖` (Higham 2008, "Functions of Matrices", §10.2), so a backward-stable method is
/// accurate to a modest multiple of that.
fn discrete_error(a: &[f64], b: &[f64], n: usize, m: usize, h: f64, ad: &[f64], bd: &[f64]) -> f64 {
    let mut aug = DMatrix::zeros(n + m, n + m);
    for j in 0..n {
        for i in 0..n {
            aug[(i, j)] = a[i + j * n] * h;
        }
    }
    for j in 0..m {
        for i in 0..n {
            aug[(i, n + j)] = b[i + j * n] * h;
        }
    }
    let e = expm_dd(&aug);
    let mut big = 0.0f64;
    let mut err = 0.0f64;
    for i in 0..n {
        for j in 0..n + m {
            let r = e[i][j];
            let got = if j < n {
                ad[i + j * n]
            } else {
                bd[i + (j - n) * n]
            };
            big = big.max(r.to_f64().abs());
            err = err.max((Dd::from_f64(got) - r).abs().to_f64());
        }
    }
    let norm = (0..n + m)
        .map(|j| (0..n + m).map(|i| aug[(i, j)].abs()).sum::<f64>())
        .fold(1.0, f64::max);
    err / big / (norm * f64::EPSILON)
}

macro_rules! discrete_check {
    ($module:ident, $rng:expr, $worst:expr, $points:expr) => {{
        use $module as g;
        let nominal = g::Params::NOMINAL.to_array();
        let mut work = g::DiscreteWork::new();
        let (mut a, mut b, mut w) = ([0.0; g::A_LEN], [0.0; g::B_LEN], [0.0; g::WORK_LEN]);
        let (mut ad, mut bd) = ([0.0; g::A_LEN], [0.0; g::B_LEN]);
        for _ in 0..$points {
            let p: [f64; g::N_PARAMS] =
                core::array::from_fn(|k| nominal[k] * (1.0 + 0.1 * ($rng.random::<f64>() - 0.5)));
            if g::eval_ab(&p, &mut a, &mut b, &mut w).is_err() {
                continue;
            }
            for h in [1e-4, 1e-3, 1e-2, 0.1, 1.0] {
                g::eval_discrete(&p, h, &mut ad, &mut bd, &mut work).expect("discrete");
                let e = discrete_error(&a, &b, g::N_STATES, g::N_INPUTS, h, &ad, &bd);
                let key = (stringify!($module), h);
                if e > $worst.0 {
                    $worst = (e, key);
                }
            }
        }
        assert_eq!(
            g::eval_discrete(&nominal, f64::NAN, &mut ad, &mut bd, &mut work),
            Err(g::Error::SampleTime)
        );
        assert_eq!(
            g::eval_discrete(&nominal, -1e-3, &mut ad, &mut bd, &mut work),
            Err(g::Error::SampleTime)
        );
    }};
}

#[test]
fn discrete_matrices_match_a_double_double_exponential() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(20261128);
    let mut worst = (0.0, ("", 0.0));
    discrete_check!(quarter_car_discrete, rng, worst, 16);
    discrete_check!(bicycle_r5, rng, worst, 16);
    discrete_check!(chain50_r10, rng, worst, 16);
    eprintln!(
        "largest relative error of Ad, Bd: {:.3} units of max(1, ‖M‖₁)·ε ({} at h = {})",
        worst.0, worst.1.0, worst.1.1
    );
    assert!(worst.0 < 50.0, "{worst:?}");
}

fn response_error(full: &StateSpace<f64>, red: &StateSpace<f64>) -> f64 {
    let f = HessenbergForm::new(full).expect("full");
    let r = HessenbergForm::new(red).expect("reduced");
    let (mut wf, mut wr) = (f.workspace(), r.workspace());
    let (mut gf, mut gr) = ([Complex64::new(0.0, 0.0)], [Complex64::new(0.0, 0.0)]);
    let mut omegas: Vec<f64> = (0..=2000)
        .map(|k| 1e-3 * 1e4f64.powf(k as f64 / 2000.0))
        .collect();
    omegas.extend(
        eom_num::modes::eigenvalues(&full.a)
            .expect("eig")
            .iter()
            .map(|z| z.im.abs()),
    );
    omegas.push(0.0);
    let mut worst = 0.0f64;
    for w in omegas {
        let s = Complex64::new(0.0, w);
        assert_eq!(
            f.evaluate_in(s, &mut wf, &mut gf).unwrap(),
            SolveStatus::Regular
        );
        assert_eq!(
            r.evaluate_in(s, &mut wr, &mut gr).unwrap(),
            SolveStatus::Regular
        );
        worst = worst.max((gf[0] - gr[0]).norm());
    }
    worst
}

#[test]
fn reduced_chain50_follows_the_full_model_within_the_bound_near_nominal() {
    use chain50_r10 as g;
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let nominal = g::Params::NOMINAL.to_array();
    let mut state = g::StateSpace::new();
    let mut worst = 0.0f64;
    for _ in 0..12 {
        let p: [f64; g::N_PARAMS] =
            core::array::from_fn(|k| nominal[k] * (1.0 + 0.1 * (rng.random::<f64>() - 0.5)));
        state
            .evaluate(&g::Params::from_array(&p))
            .expect("valid near nominal");
        let red = StateSpace::new(
            DMatrix::from_column_slice(g::N_STATES, g::N_STATES, state.a()),
            DMatrix::from_column_slice(g::N_STATES, g::N_INPUTS, state.b()),
            DMatrix::from_column_slice(g::N_OUTPUTS, g::N_STATES, state.c()),
            DMatrix::from_column_slice(g::N_OUTPUTS, g::N_INPUTS, state.d()),
        )
        .unwrap();
        let set: Vec<(&str, f64)> = g::PARAM_NAMES.iter().copied().zip(p).collect();
        let model = models::build("chain50", &set).unwrap();
        let full = Linearizer::new(&model).run().unwrap().state_space;
        let e = response_error(&full, &red);
        worst = worst.max(e);
        assert!(
            e <= g::REDUCE_BOUND,
            "{p:?}: error {e} above the nominal bound {}",
            g::REDUCE_BOUND
        );
    }
    eprintln!(
        "chain50 → 10 states at ±5 %: largest error {worst:.4} (nominal bound {:.4})",
        g::REDUCE_BOUND
    );
}

#[test]
fn reduced_bicycle_keeps_exact_zeros_and_reports_the_validity_region() {
    use bicycle_r5 as g;
    let mut p = g::Params::NOMINAL;
    let mut state = g::StateSpace::new();
    for v in [0.5, 2.0, 4.0, 5.0, 6.0, 8.0] {
        p.v = v;
        state.evaluate(&p).expect("valid");
        let a = DMatrix::from_column_slice(g::N_STATES, g::N_STATES, state.a());
        let ev = eom_num::modes::eigenvalues(&a).expect("eig");
        let zeros = ev.iter().filter(|z| z.re == 0.0 && z.im == 0.0).count();
        assert_eq!(zeros, 2, "v = {v}: {ev:?}");
    }
    p.lambda = core::f64::consts::FRAC_PI_2;
    assert!(matches!(state.evaluate(&p), Err(g::Error::Validity { .. })));
}
