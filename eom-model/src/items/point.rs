//! How a point item lists and reads its [`Point`]: its keys, settings and scalar fields.

use super::{Field, Setting, Source, VecKind, visit3};
use crate::geometry::Point;

impl<S> Point<S> {
    /// The model-file keys of a point.
    pub const KEYS: &'static [&'static str] =
        &["between", "at", "forces", "moments", "axis", "rolling_axis"];

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

    /// Every key of a point that `source` gives.
    pub(crate) fn read<R: Source<S>>(&mut self, source: &R) -> Result<(), R::Error> {
        if let Some(b) = source.bodies("between")? {
            self.bodies = b;
        }
        let polar = |key| source.vector(key, VecKind::Polar);
        if let Some(v) = polar("at")? {
            self.location = v;
        }
        self.forces = source.count("forces", 3)?.unwrap_or(self.forces);
        self.moments = source.count("moments", 3)?.unwrap_or(self.moments);
        if let Some(v) = polar("axis")? {
            self.axis = v;
        }
        if let Some(v) = polar("rolling_axis")? {
            self.rolling_axis = v;
        }
        Ok(())
    }
}
