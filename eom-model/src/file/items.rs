//! One array of tables per item kind: fields read with positions, converted through the
//! builders (so every default is the builder's), mirrored copies added where asked.

use super::error::FileError;
use super::mirror::{Mirror, mirror_name};
use super::params::{Declarations, value_expr};
use super::source::{Ctx, Table, Value, array_of};
use crate::geometry::name;
use crate::items::*;
use crate::model::{Model, Place};
use crate::warning::Warning;
use eom_sym::{Expr, Scope};
use std::collections::HashSet;
use std::ops::Range;
use toml::de::DeValue;

/// Reads the items of a file into a model.
pub(crate) struct Builder<'a> {
    pub(super) ctx: &'a Ctx<'a>,
    pub(super) decl: &'a Declarations,
    pub(super) model: &'a mut Model,
    /// Names taken so far, for duplicate detection (items and bodies have separate name
    /// spaces, as in the Rust API); sets, so that a file of many items loads in linear time.
    items: HashSet<String>,
    /// The bodies declared so far.
    bodies: HashSet<String>,
    /// Where each body and item was defined, by its place in the model, for errors found
    /// after loading.
    pub spans: Spans,
    /// Warnings of the loading (e.g. entries an AVL stability-axis file cannot give).
    pub(super) warnings: Vec<Warning>,
    /// `[model] unsteady`: the default of the wings and strips that do not set their own.
    pub(super) unsteady: Option<crate::items::Unsteady>,
}

impl<'a> Builder<'a> {
    pub fn new(
        ctx: &'a Ctx<'a>,
        _scope: &Scope,
        decl: &'a Declarations,
        model: &'a mut Model,
    ) -> Self {
        Builder {
            ctx,
            decl,
            model,
            items: HashSet::new(),
            bodies: HashSet::new(),
            spans: Spans::default(),
            warnings: Vec::new(),
            unsteady: None,
        }
    }

    /// Every kind, bodies first (items refer to them).
    pub fn all(&mut self, root: &Table<'a>) -> Result<(), FileError> {
        self.each(root, &BODY, Self::body)?;
        for &id in KindId::ALL {
            self.each(root, id.kind(), reader(id))?;
        }
        Ok(())
    }

    /// Reads every `[[kind]]` table, and its mirror image where asked: the keys checked, the
    /// name claimed, the fields read by `f`.
    fn each(&mut self, root: &Table<'a>, kind: &Kind, f: Reader<'a>) -> Result<(), FileError> {
        let Kind {
            name: label,
            key: kind,
            keys,
        } = *kind;
        let Some(v) = root.get(kind) else {
            return Ok(());
        };
        let DeValue::Array(list) = v.get_ref() else {
            return Err(root.field_error(
                kind,
                &v.span(),
                format!("expected an array of tables (`[[{kind}]]`)"),
            ));
        };
        for (k, entry) in list.iter().enumerate() {
            let t = Table::sub(self.ctx, entry, format!("{kind} #{}", k + 1))?;
            let name = t
                .string("name")?
                .ok_or_else(|| t.error(format!("every {kind} needs a `name`")))?;
            let t = Table {
                context: crate::items::label(kind, &name),
                ..t
            };
            let mirror = match t.string("mirror")? {
                None => None,
                Some(m) => Some(Mirror::parse(&m).map_err(|p| {
                    let span = t.get("mirror").map(|x| x.span()).unwrap_or(t.span.clone());
                    t.field_error("mirror", &span, p)
                })?),
            };
            t.only(&with_common(keys))?;
            self.claim(&t, label, &name)?;
            f(self, &t, &name, None)?;
            if let Some(m) = mirror {
                let mirrored = mirror_name(&name).ok_or_else(|| {
                    t.error(
                        "`mirror` needs a name with `left` or `right` (or L/R, LF/RF, LR/RR \
                         as a word) to name the copy",
                    )
                })?;
                self.claim(&t, label, &mirrored)?;
                f(self, &t, &mirrored, Some(m))?;
            }
        }
        Ok(())
    }

    pub(super) fn claim(&mut self, t: &Table<'_>, kind: &str, name: &str) -> Result<(), FileError> {
        let taken = if kind == "body" {
            self.bodies.contains(name) || name == GROUND
        } else {
            self.items.contains(name)
        };
        if taken {
            let span = t.get("name").map(|x| x.span()).unwrap_or(t.span.clone());
            let problem = if kind == "body" {
                format!("a body called `{name}` already exists")
            } else {
                format!("another item is already called `{name}` (item names are unique)")
            };
            return Err(t.field_error("name", &span, problem));
        }
        if kind == "body" {
            self.bodies.insert(name.to_string());
        } else {
            self.items.insert(name.to_string());
        }
        Ok(())
    }

    /// Adds a body or item read from table `t` to the model, and where `t` is.
    pub(super) fn add(&mut self, t: &Table<'_>, item: impl Into<Part<Expr>>) {
        let place = self.model.add_placed(item);
        self.spans.record(place, Some(t.span.clone()));
    }

    // ---------------------------------------------------------------- field readers

    pub(super) fn scalar(&self, t: &Table<'_>, key: &str) -> Result<Option<Expr>, FileError> {
        t.get(key)
            .map(|v| value_expr(self.ctx, self.decl, v, &t.field_context(key)))
            .transpose()
    }

    fn scalars<const N: usize>(
        &self,
        t: &Table<'_>,
        key: &str,
    ) -> Result<Option<[Expr; N]>, FileError> {
        let Some(v) = t.get(key) else {
            return Ok(None);
        };
        let a = array_of(t, key, v, N)?;
        let mut out = Vec::with_capacity(N);
        for x in a {
            out.push(value_expr(self.ctx, self.decl, x, &t.field_context(key))?);
        }
        Ok(Some(out.try_into().expect("N values")))
    }

    pub(super) fn vector(
        &self,
        t: &Table<'_>,
        key: &str,
        m: Option<Mirror>,
        kind: VecKind,
    ) -> Result<Option<Vec3<Expr>>, FileError> {
        Ok(self.scalars::<3>(t, key)?.map(|v| match m {
            Some(m) => m.apply(v, kind),
            None => v,
        }))
    }

    fn matrix(&self, t: &Table<'_>, key: &str) -> Result<Option<Vec<Vec<Expr>>>, FileError> {
        let Some(v) = t.get(key) else {
            return Ok(None);
        };
        let DeValue::Array(rows) = v.get_ref() else {
            return Err(t.field_error(key, &v.span(), "expected an array of rows"));
        };
        let n = rows.len();
        let mut out = Vec::with_capacity(n);
        for r in rows.iter() {
            let row = array_of(t, key, r, n)?;
            out.push(
                row.iter()
                    .map(|x| value_expr(self.ctx, self.decl, x, &t.field_context(key)))
                    .collect::<Result<Vec<_>, _>>()?,
            );
        }
        Ok(Some(out))
    }

    /// `between = [body 1, body 2]` (mirrored names where mirrored); the default is the
    /// builder's.
    fn between(&self, t: &Table<'_>, m: Option<Mirror>) -> Result<Option<[String; 2]>, FileError> {
        let Some(v) = t.get("between") else {
            return Ok(None);
        };
        let a = array_of(t, "between", v, 2)?;
        let mut out = Vec::new();
        for x in a {
            let DeValue::String(s) = x.get_ref() else {
                return Err(t.field_error("between", &x.span(), "expected body names"));
            };
            out.push(self.body_ref(t, "between", x, s, m)?);
        }
        Ok(Some([out[0].clone(), out[1].clone()]))
    }

    /// A body name that must exist (mirrored where mirrored and the mirror image exists).
    fn body_ref(
        &self,
        t: &Table<'_>,
        key: &str,
        v: &Value<'_>,
        name: &str,
        m: Option<Mirror>,
    ) -> Result<String, FileError> {
        let name = match m {
            Some(_) => mirror_name(name)
                .filter(|n| self.bodies.contains(n))
                .unwrap_or_else(|| name.to_string()),
            None => name.to_string(),
        };
        if name == GROUND || self.bodies.contains(&name) {
            return Ok(name);
        }
        let known: Vec<String> = std::iter::once(GROUND.to_string())
            .chain(self.model.bodies.iter().map(|b| b.name.to_string()))
            .collect();
        Err(t.field_error(
            key,
            &v.span(),
            format!(
                "no body called `{}`; the bodies are: {}",
                eom_text::shown(&name),
                known.join(", ")
            ),
        ))
    }

    // ---------------------------------------------------------------- kinds

    fn body(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let mut b = Body::new(name);
        if let Some(v) = self.vector(t, "at", m, VecKind::Polar)? {
            b = b.at(v);
        }
        if let Some(x) = self.scalar(t, "mass")? {
            b = b.mass(x);
        }
        if let Some(v) = self.scalars::<3>(t, "moments")? {
            b = b.moments(v);
        }
        if let Some(v) = self.scalars::<3>(t, "products")? {
            b = b.products(match m {
                Some(m) => m.products(v),
                None => v,
            });
        }
        if let Some(v) = self.vector(t, "velocity", m, VecKind::Polar)? {
            b = b.velocity(v);
        }
        if let Some(v) = self.vector(t, "angular_velocity", m, VecKind::Axial)? {
            b = b.angular_velocity(v);
        }
        self.add(t, b);
        Ok(())
    }

    fn load(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let body = self
            .named_body(t, "body", m)?
            .unwrap_or_else(|| GROUND.to_string());
        let mut l = Load::new(name, &body);
        if let Some(v) = self.vector(t, "at", m, VecKind::Polar)? {
            l = l.at(v);
        }
        if let Some(v) = self.vector(t, "force", m, VecKind::Polar)? {
            l = l.force(v);
        }
        if let Some(v) = self.vector(t, "moment", m, VecKind::Axial)? {
            l = l.moment(v);
        }
        if let Some(f) = self.named_body(t, "frame", m)? {
            l = l.frame(&f);
        }
        self.add(t, l);
        Ok(())
    }

    pub(super) fn named_body(
        &self,
        t: &Table<'_>,
        key: &str,
        m: Option<Mirror>,
    ) -> Result<Option<String>, FileError> {
        let Some(v) = t.get(key) else {
            return Ok(None);
        };
        let DeValue::String(s) = v.get_ref() else {
            return Err(t.field_error(key, &v.span(), "expected a body name"));
        };
        self.body_ref(t, key, v, s, m).map(Some)
    }

    /// `between`, `ends`, `twist` of a line item (the defaults where not given).
    fn line(&self, t: &Table<'_>, m: Option<Mirror>) -> Result<Line<Expr>, FileError> {
        let ends = match t.get("ends") {
            None => None,
            Some(v) => {
                let a = array_of(t, "ends", v, 2)?;
                let mut e = Vec::new();
                for x in a {
                    let p = array_of(t, "ends", x, 3)?;
                    let mut c = Vec::new();
                    for y in p {
                        c.push(value_expr(
                            self.ctx,
                            self.decl,
                            y,
                            &t.field_context("ends"),
                        )?);
                    }
                    let c: [Expr; 3] = c.try_into().expect("3");
                    e.push(match m {
                        Some(m) => m.apply(c, VecKind::Polar),
                        None => c,
                    });
                }
                Some([e[0], e[1]])
            }
        };
        let mut line = Line::new();
        if let Some(e) = ends {
            line.ends = e;
        }
        if let Some([b1, b2]) = self.between(t, m)? {
            line.bodies = [name(&b1), name(&b2)];
        }
        line.twist = t.bool("twist")?.unwrap_or(false);
        Ok(line)
    }

    fn spring(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let mut s = Spring::new(name);
        s.line = self.line(t, m)?;
        if let Some(x) = self.scalar(t, "stiffness")? {
            s = s.stiffness(x);
        }
        if let Some(x) = self.scalar(t, "damping")? {
            s = s.damping(x);
        }
        if let Some(x) = self.scalar(t, "inertance")? {
            s = s.inertance(x);
        }
        if let Some(x) = self.scalar(t, "preload")? {
            s = s.preload(x);
        }
        self.add(t, s);
        Ok(())
    }

    fn link(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let mut link = Link::new(name);
        link.line = self.line(t, m)?;
        self.add(t, link);
        Ok(())
    }

    fn actuator(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let mut a = Actuator::new(name);
        a.line = self.line(t, m)?;
        if let Some(x) = self.scalar(t, "gain")? {
            a = a.gain(x);
        }
        if let Some(x) = self.scalar(t, "rate_gain")? {
            a = a.rate_gain(x);
        }
        if let Some(u) = t.string("units")? {
            a = a.units(&u);
        }
        self.add(t, a);
        Ok(())
    }

    fn sensor(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let mut s = Sensor::new(name);
        s.line = self.line(t, m)?;
        if let Some(x) = self.scalar(t, "gain")? {
            s = s.gain(x);
        }
        match t.string("order")?.as_deref() {
            None | Some("displacement") => {}
            Some("velocity") => s = s.velocity(),
            Some("acceleration") => s = s.acceleration(),
            Some(other) => {
                let span = t.get("order").map(|x| x.span()).unwrap_or(t.span.clone());
                return Err(t.field_error("order", &span, format!(
                    "`{other}` is not a sensor order; use displacement, velocity or acceleration"
                )));
            }
        }
        match t.string("frame")?.as_deref() {
            None | Some("global") => {}
            Some("local") => s = s.local(),
            Some(other) => {
                let span = t.get("frame").map(|x| x.span()).unwrap_or(t.span.clone());
                return Err(t.field_error(
                    "frame",
                    &span,
                    format!("`{other}` is not a sensor frame; use global or local"),
                ));
            }
        }
        if let Some(v) = t.get("feedthrough") {
            let f = Table::sub(self.ctx, v, t.field_context("feedthrough"))?;
            f.only(&["actuator", "gain"])?;
            let actuator = f
                .string("actuator")?
                .ok_or_else(|| f.error("`feedthrough` needs an `actuator`"))?;
            let actuator = match m {
                Some(_) => mirror_name(&actuator)
                    .filter(|n| self.items.contains(n))
                    .unwrap_or(actuator),
                None => actuator,
            };
            let gain = self.scalar(&f, "gain")?.unwrap_or_else(|| Expr::int(-1));
            s = s.feedthrough(&actuator, gain);
        }
        if let Some(u) = t.string("units")? {
            s = s.units(&u);
        }
        self.add(t, s);
        Ok(())
    }

    fn beam(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let l = self.line(t, m)?;
        let mut b = Beam::new(name);
        (b.bodies, b.ends) = (l.bodies, l.ends);
        if let Some([e1, e2]) = self.scalars::<2>(t, "stiffness")? {
            b = b.stiffness(e1, e2);
        }
        if let Some(x) = self.scalar(t, "mpul")? {
            b = b.mpul(x);
        }
        if let Some(v) = self.vector(t, "perp", m, VecKind::Polar)? {
            b = b.perp(v);
        }
        self.add(t, b);
        Ok(())
    }

    /// `body`, `at`, `forward` and `down` of a lifting surface (a wing or strip); the axes not
    /// given are `forward` and `down`, mirrored where mirrored.
    pub(super) fn surface(
        &self,
        t: &Table<'_>,
        m: Option<Mirror>,
        forward: Vec3<Expr>,
        down: Vec3<Expr>,
    ) -> Result<SurfaceFrame, FileError> {
        let polar = |key| self.vector(t, key, m, VecKind::Polar);
        let mirrored = |v| m.map_or(v, |m| m.apply(v, VecKind::Polar));
        Ok(SurfaceFrame {
            body: self.named_body(t, "body", m)?,
            at: polar("at")?,
            forward: polar("forward")?.unwrap_or_else(|| mirrored(forward)),
            down: polar("down")?.unwrap_or_else(|| mirrored(down)),
        })
    }

    /// `between`, `at`, `forces`, `moments`, `axis`, `rolling_axis` of a point item (the
    /// defaults where not given).
    fn point(&self, t: &Table<'_>, m: Option<Mirror>) -> Result<Point<Expr>, FileError> {
        let mut p = Point::new();
        if let Some([b1, b2]) = self.between(t, m)? {
            p.bodies = [name(&b1), name(&b2)];
        }
        let polar = |key| self.vector(t, key, m, VecKind::Polar);
        p.location = polar("at")?.unwrap_or(p.location);
        p.forces = t.count("forces", 3)?.unwrap_or(p.forces);
        p.moments = t.count("moments", 3)?.unwrap_or(p.moments);
        p.axis = polar("axis")?.unwrap_or(p.axis);
        p.rolling_axis = polar("rolling_axis")?.unwrap_or(p.rolling_axis);
        Ok(p)
    }

    fn rigid_point(
        &mut self,
        t: &Table<'_>,
        name: &str,
        m: Option<Mirror>,
    ) -> Result<(), FileError> {
        let mut r = RigidPoint::new(name);
        r.point = self.point(t, m)?;
        self.add(t, r);
        Ok(())
    }

    fn nh_point(&mut self, t: &Table<'_>, name: &str, m: Option<Mirror>) -> Result<(), FileError> {
        let mut r = NhPoint::new(name);
        r.point = self.point(t, m)?;
        self.add(t, r);
        Ok(())
    }

    fn flex_point(
        &mut self,
        t: &Table<'_>,
        name: &str,
        m: Option<Mirror>,
    ) -> Result<(), FileError> {
        let mut f = FlexPoint::new(name);
        f.point = self.point(t, m)?;
        if let Some([k, kr]) = self.scalars::<2>(t, "stiffness")? {
            f = f.stiffness(k, kr);
        }
        if let Some([c, cr]) = self.scalars::<2>(t, "damping")? {
            f = f.damping(c, cr);
        }
        if let Some(k) = self.matrix(t, "stiffness_matrix")? {
            f = f.stiffness_matrix(k);
        }
        if let Some(c) = self.matrix(t, "damping_matrix")? {
            f = f.damping_matrix(c);
        }
        self.add(t, f);
        Ok(())
    }
}

/// The table that defined each body and item of a model, by its place in the model.
#[derive(Debug, Default)]
pub(crate) struct Spans {
    bodies: Vec<Range<usize>>,
    items: Vec<Option<Range<usize>>>,
}

impl Spans {
    /// Records the span of the body or item added at `place` (`None`: added by the loader,
    /// not defined by a table), shifting the items after it as the model did.
    pub fn record(&mut self, place: Place, span: Option<Range<usize>>) {
        match place {
            Place::Body(k) => {
                debug_assert_eq!(k, self.bodies.len(), "bodies are appended");
                self.bodies.extend(span);
            }
            Place::Item(k) => self.items.insert(k, span),
            Place::Model => {}
        }
    }

    /// The span of the table that defined the body or item at `place`.
    pub fn of(&self, place: Place) -> Option<&Range<usize>> {
        match place {
            Place::Body(k) => self.bodies.get(k),
            Place::Item(k) => self.items.get(k).and_then(Option::as_ref),
            Place::Model => None,
        }
    }
}

/// The reader of the fields of a kind (its keys are checked and its name claimed before).
fn reader<'a>(id: KindId) -> Reader<'a> {
    match id {
        KindId::Load => Builder::load,
        KindId::Spring => Builder::spring,
        KindId::FlexPoint => Builder::flex_point,
        KindId::Beam => Builder::beam,
        KindId::Link => Builder::link,
        KindId::RigidPoint => Builder::rigid_point,
        KindId::NhPoint => Builder::nh_point,
        KindId::Wing => Builder::wing,
        KindId::Strip => Builder::strip,
        KindId::Actuator => Builder::actuator,
        KindId::Sensor => Builder::sensor,
    }
}

/// The frame of a lifting surface as its table gives it (see [`Builder::surface`]).
pub(super) struct SurfaceFrame {
    pub body: Option<String>,
    pub at: Option<Vec3<Expr>>,
    pub forward: Vec3<Expr>,
    pub down: Vec3<Expr>,
}

/// `unsteady = "quasi-steady" | "jones" | "auto"` of table `t`.
pub(super) fn unsteady(t: &Table<'_>) -> Result<Option<Unsteady>, FileError> {
    let Some(u) = t.string("unsteady")? else {
        return Ok(None);
    };
    let span = t.get("unsteady").map_or(t.span.clone(), |v| v.span());
    Unsteady::parse(&u).map(Some).map_err(|_| {
        t.field_error(
            "unsteady",
            &span,
            format!("`{u}`: expected \"quasi-steady\", \"jones\" or \"auto\""),
        )
    })
}

type Reader<'a> = fn(&mut Builder<'a>, &Table<'_>, &str, Option<Mirror>) -> Result<(), FileError>;

/// How a vector transforms under a mirror: a position or direction (polar), or a rotation or
/// moment (axial, a pseudo-vector).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum VecKind {
    Polar,
    Axial,
}

fn with_common(keys: &[&'static str]) -> Vec<&'static str> {
    let mut v: Vec<&'static str> = COMMON_KEYS.to_vec();
    v.extend_from_slice(keys);
    v
}
