//! How a point item lists its [`Point`]: its settings and its scalar fields.

use super::{Field, Setting, visit3};
use crate::geometry::Point;

impl<S> Point<S> {
    /// `between`, `forces` and `moments`.
    pub(crate) fn settings(&self) -> Vec<(&'static str, Setting)> {
        vec![
            (
                "between",
                Setting::Pair(self.bodies.clone().map(|b| b.to_string())),
            ),
            ("forces", Setting::Count(self.forces)),
            ("moments", Setting::Count(self.moments)),
        ]
    }

    /// Visit the location and the two axes, in the order of [`Point::map`].
    pub(crate) fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        visit3(f, "location", &self.location);
        visit3(f, "axis", &self.axis);
        visit3(f, "rolling_axis", &self.rolling_axis);
    }
}
