//! The models of the benchmark, named once: the crate reads this file as a module and its
//! `build.rs` includes it by path (a build script cannot use the crate it builds), and
//! `build.rs` writes the dispatch of [`super::generated`] from these lists.

/// The models of the benchmark: a deliberate subset of the catalogue, one of each kind (a
/// few states, a rolling vehicle, a spinning body, wings, 100-state chains with shared and
/// per-element parameters), because each is compiled into generated code at build time (in
/// `f64` and `f32`) and timed at every run; the accuracy of every model of the catalogue is
/// tested elsewhere (`eom-cli/tests/references.rs`).
pub const MODELS: [&str; 9] = [
    "smd",
    "shimmy",
    "bicycle",
    "quarter_car",
    "top",
    "chain50",
    "chainp50",
    "smd_wing",
    "shimmy_wing",
];

/// The models of [`MODELS`] whose generated `f64` module also has the stability verdict
/// (`--stability`: at most 16 states).
pub const STABILITY: [&str; 7] = [
    "smd",
    "shimmy",
    "bicycle",
    "quarter_car",
    "top",
    "smd_wing",
    "shimmy_wing",
];

/// The models of [`MODELS`] also generated after the egg simplification pass.
pub const SIMPLIFIED: [&str; 2] = ["bicycle", "shimmy"];
