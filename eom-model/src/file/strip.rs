//! `[[strip]]`: a thin-airfoil strip's fields through the builder, and its `unsteady` setting.

use super::error::FileError;
use super::items::{Builder, VecKind};
use super::mirror::Mirror;
use super::source::Table;
use crate::items::{Strip, Unsteady};
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
        if let Some(b) = self.named_body(t, "body", m)? {
            s = s.on(&b);
        }
        if let Some(v) = self.vector(t, "at", m, VecKind::Polar)? {
            s = s.at(v);
        }
        let forward = self.vector(t, "forward", m, VecKind::Polar)?;
        let down = self.vector(t, "down", m, VecKind::Polar)?;
        let (f0, d0) = match m {
            Some(m) => (
                m.apply(s.forward, VecKind::Polar),
                m.apply(s.down, VecKind::Polar),
            ),
            None => (s.forward, s.down),
        };
        s = s.axes(forward.unwrap_or(f0), down.unwrap_or(d0));
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
        if let Some(u) = t.string("unsteady")? {
            let span = t
                .get("unsteady")
                .map(|v| v.span())
                .unwrap_or(t.span.clone());
            let u = Unsteady::parse(&u).map_err(|_| {
                t.field_error(
                    "unsteady",
                    &span,
                    format!("`{u}`: expected \"quasi-steady\", \"jones\" or \"auto\""),
                )
            })?;
            s = s.unsteady(u);
        }
        self.add(t, s);
        Ok(())
    }
}
