//! [`Model`]: parameters, bodies and items; the layer above the items, which adds, lists,
//! converts, checks and assembles them.

use crate::assemble::{Assembled, Assembly, BodyFrame};
use crate::error::ModelError;
use crate::geometry::zero3;
#[cfg(doc)]
use crate::items::KINDS;
use crate::items::{AnyItem, Body, Item, ModelScalar, Part, Strip, Wing};
use eom_sym::ExprPool;
use eom_sym::expr::Expr;
use eom_sym::pool::ParamInfo;
use eom_sym::scope::Scope;
use eom_sym::tape::Tape;

/// A multibody model: parameters, bodies and items.
#[derive(Clone, Debug)]
pub struct Model<S = Expr> {
    /// Name of the model.
    pub name: String,
    /// Parameters (symbolic models).
    pub scope: Scope,
    /// Bodies (the ground is implicit).
    pub bodies: Vec<Body<S>>,
    /// The items, in the order of [`KINDS`] (items of one kind in the order they were added).
    pub(crate) items: Vec<AnyItem<S>>,
}

/// Where in a model a body or item is (what errors found by [`Model::validate`] are about).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Place {
    /// The model as a whole.
    Model,
    /// Body `k` of [`Model::bodies`].
    Body(usize),
    /// Item `k` of [`Model::items`].
    Item(usize),
}

impl<S: 'static> Model<S> {
    /// Insert an item after the items of its kind and of the kinds before it in [`KINDS`];
    /// returns where it went.
    fn insert_item(&mut self, item: AnyItem<S>) -> usize {
        let kind = item.kind_id();
        let at = self.items.partition_point(|x| x.kind_id() <= kind);
        self.items.insert(at, item);
        at
    }

    /// Add a body or an item, and say where it went.
    pub(crate) fn add_placed(&mut self, part: impl Into<Part<S>>) -> Place {
        match part.into() {
            Part::Body(body) => {
                self.bodies.push(body);
                Place::Body(self.bodies.len() - 1)
            }
            Part::Item(item) => Place::Item(self.insert_item(item)),
        }
    }
}

impl<S: ModelScalar> Model<S> {
    /// An empty model. A symbolic model gets a new expression pool of its own, made current on
    /// this thread (so that the expressions built for it land there), and freed when the model
    /// and everything built from it are dropped.
    pub fn new(name: &str) -> Self {
        let scope = if S::SYMBOLIC {
            let pool = ExprPool::new();
            pool.make_current();
            Scope::in_pool(pool)
        } else {
            Scope::new()
        };
        Model {
            name: name.to_string(),
            scope,
            bodies: Vec::new(),
            items: Vec::new(),
        }
    }

    /// Add a body or an item (validated later, by [`Model::validate`] or the assembly).
    pub fn add(&mut self, part: impl Into<Part<S>>) -> &mut Self {
        self.add_placed(part);
        self
    }

    /// The items (bodies excluded), in the order of [`KINDS`].
    pub fn items(&self) -> &[AnyItem<S>] {
        &self.items
    }

    /// The items, mutable (for settings decided later, such as `unsteady = "auto"`).
    pub(crate) fn items_mut(&mut self) -> &mut [AnyItem<S>] {
        &mut self.items
    }

    /// The items of one kind (e.g. `"spring"`), in the order they were added.
    pub fn items_of<'a>(&'a self, kind: &'a str) -> impl Iterator<Item = &'a AnyItem<S>> + 'a {
        self.items.iter().filter(move |x| x.kind() == kind)
    }

    /// The body called `name`.
    pub fn body(&self, name: &str) -> Option<&Body<S>> {
        self.bodies.iter().find(|b| &*b.name == name)
    }
}

impl Model<Expr> {
    /// The model's expression pool.
    pub fn pool(&self) -> ExprPool {
        self.scope.pool().cloned().unwrap_or_else(ExprPool::current)
    }

    /// Runs `f` with the model's pool current (new constants and parameters go there).
    pub fn in_pool<R>(&self, f: impl FnOnce() -> R) -> R {
        match self.scope.pool() {
            Some(p) => p.enter(f),
            None => f(),
        }
    }

    /// Declare a parameter of the model.
    pub fn param(&mut self, name: &str, nominal: f64) -> Result<Expr, ModelError> {
        Ok(self.scope.declare(name, nominal)?)
    }

    /// Declare a parameter with full metadata.
    pub fn param_info(&mut self, info: ParamInfo) -> Result<Expr, ModelError> {
        Ok(self.scope.declare_info(info)?)
    }

    /// The numeric model at the given parameter values (in the order of `scope.params()`).
    pub fn evaluate(&self, values: &[f64]) -> Result<Model<f64>, ModelError> {
        let fields = self.field_values();
        for (k, e) in fields.iter().enumerate() {
            e.check().map_err(|source| {
                let (item, field) = self.field_at(k);
                ModelError::Expression {
                    item,
                    field,
                    source: Box::new(source),
                }
            })?;
        }
        let tape = Tape::new(&fields, &self.scope.params())?;
        let mut vals = vec![0.0; fields.len()];
        let mut work = vec![0.0; tape.work_len()];
        tape.eval_into(values, &mut vals, &mut work)?;
        if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
            let (item, field) = self.field_at(k);
            return Err(ModelError::NotFiniteAt {
                item,
                field,
                value: vals[k],
            });
        }
        let mut k = 0;
        Ok(self.map(&mut |_| {
            k += 1;
            vals[k - 1]
        }))
    }

    /// The numeric model at the nominal parameter values.
    pub fn nominal(&self) -> Result<Model<f64>, ModelError> {
        self.evaluate(&self.scope.nominal_values())
    }
}

impl<S: ModelScalar> Model<S> {
    /// The wings of the model, in the order they were added.
    pub fn wings(&self) -> impl Iterator<Item = &Wing<S>> {
        self.items.iter().filter_map(|x| match x {
            AnyItem::Wing(w) => Some(w),
            _ => None,
        })
    }

    /// The airspeed of `wing` in this model (given, or from its body's nominal velocity).
    pub fn airspeed_of(&self, wing: &Wing<S>) -> S {
        let velocity = self.body(&wing.body).map_or(zero3(), |b| b.velocity);
        wing.airspeed_with(&velocity)
    }

    /// The strips of the model, in the order they were added.
    pub fn strips(&self) -> impl Iterator<Item = &Strip<S>> {
        self.items.iter().filter_map(|x| match x {
            AnyItem::Strip(s) => Some(s),
            _ => None,
        })
    }
}

/// Assemble the linearized model: validate it, let every body and item add its terms, then
/// the statics, the geometric stiffness and the matrices (the steps are those of
/// [`assemble`](mod@crate::assemble)).
pub fn assemble<S: ModelScalar>(model: &Model<S>) -> Result<Assembled<S>, ModelError> {
    let warnings = model.validate()?;
    let frames = model
        .bodies
        .iter()
        .map(|b| BodyFrame {
            name: &b.name,
            location: b.location,
            velocity: b.velocity,
        })
        .collect();
    let mut cx = Assembly::new(frames, model.items().len(), warnings);
    for b in &model.bodies {
        b.assemble(&mut cx)?;
    }
    for item in model.items() {
        item.assemble(&mut cx)?;
    }
    cx.finish(&model.name)
}
