//! [`FlexPoint`]: an elastic, viscous bushing on the directions of a joint.

use super::Validation;
use super::{Field, Item, ModelScalar, Name, name};
use crate::assemble::{Assembly, Reaction, Term};
use crate::error::ModelError;
use crate::geometry::{Point, point_builders};
use eom_sym::scalar::Scalar;

/// An elastic, viscous bushing on the same directions as a joint.
#[derive(Clone, Debug, PartialEq)]
pub struct FlexPoint<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub point: Point<S>,
    /// `[translational, rotational]` stiffness (used when `stiffness_matrix` is `None`).
    pub stiffness: [S; 2],
    /// `[translational, rotational]` damping (used when `damping_matrix` is `None`).
    pub damping: [S; 2],
    /// Full `(forces+moments)²` stiffness matrix, rows ordered `[force rows; moment rows]`
    /// in the point's deterministic direction basis.
    pub stiffness_matrix: Option<Vec<Vec<S>>>,
    /// Full damping matrix.
    pub damping_matrix: Option<Vec<Vec<S>>>,
}
impl<S: Scalar> FlexPoint<S> {
    /// A bushing with zero properties.
    pub fn new(n: &str) -> Self {
        FlexPoint {
            name: name(n),
            point: Point::new(),
            stiffness: [S::zero(), S::zero()],
            damping: [S::zero(), S::zero()],
            stiffness_matrix: None,
            damping_matrix: None,
        }
    }
    /// Translational and rotational stiffness.
    pub fn stiffness(mut self, kt: impl Into<S>, kr: impl Into<S>) -> Self {
        self.stiffness = [kt.into(), kr.into()];
        self
    }
    /// Translational and rotational damping.
    pub fn damping(mut self, ct: impl Into<S>, cr: impl Into<S>) -> Self {
        self.damping = [ct.into(), cr.into()];
        self
    }
    /// Full stiffness matrix.
    pub fn stiffness_matrix(mut self, k: Vec<Vec<S>>) -> Self {
        self.stiffness_matrix = Some(k);
        self
    }
    /// Full damping matrix.
    pub fn damping_matrix(mut self, c: Vec<Vec<S>>) -> Self {
        self.damping_matrix = Some(c);
        self
    }
}
point_builders!(FlexPoint);

impl<S: Scalar> FlexPoint<S> {
    /// The flexpoint converted field by field with `f`, in the order of [`Item::fields`].
    pub fn map<T>(&self, f: &mut dyn FnMut(&S) -> T) -> FlexPoint<T> {
        FlexPoint {
            name: self.name.clone(),
            point: self.point.map(f),
            stiffness: [f(&self.stiffness[0]), f(&self.stiffness[1])],
            damping: [f(&self.damping[0]), f(&self.damping[1])],
            stiffness_matrix: map_matrix(&self.stiffness_matrix, f),
            damping_matrix: map_matrix(&self.damping_matrix, f),
        }
    }
}

impl<S: ModelScalar> Item<S> for FlexPoint<S> {
    fn kind(&self) -> &'static str {
        "flex point"
    }

    fn name(&self) -> &Name {
        &self.name
    }

    fn settings(&self) -> Vec<(&'static str, super::Setting)> {
        self.point.settings()
    }

    fn fields(&self, f: &mut dyn FnMut(Field, &S)) {
        self.point.fields(f);
        f(Field::nth("stiffness", 0), &self.stiffness[0]);
        f(Field::nth("stiffness", 1), &self.stiffness[1]);
        f(Field::nth("damping", 0), &self.damping[0]);
        f(Field::nth("damping", 1), &self.damping[1]);
        for (m, field) in [
            (&self.stiffness_matrix, "stiffness_matrix"),
            (&self.damping_matrix, "damping_matrix"),
        ] {
            for (i, row) in m.iter().flatten().enumerate() {
                for (j, x) in row.iter().enumerate() {
                    f(Field::entry(field, i, j), x);
                }
            }
        }
    }

    fn bodies(&self) -> &[Name] {
        &self.point.bodies
    }

    fn supports(&self) -> bool {
        self.point.constrains()
    }

    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        self.point
            .validate("flex point", &self.name, &mut |w| cx.warn(w))?;
        let n = (self.point.forces + self.point.moments) as usize;
        for (m, field) in [
            (&self.stiffness_matrix, "stiffness_matrix"),
            (&self.damping_matrix, "damping_matrix"),
        ] {
            if let Some(m) = m
                && (m.len() != n || m.iter().any(|r| r.len() != n))
            {
                return Err(super::field_error(
                    "flex point",
                    &self.name,
                    field,
                    format!("must be {n}×{n} (forces + moments)"),
                ));
            }
        }
        Ok(())
    }

    /// One elastic row per direction, with the stiffness and damping blocks (diagonal unless
    /// full matrices are given); the multipliers are the bushing's force and moment.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, geometry) = cx.point(&self.point, "flex point", &self.name);
        let per_direction = |v: [S; 2]| -> Vec<S> {
            let forces = geometry.forces.iter().map(|_| v[0]);
            forces
                .chain(geometry.moments.iter().map(|_| v[1]))
                .collect()
        };
        let kb =
            (self.stiffness_matrix.clone()).unwrap_or_else(|| diag(&per_direction(self.stiffness)));
        let cb =
            (self.damping_matrix.clone()).unwrap_or_else(|| diag(&per_direction(self.damping)));
        cx.add_rows_block(Term::Stiffness, &rows.rows, &kb);
        cx.add_rows_block(Term::Damping, &rows.rows, &cb);
        let reaction = Reaction::Point(&self.point, geometry);
        cx.elastic("flex point", &self.name, rows, kb, reaction);
        Ok(())
    }
}

/// A matrix field converted with `f`, row by row.
fn map_matrix<S, T>(m: &Option<Vec<Vec<S>>>, f: &mut dyn FnMut(&S) -> T) -> Option<Vec<Vec<T>>> {
    m.as_ref()
        .map(|m| m.iter().map(|r| r.iter().map(&mut *f).collect()).collect())
}

/// The diagonal matrix of `v`.
fn diag<S: Scalar>(v: &[S]) -> Vec<Vec<S>> {
    let n = v.len();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i == j { v[i] } else { S::zero() })
                .collect()
        })
        .collect()
}
