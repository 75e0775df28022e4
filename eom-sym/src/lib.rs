//! # eom-sym — symbolic core of eom
//!
//! (Narrative crate documentation to be written.)

#![warn(missing_docs)]

pub mod dd;
pub mod diff;
pub mod display;
pub mod error;
pub mod expr;
pub mod matrix;
pub mod parse;
pub mod pool;
pub mod rational;
pub mod scalar;
pub mod scope;
pub mod simplify;
pub mod subs;
pub mod model;
pub mod tape;
pub mod zero;
#[doc(hidden)]
pub mod testing;

pub use dd::Dd;
pub use diff::diff_many;
pub use display::{ExprMatrix, Latex, display_matrix, latex_matrix};
pub use error::SymError;
pub use expr::{Expr, ExprView, OpCount};
pub use matrix::{SparseMatrix, Triplets};
pub use parse::parse;
pub use pool::{Assumption, Constant, ExprPool, Func, ParamInfo, PoolStats, Sign};
pub use rational::Rational;
pub use scalar::{Elementary, Scalar};
pub use scope::Scope;
pub use simplify::{CostModel, Simplifier, SimplifyOutcome, normalize_rational};
pub use subs::subs_many;
pub use tape::{Tape, TapeWorkspace, eval_generic, eval_nominal};
