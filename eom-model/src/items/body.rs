//! [`Body`]: a rigid body, with the nominal motion about which the equations are linearized.

use super::Validation;
use super::{ModelScalar, Physics, Vec3, item, zero3};
use crate::assemble::{Assembly, Term};
use crate::error::{Inertia, ModelError};
use crate::geometry::{self, Mat3, scale, skew};
use crate::warning::{ItemRef, Warning};
use eom_sym::scalar::Scalar;

item! {
    /// A rigid body: mass, inertia about its mass centre (global axes), and the nominal motion
    /// about which the equations are linearized.
    pub struct Body<S>: "body", "body"
        (bodies: none, supports: false)
    {
        /// Mass centre location.
        pub location: Vec3<S> = zero3() => vector(at, "at", Polar),
        /// Mass (zero is allowed: a massless body).
        pub mass: S = S::zero() => scalar(mass, "mass"),
        /// `[Ixx, Iyy, Izz]` about the mass centre.
        pub moments: Vec3<S> = zero3() => vector(moments, "moments", Plain),
        /// `[Ixy, Iyz, Izx]` as positive integrals (∫xy dm, …); they enter the tensor with a
        /// minus sign.
        pub products: Vec3<S> = zero3() => vector(products, "products", Products),
        /// Nominal velocity of the mass centre.
        pub velocity: Vec3<S> = zero3() => vector(velocity, "velocity", Polar),
        /// Nominal angular velocity (spin).
        pub angular_velocity: Vec3<S> = zero3()
            => vector(angular_velocity, "angular_velocity", Axial),
    }
    /// A body with zero mass and inertia at the origin, at rest.
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for Body<S> {
    /// A negative mass is an error; moments of inertia that no physical body has are a
    /// warning. (The name is checked with the other bodies' names.)
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        if self.mass.nominal() < 0.0 {
            return Err(ModelError::NegativeMass {
                item: ItemRef::new("body", &self.name),
                mass: self.mass.nominal(),
            });
        }
        check_inertia(self, cx)
    }

    /// Mass and inertia; the momentum of the nominal velocity and the gyroscopic terms of the
    /// nominal spin (which must be about an axis of symmetry); the kinematic velocity
    /// matrix.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let k = cx.body(&self.name);
        let Some(kk) = k else {
            return Ok(());
        };
        for i in 0..3 {
            cx.add(Term::Mass, 6 * kk + i, 6 * kk + i, self.mass);
        }
        let inertia = inertia_tensor(self);
        cx.add_block(Term::Mass, (k, 3), (k, 3), &inertia, 1.0);
        let w0 = self.angular_velocity;
        if !geometry::is_zero(&w0) {
            check_spin(self, &inertia)?;
            let h = geometry::mat_vec(&inertia, &w0);
            cx.add_block(Term::Momentum, (k, 3), (k, 3), &skew(&h), -1.0);
        }
        if !geometry::is_zero(&self.velocity) {
            let mvv = scale(self.mass, &self.velocity);
            cx.add_block(Term::Momentum, (k, 0), (k, 3), &skew(&mvv), -1.0);
            cx.add_block(Term::Velocity, (k, 0), (k, 3), &skew(&self.velocity), 1.0);
        }
        Ok(())
    }
}

/// Relative size below which a negative principal moment or a violated triangle inequality
/// is rounding.
const INERTIA_ROUNDING: f64 = 1e-9;

/// A physical inertia tensor (about the mass centre) is positive semidefinite and its
/// principal moments obey the triangle inequalities `I₁ + I₂ ≥ I₃`. Checked on the full tensor,
/// products included: products that make it indefinite are an error naming the body and
/// field; principal moments that violate a triangle inequality are a warning naming them. A
/// negative moment given without products stays a warning too: EoM's sample pendulum uses
/// `Ix = −4.5` as a stand-in for an inertia about the pin, and the published eigenvalues
/// depend on it.
fn check_inertia<S: Scalar>(b: &Body<S>, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
    let t = inertia_tensor(b);
    let m = nalgebra::Matrix3::from_fn(|r, c| t[r][c].nominal());
    let has_products = b.products.iter().any(|p| p.nominal() != 0.0);
    let diag: Vec<f64> = b.moments.iter().map(|x| x.nominal()).collect();
    if m.iter().any(|x| !x.is_finite()) {
        return Err(ModelError::InertiaNotFinite {
            item: ItemRef::new("body", &b.name),
            field: if has_products { "products" } else { "moments" }.into(),
            tensor: Box::new(m),
        });
    }
    let mut e: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
    e.sort_by(f64::total_cmp);
    let scale = e.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let tol = INERTIA_ROUNDING * scale;
    // The field at fault: the moments when they fail on their own, else the products.
    let triangle = |x: &[f64]| {
        x.iter().all(|&v| v > tol) && (0..3).any(|k| x[k] > x[(k + 1) % 3] + x[(k + 2) % 3] + tol)
    };
    let moments_bad = diag.iter().any(|&v| v < -tol) || triangle(&diag);
    let field = if has_products && !moments_bad {
        "products"
    } else {
        "moments"
    };
    if e[0] < -tol {
        if !has_products {
            cx.warn(Warning::NegativeMoments {
                item: ItemRef::new("body", &b.name),
                moments: diag,
            });
            return Ok(());
        }
        return Err(ModelError::IndefiniteInertia {
            item: ItemRef::new("body", &b.name),
            field: field.into(),
            inertia: Box::new(Inertia {
                moments: [diag[0], diag[1], diag[2]],
                products: b.products.map(|p| p.nominal()),
                principal: [e[0], e[1], e[2]],
            }),
        });
    }
    // Principal moments that violate a triangle inequality stay a warning: planar models
    // and randomised tests use such values (e.g. only a yaw inertia), and they do not break
    // the linearization as an indefinite tensor does.
    if triangle(&e) {
        cx.warn(Warning::InertiaTriangle {
            item: ItemRef::new("body", &b.name),
            field,
            principal: e,
        });
    }
    Ok(())
}

/// The inertia tensor; products enter with a minus sign, ordered (xy, yz, zx).
fn inertia_tensor<S: Scalar>(b: &Body<S>) -> Mat3<S> {
    let n = |x: S| if x.is_zero() { x } else { -x };
    let [ixx, iyy, izz] = b.moments;
    let [ixy, iyz, izx] = b.products;
    [
        [ixx, n(ixy), n(izx)],
        [n(ixy), iyy, n(iyz)],
        [n(izx), n(iyz), izz],
    ]
}

/// A spinning body must spin about an axis of symmetry (at the nominal point): the
/// linearization in the non-spinning (Resal) frame has constant coefficients only then.
fn check_spin<S: Scalar>(b: &Body<S>, inertia: &Mat3<S>) -> Result<(), ModelError> {
    let w: Vec<f64> = b.angular_velocity.iter().map(|x| x.nominal()).collect();
    let i: Vec<Vec<f64>> = inertia
        .iter()
        .map(|r| r.iter().map(|x| x.nominal()).collect())
        .collect();
    let wn = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    if wn == 0.0 {
        return Ok(());
    }
    let a = [w[0] / wn, w[1] / wn, w[2] / wn];
    let ia: Vec<f64> = (0..3)
        .map(|r| (0..3).map(|c| i[r][c] * a[c]).sum())
        .collect();
    let scale = i
        .iter()
        .flatten()
        .map(|x| x.abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let c = [
        a[1] * ia[2] - a[2] * ia[1],
        a[2] * ia[0] - a[0] * ia[2],
        a[0] * ia[1] - a[1] * ia[0],
    ];
    let cn = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let item = ItemRef::new("body", &b.name);
    if cn > 1e-9 * scale {
        return Err(ModelError::SpinNotPrincipal { item });
    }
    // Transverse inertia: I projected on the plane ⊥ a must be isotropic.
    let axial = a.iter().zip(&ia).map(|(x, y)| x * y).sum::<f64>();
    let tr = i[0][0] + i[1][1] + i[2][2] - axial;
    let half = tr / 2.0;
    // Check vᵀ I v = half for two perpendicular unit vectors.
    let k = (0..3)
        .min_by(|&x, &y| a[x].abs().partial_cmp(&a[y].abs()).expect("finite"))
        .expect("3");
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let mut v1 = [
        a[1] * e[2] - a[2] * e[1],
        a[2] * e[0] - a[0] * e[2],
        a[0] * e[1] - a[1] * e[0],
    ];
    let n1 = (v1[0] * v1[0] + v1[1] * v1[1] + v1[2] * v1[2]).sqrt();
    v1.iter_mut().for_each(|x| *x /= n1);
    let q: f64 = (0..3)
        .map(|r| (0..3).map(|c| v1[r] * i[r][c] * v1[c]).sum::<f64>())
        .sum();
    if (q - half).abs() > 1e-9 * scale {
        return Err(ModelError::SpinNotSymmetric { item });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::items::vec3;

    #[test]
    fn a_spin_about_an_unsymmetric_principal_axis_is_an_error() {
        let b = Body::<f64>::new("top")
            .moments(vec3(1.0, 2.0, 3.0))
            .angular_velocity(vec3(0.0, 0.0, 1.0));
        let e = check_spin(&b, &inertia_tensor(&b)).unwrap_err();
        assert!(
            matches!(&e, ModelError::SpinNotSymmetric { item } if item.name == "top"),
            "{e:?}"
        );
        let sym = Body::<f64>::new("top")
            .moments(vec3(2.0, 2.0, 3.0))
            .angular_velocity(vec3(0.0, 0.0, 1.0));
        assert!(check_spin(&sym, &inertia_tensor(&sym)).is_ok());
    }
}
