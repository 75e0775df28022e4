//! # eom-sym — symbolic core of eom
//!
//! eom-sym turns a multibody model whose numbers are **symbols with nominal values** into the
//! linearized equations of motion, as exact expressions and as numbers, by one algorithm
//! written once for every scalar type.
//!
//! ```
//! use eom_sym::model::*;
//! use eom_sym::Expr;
//!
//! // A swivel wheel (Schwab & Meijaard's shimmy): a body pulled at speed u, a lateral spring
//! // ahead of its mass centre, a tyre that cannot slip sideways behind it.
//! let mut m = Model::new("shimmy");
//! let mass = m.param("m", 5.0).unwrap();
//! let iz = m.param("I", 1.05).unwrap();
//! let k = m.param("k", 1.5).unwrap();
//! let a = m.param("a", 0.5).unwrap();
//! let b = m.param("b", 0.5).unwrap();
//! let u = m.param("u", 10.0).unwrap();
//! m.add(Body::new("chassis").mass(mass).moments(vec3(0, 0, iz)).velocity(vec3(u, 0, 0)));
//! m.add(FlexPoint::new("spring").between("chassis", "ground").at(vec3(b, 0, 0)).forces(1).axis(y_axis()).stiffness(k, 0));
//! m.add(NhPoint::new("tyre").between("chassis", "ground").at(vec3(-a, 0, 0)).forces(1).axis(y_axis()));
//! m.add(RigidPoint::new("road").between("chassis", "ground").forces(1).moments(2).axis(z_axis()));
//! m.add(RigidPoint::new("speed").between("chassis", "ground").forces(1).axis(x_axis()));
//!
//! // Symbolic: the state matrix as expressions (3 states: y, ψ and the yaw rate — the four
//! // pinned coordinates were removed before any algebra).
//! let sym = Linearizer::new(&m).symbolic().unwrap();
//! let ss = sym.state_space();
//! assert_eq!(ss.a.nrows(), 3);
//! assert_eq!(ss.a[(2, 2)], -(mass * a * u) / (iz + mass * a * a));
//!
//! // Numeric: evaluated at other parameter values, in nanoseconds per entry.
//! let at = m.scope.values_with(&[("u", 1.0)]).unwrap();
//! let num = sym.evaluate(&at).unwrap();
//! let eig = eom_num::modes::eigenvalues(&num.a).unwrap();
//! // The characteristic polynomial (I + m a²)s³ + m a u s² + k l² s + k l u has the root
//! // −1.0548225773209977 at these values (reference-cases §B).
//! assert!((eig[0].re + 1.0548225773209977).abs() < 1e-12);
//! ```
//!
//! ## The pieces
//!
//! * **Expressions** ([`Expr`], [`pool`]): a hash-consed DAG in a thread-local pool; every
//!   unique node is stored once and handles are 4-byte ids. Smart constructors keep sums and
//!   products flattened, sorted and collected, fold exact rationals ([`Rational`]), and apply
//!   only identities that are safe (the table in [`pool`]). Nothing is ever expanded.
//!   [`parse`] reads expressions as people write them; [`display`] prints them back (plain
//!   text that re-parses to the same node, and LaTeX).
//! * **Evaluation** (guide: [`tutorials::_01_evaluation`]): a compiled [`Tape`] (no allocation per call, batch form for sweeps), the
//!   same tape as machine code ([`NativeTape`], x86-64 Unix: no compiler needed, identical
//!   values, about twice as fast on large tapes), and
//!   [`eval_generic`] in any [`Elementary`] scalar — `f64`, double-double [`Dd`] (the accuracy
//!   reference), or [`Expr`] itself (substitution, [`Expr::subs`]). [`Expr::diff`] gives
//!   derivatives for sensitivities.
//!   Every `f64` path uses eom's own [`trig::sin`] and [`trig::cos`] (within an ulp, no
//!   range branches), so all of them agree bit for bit.
//! * **The [`Scalar`] trait**: the assembly and elimination are generic over it. Structural
//!   decisions come from [`Scalar::is_zero`] and [`Scalar::nominal`], so the symbolic, `f64`
//!   and double-double runs make the same decisions and agree by construction.
//! * **Matrices** ([`SparseMatrix`]): only structural non-zeros are stored, sums of products
//!   are single n-ary nodes, and the sparsity is visible to the elimination and to code
//!   generation. [`zero`] recognises sums that are identically zero although not
//!   structurally (randomized identity testing in double-double).
//! * **Models** ([`model`]): items as in eom-method §1 with builders; [`model::assemble`]
//!   (mass, loads and load stiffness, springs, bushings, beams, holonomic and nonholonomic
//!   constraints, the static preload solution, tangent stiffness, gyroscopic terms, inputs
//!   and outputs); [`model::reduce`] (structure-first symbolic-numeric elimination with
//!   pivots chosen at the nominal point and recorded, plus validity checks);
//!   [`model::reduce_robust`] (orthonormal complements, the independent numeric reference);
//!   [`model::Linearizer`] to reach all of them in one call.
//! * **Simplification** ([`simplify`]): a bounded egg pass over whole matrices that is kept
//!   only when the shared (DAG) cost drops, and a rational-function normal form for small
//!   closed forms.

#![warn(missing_docs)]

pub mod dd;
pub mod diff;
pub mod display;
pub mod error;
pub mod expr;
pub mod matrix;
pub mod model;
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
pub mod trig;
pub mod tutorials;
pub mod zero;

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
pub use tape::{NativeTape, Tape, TapeWorkspace, eval_generic, eval_nominal};
