//! Model reduction (`eom_num::model_reduction`) on the built-in models: the Hankel singular
//! values against an independent computation, the a-priori bound against the error measured
//! for every order, and the modes a reduction must keep.
//!
//! Reference data: `tests/data/hankel.json`, written by `tests/data/gen_hankel.py` (SciPy's
//! `solve_continuous_lyapunov`, and mpmath at 40 digits, on the models built from their
//! physics; the command and versions are in the script and the file).

use eom_model::Linearizer;
use eom_num::StateSpace;
use eom_num::model_reduction::{ReducedModel, Reducer, ReductionMethod};
use serde_json::Value;

const DATA: &str = include_str!("../data/hankel.json");

fn linearize(name: &str, at: &[(&str, f64)]) -> StateSpace<f64> {
    let model = models::build(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
    Linearizer::new(&model)
        .at(at)
        .run()
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .state_space
}

fn reference(model: &str) -> (Vec<f64>, Vec<f64>, Vec<bool>) {
    let data: Value = serde_json::from_str(DATA).expect("hankel.json");
    let case = data["cases"]
        .as_array()
        .expect("cases")
        .iter()
        .find(|c| c["model"] == model)
        .unwrap_or_else(|| panic!("{model} in hankel.json"));
    let list = |k: &str| -> Vec<f64> {
        case[k]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    let resolved = case["scipy_resolved"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_bool().unwrap())
        .collect();
    (list("mpmath"), list("scipy"), resolved)
}

/// The Hankel singular values to 1e-8 relative, down to what double precision can resolve: a
/// value below `n·ε·σ₁` (the absolute accuracy of any method working in f64 on these
/// Gramians' factors) is only checked to lie below that floor.
fn check_hankel(name: &str) {
    let ss = linearize(name, &[]);
    let r = Reducer::new(&ss).run().expect("reduce");
    let (exact, scipy, resolved) = reference(name);
    assert_eq!(r.kept, 0, "{name} is stable");
    assert_eq!(r.hankel.len(), exact.len(), "{name}");
    let floor = exact.len() as f64 * f64::EPSILON * exact[0];
    let mut checked = 0;
    for (i, (&s, &e)) in r.hankel.iter().zip(&exact).enumerate() {
        if e > 1e3 * floor {
            assert!(
                (s - e).abs() <= 1e-8 * e,
                "{name} σ{}: {s} against {e}",
                i + 1
            );
            checked += 1;
        } else {
            assert!(
                s <= 1e3 * floor + e,
                "{name} σ{}: {s} above the floor {floor}",
                i + 1
            );
        }
        if resolved[i] {
            assert!(
                (s - scipy[i]).abs() <= 1e-8 * scipy[i],
                "{name} σ{} SciPy {}",
                i + 1,
                scipy[i]
            );
        }
    }
    eprintln!(
        "{name}: {checked} of {} Hankel singular values checked to 1e-8",
        exact.len()
    );
}

#[test]
fn hankel_singular_values_of_the_quarter_car() {
    check_hankel("quarter_car");
}

#[test]
fn hankel_singular_values_of_chain50() {
    check_hankel("chain50");
}

/// The measured error may exceed the bound only by rounding: both are computed in f64, and
/// where the bound is tiny the error measured is the rounding of the two models' responses.
fn within_bound(r: &ReducedModel) -> bool {
    let bound = r.bound.expect("balanced methods have a bound");
    let sigma1 = r.hankel.first().copied().unwrap_or(0.0);
    let rounding = 1e3 * r.full_states as f64 * f64::EPSILON * sigma1;
    r.error.hinf <= bound * (1.0 + 1e-9) + rounding
}

#[test]
fn the_bound_holds_for_every_order_of_every_catalogue_model() {
    let mut orders = 0;
    for info in models::catalogue() {
        let name = info.name_at(10);
        let ss = linearize(&name, &[]);
        let first = Reducer::new(&ss)
            .run()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        for r in first.kept..=first.kept + first.numerical_order {
            for method in [ReductionMethod::Balanced, ReductionMethod::MatchDc] {
                let red = Reducer::new(&ss)
                    .method(method)
                    .order(r)
                    .run()
                    .unwrap_or_else(|e| panic!("{name} {method:?} order {r}: {e}"));
                assert_eq!(red.order(), r);
                assert!(
                    within_bound(&red),
                    "{name} {method:?} order {r}: measured {} above the bound {:?}",
                    red.error.hinf,
                    red.bound
                );
                if method == ReductionMethod::MatchDc {
                    let sigma1 = red.hankel.first().copied().unwrap_or(0.0);
                    assert!(
                        red.error.dc <= 1e-8 * sigma1.max(1e-300) + 1e-12 * red.bound.unwrap(),
                        "{name} matchdc order {r}: DC error {}",
                        red.error.dc
                    );
                }
                orders += 1;
            }
        }
    }
    assert!(orders > 50, "{orders} reductions checked");
}

/// The reduced eigenvalues: how many are exactly zero, and the oscillatory one nearest `z`.
fn zeros_and_nearest(
    red: &ReducedModel,
    z: num_complex::Complex64,
) -> (usize, num_complex::Complex64) {
    let ev = eom_num::modes::eigenvalues(&red.state_space.a).expect("eigenvalues");
    let zeros = ev.iter().filter(|e| e.re == 0.0 && e.im == 0.0).count();
    let nearest = ev
        .iter()
        .copied()
        .filter(|e| e.im > 0.0)
        .min_by(|a, b| (a - z).norm().total_cmp(&(b - z).norm()))
        .expect("an oscillatory pair");
    (zeros, nearest)
}

#[test]
fn the_bicycle_at_5_m_s_keeps_its_zeros_and_its_weave() {
    let ss = linearize("bicycle", &[("v", 5.0)]);
    let full = eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues");
    let weave = *full
        .iter()
        .find(|z| z.im > 1.0)
        .expect("the weave is oscillatory at 5 m/s");
    // Balanced truncation to 5 states: the two structural zeros kept whole (exactly zero),
    // the castor mode (−14 1/s, the smallest Hankel singular value) removed, the weave close.
    let red = Reducer::new(&ss).order(5).run().expect("reduce");
    assert_eq!((red.kept, red.structural_zeros), (2, 2));
    let (zeros, near) = zeros_and_nearest(&red, weave);
    assert_eq!(zeros, 2, "{:?}", red.state_space.a);
    assert!(
        (near - weave).norm() < 0.03 * weave.norm(),
        "weave {weave}, reduced {near}"
    );
    assert!(within_bound(&red));
    // Modal truncation in a band around the weave keeps it exactly, and the zeros.
    let f = weave.norm() / (2.0 * std::f64::consts::PI);
    let modal = Reducer::new(&ss)
        .method(ReductionMethod::Modal)
        .band_hz(0.9 * f, 1.1 * f)
        .run()
        .expect("modal");
    assert_eq!(modal.order(), 4);
    let (zeros, near) = zeros_and_nearest(&modal, weave);
    assert_eq!(zeros, 2);
    assert!(
        (near - weave).norm() < 1e-12 * weave.norm(),
        "weave {weave}, modal {near}"
    );
}

/// Degenerate models are reduced, not refused: no input (every Hankel singular value zero),
/// everything kept whole (a free mass: two structural zeros), an unstable model.
#[test]
fn degenerate_and_unstable_models() {
    use nalgebra::dmatrix;
    // No input.
    let ss = StateSpace::new(
        dmatrix![0.0, 1.0; -4.0, -0.4],
        nalgebra::DMatrix::zeros(2, 0),
        dmatrix![1.0, 0.0],
        nalgebra::DMatrix::zeros(1, 0),
    )
    .unwrap();
    let r = Reducer::new(&ss).run().expect("no input");
    assert_eq!((r.order(), r.numerical_order), (0, 0));
    // A free mass: x'' = u, all kept whole.
    let ss = StateSpace::new(
        dmatrix![0.0, 1.0; 0.0, 0.0],
        dmatrix![0.0; 1.0],
        dmatrix![1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    let r = Reducer::new(&ss).run().expect("free mass");
    assert_eq!((r.kept, r.order()), (2, 2));
    // Unstable: an inverted pendulum with a damped mode beside it.
    let ss = StateSpace::new(
        dmatrix![0.0, 1.0, 0.0, 0.0; 9.0, 0.0, 0.0, 0.0; 0.0, 0.0, 0.0, 1.0; 0.0, 0.0, -100.0, -2.0],
        dmatrix![0.0; 1.0; 0.0; 1.0],
        dmatrix![1.0, 0.0, 1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    let r = Reducer::new(&ss).order(3).run().expect("unstable");
    assert_eq!(r.kept, 1, "only +3 grows; −3 is stable");
    let ev = eom_num::modes::eigenvalues(&r.state_space.a).unwrap();
    assert!(ev.iter().any(|z| (z.re - 3.0).abs() < 1e-12), "{ev:?}");
    assert!(within_bound(&r));
}
