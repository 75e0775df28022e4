//! Tutorials: narrative guides with examples that run as tests.
//!
//! * [`_01_evaluation`]: four ways to evaluate expressions for new parameter values, from a
//!   one-off value to code compiled ahead of time, and how to choose.

/// # Evaluating expressions: four ways, one set of values
///
/// A model's matrices are expressions over its parameters. Evaluating them for new parameter
/// values is the inner loop of sweeps, optimisation and controllers, and eom offers four
/// ways. All compute in `f64` with the same operations, so the first three agree bit for bit
/// and the fourth to rounding.
///
/// ```
/// use eom_sym::{Expr, NativeTape, Tape, TapeWorkspace, eval_generic};
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
///
/// // 3. Many more times: the same tape as machine code (x86-64 Unix), identical values.
/// if let Ok(native) = NativeTape::new(&tape) {
///     let mut fast = [0.0; 3];
///     native.eval(&values, &mut fast, &mut ws).unwrap();
///     assert_eq!(fast, out);
/// }
/// ```
///
/// 4. **Ahead of time**: `eom-codegen` writes a model's A, B, C, D as Rust source
///    (`no_std`-ready, with the validity checks of the symbolic reduction), for a `build.rs`
///    or to commit into a controller's crate.
///
/// ## Which one
///
/// | | set-up | per evaluation (bicycle A..D, 27 parameters) | use it for |
/// |---|---|---|---|
/// | [`eval_generic`](crate::eval_generic) | none | ≈ 70× the tape (memoised recursion) | a value now, a reference in [`Dd`](crate::Dd) |
/// | [`Tape`](crate::Tape) | µs to ms (linear) | ≈ 0.6 µs | sweeps, any platform |
/// | [`NativeTape`](crate::NativeTape) | ≈ 0.25 µs per instruction | ≈ 0.2 µs | long sweeps, optimisation loops |
/// | generated code | a compile | 70–100 ns | controllers, embedded targets |
///
/// (Measured on a 2-core VM: `cargo bench -p tests --bench codegen`; the large random DAG of
/// `cargo run --release -p eom-sym --example tape_timing` gives 4.2 ns per node interpreted
/// and 1.83–1.91 ns per node native.)
///
/// ## Why the tape is fast
///
/// * The DAG is lowered to binary instructions in the recursive evaluator's order (so the
///   values are identical), identical instructions once.
/// * The interpreter runs instructions in runs of one operation, so each run is a tight
///   loop: dispatching instruction by instruction would cost a mispredicted branch on most
///   of them.
/// * [`NativeTape`](crate::NativeTape) goes further: no dispatch at all, values in registers
///   (evicting the one needed furthest ahead), results stored only when something reads them
///   back from memory.
/// * `sin` and `cos` are eom's own ([`trig`](crate::trig)): within an ulp, and about twice as
///   fast as the system's on the arguments of a random DAG.
pub mod _01_evaluation {}
