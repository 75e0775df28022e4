//! [`Actuator`]: an input acting along (or about) a line.

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::Assembly;
use crate::error::ModelError;
use crate::geometry::{Line, line_builders};
use eom_sym::scalar::Scalar;

/// An actuator: generalized force `gain·u + rate_gain·u̇` that extends the line (or twists about
/// it).
#[derive(Clone, Debug, PartialEq)]
pub struct Actuator<S> {
    /// Unique name (the input's name).
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
    /// Gain.
    pub gain: S,
    /// Rate gain (force per input rate), e.g. a tyre damping driven by road displacement.
    pub rate_gain: S,
    /// Unit label of the input.
    pub units: String,
}
impl<S: Scalar> Actuator<S> {
    /// An actuator with gain 1.
    pub fn new(n: &str) -> Self {
        Actuator {
            name: name(n),
            line: Line::new(),
            gain: S::one(),
            rate_gain: S::zero(),
            units: "N".into(),
        }
    }
    /// Gain.
    pub fn gain(mut self, g: impl Into<S>) -> Self {
        self.gain = g.into();
        self
    }
    /// Rate gain.
    pub fn rate_gain(mut self, g: impl Into<S>) -> Self {
        self.rate_gain = g.into();
        self
    }
    /// Unit label.
    pub fn units(mut self, u: &str) -> Self {
        self.units = u.into();
        self
    }
}
line_builders!(Actuator);

impl<S: Scalar> Actuator<S> {
    /// The actuator converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Actuator<T> {
        Actuator {
            name: self.name.clone(),
            line: self.line.map(f),
            gain: f(&self.gain),
            rate_gain: f(&self.rate_gain),
            units: self.units.clone(),
        }
    }
}

impl<S: ModelScalar> Item<S> for Actuator<S> {
    fn kind(&self) -> &'static str {
        "actuator"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        let mut s = self.line.settings();
        s.push(("units", super::Setting::Text(self.units.clone())));
        s
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.line.fields(f);
        f(Field::scalar("gain"), &self.gain);
        f(Field::scalar("rate_gain"), &self.rate_gain);
    }

    fn bodies(&self) -> &[Name] {
        &self.line.bodies
    }

    fn supports(&self) -> bool {
        false
    }

    fn validate(&self, _cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.line.validate("actuator", &self.name)
    }

    /// A column of the input matrices: the generalized force of `gain·u + rate_gain·u̇`
    /// extending the line.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, _) = cx.line(&self.line, "actuator", &self.name);
        let input = cx.input(&self.name, &self.units);
        for &(i, v) in &rows.rows[0] {
            cx.add_input_force(i, input, -(self.gain * v));
            if !self.rate_gain.is_zero() {
                cx.add_input_rate_force(i, input, -(self.rate_gain * v));
            }
        }
        Ok(())
    }
}
