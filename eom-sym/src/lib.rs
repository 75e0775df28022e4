//! # eom-sym — symbolic core of eom
//!
//! eom-sym is the expression engine of eom: symbols with nominal values, exact arithmetic on a
//! hash-consed DAG, evaluation, derivatives and bounded simplification. It knows nothing of
//! multibody models (those are `eom-model`'s) and depends on no other eom crate.
//!
//! ```
//! use eom_sym::Expr;
//!
//! // Parameters are symbols with nominal values; expressions are built with operators.
//! let m = Expr::param("m", 4.0).unwrap();
//! let k = Expr::param("k", 1.5).unwrap();
//! let wn2 = k / m;
//! assert_eq!(wn2.nominal(), 0.375);
//! // Sums and products are kept in one canonical form as they are built: nothing is expanded.
//! assert_eq!(m * k + k * m, Expr::int(2) * k * m);
//! ```
//!
//! ## The pieces
//!
//! * **Expressions** ([`Expr`], [`pool`]): a hash-consed DAG in an [`ExprPool`]; every unique
//!   node is stored once, and a handle is the node's id with its pool's serial number. Pools
//!   are values ([`context`]): a model owns its pool and frees it when dropped, and
//!   expressions work on any thread. Smart constructors keep sums and
//!   products flattened, sorted and collected, fold exact rationals ([`Rational`]), and apply
//!   only identities that are safe (the table in [`pool`]). Nothing is ever expanded.
//!   [`parse`] reads expressions as people write them; [`display`] prints them back (plain
//!   text that re-parses to the same node, and LaTeX).
//! * **Evaluation** (guide: [`tutorials::_01_evaluation`]): a compiled [`Tape`] (no
//!   allocation per call, batch form for sweeps) and [`eval_generic`] in any [`Elementary`]
//!   scalar — `f64`, double-double [`Dd`] (the accuracy reference), or [`Expr`] itself
//!   (substitution, [`Expr::subs`]). [`Expr::diff`] gives derivatives for sensitivities.
//!   Every `f64` path (the tape, `eval_generic`, nominal values) evaluates a node through the
//!   one definition of its shape and its functions ([`func`]), so all of them agree bit for
//!   bit.
//! * **Lowering** ([`lower`]): the DAG as straight-line code, shared by the tape (which
//!   interprets it) and the code generator of `eom-codegen` (which renders it as Rust).
//! * **The [`Scalar`] trait**: the assembly and elimination are generic over it. Structural
//!   decisions come from [`Scalar::is_zero`] and [`Scalar::nominal`], so the symbolic, `f64`
//!   and double-double runs make the same decisions and agree by construction.
//! * **Matrices** ([`SparseMatrix`]): only structural non-zeros are stored, sums of products
//!   are single n-ary nodes, and the sparsity is visible to the elimination and to code
//!   generation. [`zero`] recognises sums that are identically zero although not
//!   structurally (randomized identity testing in double-double).
//! * **Simplification** ([`simplify`]): a bounded egg pass over whole matrices that is kept
//!   only when the shared (DAG) cost drops, and a rational-function normal form for small
//!   closed forms.

#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod closed;
pub mod context;
pub mod dd;
pub mod diff;
pub mod display;
pub mod error;
pub mod expr;
pub mod func;
pub mod lower;
pub mod matrix;
pub mod parse;
pub mod pool;
pub mod rational;
pub mod scalar;
pub mod scope;
pub mod simplify;
pub mod subs;
pub mod tape;
#[doc(hidden)]
pub mod testing;
pub mod tutorials;
pub mod zero;

pub use context::ExprPool;
pub use dd::Dd;
pub use diff::diff_many;
pub use display::{ExprMatrix, Latex, display_matrix, latex_matrix};
pub use error::SymError;
pub use expr::{Expr, ExprView, OpCount};
pub use func::{Call, Func, Parity};
pub use matrix::{SparseMatrix, Triplets};
pub use parse::parse;
pub use pool::{Assumption, Constant, ParamInfo, PoolStats, Sign};
pub use rational::Rational;
pub use scalar::{Elementary, Scalar};
pub use scope::Scope;
pub use simplify::{CostModel, Simplifier, SimplifyOutcome, normalize_rational};
pub use subs::subs_many;
pub use tape::{Tape, TapeWorkspace, eval_generic, eval_nominal};
