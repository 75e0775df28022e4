//! Issue 19, case 6: the rounding error of the bicycle's generated code (and of the symbolic
//! reduction on the tape) against a double-double evaluation of the same formulas, at 1024
//! random points with every one of the 27 parameters within ±20 % of nominal — the protocol
//! of `bench/pydy/accuracy.py`, which measures PyDy's generated C for the same model (A 6×6,
//! B 6×2 with the lean and steer torques) against a 30-digit mpmath evaluation of sympy's
//! expressions. Its figures (run 2026-11-26, 1024 points):
//!
//! | | PyDy bicycle6 |
//! |---|---|
//! | row-scaled, `|Δ|` / largest `|ref|` of the row of `[A B]` | 2.348e-14 |
//! | B, entry-wise `|Δ|/|ref|` | 1.827e-15 |
//! | A, entry-wise `|Δ|/|ref|` | 1.339e-12 |
//!
//! The row-scaled figure compares the two codes' formulas; the entry-wise ones are dominated
//! by entries that pass near zero inside the box, which depend on the choice of coordinates
//! (PyDy's are the benchmark's lean and steer, eom's the rear frame's lean and yaw and the
//! front frame's yaw), so they are not comparable entry by entry. Before the pivot choice
//! kept the heavy rear frame's coordinates independent, eom's generated code had a row-scaled
//! error of 9.7e-14 on these points.

use tests::work_precision::entries::{EntryErrors, entry_errors};

const PYDY_ROW_SCALED: f64 = 2.348e-14;
const PYDY_B_ENTRYWISE: f64 = 1.827e-15;

/// The entry errors at 1024 points for each of two seeds (PyDy's figures are the maxima over
/// another sample of the same distribution: the comparison needs a margin, which the
/// generated code has, 1.4–1.6× on the row-scaled error (1.4e-14 and 1.7e-14 for these two
/// seeds), and the tape does not: 1.6e-14 and 2.4e-14, PyDy's level).
fn rows() -> Vec<EntryErrors> {
    let mut rows = Vec::new();
    for seed in [20261126, 20261121] {
        rows.extend(entry_errors("bicycle", 1024, 0.2, seed).expect("entry errors"));
    }
    for r in &rows {
        println!("{r:?}");
    }
    rows
}

fn rows_of<'a>(rows: &'a [EntryErrors], method: &str) -> Vec<&'a EntryErrors> {
    let out: Vec<_> = rows.iter().filter(|r| r.method == method).collect();
    assert_eq!(out.len(), 2, "{method}: one row per seed");
    out
}

#[test]
fn generated_bicycle_rounds_less_than_pydy_row_by_row() {
    let rows = rows();
    for method in ["generated f64", "generated f64 egg"] {
        for r in rows_of(&rows, method) {
            assert_eq!(
                r.points, 1024,
                "{method}: a point failed its validity checks"
            );
            assert!(
                r.row_scaled <= PYDY_ROW_SCALED,
                "{method}: row-scaled error {:.3e} above PyDy's {PYDY_ROW_SCALED:.3e} (at {:?})",
                r.row_scaled,
                r.worst
            );
        }
    }
    // The tape evaluates the same formulas in another order: at PyDy's level.
    for r in rows_of(&rows, "symbolic (tape)") {
        assert!(r.row_scaled <= 1.5 * PYDY_ROW_SCALED, "{r:?}");
    }
}

#[test]
fn simplified_code_has_b_as_accurate_as_pydy() {
    // B = M⁻¹ F: its error is the reduced mass matrix's. The default generated code shares
    // one reciprocal per denominator (a second rounding) and is 1.4–1.7× PyDy's here.
    let rows = rows();
    for r in rows_of(&rows, "generated f64 egg") {
        assert!(
            r.b_entrywise <= PYDY_B_ENTRYWISE,
            "B entry-wise error {:.3e} above PyDy's {PYDY_B_ENTRYWISE:.3e}",
            r.b_entrywise
        );
    }
    for r in rows_of(&rows, "generated f64") {
        assert!(r.b_entrywise <= 2.0 * PYDY_B_ENTRYWISE, "{r:?}");
    }
}

#[test]
fn f32_code_is_within_its_precision() {
    let rows = rows();
    for r in rows_of(&rows, "generated f32") {
        // f32 rounding (6e-8) amplified as the f64 code's is (row-scaled about 60 ulps).
        assert!(r.row_scaled < 1e-4 && r.row_scaled > 1e-9, "{r:?}");
    }
}
