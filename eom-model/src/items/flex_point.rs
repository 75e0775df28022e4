//! [`FlexPoint`]: an elastic, viscous bushing on the directions of a joint.

use super::Validation;
use super::{ModelScalar, Physics, item};
use crate::assemble::{Assembly, Reaction, Term};
use crate::error::{ItemRef, ModelError};
use crate::geometry::Point;
use eom_sym::scalar::Scalar;

item! {
    /// An elastic, viscous bushing on the same directions as a joint.
    pub struct FlexPoint<S>: "flex point", "flex_point"
        (bodies: point, supports: point.constrains())
    {
        /// Geometry.
        pub point: Point<S> = Point::new() => point(),
        /// `[translational, rotational]` stiffness (used when `stiffness_matrix` is `None`).
        pub stiffness: [S; 2] = [S::zero(), S::zero()] => pair(stiffness, "stiffness"),
        /// `[translational, rotational]` damping (used when `damping_matrix` is `None`).
        pub damping: [S; 2] = [S::zero(), S::zero()] => pair(damping, "damping"),
        /// Full `(forces+moments)²` stiffness matrix, rows ordered `[force rows; moment rows]`
        /// in the point's deterministic direction basis.
        pub stiffness_matrix: Option<Vec<Vec<S>>> = None
            => matrix(stiffness_matrix, "stiffness_matrix"),
        /// Full damping matrix.
        pub damping_matrix: Option<Vec<Vec<S>>> = None
            => matrix(damping_matrix, "damping_matrix"),
    }
    /// A bushing with zero properties.
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for FlexPoint<S> {
    fn validate(&self, _cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        let n = (self.point.forces + self.point.moments) as usize;
        for (m, field) in [
            (&self.stiffness_matrix, "stiffness_matrix"),
            (&self.damping_matrix, "damping_matrix"),
        ] {
            if let Some(m) = m
                && (m.len() != n || m.iter().any(|r| r.len() != n))
            {
                return Err(ModelError::MatrixSize {
                    item: ItemRef::new("flex point", &self.name),
                    field: field.into(),
                    n,
                });
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
