//! Benchmarks a user can run on their own machine, behind `eom bench`:
//!
//! * [`work_precision`] (`eom bench accuracy`): every way eom offers to get a model's
//!   eigenvalues — the numeric and robust reductions, the symbolic reduction on the tape, and
//!   the generated code compiled into this crate by its `build.rs` — timed, and checked against
//!   a double-double reference of the same model and against published values;
//! * [`throughput`] (`eom bench throughput`): a sweep of many random parameter points of the
//!   bicycle through its generated code and the eigenvalues, in parallel, with its points per
//!   second;
//! * [`stress`] (`eom bench stress`): the failure map — sweeps into the regions where
//!   methods break, each method at each point classed accurate, reported failure or silently
//!   wrong;
//! * [`compare`]: reading reference tables and matching eigenvalues, shared with the
//!   cross-crate tests.
//!
//! Generated code is compiled at build time, so the models the accuracy benchmark can time as
//! generated code are those `build.rs` lists.

#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod compare;
pub mod stress;
pub mod throughput;
pub mod work_precision;
