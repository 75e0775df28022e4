//! [`Validation`]: what an item kind sees of the model's checks: the bodies and items it may
//! refer to, and the warnings so far. The checks themselves run in [`crate::validate`].

use super::{AnyItem, Body, Item, ModelScalar};
use crate::error::{ItemRef, ModelError};
use crate::geometry::GROUND;
use crate::warning::Warning;
use hashbrown::HashSet;

/// What an item's [`Item::validate`] sees: the bodies and items of the model, and the
/// warnings so far.
pub struct Validation<'m, S> {
    bodies: &'m [Body<S>],
    items: &'m [AnyItem<S>],
    /// The names of the bodies checked so far.
    names: HashSet<&'m str>,
    warnings: Vec<Warning>,
}

impl<'m, S> Validation<'m, S> {
    /// A validation of `bodies` and `items`, with no body checked yet.
    pub(crate) fn new(bodies: &'m [Body<S>], items: &'m [AnyItem<S>]) -> Self {
        Validation {
            bodies,
            items,
            names: HashSet::with_capacity(bodies.len()),
            warnings: Vec::new(),
        }
    }

    /// Report a warning.
    pub fn warn(&mut self, warning: Warning) {
        self.warnings.push(warning);
    }

    /// The bodies of the model.
    pub(crate) fn bodies(&self) -> &'m [Body<S>] {
        self.bodies
    }

    /// Record body `name` as checked; `false` if a body of that name was checked before.
    pub(crate) fn insert_body(&mut self, name: &'m str) -> bool {
        self.names.insert(name)
    }

    /// The warnings reported.
    pub(crate) fn into_warnings(self) -> Vec<Warning> {
        self.warnings
    }
}

impl<S: ModelScalar> Validation<'_, S> {
    /// Is `body` the ground or a body of the model?
    pub fn is_body(&self, body: &str) -> bool {
        body == GROUND || self.names.contains(body)
    }

    /// The body called `name` (`None` for the ground or an unknown name).
    pub fn body(&self, name: &str) -> Option<&Body<S>> {
        self.bodies.iter().find(|b| &*b.name == name)
    }

    /// `field` of item `kind` `item` must name a body (or the ground).
    pub fn check_body(
        &self,
        kind: &'static str,
        item: &str,
        field: &str,
        body: &str,
    ) -> Result<(), ModelError> {
        if self.is_body(body) {
            return Ok(());
        }
        let mut known: Vec<String> = self.bodies.iter().map(|b| b.name.to_string()).collect();
        known.push(GROUND.to_string());
        Err(ModelError::UnknownBody {
            item: ItemRef::new(kind, item),
            field: field.to_string(),
            body: body.to_string(),
            known: known.into(),
        })
    }

    /// `field` of item `kind` `item` must name an item of kind `target_kind`.
    pub fn check_item(
        &self,
        kind: &'static str,
        item: &str,
        field: &'static str,
        target_kind: &'static str,
        target: &str,
    ) -> Result<(), ModelError> {
        let mut of_kind = self.items.iter().filter(|x| x.kind() == target_kind);
        if of_kind.clone().any(|x| &**x.name() == target) {
            return Ok(());
        }
        let known: Vec<String> = of_kind.by_ref().map(|x| x.name().to_string()).collect();
        Err(ModelError::UnknownItem {
            item: ItemRef::new(kind, item),
            field,
            kind: target_kind,
            name: target.to_string(),
            known: Some(known.into()),
        })
    }

    /// The bodies an item connects exist, and two of them differ.
    pub(crate) fn check_connected(&self, item: &dyn Item<S>) -> Result<(), ModelError> {
        let bs = item.bodies();
        for (k, b) in bs.iter().enumerate() {
            if !self.is_body(b) {
                let field = match (bs.len(), k) {
                    (1, _) => "body",
                    (_, 0) => "body[1]",
                    _ => "body[2]",
                };
                return self.check_body(item.kind(), item.name(), field, b);
            }
        }
        if bs.len() == 2 && bs[0] == bs[1] {
            return Err(ModelError::SelfConnection {
                item: ItemRef::new(item.kind(), item.name()),
                body: bs[0].to_string(),
            });
        }
        Ok(())
    }
}
