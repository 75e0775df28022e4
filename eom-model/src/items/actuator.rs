//! [`Actuator`]: an input acting along (or about) a line.

use super::{ModelScalar, Physics, item};
use crate::assemble::Assembly;
use crate::error::ModelError;
use crate::geometry::Line;
use eom_sym::scalar::Scalar;

item! {
    /// An actuator: generalized force `gain·u + rate_gain·u̇` that extends the line (or twists
    /// about it).
    pub struct Actuator<S>: "actuator", "actuator"
        (bodies: line, supports: false)
    {
        /// Geometry.
        pub line: Line<S> = Line::new() => line(),
        /// Gain.
        pub gain: S = S::one() => scalar(gain, "gain"),
        /// Rate gain (force per input rate), e.g. a tyre damping driven by road displacement.
        pub rate_gain: S = S::zero() => scalar(rate_gain, "rate_gain"),
        /// Unit label of the input.
        pub units: String = "N".into() => text(units, "units"),
    }
    /// An actuator with gain 1.
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for Actuator<S> {
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
