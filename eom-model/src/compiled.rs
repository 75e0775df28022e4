//! Fast evaluation of a symbolic state space: [`SymbolicStateSpace`] holds the expressions
//! of a symbolic [`Reduction`] and a compiled tape of every entry of A, B, C, D, the map to
//! physical coordinates and the validity checks; [`CompiledStateSpace`] is its numeric side
//! (no expressions, `Send + Sync`), evaluated at many points by the tape interpreter.

use crate::error::ModelError;
use crate::reduce::{CheckLabel, Reduction, ValidityCheck};
use eom_num::{SignalNames, StateSpace};
use eom_sym::SymError;
use eom_sym::expr::Expr;
use eom_sym::tape::Tape;
use nalgebra::DMatrix;

/// A symbolic state-space model with its validity region, compiled for evaluation.
#[derive(Clone, Debug)]
pub struct SymbolicStateSpace {
    /// The expressions.
    pub reduction: Reduction<Expr>,
    /// Parameters in the order values are given.
    pub params: Vec<Expr>,
    compiled: CompiledStateSpace,
    /// Keeps the expressions' pool alive as long as they are.
    pool: Option<eom_sym::ExprPool>,
}

/// Size of one symbolic matrix (see [`SymbolicStateSpace::sizes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MatrixSize {
    /// "A", "B", "C", "D" or "A..D".
    pub name: &'static str,
    /// Structural non-zeros.
    pub nonzeros: usize,
    /// Unique DAG nodes.
    pub nodes: usize,
    /// Operations of straight-line code evaluating every unique node once.
    pub operations: usize,
}

/// The numeric side of a [`SymbolicStateSpace`]: a compiled tape of every entry of A, B, C,
/// D and `phys` plus the validity checks. It holds no expressions, so it is `Send + Sync`
/// and can be shared by the threads of a parallel sweep.
#[derive(Clone, Debug)]
pub struct CompiledStateSpace {
    tape: Tape,
    shapes: [(usize, usize); 5],
    n_matrix: usize,
    check_layout: Vec<(usize, usize, bool)>,
    check_labels: Vec<CheckLabel>,
    names: SignalNames,
    param_names: Vec<String>,
}

impl SymbolicStateSpace {
    /// Compile a symbolic reduction for evaluation with parameter values in the order of
    /// `params`.
    pub fn new(mut reduction: Reduction<Expr>, params: &[Expr]) -> Result<Self, ModelError> {
        crate::canonical::canonical_columns(&mut reduction.state_space.a);
        let ss = &reduction.state_space;
        let mut roots: Vec<Expr> = Vec::new();
        let mut shapes = [(0, 0); 5];
        for (k, m) in [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys]
            .into_iter()
            .enumerate()
        {
            shapes[k] = (m.nrows(), m.ncols());
            roots.extend(m.iter().copied());
        }
        let n_matrix = roots.len();
        let mut layout = Vec::new();
        for c in &reduction.checks {
            let start = roots.len();
            match c {
                ValidityCheck::Pivot { value, row, .. } => {
                    roots.push(*value);
                    roots.extend(row.iter().copied());
                    layout.push((start, 1 + row.len(), true));
                }
                ValidityCheck::Negligible { value, scale, .. } => {
                    roots.push(*value);
                    roots.extend(scale.iter().copied());
                    layout.push((start, 1 + scale.len(), false));
                }
            }
        }
        let tape = Tape::new(&roots, params)?;
        let compiled = CompiledStateSpace {
            tape,
            shapes,
            n_matrix,
            check_layout: layout,
            check_labels: reduction.checks.iter().map(|c| c.label().clone()).collect(),
            names: ss.names.clone(),
            param_names: params.iter().map(|p| p.to_string()).collect(),
        };
        // 0, 1 and −1 have the same id (0, 1, 2) in every pool and name none.
        let pool = roots
            .iter()
            .chain(params)
            .find(|e| e.id() > 2)
            .and_then(|e| eom_sym::ExprPool::find(e.pool_serial()));
        Ok(SymbolicStateSpace {
            reduction,
            params: params.to_vec(),
            compiled,
            pool,
        })
    }

    /// The descriptor pencil `(E, F)` with `A = E⁻¹F`: `E = diag(I, M, I)` with the reduced
    /// mass matrix `M` (the last identity for the lag states, if any), `F` the kinematic and dynamic rows (see
    /// [`Reduction::descriptor`](crate::Reduction::descriptor)). Closed forms computed from
    /// it carry no nested divisions by `M`.
    pub fn pencil(&self) -> (DMatrix<Expr>, DMatrix<Expr>) {
        let d = &self.reduction.descriptor;
        let n = self.reduction.state_space.a.nrows();
        let (np, nw) = (d.kinematics.nrows(), d.mass.nrows());
        let mut e = DMatrix::from_element(n, n, Expr::zero());
        let mut f = DMatrix::from_element(n, n, Expr::zero());
        for i in 0..np {
            e[(i, i)] = Expr::one();
        }
        for (i, j, v) in d.mass.iter() {
            e[(np + i, np + j)] = v;
        }
        for (i, j, v) in d.kinematics.iter() {
            f[(i, j)] = v;
        }
        for (i, j, v) in d.dynamics.iter() {
            f[(np + i, j)] = v;
        }
        for i in np + nw..n {
            e[(i, i)] = Expr::one();
        }
        for (i, j, v) in d.lags.iter() {
            f[(np + nw + i, j)] = v;
        }
        debug_assert_eq!(np + nw + d.lags.nrows(), n);
        (e, f)
    }

    /// The pool of the expressions (`None` when every entry is a constant 0, 1 or −1).
    pub fn pool(&self) -> Option<&eom_sym::ExprPool> {
        self.pool.as_ref()
    }

    /// The expression state-space model.
    pub fn state_space(&self) -> &StateSpace<Expr> {
        &self.reduction.state_space
    }

    /// Size of the symbolic result per matrix: `(name, structural non-zeros, unique nodes,
    /// operations)` for A, B, C, D, and the totals with sharing across matrices (`"A..D"`).
    pub fn sizes(&self) -> Vec<MatrixSize> {
        let ss = &self.reduction.state_space;
        let mut out = Vec::new();
        let mut all = Vec::new();
        for (name, m) in [("A", &ss.a), ("B", &ss.b), ("C", &ss.c), ("D", &ss.d)] {
            let roots: Vec<Expr> = m.iter().copied().filter(|e| !e.is_zero()).collect();
            all.extend(roots.iter().copied());
            out.push(MatrixSize {
                name,
                nonzeros: roots.len(),
                nodes: Expr::dag_size(&roots),
                operations: Expr::op_count(&roots).total(),
            });
        }
        out.push(MatrixSize {
            name: "A..D",
            nonzeros: all.len(),
            nodes: Expr::dag_size(&all),
            operations: Expr::op_count(&all).total(),
        });
        out
    }

    /// The compiled numeric side (shareable across threads).
    pub fn compiled(&self) -> &CompiledStateSpace {
        &self.compiled
    }

    /// The compiled tape (matrix entries of A, B, C, D, phys column-major, then the checks).
    pub fn tape(&self) -> &Tape {
        &self.compiled.tape
    }

    /// Evaluate at parameter values (in the order of [`SymbolicStateSpace::params`]). Returns
    /// [`ModelError::PivotBreakdown`] naming the first check that fails instead of numbers when
    /// the point is outside the validity region.
    pub fn evaluate(&self, values: &[f64]) -> Result<StateSpace<f64>, ModelError> {
        self.compiled.evaluate(values)
    }
}

/// Reusable buffers for [`CompiledStateSpace::evaluate_with`].
#[derive(Clone, Debug, Default)]
pub struct EvalWorkspace {
    out: Vec<f64>,
    work: Vec<f64>,
}

impl CompiledStateSpace {
    /// Parameter names in the order values are given.
    pub fn param_names(&self) -> &[String] {
        &self.param_names
    }

    /// Number of states.
    pub fn states(&self) -> usize {
        self.shapes[0].0
    }

    /// Evaluate at parameter values (see [`SymbolicStateSpace::evaluate`]).
    pub fn evaluate(&self, values: &[f64]) -> Result<StateSpace<f64>, ModelError> {
        self.evaluate_with(values, &mut EvalWorkspace::default())
    }

    /// [`CompiledStateSpace::evaluate`] reusing the buffers of `ws`.
    pub fn evaluate_with(
        &self,
        values: &[f64],
        ws: &mut EvalWorkspace,
    ) -> Result<StateSpace<f64>, ModelError> {
        let out = self.run(values, ws)?;
        let mut k = 0;
        let mut take = |(r, c): (usize, usize)| {
            let m = DMatrix::from_column_slice(r, c, &out[k..k + r * c]);
            k += r * c;
            m
        };
        let a = take(self.shapes[0]);
        let b = take(self.shapes[1]);
        let c = take(self.shapes[2]);
        let d = take(self.shapes[3]);
        let phys = take(self.shapes[4]);
        Ok(StateSpace {
            a,
            b,
            c,
            d,
            phys,
            names: self.names.clone(),
        })
    }

    /// The number of entries of A, B, C and D together: the length of the slice
    /// [`CompiledStateSpace::evaluate_into`] fills per point.
    pub fn abcd_len(&self) -> usize {
        self.shapes[..4].iter().map(|(r, c)| r * c).sum()
    }

    /// A, B, C, D at a point written into `out` (length [`CompiledStateSpace::abcd_len`]):
    /// one after the other, each row-major (NumPy's order), the same numbers as
    /// [`CompiledStateSpace::evaluate`] with the same validity checks, and no allocation
    /// once `ws` has grown. The inner loop of a sweep that writes straight into the caller's
    /// buffers (one slice per point, split across threads). `out` is left unspecified when
    /// an error is returned.
    ///
    /// # Panics
    /// When `out.len()` is not [`CompiledStateSpace::abcd_len`] (as `copy_from_slice`).
    pub fn evaluate_into(
        &self,
        values: &[f64],
        ws: &mut EvalWorkspace,
        out: &mut [f64],
    ) -> Result<(), ModelError> {
        assert_eq!(
            out.len(),
            self.abcd_len(),
            "evaluate_into: the output slice must hold A, B, C and D"
        );
        let tape = self.run(values, ws)?;
        let mut dst = 0;
        let mut src = 0;
        for &(r, c) in &self.shapes[..4] {
            // The tape holds each matrix column-major.
            let m = &tape[src..src + r * c];
            for i in 0..r {
                for j in 0..c {
                    out[dst] = m[j * r + i];
                    dst += 1;
                }
            }
            src += r * c;
        }
        Ok(())
    }

    /// The tape at `values` into `ws.out`, checked: the first validity check that fails is a
    /// [`ModelError::PivotBreakdown`], a non-finite matrix entry an error naming it.
    fn run<'w>(&self, values: &[f64], ws: &'w mut EvalWorkspace) -> Result<&'w [f64], ModelError> {
        ws.out.resize(self.tape.n_outputs(), 0.0);
        ws.work.resize(self.tape.work_len(), 0.0);
        self.tape.eval_into(values, &mut ws.out, &mut ws.work)?;
        let out = &ws.out;
        for ((start, len, pivot), label) in self.check_layout.iter().zip(&self.check_labels) {
            let v = out[*start];
            let others = &out[start + 1..start + len];
            if !ValidityCheck::<f64>::holds(v, others, *pivot) {
                return Err(ModelError::PivotBreakdown {
                    check: label.to_string(),
                    value: v,
                    row_max: others.iter().fold(0.0f64, |a, b| a.max(b.abs())),
                });
            }
        }
        if let Some(k) = out[..self.n_matrix].iter().position(|v| !v.is_finite()) {
            return Err(SymError::EvalNonFinite {
                what: format!("state-space entry {k}"),
                value: out[k],
            }
            .into());
        }
        Ok(out)
    }

    /// Only the state matrix A at a point, with the validity checks (the inner loop of a sweep).
    pub fn evaluate_a(
        &self,
        values: &[f64],
        ws: &mut EvalWorkspace,
    ) -> Result<DMatrix<f64>, ModelError> {
        let out = self.run(values, ws)?;
        let (r, c) = self.shapes[0];
        Ok(DMatrix::from_column_slice(r, c, &out[..r * c]))
    }
}
