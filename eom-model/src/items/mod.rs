//! The items a model is made of, one module per kind, with builders that read like the model.
//!
//! Every numeric field is a scalar `S` — an [`Expr`] in a symbolic model, `f64` (or [`Dd`]) in
//! a numeric one — and every builder method takes anything that converts into it (`Expr`,
//! `f64`, `i32`). Vectors are `[S; 3]` in global axes (x forward, y left, z up by default);
//! build them with [`vec3`].
//!
//! Items name the bodies they connect; `"ground"` is the fixed frame and the default.
//!
//! Every kind is declared once with its fields, in its module, by `item!` (see `declare.rs`:
//! its name in messages, its model-file key, and each field's type, default, builder and key),
//! writes its [`Physics`] by hand, and so implements [`Item`]. The `kinds!` table of this
//! module lists the kinds in the order of [`KINDS`]; from it come the closed enum [`AnyItem`]
//! a model stores its items in, the model-file reader's loop and keys, the exporter's keys and
//! the key table of docs/model-files.md. The crate documentation ("Adding an item kind")
//! describes how a new kind is added.

mod actuator;
mod beam;
mod body;
mod declare;
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
mod surface;
mod unsteady;
mod validation;
mod wing;

pub use actuator::Actuator;
pub use beam::Beam;
pub use body::Body;
pub use declare::{Choice, Connects, Declared, Physics, Source, VecKind};
pub(crate) use declare::{concat_keys, item, key_count, map_matrix};
pub use flex_point::FlexPoint;
pub use link::Link;
pub use load::Load;
pub use nh_point::NhPoint;
pub use rigid_point::RigidPoint;
pub use sensor::{Sensor, SensorFrame, SensorOrder};
pub use spring::Spring;
pub use strip::Strip;
pub(crate) use surface::surface_fields;
pub use unsteady::{AUTO_REDUCED_FREQUENCY, JONES, JONES_DIRECT, Unsteady, jones_c};
pub use validation::Validation;
pub use wing::{WING_ACCELERATION_DERIVATIVES, WING_DERIVATIVES, Wing, wing_derivative_index};

pub use crate::geometry::{GROUND, Line, Name, Point, Vec3, vec3, x_axis, y_axis, z_axis, zero3};

use crate::assemble::Assembly;
use crate::error::ModelError;
pub(crate) use crate::error::label;
pub(crate) use crate::geometry::name;
use crate::warning::Warning;
use eom_sym::scalar::Scalar;
use eom_sym::{Dd, Expr};

/// The scalar types a model can hold and be converted between: eom-sym's [`Expr`], `f64` and
/// [`Dd`].
pub trait ModelScalar: Scalar + Send + Sync + 'static {}

impl ModelScalar for f64 {}
impl ModelScalar for Dd {}
impl ModelScalar for Expr {}

/// What messages and model files know of an item kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Kind {
    /// How messages name it: `flex point`.
    pub name: &'static str,
    /// Its array of tables in a model file: `[[flex_point]]`.
    pub key: &'static str,
    /// The keys its tables take besides `name` and `mirror`.
    pub keys: &'static [&'static str],
}

/// The keys every table of a body or item takes besides its kind's own.
pub const COMMON_KEYS: [&str; 2] = ["name", "mirror"];

/// The body: not an item (a model keeps its bodies apart and first), but a table of a model
/// file like one.
pub const BODY: Kind = Body::<f64>::KIND;

/// Lists the item kinds (each declared with its name, key and fields by `item!` in its
/// module), in the order in which a model stores, validates and assembles them. From this
/// come the closed enum [`AnyItem`] (with the [`Item`] methods dispatched to the kind),
/// [`KindId`], [`KINDS`], and the conversions [`Model::add`] takes.
///
/// [`Model::add`]: crate::Model::add
macro_rules! kinds {
    ($($kind:ident),* $(,)?) => {
        /// Any item of a model: one variant per kind (bodies are kept apart).
        #[derive(Clone, Debug, PartialEq)]
        pub enum AnyItem<S> {
            $(
                #[doc = concat!("A [`", stringify!($kind), "`].")]
                $kind($kind<S>),
            )*
        }

        /// The item kinds, in the order of [`KINDS`].
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum KindId {
            $(
                #[doc = concat!("The kind of [`", stringify!($kind), "`].")]
                $kind,
            )*
        }

        const ALL_KINDS: [KindId; KINDS.len()] = [$(KindId::$kind,)*];

        /// The item kinds in the order in which a model stores, validates and assembles them
        /// (bodies are kept apart and come first). The order fixes the order of the
        /// constraint rows and of their multipliers: the elastic rows are the springs', the
        /// flex points' and then the beams'; the holonomic rows the links' and then the rigid
        /// points'. Inputs come before outputs, so a sensor finds the actuator it feeds
        /// through.
        pub const KINDS: &[Kind] = &[$($kind::<f64>::KIND,)*];

        impl<S> AnyItem<S> {
            /// The item's kind.
            pub fn kind_id(&self) -> KindId {
                match self {
                    $(AnyItem::$kind(_) => KindId::$kind,)*
                }
            }

            /// The item converted field by field with `f`, in the order of [`Item::fields`].
            pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> AnyItem<T>
            where
                S: Scalar,
            {
                match self {
                    $(AnyItem::$kind(x) => AnyItem::$kind(x.map(f)),)*
                }
            }

            /// The kind as messages name it (`flex point`).
            pub fn kind(&self) -> &'static str {
                self.kind_id().kind().name
            }

            /// The item's name.
            pub fn name(&self) -> &Name {
                match self {
                    $(AnyItem::$kind(x) => &x.name,)*
                }
            }

            /// The item as its kind's [`Item`].
            pub fn as_item(&self) -> &dyn Item<S>
            where
                S: ModelScalar,
            {
                match self {
                    $(AnyItem::$kind(x) => x,)*
                }
            }

            /// An item of kind `id` with every field at its declared default.
            pub(crate) fn declared(id: KindId, name: &str) -> Self
            where
                S: Scalar,
            {
                match id {
                    $(KindId::$kind => AnyItem::$kind($kind::declared(name)),)*
                }
            }

            /// Sets every field of the item that `source` gives.
            pub(crate) fn read<R: Source<S>>(&mut self, source: &R) -> Result<(), R::Error> {
                match self {
                    $(AnyItem::$kind(x) => x.read(source),)*
                }
            }
        }

        $(
            impl<S> From<$kind<S>> for AnyItem<S> {
                fn from(x: $kind<S>) -> Self {
                    AnyItem::$kind(x)
                }
            }

            impl<S> From<$kind<S>> for Part<S> {
                fn from(x: $kind<S>) -> Self {
                    Part::Item(AnyItem::$kind(x))
                }
            }
        )*
    };
}

kinds! {
    Load, Spring, FlexPoint, Beam, Link, RigidPoint, NhPoint, Wing, Strip, Actuator, Sensor,
}

impl KindId {
    /// Every kind, in the order of [`KINDS`].
    pub const ALL: &'static [KindId] = &ALL_KINDS;

    /// What messages and model files know of the kind.
    pub fn kind(self) -> &'static Kind {
        &KINDS[self as usize]
    }
}

/// A body or an item: what [`Model::add`](crate::Model::add) takes.
#[derive(Clone, Debug, PartialEq)]
pub enum Part<S> {
    /// A body (kept apart from the items).
    Body(Body<S>),
    /// An item.
    Item(AnyItem<S>),
}

impl<S> From<Body<S>> for Part<S> {
    fn from(b: Body<S>) -> Self {
        Part::Body(b)
    }
}

impl<S> From<AnyItem<S>> for Part<S> {
    fn from(x: AnyItem<S>) -> Self {
        Part::Item(x)
    }
}

/// An item dispatches to its kind.
impl<S: ModelScalar> Declared<S> for AnyItem<S> {
    fn item_kind(&self) -> &'static str {
        AnyItem::kind(self)
    }
    fn item_name(&self) -> &Name {
        AnyItem::name(self)
    }
    fn item_bodies(&self) -> &[Name] {
        self.as_item().bodies()
    }
    fn item_supports(&self) -> bool {
        self.as_item().supports()
    }
    /// Checked by the kind's own validation (which this dispatches to).
    fn check_shapes(&self, _warn: &mut dyn FnMut(Warning)) -> Result<(), ModelError> {
        Ok(())
    }
    fn visit_fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.as_item().fields(f)
    }
    fn list_settings(&self) -> Vec<(&'static str, Setting)> {
        self.as_item().settings()
    }
}

/// An item dispatches to its kind.
impl<S: ModelScalar> Physics<S> for AnyItem<S> {
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.as_item().validate(cx)
    }
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        self.as_item().assemble(cx)
    }
}

/// Every declared kind with its physics is an item.
impl<S, T> Item<S> for T
where
    S: ModelScalar,
    T: Declared<S> + Physics<S> + std::fmt::Debug + Send + Sync,
{
    fn kind(&self) -> &'static str {
        self.item_kind()
    }
    fn name(&self) -> &Name {
        self.item_name()
    }
    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.visit_fields(f)
    }
    fn settings(&self) -> Vec<(&'static str, Setting)> {
        self.list_settings()
    }
    fn bodies(&self) -> &[Name] {
        self.item_bodies()
    }
    fn supports(&self) -> bool {
        self.item_supports()
    }
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.check_shapes(&mut |w| cx.warn(w))?;
        Physics::validate(self, cx)
    }
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        Physics::assemble(self, cx)
    }
}

/// What every item kind implements: its fields, its checks, the bodies it connects and its
/// contribution to the linearized equations. See the crate documentation, "Adding an item
/// kind".
pub trait Item<S>: std::fmt::Debug + Send + Sync {
    /// The kind as it appears in messages and in [`KINDS`], e.g. `"flex point"`.
    fn kind(&self) -> &'static str;

    /// The item's name, unique among the items of a model.
    fn name(&self) -> &Name;

    /// Visit every scalar field with its name, in the order in which the kind's `map`
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

/// Visit the two points of field `name` (`ends[1][x]` …).
pub(crate) fn visit_ends<S>(f: &mut dyn FnMut(Field, &S), name: &'static str, ends: &[Vec3<S>; 2]) {
    for (i, end) in ends.iter().enumerate() {
        for (k, x) in end.iter().enumerate() {
            f(Field::nth_axis(name, i, k), x);
        }
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

    /// Checks the contract between [`Item::fields`] and the kind's `map` for a body or item
    /// whose fields hold the distinct values 1, 2, 3, …: the map visits the fields in the
    /// order of `fields`, converts every one of them, and keeps their names.
    fn check_fields_and_map(part: impl Into<Part<f64>>) {
        let part = part.into();
        let mut seen = Vec::new();
        let mut convert = |x: &f64| {
            seen.push(*x);
            *x + 1000.0
        };
        let mapped = match &part {
            Part::Body(b) => Part::Body(b.map(&mut convert)),
            Part::Item(x) => Part::Item(x.map(&mut convert)),
        };
        let item = |p: &Part<f64>| -> Box<dyn Item<f64>> {
            match p {
                Part::Body(b) => Box::new(b.clone()),
                Part::Item(x) => Box::new(x.clone()),
            }
        };
        let (item, mapped) = (item(&part), item(&mapped));
        let mut names = Vec::new();
        let mut values = Vec::new();
        item.fields(&mut |fd, x| {
            names.push(fd.to_string());
            values.push(*x);
        });
        assert_eq!(
            seen, values,
            "map visits the fields in the order of fields()"
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
        fn v(&self) -> Vec3<f64> {
            [self.x(), self.x(), self.x()]
        }
    }

    /// Every kind's field visitor and conversion agree (fields with distinct values).
    #[test]
    fn fields_and_map_agree() {
        let c = Counter::default();
        check_fields_and_map(
            Body::new("b")
                .at(c.v())
                .moments(c.v())
                .products(c.v())
                .velocity(c.v())
                .angular_velocity(c.v())
                .mass(100.0),
        );
        check_fields_and_map(
            Load::new("l", "b")
                .at(c.v())
                .force(c.v())
                .moment(c.v())
                .frame("b"),
        );
        check_fields_and_map(
            Spring::new("s")
                .between("a", "b")
                .ends(c.v(), c.v())
                .stiffness(c.x())
                .damping(c.x())
                .inertance(c.x())
                .preload(c.x()),
        );
        check_fields_and_map(
            Spring::new("t")
                .ends(c.v(), c.v())
                .stiffness(c.x())
                .damping(c.x())
                .inertance(c.x()),
        );
        check_fields_and_map(
            FlexPoint::new("p")
                .between("a", "b")
                .at(c.v())
                .axis(c.v())
                .rolling_axis(c.v())
                .forces(1)
                .moments(1)
                .stiffness(c.x(), c.x())
                .damping(c.x(), c.x())
                .stiffness_matrix(vec![vec![c.x(), c.x()], vec![c.x(), c.x()]])
                .damping_matrix(vec![vec![c.x(), c.x()], vec![c.x(), c.x()]]),
        );
        check_fields_and_map(
            Beam::new("b")
                .between("a", "b")
                .ends(c.v(), c.v())
                .stiffness(c.x(), c.x())
                .mpul(c.x())
                .perp(c.v()),
        );
        check_fields_and_map(Link::new("l").between("a", "b").ends(c.v(), c.v()));
        check_fields_and_map(
            RigidPoint::new("p")
                .between("a", "b")
                .at(c.v())
                .axis(c.v())
                .rolling_axis(c.v()),
        );
        check_fields_and_map(
            NhPoint::new("p")
                .between("a", "b")
                .at(c.v())
                .axis(c.v())
                .rolling_axis(c.v()),
        );
        let mut w = Wing::new("w")
            .on("a")
            .at(c.v())
            .axes(c.v(), c.v())
            .area(c.x())
            .chord(c.x())
            .span(c.x())
            .density(c.x())
            .airspeed(c.x());
        for n in WING_DERIVATIVES
            .iter()
            .flatten()
            .chain(&WING_ACCELERATION_DERIVATIVES)
        {
            w = w.derivative(n, c.x());
        }
        check_fields_and_map(w);
        check_fields_and_map(
            Strip::new("s")
                .on("a")
                .at(c.v())
                .axes(c.v(), c.v())
                .semichord(c.x())
                .elastic_axis(c.x())
                .width(c.x())
                .lift_slope(c.x())
                .density(c.x())
                .airspeed(c.x()),
        );
        check_fields_and_map(
            Actuator::new("a")
                .between("a", "b")
                .ends(c.v(), c.v())
                .gain(c.x())
                .rate_gain(c.x()),
        );
        check_fields_and_map(
            Sensor::new("s")
                .between("a", "b")
                .ends(c.v(), c.v())
                .gain(c.x())
                .feedthrough("a", c.x()),
        );
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
    fn every_kind_names_itself_as_declared() {
        let all: Vec<AnyItem<f64>> = vec![
            Load::new("a", "b").into(),
            Spring::new("a").into(),
            FlexPoint::new("a").into(),
            Beam::new("a").into(),
            Link::new("a").into(),
            RigidPoint::new("a").into(),
            NhPoint::new("a").into(),
            Wing::new("a").into(),
            Strip::new("a").into(),
            Actuator::new("a").into(),
            Sensor::new("a").into(),
        ];
        assert_eq!(all.len(), KINDS.len());
        for (i, x) in all.iter().enumerate() {
            assert_eq!(x.kind_id() as usize, i);
            assert_eq!(x.as_item().kind(), KINDS[i].name);
            assert_eq!(x.kind(), KINDS[i].name);
        }
    }
}
