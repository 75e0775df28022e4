//! [`Link`]: an inextensible rigid link between two bodies.

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::{Assembly, Reaction};
use crate::error::ModelError;
use crate::geometry::{Line, line_builders};
use eom_sym::scalar::Scalar;

/// An inextensible rigid link.
#[derive(Clone, Debug, PartialEq)]
pub struct Link<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
}
impl<S: Scalar> Link<S> {
    /// A link between ground and ground (set bodies and ends).
    pub fn new(n: &str) -> Self {
        Link {
            name: name(n),
            line: Line::new(),
        }
    }
}
line_builders!(Link);

impl<S: Scalar> Link<S> {
    /// The link converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Link<T> {
        Link {
            name: self.name.clone(),
            line: self.line.map(f),
        }
    }
}

impl<S: ModelScalar> Item<S> for Link<S> {
    fn kind(&self) -> &'static str {
        "link"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        self.line.settings()
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.line.fields(f);
    }

    fn bodies(&self) -> &[Name] {
        &self.line.bodies
    }

    fn supports(&self) -> bool {
        true
    }

    fn validate(&self, _cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.line.validate("link", &self.name)
    }

    /// One holonomic row; its multiplier is the tension.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, geometry) = cx.line(&self.line, "link", &self.name);
        cx.holonomic("link", &self.name, rows, Reaction::Line(geometry));
        Ok(())
    }
}
