//! [`Model::validate`]: names, references, geometry and values, checked before any assembly.
//! Errors name the item and field; physically dubious but computable input gives warnings.
//!
//! 0. **Names**: the model's, the bodies' and the items' names hold no control character,
//!    bidirectional-text override or line separator (`eom_text::name_problem`): names reach
//!    terminals, exported files and generated code.
//! 1. **Values**: every field is finite at the nominal point.
//! 2. **Bodies**: each has a name, not `ground`, unique; then its own checks
//!    ([`Item::validate`] of [`Body`]: no negative mass; physical moments of inertia, else a
//!    warning).
//! 3. **Item names**: each item has a name, unique among the items.
//! 4. **Items**: the bodies each item connects ([`Item::bodies`]) exist and differ; then the
//!    item's own checks ([`Item::validate`]).
//! 5. **Support**: every body is attached to an item that [`Item::supports`] it.
//! 6. The model has a body.

use crate::Model;
use crate::error::ModelError;
use crate::items::{Body, GROUND, Item, ModelScalar, Name, field_error, label};
use hashbrown::HashSet;

/// What an item's [`Item::validate`] sees: the bodies and items of the model, and the
/// warnings so far.
pub struct Validation<'m, S> {
    model: &'m Model<S>,
    bodies: HashSet<&'m str>,
    warnings: Vec<String>,
}

impl<S> Validation<'_, S> {
    /// Report a warning.
    pub fn warn(&mut self, message: String) {
        self.warnings.push(message);
    }
}

impl<S: ModelScalar> Validation<'_, S> {
    /// Is `body` the ground or a body of the model?
    pub fn is_body(&self, body: &str) -> bool {
        body == GROUND || self.bodies.contains(body)
    }

    /// The body called `name` (`None` for the ground or an unknown name).
    pub fn body(&self, name: &str) -> Option<&Body<S>> {
        self.model.body(name)
    }

    /// `field` of item `kind` `item` must name a body (or the ground).
    pub fn check_body(
        &self,
        kind: &str,
        item: &str,
        field: &str,
        body: &str,
    ) -> Result<(), ModelError> {
        if self.is_body(body) {
            return Ok(());
        }
        let mut names: Vec<&str> = self.model.bodies.iter().map(|b| &*b.name).collect();
        names.push(GROUND);
        Err(field_error(
            kind,
            item,
            field,
            format!("unknown body `{body}`; bodies are: {}", names.join(", ")),
        ))
    }

    /// `field` of item `kind` `item` must name an item of kind `target_kind`.
    pub fn check_item(
        &self,
        kind: &str,
        item: &str,
        field: &str,
        target_kind: &str,
        target: &str,
    ) -> Result<(), ModelError> {
        let mut of_kind = self
            .model
            .items()
            .iter()
            .filter(|x| x.kind() == target_kind);
        if of_kind.clone().any(|x| &**x.name() == target) {
            return Ok(());
        }
        let names: Vec<&str> = of_kind.by_ref().map(|x| &**x.name()).collect();
        Err(field_error(
            kind,
            item,
            field,
            format!(
                "unknown {target_kind} `{target}`; {target_kind}s are: {}",
                names.join(", ")
            ),
        ))
    }

    /// The bodies an item connects exist, and two of them differ.
    fn check_connected(&self, item: &dyn Item<S>) -> Result<(), ModelError> {
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
            return Err(field_error(
                item.kind(),
                item.name(),
                "bodies",
                format!("connects `{}` to itself", bs[0]),
            ));
        }
        Ok(())
    }
}

impl<S: ModelScalar> Model<S> {
    /// Check names, references, geometry and values (see [`crate::validate`] for the steps).
    /// Errors name the item and field. Warnings (physically dubious but computable input) are
    /// returned.
    pub fn validate(&self) -> Result<Vec<String>, ModelError> {
        if let Some(p) = eom_text::name_problem(&self.name) {
            return Err(ModelError::Model {
                item: "the model".into(),
                field: "name".into(),
                problem: p,
            });
        }
        self.check_values()?;
        let mut cx = Validation {
            model: self,
            bodies: HashSet::with_capacity(self.bodies.len()),
            warnings: Vec::new(),
        };
        check_bodies(&mut cx)?;
        self.check_item_names()?;
        for item in self.items() {
            cx.check_connected(&**item)?;
            item.validate(&mut cx)?;
        }
        self.check_support()?;
        if self.bodies.is_empty() {
            return Err(ModelError::Model {
                item: format!("model `{}`", self.name),
                field: "bodies".into(),
                problem: "the model has no bodies".into(),
            });
        }
        Ok(cx.warnings)
    }

    /// Step 1: every field is finite at the nominal point (a cheap pass; the first bad field
    /// is located, and labelled, only when there is one).
    fn check_values(&self) -> Result<(), ModelError> {
        let bodies = self.bodies.iter().map(|b| b as &dyn Item<S>);
        let items = || bodies.clone().chain(self.items().iter().map(|x| &**x));
        let mut finite = true;
        for item in items() {
            item.fields(&mut |_, x| finite &= x.nominal().is_finite());
        }
        if finite {
            return Ok(());
        }
        let mut bad = None;
        let mut k = 0;
        for item in items() {
            item.fields(&mut |_, x| {
                if bad.is_none() && !x.nominal().is_finite() {
                    bad = Some((k, x.nominal()));
                }
                k += 1;
            });
        }
        match bad {
            Some((k, v)) => Err(self.field_error(k, format!("value {v} is not finite"))),
            None => Ok(()),
        }
    }

    /// Step 3: every item has a name, unique among the items.
    fn check_item_names(&self) -> Result<(), ModelError> {
        // Borrowed names, sized up front: no reference counting, no rehashing.
        let mut names: HashSet<&str> = HashSet::with_capacity(self.items().len());
        for item in self.items() {
            let (kind, n) = (item.kind(), item.name());
            if n.is_empty() {
                return Err(field_error(kind, "", "name", "an item needs a name".into()));
            }
            if !names.insert(n) {
                return Err(field_error(kind, n, "name", "duplicate item name".into()));
            }
            if let Some(p) = eom_text::name_problem(n) {
                return Err(field_error(kind, n, "name", p));
            }
        }
        Ok(())
    }

    /// Step 5: every body is attached to an item that supports it.
    fn check_support(&self) -> Result<(), ModelError> {
        let mut supported: HashSet<&str> = HashSet::new();
        for item in self.items().iter().filter(|x| x.supports()) {
            supported.extend(item.bodies().iter().map(|b: &Name| &**b));
        }
        for b in &self.bodies {
            if !supported.contains(&*b.name) {
                return Err(field_error(
                    "body",
                    &b.name,
                    "",
                    "nothing constrains or supports it (no joint, spring, link or beam attaches to it)".into(),
                ));
            }
        }
        Ok(())
    }
}

/// Step 2: the bodies' names, and each body's own checks.
fn check_bodies<'m, S: ModelScalar>(cx: &mut Validation<'m, S>) -> Result<(), ModelError> {
    let bodies: &'m [Body<S>] = &cx.model.bodies;
    for b in bodies {
        let problem = if b.name.is_empty() {
            Some("a body needs a name".to_string())
        } else if &*b.name == GROUND {
            Some("`ground` is reserved for the fixed frame".to_string())
        } else if !cx.bodies.insert(&b.name) {
            Some("duplicate body name".to_string())
        } else {
            eom_text::name_problem(&b.name)
        };
        if let Some(p) = problem {
            return Err(ModelError::Model {
                item: label("body", &b.name),
                field: "name".into(),
                problem: p,
            });
        }
        b.validate(cx)?;
    }
    Ok(())
}
