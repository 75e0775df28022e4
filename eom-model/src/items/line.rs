//! How a line item lists its [`Line`]: its settings and its scalar fields.

use super::{Field, Setting};
use crate::geometry::Line;

impl<S> Line<S> {
    /// `between` and `twist`.
    pub(crate) fn settings(&self) -> Vec<(&'static str, Setting)> {
        vec![
            (
                "between",
                Setting::Pair(self.bodies.clone().map(|b| b.to_string())),
            ),
            ("twist", Setting::Flag(self.twist)),
        ]
    }

    /// Visit the end points, in the order of [`Line::map`].
    pub(crate) fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        for (i, end) in self.ends.iter().enumerate() {
            for (k, x) in end.iter().enumerate() {
                f(Field::nth_axis("ends", i, k), x);
            }
        }
    }
}
