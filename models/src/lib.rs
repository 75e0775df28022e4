//! # models — the eom model library
//!
//! Built-in models with named parameters, defaults and known answers. Each named model is a
//! model file shipped in `models/` (`models/smd.toml`, …), embedded in the library and read
//! by eom-model's file reader, so that the file is the model's one home; the families with a
//! size (`chainN`, `chainpN`) are built in Rust. Every model is a function from parameter
//! values to a symbolic [`Model`]; parameters not given take their defaults.
//!
//! ```
//! let shimmy = models::build("shimy", &[]).unwrap_err();
//! assert!(shimmy.to_string().contains("shimmy"));
//! let shimmy = models::build("shimmy", &[("u", 1.0)]).unwrap();
//! assert_eq!(shimmy.scope.get("u").unwrap().nominal(), 1.0);
//! // The catalogue is what tests and tools iterate; a named model's file text is at hand.
//! assert!(models::names().contains(&"bicycle"));
//! assert!(models::file_text("bicycle").unwrap().contains("[[body]]"));
//! ```
//!
//! | model | what it is | reference |
//! |---|---|---|
//! | `smd` | spring–mass–damper on a slider | closed form |
//! | `pendulum` | one-degree-of-freedom pendulum on a pin | closed form |
//! | `shimmy` | Schwab–Meijaard swivel wheel (nonholonomic tyre) | closed-form cubic |
//! | `bicycle` | Meijaard et al. 2007 Whipple bicycle benchmark | published table |
//! | `quarter_car` | two-mass suspension with tyre damping driven by road displacement | closed-form transfer functions |
//! | `top` | heavy symmetric top on a fixed point | closed form |
//! | `disk` | rolling disk | closed form |
//! | `chainN` | N masses in series (e.g. `chain50`) | closed form |
//! | `chainpN` | the chain with its own m, k, c per element (`chainp50`: 150 parameters) | the matrices M, C, K by hand |
//! | `smd_wing` | the spring–mass–damper under a horizontal wing (the wing item's seed example) | closed form |
//! | `shimmy_wing` | the shimmy with a vertical fin at the spring point, given derivatives | the seed paper's damping entries; closed-form cubic |
//! | `shimmy_fin` | the same fin, derivatives from eom-aero's vortex lattice | within 0.3 % of the paper's entries |
//! | `ride_wings` | a car's bounce–pitch ride model with a front and a rear wing (illustrative) | a two-degree-of-freedom model derived by hand |
//! | `truck_trailer` | truck with a one-axle trailer, linear single-track tyres (Minaker 2019) | closed-form steady-state yaw-rate gain; hand-written single-track equations |
//! | `typical_section` | the pitch–plunge typical section (Hodges & Pierce) on a strip with Jones' lag states | exact Theodorsen flutter (k-method, determinant root) |
//! | `goland_wing` | Goland's cantilever wing, 16 beam segments carrying strips | converged Theodorsen strip-theory flutter |
//! | `navion` | the Navion in level free flight from Nelson's stability derivatives | the flight equations by hand; Nelson's printed roots |
//! | `aircraft_ground` | a light taildragger on its landing gear with a wing and a tail (illustrative) | the three reduction paths |

#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod aeroelastic;
mod catalogue;
mod chainp;
pub mod generate;

pub use catalogue::{
    FAMILIES, Family, MAX_CHAIN, ModelInfo, build, catalogue, file_text, find, names,
};
pub use eom_model::file::{ParamRange, ParamSpec};

/// Errors of the model library (the catalogue of built-in models).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CatalogueError {
    /// No model of this name.
    #[error(
        "unknown model `{name}`{}; models are: {}",
        eom_text::did_you_mean(name, known),
        known.join(", ")
    )]
    UnknownModel {
        /// The name asked for.
        name: String,
        /// The names that exist.
        known: Vec<String>,
    },
    /// A chain longer than the catalogue builds ([`catalogue::MAX_CHAIN`]).
    #[error(
        "model `{name}`: a chain has at most {max} masses here (the analysis grows as the \
         cube of the size); for a longer chain write a model file (`eom export chain10` \
         shows the pattern)"
    )]
    ChainTooLong {
        /// The name asked for.
        name: String,
        /// The largest chain.
        max: usize,
    },
    /// A parameter that the model does not have.
    #[error(
        "model `{model}` has no parameter `{name}`{}; its parameters are: {}",
        eom_text::did_you_mean(name, known),
        known.join(", ")
    )]
    UnknownParameter {
        /// The model.
        model: String,
        /// The name asked for.
        name: String,
        /// The parameters that exist.
        known: Vec<String>,
    },
    /// A parameter value that the model cannot take.
    #[error("model `{model}`, parameter `{name}` = {value:?}: {problem}")]
    BadValue {
        /// The model.
        model: String,
        /// The parameter.
        name: String,
        /// The value.
        value: f64,
        /// Why it is not acceptable.
        problem: String,
    },
    /// An error of an expression while building the model.
    #[error(transparent)]
    Sym(#[from] eom_sym::SymError),
    /// A shipped model file that does not load (a defect of the library, which its tests
    /// catch).
    #[error("the built-in model's file does not load: {0}")]
    Shipped(String),
    /// An error of the model layer while building the model.
    #[error(transparent)]
    Model(#[from] eom_model::ModelError),
}

pub use eom_model::Model;
