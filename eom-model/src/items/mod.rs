//! The items a model is made of, one module per kind, with builders that read like the model.
//!
//! Every numeric field is a scalar `S` — an [`Expr`] in a symbolic model, `f64` (or [`Dd`]) in
//! a numeric one — and every builder method takes anything that converts into it (`Expr`,
//! `f64`, `i32`). Vectors are `[S; 3]` in global axes (x forward, y left, z up by default);
//! build them with [`vec3`].
//!
//! Items name the bodies they connect; `"ground"` is the fixed frame and the default.
//!
//! Every kind implements [`Item`]; the crate documentation ("Adding an item kind") describes
//! the trait and how a new kind is added. [`KINDS`] fixes the order in which the kinds are
//! visited.

mod actuator;
mod beam;
mod body;
mod flex_point;
mod line;
mod link;
mod load;
mod nh_point;
mod point;
mod rigid_point;
mod sensor;
mod spring;
mod strip;
mod unsteady;
mod validation;
mod wing;

pub use actuator::Actuator;
pub use beam::Beam;
pub use body::Body;
pub use flex_point::FlexPoint;
pub use link::Link;
pub use load::Load;
pub use nh_point::NhPoint;
pub use rigid_point::RigidPoint;
pub use sensor::{Sensor, SensorFrame, SensorOrder};
pub use spring::Spring;
pub use strip::Strip;
pub use unsteady::{AUTO_REDUCED_FREQUENCY, JONES, JONES_DIRECT, Unsteady, jones_c};
pub use validation::Validation;
pub use wing::{WING_ACCELERATION_DERIVATIVES, WING_DERIVATIVES, Wing, wing_derivative_index};

pub use crate::geometry::{GROUND, Line, Name, Point, Vec3, vec3, x_axis, y_axis, z_axis, zero3};

use crate::assemble::Assembly;
use crate::error::ModelError;
pub(crate) use crate::error::{field_error, label};
pub(crate) use crate::geometry::{map3, name};
use eom_sym::scalar::Scalar;
use eom_sym::{Dd, Expr};

/// The item kinds in the order in which a model stores, validates and assembles them (bodies
/// are kept apart and come first). The order fixes the order of the constraint rows and of
/// their multipliers: the elastic rows are the springs', the flex points' and then the
/// beams'; the holonomic rows the links' and then the rigid points'. Inputs come before
/// outputs, so a sensor finds the actuator it feeds through. A new kind is registered by
/// adding its [`Item::kind`] here.
pub const KINDS: &[&str] = &[
    "load",
    "spring",
    "flex point",
    "beam",
    "link",
    "rigid point",
    "nh point",
    "wing",
    "strip",
    "actuator",
    "sensor",
];

/// The position of `kind` in [`KINDS`] (an unregistered kind sorts last).
pub(crate) fn kind_rank(kind: &str) -> usize {
    KINDS.iter().position(|k| *k == kind).unwrap_or(KINDS.len())
}

/// The scalar types a model can hold and be converted between: eom-sym's [`Expr`], `f64` and
/// [`Dd`]. A model stores its items as trait objects, and a trait object cannot have a method
/// generic in the target type; the conversion is therefore one method per target scalar
/// ([`MapItem`]), and this trait picks the one for `Self`.
pub trait ModelScalar: Scalar + Send + Sync {
    /// `item` converted field by field with `f`.
    fn map_item<S: ModelScalar>(
        item: &dyn Item<S>,
        f: &mut dyn FnMut(&S) -> Self,
    ) -> Box<dyn Item<Self>>;
}

impl ModelScalar for f64 {
    fn map_item<S: ModelScalar>(
        item: &dyn Item<S>,
        f: &mut dyn FnMut(&S) -> f64,
    ) -> Box<dyn Item<f64>> {
        MapItem::<S, f64>::map_item(item, f)
    }
}

impl ModelScalar for Dd {
    fn map_item<S: ModelScalar>(
        item: &dyn Item<S>,
        f: &mut dyn FnMut(&S) -> Dd,
    ) -> Box<dyn Item<Dd>> {
        MapItem::<S, Dd>::map_item(item, f)
    }
}

impl ModelScalar for Expr {
    fn map_item<S: ModelScalar>(
        item: &dyn Item<S>,
        f: &mut dyn FnMut(&S) -> Expr,
    ) -> Box<dyn Item<Expr>> {
        MapItem::<S, Expr>::map_item(item, f)
    }
}

/// Conversion of an item into scalar type `T`, every field with `f`, in the order of
/// [`Item::fields`]. Implemented once per kind, generically in `S` and `T`.
pub trait MapItem<S, T> {
    /// The converted item.
    fn map_item(&self, f: &mut dyn FnMut(&S) -> T) -> Box<dyn Item<T>>;
}

/// A boxed copy of an item (implemented for every `Clone` item).
pub trait CloneItem<S> {
    /// The copy.
    fn clone_box(&self) -> Box<dyn Item<S>>;
}

impl<S, I: Item<S> + Clone> CloneItem<S> for I {
    fn clone_box(&self) -> Box<dyn Item<S>> {
        Box::new(self.clone())
    }
}

impl<S> Clone for Box<dyn Item<S>> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// What every item kind implements: its fields, its checks, the bodies it connects and its
/// contribution to the linearized equations. See the crate documentation, "Adding an item
/// kind".
pub trait Item<S>:
    std::fmt::Debug
    + CloneItem<S>
    + MapItem<S, f64>
    + MapItem<S, Dd>
    + MapItem<S, Expr>
    + Send
    + Sync
    + std::any::Any
    + 'static
{
    /// The kind as it appears in messages and in [`KINDS`], e.g. `"flex point"`.
    fn kind(&self) -> &'static str;

    /// The item's name, unique among the items of a model.
    fn name(&self) -> &Name;

    /// Visit every scalar field with its name, in the order in which [`MapItem::map_item`]
    /// converts them.
    fn fields(&self, f: &mut dyn FnMut(Field, &S));

    /// The item's settings that are not scalar fields (the bodies it connects, counts, flags,
    /// labels), by the names a model file uses for them.
    fn settings(&self) -> Vec<(&'static str, Setting)> {
        Vec::new()
    }

    /// The bodies the item connects: each must exist, and two must differ. (Other body
    /// references, like a load's frame, are checked by [`Item::validate`].)
    fn bodies(&self) -> &[Name];

    /// Whether the item constrains or supports the bodies it connects (a joint, link, spring
    /// or beam does; a load, actuator or sensor does not). A body that nothing supports is an
    /// error.
    fn supports(&self) -> bool;

    /// Check the item's own fields (geometry, ranges, references other than
    /// [`Item::bodies`]), after its bodies have been found to exist; errors name the item and
    /// field, warnings go to the context.
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError>;

    /// Add the item's terms to the linearized equations.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError>;

    /// The item as a body (a body overrides this), or else itself: [`Model::add`] keeps
    /// bodies apart from the items.
    ///
    /// [`Model::add`]: crate::Model::add
    fn into_body(self: Box<Self>) -> Result<Body<S>, Box<dyn Item<S>>>
    where
        Self: Sized,
    {
        Err(self)
    }
}

/// A setting of an item that is not a scalar field (see [`Item::settings`]).
#[derive(Clone, Debug, PartialEq)]
pub enum Setting {
    /// A name or label.
    Text(String),
    /// Two body names.
    Pair([String; 2]),
    /// A count.
    Count(u8),
    /// A flag.
    Flag(bool),
}

/// The name of a scalar field of an item, with up to two indices: `mass`, `location[x]`,
/// `stiffness[1]`, `ends[2][z]`, `stiffness_matrix[1][3]`. Made without allocating; formatted
/// only when a message needs it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// The field's name.
    pub name: &'static str,
    /// Its indices (outermost first).
    pub index: [Index; 2],
}

/// One index of a [`Field`] (small: a field is made for every scalar a visitor sees).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Index {
    /// No index.
    None,
    /// A 0-based position, displayed 1-based (`[1]`).
    Nth(u16),
    /// A vector component 0, 1, 2, displayed `[x]`, `[y]`, `[z]`.
    Axis(u8),
}

impl Field {
    /// A scalar field.
    pub fn scalar(name: &'static str) -> Self {
        Field {
            name,
            index: [Index::None; 2],
        }
    }
    /// Component `k` of a vector field.
    pub fn axis(name: &'static str, k: usize) -> Self {
        Field {
            name,
            index: [Index::Axis(k as u8), Index::None],
        }
    }
    /// Element `i` of an array field.
    pub fn nth(name: &'static str, i: usize) -> Self {
        Field {
            name,
            index: [Index::Nth(i as u16), Index::None],
        }
    }
    /// Component `k` of vector `i` of an array of vectors.
    pub fn nth_axis(name: &'static str, i: usize, k: usize) -> Self {
        Field {
            name,
            index: [Index::Nth(i as u16), Index::Axis(k as u8)],
        }
    }
    /// Entry `(i, j)` of a matrix field.
    pub fn entry(name: &'static str, i: usize, j: usize) -> Self {
        Field {
            name,
            index: [Index::Nth(i as u16), Index::Nth(j as u16)],
        }
    }
}

impl std::fmt::Display for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)?;
        for i in self.index {
            match i {
                Index::None => {}
                Index::Nth(k) => write!(f, "[{}]", k + 1)?,
                Index::Axis(k) => write!(f, "[{}]", ["x", "y", "z"][k as usize])?,
            }
        }
        Ok(())
    }
}

/// Visit the three components of vector field `name`.
pub(crate) fn visit3<S>(f: &mut dyn FnMut(Field, &S), name: &'static str, v: &Vec3<S>) {
    for (k, x) in v.iter().enumerate() {
        f(Field::axis(name, k), x);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Checks the contract between [`Item::fields`] and [`MapItem::map_item`] for an item whose
    /// fields hold the distinct values 1, 2, 3, …: the map visits the fields in the order of
    /// `fields`, converts every one of them, and keeps their names.
    pub(crate) fn check_fields_and_map(item: &dyn Item<f64>) {
        let mut names = Vec::new();
        let mut values = Vec::new();
        item.fields(&mut |fd, x| {
            names.push(fd.to_string());
            values.push(*x);
        });
        let mut seen = Vec::new();
        let mapped = MapItem::<f64, f64>::map_item(item, &mut |x| {
            seen.push(*x);
            *x + 1000.0
        });
        assert_eq!(
            seen, values,
            "map_item visits the fields in the order of fields()"
        );
        let mut after = Vec::new();
        let mut after_names = Vec::new();
        mapped.fields(&mut |fd, x| {
            after_names.push(fd.to_string());
            after.push(*x);
        });
        let shifted: Vec<f64> = values.iter().map(|x| x + 1000.0).collect();
        assert_eq!(after, shifted);
        assert_eq!(after_names, names);
        assert_eq!(mapped.kind(), item.kind());
        assert_eq!(mapped.name(), item.name());
        let mut distinct = values.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        assert_eq!(
            distinct.len(),
            values.len(),
            "the test item's fields are distinct"
        );
    }

    /// Distinct field values 1, 2, 3, … for [`check_fields_and_map`].
    #[derive(Default)]
    pub(crate) struct Counter(std::cell::Cell<f64>);

    impl Counter {
        /// The next value.
        pub(crate) fn x(&self) -> f64 {
            let k = self.0.get() + 1.0;
            self.0.set(k);
            k
        }
        /// A vector of the next three values.
        pub(crate) fn v(&self) -> Vec3<f64> {
            [self.x(), self.x(), self.x()]
        }
    }

    #[test]
    fn field_names_read_like_the_builders() {
        assert_eq!(Field::scalar("mass").to_string(), "mass");
        assert_eq!(Field::axis("location", 2).to_string(), "location[z]");
        assert_eq!(Field::nth("stiffness", 0).to_string(), "stiffness[1]");
        assert_eq!(Field::nth_axis("ends", 1, 0).to_string(), "ends[2][x]");
        assert_eq!(
            Field::entry("damping_matrix", 0, 2).to_string(),
            "damping_matrix[1][3]"
        );
    }

    #[test]
    fn every_kind_is_registered_once() {
        for (i, k) in KINDS.iter().enumerate() {
            assert_eq!(kind_rank(k), i);
        }
        assert_eq!(kind_rank("no such kind"), KINDS.len());
    }
}
