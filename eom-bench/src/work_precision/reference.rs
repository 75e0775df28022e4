//! The reference of one model at one point: the symbolic state matrix evaluated in
//! double-double arithmetic (the exact value of the formulas to ~1e-32, the parameters taken
//! exactly as the `f64` values every method sees), and its eigenvalues: those of A rounded to
//! `f64` (structural zeros deflated exactly, see `eom_num::deflate`), each refined to
//! double-double accuracy by Newton's method on the double-double A
//! (`eom_sym::dd::refine_eigenvalue`).

use super::WorkPrecisionError;
use eom_model::SymbolicStateSpace;
use eom_sym::Dd;
use eom_sym::dd::refine_eigenvalue;
use eom_sym::tape::eval_generic;
use nalgebra::DMatrix;
use num_complex::Complex64;
use std::collections::HashMap;

/// Reference values at one point.
#[derive(Clone, Debug)]
pub struct Reference {
    /// A evaluated in double-double, rounded to `f64`.
    pub a: DMatrix<f64>,
    /// Eigenvalues of A (structural zeros exactly 0), refined where Newton's method settles.
    pub eigenvalues: Vec<Complex64>,
    /// How many non-zero eigenvalues did not settle under refinement (multiple eigenvalues)
    /// and are the `f64` eigenvalues of the rounded A.
    pub unrefined: usize,
}

/// Evaluates the symbolic A of a model in double-double.
pub struct ReferenceModel<'a> {
    sym: &'a SymbolicStateSpace,
    /// Parameter position in the value vector by pool index.
    pos: HashMap<u32, usize>,
}

impl<'a> ReferenceModel<'a> {
    /// The reference of the symbolic state space `sym` (parameters in the order of
    /// `sym.params`).
    pub fn new(sym: &'a SymbolicStateSpace) -> Self {
        let pos = sym
            .params
            .iter()
            .enumerate()
            .filter_map(|(k, p)| Some((p.param_index()?, k)))
            .collect();
        ReferenceModel { sym, pos }
    }

    /// A in double-double at `values`, as rows.
    pub fn a_dd(&self, values: &[f64]) -> Result<Vec<Vec<Dd>>, WorkPrecisionError> {
        let a = &self.sym.state_space().a;
        let n = a.nrows();
        let roots: Vec<eom_sym::Expr> = a.iter().copied().collect();
        let dd = eval_generic::<Dd>(&roots, |i| {
            self.pos.get(&i).map(|&k| Dd::from_f64(values[k]))
        })?;
        // Column-major.
        Ok((0..n)
            .map(|i| (0..n).map(|j| dd[i + j * n]).collect())
            .collect())
    }

    /// B in double-double at `values`, as rows.
    pub fn b_dd(&self, values: &[f64]) -> Result<Vec<Vec<Dd>>, WorkPrecisionError> {
        let b = &self.sym.state_space().b;
        let (n, m) = (b.nrows(), b.ncols());
        let roots: Vec<eom_sym::Expr> = b.iter().copied().collect();
        let dd = eval_generic::<Dd>(&roots, |i| {
            self.pos.get(&i).map(|&k| Dd::from_f64(values[k]))
        })?;
        Ok((0..n)
            .map(|i| (0..m).map(|j| dd[i + j * n]).collect())
            .collect())
    }

    /// The reference at `values`.
    pub fn at(&self, values: &[f64]) -> Result<Reference, WorkPrecisionError> {
        let rows = self.a_dd(values)?;
        let n = rows.len();
        let a = DMatrix::from_fn(n, n, |i, j| rows[i][j].to_f64());
        if a.iter().any(|x| !x.is_finite()) {
            return Err(WorkPrecisionError::Reference(format!(
                "A is not finite at {values:?}"
            )));
        }
        // The starting values from faer's solver, not the small-matrix kernel that the chart
        // grades: where Newton's method does not settle, the reference keeps them.
        let mut approx = vec![Complex64::new(0.0, 0.0); n];
        let mut ws = eom_num::modes::EigenvaluesWorkspace::new(n);
        eom_num::modes::eigenvalues_faer_in(&a, &mut ws, &mut approx)?;
        let mut eigenvalues = Vec::with_capacity(n);
        let mut unrefined = 0;
        for z in &approx {
            if *z == Complex64::new(0.0, 0.0) || z.im < 0.0 {
                // Exact zeros stay; a conjugate is taken from its partner below.
                eigenvalues.push(*z);
                continue;
            }
            match refine_eigenvalue(&rows, (z.re, z.im)) {
                Some((re, im))
                    if (Complex64::new(re.to_f64(), im.to_f64()) - z).norm() <= 1e-6 * z.norm() =>
                {
                    let im = if z.im == 0.0 { 0.0 } else { im.to_f64() };
                    eigenvalues.push(Complex64::new(re.to_f64(), im));
                }
                // Did not settle, or settled on another eigenvalue.
                _ => {
                    unrefined += 1;
                    eigenvalues.push(*z);
                }
            }
        }
        // The conjugates of the refined upper-half-plane eigenvalues.
        for k in 0..n {
            if approx[k].im < 0.0 {
                let partner = (0..n).filter(|&j| approx[j].im > 0.0).min_by(|&x, &y| {
                    (approx[x].conj() - approx[k])
                        .norm()
                        .total_cmp(&(approx[y].conj() - approx[k]).norm())
                });
                if let Some(j) = partner {
                    eigenvalues[k] = eigenvalues[j].conj();
                }
            }
        }
        Ok(Reference {
            a,
            eigenvalues,
            unrefined,
        })
    }
}
