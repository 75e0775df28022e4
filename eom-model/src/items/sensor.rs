//! [`Sensor`]: an output measuring the elongation (or twist) of a line, or its rates.

use super::Validation;
use super::{Choice, ModelScalar, Name, Physics, item, name};
use crate::assemble::{Assembly, OutputFrame, OutputKind, OutputOrder};
use crate::error::{ItemRef, ModelError};
use crate::geometry::Line;
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

item! {
    /// A sensor: output `gain × elongation` (or its rate / acceleration) of its line.
    pub struct Sensor<S>: "sensor", "sensor"
        (bodies: line, supports: false)
    {
        /// Geometry.
        pub line: Line<S> = Line::new() => line(),
        /// Gain.
        pub gain: S = S::one() => scalar(gain, "gain"),
        /// Displacement, velocity or acceleration.
        pub order: SensorOrder = SensorOrder::Displacement => choice("order"),
        /// Global or body frame.
        pub frame: SensorFrame = SensorFrame::Global => choice("frame"),
        /// An actuator whose input is fed through to this output.
        pub actuator: Option<Name> = None => item_ref("feedthrough"),
        /// Coefficient of that feedthrough (default −1).
        pub actuator_gain: S = -S::one() => part_of("feedthrough"),
        /// Unit label.
        pub units: String = "m".into() => text(units, "units"),
    }
    /// A displacement sensor with gain 1.
    pub fn new;
}

impl<S: Scalar> Sensor<S> {
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
}

impl Choice for SensorOrder {
    fn name(self) -> &'static str {
        match self {
            SensorOrder::Displacement => "displacement",
            SensorOrder::Velocity => "velocity",
            SensorOrder::Acceleration => "acceleration",
        }
    }
    fn from_name(s: &str) -> Result<Self, String> {
        match s {
            "displacement" => Ok(SensorOrder::Displacement),
            "velocity" => Ok(SensorOrder::Velocity),
            "acceleration" => Ok(SensorOrder::Acceleration),
            other => Err(format!(
                "`{other}` is not a sensor order; use displacement, velocity or acceleration"
            )),
        }
    }
}

impl Choice for SensorFrame {
    fn name(self) -> &'static str {
        match self {
            SensorFrame::Global => "global",
            SensorFrame::Local => "local",
        }
    }
    fn from_name(s: &str) -> Result<Self, String> {
        match s {
            "global" => Ok(SensorFrame::Global),
            "local" => Ok(SensorFrame::Local),
            other => Err(format!(
                "`{other}` is not a sensor frame; use global or local"
            )),
        }
    }
}

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

impl<S: ModelScalar> Physics<S> for Sensor<S> {
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
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
            let input = cx.input_index(a).ok_or_else(|| ModelError::UnknownItem {
                item: ItemRef::new("sensor", &self.name),
                field: "actuator",
                kind: "actuator",
                name: a.to_string(),
                known: None,
            })?;
            cx.add_feedthrough(output, input, self.actuator_gain);
        }
        Ok(())
    }
}
