//! One array of tables per item kind: each table's keys checked against its kind's, its fields
//! read as the kind's declaration says (`Source`, so every default is the declaration's),
//! what a declaration cannot say done by hand (a wing's AVL file and derivatives, a sensor's
//! feedthrough), mirrored copies added where asked.

use super::error::FileError;
use super::mirror::{Mirror, mirror_name};
use super::params::{Declarations, value_expr};
use super::source::{Ctx, Table, Value, array_of};
use crate::geometry::name;
pub(crate) use crate::items::VecKind;
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
        self.each(root, &BODY, None)?;
        for &id in KindId::ALL {
            self.each(root, id.kind(), Some(id))?;
        }
        Ok(())
    }

    /// Reads every `[[kind]]` table (bodies where `id` is `None`), and its mirror image where
    /// asked: the keys checked, the name claimed, the fields read by [`Builder::read`].
    fn each(&mut self, root: &Table<'a>, kind: &Kind, id: Option<KindId>) -> Result<(), FileError> {
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
            self.read(&t, id, &name, None)?;
            if let Some(m) = mirror {
                let mirrored = mirror_name(&name).ok_or_else(|| {
                    t.error(
                        "`mirror` needs a name with `left` or `right` (or L/R, LF/RF, LR/RR \
                         as a word) to name the copy",
                    )
                })?;
                self.claim(&t, label, &mirrored)?;
                self.read(&t, id, &mirrored, Some(m))?;
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

    /// Reads the body or item of kind `id` called `name` from table `t` (mirrored by `m`)
    /// into the model: its declared fields, and what its kind reads by hand before and after.
    fn read(
        &mut self,
        t: &Table<'_>,
        id: Option<KindId>,
        name: &str,
        m: Option<Mirror>,
    ) -> Result<(), FileError> {
        let Some(id) = id else {
            let mut body = Body::new(name);
            body.read(&TableSource { b: self, t, m })?;
            self.add(t, body);
            return Ok(());
        };
        let mut item = AnyItem::declared(id, name);
        match &mut item {
            AnyItem::Wing(w) => self.wing_before(t, name, w)?,
            AnyItem::Strip(s) => s.unsteady = self.unsteady.unwrap_or(s.unsteady),
            _ => {}
        }
        item.read(&TableSource { b: self, t, m })?;
        match &mut item {
            AnyItem::Wing(w) => {
                (w.forward, w.down) = mirrored_axes(t, m, w.forward, w.down);
                self.wing_after(t, m, w)?;
            }
            AnyItem::Strip(s) => (s.forward, s.down) = mirrored_axes(t, m, s.forward, s.down),
            AnyItem::Sensor(s) => self.feedthrough(t, m, s)?,
            _ => {}
        }
        self.add(t, item);
        Ok(())
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

    fn vector(
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

    /// Two points, `key = [[x, y, z], [x, y, z]]` (mirrored where mirrored).
    fn ends(
        &self,
        t: &Table<'_>,
        key: &str,
        m: Option<Mirror>,
    ) -> Result<Option<[Vec3<Expr>; 2]>, FileError> {
        let Some(v) = t.get(key) else {
            return Ok(None);
        };
        let a = array_of(t, key, v, 2)?;
        let mut e = Vec::new();
        for x in a {
            let p = array_of(t, key, x, 3)?;
            let mut c = Vec::new();
            for y in p {
                c.push(value_expr(self.ctx, self.decl, y, &t.field_context(key))?);
            }
            let c: [Expr; 3] = c.try_into().expect("3");
            e.push(match m {
                Some(m) => m.apply(c, VecKind::Polar),
                None => c,
            });
        }
        Ok(Some([e[0], e[1]]))
    }

    /// `key = [body 1, body 2]` (mirrored names where mirrored).
    fn between(
        &self,
        t: &Table<'_>,
        key: &str,
        m: Option<Mirror>,
    ) -> Result<Option<[Name; 2]>, FileError> {
        let Some(v) = t.get(key) else {
            return Ok(None);
        };
        let a = array_of(t, key, v, 2)?;
        let mut out = Vec::new();
        for x in a {
            let DeValue::String(s) = x.get_ref() else {
                return Err(t.field_error(key, &x.span(), "expected body names"));
            };
            out.push(name(&self.body_ref(t, key, x, s, m)?));
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

    fn named_body(
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

    // ---------------------------------------------------------------- read by hand

    /// `feedthrough = { actuator = "…", gain = … }` of a sensor (the actuator's mirror image
    /// in a mirrored copy, where it exists).
    fn feedthrough(
        &self,
        t: &Table<'_>,
        m: Option<Mirror>,
        s: &mut Sensor<Expr>,
    ) -> Result<(), FileError> {
        let Some(v) = t.get("feedthrough") else {
            return Ok(());
        };
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
        *s = s.clone().feedthrough(&actuator, gain);
        Ok(())
    }
}

/// A table's fields as a kind's declaration reads them: with the table's positions in errors,
/// mirrored by the table's mirror.
struct TableSource<'s, 'a, 't> {
    b: &'s Builder<'a>,
    t: &'s Table<'t>,
    m: Option<Mirror>,
}

impl Source<Expr> for TableSource<'_, '_, '_> {
    type Error = FileError;

    fn scalar(&self, key: &'static str) -> Result<Option<Expr>, FileError> {
        self.b.scalar(self.t, key)
    }
    fn vector(&self, key: &'static str, kind: VecKind) -> Result<Option<Vec3<Expr>>, FileError> {
        self.b.vector(self.t, key, self.m, kind)
    }
    fn pair(&self, key: &'static str) -> Result<Option<[Expr; 2]>, FileError> {
        self.b.scalars::<2>(self.t, key)
    }
    fn matrix(&self, key: &'static str) -> Result<Option<Vec<Vec<Expr>>>, FileError> {
        self.b.matrix(self.t, key)
    }
    fn ends(&self, key: &'static str) -> Result<Option<[Vec3<Expr>; 2]>, FileError> {
        self.b.ends(self.t, key, self.m)
    }
    fn bodies(&self, key: &'static str) -> Result<Option<[Name; 2]>, FileError> {
        self.b.between(self.t, key, self.m)
    }
    fn body(&self, key: &'static str) -> Result<Option<Name>, FileError> {
        Ok(self.b.named_body(self.t, key, self.m)?.map(|b| name(&b)))
    }
    fn text(&self, key: &'static str) -> Result<Option<String>, FileError> {
        self.t.string(key)
    }
    fn flag(&self, key: &'static str) -> Result<Option<bool>, FileError> {
        self.t.bool(key)
    }
    fn count(&self, key: &'static str, max: u8) -> Result<Option<u8>, FileError> {
        self.t.count(key, max)
    }
    fn choice<T: Choice>(&self, key: &'static str) -> Result<Option<T>, FileError> {
        choice(self.t, key)
    }
}

/// One of the names of a [`Choice`] at `key` of table `t`.
fn choice<T: Choice>(t: &Table<'_>, key: &str) -> Result<Option<T>, FileError> {
    let Some(s) = t.string(key)? else {
        return Ok(None);
    };
    let span = t.get(key).map_or(t.span.clone(), |v| v.span());
    T::from_name(&s)
        .map(Some)
        .map_err(|p| t.field_error(key, &span, p))
}

/// The axes of a lifting surface: those not given in its table are the defaults, mirrored
/// where mirrored (those given were mirrored as they were read).
fn mirrored_axes(
    t: &Table<'_>,
    m: Option<Mirror>,
    forward: Vec3<Expr>,
    down: Vec3<Expr>,
) -> (Vec3<Expr>, Vec3<Expr>) {
    let Some(m) = m else {
        return (forward, down);
    };
    let default = |key, v| match t.get(key) {
        None => m.apply(v, VecKind::Polar),
        Some(_) => v,
    };
    (default("forward", forward), default("down", down))
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

/// `unsteady = "quasi-steady" | "jones" | "auto"` of table `t`.
pub(super) fn unsteady(t: &Table<'_>) -> Result<Option<Unsteady>, FileError> {
    choice(t, "unsteady")
}

fn with_common(keys: &[&'static str]) -> Vec<&'static str> {
    let mut v: Vec<&'static str> = COMMON_KEYS.to_vec();
    v.extend_from_slice(keys);
    v
}
