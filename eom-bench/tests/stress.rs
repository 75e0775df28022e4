//! The reduced failure map (the CI grid) through the library: no method is silently wrong in
//! any region but those docs/stress.md lists as not fixed yet; and the classification can
//! fail: an eigenvalue set moved by 1e-5, or one missing, is silently wrong.

use eom_bench::stress::classify::{MethodResult, Outcome, Verdict, classify};
use eom_bench::stress::{METHODS, run};
use num_complex::Complex64;

/// (region, method) pairs known to be silently wrong (docs/stress.md, "What is not fixed").
const KNOWN: [(&str, &str); 2] = [
    ("chain_stiffness", "numeric"),
    ("chain_stiffness", "symbolic"),
];

#[test]
fn quick_grid_has_no_silently_wrong_outcome() {
    let map = run(true, &mut |_| {}).expect("the map runs");
    for r in &map.regions {
        for m in METHODS {
            if KNOWN.contains(&(r.name, m)) {
                continue;
            }
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
fn a_known_silently_wrong_pair_is_still_wrong() {
    // If a fix lands, KNOWN must shrink (and docs/stress.md be updated): this fails then.
    let map = run(true, &mut |_| {}).expect("the map runs");
    for (region, method) in KNOWN {
        assert!(
            map.count(region, method, Outcome::SilentlyWrong) > 0,
            "{region}/{method} is no longer silently wrong: update KNOWN and docs/stress.md"
        );
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
