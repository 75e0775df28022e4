//! Tests of the lowering's rewrites.

use super::*;

/// Lowers `roots` over the parameters `ps` (interface positions in order), with `pivots`
/// checked nonzero.
fn lowered(roots: &[Expr], ps: &[Expr], pivots: &[Expr]) -> Lowered {
    lower(roots, ps, pivots, Rounding::Free).expect("lower")
}

/// `a + b − cos x · (a + b − c) / cos x` is `c`: the pool keeps `cos x / cos x` (cos x may
/// be zero), the lowering cancels it where a validity check keeps `cos x` nonzero (as in
/// the bicycle, with `cos λ`), and then the sum must cancel too rather than compute `c`
/// plus the rounding error of `a + b`.
#[test]
fn sums_that_cancel_after_a_cancelled_product_are_expanded() {
    let [a, b, c, x] = ["ea", "eb", "ec", "ex"].map(|n| Expr::param(n, 0.5).expect("param"));
    let inner = a + b - c;
    let cx = x.cos();
    let e = a + b - cx * inner * cx.recip();
    // The pool has not cancelled it (or this test tests nothing).
    assert!(e.to_string().contains("cos"), "{e}");
    let l = lowered(&[inner, e], &[a, b, c, x], &[cx]);
    let (op, neg) = l.roots[1];
    assert_eq!(op, Operand::Param(2), "{:?}", l.insts);
    assert!(!neg);
    // `a + b − c` is still computed once for the first root, and nothing else is.
    let sums = l
        .insts
        .iter()
        .filter(|i| matches!(i.rhs, Rhs::Sum { .. }))
        .count();
    assert_eq!(sums, 1, "{:?}", l.insts);
}

/// Expansion is refused when it would add operations: `d + cos x·(a + b + c)/cos x` keeps
/// the shared sum as one term.
#[test]
fn sums_without_cancellation_are_not_expanded() {
    let [a, b, c, d, x] =
        ["fa", "fb", "fc", "fd", "fx"].map(|n| Expr::param(n, 0.5).expect("param"));
    let inner = a + b + c;
    let cx = x.cos();
    let e = d + cx * inner * cx.recip();
    let l = lowered(&[inner, e], &[a, b, c, d, x], &[cx]);
    let Operand::Temp(t) = l.roots[1].0 else {
        panic!("{:?}", l.roots)
    };
    let rhs = &l.insts.iter().find(|i| i.def == t).expect("def").rhs;
    let Rhs::Sum { terms, .. } = rhs else {
        panic!("{rhs:?}")
    };
    assert_eq!(terms.len(), 2, "{rhs:?}");
}

/// Multiplications of the instructions (a coefficient other than ±1 counts as one).
fn multiplications(l: &Lowered) -> usize {
    l.insts
        .iter()
        .map(|i| match &i.rhs {
            Rhs::Prod { coef, num, den } => {
                let factors = num.len() + den.len() + usize::from(coef.abs() != 1.0);
                factors.saturating_sub(1)
            }
            _ => 0,
        })
        .sum()
}

/// `m·l²·x²` next to `l·x` (the shimmy's pivot) is `m·(l·x)²`: three multiplications in
/// all, sharing `l·x`, where one chain per square takes four.
#[test]
fn equal_powers_are_grouped_and_share_their_base() {
    let [m, l, x] = ["gm", "gl", "gx"].map(|n| Expr::param(n, 0.5).expect("param"));
    let pivot = m * l.powi(2) * x.powi(2);
    let lowered = lowered(&[pivot, l * x], &[m, l, x], &[]);
    assert_eq!(multiplications(&lowered), 3, "{:?}", lowered.insts);
    let lx = |i: &Inst| {
        matches!(&i.rhs, Rhs::Prod { num, den, .. }
            if den.is_empty() && num.len() == 2 && num.contains(&Operand::Param(1))
                && num.contains(&Operand::Param(2)))
    };
    assert_eq!(lowered.insts.iter().filter(|i| lx(i)).count(), 1);
}

/// A square that exists already is shared instead: `l²` then `m·l²·x²` keeps `l²`.
#[test]
fn equal_powers_are_not_grouped_when_a_power_exists() {
    let [m, l, x] = ["hm", "hl", "hx"].map(|n| Expr::param(n, 0.5).expect("param"));
    let square = l.powi(2);
    let lowered = lowered(&[square, m * square * x.powi(2)], &[m, l, x], &[]);
    // l², x², and the product of three: four, the same as grouping would take.
    assert_eq!(multiplications(&lowered), 4, "{:?}", lowered.insts);
    let ll = |i: &Inst| matches!(&i.rhs, Rhs::Prod { num, .. } if num == &[Operand::Param(1), Operand::Param(1)]);
    assert_eq!(
        lowered.insts.iter().filter(|i| ll(i)).count(),
        1,
        "{:?}",
        lowered.insts
    );
}
