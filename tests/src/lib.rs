//! Shared helpers for the cross-crate tests: the reference data readers, eigenvalue matching
//! and the work-precision machinery live in `eom-bench` (the `eom bench` commands use them too).

pub use eom_bench::compare::*;
pub use eom_bench::work_precision;
