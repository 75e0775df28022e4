//! Stability without eigenvalues (`EmitOptions::stability`): the characteristic polynomial's
//! coefficients and the Liénard–Chipart conditions as straight-line code in the parameters,
//! each with a bound on its rounding error, and a verdict that says "undecided" where a
//! condition is within its bound of zero.
//!
//! The polynomial is the closed form `eom symbolic` computes (`eom_sym::closed`):
//! `det(sI − A) = s^k · p(s) / scale` from the descriptor pencil `det(sE − F)/det(E)` of the
//! reduction, the `k` structural zero roots divided out exactly (they are neutral, as the
//! eigenvalue verdict's structural zeros are). With `p(s) = a₀ + a₁s + … + a_d s^d`, the
//! roots of `p` all have negative real parts exactly when (Liénard & Chipart 1914; Gantmacher,
//! *The Theory of Matrices*, vol. 2, XV §13) every coefficient has the sign of `a_d` and the
//! Hurwitz determinants `Δ_{d−1}, Δ_{d−3}, …` (taken on `p·sign(a_d)`) are positive. The
//! conditions are evaluated as such from the coefficients' formulas — no factor of known
//! sign is divided out, so they hold whatever the parameters' values.
//!
//! The bounds come from the a-priori analysis of the straight-line code, with magnitudes the
//! code computes next to the values (see `render/bounded.rs`): a condition whose value
//! exceeds its bound has the sign computed, whatever the rounding.

use crate::CodegenError;
use crate::render::{BoundedCode, Ctx, FilterCode, render_bounded, render_filter};
use eom_model::SymbolicStateSpace;
use eom_sym::closed::{ClosedForms, hurwitz_minor};
use eom_sym::lower::{Rounding, lower};
use eom_sym::{Expr, subs_many};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// The largest model (states) whose characteristic polynomial is formed for `--stability`
/// (the expansion by minors grows as `n·2ⁿ`).
pub const MAX_STABILITY_STATES: usize = 16;

/// The polynomial and the conditions, as expressions of the generated code's parameters.
pub(crate) struct StabilityForm {
    /// The degree of `p`.
    degree: usize,
    /// The structural zero roots divided out.
    zero_roots: usize,
    /// `a₀ … a_d`, then the Hurwitz determinants.
    conditions: Vec<Expr>,
    /// Per condition: its description, and its degree in the coefficients (the power of
    /// `sign(a_d)` that normalises it).
    labels: Vec<(String, usize)>,
}

impl StabilityForm {
    /// The form of `sym`, with the fixed parameters (`fixed`: parameter and value)
    /// substituted first.
    pub(crate) fn new(
        sym: &SymbolicStateSpace,
        fixed: &[(Expr, Expr)],
    ) -> Result<StabilityForm, CodegenError> {
        let (e, f) = sym.pencil();
        let n = f.nrows();
        if n > MAX_STABILITY_STATES {
            return Err(CodegenError::BadOption {
                option: "stability",
                problem: format!(
                    "the characteristic polynomial of a {n}-state model is not formed (at most {MAX_STABILITY_STATES} states)"
                ),
            });
        }
        let sub = |m: &nalgebra::DMatrix<Expr>| -> Result<nalgebra::DMatrix<Expr>, CodegenError> {
            if fixed.is_empty() {
                return Ok(m.clone());
            }
            let v = subs_many(m.as_slice(), fixed)?;
            Ok(nalgebra::DMatrix::from_vec(m.nrows(), m.ncols(), v))
        };
        let (e, f) = (sub(&e)?, sub(&f)?);
        let p = ClosedForms::default()
            .with_max_states(MAX_STABILITY_STATES)
            .pencil_polynomial(Some(&e), &f)?;
        let a = p.polynomial.coefficients.clone();
        let d = a.len().saturating_sub(1);
        let mut conditions = a.clone();
        let mut labels: Vec<(String, usize)> = (0..=d)
            .map(|k| (format!("coefficient of s^{k}"), 1))
            .collect();
        let mut k = d.saturating_sub(1);
        while k >= 2 {
            conditions.push(hurwitz_minor(&a, k));
            labels.push((format!("Hurwitz determinant Δ{k}"), k));
            k -= 2;
        }
        Ok(StabilityForm {
            degree: d,
            zero_roots: p.zero_roots,
            conditions,
            labels,
        })
    }
}

/// The items of the generated module: constants, `Verdict`, `characteristic_polynomial`,
/// `stability_conditions`, `stability`. `validate`, when given, is a
/// statement that returns the generated `Error` when the point `p` is outside the validity
/// region of the reduction's rank decisions.
pub(crate) fn render(
    ctx: &Ctx,
    form: &StabilityForm,
    validate: Option<TokenStream>,
) -> Result<TokenStream, CodegenError> {
    let lowered = lower(
        &form.conditions,
        &ctx.problem.param_exprs,
        &[],
        Rounding::Free,
    )?;
    let nc = form.conditions.len();
    let d = form.degree;
    let k = form.zero_roots;
    let lead = d;
    let scalar = raw_body(ctx, &lowered)?;
    let quick = quick_items(ctx, &lowered, lead)?;
    let labels = form.labels.iter().map(|(l, _)| l.as_str());
    let degrees = form.labels.iter().map(|(_, g)| *g);
    let check = validate.unwrap_or_default();
    let doc_raw = " The coefficients `a₀ … a_d` of `p(s)` (as computed: not normalised by \
                   the sign of `a_d`) and the Hurwitz determinants, with bounds on their \
                   rounding errors.";
    Ok(quote! {
        /// The degree `d` of `p(s)`, the characteristic polynomial with its structural zero
        /// roots divided out: `det(sI − A) = s^ZERO_ROOTS · p(s) / scale`.
        pub const POLY_DEGREE: usize = #d;
        /// The structural zero roots of `det(sI − A)` (neutral in the verdict).
        pub const ZERO_ROOTS: usize = #k;
        /// The number of Liénard–Chipart conditions.
        pub const N_CONDITIONS: usize = #nc;
        /// What each condition is: the coefficients of `p(s)` from `s⁰` up, then the Hurwitz
        /// determinants.
        pub const CONDITIONS: [&str; N_CONDITIONS] = [#(#labels),*];
        /// The degree of each condition in the coefficients: the power of `sign(a_d)` that
        /// normalises it.
        pub const CONDITION_DEGREES: [usize; N_CONDITIONS] = [#(#degrees),*];

        /// Whether every root of `p(s)` (every eigenvalue but the structural zeros) has a
        /// negative real part, decided from the conditions and their rounding-error bounds.
        /// `#[repr(i8)]`: `-1`, `0`, `1` across a foreign-function boundary.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(i8)]
        pub enum Verdict {
            /// A condition is certainly not positive (at most minus its bound, or exactly
            /// zero with no rounding): some root has a real part ≥ 0 (unstable or marginal).
            Unstable = -1,
            /// No condition is negative beyond its bound, but one (or the leading coefficient)
            /// is within its bound of zero: rounding could change the answer.
            Undecided = 0,
            /// Every condition is positive beyond its bound.
            Stable = 1,
        }

        #[doc = #doc_raw]
        #[inline(always)]
        fn stability_raw(p: &[f64; N_PARAMS], c: &mut [f64; N_CONDITIONS], e: &mut [f64; N_CONDITIONS]) {
            #scalar
        }

        /// The conditions normalised by the sign of the leading coefficient; `false` (left
        /// as computed) when that sign is not decided.
        #[inline(always)]
        fn normalise(c: &mut [f64; N_CONDITIONS], e: &[f64; N_CONDITIONS]) -> bool {
            let lead = c[#lead];
            if !(lead.abs() > e[#lead]) {
                return false;
            }
            if lead < 0.0 {
                for (x, g) in c.iter_mut().zip(CONDITION_DEGREES) {
                    if g % 2 == 1 {
                        *x = -*x;
                    }
                }
            }
            true
        }

        /// The verdict from the raw conditions.
        #[inline(always)]
        fn verdict_of(c: &mut [f64; N_CONDITIONS], e: &[f64; N_CONDITIONS]) -> Verdict {
            if !normalise(c, e) {
                return Verdict::Undecided;
            }
            let (mut negative, mut open) = (false, false);
            for (x, b) in c.iter().zip(e) {
                // `x ≤ −b`: the exact value is ≤ 0 (a condition exactly 0, such as the
                // damping of an undamped model, fails: marginal is not stable).
                negative |= *x <= -*b;
                open |= !(*x > *b);
            }
            if negative {
                Verdict::Unstable
            } else if open {
                Verdict::Undecided
            } else {
                Verdict::Stable
            }
        }

        /// The coefficients `a₀ … a_d` of `p(s)` (`c`, lowest first) and bounds on their
        /// rounding errors (`e`: `|c[k] − a_k| ≤ e[k]`, `a_k` the exact value at `p`).
        pub fn characteristic_polynomial(
            p: &[f64; N_PARAMS],
            c: &mut [f64; POLY_DEGREE + 1],
            e: &mut [f64; POLY_DEGREE + 1],
        ) {
            let (mut cc, mut ee) = ([0.0; N_CONDITIONS], [0.0; N_CONDITIONS]);
            stability_raw(p, &mut cc, &mut ee);
            c.copy_from_slice(&cc[..POLY_DEGREE + 1]);
            e.copy_from_slice(&ee[..POLY_DEGREE + 1]);
        }

        /// The Liénard–Chipart conditions (see [`CONDITIONS`]), each `> 0` for stability,
        /// normalised by the sign of the leading coefficient, with bounds on their rounding
        /// errors. Returns `false` (conditions left as computed) when the leading
        /// coefficient is within its bound of zero.
        pub fn stability_conditions(
            p: &[f64; N_PARAMS],
            c: &mut [f64; N_CONDITIONS],
            e: &mut [f64; N_CONDITIONS],
        ) -> bool {
            stability_raw(p, c, e);
            normalise(c, e)
        }

        /// The stability verdict at `p` without eigenvalues: [`Verdict::Stable`] when every
        /// Liénard–Chipart condition exceeds its rounding-error bound, [`Verdict::Unstable`]
        /// when one is at most minus its bound, [`Verdict::Undecided`] otherwise (and when a
        /// value is not finite). Errors: the point is outside the validity region of the
        /// reduction's rank decisions (pivots need no check here: a divisor near zero makes
        /// the bounds infinite, and the verdict undecided).
        pub fn stability(p: &[f64; N_PARAMS]) -> Result<Verdict, Error> {
            stability_valid(p)?;
            Ok(stability_unchecked(p))
        }

        /// The points the batch verdict [`stability_many`] takes at once.
        pub const LANES: usize = 4;

        /// The stability verdicts of many points, as [`stability`] gives them one by one:
        /// `verdicts[k]` for `points[k]`, for the first `n` points, `n` the shorter length
        /// (returned). The first stage runs on [`LANES`] points at a time (packed
        /// arithmetic), so the verdict costs less per point than one call of [`stability`].
        pub fn stability_many(
            points: &[[f64; N_PARAMS]],
            verdicts: &mut [Result<Verdict, Error>],
        ) -> usize {
            let n = points.len().min(verdicts.len());
            let (points, verdicts) = (&points[..n], &mut verdicts[..n]);
            let mut blocks = points.chunks_exact(LANES);
            let mut out = verdicts.chunks_exact_mut(LANES);
            for (block, out) in (&mut blocks).zip(&mut out) {
                let Ok(block) = <&[[f64; N_PARAMS]; LANES]>::try_from(block) else {
                    continue;
                };
                let quick = stability_quick_lanes(block);
                for ((p, q), v) in block.iter().zip(quick).zip(out.iter_mut()) {
                    *v = stability_valid(p).map(|()| match q {
                        Some(q) => q,
                        None => stability_running(p),
                    });
                }
            }
            for (p, v) in blocks.remainder().iter().zip(out.into_remainder()) {
                *v = stability(p);
            }
            n
        }

        /// `Ok` when `p` is inside the validity region of the reduction's rank decisions.
        #[inline(always)]
        fn stability_valid(p: &[f64; N_PARAMS]) -> Result<(), Error> {
            let _ = p;
            #check
            Ok(())
        }

        /// The verdict, the validity region not tested: the cheap stage first, the running
        /// bound where it leaves the point open.
        #[inline(always)]
        fn stability_unchecked(p: &[f64; N_PARAMS]) -> Verdict {
            match stability_quick(p) {
                Some(v) => v,
                None => stability_running(p),
            }
        }

        /// The verdict by the running error bound alone.
        #[inline(never)]
        #[cold]
        fn stability_running(p: &[f64; N_PARAMS]) -> Verdict {
            let (mut c, mut e) = ([0.0; N_CONDITIONS], [0.0; N_CONDITIONS]);
            stability_raw(p, &mut c, &mut e);
            verdict_of(&mut c, &e)
        }

        #quick
    })
}

/// The cheap first stage: `stability_quick_raw` (the conditions and their a-priori bounds,
/// see `render/filter.rs`), the public `stability_conditions_quick`, and `stability_quick`,
/// which decides a point only where every condition is clear of its bound (or one is
/// certainly negative). Without a filter (a function with no magnitude form),
/// `stability_quick` decides nothing. `lead` is the position of the leading coefficient.
fn quick_items(
    ctx: &Ctx,
    lowered: &eom_sym::lower::Lowered,
    lead: usize,
) -> Result<TokenStream, CodegenError> {
    let Some(FilterCode { body, tests, roots }) = render_filter(ctx, lowered, false)? else {
        return Ok(quote! {
            #[inline(always)]
            fn stability_quick(_p: &[f64; N_PARAMS]) -> Option<Verdict> {
                None
            }

            #[inline(always)]
            fn stability_quick_lanes(_p: &[[f64; N_PARAMS]; LANES]) -> [Option<Verdict>; LANES] {
                [None; LANES]
            }
        });
    };
    let lanes = lane_items(ctx, lowered, lead)?;
    let params = param_locals(ctx);
    let stores = roots
        .iter()
        .enumerate()
        .map(|(i, (v, e))| quote!(c[#i] = #v; e[#i] = #e;));
    let tests = if tests.is_empty() {
        quote!(true)
    } else {
        quote!(#(#tests)&*)
    };
    Ok(quote! {
        /// The conditions (as computed, not normalised) and their a-priori bounds; `false`
        /// when a divisor has cancelled too much for the bounds to hold.
        #[inline(always)]
        fn stability_quick_raw(p: &[f64; N_PARAMS], c: &mut [f64; N_CONDITIONS], e: &mut [f64; N_CONDITIONS]) -> bool {
            #(#params)*
            #body
            #(#stores)*
            #tests
        }

        /// The Liénard–Chipart conditions as [`stability_conditions`] computes them (not
        /// normalised), with the cheaper a-priori bounds of the verdict's first stage
        /// (`|c[k] − exact| ≤ e[k]`); `false` when they do not apply at `p` (a divisor
        /// within a factor 2 of cancelling), and then `c` and `e` mean nothing.
        pub fn stability_conditions_quick(
            p: &[f64; N_PARAMS],
            c: &mut [f64; N_CONDITIONS],
            e: &mut [f64; N_CONDITIONS],
        ) -> bool {
            stability_quick_raw(p, c, e)
        }

        /// The verdict of the first stage: `None` where it is not clear.
        #[inline(always)]
        fn stability_quick(p: &[f64; N_PARAMS]) -> Option<Verdict> {
            let (mut c, mut e) = ([0.0; N_CONDITIONS], [0.0; N_CONDITIONS]);
            if !stability_quick_raw(p, &mut c, &mut e) {
                return None;
            }
            quick_verdict(&mut c, &e)
        }

        /// The first stage's verdict from its conditions and bounds: `None` where a bound or
        /// value is not finite, or where [`verdict_of`] is undecided. (The lanes of
        /// [`stability_many`] decide by the same rule without branches: `lane_verdicts`.)
        #[inline(always)]
        fn quick_verdict(c: &mut [f64; N_CONDITIONS], e: &[f64; N_CONDITIONS]) -> Option<Verdict> {
            // Infinite or NaN bounds decide nothing.
            if !c.iter().zip(e).all(|(x, b)| (x.abs() + b) < f64::INFINITY) {
                return None;
            }
            match verdict_of(c, e) {
                Verdict::Undecided => None,
                v => Some(v),
            }
        }

        #lanes
    })
}

/// The first stage over `LANES` points at once: every value a `[f64; LANES]`, every
/// operation a loop over the lanes that the compiler turns into packed instructions.
fn lane_items(
    ctx: &Ctx,
    lowered: &eom_sym::lower::Lowered,
    lead: usize,
) -> Result<TokenStream, CodegenError> {
    let FilterCode { body, tests, roots } =
        render_filter(ctx, lowered, true)?.expect("the scalar filter exists");
    let params = ctx.problem.params.iter().enumerate().map(|(i, p)| {
        let local = format_ident!("{}", p.local);
        quote!(let #local: [f64; LANES] = core::array::from_fn(|l| p[l][#i]);)
    });
    let stores = roots
        .iter()
        .enumerate()
        .map(|(i, (v, e))| quote!(c[#i] = #v; e[#i] = #e;));
    let tests = if tests.is_empty() {
        quote!([true; LANES])
    } else {
        let mut it = tests.into_iter();
        let first = it.next().expect("a test");
        it.fold(first, |acc, t| quote!(l_and(#acc, #t)))
    };
    let has_sincos = lowered
        .insts
        .iter()
        .any(|i| matches!(i.rhs, eom_sym::lower::Rhs::SinCos(_)));
    let sincos = has_sincos.then(|| {
        quote! {
            #[inline(always)]
            fn l_sincos(x: [f64; LANES]) -> ([f64; LANES], [f64; LANES]) {
                let sc: [(f64, f64); LANES] = core::array::from_fn(|l| sincos(x[l]));
                (core::array::from_fn(|l| sc[l].0), core::array::from_fn(|l| sc[l].1))
            }
        }
    });
    Ok(quote! {
        #[inline(always)]
        fn l_add(a: [f64; LANES], b: [f64; LANES]) -> [f64; LANES] {
            core::array::from_fn(|l| a[l] + b[l])
        }
        #[inline(always)]
        fn l_sub(a: [f64; LANES], b: [f64; LANES]) -> [f64; LANES] {
            core::array::from_fn(|l| a[l] - b[l])
        }
        #[inline(always)]
        fn l_mul(a: [f64; LANES], b: [f64; LANES]) -> [f64; LANES] {
            core::array::from_fn(|l| a[l] * b[l])
        }
        #[inline(always)]
        fn l_div(a: [f64; LANES], b: [f64; LANES]) -> [f64; LANES] {
            core::array::from_fn(|l| a[l] / b[l])
        }
        #[inline(always)]
        fn l_abs(a: [f64; LANES]) -> [f64; LANES] {
            core::array::from_fn(|l| a[l].abs())
        }
        #[inline(always)]
        fn l_neg(a: [f64; LANES]) -> [f64; LANES] {
            core::array::from_fn(|l| -a[l])
        }
        #[inline(always)]
        fn l_ge_half(b: [f64; LANES], m: f64) -> [bool; LANES] {
            core::array::from_fn(|l| b[l].abs() >= 0.5 * m)
        }
        /// The block's magnitude of a value: the largest `|x|` of its lanes (a lane whose
        /// value is NaN is left out: its verdict is undecided by its own NaN).
        #[inline(always)]
        fn l_max_abs(a: [f64; LANES]) -> f64 {
            a.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
        }
        /// The smallest `|x|` of the lanes (NaN lanes left out, as in `l_max_abs`).
        #[inline(always)]
        fn l_min_abs(a: [f64; LANES]) -> f64 {
            a.iter().fold(f64::INFINITY, |m: f64, x| m.min(x.abs()))
        }
        #[inline(always)]
        fn l_and(a: [bool; LANES], b: [bool; LANES]) -> [bool; LANES] {
            core::array::from_fn(|l| a[l] & b[l])
        }
        #sincos

        /// The conditions at `LANES` points and their a-priori bounds, one magnitude per
        /// block of points; per point `false` when a divisor has cancelled too much.
        #[inline(always)]
        fn stability_quick_lanes_raw(
            p: &[[f64; N_PARAMS]; LANES],
            c: &mut [[f64; LANES]; N_CONDITIONS],
            e: &mut [[f64; LANES]; N_CONDITIONS],
        ) -> [bool; LANES] {
            #(#params)*
            #body
            #(#stores)*
            #tests
        }

        /// The Liénard–Chipart conditions at [`LANES`] points as [`stability_many`]'s first
        /// stage computes them (`c[k][l]`: condition `k` at `p[l]`, not normalised), with
        /// its a-priori bounds (`|c[k][l] − exact| ≤ e[k][l]`, each from the largest
        /// magnitudes of the block, so never below the bound of
        /// [`stability_conditions_quick`] at the same point); per point `false` when they
        /// do not apply there.
        pub fn stability_conditions_quick_lanes(
            p: &[[f64; N_PARAMS]; LANES],
            c: &mut [[f64; LANES]; N_CONDITIONS],
            e: &mut [[f64; LANES]; N_CONDITIONS],
        ) -> [bool; LANES] {
            stability_quick_lanes_raw(p, c, e)
        }

        /// The first stage at `LANES` points.
        #[inline(never)]
        fn stability_quick_lanes(p: &[[f64; N_PARAMS]; LANES]) -> [Option<Verdict>; LANES] {
            let mut c = [[0.0; LANES]; N_CONDITIONS];
            let mut e = [[0.0; LANES]; N_CONDITIONS];
            let ok = stability_quick_lanes_raw(p, &mut c, &mut e);
            lane_verdicts(ok, &c, &e)
        }

        /// The first stage's verdicts of a block (`c[k][l]`: condition `k` at point `l`), by
        /// the rule of `quick_verdict`: `None` where the bounds do not apply (`ok` false), a
        /// bound or value is not finite, the sign of the leading coefficient is not clear,
        /// or no condition is certainly negative and one is within its bound of zero.
        /// Without a branch on the values: the verdicts of a sweep's points are as random
        /// as the points, and a mispredicted branch per point costs more than the
        /// comparisons (one point at a time, where the chain of one point is the time, the
        /// branches are cheaper: `quick_verdict`). A function of its own: inlined into the
        /// block's arithmetic, the comparisons change how the compiler packs the whole
        /// block (slower).
        #[inline(never)]
        fn lane_verdicts(
            ok: [bool; LANES],
            c: &[[f64; LANES]; N_CONDITIONS],
            e: &[[f64; LANES]; N_CONDITIONS],
        ) -> [Option<Verdict>; LANES] {
            let lead = c[#lead];
            let mut unclear: [u32; LANES] = core::array::from_fn(|l| {
                u32::from(!ok[l]) | u32::from(!(lead[l].abs() > e[#lead][l]))
            });
            // Normalised by the sign of `a_d` (exact: a product with ±1).
            let sign: [f64; LANES] = core::array::from_fn(|l| 1.0f64.copysign(lead[l]));
            let (mut negative, mut positive) = ([0u32; LANES], [0u32; LANES]);
            for k in 0..N_CONDITIONS {
                let odd = CONDITION_DEGREES[k] % 2 == 1;
                for l in 0..LANES {
                    let x = if odd { c[k][l] * sign[l] } else { c[k][l] };
                    let b = e[k][l];
                    unclear[l] |= u32::from(!((x.abs() + b) < f64::INFINITY));
                    negative[l] |= u32::from(x <= -b);
                    positive[l] += u32::from(x > b);
                }
            }
            const OUT: [Option<Verdict>; 3] = [None, Some(Verdict::Stable), Some(Verdict::Unstable)];
            core::array::from_fn(|l| {
                let stable = (negative[l] == 0) & (positive[l] == N_CONDITIONS as u32);
                let code = (1 - unclear[l]) * (2 * negative[l] + u32::from(stable));
                OUT[code as usize]
            })
        }
    })
}

/// The parameters' locals.
fn param_locals(ctx: &Ctx) -> Vec<TokenStream> {
    ctx.problem
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let local = format_ident!("{}", p.local);
            quote!(let #local: f64 = p[#i];)
        })
        .collect()
}

/// The body of `stability_raw`: the parameters' locals, the bounded code, the stores.
fn raw_body(ctx: &Ctx, lowered: &eom_sym::lower::Lowered) -> Result<TokenStream, CodegenError> {
    let BoundedCode { body, roots } = render_bounded(ctx, lowered)?;
    let params = param_locals(ctx);
    let stores = roots
        .iter()
        .enumerate()
        .map(|(i, (v, e))| quote!(c[#i] = #v; e[#i] = #e;));
    Ok(quote! {
        #(#params)*
        #body
        #(#stores)*
    })
}
