//! Shared helpers for the cross-crate tests: the models' reference answers
//! ([`references`], the sidecars `models/NAME.ref.toml`, also read by eom-cli's tests); the
//! reference data readers, eigenvalue matching and the work-precision machinery live in
//! `eom-bench` (the `eom bench` commands use them too).

pub mod references;

pub use eom_bench::compare::*;
pub use eom_bench::work_precision;
