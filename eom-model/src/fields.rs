//! Every scalar field of a model: visited ([`Model::for_each_field`]), listed with its item
//! and field name ([`Model::fields`]), converted to another scalar type ([`Model::map`]), and
//! named in errors.

use crate::Model;
use crate::error::ItemRef;
#[cfg(doc)]
use crate::items::KINDS;
use crate::items::{Field, Item, ModelScalar, label};

impl<S: ModelScalar> Model<S> {
    /// Every body and item in order, as items.
    fn all_items(&self) -> impl Iterator<Item = &dyn Item<S>> {
        let bodies = self.bodies.iter().map(|b| b as &dyn Item<S>);
        bodies.chain(self.items.iter().map(|x| x as &dyn Item<S>))
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
            items: self.items.iter().map(|x| x.map(f)).collect(),
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

    /// The item and the name of field `k` (in the order of [`Model::map`]); the model and no
    /// field when there is no such field.
    pub(crate) fn field_at(&self, k: usize) -> (ItemRef, String) {
        let mut seen = 0;
        let mut at: Option<(ItemRef, Field)> = None;
        for item in self.all_items() {
            item.fields(&mut |fd, _| {
                if seen == k {
                    at = Some((ItemRef::new(item.kind(), item.name()), fd));
                }
                seen += 1;
            });
            if at.is_some() {
                break;
            }
        }
        at.map_or(
            (ItemRef::new("model", &self.name), String::new()),
            |(i, f)| (i, f.to_string()),
        )
    }
}

#[cfg(test)]
mod tests {
    use crate::items::*;
    use crate::{Model, ModelError};

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
        let ranks: Vec<KindId> = m.items().iter().map(|x| x.kind_id()).collect();
        assert!(ranks.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(m.items_of("spring").count(), 2);
    }

    #[test]
    fn a_field_error_names_the_item_and_the_field() {
        let mut m = Model::<f64>::new("m");
        m.add(Body::new("b").mass(1.0));
        m.add(Spring::new("k").stiffness(f64::NAN));
        let e = m.validate().unwrap_err();
        assert!(
            matches!(
                &e,
                ModelError::NotFinite { item, field, value }
                    if item.kind == "spring" && item.name == "k" && field == "stiffness" && value.is_nan()
            ),
            "{e:?}"
        );
    }
}
