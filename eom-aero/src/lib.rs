//! # eom-aero — quasi-steady wing aerodynamics
//!
//! (crate docs written below)

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod avl_input;
pub mod avl_output;
pub mod derivatives;
pub mod error;
pub mod geometry;
mod kernel;
mod lattice;
pub mod solver;
pub mod spacing;
pub mod stability;
pub mod validity;

pub use avl_input::{parse_avl, read_avl};
pub use avl_output::{AvlOutput, AvlOutputKind};
pub use derivatives::{Derivatives, Reference, StabilityDerivatives};
pub use error::{AeroError, Result};
pub use geometry::{Configuration, Section, Surface, Symmetry};
pub use solver::{LatticeSize, Solution, SolverOptions, Totals, solve};
pub use spacing::Spacing;
pub use stability::BodyDerivatives;
