//! [`Spring`]: a spring–damper–inerter along (or, twisted, about) a line.

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::{Assembly, Reaction, Term};
use crate::error::ModelError;
use crate::geometry::{Line, line_builders};
use eom_sym::scalar::Scalar;

/// A spring–damper–inerter along (or, twisted, about) a line.
#[derive(Clone, Debug, PartialEq)]
pub struct Spring<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
    /// Stiffness (N/m, or N·m/rad twisted).
    pub stiffness: S,
    /// Damping.
    pub damping: S,
    /// Inertance (force proportional to relative acceleration).
    pub inertance: S,
    /// Known tension at the given geometry; `None` = solved from equilibrium.
    pub preload: Option<S>,
}
impl<S: Scalar> Spring<S> {
    /// A spring with zero properties.
    pub fn new(n: &str) -> Self {
        Spring {
            name: name(n),
            line: Line::new(),
            stiffness: S::zero(),
            damping: S::zero(),
            inertance: S::zero(),
            preload: None,
        }
    }
    /// Stiffness.
    pub fn stiffness(mut self, k: impl Into<S>) -> Self {
        self.stiffness = k.into();
        self
    }
    /// Damping.
    pub fn damping(mut self, c: impl Into<S>) -> Self {
        self.damping = c.into();
        self
    }
    /// Inertance.
    pub fn inertance(mut self, b: impl Into<S>) -> Self {
        self.inertance = b.into();
        self
    }
    /// Known preload (tension positive).
    pub fn preload(mut self, t: impl Into<S>) -> Self {
        self.preload = Some(t.into());
        self
    }
}
line_builders!(Spring);

impl<S: Scalar> Spring<S> {
    /// The spring converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Spring<T> {
        Spring {
            name: self.name.clone(),
            line: self.line.map(f),
            stiffness: f(&self.stiffness),
            damping: f(&self.damping),
            inertance: f(&self.inertance),
            preload: self.preload.as_ref().map(&mut *f),
        }
    }
}

impl<S: ModelScalar> Item<S> for Spring<S> {
    fn kind(&self) -> &'static str {
        "spring"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        self.line.settings()
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.line.fields(f);
        f(Field::scalar("stiffness"), &self.stiffness);
        f(Field::scalar("damping"), &self.damping);
        f(Field::scalar("inertance"), &self.inertance);
        if let Some(p) = &self.preload {
            f(Field::scalar("preload"), p);
        }
    }

    fn bodies(&self) -> &[Name] {
        &self.line.bodies
    }

    fn supports(&self) -> bool {
        true
    }

    fn validate(&self, _cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.line.validate("spring", &self.name)
    }

    /// One elastic row with its stiffness, damping and inertance; its multiplier is the
    /// tension, known when a preload is given.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, geometry) = cx.line(&self.line, "spring", &self.name);
        cx.add_rows_block(Term::Stiffness, &rows.rows, &[vec![self.stiffness]]);
        cx.add_rows_block(Term::Damping, &rows.rows, &[vec![self.damping]]);
        cx.add_rows_block(Term::ItemMass, &rows.rows, &[vec![self.inertance]]);
        let row = cx.elastic(
            "spring",
            &self.name,
            rows,
            vec![vec![self.stiffness]],
            Reaction::Line(geometry),
        );
        if let Some(p) = self.preload {
            cx.known_preload(row, p, self.stiffness);
        }
        Ok(())
    }
}
