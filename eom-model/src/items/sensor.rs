//! [`Sensor`]: an output measuring the elongation (or twist) of a line, or its rates.

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::{Assembly, OutputFrame, OutputKind, OutputOrder};
use crate::error::ModelError;
use crate::geometry::{Line, line_builders};
use eom_sym::scalar::Scalar;

/// What a sensor measures: the elongation (or twist) of its line, or its first or second
/// derivative.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensorOrder {
    /// Displacement.
    Displacement,
    /// Velocity.
    Velocity,
    /// Acceleration.
    Acceleration,
}

/// The frame in which a sensor's velocity or acceleration is taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensorFrame {
    /// Global (rates of the global displacement).
    Global,
    /// Body-fixed (perturbation velocities in the axes of the moving bodies; accelerations as
    /// felt by the body: `δv̇ + δω × v`).
    Local,
}

/// A sensor: output `gain × elongation` (or its rate / acceleration) of its line.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensor<S> {
    /// Unique name (the output's name).
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
    /// Gain.
    pub gain: S,
    /// Displacement, velocity or acceleration.
    pub order: SensorOrder,
    /// Global or body frame.
    pub frame: SensorFrame,
    /// An actuator whose input is fed through to this output.
    pub actuator: Option<Name>,
    /// Coefficient of that feedthrough (default −1).
    pub actuator_gain: S,
    /// Unit label.
    pub units: String,
}
impl<S: Scalar> Sensor<S> {
    /// A displacement sensor with gain 1.
    pub fn new(n: &str) -> Self {
        Sensor {
            name: name(n),
            line: Line::new(),
            gain: S::one(),
            order: SensorOrder::Displacement,
            frame: SensorFrame::Global,
            actuator: None,
            actuator_gain: -S::one(),
            units: "m".into(),
        }
    }
    /// Gain.
    pub fn gain(mut self, g: impl Into<S>) -> Self {
        self.gain = g.into();
        self
    }
    /// Measure the velocity.
    pub fn velocity(mut self) -> Self {
        self.order = SensorOrder::Velocity;
        self
    }
    /// Measure the acceleration.
    pub fn acceleration(mut self) -> Self {
        self.order = SensorOrder::Acceleration;
        self
    }
    /// Take rates in the body frame.
    pub fn local(mut self) -> Self {
        self.frame = SensorFrame::Local;
        self
    }
    /// Feed the input of `actuator` through with coefficient `gain`.
    pub fn feedthrough(mut self, actuator: &str, gain: impl Into<S>) -> Self {
        self.actuator = Some(name(actuator));
        self.actuator_gain = gain.into();
        self
    }
    /// Unit label.
    pub fn units(mut self, u: &str) -> Self {
        self.units = u.into();
        self
    }
}
line_builders!(Sensor);

impl<S> Sensor<S> {
    /// What the sensor's output row measures, in the assembly's terms.
    fn output_kind(&self) -> OutputKind {
        OutputKind {
            order: match self.order {
                SensorOrder::Displacement => OutputOrder::Displacement,
                SensorOrder::Velocity => OutputOrder::Velocity,
                SensorOrder::Acceleration => OutputOrder::Acceleration,
            },
            frame: match self.frame {
                SensorFrame::Global => OutputFrame::Global,
                SensorFrame::Local => OutputFrame::Local,
            },
        }
    }
}

impl<S: Scalar> Sensor<S> {
    /// The sensor converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> Sensor<T> {
        Sensor {
            name: self.name.clone(),
            line: self.line.map(f),
            gain: f(&self.gain),
            order: self.order,
            frame: self.frame,
            actuator: self.actuator.clone(),
            actuator_gain: f(&self.actuator_gain),
            units: self.units.clone(),
        }
    }
}

impl<S: ModelScalar> Item<S> for Sensor<S> {
    fn kind(&self) -> &'static str {
        "sensor"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        use super::Setting::Text;
        let mut s = self.line.settings();
        let order = match self.order {
            SensorOrder::Displacement => "displacement",
            SensorOrder::Velocity => "velocity",
            SensorOrder::Acceleration => "acceleration",
        };
        s.push(("order", Text(order.into())));
        let frame = match self.frame {
            SensorFrame::Global => "global",
            SensorFrame::Local => "local",
        };
        s.push(("frame", Text(frame.into())));
        if let Some(a) = &self.actuator {
            s.push(("feedthrough", Text(a.to_string())));
        }
        s.push(("units", Text(self.units.clone())));
        s
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.line.fields(f);
        f(Field::scalar("gain"), &self.gain);
        f(Field::scalar("actuator_gain"), &self.actuator_gain);
    }

    fn bodies(&self) -> &[Name] {
        &self.line.bodies
    }

    fn supports(&self) -> bool {
        false
    }

    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.line.validate("sensor", &self.name)?;
        match &self.actuator {
            Some(a) => cx.check_item("sensor", &self.name, "actuator", "actuator", a),
            None => Ok(()),
        }
    }

    /// A row of the output matrices, and the feedthrough of its actuator.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, _) = cx.line(&self.line, "sensor", &self.name);
        let output = cx.output(&self.name, &self.units, self.output_kind());
        for &(j, v) in &rows.rows[0] {
            cx.add_output(output, j, -(self.gain * v));
        }
        if let Some(a) = &self.actuator {
            let input = cx.input_index(a).ok_or_else(|| {
                super::field_error(
                    "sensor",
                    &self.name,
                    "actuator",
                    format!("unknown actuator `{a}`"),
                )
            })?;
            cx.add_feedthrough(output, input, self.actuator_gain);
        }
        Ok(())
    }
}
