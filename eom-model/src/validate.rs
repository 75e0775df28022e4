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

use crate::error::{ItemRef, ModelError, NameProblem};
use crate::geometry::{GROUND, Name};
use crate::items::{Body, Item, ModelScalar};
use crate::model::{Model, Place};
use crate::warning::Warning;
use hashbrown::HashSet;

/// An error with the place of the body or item at fault (boxed: the result stays small).
pub(crate) type Located = Box<(Place, ModelError)>;

pub use crate::items::Validation;

impl<S: ModelScalar> Model<S> {
    /// Check names, references, geometry and values (see [`crate::validate`] for the steps).
    /// Errors name the item and field. Warnings (physically dubious but computable input) are
    /// returned.
    pub fn validate(&self) -> Result<Vec<Warning>, ModelError> {
        self.validate_at().map_err(|e| e.1)
    }

    /// [`Model::validate`], an error with the place of the body or item at fault.
    pub(crate) fn validate_at(&self) -> Result<Vec<Warning>, Located> {
        if let Some(p) = eom_text::name_problem(&self.name) {
            let e = ModelError::ModelName { problem: p };
            return Err(Box::new((Place::Model, e)));
        }
        self.check_values()?;
        let mut cx = Validation::new(&self.bodies, self.items());
        check_bodies(&mut cx)?;
        self.check_item_names()?;
        for (k, item) in self.items().iter().enumerate() {
            let at = |e| Box::new((Place::Item(k), e));
            cx.check_connected(item).map_err(at)?;
            item.validate(&mut cx).map_err(at)?;
        }
        self.check_support()?;
        if self.bodies.is_empty() {
            let e = ModelError::NoBodies {
                model: self.name.to_string(),
            };
            return Err(Box::new((Place::Model, e)));
        }
        Ok(cx.into_warnings())
    }

    /// Step 1: every field is finite at the nominal point (a cheap pass; the first bad field
    /// is located, and labelled, only when there is one).
    fn check_values(&self) -> Result<(), Located> {
        let bodies = self.bodies.iter().map(|b| b as &dyn Item<S>);
        let items = || {
            let items = self.items().iter().map(|x| x as &dyn Item<S>);
            bodies.clone().chain(items)
        };
        let mut finite = true;
        for item in items() {
            item.fields(&mut |_, x| finite &= x.nominal().is_finite());
        }
        if finite {
            return Ok(());
        }
        let mut k = 0;
        for (i, item) in items().enumerate() {
            let mut bad = None;
            item.fields(&mut |_, x| {
                if bad.is_none() && !x.nominal().is_finite() {
                    bad = Some((k, x.nominal()));
                }
                k += 1;
            });
            if let Some((k, v)) = bad {
                let place = match i.checked_sub(self.bodies.len()) {
                    None => Place::Body(i),
                    Some(j) => Place::Item(j),
                };
                return Err(Box::new((place, {
                    let (item, field) = self.field_at(k);
                    ModelError::NotFinite {
                        item,
                        field,
                        value: v,
                    }
                })));
            }
        }
        Ok(())
    }

    /// Step 3: every item has a name, unique among the items.
    fn check_item_names(&self) -> Result<(), Located> {
        // Borrowed names, sized up front: no reference counting, no rehashing.
        let mut names: HashSet<&str> = HashSet::with_capacity(self.items().len());
        for (k, item) in self.items().iter().enumerate() {
            let (kind, n) = (item.kind(), item.name());
            let problem = if n.is_empty() {
                Some(NameProblem::Missing)
            } else if !names.insert(n) {
                Some(NameProblem::Duplicate)
            } else {
                eom_text::name_problem(n).map(NameProblem::Invalid)
            };
            if let Some(problem) = problem {
                let item = ItemRef::new(kind, n);
                return Err(Box::new((
                    Place::Item(k),
                    ModelError::Name { item, problem },
                )));
            }
        }
        Ok(())
    }

    /// Step 5: every body is attached to an item that supports it.
    fn check_support(&self) -> Result<(), Located> {
        let mut supported: HashSet<&str> = HashSet::new();
        for item in self.items().iter().filter(|x| x.supports()) {
            supported.extend(item.bodies().iter().map(|b: &Name| &**b));
        }
        for (k, b) in self.bodies.iter().enumerate() {
            if !supported.contains(&*b.name) {
                let body = ItemRef::new("body", &b.name);
                return Err(Box::new((Place::Body(k), ModelError::Unattached { body })));
            }
        }
        Ok(())
    }
}

/// Step 2: the bodies' names, and each body's own checks.
fn check_bodies<'m, S: ModelScalar>(cx: &mut Validation<'m, S>) -> Result<(), Located> {
    let bodies: &'m [Body<S>] = cx.bodies();
    for (k, b) in bodies.iter().enumerate() {
        let problem = if b.name.is_empty() {
            Some(NameProblem::Missing)
        } else if &*b.name == GROUND {
            Some(NameProblem::Reserved)
        } else if !cx.insert_body(&b.name) {
            Some(NameProblem::Duplicate)
        } else {
            eom_text::name_problem(&b.name).map(NameProblem::Invalid)
        };
        if let Some(problem) = problem {
            let item = ItemRef::new("body", &b.name);
            return Err(Box::new((
                Place::Body(k),
                ModelError::Name { item, problem },
            )));
        }
        b.validate(cx).map_err(|e| Box::new((Place::Body(k), e)))?;
    }
    Ok(())
}
