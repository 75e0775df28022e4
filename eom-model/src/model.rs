//! [`Model`]: parameters, bodies and items.

use crate::error::ModelError;
#[cfg(doc)]
use crate::items::KINDS;
use crate::items::{Body, Field, Item, ModelScalar, kind_rank, label};
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
    items: Vec<Box<dyn Item<S>>>,
}

impl<S: 'static> Model<S> {
    /// Insert an item after the items of its kind and of the kinds before it in [`KINDS`].
    pub(crate) fn insert_item(&mut self, item: Box<dyn Item<S>>) {
        let rank = kind_rank(item.kind());
        let at = self.items.partition_point(|x| kind_rank(x.kind()) <= rank);
        self.items.insert(at, item);
    }
}

impl<S: ModelScalar> Model<S> {
    /// An empty model.
    pub fn new(name: &str) -> Self {
        Model {
            name: name.to_string(),
            scope: Scope::new(),
            bodies: Vec::new(),
            items: Vec::new(),
        }
    }

    /// Add a body or an item (validated later, by [`Model::validate`] or the assembly).
    pub fn add(&mut self, item: impl Item<S>) -> &mut Self {
        item.add_to(self);
        self
    }

    /// The items (bodies excluded), in the order of [`KINDS`].
    pub fn items(&self) -> &[Box<dyn Item<S>>] {
        &self.items
    }

    /// The items of one kind (e.g. `"spring"`), in the order they were added.
    pub fn items_of<'a>(&'a self, kind: &'a str) -> impl Iterator<Item = &'a dyn Item<S>> + 'a {
        self.items
            .iter()
            .filter(move |x| x.kind() == kind)
            .map(|x| &**x)
    }

    /// The body called `name`.
    pub fn body(&self, name: &str) -> Option<&Body<S>> {
        self.bodies.iter().find(|b| &*b.name == name)
    }

    /// Every body and item in order, as items.
    fn all_items(&self) -> impl Iterator<Item = &dyn Item<S>> {
        let bodies = self.bodies.iter().map(|b| b as &dyn Item<S>);
        bodies.chain(self.items.iter().map(|x| &**x))
    }

    /// Visit every field in the order of [`Model::map`], without building anything.
    pub fn for_each_field(&self, f: &mut dyn FnMut(&S)) {
        for item in self.all_items() {
            item.fields(&mut |_, x| f(x));
        }
    }

    /// Convert every field with `f`, visiting fields in a fixed order: the bodies', then the
    /// items' in the order of [`KINDS`], each in the order of its [`Item::fields`].
    pub fn map<T: ModelScalar>(&self, f: &mut dyn FnMut(&S) -> T) -> Model<T> {
        Model {
            name: self.name.clone(),
            scope: self.scope.clone(),
            bodies: self.bodies.iter().map(|b| b.map(f)).collect(),
            items: self.items.iter().map(|x| T::map_item(&**x, f)).collect(),
        }
    }

    /// Every field with its item and field name (``spring `front`.stiffness``), in the order
    /// [`Model::map`] visits them.
    pub fn fields(&self) -> Vec<(String, S)> {
        let mut out = Vec::new();
        for item in self.all_items() {
            let n = label(item.kind(), item.name());
            item.fields(&mut |fd, x| out.push((format!("{n}.{fd}"), *x)));
        }
        out
    }

    /// The values of every field, in the order of [`Model::map`].
    pub(crate) fn field_values(&self) -> Vec<S> {
        let mut out = Vec::new();
        self.for_each_field(&mut |x| out.push(*x));
        out
    }

    /// The error of field `k` (in the order of [`Model::map`]).
    pub(crate) fn field_error(&self, k: usize, problem: String) -> ModelError {
        let mut seen = 0;
        let mut at: Option<(String, Field)> = None;
        for item in self.all_items() {
            item.fields(&mut |fd, _| {
                if seen == k {
                    at = Some((label(item.kind(), item.name()), fd));
                }
                seen += 1;
            });
            if at.is_some() {
                break;
            }
        }
        let (item, field) = at.map_or((String::new(), String::new()), |(i, f)| (i, f.to_string()));
        ModelError::Model {
            item,
            field,
            problem,
        }
    }
}

impl Model<Expr> {
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
            e.check().map_err(|x| self.field_error(k, x.to_string()))?;
        }
        let tape = Tape::new(&fields, &self.scope.params())?;
        let mut vals = vec![0.0; fields.len()];
        let mut work = vec![0.0; tape.work_len()];
        tape.eval_into(values, &mut vals, &mut work)?;
        if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
            return Err(self.field_error(
                k,
                format!("evaluates to {} at the given parameter values", vals[k]),
            ));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::items::*;

    #[test]
    fn items_are_kept_in_the_order_of_the_kind_table() {
        let mut m = Model::<f64>::new("m");
        m.add(Sensor::new("s1"));
        m.add(Link::new("l1"));
        m.add(Spring::new("k1"));
        m.add(Body::new("b"));
        m.add(Link::new("l2"));
        m.add(Spring::new("k2"));
        m.add(Load::new("f", "b"));
        let got: Vec<String> = m
            .items()
            .iter()
            .map(|x| label(x.kind(), x.name()))
            .collect();
        let want = [
            "load `f`",
            "spring `k1`",
            "spring `k2`",
            "link `l1`",
            "link `l2`",
            "sensor `s1`",
        ];
        assert_eq!(got, want);
        assert_eq!(m.bodies.len(), 1);
        let ranks: Vec<usize> = m.items().iter().map(|x| kind_rank(x.kind())).collect();
        assert!(ranks.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(KINDS.len(), 9);
        assert_eq!(m.items_of("spring").count(), 2);
    }

    #[test]
    fn a_field_error_names_the_item_and_the_field() {
        let mut m = Model::<f64>::new("m");
        m.add(Body::new("b").mass(1.0));
        m.add(Spring::new("k").stiffness(f64::NAN));
        let e = m.validate().unwrap_err();
        assert_eq!(
            e,
            ModelError::Model {
                item: "spring `k`".into(),
                field: "stiffness".into(),
                problem: "value NaN is not finite".into(),
            }
        );
    }
}
