//! Descriptor models `E ẋ = A x + B u`: reduction to a standard state space and finite
//! generalized eigenvalues.
//!
//! # Reduction (index-1 pencils)
//!
//! [`descriptor_to_state_space`] follows the descriptor reduction of the EoM software
//! (Minaker et al.), with scale-aware decisions; one function per step:
//!
//! 0. Rows and columns of E at the rounding level of ‖E‖ are set to exactly zero.
//! 1. The pencil is equilibrated by exact power-of-two row and column scalings
//!    `R (sE − A) S` (rows then columns of E, as [`crate::linalg::equilibrate`]; rows and
//!    columns where E is zero are scaled by A), so that the rank of E does not depend on
//!    units. This leaves the transfer function and the eigenvalues unchanged.
//! 2. `E = U Σ Vᵀ` (SVD); the rank r of E is decided with a [`RankTolerance`] (default
//!    `10·n·ε·σ_max`, not EoM.jl's ULP-tight `n·ulp(σ_max)`), and the decision and its gap are
//!    returned in the [`DescriptorReport`]. Exactly zero rows and columns of E (input states,
//!    massless coordinates) are split off before the SVD, so that their part of the
//!    nullspace — and of A22 below — is exact rather than rotated by rounding.
//! 3. If E has full rank, `ẋ = E⁻¹A x + E⁻¹B u` (LU) in the original coordinates.
//!    Otherwise, in the coordinates `x = V [x₁; x₂]` and equations `Uᵀ` — or, when the
//!    nullspace of E is exactly its zero rows and columns and E11 decouples into groups of
//!    coordinates, in the descriptor's own coordinates
//!    split by a permutation, E11 kept and later solved with by LU instead of Σ⁻¹ (the
//!    rotation by V mixes coordinates within every group of equal singular values, equal
//!    masses say, and turns an exact decoupling into a rounding-level coupling) — the last
//!    n − r equations are algebraic: `0 = A21 x₁ + A22 x₂ + B2 u`. A22 must be invertible (index 1).
//!    Its rows are algebraic equations and its columns algebraic variables, whose units are
//!    arbitrary (the Schur complement does not depend on them), so its rank is decided by
//!    SVD of the row- and column-equilibrated A22; the equilibrated A22 is then factored by
//!    LU with partial pivoting and its condition number is reported. When the nullspace of E
//!    is not structural and A22 is within a factor 100 of the rounding level `ε‖A‖` of the
//!    rotation, a warning says the pencil may have index > 1. A singular A22 is an error:
//!    [`NumError::SingularPencil`] when `sE − A` is singular for every s (tested at two
//!    generic complex points), [`NumError::HigherIndex`] otherwise.
//! 4. The Schur complement gives
//!    `A_s = Σ⁻¹(A11 − A12 A22⁻¹ A21)`, `B_s = Σ⁻¹(B1 − A12 A22⁻¹ B2)` (E11⁻¹ for Σ⁻¹ when
//!    permuted),
//!    `C_s = C1 − C2 A22⁻¹ A21`, `D_s = D − C2 A22⁻¹ B2`,
//!    and the physical map is transformed the same way as C (with u = 0, as for mode shapes):
//!    `phys_s = P1 − P2 A22⁻¹ A21` where `[P1 P2] = phys · S · V`.
//!
//! # Finite generalized eigenvalues
//!
//! [`generalized_eigenvalues`] uses faer's QZ on the equilibrated pencil and drops infinite
//! eigenvalues with a scale-aware test instead of a fixed bound like `|λ| < 1e9`; see
//! [`GenEigOptions`].

use faer::MatMut;
use faer::diag::DiagMut;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::ComputeEigenvectors;
use faer::linalg::gevd::{gevd_real, gevd_scratch};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

use crate::linalg::{Equilibrate, Rank, RankTolerance, Scaling, equilibrate, rank, svd};
use crate::statespace::{Descriptor, SignalNames, StateSpace, check_finite};
use crate::{
    A22Rank, Bound, ConvergenceError, DimensionError, NumError, NumWarning, OptionError,
    PencilError, SingularError,
};

/// Rows or columns of E whose largest entry is at most `RANK_NOISE_FACTOR · n · ε · max|E|`
/// are rounding noise and treated as exactly zero (the same scale as the default rank
/// tolerance, [`RankTolerance::Default`]).
pub const RANK_NOISE_FACTOR: f64 = crate::linalg::DEFAULT_RANK_SAFETY;

/// Options of [`descriptor_to_state_space`].
#[derive(Clone, Debug, PartialEq)]
pub struct DescriptorOptions<'a> {
    /// Tolerance of the rank decision on (the equilibrated) E; also used for the
    /// invertibility of the equilibrated A22. Default [`RankTolerance::Default`].
    pub rank_tol: RankTolerance,
    /// Equilibrate the pencil before deciding (default `true`).
    pub equilibrate: bool,
    /// Condition numbers of A22 (and of the kept part of E) above this value produce a
    /// warning in the report (default `1e8`, i.e. about half the digits are lost).
    pub warn_condition: f64,
    /// Map from the descriptor state to physical coordinates (rows × n), transformed into
    /// [`StateSpace::phys`]. `None` gives a `phys` with zero rows.
    pub phys: Option<&'a DMatrix<f64>>,
    /// Names copied into the result; `states` is replaced by `x1, x2, …` unless E has full
    /// rank (then the original state names are kept, as the coordinates are).
    pub names: SignalNames,
}

impl Default for DescriptorOptions<'_> {
    fn default() -> Self {
        DescriptorOptions {
            rank_tol: RankTolerance::Default,
            equilibrate: true,
            warn_condition: 1e8,
            phys: None,
            names: SignalNames::default(),
        }
    }
}

/// What the reduction decided, and how close the decisions were.
#[derive(Clone, Debug, PartialEq)]
pub struct DescriptorReport {
    /// Number of descriptor states n.
    pub states: usize,
    /// Number of dynamic states kept (rank of E).
    pub dynamic: usize,
    /// Number of algebraic states eliminated (n − rank E).
    pub algebraic: usize,
    /// The rank decision on (the equilibrated) E, with its singular values and gap.
    pub e_rank: Rank,
    /// The invertibility decision on A22 (empty when there is no algebraic part).
    pub a22_rank: Option<Rank>,
    /// 2-norm condition number of the equilibrated A22 (1 when there is no algebraic part).
    pub a22_condition: f64,
    /// `σ_1 / σ_r` of the kept part of E (how stiff the reduced model is).
    pub e_condition: f64,
    /// The pencil scaling applied (`None` when not equilibrated).
    pub scaling: Option<Scaling>,
    /// Warnings (near-tolerance rank decisions, ill-conditioning, rounding noise).
    pub warnings: Vec<NumWarning>,
}

/// Scales the pencil: rows then columns of E, plus A-based scaling of the rows/columns where
/// E is zero.
fn pencil_scaling(e: &DMatrix<f64>, a: &DMatrix<f64>) -> Result<Scaling, NumError> {
    let (_, mut s) = equilibrate(e, Equilibrate::Both)?;
    let n = e.nrows();
    let pow2 = |x: f64| (1.0 / x).log2().round().clamp(-1000.0, 1000.0).exp2();
    for i in 0..n {
        if e.row(i).iter().all(|&x| x == 0.0) {
            let mx = (0..n).fold(0.0f64, |acc, j| acc.max((a[(i, j)] * s.cols[j]).abs()));
            if mx > 0.0 {
                s.rows[i] = pow2(mx);
            }
        }
    }
    for j in 0..n {
        if e.column(j).iter().all(|&x| x == 0.0) {
            let mx = (0..n).fold(0.0f64, |acc, i| acc.max((a[(i, j)] * s.rows[i]).abs()));
            if mx > 0.0 {
                s.cols[j] = pow2(mx);
            }
        }
    }
    Ok(s)
}

fn scale_rows(m: &mut DMatrix<f64>, f: &DVector<f64>) {
    for (i, mut r) in m.row_iter_mut().enumerate() {
        r.scale_mut(f[i]);
    }
}

fn scale_cols(m: &mut DMatrix<f64>, f: &DVector<f64>) {
    for (j, mut c) in m.column_iter_mut().enumerate() {
        c.scale_mut(f[j]);
    }
}

fn near_note(what: &'static str, r: &Rank, out: &mut Vec<NumWarning>) {
    if r.is_near_tolerance(100.0) {
        out.push(NumWarning::FragileRank {
            what,
            rank: r.rank,
            margin: r.margin,
            threshold: r.threshold,
            gap: r.gap,
        });
    }
}

/// Is `sE − A` rank deficient at two generic complex points? (singular pencil test)
fn pencil_is_singular(
    e: &DMatrix<f64>,
    a: &DMatrix<f64>,
    tol: RankTolerance,
) -> Result<bool, NumError> {
    let n = e.nrows();
    let ne = e.norm();
    let na = a.norm();
    let base = if ne > 0.0 && na > 0.0 { na / ne } else { 1.0 };
    // Two fixed, "generic" points: irrational-looking ratios avoid hitting an eigenvalue.
    let points = [
        Complex64::new(0.618_033_988_7, 0.303_577_269_0) * base,
        Complex64::new(-0.414_213_562_3, 1.259_921_049_9) * base,
    ];
    let mut singular = true;
    for s in points {
        // Real embedding [[P, −Q], [Q, P]] of P + iQ = sE − A; its singular values are those of
        // the complex matrix, each twice.
        let mut m = DMatrix::<f64>::zeros(2 * n, 2 * n);
        for i in 0..n {
            for j in 0..n {
                let p = s.re * e[(i, j)] - a[(i, j)];
                let q = s.im * e[(i, j)];
                m[(i, j)] = p;
                m[(i + n, j + n)] = p;
                m[(i, j + n)] = -q;
                m[(i + n, j)] = q;
            }
        }
        if rank(&m, tol)?.rank == 2 * n {
            singular = false;
        }
    }
    Ok(singular)
}

/// Reduces an index-1 descriptor model to a standard state space (see the module docs).
///
/// Errors: [`NumError::Dimension`] / [`NumError::NonFinite`] for a malformed model or `phys`
/// (names the matrix), [`NumError::InvalidOption`] for a bad tolerance,
/// [`NumError::HigherIndex`] when A22 is singular but the pencil is regular,
/// [`NumError::SingularPencil`] when `det(sE − A) ≡ 0`, [`NumError::Singular`] when E has full
/// rank by the decision but its LU breaks down, [`NumError::NoConvergence`].
pub fn descriptor_to_state_space(
    d: &Descriptor<f64>,
    opts: &DescriptorOptions<'_>,
) -> Result<(StateSpace<f64>, DescriptorReport), NumError> {
    let phys0 = check_arguments(d, opts)?;
    let (d, noise_notes) = clean_noise(d);
    let (p, scaling) = equilibrate_pencil(&d, phys0, opts)?;
    let mut warnings = noise_notes;
    let e = decide_e_rank(&p.e, opts, &mut warnings)?;
    let report = DescriptorReport {
        states: d.states(),
        dynamic: e.rank.rank,
        algebraic: d.states() - e.rank.rank,
        e_rank: e.rank.clone(),
        a22_rank: None,
        a22_condition: 1.0,
        e_condition: e.condition,
        scaling: opts.equilibrate.then(|| scaling.clone()),
        warnings: Vec::new(),
    };
    if e.rank.rank == d.states() {
        let ss = full_rank(&d, &p, &scaling, opts)?;
        return Ok((ss, DescriptorReport { warnings, ..report }));
    }
    let blocks = Blocks::rotate(&p, &e);
    let a22 = decide_a22(&p, &blocks, &e, opts, &mut warnings)?;
    let ss = schur_complement(&d, &blocks, &e, &a22, opts)?;
    Ok((
        ss,
        DescriptorReport {
            a22_rank: Some(a22.rank),
            a22_condition: a22.condition,
            warnings,
            ..report
        },
    ))
}

/// The pencil `R (sE − A) S` with `B' = R B`, `C' = C S`, `phys' = phys S`.
struct Pencil {
    e: DMatrix<f64>,
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    c: DMatrix<f64>,
    ph: DMatrix<f64>,
}

/// Step 2: the SVD of E, its rank decision and condition.
struct ERank {
    svd: crate::linalg::Svd,
    rank: Rank,
    /// The nullspace of E is exactly its zero rows and columns.
    structural: bool,
    /// Those rows and columns, when `structural`, E is not of full rank and its kept block
    /// E11 decouples (then the coordinates are permuted, not rotated).
    split: Option<Split>,
    condition: f64,
}

/// The rotated pencil `Uᵀ A V` etc., split at the rank r of E.
struct Blocks {
    at: DMatrix<f64>,
    bt: DMatrix<f64>,
    ct: DMatrix<f64>,
    pt: DMatrix<f64>,
    r: usize,
    k: usize,
    /// The kept block E11 of E when the coordinates were permuted, not rotated: the
    /// equations are then solved with it instead of scaled by Σ⁻¹.
    e11: Option<DMatrix<f64>>,
}

/// Step 3 (rank deficient): the invertibility decision on A22, and its equilibrated LU
/// factors' inputs.
struct A22 {
    rank: Rank,
    condition: f64,
    equilibrated: DMatrix<f64>,
    scaling: Scaling,
}

/// The options and `phys` are valid; returns `phys` (zero rows when absent).
fn check_arguments(
    d: &Descriptor<f64>,
    opts: &DescriptorOptions<'_>,
) -> Result<DMatrix<f64>, NumError> {
    d.validate()?;
    opts.rank_tol.validate()?;
    if opts.warn_condition.is_nan() || opts.warn_condition <= 0.0 {
        return Err(NumError::InvalidOption(OptionError::Value {
            option: "DescriptorOptions::warn_condition",
            value: opts.warn_condition,
            must: Bound::Positive,
        }));
    }
    let n = d.states();
    match opts.phys {
        Some(ph) => {
            if ph.ncols() != n {
                return Err(NumError::Dimension(DimensionError::PhysColumns {
                    rows: ph.nrows(),
                    cols: ph.ncols(),
                    states: n,
                    descriptor: true,
                }));
            }
            check_finite(ph, "phys")?;
            Ok(ph.clone())
        }
        None => Ok(DMatrix::zeros(0, n)),
    }
}

/// Step 0: rows and columns of E at the rounding level of ‖E‖ are zero rows/columns (input
/// states and massless coordinates after orthonormal projections carry ε-size residues).
/// They must be made exactly zero before equilibration, which would otherwise scale the
/// noise up to O(1) and turn it into an equation.
fn clean_noise(d: &Descriptor<f64>) -> (Descriptor<f64>, Vec<NumWarning>) {
    let n = d.states();
    let mut e_clean = d.e.clone();
    let mut notes = Vec::new();
    let emax = e_clean.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let noise = RANK_NOISE_FACTOR * n as f64 * f64::EPSILON * emax;
    for i in 0..n {
        let rmax = e_clean.row(i).iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if rmax > 0.0 && rmax <= noise {
            e_clean.row_mut(i).fill(0.0);
            notes.push(NumWarning::RoundingNoise {
                line: "row",
                index: i,
                largest: rmax,
                noise,
            });
        }
    }
    for j in 0..n {
        let cmax = e_clean.column(j).iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if cmax > 0.0 && cmax <= noise {
            e_clean.column_mut(j).fill(0.0);
            notes.push(NumWarning::RoundingNoise {
                line: "column",
                index: j,
                largest: cmax,
                noise,
            });
        }
    }
    let d = Descriptor {
        e: e_clean,
        a: d.a.clone(),
        b: d.b.clone(),
        c: d.c.clone(),
        d: d.d.clone(),
    };
    (d, notes)
}

/// Step 1: `E' = R E S`, `A' = R A S`, `B' = R B`, `C' = C S`, `phys' = phys S` (unit
/// scalings when not equilibrating).
fn equilibrate_pencil(
    d: &Descriptor<f64>,
    phys: DMatrix<f64>,
    opts: &DescriptorOptions<'_>,
) -> Result<(Pencil, Scaling), NumError> {
    let n = d.states();
    let scaling = if opts.equilibrate {
        pencil_scaling(&d.e, &d.a)?
    } else {
        Scaling {
            rows: DVector::from_element(n, 1.0),
            cols: DVector::from_element(n, 1.0),
        }
    };
    let mut p = Pencil {
        e: d.e.clone(),
        a: d.a.clone(),
        b: d.b.clone(),
        c: d.c.clone(),
        ph: phys,
    };
    scale_rows(&mut p.e, &scaling.rows);
    scale_cols(&mut p.e, &scaling.cols);
    scale_rows(&mut p.a, &scaling.rows);
    scale_cols(&mut p.a, &scaling.cols);
    scale_rows(&mut p.b, &scaling.rows);
    scale_cols(&mut p.c, &scaling.cols);
    scale_cols(&mut p.ph, &scaling.cols);
    Ok((p, scaling))
}

/// Step 2: the SVD of E and its rank. Exactly zero rows and columns (input states,
/// massless coordinates) are split off first, so that their part of A22 is exact.
fn decide_e_rank(
    e: &DMatrix<f64>,
    opts: &DescriptorOptions<'_>,
    warnings: &mut Vec<NumWarning>,
) -> Result<ERank, NumError> {
    let n = e.nrows();
    let (f, split) = structured_svd(e)?;
    let zeros = split.as_ref().map_or(0, |s| s.rows.1.len());
    let smax = f.singular_values.first().copied().unwrap_or(0.0);
    let e_rank = rank_from(&f.singular_values, opts.rank_tol.threshold(smax, n, n));
    let r = e_rank.rank;
    near_note("rank of E", &e_rank, warnings);
    let condition = if r == 0 {
        1.0
    } else {
        f.singular_values[0] / f.singular_values[r - 1]
    };
    if condition > opts.warn_condition {
        warnings.push(NumWarning::StiffE { condition });
    }
    let structural = n - r == zeros;
    // Permuted rather than rotated only where there is structure to keep: E11 decouples into
    // groups of coordinates. A coupled E11 is rotated as before (its SVD is then the more
    // accurate factorization: the truck–trailer's gain at its split zero pair lost a digit
    // to the LU of a coupled E11).
    let split = split.filter(|sp| {
        structural && {
            let e11 = e.select_rows(&sp.rows.0).select_columns(&sp.cols.0);
            crate::linalg::column_groups(&e11).len() > 1
        }
    });
    Ok(ERank {
        structural,
        split,
        svd: f,
        rank: e_rank,
        condition,
    })
}

/// Step 3, full rank: `ẋ = E⁻¹A x + E⁻¹B u` in the original coordinates. With `E' = R E S`:
/// `E⁻¹A = S (E'⁻¹ A') S⁻¹` and `E⁻¹B = S E'⁻¹ B'`.
fn full_rank(
    d: &Descriptor<f64>,
    p: &Pencil,
    scaling: &Scaling,
    opts: &DescriptorOptions<'_>,
) -> Result<StateSpace<f64>, NumError> {
    let n = d.states();
    let m = d.b.ncols();
    let mut rhs = DMatrix::zeros(n, n + m);
    rhs.columns_mut(0, n).copy_from(&p.a);
    rhs.columns_mut(n, m).copy_from(&p.b);
    let x = if n == 0 {
        rhs
    } else {
        p.e.clone()
            .lu()
            .solve(&rhs)
            .ok_or(NumError::Singular(SingularError::LuFailed {
                matrix: "E",
                n,
                passed: "has full numerical rank",
                failed: "factorisation broke down",
            }))?
    };
    let mut a_s = x.columns(0, n).into_owned();
    let mut b_s = x.columns(n, m).into_owned();
    for i in 0..n {
        for j in 0..n {
            a_s[(i, j)] *= scaling.cols[i] / scaling.cols[j];
        }
        for j in 0..m {
            b_s[(i, j)] *= scaling.cols[i];
        }
    }
    check_finite(&a_s, "A_s = E⁻¹A")?;
    let phys = match opts.phys {
        Some(ph0) => ph0.clone(),
        None => DMatrix::zeros(0, n),
    };
    let ss = StateSpace {
        a: a_s,
        b: b_s,
        c: d.c.clone(),
        d: d.d.clone(),
        phys,
        names: opts.names.clone(),
    };
    ss.validate()?;
    Ok(ss)
}

impl Blocks {
    /// Step 3, rank deficient: the coordinates `x = V [x₁; x₂]` and equations `Uᵀ` — or,
    /// when the nullspace of E is exactly its zero rows and columns, the same split by a
    /// permutation, E11 kept as it is. The rotation by V would mix the dynamic coordinates
    /// (arbitrarily, within every group of equal singular values, e.g. equal masses) and turn
    /// the exact zeros of a decoupled model into rounding errors; the permutation keeps the
    /// descriptor's own coordinates as the states.
    fn rotate(p: &Pencil, e: &ERank) -> Self {
        if let Some(split) = &e.split {
            return Blocks::permute(p, split);
        }
        let f = &e.svd;
        let ut = f.u.transpose();
        let r = e.rank.rank;
        Blocks {
            at: &ut * &p.a * &f.v,
            bt: &ut * &p.b,
            ct: &p.c * &f.v,
            pt: &p.ph * &f.v,
            r,
            k: p.e.nrows() - r,
            e11: None,
        }
    }

    /// The split by a permutation (see [`Blocks::rotate`]).
    fn permute(p: &Pencil, split: &Split) -> Self {
        let rows: Vec<usize> = split.rows.0.iter().chain(&split.rows.1).copied().collect();
        let cols: Vec<usize> = split.cols.0.iter().chain(&split.cols.1).copied().collect();
        let r = split.rows.0.len();
        Blocks {
            at: p.a.select_rows(&rows).select_columns(&cols),
            bt: p.b.select_rows(&rows),
            ct: p.c.select_columns(&cols),
            pt: p.ph.select_columns(&cols),
            r,
            k: p.e.nrows() - r,
            e11: Some(p.e.select_rows(&split.rows.0).select_columns(&split.cols.0)),
        }
    }

    fn a22(&self) -> DMatrix<f64> {
        let (r, k) = (self.r, self.k);
        self.at.view((r, r), (k, k)).into_owned()
    }
}

/// Step 3, rank deficient: A22 invertibility, decided on the equilibrated A22 (its rows are
/// algebraic equations and its columns algebraic variables, whose units are arbitrary: the
/// Schur complement does not depend on them). A singular A22 is an error that says whether
/// the pencil is singular or of higher index.
fn decide_a22(
    p: &Pencil,
    blocks: &Blocks,
    e: &ERank,
    opts: &DescriptorOptions<'_>,
    warnings: &mut Vec<NumWarning>,
) -> Result<A22, NumError> {
    let (n, r, k) = (p.e.nrows(), blocks.r, blocks.k);
    let a22 = blocks.a22();
    let (a22e, sc22) = equilibrate(&a22, Equilibrate::Both)?;
    let s22 = crate::linalg::singular_values(&a22e)?;
    let thr22 = opts.rank_tol.threshold(s22[0], k, k);
    let a22_rank = rank_from(&s22, thr22);
    if a22_rank.rank < k {
        let singular = pencil_is_singular(&p.e, &p.a, opts.rank_tol)?;
        let smin = s22.last().copied().unwrap_or(0.0);
        let decision = A22Rank {
            e_rank: r,
            n,
            k,
            a22_rank: a22_rank.rank,
            smallest: smin,
            threshold: thr22,
        };
        return Err(if singular {
            NumError::SingularPencil(PencilError::RankDeficient(decision))
        } else {
            NumError::HigherIndex(decision)
        });
    }
    let condition = s22[0] / s22[k - 1];
    near_note("invertibility of A22", &a22_rank, warnings);
    if condition > opts.warn_condition {
        warnings.push(NumWarning::IllConditionedA22 { size: k, condition });
    }
    if !e.structural {
        // A rotated (non-structural) nullspace of E puts rounding errors of size ε‖A‖ into
        // A22; an A22 at that level may be an index-2 pencil in disguise.
        let anorm = crate::linalg::singular_values(&p.a)?
            .first()
            .copied()
            .unwrap_or(0.0);
        let s22raw = crate::linalg::singular_values(&a22)?;
        let noise = 10.0 * n as f64 * f64::EPSILON * anorm;
        if s22raw.last().copied().unwrap_or(0.0) <= 100.0 * noise {
            warnings.push(NumWarning::A22NearNoise {
                smallest: s22raw.last().copied().unwrap_or(0.0),
                noise,
            });
        }
    }
    Ok(A22 {
        rank: a22_rank,
        condition,
        equilibrated: a22e,
        scaling: sc22,
    })
}

/// Step 4: the Schur complement, `A22⁻¹ Y = C22 (R22 A22 C22)⁻¹ R22 Y` by the LU of the
/// equilibrated A22.
fn schur_complement(
    d: &Descriptor<f64>,
    blocks: &Blocks,
    e: &ERank,
    a22: &A22,
    opts: &DescriptorOptions<'_>,
) -> Result<StateSpace<f64>, NumError> {
    let (r, k) = (blocks.r, blocks.k);
    let m = d.b.ncols();
    let at = &blocks.at;
    let a11 = at.view((0, 0), (r, r));
    let a12 = at.view((0, r), (r, k));
    let a21 = at.view((r, 0), (k, r));
    let b1 = blocks.bt.rows(0, r);
    let b2 = blocks.bt.rows(r, k);
    let c1 = blocks.ct.columns(0, r);
    let c2 = blocks.ct.columns(r, k);
    let p1 = blocks.pt.columns(0, r);
    let p2 = blocks.pt.columns(r, k);
    let lu = a22.equilibrated.clone().lu();
    let mut rhs = DMatrix::zeros(k, r + m);
    rhs.columns_mut(0, r).copy_from(&a21);
    rhs.columns_mut(r, m).copy_from(&b2);
    scale_rows(&mut rhs, &a22.scaling.rows);
    let mut x = lu
        .solve(&rhs)
        .ok_or(NumError::Singular(SingularError::LuFailed {
            matrix: "A22",
            n: k,
            passed: "passed the rank test",
            failed: "factorisation broke down",
        }))?;
    scale_rows(&mut x, &a22.scaling.cols);
    let xa = x.columns(0, r);
    let xb = x.columns(r, m);
    let mut a_s = a11 - a12 * xa;
    let mut b_s = b1 - a12 * xb;
    match &blocks.e11 {
        Some(e11) => {
            let mut rhs = DMatrix::zeros(r, r + m);
            rhs.columns_mut(0, r).copy_from(&a_s);
            rhs.columns_mut(r, m).copy_from(&b_s);
            let x = e11.clone().lu().solve(&rhs).ok_or(NumError::Singular(
                SingularError::LuFailed {
                    matrix: "E11",
                    n: r,
                    passed: "has full numerical rank",
                    failed: "factorisation broke down",
                },
            ))?;
            a_s = x.columns(0, r).into_owned();
            b_s = x.columns(r, m).into_owned();
        }
        None => {
            for i in 0..r {
                let inv = 1.0 / e.svd.singular_values[i];
                a_s.row_mut(i).scale_mut(inv);
                b_s.row_mut(i).scale_mut(inv);
            }
        }
    }
    let c_s = c1 - c2 * xa;
    let d_s = &d.d - c2 * xb;
    let phys_s = p1 - p2 * xa;
    let mut names = opts.names.clone();
    names.states = (1..=r).map(|i| format!("x{i}")).collect();
    let ss = StateSpace {
        a: a_s,
        b: b_s,
        c: c_s,
        d: d_s,
        phys: phys_s,
        names,
    };
    debug_assert_eq!(ss.c.nrows(), d.c.nrows());
    ss.validate()?;
    Ok(ss)
}

/// SVD of E with exactly zero rows and columns split off: if E has z zero rows and z zero
/// columns, `E = P_r [[E11, 0], [0, 0]] P_cᵀ`, only E11 is decomposed and the null part of
/// U, V consists of exact unit vectors. Returns the SVD and the split (`None` when E has no
/// zero rows, or not as many zero rows as zero columns).
fn structured_svd(e: &DMatrix<f64>) -> Result<(crate::linalg::Svd, Option<Split>), NumError> {
    let n = e.nrows();
    let zr: Vec<usize> = (0..n)
        .filter(|&i| e.row(i).iter().all(|&x| x == 0.0))
        .collect();
    let zc: Vec<usize> = (0..n)
        .filter(|&j| e.column(j).iter().all(|&x| x == 0.0))
        .collect();
    if zr.is_empty() || zr.len() != zc.len() {
        return Ok((svd(e)?, None));
    }
    let z = zr.len();
    let nr: Vec<usize> = (0..n).filter(|i| !zr.contains(i)).collect();
    let nc: Vec<usize> = (0..n).filter(|j| !zc.contains(j)).collect();
    let e11 = DMatrix::from_fn(n - z, n - z, |i, j| e[(nr[i], nc[j])]);
    let f11 = svd(&e11)?;
    let mut u = DMatrix::zeros(n, n);
    let mut v = DMatrix::zeros(n, n);
    for (i, &ri) in nr.iter().enumerate() {
        for j in 0..n - z {
            u[(ri, j)] = f11.u[(i, j)];
        }
    }
    for (j, &cj) in nc.iter().enumerate() {
        for i in 0..n - z {
            // V rows are indexed by columns of E.
            v[(cj, i)] = f11.v[(j, i)];
        }
    }
    for (k, (&ri, &cj)) in zr.iter().zip(zc.iter()).enumerate() {
        u[(ri, n - z + k)] = 1.0;
        v[(cj, n - z + k)] = 1.0;
    }
    let mut sv = f11.singular_values.clone();
    sv.extend(std::iter::repeat_n(0.0, z));
    Ok((
        crate::linalg::Svd {
            u,
            singular_values: sv,
            v,
        },
        Some(Split {
            rows: (nr, zr),
            cols: (nc, zc),
        }),
    ))
}

/// The exactly zero rows and columns of E split off by [`structured_svd`]: `(nonzero, zero)`
/// indices of each.
#[derive(Clone, Debug)]
struct Split {
    rows: (Vec<usize>, Vec<usize>),
    cols: (Vec<usize>, Vec<usize>),
}

fn rank_from(s: &[f64], threshold: f64) -> Rank {
    crate::linalg::decide(s.to_vec(), threshold)
}

/// Options of [`generalized_eigenvalues_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GenEigOptions {
    /// Rank tolerance for E: a regular pencil has at least `n − rank E` infinite
    /// eigenvalues, which are always dropped.
    pub rank_tol: RankTolerance,
    /// Beyond those, an eigenvalue is also infinite when
    /// `θ = |β̂| / √(|α̂|² + |β̂|²) ≤ infinite_tol`, with `α̂ = α/‖A‖_F`, `β̂ = β/‖E‖_F`
    /// (the angle of (α, β) in the scaled projective line). Default `√ε ≈ 1.5e-8`, i.e. a
    /// finite eigenvalue must satisfy `|λ| < ‖A‖/(‖E‖ √ε)`; perturbed higher-index infinite
    /// eigenvalues typically land near `√ε`.
    pub infinite_tol: f64,
    /// Equilibrate the pencil first (default `true`).
    pub equilibrate: bool,
}

impl Default for GenEigOptions {
    fn default() -> Self {
        GenEigOptions {
            rank_tol: RankTolerance::Default,
            infinite_tol: f64::EPSILON.sqrt(),
            equilibrate: true,
        }
    }
}

/// Finite and infinite generalized eigenvalues of a pencil.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneralizedEigenvalues {
    /// Finite eigenvalues, sorted by (Re, Im).
    pub finite: Vec<Complex64>,
    /// Number of eigenvalues judged infinite.
    pub infinite: usize,
    /// Rank decision on E (lower bound n − rank for the infinite count).
    pub e_rank: Rank,
    /// Ratio of θ across the finite/infinite split (smallest finite θ over largest infinite
    /// θ; `∞` if one side is empty or exact). Close to 1 means the split was close.
    pub gap: f64,
    /// Warnings (close split, disagreement between the rank of E and QZ).
    pub warnings: Vec<NumWarning>,
}

/// Finite generalized eigenvalues of `(A, E)` (`det(λE − A) = 0`), sorted by (Re, Im), with
/// default [`GenEigOptions`].
///
/// Errors: [`NumError::Dimension`], [`NumError::NonFinite`], [`NumError::SingularPencil`]
/// when some (α, β) are both zero (det(sE − A) ≡ 0), [`NumError::NoConvergence`].
pub fn generalized_eigenvalues(d: &Descriptor<f64>) -> Result<Vec<Complex64>, NumError> {
    Ok(generalized_eigenvalues_with(d, &GenEigOptions::default())?.finite)
}

/// [`generalized_eigenvalues`] with options and the full report.
pub fn generalized_eigenvalues_with(
    d: &Descriptor<f64>,
    opts: &GenEigOptions,
) -> Result<GeneralizedEigenvalues, NumError> {
    d.validate()?;
    opts.rank_tol.validate()?;
    if !(opts.infinite_tol.is_finite() && opts.infinite_tol >= 0.0) {
        return Err(NumError::InvalidOption(OptionError::Value {
            option: "GenEigOptions::infinite_tol",
            value: opts.infinite_tol,
            must: Bound::FiniteNonNegative,
        }));
    }
    let n = d.states();
    let (mut e, mut a) = (d.e.clone(), d.a.clone());
    if opts.equilibrate {
        let s = pencil_scaling(&d.e, &d.a)?;
        scale_rows(&mut e, &s.rows);
        scale_cols(&mut e, &s.cols);
        scale_rows(&mut a, &s.rows);
        scale_cols(&mut a, &s.cols);
    }
    let e_rank = rank(&e, opts.rank_tol)?;
    let ne = e.norm();
    let na = a.norm();
    let mut re = vec![0.0; n];
    let mut im = vec![0.0; n];
    let mut beta = vec![0.0; n];
    if n > 0 {
        let mut aw = a.clone();
        let mut ew = e.clone();
        let par = crate::linalg::par(n);
        let req = gevd_scratch::<f64>(
            n,
            ComputeEigenvectors::No,
            ComputeEigenvectors::No,
            par,
            Default::default(),
        );
        let mut buf = MemBuffer::new(req);
        gevd_real(
            MatMut::from_column_major_slice_mut(aw.as_mut_slice(), n, n),
            MatMut::from_column_major_slice_mut(ew.as_mut_slice(), n, n),
            DiagMut::from_slice_mut(&mut re),
            DiagMut::from_slice_mut(&mut im),
            DiagMut::from_slice_mut(&mut beta),
            None,
            None,
            par,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .map_err(|_| {
            NumError::NoConvergence(ConvergenceError::Factorisation {
                step: "QZ",
                rows: n,
                cols: n,
                object: "pencil",
            })
        })?;
    }
    // Scaled (α̂, β̂) and the angle θ.
    let sa = if na > 0.0 { na } else { 1.0 };
    let se = if ne > 0.0 { ne } else { 1.0 };
    let zero_tol = 10.0 * (n.max(1) as f64) * f64::EPSILON;
    let mut items: Vec<(f64, Complex64)> = Vec::with_capacity(n);
    let mut j = 0;
    while j < n {
        let pair = im[j] != 0.0 && j + 1 < n;
        let alpha = Complex64::new(re[j], im[j]);
        let ah = alpha.norm() / sa;
        let bh = beta[j].abs() / se;
        if ah <= zero_tol && bh <= zero_tol {
            return Err(NumError::SingularPencil(PencilError::VanishingEigenvalue {
                alpha: ah,
                beta: bh,
                index: j,
                n,
                e_rank: e_rank.rank,
            }));
        }
        let theta = bh / (ah * ah + bh * bh).sqrt();
        let lambda = if beta[j] != 0.0 {
            alpha / beta[j]
        } else {
            Complex64::new(f64::INFINITY, 0.0)
        };
        items.push((theta, lambda));
        if pair {
            items.push((theta, lambda.conj()));
            j += 2;
        } else {
            j += 1;
        }
    }
    // Smallest θ first: the n − rank(E) smallest are infinite regardless; then the threshold.
    items.sort_by(|x, y| x.0.total_cmp(&y.0));
    let forced = n - e_rank.rank;
    let mut n_inf = forced;
    while n_inf < n && (items[n_inf].0 <= opts.infinite_tol || !items[n_inf].1.re.is_finite()) {
        n_inf += 1;
    }
    let mut warnings = Vec::new();
    // Conjugate pairs share θ; never split a pair.
    while n_inf > 0 && n_inf < n && items[n_inf].0 == items[n_inf - 1].0 && items[n_inf].1.im != 0.0
    {
        n_inf += 1;
    }
    if forced > 0 && items[forced - 1].0 > opts.infinite_tol {
        warnings.push(NumWarning::InfiniteCountDisagrees {
            e_rank: e_rank.rank,
            forced,
            theta: items[forced - 1].0,
            tolerance: opts.infinite_tol,
        });
    }
    let gap = if n_inf == 0 || n_inf == n || items[n_inf - 1].0 == 0.0 {
        f64::INFINITY
    } else {
        items[n_inf].0 / items[n_inf - 1].0
    };
    if gap < 100.0 {
        warnings.push(NumWarning::CloseInfiniteSplit { gap });
    }
    let mut finite: Vec<Complex64> = items[n_inf..].iter().map(|x| x.1).collect();
    finite.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    Ok(GeneralizedEigenvalues {
        finite,
        infinite: n_inf,
        e_rank,
        gap,
        warnings,
    })
}
