//! The reduced failure map (the CI grid) through the library: no method is silently wrong
//! anywhere; and the classification can fail: an eigenvalue set moved by 1e-5, or one
//! missing, is silently wrong.

use eom_bench::stress::classify::{MethodResult, Outcome, Verdict, classify};
use eom_bench::stress::{METHODS, run};
use num_complex::Complex64;

#[test]
fn quick_grid_has_no_silently_wrong_outcome() {
    let map = run(true, &mut |_| {}).expect("the map runs");
    for r in &map.regions {
        for m in METHODS {
            let bad: Vec<_> = map
                .cells
                .iter()
                .filter(|c| c.region == r.name && c.method == m)
                .filter(|c| c.outcome == Outcome::SilentlyWrong)
                .collect();
            assert!(bad.is_empty(), "{}/{m}: {bad:#?}", r.name);
        }
    }
    // Every point of every region has a reference (no unchecked cell on this grid).
    assert!(
        map.cells.iter().all(|c| c.outcome != Outcome::Unchecked),
        "{:#?}",
        map.cells
            .iter()
            .filter(|c| c.outcome == Outcome::Unchecked)
            .collect::<Vec<_>>()
    );
}

#[test]
fn the_stiff_chain_is_reported_not_silently_wrong() {
    // At a stiffness ratio of 1e±10 the slow eigenvalues of the chain are off by about 2e-6
    // on the elimination paths (the rounding of the assembled stiffness entries): the cells
    // are reported through the modes' accuracy estimate, which `eom analyze` warns about.
    let map = run(true, &mut |_| {}).expect("the map runs");
    for m in ["numeric", "symbolic"] {
        let extreme: Vec<_> = map
            .cells
            .iter()
            .filter(|c| c.region == "chain_stiffness" && c.method == m)
            .filter(|c| c.value <= 1e-9 || c.value >= 1e9)
            .collect();
        assert!(!extreme.is_empty());
        for c in extreme {
            let err = c.error.expect("measured");
            if err > 1e-6 {
                assert_eq!(c.outcome, Outcome::Reported, "{c:?}");
                assert!(c.note.contains("relative accuracy about"), "{c:?}");
            }
        }
    }
}

#[test]
fn deliberately_wrong_eigenvalues_are_silently_wrong() {
    let want = [
        Complex64::new(-0.5, 3.0),
        Complex64::new(-0.5, -3.0),
        Complex64::new(2.0, 0.0),
    ];
    let moved: Vec<Complex64> = want.iter().map(|z| z * (1.0 + 1e-5)).collect();
    let r = MethodResult::Done {
        eigenvalues: moved,
        verdict: Verdict::Unstable,
        doubts: Vec::new(),
    };
    assert_eq!(classify(&r, Some(&want)).0, Outcome::SilentlyWrong);
    let missing = MethodResult::Done {
        eigenvalues: want[..2].to_vec(),
        verdict: Verdict::Stable,
        doubts: Vec::new(),
    };
    assert_eq!(classify(&missing, Some(&want)).0, Outcome::SilentlyWrong);
}
