//! Steady-state gains `G(0) = D − C A⁻¹ B`, with integrating outputs identified.
//!
//! # Method
//!
//! A is balanced (diagonal similarity) and its rank decided ([`RankTolerance`], scale aware,
//! reported). A clearly regular A is certified without its singular values, from the LU
//! factors: `σ_min ≥ 1/‖A⁻¹‖` and `σ_max ≤ ‖A‖` with `‖M‖ = min(‖M‖_F, √(‖M‖₁‖M‖_∞))`, an
//! upper bound of the spectral norm, and the lower bound must clear the threshold (taken at
//! the upper bound) by [`CERTIFICATE_MARGIN`]; the bounds are reported in
//! [`SteadyStateGain::certificate`]. Otherwise the SVD decides. If A is nonsingular,
//! `G(0) = D − C A⁻¹ B` by LU and every pair is [`Gain::Finite`]; the condition number of A
//! is reported (an upper bound when certified).
//!
//! If A is singular (rigid-body modes, integrators from position/heading outputs) the state
//! space is split into the invariant subspace of the zero eigenvalue and its complement:
//!
//! * `V₀` = orthonormal basis of `ker(A^ν)` (ν the index of the zero eigenvalue), built by
//!   the ascending chain `ker A ⊂ ker A² ⊂ …`, each step an SVD nullspace;
//! * `V₁` = orthonormal basis of `range(A^ν)`, the orthogonal complement of the left chain
//!   `ker (Aᵀ)^ν`;
//! * with `T = [V₀ V₁]`, `T⁻¹ A T = diag(N, A₁)`, N nilpotent (q × q), A₁ nonsingular.
//!
//! Then `G(s) = D + C V₁ (sI − A₁)⁻¹ W₁ B + Σ_{k<q} C V₀ Nᵏ W₀ B / s^{k+1}` (W = T⁻¹). The
//! pair (i, j) has a pole at s = 0 — its output sees an unbounded response to a constant
//! input — exactly when some `Mₖ = C V₀ Nᵏ W₀ B` has a nonzero (i, j) entry, i.e. when the
//! input reaches a zero-eigenvalue mode that the output observes. Such pairs are reported
//! as [`Gain::Integrating`] with the pole order r (the step response grows like `t^r`) and
//! the leading coefficient `lim s^r G(s) = M_{r−1}` (for r = 1: the slope of the ramp per
//! unit step). The remaining pairs get the exact limit `G(0) = D − C V₁ A₁⁻¹ W₁ B`. A
//! coefficient counts as nonzero when `|Mₖ(i,j)| > 10·n·ε·‖cᵢ‖‖bⱼ‖‖W₀‖‖A‖ᵏ` (the size of its
//! rounding error), in balanced coordinates.
//!
//! EoM.jl replaced the gain by `Re G(jω)` one decade below the plot range whenever
//! `cond(A) ≥ 1e6`, which is meaningless for integrating outputs and
//! silently approximate for the others.

use faer::MatRef;
use nalgebra::DMatrix;
use std::borrow::Cow;

use crate::linalg::{
    Rank, RankTolerance, balance_in_place, decide, faer_view, nullspace, singular_values,
};
use crate::statespace::StateSpace;
use crate::{AmbiguousRankError, Bound, NumError, NumWarning, OptionError, SingularError};

/// The steady-state gain of one input/output pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Gain {
    /// A finite limit `G_ij(0)`.
    Finite(f64),
    /// The output integrates a constant input: `G_ij(s)` has a pole of order `order` at 0, and
    /// a unit step gives `y(t) ≈ coefficient · t^order / order!` for large t.
    Integrating {
        /// Order of the pole at s = 0 (1 = ramp, 2 = parabola, …).
        order: usize,
        /// `lim_{s→0} s^order G_ij(s)`.
        coefficient: f64,
    },
}

impl Gain {
    /// The finite value, if any.
    pub fn finite(&self) -> Option<f64> {
        match *self {
            Gain::Finite(v) => Some(v),
            Gain::Integrating { .. } => None,
        }
    }
}

/// Options of [`steady_state_gain_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GainOptions {
    /// Tolerance of the rank decisions on A (default [`RankTolerance::Default`]; relative
    /// to ‖A‖ for every step of the chain).
    pub rank_tol: RankTolerance,
    /// Condition numbers above this produce a warning (default 1e8).
    pub warn_condition: f64,
    /// The number of zero eigenvalues the model's structure proves (default 0: unknown), e.g.
    /// from the elimination path at the same point (`Linearization::structural_zeros` of
    /// eom-model). A basis that hides them in rounding (the robust path's) can make the rank
    /// decision on A call a defective zero pair, split into `±δ`, regular: see
    /// [`steady_state_gain_with`].
    pub structural_zeros: usize,
}

impl Default for GainOptions {
    fn default() -> Self {
        GainOptions {
            rank_tol: RankTolerance::Default,
            warn_condition: 1e8,
            structural_zeros: 0,
        }
    }
}

/// Steady-state gains of all pairs, with the decisions behind them.
#[derive(Clone, Debug, PartialEq)]
pub struct SteadyStateGain {
    /// Gains, outputs × inputs.
    pub gains: DMatrix<Gain>,
    /// Rank decision on (balanced) A.
    pub a_rank: Rank,
    /// Dimension q of the zero-eigenvalue invariant subspace (algebraic multiplicity).
    pub zero_dimension: usize,
    /// Index ν of the zero eigenvalue (size of its largest Jordan block; 0 if A is regular).
    pub index: usize,
    /// Condition number of A (regular case) or of A₁ (the part without the zero modes).
    pub condition: f64,
    /// Condition number of `T = [V₀ V₁]`: how well the zero modes separate from the others
    /// (1 when A is regular).
    pub separation_condition: f64,
    /// Every nullspace decision of the chains (right then left), with gaps.
    pub decisions: Vec<Rank>,
    /// Warnings (near-tolerance decisions, ill-conditioning).
    pub warnings: Vec<NumWarning>,
    /// When A was decided regular by the certificate of its inverse instead of by its
    /// singular values (see the module documentation): the bounds. Then
    /// [`SteadyStateGain::a_rank`] has no singular values (its margin is a lower bound) and
    /// [`SteadyStateGain::condition`] is the upper bound `‖A‖ ‖A⁻¹‖` of [`RegularBounds`].
    pub certificate: Option<RegularBounds>,
    /// The error estimate of each finite gain (outputs × inputs; 0 for an integrating pair):
    /// the first-order effect of a backward-stable LU solve and of rounding the products,
    /// `10·k·ε·(|yᵢ|ᵀ|M||xⱼ| + |cᵢ|ᵀ|xⱼ|) + ε|Dᵢⱼ|` with `M` the (balanced) matrix solved
    /// (A, or A₁ without the zero modes) of order k, `xⱼ = M⁻¹bⱼ`, `yᵢ = M⁻ᵀcᵢ` (Skeel's
    /// componentwise bound). A gain within it has no known sign and prints as 0.
    pub errors: DMatrix<f64>,
}

impl SteadyStateGain {
    /// The gain of one pair. Panics if out of range.
    pub fn get(&self, output: usize, input: usize) -> Gain {
        self.gains[(output, input)]
    }

    /// Whether any pair integrates.
    pub fn has_integrating(&self) -> bool {
        self.gains
            .iter()
            .any(|g| matches!(g, Gain::Integrating { .. }))
    }
}

/// Steady-state gains with default options (see the module docs).
///
/// Errors: those of [`StateSpace::validate`], [`NumError::NoConvergence`],
/// [`NumError::Singular`] when the zero-eigenvalue subspace cannot be separated (left and
/// right chains disagree).
pub fn steady_state_gain(ss: &StateSpace<f64>) -> Result<SteadyStateGain, NumError> {
    steady_state_gain_with(ss, &GainOptions::default())
}

/// [`steady_state_gain`] with options.
///
/// When the rank decision on A lies within [`AMBIGUITY_FACTOR`] of its threshold, or finds
/// fewer zero eigenvalues than [`GainOptions::structural_zeros`], the gains are computed
/// again with every threshold raised by that factor. Equal gains (to 1e-9 of the largest):
/// the first result, unless neither decision finds the zero eigenvalues the structure proves
/// ([`NumError::AmbiguousRank`]). Different gains, where the raised threshold finds them:
/// that result, with a warning (a defective zero pair split by
/// rounding into `±δ` is not a pair of genuine modes, and `C A⁻¹ B` would amplify the
/// rounding in their couplings by `1/δ²`). Otherwise [`NumError::AmbiguousRank`].
///
/// Errors: as [`steady_state_gain`], plus [`NumError::InvalidOption`] for a bad tolerance
/// and [`NumError::AmbiguousRank`].
pub fn steady_state_gain_with(
    ss: &StateSpace<f64>,
    opts: &GainOptions,
) -> Result<SteadyStateGain, NumError> {
    ss.validate()?;
    opts.rank_tol.validate()?;
    if opts.warn_condition.is_nan() || opts.warn_condition <= 0.0 {
        return Err(NumError::InvalidOption(OptionError::Value {
            option: "GainOptions::warn_condition",
            value: opts.warn_condition,
            must: Bound::Positive,
        }));
    }
    let ss = &structural(ss);
    let first = gain_at_tolerance(ss, opts, 1.0)?;
    let fragile = first.a_rank.is_near_tolerance(AMBIGUITY_FACTOR);
    let too_few = first.zero_dimension < opts.structural_zeros;
    if !fragile && !too_few {
        return Ok(first);
    }
    // The decision on A is fragile, or contradicts the structure: decide again with the
    // threshold raised by the factor that counts as near, and compare.
    let second = gain_at_tolerance(ss, opts, AMBIGUITY_FACTOR)?;
    if second.zero_dimension < opts.structural_zeros {
        // Both decisions contradict the structure: A's rounding hides zero eigenvalues that
        // exist, and `C A⁻¹ B` would amplify that rounding into the gains.
        return Err(NumError::AmbiguousRank(
            AmbiguousRankError::StructuralZeros {
                structural: opts.structural_zeros,
                n: ss.states(),
                first: first.zero_dimension,
                second: second.zero_dimension,
            },
        ));
    }
    if same_gains(&first.gains, &second.gains) {
        return Ok(first);
    }
    if too_few && second.zero_dimension >= opts.structural_zeros {
        let mut out = second;
        out.warnings.push(NumWarning::GainZerosRedecided {
            found: first.zero_dimension,
            structural: opts.structural_zeros,
            factor: AMBIGUITY_FACTOR,
            redecided: out.zero_dimension,
        });
        return Ok(out);
    }
    Err(NumError::AmbiguousRank(AmbiguousRankError::Gains {
        n: ss.states(),
        margin: first.a_rank.margin,
        first: first.zero_dimension,
        second: second.zero_dimension,
        first_gains: first.gains.iter().copied().collect(),
        second_gains: second.gains.iter().copied().collect(),
    }))
}

/// A rank decision within this factor of its threshold is checked by deciding again at a
/// threshold this much larger (the factor at which decisions are reported as near).
pub const AMBIGUITY_FACTOR: f64 = 100.0;

/// Relative agreement of two sets of finite gains (to the largest of them) for the rank
/// decision behind them not to matter.
const SAME_GAIN_REL: f64 = 1e-9;

/// Whether two gain matrices agree: the same kinds, integrating orders, and finite values
/// and coefficients within [`SAME_GAIN_REL`] of the largest of their kind.
fn same_gains(x: &DMatrix<Gain>, y: &DMatrix<Gain>) -> bool {
    let scale = x.iter().chain(y.iter()).fold(0.0f64, |m, g| match g {
        Gain::Finite(v) => m.max(v.abs()),
        Gain::Integrating { .. } => m,
    });
    let close = |a: f64, b: f64, s: f64| (a - b).abs() <= SAME_GAIN_REL * s;
    x.iter().zip(y.iter()).all(|(a, b)| match (a, b) {
        (Gain::Finite(a), Gain::Finite(b)) => close(*a, *b, scale),
        (
            Gain::Integrating {
                order: o1,
                coefficient: c1,
            },
            Gain::Integrating {
                order: o2,
                coefficient: c2,
            },
        ) => o1 == o2 && close(*c1, *c2, c1.abs().max(c2.abs())),
        _ => false,
    })
}

/// The gains in one line, for messages.
pub(crate) fn describe(g: &[Gain]) -> String {
    let items: Vec<String> = g
        .iter()
        .map(|x| match x {
            Gain::Finite(v) => format!("{v:.6e}"),
            Gain::Integrating { order, .. } => format!("integrating (order {order})"),
        })
        .collect();
    format!("[{}]", items.join(", "))
}

/// The gains with every rank threshold multiplied by `factor`.
fn gain_at_tolerance(
    ss: &StateSpace<f64>,
    opts: &GainOptions,
    factor: f64,
) -> Result<SteadyStateGain, NumError> {
    let (n, m, p) = (ss.states(), ss.inputs(), ss.outputs());
    let (a, b, c) = balanced(ss);
    let mut warnings = Vec::new();
    if let Some(cert) = certify_regular(&a, &opts.rank_tol, factor)? {
        return regular(ss, (&a, &b, &c), cert, opts, warnings);
    }
    let sv = singular_values(&a)?;
    let smax = sv.first().copied().unwrap_or(0.0);
    let thr = factor * opts.rank_tol.threshold(smax, n, n);
    let a_rank = decide(sv.clone(), thr);
    if a_rank.is_near_tolerance(100.0) {
        warnings.push(NumWarning::GainFragileRank {
            rank: a_rank.rank,
            margin: a_rank.margin,
            threshold: thr,
        });
    }

    if a_rank.rank == n {
        let condition = if n == 0 { 1.0 } else { sv[0] / sv[n - 1] };
        let cert = Regular {
            lu: faer_view(&a).partial_piv_lu(),
            a_rank,
            condition,
            bounds: None,
        };
        return regular(ss, (&a, &b, &c), cert, opts, warnings);
    }

    let ZeroSplit {
        v0,
        v1,
        w,
        index: nu,
        decisions,
        separation_condition,
    } = zero_split(&a, thr, opts, &mut warnings)?;
    let q = v0.ncols();
    let w0 = w.rows(0, q);
    let w1 = w.rows(q, n - q);
    let nmat = w0 * &a * &v0;
    let a1 = w1 * &a * &v1;
    let bz = w0 * &b;
    let cz = &c * &v0;
    let b1 = w1 * &b;
    let c1 = &c * &v1;

    // Finite part.
    let (fin, fin_errors, condition, a1_min) =
        finite_part(&a1, &b1, &c1, &ss.d, opts, &mut warnings)?;

    // Markov-like coefficients Mₖ = C V₀ Nᵏ W₀ B and their rounding-level tolerances.
    let w0n = singular_values(&w0.into_owned())?
        .first()
        .copied()
        .unwrap_or(0.0);
    // The coefficients' rounding level, relative to ‖A‖ as the rank threshold is (10·n·ε at
    // the default tolerance): a threshold raised to count a split zero pair as zero also
    // counts its couplings to the outputs, of the same origin, as zero.
    let relative = if smax > 0.0 {
        thr / smax
    } else {
        10.0 * n as f64 * f64::EPSILON
    };
    // The split's basis V₀ is known to the backward error over the separation of the zero
    // modes from the others (σ_min of A₁): so are the coefficients.
    let separation = if a1_min > 0.0 && a1_min < smax {
        smax / a1_min
    } else {
        1.0
    };
    let scale = relative.max(10.0 * n as f64 * f64::EPSILON) * separation * w0n;
    let (order, coef) = integrating_orders(
        &Zeros {
            nmat: &nmat,
            bz: &bz,
            cz: &cz,
            q,
        },
        &b,
        &c,
        scale,
        smax,
    );
    let gains = DMatrix::from_fn(p, m, |i, j| {
        if order[(i, j)] > 0 {
            Gain::Integrating {
                order: order[(i, j)],
                coefficient: coef[(i, j)],
            }
        } else {
            Gain::Finite(fin[(i, j)])
        }
    });
    Ok(SteadyStateGain {
        gains,
        a_rank,
        zero_dimension: q,
        index: nu,
        condition,
        separation_condition,
        decisions,
        warnings,
        certificate: None,
        errors: DMatrix::from_fn(p, m, |i, j| {
            if order[(i, j)] > 0 {
                0.0
            } else {
                fin_errors[(i, j)]
            }
        }),
    })
}

/// The zero/nonzero eigenvalue split of A: the right basis `[V₀ V₁]` (V₀ spans the
/// zero-eigenvalue chain ker A^ν, V₁ = range(A^ν)), its inverse `w`, and the decisions made.
struct ZeroSplit {
    v0: DMatrix<f64>,
    v1: DMatrix<f64>,
    w: DMatrix<f64>,
    index: usize,
    decisions: Vec<Rank>,
    separation_condition: f64,
}

/// Splits A at rank threshold `thr` by its zero-eigenvalue chains (right ker A^k, left
/// ker (Aᵀ)^k), which must agree; decisions near the threshold and a poor separation are
/// warned about.
fn zero_split(
    a: &DMatrix<f64>,
    thr: f64,
    opts: &GainOptions,
    warnings: &mut Vec<NumWarning>,
) -> Result<ZeroSplit, NumError> {
    let n = a.nrows();
    let mut decisions = Vec::new();
    let (v0, nu) = zero_chain(a, thr, &mut decisions)?;
    let (l0, nu_l) = zero_chain(&a.transpose(), thr, &mut decisions)?;
    let q = v0.ncols();
    for d in &decisions {
        if d.is_near_tolerance(100.0) {
            warnings.push(NumWarning::GainFragileZeroChain {
                rank: d.rank,
                margin: d.margin,
            });
        }
    }
    if l0.ncols() != q || nu_l != nu {
        return Err(NumError::Singular(SingularError::ZeroSubspace {
            n,
            right: q,
            right_index: nu,
            left: l0.ncols(),
            left_index: nu_l,
        }));
    }
    // V₁ = (ker (Aᵀ)^ν)⊥ = range(A^ν).
    let v1 = if q == 0 {
        DMatrix::identity(n, n)
    } else {
        nullspace(&l0.transpose(), RankTolerance::Default)?.basis
    };
    let mut t = DMatrix::<f64>::zeros(n, n);
    t.columns_mut(0, q).copy_from(&v0);
    t.columns_mut(q, n - q).copy_from(&v1);
    let st = singular_values(&t)?;
    let separation_condition = st[0] / st[n - 1];
    if !separation_condition.is_finite() || separation_condition > opts.warn_condition {
        warnings.push(NumWarning::GainZeroModesMixed {
            condition: separation_condition,
        });
    }
    let w = t
        .clone()
        .lu()
        .try_inverse()
        .ok_or(NumError::Singular(SingularError::SplitBasis { n }))?;
    Ok(ZeroSplit {
        v0,
        v1,
        w,
        index: nu,
        decisions,
        separation_condition,
    })
}

/// The system in the coordinates where the zero eigenvalues its structure proves are exact
/// ([`crate::deflate::structural_coordinates`]): a pair of states on which the equations
/// depend only through their difference has two columns that are negatives of each other to
/// rounding, and left so, A is regular with a condition number of 1/ε and its "inverse"
/// amplifies that rounding into the gains (the bicycle's heading pair gave gains of 0 instead
/// of 5e-4). The gains are invariant under the change of coordinates.
fn structural(ss: &StateSpace<f64>) -> Cow<'_, StateSpace<f64>> {
    let t = crate::deflate::structural_coordinates(&ss.a, &ss.b, &ss.c);
    if t.zeros == 0 {
        return Cow::Borrowed(ss);
    }
    // The gains read A, B, C and D only: no physical map or names to carry over.
    Cow::Owned(StateSpace {
        a: t.a,
        b: t.b,
        c: t.c,
        d: ss.d.clone(),
        phys: DMatrix::zeros(0, ss.states()),
        names: Default::default(),
    })
}

/// The balanced system: Ã = D⁻¹ A D, B̃ = D⁻¹ B, C̃ = C D, with D from [`balance_in_place`]
/// — or A, B, C themselves when the scaling would spread beyond 1/ε.
fn balanced(ss: &StateSpace<f64>) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let (n, m, p) = (ss.states(), ss.inputs(), ss.outputs());
    let mut av = ss.a.as_slice().to_vec();
    let mut sc = vec![1.0; n];
    balance_in_place(&mut av, n, &mut sc);
    let spread =
        sc.iter().fold(1.0f64, |m, s| m.max(*s)) / sc.iter().fold(1.0f64, |m, s| m.min(*s));
    if spread > 1.0 / f64::EPSILON {
        // Scalings beyond 1/ε push the couplings of a nearly singular A's zero modes below
        // every threshold (a spring of 1e-100 N/m gave gains of 0 instead of integrating):
        // decide in the model's own coordinates instead.
        av.copy_from_slice(ss.a.as_slice());
        sc.iter_mut().for_each(|s| *s = 1.0);
    }
    let a = DMatrix::from_vec(n, n, av);
    let b = DMatrix::from_fn(n, m, |i, j| ss.b[(i, j)] / sc[i]);
    let c = DMatrix::from_fn(p, n, |i, j| ss.c[(i, j)] * sc[j]);
    (a, b, c)
}

/// The gain of the nonzero modes, `D − C₁ A₁⁻¹ B₁`, its error estimates
/// ([`SteadyStateGain::errors`]), the condition number of `A₁` and its smallest singular
/// value.
fn finite_part(
    a1: &DMatrix<f64>,
    b1: &DMatrix<f64>,
    c1: &DMatrix<f64>,
    d: &DMatrix<f64>,
    opts: &GainOptions,
    warnings: &mut Vec<NumWarning>,
) -> Result<(DMatrix<f64>, DMatrix<f64>, f64, f64), NumError> {
    let s1 = singular_values(a1)?;
    let smallest = s1.last().copied().unwrap_or(0.0);
    let condition = if s1.is_empty() {
        1.0
    } else if s1[s1.len() - 1] > 0.0 {
        s1[0] / s1[s1.len() - 1]
    } else {
        f64::INFINITY
    };
    if condition > opts.warn_condition {
        warnings.push(NumWarning::GainReducedIllConditioned { condition });
    }
    let (fin, errors) = if a1.nrows() == 0 {
        (d.clone(), d.map(|v| f64::EPSILON * v.abs()))
    } else {
        let singular = || NumError::Singular(SingularError::NonzeroModes { n: a1.nrows() });
        let lu = a1.clone().lu();
        let x = lu.solve(b1).ok_or_else(singular)?;
        let y = a1
            .transpose()
            .lu()
            .solve(&c1.transpose())
            .ok_or_else(singular)?;
        let errors = solve_errors(a1, c1, d, &x, &y);
        (d - c1 * x, errors)
    };
    Ok((fin, errors, condition, smallest))
}

/// [`SteadyStateGain::errors`] of `D − C X` with `X = M⁻¹ B` and `Y = M⁻ᵀ Cᵀ` (columns
/// `xⱼ`, `yᵢ`): `10·k·ε·(|yᵢ|ᵀ|M||xⱼ| + |cᵢ|ᵀ|xⱼ|) + ε|Dᵢⱼ|`.
fn solve_errors(
    m: &DMatrix<f64>,
    c: &DMatrix<f64>,
    d: &DMatrix<f64>,
    x: &DMatrix<f64>,
    y: &DMatrix<f64>,
) -> DMatrix<f64> {
    let k = m.nrows() as f64;
    let (mabs, xabs, yabs, cabs) = (m.abs(), x.abs(), y.abs(), c.abs());
    let solve = yabs.transpose() * mabs * &xabs;
    let product = cabs * &xabs;
    DMatrix::from_fn(d.nrows(), d.ncols(), |i, j| {
        10.0 * k * f64::EPSILON * (solve[(i, j)] + product[(i, j)]) + f64::EPSILON * d[(i, j)].abs()
    })
}

/// The zero-eigenvalue chain of `mat`: a basis of `ker mat^ν` and the index ν, each nullspace
/// decision recorded.
fn zero_chain(
    mat: &DMatrix<f64>,
    thr: f64,
    decisions: &mut Vec<Rank>,
) -> Result<(DMatrix<f64>, usize), NumError> {
    let n = mat.nrows();
    let mut k = DMatrix::<f64>::zeros(n, 0);
    let mut steps = 0;
    loop {
        // {x : M x ∈ span K} = ker((I − K Kᵀ) M).
        let proj = if k.ncols() == 0 {
            mat.clone()
        } else {
            mat - &k * (k.transpose() * mat)
        };
        let ns = nullspace(&proj, RankTolerance::Absolute(thr))?;
        decisions.push(ns.decision());
        if ns.basis.ncols() <= k.ncols() || steps >= n {
            return Ok((k, steps));
        }
        k = ns.basis;
        steps += 1;
    }
}

/// The zero-mode part of a singular A: `N = W₀ A V₀` (q × q), `W₀ B` and `C V₀`.
struct Zeros<'a> {
    nmat: &'a DMatrix<f64>,
    bz: &'a DMatrix<f64>,
    cz: &'a DMatrix<f64>,
    q: usize,
}

/// For each output/input pair, the order of its pole at s = 0 (0: none) and its coefficient:
/// the first Markov-like coefficient `Mₖ = C V₀ Nᵏ W₀ B` above its rounding level
/// (`scale · σ_max(A)ᵏ · ‖cᵢ‖ · ‖bⱼ‖`).
fn integrating_orders(
    z: &Zeros<'_>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
    scale: f64,
    smax: f64,
) -> (DMatrix<usize>, DMatrix<f64>) {
    let (p, m) = (c.nrows(), b.ncols());
    let cn: Vec<f64> = (0..p).map(|i| c.row(i).norm()).collect();
    let bn: Vec<f64> = (0..m).map(|j| b.column(j).norm()).collect();
    let mut order = DMatrix::<usize>::zeros(p, m);
    let mut coef = DMatrix::<f64>::zeros(p, m);
    let mut nk_bz = z.bz.clone(); // Nᵏ W₀ B
    for k in 0..z.q {
        let mk = z.cz * &nk_bz;
        let scale_k = scale * smax.powi(k as i32);
        for i in 0..p {
            for j in 0..m {
                if mk[(i, j)].abs() > scale_k * cn[i] * bn[j] {
                    order[(i, j)] = k + 1;
                    coef[(i, j)] = mk[(i, j)];
                }
            }
        }
        nk_bz = z.nmat * nk_bz;
    }
    (order, coef)
}

/// Margin by which the certificate of [`certify_regular`] must clear the rank threshold.
pub const CERTIFICATE_MARGIN: f64 = 1e4;

/// A regular A, decided by SVD or by the certificate, with its LU factors.
struct Regular {
    lu: faer::linalg::solvers::PartialPivLu<f64>,
    a_rank: Rank,
    condition: f64,
    bounds: Option<RegularBounds>,
}

/// The certificate of [`certify_regular`]: `σ_min(A) ≥ 1/‖A⁻¹‖` and `σ_max(A) ≤ ‖A‖`
/// (balanced A) with the bound [`spectral_norm_bound`] of the spectral norm, cheaper than the
/// singular values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegularBounds {
    /// `1/‖A⁻¹‖`, a lower bound of the smallest singular value.
    pub sigma_min_lower: f64,
    /// `‖A‖`, an upper bound of the largest singular value.
    pub sigma_max_upper: f64,
}

/// An upper bound of the spectral norm `‖M‖₂ = σ_max(M)` in O(n²): the smaller of the
/// Frobenius norm and `√(‖M‖₁ ‖M‖_∞)` (the largest column and row sums of |M|; `‖M‖₂² ≤
/// ‖M‖₁ ‖M‖_∞`, Golub & Van Loan, *Matrix Computations*, §2.3). The Frobenius norm
/// overestimates σ_max by up to √n when many singular values are alike (a long chain of
/// springs: ‖A‖_F ≈ 34 σ_max at 2000 states); the second bound does not.
pub fn spectral_norm_bound(m: MatRef<'_, f64>) -> f64 {
    let (r, c) = (m.nrows(), m.ncols());
    let big = (0..c).fold(0.0f64, |b, j| (0..r).fold(b, |b, i| b.max(m[(i, j)].abs())));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    let mut rows = vec![0.0f64; r];
    let (mut one, mut sum2) = (0.0f64, 0.0f64);
    for j in 0..c {
        let mut col = 0.0;
        for (i, row) in rows.iter_mut().enumerate() {
            let v = m[(i, j)].abs();
            col += v;
            *row += v;
            sum2 += (v / big) * (v / big);
        }
        one = one.max(col);
    }
    let inf = rows.iter().fold(0.0f64, |a, &v| a.max(v));
    // √(‖M‖₁‖M‖_∞) without overflow of the product.
    (big * sum2.sqrt()).min(one.sqrt() * inf.sqrt())
}

/// Decides that A has full rank without its singular values when the decision is clear:
/// with the inverse from an LU factorisation (partial pivoting), `1/‖A⁻¹‖ ≤ σ_min` and
/// `‖A‖ ≥ σ_max` ([`spectral_norm_bound`]); the rank threshold is evaluated at the upper bound of σ_max (so it is at
/// least the SVD's), and A is certified regular when the lower bound of σ_min exceeds it by
/// [`CERTIFICATE_MARGIN`] (far more than the relative error of the computed inverse, about
/// `n ε κ(A)`, can change). `None` (then the SVD decides) when it does not, or when the LU
/// breaks down. O(n³) in matrix products, a fraction of an SVD's cost.
fn certify_regular(
    a: &DMatrix<f64>,
    tol: &RankTolerance,
    factor: f64,
) -> Result<Option<Regular>, NumError> {
    let n = a.nrows();
    if n == 0 {
        return Ok(None);
    }
    crate::budget::check("the inverse of A (steady-state gains)", 3 * 8 * n * n)?;
    let lu = faer_view(a).partial_piv_lu();
    let inv = faer::linalg::solvers::DenseSolveCore::inverse(&lu);
    let inv_norm = spectral_norm_bound(inv.as_ref());
    let a_norm = spectral_norm_bound(faer_view(a));
    if !(inv_norm.is_finite() && inv_norm > 0.0) {
        return Ok(None);
    }
    let bounds = RegularBounds {
        sigma_min_lower: 1.0 / inv_norm,
        sigma_max_upper: a_norm,
    };
    let thr = factor * tol.threshold(a_norm, n, n);
    if bounds.sigma_min_lower <= CERTIFICATE_MARGIN * thr {
        return Ok(None);
    }
    Ok(Some(Regular {
        lu,
        a_rank: Rank {
            rank: n,
            singular_values: Vec::new(),
            threshold: thr,
            gap: f64::INFINITY,
            margin: bounds.sigma_min_lower / thr,
        },
        condition: a_norm * inv_norm,
        bounds: Some(bounds),
    }))
}

/// The regular case: `G(0) = D − C A⁻¹ B` with the LU factors.
fn regular(
    ss: &StateSpace<f64>,
    (a, b, c): (&DMatrix<f64>, &DMatrix<f64>, &DMatrix<f64>),
    reg: Regular,
    opts: &GainOptions,
    mut warnings: Vec<NumWarning>,
) -> Result<SteadyStateGain, NumError> {
    let n = ss.states();
    if reg.condition > opts.warn_condition {
        warnings.push(NumWarning::GainIllConditioned {
            condition: reg.condition,
            bound: reg.bounds.is_some(),
        });
    }
    let (g, errors) = if n == 0 {
        (ss.d.clone(), ss.d.map(|v| f64::EPSILON * v.abs()))
    } else {
        use faer::linalg::solvers::Solve;
        let x = reg.lu.solve(faer_view(b));
        let x = DMatrix::from_fn(n, b.ncols(), |i, j| x[(i, j)]);
        let ct = c.transpose();
        let y = reg.lu.solve_transpose(faer_view(&ct));
        let y = DMatrix::from_fn(n, c.nrows(), |i, j| y[(i, j)]);
        if x.iter().chain(y.iter()).any(|v| !v.is_finite()) {
            return Err(NumError::Singular(SingularError::LuFailed {
                matrix: "A",
                n,
                passed: "passed the rank test",
                failed: "solve is not finite",
            }));
        }
        let errors = solve_errors(a, c, &ss.d, &x, &y);
        (&ss.d - c * x, errors)
    };
    Ok(SteadyStateGain {
        gains: g.map(Gain::Finite),
        a_rank: reg.a_rank,
        zero_dimension: 0,
        index: 0,
        condition: reg.condition,
        separation_condition: 1.0,
        decisions: Vec::new(),
        warnings,
        certificate: reg.bounds,
        errors,
    })
}
