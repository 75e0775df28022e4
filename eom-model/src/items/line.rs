//! How a line item lists and reads its [`Line`]: its keys, settings and scalar fields.

use super::{Field, Setting, Source, visit_ends};
use crate::geometry::Line;

impl<S> Line<S> {
    /// The model-file keys of a line.
    pub const KEYS: &'static [&'static str] = &["between", "ends", "twist"];

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
        visit_ends(f, "ends", &self.ends);
    }

    /// `ends`, `between` and `twist` where `source` gives them.
    pub(crate) fn read<R: Source<S>>(&mut self, source: &R) -> Result<(), R::Error> {
        if let Some(e) = source.ends("ends")? {
            self.ends = e;
        }
        if let Some(b) = source.bodies("between")? {
            self.bodies = b;
        }
        self.twist = source.flag("twist")?.unwrap_or(false);
        Ok(())
    }
}
