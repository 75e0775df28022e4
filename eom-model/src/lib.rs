//! # eom-model — the multibody model
//!
//! A [`Model`] holds parameters, bodies and the items connecting them (springs, links, joints,
//! rolling contacts, beams, loads, actuators, sensors). Every numeric field is a scalar `S`: in a
//! symbolic model (`Model<Expr>`, the default) fields are expressions over the model's
//! parameters; [`Model::evaluate`] turns it into a numeric `Model<f64>` at given parameter values,
//! and [`Model::map`] into any other [`ModelScalar`] (e.g. double-double).
//!
//! The data flow is one algorithm written once for every scalar type:
//!
//! 1. [`assemble()`]: mass, stiffness (with the tangent stiffness of the static preloads), damping
//!    (with the gyroscopic and momentum terms), the holonomic and nonholonomic constraint
//!    Jacobians, inputs and outputs;
//! 2. [`reduce()`]: structure-first symbolic-numeric elimination of the constraints, with pivots
//!    chosen at the nominal point and recorded as validity checks; or [`reduce_robust`], the
//!    orthonormal-complement reduction that is the independent numeric reference;
//! 3. [`Linearizer`] reaches all of them in one call; [`compiled`] evaluates a symbolic state
//!    space quickly at many points.
//!
//! The method is that of the EoM software (Minaker et al., University of Windsor); where eom
//! deliberately differs from it is documented in the modules ([`assemble`](mod@assemble),
//! [`reduce`](mod@reduce), [`robust`]).
//!
//! # Examples
//!
//! A model in a few lines, from `examples/spring_mass.rs` (run it with
//! `cargo run --release -p eom-model --example spring_mass`):
//!
//! ```
#![doc = include_str!("../examples/spring_mass.rs")]
//! ```
//!
//! The shimmy, with its symbolic state matrix checked against the closed form:
//!
//! ```
//! use eom_model::*;
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
//! // Numeric: evaluated at other parameter values.
//! let at = m.scope.values_with(&[("u", 1.0)]).unwrap();
//! let num = sym.evaluate(&at).unwrap();
//! let eig = eom_num::modes::eigenvalues(&num.a).unwrap();
//! // The characteristic polynomial (I + m a²)s³ + m a u s² + k l² s + k l u has the root
//! // −1.0548225773209977 at these values (Schwab & Meijaard 2003).
//! assert!((eig[0].re + 1.0548225773209977).abs() < 1e-12);
//! ```
//!
//! # The item layer
//!
//! A body or item is a struct in its own module under `items/`, declared with its fields by
//! the `item!` macro (`items/declare.rs`), and implements the trait [`Item`], which is all the
//! rest of the crate knows of it:
//!
//! * [`Item::kind`], [`Item::name`]: how messages name it (``flex point `tyre` ``);
//! * [`Item::fields`]: every scalar field with its [`Field`] name, in a fixed order, and the
//!   kind's `map`: the item converted to another scalar type, field by field in the same order
//!   (this is how [`Model::evaluate`] turns expressions into numbers);
//! * [`Item::bodies`] and [`Item::supports`]: the bodies it connects (checked to exist and to
//!   differ) and whether it holds them; [`Item::validate`]: its own checks, whose errors name
//!   the item and field ([`Validation`] gives the known bodies and items, and takes warnings);
//! * [`Item::assemble`]: its terms of the linearized equations, through the assembly context
//!   [`Assembly`]: the bodies' indices and mass centres, the Jacobian rows of a line or point
//!   geometry ([`Assembly::line`], [`Assembly::point`]), 3×3 blocks and `Rᵀ P R` property
//!   blocks added to a [`Term`] (mass, item mass, stiffness, damping, momentum, velocity, load
//!   stiffness), holonomic, elastic or nonholonomic rows with the [`Reaction`] their
//!   multipliers carry (which gives the item's preload and its geometric stiffness), known
//!   preloads, applied forces, inputs and outputs, and first-order lag states
//!   ([`Assembly::lag_state`], [`Assembly::add_lag`]: a strip's or wing's unsteady lift),
//!   which every reduction carries after the mechanical states.
//!
//! A kind's declaration gives, once, its name in messages, its model-file key, the field
//! holding the bodies it connects, whether it supports them, and every field with its type,
//! default, documentation (units included), builder and model-file key. From it come the
//! struct, its constructor and builders, its `map`, [`Item::fields`] and
//! [`Item::settings`], its keys ([`Kind`]), the reading of its table in a model file
//! (through the [`Source`](items::Source) trait the file reader implements) and the checks of
//! the shapes it shares ([`Line`]'s length, [`Point`]'s directions). Only what the kind
//! *does* is written by hand, as its [`Physics`](items::Physics): `validate` and `assemble`.
//!
//! The kinds are listed once, in order, in the `kinds!` table of `items/mod.rs`. From it come
//! the closed enum [`AnyItem`] in which a [`Model`] keeps its items (bodies apart), in the
//! order of [`KINDS`], which fixes the order of the constraint rows and of their multipliers;
//! the model-file reader's loop over the kinds and their allowed keys, the exporter's keys and
//! defaults, and the key table of docs/model-files.md (checked by a test).
//!
//! [`Item`]: items::Item
//! [`Field`]: items::Field
//! [`Kind`]: items::Kind
//! [`AnyItem`]: items::AnyItem
//! [`KINDS`]: items::KINDS
//! [`Item::kind`]: items::Item::kind
//! [`Item::name`]: items::Item::name
//! [`Item::fields`]: items::Item::fields
//! [`Item::bodies`]: items::Item::bodies
//! [`Item::supports`]: items::Item::supports
//! [`Item::validate`]: items::Item::validate
//! [`Item::assemble`]: items::Item::assemble
//! [`Item::settings`]: items::Item::settings
//!
//! ## Adding an item kind
//!
//! 1. Write `items/<kind>.rs`: the declaration and the physics, e.g.
//!
//!    ```text
//!    item! {
//!        /// A torsional damper about a line.
//!        pub struct Damper<S>: "damper", "damper" (bodies: line, supports: false) {
//!            /// Geometry.
//!            pub line: Line<S> = Line::new() => line(),
//!            /// Damping (N·m·s/rad).
//!            pub damping: S = S::zero() => scalar(damping, "damping"),
//!        }
//!        /// A damper with zero damping.
//!        pub fn new;
//!    }
//!
//!    impl<S: ModelScalar> Physics<S> for Damper<S> {
//!        fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
//!            let (rows, _) = cx.line(&self.line, "damper", &self.name);
//!            cx.add_rows_block(Term::Damping, &rows.rows, &[vec![self.damping]]);
//!            Ok(())
//!        }
//!    }
//!    ```
//!
//!    The field shapes (`scalar`, `optional`, `vector`, `pair`, `matrix`, `ends`, `bodies`,
//!    `body`, `text`, `choice`, `line`, `point`, …) are listed in `items/declare.rs`; a
//!    field's reading, listing and export follow from its shape. Write `validate` only for
//!    checks beyond the shapes' (a shared shape checks itself); what a model file gives in a
//!    way no shape says (a wing's AVL file, a sensor's feedthrough table) is read by hand in
//!    `file/items.rs` (`Builder::read`), before or after the declared fields.
//!    Fields that several kinds share are declared once as a field group and listed as
//!    `..group!(args),` (the lifting surfaces' `surface_fields!` in `items/surface.rs`).
//! 2. List it: `mod <kind>; pub use <kind>::<Kind>;` and its place in the `kinds!` table of
//!    `items/mod.rs` (where it stands there decides where its rows go); add its row to the key
//!    table of docs/model-files.md (the test `key_table` prints it) and describe its keys there.
//! 3. Test it: add it to `fields_and_map_agree` in `items/mod.rs` (the field visitor and the
//!    conversion agree); a closed-form model checks its terms.
//!

#![warn(missing_docs)]
#![forbid(unsafe_code)]

pub mod aero;
pub mod assemble;
mod canonical;
pub mod compiled;
pub mod eliminate;
pub mod error;
mod fields;
pub mod file;
pub mod geometry;
pub mod items;
pub mod linearize;
mod model;
pub mod preloads;
pub mod reduce;
pub mod robust;
pub mod sensitivity;
pub mod tutorials;
pub mod validate;
pub mod warning;

/// The types a user needs to build and linearize a model: `use eom_model::prelude::*;`.
pub mod prelude {
    pub use crate::error::ModelError;
    pub use crate::items::{
        Actuator, Beam, Body, FlexPoint, Link, Load, NhPoint, RigidPoint, Sensor, SensorFrame,
        SensorOrder, Spring, Strip, Unsteady, Wing, vec3, x_axis, y_axis, z_axis,
    };
    pub use crate::linearize::{Linearization, Linearizer, Method};
    pub use crate::warning::Warning;
    pub use crate::{Model, SymbolicStateSpace};
}

pub use aero::{
    ReducedFrequency, WingRates, reduced_frequencies, resolve_unsteady, response_rates,
    simulated_rates,
};
pub use assemble::{
    Assembled, Assembly, ItemRow, LagTerm, Lags, LineGeometry, OutputFrame, OutputKind,
    OutputOrder, PointGeometry, Preload, Reaction, RowLabel, Rows, Statics, Term,
};
pub use compiled::{CompiledStateSpace, EvalWorkspace, MatrixSize, SymbolicStateSpace};
pub use error::ModelError;
// The item kinds and geometry a model is built from; what only an item author needs (the
// `Item` trait, `Physics`, `Part`, the kind table, …) stays under [`items`].
pub use items::{
    Actuator, Beam, Body, FlexPoint, GROUND, Line, Link, Load, ModelScalar, Name, NhPoint, Point,
    RigidPoint, Sensor, SensorFrame, SensorOrder, Spring, Strip, Unsteady, Vec3, Wing, vec3,
    x_axis, y_axis, z_axis, zero3,
};
pub use linearize::{Linearization, Linearizer, Method};
pub use model::{Model, assemble};
pub use reduce::{
    CheckLabel, Coord, ReducedDescriptor, Reduction, ReductionPlan, ReductionReport, ValidityCheck,
    reduce, reduce_report,
};
pub use robust::{ConstrainedDescriptor, RobustReport, constrained_descriptor, reduce_robust};
pub use sensitivity::{Sensitivities, sensitivities};
pub use validate::Validation;
pub use warning::{ItemRef, Warning};
