//! The PBH deflation pass of [`crate::minreal`]: removes the uncontrollable directions of
//! clustered eigenvalues that the Krylov staircase cannot see.
//!
//! For a cluster of eigenvalues with mean `λ`, the left singular vectors `W` of
//! `[A − λI, B]` whose singular values are `≤ tol` satisfy `Wᴴ(A − λI) ≈ 0`, `WᴴB ≈ 0`
//! (Popov–Belevitch–Hautus). In real arithmetic the span of `Re W, Im W` is then left
//! invariant, its orthogonal complement right invariant and containing `range(B)`: with
//! `Q = [Q1 Q2]`, `Q2` an orthonormal basis of that span,
//! `Qᵀ A Q = [A11 A12; ≈0 A22]`, `Qᵀ B = [B1; ≈0]`, and the `≈0` blocks are set to exact
//! zeros. The modes of `A22` are removed as uncontrollable. The dual (`Aᵀ, Cᵀ`) gives the
//! unobservable ones.
//!
//! A defective cluster deflates one Jordan level at a time (`rank [A − λI, B]` drops by the
//! geometric multiplicity only): after a pass that removed something the staircase runs
//! again, and removes the next level, now an eigenvalue alone. See the documentation of
//! [`crate::minreal`] for the whole algorithm.

use nalgebra::DMatrix;
use num_complex::Complex64;
use rayon::prelude::*;

use crate::error::NumError;
use crate::minreal::pbh_subspace::{cluster_pbh, lower_bandwidth};
use crate::minreal::staircase::{StaircaseForm, staircase};
use crate::minreal::{RankDecision, RankStage, eigenvalues_sorted, sort_complex, svd_full};
use crate::reach::{block_triangular_eigenvalues, reachable};

/// Eigenvalues of a square matrix, sorted by (re, im).
fn eigenvalues_of(a: &DMatrix<f64>) -> Result<Vec<Complex64>, NumError> {
    eigenvalues_sorted(a.view((0, 0), (a.nrows(), a.ncols())))
}

/// A group of eigenvalues within the cluster distance of each other (transitively),
/// represented once per conjugate pair: `mean` has `im ≥ 0`, exactly 0 for a cluster that is
/// its own conjugate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Cluster {
    pub mean: Complex64,
    pub size: usize,
}

/// Clusters of `ev` at distance `dist` (single linkage), the upper half-plane ones and the
/// real ones.
pub(crate) fn clusters(ev: &[Complex64], dist: f64) -> Vec<Cluster> {
    let n = ev.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| ev[i].re.total_cmp(&ev[j].re));
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for (x, &i) in order.iter().enumerate() {
        for &j in &order[x + 1..] {
            if ev[j].re - ev[i].re > dist {
                break;
            }
            if (ev[j] - ev[i]).norm() <= dist {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                parent[ri] = rj;
            }
        }
    }
    let mut sums: Vec<(Complex64, usize)> = vec![(Complex64::new(0.0, 0.0), 0); n];
    for (i, &e) in ev.iter().enumerate() {
        let r = root(&mut parent, i);
        sums[r].0 += e;
        sums[r].1 += 1;
    }
    let mut out = Vec::new();
    for &(sum, size) in sums.iter().filter(|s| s.1 > 0) {
        let mut mean = sum / size as f64;
        // A cluster holding a member within dist/2 of the real axis holds its conjugate too:
        // its mean is real. The other clusters come in conjugate pairs: keep the upper one.
        if mean.im.abs() <= 0.5 * dist {
            mean.im = 0.0;
        } else if mean.im < 0.0 {
            continue;
        }
        out.push(Cluster { mean, size });
    }
    out.sort_by(|x, y| {
        x.mean
            .re
            .total_cmp(&y.mean.re)
            .then(x.mean.im.total_cmp(&y.mean.im))
    });
    out
}

/// An orthogonal `Q = [Q1 Q2]` whose last columns `Q2` span the columns of `x` (k × r, of
/// full column rank), and `r`.
fn rotation_with_last(x: &DMatrix<f64>) -> Result<(DMatrix<f64>, usize), NumError> {
    let (k, r) = x.shape();
    let (u, _, _) = svd_full(x)?;
    let mut q = DMatrix::zeros(k, k);
    q.columns_mut(0, k - r).copy_from(&u.columns(r, k - r));
    q.columns_mut(k - r, r).copy_from(&u.columns(0, r));
    Ok((q, r))
}

/// One factor of the reduction's basis change: old coordinates = factor · new ones.
enum Factor {
    /// A staircase; its leading `kept` columns are kept.
    Staircase(StaircaseForm),
    /// A rotation of the PBH pass, its kept columns only.
    Dense(DMatrix<f64>),
    /// The states a structural reduction kept, in order.
    Select(Vec<usize>),
}

/// The part of `(A, B, C)` a [`reduce`] keeps, `a = Q1ᵀ A Q1`, `b = Q1ᵀ B`, `c = C Q1`,
/// with what it removed and the decisions it took.
pub(crate) struct Reduction {
    pub a: DMatrix<f64>,
    pub b: DMatrix<f64>,
    pub c: DMatrix<f64>,
    /// Eigenvalues of the removed parts, sorted by (re, im).
    pub removed: Vec<Complex64>,
    /// Every decision, in the order taken.
    pub decisions: Vec<RankDecision>,
    /// The eigenvalues of `a`, when the last PBH pass computed them and nothing was removed
    /// since (for reuse by the next stage).
    pub eigenvalues: Option<Vec<Complex64>>,
    /// States removed by the structure ([`Reduction::structural`]), no rank decision.
    pub structural: usize,
    factors: Vec<Factor>,
}

impl Reduction {
    /// `M ← M Q1` for a matrix with one column per state of the input system.
    pub fn apply_right(&self, m: DMatrix<f64>) -> DMatrix<f64> {
        let mut m = m;
        for f in &self.factors {
            m = match f {
                Factor::Staircase(s) => {
                    s.apply_right(&mut m);
                    m.columns(0, s.kept).clone_owned()
                }
                Factor::Dense(q) => m * q,
                Factor::Select(kept) => m.select_columns(kept),
            };
        }
        m
    }
}

impl Reduction {
    /// The system before any reduction.
    pub fn new(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>) -> Self {
        Reduction {
            a,
            b,
            c,
            removed: Vec::new(),
            decisions: Vec::new(),
            eigenvalues: None,
            structural: 0,
            factors: Vec::new(),
        }
    }

    /// The dual `(aᵀ, cᵀ, bᵀ)` of the kept part, as a new reduction.
    pub fn dual(&self) -> Self {
        Reduction::new(self.a.transpose(), self.c.transpose(), self.b.transpose())
    }

    /// Removes the states no input reaches in the graph of the kept part's `(a, b)`
    /// ([`crate::reach`]): exactly uncontrollable, no rank decision. Returns how many (also
    /// added to `structural`).
    pub fn structural(&mut self) -> Result<usize, NumError> {
        let k = self.a.nrows();
        let reached = reachable(&self.a, &self.b);
        let kept: Vec<usize> = (0..k).filter(|&i| reached[i]).collect();
        if kept.len() == k {
            return Ok(0);
        }
        let gone: Vec<usize> = (0..k).filter(|&i| !reached[i]).collect();
        self.removed.extend(block_triangular_eigenvalues(
            &self.a.select_rows(&gone).select_columns(&gone),
        )?);
        self.a = self.a.select_rows(&kept).select_columns(&kept);
        self.b = self.b.select_rows(&kept);
        self.c = self.c.select_columns(&kept);
        self.eigenvalues = None;
        self.factors.push(Factor::Select(kept));
        self.structural += gone.len();
        Ok(gone.len())
    }

    /// One controllability staircase with tolerance `tol` (decisions named `stage`) on the
    /// kept part.
    pub fn staircase(&mut self, tol: f64, stage: RankStage) -> Result<(), NumError> {
        let k = self.a.nrows();
        let sf = staircase(
            std::mem::take(&mut self.a),
            std::mem::take(&mut self.b),
            std::mem::take(&mut self.c),
            tol,
            stage,
        )?;
        let kept = sf.kept;
        self.removed.extend(eigenvalues_sorted(
            sf.a.view((kept, kept), (k - kept, k - kept)),
        )?);
        self.decisions.extend(sf.decisions.iter().cloned());
        self.a = sf.a.view((0, 0), (kept, kept)).clone_owned();
        self.b = sf.b.rows(0, kept).clone_owned();
        self.c = sf.c.columns(0, kept).clone_owned();
        if kept < k {
            self.eigenvalues = None;
        }
        self.factors.push(Factor::Staircase(sf));
        Ok(())
    }

    /// After a staircase: the PBH pass at the clusters of eigenvalues at distance `dist`, and
    /// the staircase again on what it kept, until the pass removes nothing. `eigenvalues`,
    /// when given, are those of the kept part (computed otherwise); those of the final kept
    /// part are left in `self.eigenvalues`.
    pub fn finish(
        &mut self,
        tol: f64,
        dist: f64,
        stages: (RankStage, RankStage),
        eigenvalues: Option<Vec<Complex64>>,
    ) -> Result<(), NumError> {
        let mut ev = eigenvalues;
        loop {
            let e = match ev.take() {
                Some(e) => e,
                None => eigenvalues_of(&self.a)?,
            };
            match deflate_clusters(self, &e, tol, dist, stages.1)? {
                None => {
                    self.eigenvalues = Some(e);
                    break;
                }
                Some(q1) => self.factors.push(Factor::Dense(q1)),
            }
            self.staircase(tol, stages.0)?;
        }
        sort_complex(&mut self.removed);
        Ok(())
    }
}

/// Eigenvalues of the kept part of `r`, for [`Reduction::finish`].
pub(crate) fn kept_eigenvalues(r: &Reduction) -> Result<Vec<Complex64>, NumError> {
    eigenvalues_of(&r.a)
}

/// One PBH pass over the clusters (of two or more) of `ev`, the eigenvalues of `r.a`:
/// rotates and truncates `r.a`, `r.b`, `r.c` in place and returns the kept columns of the
/// rotation, `None` when nothing was removed.
///
/// At a cluster of `s` eigenvalues at most `s − 1` directions are removed: the staircase is
/// reliable for an uncontrollable mode whose eigenvalue no controllable mode shares, so at
/// least one mode of a cluster it kept is controllable. A mode left alone by this rule but
/// whose singular value is below the tolerance shows as a kept singular value below it, a
/// fragile decision.
///
/// The directions of all clusters are found on the same `A` (its Hessenberg form makes each
/// test cheap) and removed by one rotation: the orthogonal complement of each cluster's
/// directions is invariant, and so is their intersection.
fn deflate_clusters(
    r: &mut Reduction,
    ev: &[Complex64],
    tol: f64,
    dist: f64,
    stage: RankStage,
) -> Result<Option<DMatrix<f64>>, NumError> {
    let k = r.a.nrows();
    let targets: Vec<Cluster> = clusters(ev, dist)
        .into_iter()
        .filter(|cl| cl.size >= 2)
        .collect();
    if targets.is_empty() || k < 2 {
        return Ok(None);
    }
    let p = lower_bandwidth(&r.a);
    let tests = cluster_tests(r, &targets, p)?;
    // Real basis vectors of the directions to remove: Re w, and Im w for a complex λ.
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for (cl, (w, s)) in targets.iter().zip(tests) {
        let below = s.iter().filter(|&&v| v <= tol).count();
        let d = below.min(s.len().saturating_sub(1));
        let step = r.decisions.len();
        r.decisions.push(pbh_decision(
            stage,
            step,
            (k, k + r.b.ncols()),
            &s,
            tol,
            s.len() - d,
        ));
        for wj in &w[s.len() - d..] {
            basis.push(wj.iter().map(|v| v.re).collect());
            if cl.mean.im != 0.0 {
                basis.push(wj.iter().map(|v| v.im).collect());
            }
        }
    }
    if basis.is_empty() || basis.len() >= k {
        return Ok(None);
    }
    let x = DMatrix::from_fn(k, basis.len(), |i, j| basis[j][i]);
    let (q, n2) = rotation_with_last(&x)?;
    let kept = k - n2;
    let at = q.transpose() * &r.a * &q;
    // The coupling blocks `Q2ᵀ A Q1`, `Q2ᵀ B` are zero by the decisions: dropping the
    // trailing part sets them to exact zeros.
    r.removed.extend(eigenvalues_of(
        &at.view((kept, kept), (n2, n2)).clone_owned(),
    )?);
    let q1 = q.columns(0, kept).clone_owned();
    r.a = at.view((0, 0), (kept, kept)).clone_owned();
    r.b = q1.transpose() * &r.b;
    r.c = &r.c * &q1;
    Ok(Some(q1))
}

/// The PBH test ([`cluster_pbh`]) at each cluster, in order. The clusters are independent
/// (each test starts from the same seed): on a large model they run on the threads of the
/// current pool, as many at once as threads, and as the memory limit allows — each holds a
/// complex `k × k` factor of `A − λI` ([`crate::budget`]).
fn cluster_tests(
    r: &Reduction,
    targets: &[Cluster],
    p: usize,
) -> Result<Vec<ClusterTest>, NumError> {
    let k = r.a.nrows();
    let per_test = crate::budget::product(&[k, k, 16]);
    let at_once = (crate::budget::limit() / per_test.max(1))
        .min(rayon::current_num_threads())
        .min(targets.len());
    if k < crate::linalg::PARALLEL_MIN || at_once < 2 {
        return targets
            .iter()
            .map(|cl| cluster_pbh(&r.a, &r.b, cl.mean, cl.size, p))
            .collect();
    }
    let mut tests = Vec::with_capacity(targets.len());
    for group in targets.chunks(at_once) {
        let done: Vec<Result<ClusterTest, NumError>> = group
            .par_iter()
            .map(|cl| cluster_pbh(&r.a, &r.b, cl.mean, cl.size, p))
            .collect();
        for t in done {
            tests.push(t?);
        }
    }
    Ok(tests)
}

/// The directions of one cluster and their singular values (see [`cluster_pbh`]).
type ClusterTest = (Vec<Vec<Complex64>>, Vec<f64>);

/// The decision of the PBH pass at one cluster: the listed (smallest) singular values and
/// how many of them were kept.
fn pbh_decision(
    stage: RankStage,
    step: usize,
    (rows, cols): (usize, usize),
    listed: &[f64],
    tolerance: f64,
    rank: usize,
) -> RankDecision {
    let gap = (rank > 0 && rank < listed.len()).then(|| listed[rank - 1] / listed[rank]);
    RankDecision {
        stage,
        step,
        rows,
        cols,
        singular_values: listed.to_vec(),
        tolerance,
        rank,
        gap,
    }
}
