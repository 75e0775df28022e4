//! The typed errors print the messages the string ones did.

use super::{
    A22Rank, AmbiguousRankError, Bound, ConvergenceError, DimensionError, MatrixEntry,
    NonFiniteError, NumError, OptionError, PencilError, SingularError,
};
use crate::gain::{AMBIGUITY_FACTOR, Gain};
use crate::linalg::RankTolerance;
use num_complex::Complex64;

fn text(e: OptionError) -> String {
    NumError::InvalidOption(e).to_string()
}

/// The typed option errors print the messages the string ones did (the old format
/// strings, copied here, are the reference).
#[test]
fn option_errors_print_the_former_messages() {
    let (r, t, f) = (-1.5, f64::NAN, 0.0);
    assert_eq!(
        text(OptionError::Tolerance {
            option: "MinrealOptions.rtol",
            value: r,
            must: Bound::FiniteNonNegative
        }),
        format!("invalid option: MinrealOptions.rtol = {r} (must be finite and ≥ 0)")
    );
    assert_eq!(
        text(OptionError::Value {
            option: "ModeOptions::tol_factor",
            value: f,
            must: Bound::FinitePositive
        }),
        format!("invalid option: ModeOptions::tol_factor = {f}: must be finite and > 0")
    );
    assert_eq!(
        text(OptionError::Value {
            option: "TimeOptions::max_steps",
            value: 1.0,
            must: Bound::Between(2, 50_000_000)
        }),
        "invalid option: TimeOptions::max_steps = 1: must be in 2..=50000000"
    );
    assert_eq!(
        text(OptionError::SizeLimit {
            kind: "Absolute",
            value: f,
            must: Bound::Positive
        }),
        format!("invalid option: SizeLimit::Absolute({f}): must be > 0")
    );
    let tol = RankTolerance::Relative(t);
    assert_eq!(
        text(OptionError::RankTolerance { tolerance: tol }),
        format!("invalid option: rank tolerance {tol:?}: must be finite and ≥ 0")
    );
    let (steps, decades, ppd) = (1.234e10, 4.56, 1_000_000_000usize);
    assert_eq!(
        text(OptionError::FrequencyGridTooLarge {
            points: steps,
            decades,
            per_decade: ppd,
            limit: 10_000_000
        }),
        format!(
            "invalid option: frequency grid of {steps:.3e} points ({decades:.1} decades at \
             {ppd} per decade) exceeds the limit of 10000000"
        )
    );
    let (low, high) = (2.0, 1.0);
    assert_eq!(
        text(OptionError::FrequencyRange { low, high }),
        format!(
            "invalid option: FreqRange::Range {{ low: {low}, high: {high} }}: need 0 < low \
             < high, finite"
        )
    );
    assert_eq!(
        text(OptionError::SweepNotMonotone {
            param: "v".into(),
            index: 3,
            values: [2.0, 1.5]
        }),
        "invalid option: sweep values of v must be strictly monotone (values 3 and 4: 2 and \
         1.5)"
    );
    let lam_re = 0.25;
    assert_eq!(
        text(OptionError::UnstableLyapunovBlock {
            block: 2,
            real_part: lam_re
        }),
        format!(
            "invalid option: Lyapunov equation: the diagonal block at 2 has an eigenvalue \
             with real part {lam_re:e}, not in the open left half-plane"
        )
    );
    for (hidden, note) in [(0, ""), (2, "; 2 are uncontrollable or unobservable")] {
        assert_eq!(
            text(OptionError::OrderAboveReducible {
                order: 9,
                kept: 2,
                reducible: 5,
                hidden
            }),
            format!(
                "invalid option: order 9: at most 7 (2 kept whole and 5 stable states above \
                 rounding{note})"
            )
        );
    }
    let hz = 1.0 / 3.0;
    assert_eq!(
        text(OptionError::OrderSplitsModes { order: 4, hz }),
        format!(
            "invalid option: order 4 would split the modes at {hz:.6} Hz (a complex pair or \
             equal frequencies): use 3 or 5"
        )
    );
}

/// The typed dimension errors print the messages the string ones did.
#[test]
fn dimension_errors_print_the_former_messages() {
    let text = |e: DimensionError| NumError::Dimension(e).to_string();
    assert_eq!(
        text(DimensionError::Shape {
            matrix: "B",
            rows: 3,
            cols: 1,
            expected_rows: 2,
            expected_cols: 1,
            why: "B has one row per state"
        }),
        "dimension mismatch: B is 3×1, expected 2×1 (B has one row per state)"
    );
    assert_eq!(
        text(DimensionError::PhysColumns {
            rows: 6,
            cols: 3,
            states: 2,
            descriptor: true
        }),
        "dimension mismatch: phys is 6×3, expected one column per descriptor state (2)"
    );
    assert_eq!(
        text(DimensionError::PhysColumns {
            rows: 6,
            cols: 3,
            states: 2,
            descriptor: false
        }),
        "dimension mismatch: phys is 6×3, expected one column per state (2)"
    );
    assert_eq!(
        text(DimensionError::FreqWorkspace {
            function: "evaluate_in",
            n: 3,
            m: 1,
            p: 2,
            workspace_n: 3,
            workspace_m: 1,
            out: 0,
            expected: 2
        }),
        "dimension mismatch: evaluate_in: model has n = 3, m = 1, p = 2; workspace is for \
         n = 3, m = 1; output has length 0 (expected 2)"
    );
    assert_eq!(
        text(DimensionError::SweepOrder {
            states: 4,
            first: 2,
            param: "v".into(),
            value: 1.5
        }),
        "dimension mismatch: A is 4×4 here but 2×2 at v = 1.5"
    );
}

/// The typed convergence errors print the messages the string ones did.
#[test]
fn convergence_errors_print_the_former_messages() {
    let text = |e: ConvergenceError| NumError::NoConvergence(e).to_string();
    let (r, c, lam) = (3, 4, Complex64::new(-1.0, 2.0));
    assert_eq!(
        text(ConvergenceError::Factorisation {
            step: "singular values",
            rows: r,
            cols: c,
            object: "matrix"
        }),
        format!("no convergence: singular values of a {r}×{c} matrix")
    );
    assert_eq!(
        text(ConvergenceError::AtEigenvalue {
            step: "PBH SVD",
            lambda: lam,
            detail: Some("NoConvergence".into())
        }),
        format!("no convergence: PBH SVD at λ = {lam}: NoConvergence")
    );
    assert_eq!(
        text(ConvergenceError::AtEigenvalue {
            step: "inverse iteration of the PBH test",
            lambda: lam,
            detail: None
        }),
        format!("no convergence: inverse iteration of the PBH test at λ = {lam}")
    );
    let (first, second) = (vec![lam, lam.conj()], vec![Complex64::new(-1.0, 0.0)]);
    let (below, scale) = (1e-9, 2.5);
    assert_eq!(
        text(ConvergenceError::SchurSwap {
            first: first.clone(),
            second: second.clone(),
            perturbation: below,
            scale
        }),
        format!(
            "no convergence: reordering the real Schur form: swapping the blocks of \
             {first:?} and {second:?} would perturb them by {below:.3e} relative to \
             {scale:.3e} (eigenvalues too close to separate)"
        )
    );
}

/// The typed singular-matrix errors print the messages the string ones did.
#[test]
fn singular_errors_print_the_former_messages() {
    let text = |e: SingularError| NumError::Singular(e).to_string();
    let k = 3;
    assert_eq!(
        text(SingularError::LuFailed {
            matrix: "A22",
            n: k,
            passed: "passed the rank test",
            failed: "factorisation broke down"
        }),
        format!(
            "singular matrix: A22 ({k}×{k}) passed the rank test but its LU factorisation \
             broke down"
        )
    );
    let s = Complex64::new(0.0, 2.0);
    assert_eq!(
        text(SingularError::Eigenvalue { s, n: 2 }),
        format!(
            "singular matrix: sI − A at s = {s} (2×2 model): s is numerically an eigenvalue of A"
        )
    );
    assert_eq!(
        text(SingularError::ZeroSubspace {
            n: 4,
            right: 2,
            right_index: 1,
            left: 1,
            left_index: 1
        }),
        "singular matrix: A (4×4) is singular but its zero-eigenvalue subspace is \
         ill-determined: the right chain gives dimension 2 (index 1), the left chain 1 \
         (index 1)"
    );
}

/// The typed non-finite errors print the messages the string ones did.
#[test]
fn non_finite_errors_print_the_former_messages() {
    let text = |e: NonFiniteError| NumError::NonFinite(e).to_string();
    let entry = MatrixEntry {
        matrix: "A".into(),
        row: 1,
        col: 0,
        value: f64::NAN,
        nrows: 3,
        ncols: 3,
    };
    assert_eq!(
        text(NonFiniteError::Entry(entry.clone())),
        format!("non-finite entry in {entry}")
    );
    assert_eq!(
        text(NonFiniteError::Entry(entry)),
        "non-finite entry in A[1, 0] = NaN (3×3 matrix)"
    );
    let s = Complex64::new(f64::NAN, 1.0);
    assert_eq!(
        text(NonFiniteError::EvaluationPoint { s }),
        format!("non-finite entry in evaluation point s = {s}")
    );
    assert_eq!(
        text(NonFiniteError::Matrix { matrix: "B" }),
        "non-finite entry in B"
    );
}

/// The pencil and ambiguous-rank errors print the messages the string ones did.
#[test]
fn pencil_and_rank_errors_print_the_former_messages() {
    let (r, n, k, rank, smin, thr22) = (1, 3, 2, 1, 1.5e-17, 2.2e-15);
    let detail = format!(
        "E has rank {r} of {n}; the algebraic block A22 ({k}×{k}) has rank {rank} (smallest \
         singular value of the equilibrated A22 {smin:.3e} ≤ threshold {thr22:.3e})"
    );
    let decision = A22Rank {
        e_rank: r,
        n,
        k,
        a22_rank: rank,
        smallest: smin,
        threshold: thr22,
    };
    assert_eq!(
        NumError::SingularPencil(PencilError::RankDeficient(decision.clone())).to_string(),
        format!(
            "singular pencil: {detail}, and sE − A is rank deficient at generic s: the equations \
             do not determine the motion (missing equation or redundant coordinate)"
        )
    );
    assert_eq!(
        NumError::HigherIndex(decision).to_string(),
        format!(
            "descriptor index > 1: {detail}; the pencil is regular, so its index is > 1 (e.g. a \
             constraint on a position without its derivative); reduce the index before calling \
             descriptor_to_state_space"
        )
    );
    let (ah, bh, j) = (1e-18, 3e-19, 2);
    assert_eq!(
        NumError::SingularPencil(PencilError::VanishingEigenvalue {
            alpha: ah,
            beta: bh,
            index: j,
            n,
            e_rank: r
        })
        .to_string(),
        format!(
            "singular pencil: QZ returned α ≈ β ≈ 0 (|α|/‖A‖ = {ah:.2e}, |β|/‖E‖ = {bh:.2e}) for \
             eigenvalue {j}: det(sE − A) vanishes identically ({n}×{n} pencil, rank E = {r})"
        )
    );
    assert_eq!(
        NumError::AmbiguousRank(AmbiguousRankError::StructuralZeros {
            structural: 2,
            n: 4,
            first: 1,
            second: 1
        })
        .to_string(),
        format!(
            "ambiguous rank decision: the structure of the model proves 2 zero eigenvalue(s), but \
             the rank decisions on A (4×4) find 1 at the default threshold and 1 at one \
             {AMBIGUITY_FACTOR} times larger: the gains would amplify rounding"
        )
    );
    let margin = 3.25;
    assert_eq!(
        NumError::AmbiguousRank(AmbiguousRankError::Gains {
            n: 4,
            margin,
            first: 0,
            second: 1,
            first_gains: vec![Gain::Finite(2.0), Gain::Finite(-0.5)],
            second_gains: vec![
                Gain::Integrating {
                    order: 1,
                    coefficient: 1.0
                },
                Gain::Finite(-0.5)
            ],
        })
        .to_string(),
        format!(
            "ambiguous rank decision: the rank of A (4×4) was decided within a factor \
             {margin:.3} of its threshold, and a threshold {AMBIGUITY_FACTOR} times larger (1 \
             zero eigenvalue(s) instead of 0) gives other gains ([integrating (order 1), \
             {:.6e}] instead of [{:.6e}, {:.6e}])",
            -0.5, 2.0, -0.5
        )
    );
}
