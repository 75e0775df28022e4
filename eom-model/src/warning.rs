//! [`Warning`]: input or results that are computable but doubtful, as data. Each variant
//! holds the item and values that triggered it; `Display` gives the message users see.

use std::fmt;

use eom_num::NumWarning;
use num_complex::Complex64;

pub use crate::error::ItemRef;

/// A warning of reading, checking, assembling, reducing or linearizing a model.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Warning {
    /// A point item whose `forces` and `moments` are both 0.
    ConstrainsNothing {
        /// The item.
        item: ItemRef,
    },
    /// A body whose moments of inertia (given without products) include a negative one.
    NegativeMoments {
        /// The body.
        item: ItemRef,
        /// Its moments of inertia (x, y, z).
        moments: Vec<f64>,
    },
    /// A body whose principal moments of inertia violate the triangle inequality.
    InertiaTriangle {
        /// The body.
        item: ItemRef,
        /// The field at fault (`moments` or `products`).
        field: &'static str,
        /// The principal moments, ascending.
        principal: Vec<f64>,
    },
    /// A load on the ground: it has no effect.
    LoadOnGround {
        /// The load.
        item: ItemRef,
    },
    /// A wing without derivatives: it adds nothing.
    NoDerivatives {
        /// The wing.
        item: ItemRef,
    },
    /// A surface with `unsteady = "auto"` assembled on its own (outside a linearization),
    /// hence quasi-steady.
    AutoAssembled {
        /// The wing or strip.
        item: ItemRef,
    },
    /// A surface with `unsteady = "auto"` that got Jones' lag states: a mode has a reduced
    /// frequency above the threshold.
    AutoLagged {
        /// The wing or strip.
        item: ItemRef,
        /// Real part of the mode's eigenvalue.
        re: f64,
        /// Imaginary part of the mode's eigenvalue.
        im: f64,
        /// Its reduced frequency `|Im λ|·b/V`.
        reduced_frequency: f64,
        /// The threshold.
        threshold: f64,
    },
    /// A surface with `unsteady = "auto"` kept quasi-steady: no mode has a reduced frequency
    /// above the threshold.
    AutoQuasiSteady {
        /// The wing or strip.
        item: ItemRef,
        /// The largest reduced frequency of a mode (`None` when no mode oscillates).
        largest: Option<f64>,
        /// The threshold.
        threshold: f64,
    },
    /// The statics removed redundant holonomic constraint rows: their preloads are not unique.
    StaticsRedundant {
        /// The rows removed.
        rows: Vec<String>,
        /// The smallest singular value kept, relative to the largest.
        smallest_kept: f64,
        /// The largest singular value dropped, relative to the largest.
        largest_dropped: f64,
        /// The rank threshold.
        threshold: f64,
        /// The self-stress removed, relative to the largest preload.
        self_stress: f64,
    },
    /// The given geometry is close to, but not exactly, an equilibrium.
    NearEquilibrium {
        /// The force or moment equation with the largest residual (``body `frame` x force``).
        equation: String,
        /// Its residual.
        residual: f64,
        /// The residual relative to the body's largest force or moment.
        ratio: f64,
        /// The model's length scale.
        length: f64,
    },
    /// The elimination removed redundant position constraint rows.
    ReductionRedundant {
        /// The rows removed.
        rows: Vec<String>,
        /// The relative size below which the remaining entries were negligible.
        negligible: f64,
    },
    /// The robust (SVD) reduction found redundant constraint rows.
    RobustRedundant {
        /// How many rows are redundant.
        redundant: usize,
        /// Of how many.
        rows: usize,
        /// The gap of the rank decision.
        gap: f64,
    },
    /// A warning of the numeric reduction of the descriptor system.
    Numeric(NumWarning),
    /// A warning about the AVL output file of a wing.
    AvlFile {
        /// The wing.
        item: ItemRef,
        /// The file.
        path: String,
        /// The reader's warning.
        warning: eom_aero::AeroWarning,
    },
    /// A mode whose reduced frequency at a quasi-steady wing is beyond the limit of its
    /// derivatives.
    ReducedFrequencyBeyondLimit {
        /// The wing.
        item: ItemRef,
        /// The mode's eigenvalue (the member of its pair with positive imaginary part).
        eigenvalue: Complex64,
        /// Its reduced frequency `β = |Im λ|·c/V`.
        beta: f64,
        /// The limit.
        limit: f64,
    },
    /// A wing's normalised rate beyond the limit of its quasi-steady derivatives along a
    /// response.
    RateBeyondLimit {
        /// The wing.
        item: ItemRef,
        /// The rate (`p b/2V`, `q c/2V`, `r b/2V`).
        rate: &'static str,
        /// Its largest magnitude.
        max: f64,
        /// The sample where it is reached.
        sample: usize,
        /// The limit.
        limit: f64,
    },
}

impl Warning {
    /// The kind of warning, as a short snake-case name (`"statics_redundant"`): the `kind` of
    /// the JSON output and of the Python package.
    pub fn kind(&self) -> &'static str {
        match self {
            Warning::ConstrainsNothing { .. } => "constrains_nothing",
            Warning::NegativeMoments { .. } => "negative_moments",
            Warning::InertiaTriangle { .. } => "inertia_triangle",
            Warning::LoadOnGround { .. } => "load_on_ground",
            Warning::NoDerivatives { .. } => "no_derivatives",
            Warning::AutoAssembled { .. } => "auto_assembled",
            Warning::AutoLagged { .. } => "auto_lagged",
            Warning::AutoQuasiSteady { .. } => "auto_quasi_steady",
            Warning::StaticsRedundant { .. } => "statics_redundant",
            Warning::NearEquilibrium { .. } => "near_equilibrium",
            Warning::ReductionRedundant { .. } => "reduction_redundant",
            Warning::RobustRedundant { .. } => "robust_redundant",
            Warning::Numeric(w) => w.kind(),
            Warning::AvlFile { .. } => "avl_file",
            Warning::ReducedFrequencyBeyondLimit { .. } => "reduced_frequency_beyond_limit",
            Warning::RateBeyondLimit { .. } => "rate_beyond_limit",
        }
    }

    /// The item the warning is about, if it is about one.
    pub fn item(&self) -> Option<&ItemRef> {
        match self {
            Warning::ConstrainsNothing { item }
            | Warning::NegativeMoments { item, .. }
            | Warning::InertiaTriangle { item, .. }
            | Warning::LoadOnGround { item }
            | Warning::NoDerivatives { item }
            | Warning::AutoAssembled { item }
            | Warning::AutoLagged { item, .. }
            | Warning::AutoQuasiSteady { item, .. }
            | Warning::AvlFile { item, .. }
            | Warning::ReducedFrequencyBeyondLimit { item, .. }
            | Warning::RateBeyondLimit { item, .. } => Some(item),
            Warning::StaticsRedundant { .. }
            | Warning::NearEquilibrium { .. }
            | Warning::ReductionRedundant { .. }
            | Warning::RobustRedundant { .. }
            | Warning::Numeric(_) => None,
        }
    }

    /// Whether the warning makes the linearization's result doubtful: a numerical rank
    /// decision removed constraint rows as redundant, or the geometry is only nearly an
    /// equilibrium. (Warnings about the input, e.g. an inertia violating the triangle
    /// inequality, do not.)
    pub fn doubts_result(&self) -> bool {
        matches!(
            self,
            Warning::StaticsRedundant { .. }
                | Warning::ReductionRedundant { .. }
                | Warning::RobustRedundant { .. }
                | Warning::NearEquilibrium { .. }
        )
    }
}

impl From<NumWarning> for Warning {
    fn from(w: NumWarning) -> Self {
        Warning::Numeric(w)
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::ConstrainsNothing { item } => {
                write!(f, "{item} constrains nothing (forces = moments = 0)")
            }
            Warning::NegativeMoments { item, moments } => write!(
                f,
                "{item}: moments of inertia {moments:?} are not those of a physical body \
                 (negative)"
            ),
            Warning::InertiaTriangle {
                item,
                field,
                principal,
            } => write!(
                f,
                "{item}, field `{field}`: principal moments of inertia {principal:.6?} violate the \
                 triangle inequality I₁ + I₂ ≥ I₃: no body has this inertia"
            ),
            Warning::LoadOnGround { item } => {
                write!(f, "{item} acts on the ground and has no effect")
            }
            Warning::NoDerivatives { item } => {
                write!(f, "{item} has no derivatives: it adds nothing")
            }
            Warning::AutoAssembled { item } => write!(
                f,
                "{item}: unsteady = \"auto\" is decided by the linearization (eom analyze, sweep, \
                 …); assembled here as quasi-steady"
            ),
            Warning::AutoLagged {
                item,
                re,
                im,
                reduced_frequency: k,
                threshold,
            } => write!(
                f,
                "{item}: unsteady = \"auto\": Jones' lag states added: the mode λ = {re:.6} ± \
                 {im:.6}i has the reduced frequency k = |Im λ|·b/V = {k:.4} > {threshold} \
                 (quasi-steady lift would be off by |1 − C(k)| ≥ 0.16)"
            ),
            Warning::AutoQuasiSteady {
                item,
                largest: Some(k),
                threshold,
            } => write!(
                f,
                "{item}: unsteady = \"auto\": quasi-steady: every mode has k = |Im λ|·b/V ≤ \
                 {threshold} (largest {k:.4})"
            ),
            Warning::AutoQuasiSteady {
                item,
                largest: None,
                ..
            } => write!(
                f,
                "{item}: unsteady = \"auto\": quasi-steady: no oscillatory mode"
            ),
            Warning::StaticsRedundant {
                rows,
                smallest_kept,
                largest_dropped,
                threshold,
                self_stress,
            } => write!(
                f,
                "statics: {} redundant constraint row(s) ({}): combinations of the other \
                 holonomic rows (singular values of the scaled Jacobian: smallest kept \
                 {smallest_kept:.1e}, largest dropped {largest_dropped:.1e} of the largest, \
                 threshold {threshold:.0e}); their preloads are not unique: the minimum-norm \
                 preloads are used (self-stress removed: {self_stress:.1e} of the largest \
                 preload), and the geometric stiffness depends on that choice",
                rows.len(),
                rows.join(", ")
            ),
            Warning::NearEquilibrium {
                equation,
                residual,
                ratio,
                length,
            } => write!(
                f,
                "statics: the given geometry is close to, but not exactly, an equilibrium: \
                 {equation} residual {residual:.3e}, {ratio:.1e} of the body's largest force or \
                 moment (model length scale {length:.3e}); the residual load is left out of the \
                 linearization"
            ),
            Warning::ReductionRedundant { rows, negligible } => write!(
                f,
                "reduction: {} redundant position constraint row(s) ({}): combinations of the \
                 other rows at the nominal point (remaining entries below {negligible:.0e} of \
                 the row's size), removed",
                rows.len(),
                rows.join(", ")
            ),
            Warning::RobustRedundant {
                redundant,
                rows,
                gap,
            } => write!(
                f,
                "{redundant} of {rows} constraint rows are redundant (rank decision gap {gap:.3e})"
            ),
            Warning::Numeric(w) => w.fmt(f),
            Warning::AvlFile {
                item,
                path,
                warning,
            } => write!(f, "{item}: {path}: {warning}"),
            Warning::ReducedFrequencyBeyondLimit {
                item,
                eigenvalue: z,
                beta,
                limit,
            } => write!(
                f,
                "{item}: the mode λ = {:.6} ± {:.6}i has the reduced frequency β = |Im λ|·c/V = \
                 {beta:.3} > {limit}: its quasi-steady derivatives are doubtful there (unsteady \
                 lift lags)",
                z.re,
                z.im.abs()
            ),
            Warning::RateBeyondLimit {
                item,
                rate,
                max,
                sample,
                limit,
            } => write!(
                f,
                "{item}: |{rate}| reaches {max:.4} (sample {sample}), beyond {limit}: the \
                 quasi-steady derivatives are doubtful there"
            ),
        }
    }
}
