//! Evaluation: a compiled [`Tape`] for fast repeated `f64` evaluation, and
//! [`eval_generic`] for evaluation in any [`Elementary`](crate::Elementary) scalar
//! (double-double references, substitution of expressions).
//!
//! A tape is the straight-line code of a set of roots ([`lower`](crate::lower), with
//! [`Rounding::Exact`]) as a register program of unary and binary instructions over one `f64`
//! work buffer, which holds the parameters, then the constants, then one slot per instruction;
//! every instruction reads earlier slots only. The lowering keeps the order of operations of
//! [`eval_generic`], so the tape computes the same values bit for bit. Identical instructions
//! (the same operation on the same slots) are emitted once: a sum that extends another sum
//! term by term in the same order, the `x²` of several products, reuse them.
//! [`Tape::new_reassociating`] interprets the code generator's lowering instead
//! ([`Rounding::Free`]), which removes more operations and rounds differently.
//!
//! The instructions are then scheduled into runs of one operation, each run a tight loop:
//! interpreting instruction by instruction would cost a mispredicted indirect branch on almost
//! every instruction, more than the arithmetic. Evaluation allocates nothing; the work buffer
//! is the caller's ([`Tape::eval_into`]) or kept in a [`TapeWorkspace`].

mod build;
mod exec;
mod generic;

pub use generic::{eval_generic, eval_nominal};

use crate::error::SymError;
use crate::expr::Expr;
use crate::lower::{Rounding, lower};
use build::{Builder, REF_PARAM};
use exec::{Args, Block, LANES, Lane, exec};

/// A compiled evaluation program for a set of root expressions.
#[derive(Clone, Debug)]
pub struct Tape {
    params: Vec<u32>,
    param_names: Vec<String>,
    /// Values of the constant slots (after the parameters).
    consts: Vec<f64>,
    /// The program: runs of one operation over consecutive entries of `args`.
    blocks: Vec<Block>,
    args: Vec<Args>,
    outputs: Vec<u32>,
    /// Unique nodes of the DAG compiled (for reporting).
    nodes: usize,
}

/// Reusable work buffer for [`Tape::eval`].
#[derive(Clone, Debug, Default)]
pub struct TapeWorkspace {
    work: Vec<f64>,
    /// Structure-of-arrays buffer of [`Tape::eval_batch`]: one slot holds `LANES` points.
    lanes: Vec<[f64; LANES]>,
}

impl Tape {
    /// Compile `roots` for evaluation with parameter values supplied in the order of `params`
    /// (which must be parameter expressions). A root that depends on a parameter not in
    /// `params` is an error naming it; so is an invalid root. The tape computes exactly the
    /// values of [`eval_generic`]`::<f64>`.
    pub fn new(roots: &[Expr], params: &[Expr]) -> Result<Tape, SymError> {
        Tape::compile(roots, params, Rounding::Exact)
    }

    /// [`Tape::new`] from the code generator's lowering ([`Rounding::Free`]): sums with their
    /// terms merged, shared monomials, powers and reciprocals, common pairs of operands. This
    /// removes operations that canonical flattening duplicates, at the price of values that
    /// differ from [`eval_generic`]'s in the rounding of sums and products (within the same
    /// error bounds; on an ill-conditioned DAG the difference can be large) and a slower
    /// compilation.
    pub fn new_reassociating(roots: &[Expr], params: &[Expr]) -> Result<Tape, SymError> {
        Tape::compile(roots, params, Rounding::Free)
    }

    fn compile(roots: &[Expr], params: &[Expr], rounding: Rounding) -> Result<Tape, SymError> {
        let mut param_index = Vec::with_capacity(params.len());
        let mut param_names = Vec::with_capacity(params.len());
        for (k, p) in params.iter().enumerate() {
            let info = p.param_info().ok_or_else(|| {
                SymError::Dimension(format!("tape parameter {k} (`{p}`) is not a parameter"))
            })?;
            param_index.push(p.param_index().expect("a parameter"));
            param_names.push(info.name);
        }
        let lowered = lower(roots, params, &[], rounding)?;
        let (mut b, outputs) = Builder::program(&lowered);
        let outputs = b.prune(&outputs);
        b.normalise();
        let (np, nc) = (params.len() as u32, b.consts.len() as u32);
        let base = np + nc;
        if base as usize + b.code.len() >= REF_PARAM as usize {
            return Err(SymError::Unsupported(format!(
                "a tape of {} instructions and {nc} constants is too large",
                b.code.len()
            )));
        }
        let (order, blocks) = build::schedule(&b.code);
        let (args, slot) = build::layout(&b.code, &order, np, nc);
        debug_assert!(args.iter().enumerate().all(|(k, g)| {
            let own = base + k as u32;
            g.a < own && g.b < own && g.c < own
        }));
        Ok(Tape {
            params: param_index,
            param_names,
            consts: b.consts,
            blocks,
            args,
            outputs: outputs.into_iter().map(slot).collect(),
            nodes: Expr::dag_size(roots),
        })
    }

    /// Number of parameters expected.
    pub fn n_params(&self) -> usize {
        self.params.len()
    }
    /// Names of the parameters, in the order values are expected.
    pub fn param_names(&self) -> &[String] {
        &self.param_names
    }
    /// Number of outputs (roots).
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }
    /// Number of instructions (binary or unary operations).
    pub fn len(&self) -> usize {
        self.args.len()
    }
    /// Does the tape compute nothing (no roots, or roots that are parameters or constants)?
    pub fn is_empty(&self) -> bool {
        self.args.is_empty()
    }
    /// Number of unique nodes of the DAG compiled (numbers included).
    pub fn n_nodes(&self) -> usize {
        self.nodes
    }
    /// Length of the work buffer [`Tape::eval_into`] needs.
    pub fn work_len(&self) -> usize {
        self.base() + self.args.len()
    }

    /// Slots before the first instruction's: parameters and constants.
    fn base(&self) -> usize {
        self.params.len() + self.consts.len()
    }

    /// The kernel: evaluate with a caller-provided work buffer, no allocation, no checks on the
    /// result. `values.len() == n_params()`, `out.len() == n_outputs()`,
    /// `work.len() >= work_len()`; otherwise an error.
    pub fn eval_into(
        &self,
        values: &[f64],
        out: &mut [f64],
        work: &mut [f64],
    ) -> Result<(), SymError> {
        self.check_lengths(values, out, work)?;
        self.run(values, work);
        for (o, &s) in out.iter_mut().zip(&self.outputs) {
            *o = work[s as usize];
        }
        Ok(())
    }

    /// The buffer lengths [`Tape::eval_into`] requires, or an error saying which is wrong.
    fn check_lengths(&self, values: &[f64], out: &[f64], work: &[f64]) -> Result<(), SymError> {
        if values.len() != self.params.len() {
            return Err(SymError::Dimension(format!(
                "{} parameter values given, the tape expects {} ({})",
                values.len(),
                self.params.len(),
                self.param_names.join(", ")
            )));
        }
        if out.len() != self.outputs.len() || work.len() < self.work_len() {
            return Err(SymError::Dimension(format!(
                "output buffer {} (expected {}), work buffer {} (expected ≥ {})",
                out.len(),
                self.outputs.len(),
                work.len(),
                self.work_len()
            )));
        }
        Ok(())
    }

    /// The number of points of a batch, or an error if the buffers do not match.
    fn batch_count(&self, points: &[f64], out: &[f64]) -> Result<usize, SymError> {
        let np = self.params.len().max(1);
        let no = self.outputs.len();
        let count = if self.params.is_empty() {
            out.len() / no.max(1)
        } else {
            points.len() / np
        };
        if (!self.params.is_empty() && points.len() != count * np) || out.len() != count * no {
            return Err(SymError::Dimension(format!(
                "batch of {} values / {} outputs does not match {} parameters and {} outputs per point",
                points.len(),
                out.len(),
                self.params.len(),
                no
            )));
        }
        Ok(count)
    }

    /// The parameters and constants into their slots (lengths checked by the callers).
    fn load_inputs(&self, values: &[f64], w: &mut [f64]) {
        let np = self.params.len();
        w[..np].copy_from_slice(values);
        w[np..self.base()].copy_from_slice(&self.consts);
    }

    /// One point; `values` and `w` have the lengths checked by the callers.
    #[inline]
    fn run(&self, values: &[f64], w: &mut [f64]) {
        self.load_inputs(values, w);
        exec(
            &self.blocks,
            &self.args,
            &mut w[..self.work_len()],
            self.base(),
        );
    }

    /// Evaluate, checking that every output is finite (an error names the first output that is
    /// not). The workspace grows on first use and is reused afterwards.
    pub fn eval(
        &self,
        values: &[f64],
        out: &mut [f64],
        ws: &mut TapeWorkspace,
    ) -> Result<(), SymError> {
        if ws.work.len() < self.work_len() {
            ws.work.resize(self.work_len(), 0.0);
        }
        self.eval_into(values, out, &mut ws.work)?;
        first_non_finite(out)
    }

    /// Evaluate into a new vector (allocates; convenient for one-off use).
    pub fn eval_vec(&self, values: &[f64]) -> Result<Vec<f64>, SymError> {
        let mut out = vec![0.0; self.outputs.len()];
        self.eval(values, &mut out, &mut TapeWorkspace::default())?;
        Ok(out)
    }

    /// Evaluate at many points: `points` holds `n_params()` values per point (row-major),
    /// `out` receives `n_outputs()` values per point. Non-finite outputs are an error naming
    /// the point and the output (the first in point order). Points are evaluated in chunks of
    /// 16, each instruction applied to the whole chunk; the results are identical to
    /// [`Tape::eval_into`] point by point, at a fraction of the cost per point.
    pub fn eval_batch(
        &self,
        points: &[f64],
        out: &mut [f64],
        ws: &mut TapeWorkspace,
    ) -> Result<(), SymError> {
        let np = self.params.len().max(1);
        let no = self.outputs.len();
        let count = self.batch_count(points, out)?;
        let n_params = self.params.len();
        let (base, len) = (self.base(), self.work_len());
        // Chunks of LANES points; a final remainder of fewer than LANES/4 points is cheaper
        // point by point than padded to a full chunk.
        let chunked = if count % LANES < LANES / 4 {
            count - count % LANES
        } else {
            count
        };
        if chunked > 0 {
            if ws.lanes.len() < len {
                ws.lanes.resize(len, [0.0; LANES]);
            }
            // Constants once for all chunks: instructions never write these slots.
            for (slot, &c) in ws.lanes[n_params..base].iter_mut().zip(&self.consts) {
                *slot = <[f64; LANES]>::splat(c);
            }
        }
        for first in (0..chunked).step_by(LANES) {
            let n = LANES.min(count - first);
            // Transpose the chunk; a partial chunk repeats its last point in the unused lanes.
            for (p, lane) in ws.lanes[..n_params].iter_mut().enumerate() {
                for (l, slot) in lane.iter_mut().enumerate() {
                    *slot = points[(first + l.min(n - 1)) * np + p];
                }
            }
            exec(&self.blocks, &self.args, &mut ws.lanes[..len], base);
            for l in 0..n {
                let k = first + l;
                for (j, &s) in self.outputs.iter().enumerate() {
                    let v = ws.lanes[s as usize][l];
                    if !v.is_finite() {
                        return Err(SymError::EvalNonFinite {
                            what: format!("output {j} at point {k}"),
                            value: v,
                        });
                    }
                    out[k * no + j] = v;
                }
            }
        }
        if chunked < count && ws.work.len() < len {
            ws.work.resize(len, 0.0);
        }
        for k in chunked..count {
            let vals = if self.params.is_empty() {
                &[][..]
            } else {
                &points[k * np..(k + 1) * np]
            };
            self.run(vals, &mut ws.work);
            for (j, &s) in self.outputs.iter().enumerate() {
                let v = ws.work[s as usize];
                if !v.is_finite() {
                    return Err(SymError::EvalNonFinite {
                        what: format!("output {j} at point {k}"),
                        value: v,
                    });
                }
                out[k * no + j] = v;
            }
        }
        Ok(())
    }
}

/// An error naming the first output that is not finite.
fn first_non_finite(out: &[f64]) -> Result<(), SymError> {
    match out.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((k, &v)) => Err(SymError::EvalNonFinite {
            what: format!("output {k}"),
            value: v,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::Rational;
    use crate::testing::{params, random_dag};
    use hashbrown::HashMap;

    /// Values bit for bit (NaN matching NaN).
    fn same(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    fn check(roots: &[Expr], ps: &[Expr], points: &[Vec<f64>]) {
        let tape = Tape::new(roots, ps).unwrap();
        let mut work = vec![0.0; tape.work_len()];
        let mut out = vec![0.0; tape.n_outputs()];
        for x in points {
            tape.eval_into(x, &mut out, &mut work).unwrap();
            let index: HashMap<u32, f64> = ps
                .iter()
                .zip(x)
                .map(|(p, &v)| (p.param_index().unwrap(), v))
                .collect();
            let want = eval_generic::<f64>(roots, |i| index.get(&i).copied()).unwrap();
            for (k, (&t, &g)) in out.iter().zip(&want).enumerate() {
                assert!(same(t, g), "output {k}: tape {t:e} vs eval_generic {g:e}");
            }
        }
    }

    /// The tape keeps the recursive evaluator's order of operations, so it computes the
    /// same values exactly, even on DAGs whose values are pure rounding noise (repeated
    /// squaring, sines of huge arguments) where any reassociation would show.
    #[test]
    fn tape_equals_the_recursive_evaluator_bit_for_bit() {
        for seed in 1..4 {
            let ps = params(6, seed, seed % 2 == 0);
            let roots = random_dag(&ps, 1500, 20, seed);
            let nominal: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
            let other: Vec<f64> = nominal.iter().map(|v| 1.3 * v - 0.2).collect();
            check(&roots, &ps, &[nominal, other]);
        }
        let ps = params(3, 9, true);
        let (x, y, z) = (ps[0], ps[1], ps[2]);
        let half = Rational::new(1, 2).unwrap();
        let roots = [
            x.powi(-3) * y.powi(5) + z.powi(70) * Expr::int(3) - x.powi(-70),
            (x * y).pow_rational(Rational::new(2, 3).unwrap())
                / (Expr::one() + z).pow_rational(half),
            (x * Expr::int(2) - y * Expr::int(3)).sqrt().recip() - x.pow(y)
                + y.atan2(x - Expr::one()),
            (x.cos() * y.tan() + z.exp() - (x + Expr::one()).ln()).abs() * Expr::pi(),
            -(x * y * z) - (x * y).recip() + Expr::int(5),
            x / (y * z.powi(2)) - x.sin() * Expr::int(7),
        ];
        check(
            &roots,
            &ps,
            &[
                vec![1.2, 0.7, 0.9],
                vec![0.4, 2.5, 1.1],
                vec![-0.3, 0.2, 3.0],
            ],
        );
    }

    /// Sharing by reassociation: sums and products that contain others computed by the tape
    /// start from them (also with a power-of-two multiple), and compute nearly the same values.
    #[test]
    fn reassociating_tape_shares_contained_sums_and_products() {
        let ps = params(5, 3, true);
        let (x, y, z, u, v) = (ps[0], ps[1], ps[2], ps[3], ps[4]);
        let s3 = z + u + v;
        let p3 = z * u * v;
        let roots = [
            s3,
            s3 + x + y,
            s3 * Expr::int(2) + x,
            p3,
            p3 * x * y * Expr::int(3),
            p3.sqrt(),
        ];
        let exact = Tape::new(&roots, &ps).unwrap();
        let shared = Tape::new_reassociating(&roots, &ps).unwrap();
        // x+y+z+u+v from the node z+u+v: 2 additions instead of 4; 2z+2u+2v+x: a
        // multiplication and an addition instead of 3 scaled additions; 3xyzuv: 3
        // multiplications instead of 5.
        assert!(
            shared.len() + 5 <= exact.len(),
            "{} vs {}",
            shared.len(),
            exact.len()
        );
        let pt = [0.3, 1.7, 0.4, 2.2, 0.9];
        let (a, b) = (exact.eval_vec(&pt).unwrap(), shared.eval_vec(&pt).unwrap());
        for (a, b) in a.iter().zip(&b) {
            assert!((a - b).abs() <= 1e-15 * a.abs(), "{a} vs {b}");
        }
        // A large DAG compiles to fewer instructions and evaluates.
        let ps = params(6, 1, true);
        let roots = random_dag(&ps, 1500, 20, 1);
        let (exact, shared) = (
            Tape::new(&roots, &ps).unwrap(),
            Tape::new_reassociating(&roots, &ps).unwrap(),
        );
        assert!(shared.len() < exact.len());
        let nominal: Vec<f64> = ps.iter().map(|p| p.nominal()).collect();
        let mut out = vec![0.0; shared.n_outputs()];
        let mut work = vec![0.0; shared.work_len()];
        shared.eval_into(&nominal, &mut out, &mut work).unwrap();
    }
}
