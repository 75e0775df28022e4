//! Rank, nullspace, equilibration and condition numbers against hand-made matrices whose
//! rank and nullspace are known exactly.

mod closed_forms;

use eom_num::linalg::{
    Equilibrate, RankTolerance, balance_in_place, condition_number, equilibrate, faer_view,
    from_faer, nullspace, nullspace_equilibrated, rank, rank_equilibrated, svd, to_faer,
};
use eom_num::{MatrixEntry, NonFiniteError, NumError, OptionError};
use nalgebra::{DMatrix, dmatrix};

/// Projector onto the column space of an orthonormal basis.
fn projector(basis: &DMatrix<f64>) -> DMatrix<f64> {
    basis * basis.transpose()
}

#[test]
fn conversions_round_trip() {
    let m = dmatrix![1.0, 2.0, 3.0; 4.0, 5.0, 6.0];
    let f = to_faer(&m);
    assert_eq!(f[(1, 2)], 6.0);
    assert_eq!(faer_view(&m)[(0, 1)], 2.0);
    assert_eq!(from_faer(f.as_ref()), m);
    // A transposed (strided) view converts too.
    assert_eq!(from_faer(f.as_ref().transpose()), m.transpose());
}

#[test]
fn svd_reconstructs_and_is_orthogonal() {
    let mut r = closed_forms::rng(1);
    let m = closed_forms::random_matrix(&mut r, 5, 3);
    let f = svd(&m).unwrap();
    let mut s = DMatrix::zeros(5, 3);
    for (i, &v) in f.singular_values.iter().enumerate() {
        s[(i, i)] = v;
    }
    let back = &f.u * s * f.v.transpose();
    assert!((back - &m).norm() < 1e-14 * m.norm());
    assert!((f.u.transpose() * &f.u - DMatrix::identity(5, 5)).norm() < 1e-14);
    assert!((f.v.transpose() * &f.v - DMatrix::identity(3, 3)).norm() < 1e-14);
}

#[test]
fn nullspace_of_exactly_rank_deficient_matrix() {
    // Row 3 = row 1 + row 2 exactly (small integers): rank 2, nullspace spanned by
    // n = (1, 1, −1, 0) × ... computed by hand: x with x1 + 2x3 = 0, x2 + x4 = 0.
    let m = dmatrix![1.0, 0.0, 2.0, 0.0; 0.0, 1.0, 0.0, 1.0; 1.0, 1.0, 2.0, 1.0];
    let ns = nullspace(&m, RankTolerance::Default).unwrap();
    assert_eq!(ns.rank, 2);
    assert_eq!(ns.basis.ncols(), 2);
    let expected = dmatrix![-2.0, 0.0; 0.0, -1.0; 1.0, 0.0; 0.0, 1.0];
    let q = expected.clone().qr().q();
    assert!((projector(&ns.basis) - projector(&q)).norm() < 1e-14);
    assert!((&m * &ns.basis).norm() < 1e-14);
    // An exact zero singular value: the gap is huge and the decision is not near tolerance.
    assert!(ns.gap > 1e12, "gap {}", ns.gap);
    assert!(!ns.decision().is_near_tolerance(100.0));
}

#[test]
fn empty_and_zero_matrices() {
    let ns = nullspace(&DMatrix::zeros(0, 3), RankTolerance::Default).unwrap();
    assert_eq!(ns.rank, 0);
    assert_eq!(ns.basis, DMatrix::identity(3, 3));
    let z = rank(&DMatrix::zeros(2, 2), RankTolerance::Default).unwrap();
    assert_eq!(z.rank, 0);
    assert!(z.gap.is_infinite());
}

#[test]
fn default_tolerance_value() {
    // 10 · max(m, n) · ε · σ_max.
    let t = RankTolerance::Default.threshold(3.0, 4, 7);
    assert_eq!(t, 10.0 * 7.0 * f64::EPSILON * 3.0);
    assert_eq!(RankTolerance::Relative(1e-3).threshold(2.0, 1, 1), 2e-3);
    assert_eq!(RankTolerance::Absolute(0.5).threshold(2.0, 1, 1), 0.5);
}

#[test]
fn gap_reports_a_close_decision() {
    // σ = (1, 1e-9): with a relative tolerance of 5e-10 the decision is rank 2, but only a
    // factor 2 above the threshold.
    let m = dmatrix![1.0, 0.0; 0.0, 1e-9];
    let r = rank(&m, RankTolerance::Relative(5e-10)).unwrap();
    assert_eq!(r.rank, 2);
    assert!((r.margin - 2.0).abs() < 1e-12);
    assert!(r.is_near_tolerance(100.0));
}

/// A constraint Jacobian whose two rows are in very different units: the first in N/m
/// (1e9 scale), the second in rad (1e-9 scale). Both constraints are genuine, so the rank is
/// 2 and the nullspace is span{(1, −1, 0, 0), (0, 0, 1, −1)}.
fn mixed_rows() -> DMatrix<f64> {
    dmatrix![1e9, 1e9, 0.0, 0.0; 0.0, 0.0, 1e-9, 1e-9]
}

#[test]
fn unequilibrated_default_flips_on_mixed_row_units() {
    let m = mixed_rows();
    let plain = nullspace(&m, RankTolerance::Default).unwrap();
    // σ_min / σ_max = 1e-18 is below 10·4·ε: the second constraint is lost.
    assert_eq!(plain.rank, 1);
    assert_eq!(plain.basis.ncols(), 3);
    for mode in [Equilibrate::Rows, Equilibrate::Both] {
        let eq = nullspace_equilibrated(&m, RankTolerance::Default, mode).unwrap();
        assert_eq!(eq.rank, 2, "{mode:?}");
        let expected = dmatrix![1.0, 0.0; -1.0, 0.0; 0.0, 1.0; 0.0, -1.0];
        let q = expected.clone().qr().q();
        let err = (projector(&eq.basis) - projector(&q)).norm();
        assert!(
            err < 1e-14,
            "{mode:?}: projector error {err:e}\n{}",
            eq.basis
        );
        assert!(eq.gap > 1e10);
    }
}

#[test]
fn unequilibrated_default_flips_on_mixed_column_units() {
    // Columns: a translation in m and a rotation in µrad-scaled units (factor 1e-17). The
    // 2×2 core [[1, 2], [3, 4]] is nonsingular, so the true rank is 2 and the nullspace is {0}.
    let s = 1e-17;
    let m = dmatrix![1.0, 2.0 * s; 3.0, 4.0 * s];
    assert_eq!(rank(&m, RankTolerance::Default).unwrap().rank, 1);
    let r = rank_equilibrated(&m, RankTolerance::Default, Equilibrate::Columns).unwrap();
    assert_eq!(r.rank, 2);
    let ns = nullspace_equilibrated(&m, RankTolerance::Default, Equilibrate::Both).unwrap();
    assert_eq!(ns.basis.ncols(), 0);
}

#[test]
fn equilibration_keeps_a_true_rank_deficiency() {
    // N has rank 1 exactly; R N C with power-of-two scalings is exact in floating point, so
    // the scaled matrix is exactly rank 1 too and equilibration must not invent rank.
    let n = dmatrix![1.0, 2.0, 3.0; 2.0, 4.0, 6.0];
    let r = DMatrix::from_diagonal(&nalgebra::dvector![2f64.powi(40), 2f64.powi(-40)]);
    let c = DMatrix::from_diagonal(&nalgebra::dvector![2f64.powi(-30), 1.0, 2f64.powi(30)]);
    let m = r * n * c;
    for mode in [Equilibrate::Rows, Equilibrate::Columns, Equilibrate::Both] {
        let ns = nullspace_equilibrated(&m, RankTolerance::Default, mode).unwrap();
        assert_eq!(ns.rank, 1, "{mode:?}");
        // The mapped basis is orthonormal and annihilates M (relative to the column scales).
        assert!((ns.basis.transpose() * &ns.basis - DMatrix::identity(2, 2)).norm() < 1e-12);
        let (eq, sc) = equilibrate(&m, mode).unwrap();
        let y = DMatrix::from_fn(3, 2, |i, j| ns.basis[(i, j)] / sc.cols[i]);
        assert!((eq * y).norm() < 1e-10, "{mode:?}");
    }
}

#[test]
fn equilibrate_uses_powers_of_two() {
    let m = dmatrix![3e6, 0.0; 0.0, 7e-5];
    let (eq, sc) = equilibrate(&m, Equilibrate::Both).unwrap();
    for v in sc.rows.iter().chain(sc.cols.iter()) {
        assert_eq!(v.log2().fract(), 0.0, "{v} is not a power of two");
    }
    for i in 0..2 {
        let mx = eq.row(i).iter().fold(0.0f64, |a, x| a.max(x.abs()));
        assert!((0.5..=2.0).contains(&mx), "row {i} max {mx}");
    }
}

#[test]
fn condition_number_closed_form() {
    let m = dmatrix![4.0, 0.0; 0.0, 0.5];
    assert!((condition_number(&m).unwrap() - 8.0).abs() < 1e-14);
    assert!(condition_number(&dmatrix![1.0, 1.0; 1.0, 1.0]).unwrap() > 1e15);
    assert_eq!(
        condition_number(&DMatrix::zeros(2, 2)).unwrap(),
        f64::INFINITY
    );
    assert_eq!(condition_number(&DMatrix::zeros(0, 0)).unwrap(), 1.0);
}

#[test]
fn balancing_is_a_similarity() {
    // Badly scaled matrix: D⁻¹ A D with D = diag(scale) must hold exactly (powers of two).
    let a = dmatrix![1.0, 1e6, 0.0; 1e-6, 2.0, 1e6; 0.0, 1e-6, 3.0];
    let mut b = a.as_slice().to_vec();
    let mut s = vec![0.0; 3];
    balance_in_place(&mut b, 3, &mut s);
    let bm = DMatrix::from_vec(3, 3, b);
    let d = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(s.clone()));
    let dinv = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(
        s.iter().map(|x| 1.0 / x).collect(),
    ));
    assert_eq!(&dinv * &a * &d, bm);
    assert!(
        bm.norm() < 1e-3 * a.norm(),
        "balancing should shrink the norm"
    );
}

#[test]
fn errors_name_the_problem() {
    let bad = dmatrix![1.0, f64::NAN];
    match rank(&bad, RankTolerance::Default) {
        Err(NumError::NonFinite(NonFiniteError::Entry(MatrixEntry { row: 0, col: 1, .. }))) => {}
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert!(matches!(svd(&bad), Err(NumError::NonFinite(_))));
    assert!(matches!(
        equilibrate(&bad, Equilibrate::Both),
        Err(NumError::NonFinite(_))
    ));
    assert!(matches!(
        condition_number(&bad),
        Err(NumError::NonFinite(_))
    ));
    let ok = dmatrix![1.0, 0.0];
    match nullspace(&ok, RankTolerance::Relative(-1.0)) {
        Err(NumError::InvalidOption(OptionError::RankTolerance {
            tolerance: RankTolerance::Relative(-1.0),
        })) => {}
        other => panic!("expected InvalidOption, got {other:?}"),
    }
    assert!(matches!(
        rank(&ok, RankTolerance::Absolute(f64::NAN)),
        Err(NumError::InvalidOption(_))
    ));
}

/// A matrix that decouples into two groups of columns (and a column no row touches): the
/// structured nullspace has the rank of the whole matrix's, every basis vector lies in one
/// group, the untouched column is its own unit vector, and the basis is an orthonormal basis
/// of the nullspace.
#[test]
fn structured_nullspace_keeps_decoupled_coordinates_apart() {
    use eom_num::linalg::{Equilibrate, RankTolerance, nullspace, nullspace_structured};
    // Columns 0, 2, 5 joined by rows 0, 2; columns 1, 3 by row 1; column 4 untouched.
    let m = DMatrix::from_row_slice(
        3,
        6,
        &[
            1.0, 0.0, 2.0, 0.0, 0.0, 0.0, //
            0.0, 3.0, 0.0, -1e3, 0.0, 0.0, //
            0.0, 0.0, 1.0, 0.0, 0.0, 4.0,
        ],
    );
    for eq in [None, Some(Equilibrate::Both)] {
        let ns = nullspace_structured(&m, RankTolerance::Default, eq).unwrap();
        let whole = nullspace(&m, RankTolerance::Default).unwrap();
        assert_eq!(ns.rank, whole.rank);
        assert_eq!(ns.basis.ncols(), 3);
        assert!((&m * &ns.basis).norm() < 1e-12);
        let gram = ns.basis.transpose() * &ns.basis;
        assert!((gram - DMatrix::<f64>::identity(3, 3)).norm() < 1e-12);
        let groups: [&[usize]; 3] = [&[0, 2, 5], &[1, 3], &[4]];
        for j in 0..3 {
            let col = ns.basis.column(j);
            let inside: Vec<usize> = groups
                .iter()
                .enumerate()
                .filter(|(_, g)| g.iter().any(|&i| col[i] != 0.0))
                .map(|(k, _)| k)
                .collect();
            assert_eq!(inside.len(), 1, "column {j} spans groups {inside:?}: {col}");
        }
        // The untouched coordinate: exactly e₄.
        assert!((0..3).any(|j| ns.basis[(4, j)].abs() == 1.0));
        // The singular values are all of the whole matrix's (three, largest first).
        assert_eq!(ns.singular_values.len(), 3);
        assert!(ns.singular_values.windows(2).all(|w| w[0] >= w[1]));
    }
}
