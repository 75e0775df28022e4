//! `[[strip]]`: a thin-airfoil strip's fields through the builder, and its `unsteady` setting.

use super::error::FileError;
use super::items::{Builder, unsteady};
use super::mirror::Mirror;
use super::source::Table;
use crate::items::Strip;
use eom_sym::Expr;

impl Builder<'_> {
    pub(super) fn strip(
        &mut self,
        t: &Table<'_>,
        name: &str,
        m: Option<Mirror>,
    ) -> Result<(), FileError> {
        let mut s = Strip::new(name);
        if let Some(u) = self.unsteady {
            s = s.unsteady(u);
        }
        let frame = self.surface(t, m, s.forward, s.down)?;
        if let Some(b) = frame.body {
            s = s.on(&b);
        }
        if let Some(v) = frame.at {
            s = s.at(v);
        }
        s = s.axes(frame.forward, frame.down);
        for (key, set) in [
            (
                "semichord",
                Strip::semichord as fn(Strip<Expr>, Expr) -> Strip<Expr>,
            ),
            ("elastic_axis", Strip::elastic_axis),
            ("width", Strip::width),
            ("lift_slope", Strip::lift_slope),
            ("density", Strip::density),
            ("airspeed", Strip::airspeed),
        ] {
            if let Some(x) = self.scalar(t, key)? {
                s = set(s, x);
            }
        }
        if let Some(u) = unsteady(t)? {
            s = s.unsteady(u);
        }
        self.add(t, s);
        Ok(())
    }
}
