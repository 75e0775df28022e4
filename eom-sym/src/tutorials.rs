//! Tutorials: narrative guides with examples that run as tests.
//!
//! * [`_01_evaluation`]: three ways to evaluate expressions for new parameter values, from a
//!   one-off value to code compiled ahead of time, and how to choose.

/// # Evaluating expressions: three ways, one set of values
///
/// A model's matrices are expressions over its parameters. Evaluating them for new parameter
/// values is the inner loop of sweeps, optimisation and controllers, and eom offers three
/// ways. All compute in `f64`; the first two with the same operations, so they agree bit for
/// bit, and the third to rounding.
///
/// ```
/// use eom_sym::{Expr, Tape, TapeWorkspace, eval_generic};
///
/// let m = Expr::param("m", 2.0).unwrap();
/// let k = Expr::param("k", 8.0).unwrap();
/// let c = Expr::param("c", 0.4).unwrap();
/// let wn = (k / m).sqrt();
/// let zeta = c / (Expr::int(2) * (k * m).sqrt());
/// let roots = [wn, zeta, -(zeta * wn)];
///
/// // 1. One-off: the recursive evaluator, in any scalar (f64 here; `Dd` for a
/// //    double-double reference). Looks parameters up by pool index.
/// let values = [2.0, 8.0, 0.4];
/// let at = |i: u32| [m, k, c].iter().position(|p| p.param_index() == Some(i)).map(|j| values[j]);
/// let once = eval_generic::<f64>(&roots, at).unwrap();
///
/// // 2. Many times: compile a tape once, evaluate with no allocation per call.
/// let tape = Tape::new(&roots, &[m, k, c]).unwrap();
/// let mut out = [0.0; 3];
/// let mut ws = TapeWorkspace::default();
/// tape.eval(&values, &mut out, &mut ws).unwrap(); // errors on a non-finite output
/// assert_eq!(out, once.as_slice());
/// ```
///
/// 3. **Ahead of time**: `eom-codegen` writes a model's A, B, C, D as Rust source
///    (`no_std`-ready, with the validity checks of the symbolic reduction), for a `build.rs`
///    or to commit into a controller's crate.
///
/// ## Which one
///
/// | | set-up | per evaluation | use it for |
/// |---|---|---|---|
/// | [`eval_generic`](crate::eval_generic) | none | slowest (memoised recursion, allocations) | a value now, a reference in [`Dd`](crate::Dd) |
/// | [`Tape`](crate::Tape) | linear in the DAG | interpreted, no allocation | sweeps, optimisation loops, any platform |
/// | generated code | a compile | fastest (straight-line code the compiler optimises) | controllers, embedded targets |
///
/// The figures for the bicycle and the other models are measured by
/// `cargo bench -p tests --bench codegen`, and for a large random DAG by
/// `cargo run --release -p eom-sym --example tape_timing`.
///
/// ## Why the tape is fast
///
/// * The DAG is lowered to straight-line code ([`lower`](crate::lower)) in the recursive
///   evaluator's order (so the values are identical), identical instructions once.
/// * The interpreter runs instructions in runs of one operation, so each run is a tight
///   loop: dispatching instruction by instruction would cost a mispredicted branch on most
///   of them.
pub mod _01_evaluation {}
