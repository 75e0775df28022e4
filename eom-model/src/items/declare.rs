//! How an item kind is declared: once, with its fields (`item!`), from which come its struct,
//! its defaults and builders, its conversion to another scalar type, the listing of its fields
//! and settings, its model-file keys and the reading of its table.
//!
//! A kind's declaration reads like its struct:
//!
//! ```text
//! item! {
//!     /// A spring–damper–inerter along (or, twisted, about) a line.
//!     pub struct Spring<S>: "spring", "spring" (bodies: line, supports: true) {
//!         /// Geometry.
//!         line: Line<S> = Line::new() => line(),
//!         /// Stiffness (N/m, or N·m/rad twisted).
//!         stiffness: S = S::zero() => scalar(stiffness, "stiffness"),
//!         /// Known tension at the given geometry; `None` = solved from equilibrium.
//!         preload: Option<S> = None => optional(preload, "preload"),
//!     }
//!     /// A spring with zero properties.
//!     pub fn new;
//! }
//! ```
//!
//! The header gives the kind's name in messages and its model-file key, the field that holds
//! the bodies it connects (`none` for a body) and whether it supports them (`true`, `false`
//! or a method such as `point.constrains()`); `pub fn new;` with its documentation makes the
//! constructor that takes a name and leaves every field at its default.
//!
//! Each field gives its type, its default, and after `=>` its *shape*: what it is in a model
//! file and how its builder takes it (the builder's name, then the file key). The shapes:
//!
//! | shape | field type | builder | in a model file |
//! |---|---|---|---|
//! | `scalar(b, "k")` | `S` | `b(impl Into<S>)` | `k = expr` |
//! | `optional(b, "k")` | `Option<S>` | `b(impl Into<S>)` sets it | `k = expr` |
//! | `vector(b, "k", Polar)` | `Vec3<S>` | `b(Vec3<S>)` | `k = [x, y, z]`, mirrored as a [`VecKind`] |
//! | `pair(b, "k")` | `[S; 2]` | `b(a, b)` | `k = [a, b]` |
//! | `matrix(b, "k")` | `Option<Vec<Vec<S>>>` | `b(rows)` sets it | `k = [[…], …]` (square) |
//! | `ends(b, "k")` | `[Vec3<S>; 2]` | `b(p1, p2)` | `k = [[…], […]]` |
//! | `bodies(b, "k")` | `[Name; 2]` | `b(body1, body2)` | `k = ["a", "b"]` |
//! | `body(b, "k")` | `Name` | `b(&str)` | `k = "body"` (must exist) |
//! | `text(b, "k")` | `String` | `b(&str)` | `k = "text"` |
//! | `choice(b, "k")` | a [`Choice`] | `b(value)` | `k = "name"` (`unless_default`: exported only when set) |
//! | `line()` | [`Line`] | `between`, `ends`, `twist` | `between`, `ends`, `twist` |
//! | `point()` | [`Point`] | `between`, `at`, `forces`, `moments`, `axis`, `rolling_axis` | the same keys |
//! | `part_of("k")` | `S` | written by hand | part of key `k`, read by hand |
//! | `item_ref("k")` | `Option<Name>` | written by hand | key `k`, read by hand |
//! | `named(NAMES)`, `named_rows(NAMES, "k"…)` | `[S; N]`, `[[S; N]; M]` | written by hand | keys `k`…, read by hand; fields named by `NAMES` |
//! | `hidden()` | any `Clone` | none | none |
//!
//! Fields that several kinds share, with the same documentation, default, shape and keys,
//! are declared once as a *group*: a macro that takes `(args) [header] [fields so far]
//! [fields to come] rest` and hands them back to `item!(@fields …)` with its own fields put
//! in after those so far. A kind lists the group among its fields as `..group!(args),`
//! (the lifting surfaces' `..surface_fields!(mount),` and `..surface_fields!(air),`, in
//! `surface.rs`); the group's fields take that place in the struct, the listing and the keys.
//!
//! The builder may be left out (`vector("forward", Polar)`) where a hand-written builder sets
//! the field (a wing's `axes` sets `forward` and `down`). What a kind does — the bodies it
//! connects, whether it supports them, its checks and its terms — is its [`Physics`], written
//! by hand in its module.

use super::{Field, Name, Setting, Vec3};
use crate::assemble::Assembly;
use crate::error::ModelError;
use crate::warning::Warning;

/// What a declaration gives of an item (implemented by `item!`; [`Item`](super::Item) is
/// implemented for every kind with its [`Physics`]).
pub trait Declared<S> {
    /// The kind's name in messages.
    fn item_kind(&self) -> &'static str;
    /// The item's name.
    fn item_name(&self) -> &Name;
    /// The bodies it connects (the field named by `bodies:`).
    fn item_bodies(&self) -> &[Name];
    /// Whether it supports them (`supports:` `true`, `false` or a method).
    fn item_supports(&self) -> bool;
    /// Visit every scalar field, in the order of the kind's `map`.
    fn visit_fields(&self, f: &mut dyn FnMut(Field, &S));
    /// The settings that are not scalar fields, by their model-file keys.
    fn list_settings(&self) -> Vec<(&'static str, Setting)>;
    /// The checks of its shared shapes (a line's length, a point's directions), before the
    /// kind's own [`Physics::validate`]; warnings go to `warn`.
    fn check_shapes(&self, warn: &mut dyn FnMut(Warning)) -> Result<(), ModelError>;
}

/// What a kind does, written by hand in its module: its checks and its terms (see
/// [`Item`](super::Item) for each).
pub trait Physics<S> {
    /// See [`Item::validate`](super::Item::validate): the kind's own checks, after those of
    /// its shapes ([`Declared::check_shapes`]); none by default.
    fn validate(&self, _cx: &mut super::Validation<'_, S>) -> Result<(), ModelError> {
        Ok(())
    }
    /// See [`Item::assemble`](super::Item::assemble).
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError>;
}

/// A field that names the bodies an item connects (`bodies:` of a declaration).
pub trait Connects {
    /// The bodies.
    fn bodies(&self) -> &[Name];
}

impl Connects for Name {
    fn bodies(&self) -> &[Name] {
        std::slice::from_ref(self)
    }
}

impl Connects for [Name; 2] {
    fn bodies(&self) -> &[Name] {
        self
    }
}

impl<S> Connects for super::Line<S> {
    fn bodies(&self) -> &[Name] {
        &self.bodies
    }
}

impl<S> Connects for super::Point<S> {
    fn bodies(&self) -> &[Name] {
        &self.bodies
    }
}

/// A setting chosen by name from a few (`unsteady = "jones"`, `order = "velocity"`).
pub trait Choice: Copy + PartialEq {
    /// The name a model file uses.
    fn name(self) -> &'static str;
    /// The value of a name, or the message saying what the names are.
    fn from_name(s: &str) -> Result<Self, String>;
}

/// How a vector transforms under a mirror: a position or direction (polar), a rotation or
/// moment (axial, a pseudo-vector), the products of inertia, or not at all (moments of
/// inertia).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VecKind {
    /// A position or direction.
    Polar,
    /// A rotation or moment.
    Axial,
    /// Products of inertia `[xy, yz, zx]`.
    Products,
    /// Unchanged by a mirror.
    Plain,
}

/// Where a kind's fields are read from: a model file's table, with its positions and mirror
/// (implemented in `file`). Each method gives the value of key `key` if the table has it;
/// names of bodies come checked and, in a mirrored copy, mirrored.
pub trait Source<S> {
    /// The error of a bad value.
    type Error;
    /// A number or expression.
    fn scalar(&self, key: &'static str) -> Result<Option<S>, Self::Error>;
    /// A vector, mirrored as `kind`.
    fn vector(&self, key: &'static str, kind: VecKind) -> Result<Option<Vec3<S>>, Self::Error>;
    /// Two numbers.
    fn pair(&self, key: &'static str) -> Result<Option<[S; 2]>, Self::Error>;
    /// A square matrix.
    fn matrix(&self, key: &'static str) -> Result<Option<Vec<Vec<S>>>, Self::Error>;
    /// Two points (positions).
    fn ends(&self, key: &'static str) -> Result<Option<[Vec3<S>; 2]>, Self::Error>;
    /// Two body names.
    fn bodies(&self, key: &'static str) -> Result<Option<[Name; 2]>, Self::Error>;
    /// A body name.
    fn body(&self, key: &'static str) -> Result<Option<Name>, Self::Error>;
    /// A string.
    fn text(&self, key: &'static str) -> Result<Option<String>, Self::Error>;
    /// `true` or `false`.
    fn flag(&self, key: &'static str) -> Result<Option<bool>, Self::Error>;
    /// A count from 0 to `max`.
    fn count(&self, key: &'static str, max: u8) -> Result<Option<u8>, Self::Error>;
    /// One of the names of a [`Choice`].
    fn choice<T: Choice>(&self, key: &'static str) -> Result<Option<T>, Self::Error>;
}

/// The number of keys in `parts` (for [`concat_keys`]).
pub(crate) const fn key_count(parts: &[&[&str]]) -> usize {
    let (mut n, mut i) = (0, 0);
    while i < parts.len() {
        n += parts[i].len();
        i += 1;
    }
    n
}

/// The keys of `parts` in one array: a kind's keys, made at compile time from its fields'.
pub(crate) const fn concat_keys<const N: usize>(parts: &[&[&'static str]]) -> [&'static str; N] {
    let mut out = [""; N];
    let (mut k, mut i) = (0, 0);
    while i < parts.len() {
        let mut j = 0;
        while j < parts[i].len() {
            out[k] = parts[i][j];
            k += 1;
            j += 1;
        }
        i += 1;
    }
    out
}

/// A matrix field converted with `f`, row by row.
pub(crate) fn map_matrix<S, T>(
    m: &Option<Vec<Vec<S>>>,
    f: &mut dyn FnMut(&S) -> T,
) -> Option<Vec<Vec<T>>> {
    m.as_ref()
        .map(|m| m.iter().map(|r| r.iter().map(&mut *f).collect()).collect())
}

/// Declares an item kind with its fields (see the module documentation).
macro_rules! item {
    // ---------------------------------------------------------------- field groups
    // The declaration as written: its fields, with groups, go through `@fields` one by one;
    // a group `..group!(args),` hands the rest to the group's macro, which puts its fields in
    // and hands back (see `surface_fields!` in `surface.rs`).
    (
        $(#[doc = $doc:literal])*
        pub struct $kind:ident<S>: $label:literal, $key:literal
            (bodies: $bodies:ident, supports: $($supports:tt)+)
        { $($fields:tt)* }
        $($new:tt)*
    ) => {
        $crate::items::item!(@fields
            [$(#[doc = $doc])* pub struct $kind<S>: $label, $key
                (bodies: $bodies, supports: $($supports)+)]
            [] [$($fields)*] $($new)*);
    };
    (@fields [$($head:tt)*] [$($done:tt)*] [] $($new:tt)*) => {
        $crate::items::item!(@declare $($head)* { $($done)* } $($new)*);
    };
    (@fields [$($head:tt)*] [$($done:tt)*]
        [.. $group:ident ! ($($args:tt)*), $($rest:tt)*] $($new:tt)*) => {
        $crate::items::$group!(($($args)*) [$($head)*] [$($done)*] [$($rest)*] $($new)*);
    };
    (@fields [$($head:tt)*] [$($done:tt)*]
        [
            $(#[doc = $fdoc:literal])*
            $vis:vis $field:ident: $ty:ty = $default:expr => $shape:ident($($arg:tt)*),
            $($rest:tt)*
        ]
        $($new:tt)*) => {
        $crate::items::item!(@fields [$($head)*]
            [$($done)* $(#[doc = $fdoc])* $vis $field: $ty = $default => $shape($($arg)*),]
            [$($rest)*] $($new)*);
    };

    // ---------------------------------------------------------------- the declaration
    (
        @declare
        $(#[doc = $doc:literal])*
        pub struct $kind:ident<S>: $label:literal, $key:literal
            (bodies: $bodies:ident, supports: $($supports:tt)+)
        {
            $(
                $(#[doc = $fdoc:literal])*
                $vis:vis $field:ident: $ty:ty = $default:expr => $shape:ident($($arg:tt)*),
            )*
        }
        $($(#[doc = $newdoc:literal])+ pub fn new;)?
    ) => {
        $(#[doc = $doc])*
        #[derive(Clone, Debug, PartialEq)]
        pub struct $kind<S> {
            /// Unique name.
            pub name: $crate::geometry::Name,
            $($(#[doc = $fdoc])* $vis $field: $ty,)*
        }

        impl<S> $kind<S> {
            /// What messages and model files know of the kind.
            pub const KIND: $crate::items::Kind = $crate::items::Kind {
                name: $label,
                key: $key,
                keys: {
                    const PARTS: &[&[&str]] = &[$($crate::items::item!(@keys $shape($($arg)*)),)*];
                    const KEYS: [&str; $crate::items::key_count(PARTS)] =
                        $crate::items::concat_keys(PARTS);
                    &KEYS
                },
            };

            /// Sets every field that `source` gives; the others keep their values.
            pub(crate) fn read<R: $crate::items::Source<S>>(
                &mut self,
                source: &R,
            ) -> Result<(), R::Error> {
                $($crate::items::item!(@read $shape($($arg)*), self.$field, source);)*
                Ok(())
            }
        }

        impl<S: eom_sym::scalar::Scalar> $kind<S> {
            $(
                $(#[doc = $newdoc])+
                pub fn new(n: &str) -> Self {
                    Self::declared(n)
                }
            )?

            /// The kind with every field at its declared default.
            pub(crate) fn declared(n: &str) -> Self {
                $kind {
                    name: $crate::geometry::name(n),
                    $($field: $default,)*
                }
            }

            #[doc = concat!(
                "The ", $label, " converted field by field with `f`, in the order of ",
                "[`Item::fields`](crate::items::Item::fields)."
            )]
            pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> $kind<T> {
                $kind {
                    name: self.name.clone(),
                    $($field: $crate::items::item!(@map $shape($($arg)*), &self.$field, f),)*
                }
            }
        }

        $($crate::items::item!(@builder $kind [$($fdoc)*] $shape($($arg)*) $field: $ty);)*

        impl<S: eom_sym::scalar::Scalar> $crate::items::Declared<S> for $kind<S> {
            fn item_kind(&self) -> &'static str {
                $label
            }
            fn item_name(&self) -> &$crate::geometry::Name {
                &self.name
            }
            fn item_bodies(&self) -> &[$crate::geometry::Name] {
                $crate::items::item!(@bodies self, $bodies)
            }
            fn item_supports(&self) -> bool {
                $crate::items::item!(@supports self, $($supports)+)
            }
            #[allow(unused_variables)]
            fn visit_fields(&self, f: &mut dyn FnMut($crate::items::Field, &S)) {
                $(
                    let name = stringify!($field);
                    $crate::items::item!(@visit $shape($($arg)*), &self.$field, name, f);
                )*
            }
            #[allow(unused_variables)]
            fn check_shapes(
                &self,
                warn: &mut dyn FnMut($crate::warning::Warning),
            ) -> Result<(), $crate::error::ModelError> {
                $(
                    let x = &self.$field;
                    $crate::items::item!(@check $shape($($arg)*), x, $label, &self.name, warn);
                )*
                Ok(())
            }
            // Settings are pushed field by field, as the declaration lists them.
            #[allow(unused_mut, clippy::vec_init_then_push)]
            fn list_settings(&self) -> Vec<(&'static str, $crate::items::Setting)> {
                let mut out = Vec::new();
                $($crate::items::item!(@setting $shape($($arg)*), &self.$field, $default, out);)*
                out
            }
        }
    };

    // ---------------------------------------------------------------- bodies and support
    (@bodies $s:ident, none) => { &[] };
    (@bodies $s:ident, $f:ident) => { $crate::items::Connects::bodies(&$s.$f) };
    (@supports $s:ident, true) => { true };
    (@supports $s:ident, false) => { false };
    (@supports $s:ident, $($path:ident).+ ()) => { $s.$($path).+() };

    // ---------------------------------------------------------------- keys
    (@keys line()) => { $crate::geometry::Line::<()>::KEYS };
    (@keys point()) => { $crate::geometry::Point::<()>::KEYS };
    (@keys named_rows($names:path $(, $k:literal)*)) => { &[$($k),*] };
    (@keys part_of($k:literal)) => { &[] };
    (@keys $shape:ident($($b:ident,)? $k:literal $(, $rest:tt)*)) => { &[$k] };
    (@keys $shape:ident($($rest:tt)*)) => { &[] };

    // ---------------------------------------------------------------- reading
    (@read scalar($($b:ident,)? $k:literal), $x:expr, $r:ident) => {
        if let Some(v) = $r.scalar($k)? { $x = v; }
    };
    (@read optional($($b:ident,)? $k:literal), $x:expr, $r:ident) => {
        if let Some(v) = $r.scalar($k)? { $x = Some(v); }
    };
    (@read vector($($b:ident,)? $k:literal, $vk:ident), $x:expr, $r:ident) => {
        if let Some(v) = $r.vector($k, $crate::items::VecKind::$vk)? { $x = v; }
    };
    (@read matrix($($b:ident,)? $k:literal), $x:expr, $r:ident) => {
        if let Some(v) = $r.matrix($k)? { $x = Some(v); }
    };
    (@read choice($($b:ident,)? $k:literal $(, $when:ident)?), $x:expr, $r:ident) => {
        if let Some(v) = $r.choice($k)? { $x = v; }
    };
    (@read part_of($k:literal), $x:expr, $r:ident) => {};
    (@read item_ref($k:literal), $x:expr, $r:ident) => {};
    (@read line(), $x:expr, $r:ident) => { $x.read($r)?; };
    (@read point(), $x:expr, $r:ident) => { $x.read($r)?; };
    (@read $shape:ident($($b:ident,)? $k:literal), $x:expr, $r:ident) => {
        if let Some(v) = $r.$shape($k)? { $x = v; }
    };
    (@read $shape:ident($($rest:tt)*), $x:expr, $r:ident) => {};

    // ---------------------------------------------------------------- conversion
    (@map scalar($($rest:tt)*), $x:expr, $f:ident) => { $f($x) };
    (@map part_of($($rest:tt)*), $x:expr, $f:ident) => { $f($x) };
    (@map optional($($rest:tt)*), $x:expr, $f:ident) => { $x.as_ref().map(&mut *$f) };
    (@map vector($($rest:tt)*), $x:expr, $f:ident) => { $crate::geometry::map3($x, $f) };
    (@map pair($($rest:tt)*), $x:expr, $f:ident) => { [$f(&$x[0]), $f(&$x[1])] };
    (@map matrix($($rest:tt)*), $x:expr, $f:ident) => { $crate::items::map_matrix($x, $f) };
    (@map ends($($rest:tt)*), $x:expr, $f:ident) => {
        [$crate::geometry::map3(&$x[0], $f), $crate::geometry::map3(&$x[1], $f)]
    };
    (@map named($($rest:tt)*), $x:expr, $f:ident) => { std::array::from_fn(|i| $f(&$x[i])) };
    (@map named_rows($($rest:tt)*), $x:expr, $f:ident) => {
        std::array::from_fn(|i| std::array::from_fn(|j| $f(&$x[i][j])))
    };
    (@map line(), $x:expr, $f:ident) => { $x.map($f) };
    (@map point(), $x:expr, $f:ident) => { $x.map($f) };
    (@map $shape:ident($($rest:tt)*), $x:expr, $f:ident) => { $x.clone() };

    // ---------------------------------------------------------------- fields
    (@visit scalar($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        $f($crate::items::Field::scalar($n), $x)
    };
    (@visit part_of($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        $f($crate::items::Field::scalar($n), $x)
    };
    (@visit optional($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        if let Some(v) = $x { $f($crate::items::Field::scalar($n), v) }
    };
    (@visit vector($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        $crate::items::visit3($f, $n, $x)
    };
    (@visit pair($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        for (i, v) in $x.iter().enumerate() { $f($crate::items::Field::nth($n, i), v) }
    };
    (@visit matrix($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        for (i, row) in $x.iter().flatten().enumerate() {
            for (j, v) in row.iter().enumerate() { $f($crate::items::Field::entry($n, i, j), v) }
        }
    };
    (@visit ends($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {
        $crate::items::visit_ends($f, $n, $x)
    };
    (@visit named($names:path), $x:expr, $n:expr, $f:ident) => {
        for (n, v) in $names.iter().zip($x) { $f($crate::items::Field::scalar(n), v) }
    };
    (@visit named_rows($names:path $(, $k:literal)*), $x:expr, $n:expr, $f:ident) => {
        for (names, row) in $names.iter().zip($x) {
            for (n, v) in names.iter().zip(row) { $f($crate::items::Field::scalar(n), v) }
        }
    };
    (@visit line(), $x:expr, $n:expr, $f:ident) => { $x.fields($f) };
    (@visit point(), $x:expr, $n:expr, $f:ident) => { $x.fields($f) };
    (@visit $shape:ident($($rest:tt)*), $x:expr, $n:expr, $f:ident) => {};

    // ---------------------------------------------------------------- checks of the shapes
    (@check line(), $x:expr, $label:literal, $name:expr, $warn:ident) => {
        $x.validate($label, $name)?
    };
    (@check point(), $x:expr, $label:literal, $name:expr, $warn:ident) => {
        $x.validate($label, $name, $warn)?
    };
    (@check $shape:ident($($rest:tt)*), $x:expr, $label:literal, $name:expr, $warn:ident) => {};

    // ---------------------------------------------------------------- settings
    (@setting bodies($($b:ident,)? $k:literal), $x:expr, $d:expr, $out:ident) => {
        $out.push(($k, $crate::items::Setting::Pair($x.clone().map(|b| b.to_string()))))
    };
    (@setting body($($b:ident,)? $k:literal), $x:expr, $d:expr, $out:ident) => {
        $out.push(($k, $crate::items::Setting::Text($x.to_string())))
    };
    (@setting text($($b:ident,)? $k:literal), $x:expr, $d:expr, $out:ident) => {
        $out.push(($k, $crate::items::Setting::Text($x.clone())))
    };
    (@setting item_ref($k:literal), $x:expr, $d:expr, $out:ident) => {
        if let Some(a) = $x { $out.push(($k, $crate::items::Setting::Text(a.to_string()))) }
    };
    (@setting choice($($b:ident,)? $k:literal), $x:expr, $d:expr, $out:ident) => {
        $out.push(($k, $crate::items::Setting::Text($crate::items::Choice::name(*$x).into())))
    };
    (@setting choice($($b:ident,)? $k:literal, unless_default), $x:expr, $d:expr, $out:ident) => {
        if *$x != $d {
            $out.push(($k, $crate::items::Setting::Text($crate::items::Choice::name(*$x).into())))
        }
    };
    (@setting line(), $x:expr, $d:expr, $out:ident) => { $out.extend($x.settings()) };
    (@setting point(), $x:expr, $d:expr, $out:ident) => { $out.extend($x.settings()) };
    (@setting $shape:ident($($rest:tt)*), $x:expr, $d:expr, $out:ident) => {};

    // ---------------------------------------------------------------- builders
    (@builder $kind:ident [$($d:literal)*] scalar($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, x: impl Into<S>) -> Self {
                self.$f = x.into();
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] optional($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, x: impl Into<S>) -> Self {
                self.$f = Some(x.into());
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] pair($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, x1: impl Into<S>, x2: impl Into<S>) -> Self {
                self.$f = [x1.into(), x2.into()];
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] matrix($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, m: Vec<Vec<S>>) -> Self {
                self.$f = Some(m);
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] ends($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(
                mut self,
                p1: $crate::geometry::Vec3<S>,
                p2: $crate::geometry::Vec3<S>,
            ) -> Self {
                self.$f = [p1, p2];
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] bodies($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, b1: &str, b2: &str) -> Self {
                self.$f = [$crate::geometry::name(b1), $crate::geometry::name(b2)];
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] body($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, body: &str) -> Self {
                self.$f = $crate::geometry::name(body);
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] text($b:ident, $k:literal) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, text: &str) -> Self {
                self.$f = text.into();
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] line() $f:ident: $t:ty) => {
        $crate::geometry::line_builders!($kind);
    };
    (@builder $kind:ident [$($d:literal)*] point() $f:ident: $t:ty) => {
        $crate::geometry::point_builders!($kind);
    };
    (@builder $kind:ident [$($d:literal)*] named_rows($($rest:tt)*) $f:ident: $t:ty) => {};
    // `vector` and `choice` take the value itself.
    (@builder $kind:ident [$($d:literal)*]
        $shape:ident($b:ident, $k:literal $(, $rest:tt)*) $f:ident: $t:ty) => {
        impl<S> $kind<S> {
            $(#[doc = $d])*
            pub fn $b(mut self, x: $t) -> Self {
                self.$f = x;
                self
            }
        }
    };
    (@builder $kind:ident [$($d:literal)*] $shape:ident($($rest:tt)*) $f:ident: $t:ty) => {};
}
pub(crate) use item;
