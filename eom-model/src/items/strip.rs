//! [`Strip`]: a two-dimensional thin-airfoil section of a given span width on a body — the
//! aerodynamics of the typical section and of strip theory on a flexible wing.
//!
//! The section has semichord `b`, its elastic axis (the item's point) `a` semichords aft of
//! mid-chord, width `Δ`, lift slope `c_l` (2π by default) in air of density ρ at airspeed U.
//! With the plunge h of the point positive down, the pitch θ positive nose up, the lift L
//! positive up and the moment M about the point positive nose up (Theodorsen, NACA Report 496;
//! Hodges & Pierce, *Introduction to Structural Dynamics and Aeroelasticity*, ch. 5):
//!
//! ```text
//! L = Δ·[ πρb² (ḧ + U θ̇ − b a θ̈)                        + c_l ρ U b · C[w] ]
//! M = Δ·[ πρb² (b a ḧ − U b (½ − a) θ̇ − b² (⅛ + a²) θ̈)  + c_l ρ U b² (a + ½) · C[w] ]
//! w = ḣ + U θ + b (½ − a) θ̇                               (the downwash at ¾ chord)
//! ```
//!
//! The apparent-mass (non-circulatory) terms are an added mass `πρb²Δ[[1, −ba], [−ba,
//! b²(⅛ + a²)]]` and an added damping on (h, θ); the circulatory lift passes through
//! `C[w] = w` (quasi-steady) or R. T. Jones' two lag states ([`Unsteady`]). The equations and
//! the reference flutter speeds they reproduce are in docs/aero-references.md.
//!
//! **Axes.** `forward` points from the trailing edge to the leading edge, `down` is the
//! section's down (the lift acts along `−down`), and the pitch axis is `down × forward` (nose
//! up turns `forward` towards `−down`). The defaults are those of the wing: forward +x, down −z.
//!
//! **Airspeed and air stream** as for the wing: without a given airspeed the air is still and
//! the body flies at its nominal velocity (U its component along `forward`; the body-axis
//! velocities of the point are the air-relative ones, and include `U θ`); with a given
//! airspeed the air moves at `v_air = v_body − U·forward`, and the stream turned by the body's
//! rotation adds the `U θ` part of the downwash as a stiffness on the rotations.

use super::Validation;
use super::surface::{self, Surface};
use super::unsteady::{JONES_DIRECT, Unsteady};
use super::{GROUND, ModelScalar, Physics, Vec3, item, name, zero3};
use crate::assemble::{Assembly, ItemRow, LagTerm, Term};
use crate::error::ModelError;
use crate::geometry::Point;
use crate::geometry::cross;
use eom_sym::scalar::Scalar;

item! {
    /// A thin-airfoil strip at a point of a body (see the module documentation).
    pub struct Strip<S>: "strip", "strip"
        (bodies: body, supports: false)
    {
        ..surface_fields!(mount),
        /// Semichord b.
        pub semichord: S = S::one() => scalar(semichord, "semichord"),
        /// Elastic-axis position a, in semichords aft of mid-chord (−1 the leading edge).
        pub elastic_axis: S = S::zero() => scalar(elastic_axis, "elastic_axis"),
        /// Span width Δ of the strip.
        pub width: S = S::one() => scalar(width, "width"),
        /// Lift slope c_l per radian (2π: thin-airfoil theory).
        pub lift_slope: S = S::from_f64(2.0 * std::f64::consts::PI)
            => scalar(lift_slope, "lift_slope"),
        ..surface_fields!(air),
        /// Quasi-steady, Jones' lag states, or decided by the linearization (`Auto`).
        pub unsteady: Unsteady = Unsteady::QuasiSteady => choice(unsteady, "unsteady"),
    }
    /// A strip on the ground with unit semichord and width, the elastic axis at mid-chord,
    /// lift slope 2π, ρ = 1.225, the wing's default axes, quasi-steady.
    pub fn new;
}

impl<S: Scalar> Strip<S> {
    /// The forward (towards the leading edge) and down axes in model axes.
    pub fn axes(mut self, forward: Vec3<S>, down: Vec3<S>) -> Self {
        self.forward = forward;
        self.down = down;
        self
    }

    /// The airspeed used: the given one, else `velocity` along `forward`.
    pub fn airspeed_with(&self, velocity: &Vec3<S>) -> S {
        surface::airspeed_with(self.airspeed, &self.forward, velocity)
    }

    /// The nominal velocity of the air (zero without a given airspeed).
    fn air_velocity(&self, velocity: &Vec3<S>) -> Vec3<S> {
        surface::air_velocity(self.airspeed, &self.forward, velocity)
    }

    /// The lift direction `−down` and the pitch axis `down × forward`.
    fn lift_and_pitch_axes(&self) -> (Vec3<S>, Vec3<S>) {
        let up = self.down.map(|x| -x);
        (up, cross(&self.down, &self.forward))
    }

    /// The section's coefficients at airspeed `u`, per unit of the rows (z along the lift
    /// direction, φ about the pitch axis: h = −z, θ = φ), width included:
    /// `(added mass, added damping, circulatory force f, downwash gradient g)`, so that the
    /// circulatory force on (z, φ) is `f · C[w]` with `w = g · (ż, φ̇) + U θ`.
    #[allow(clippy::type_complexity)]
    pub fn coefficients(&self, u: S) -> ([[S; 2]; 2], [[S; 2]; 2], [S; 2], [S; 2]) {
        let (b, a, half) = (self.semichord, self.elastic_axis, S::from_f64(0.5));
        let pi = S::from_f64(std::f64::consts::PI);
        let q = pi * self.density * b * b * self.width;
        let ba = b * a;
        let inertia = b * b * (S::from_f64(0.125) + a * a);
        // T·M_a·T, T·C_a·T with T = diag(−1, 1) (h = −z).
        let mass = [[q, q * ba], [q * ba, q * inertia]];
        let back = b * (half - a);
        let damping = [[S::zero(), -(q * u)], [S::zero(), q * u * back]];
        let c = self.lift_slope * self.density * u * b * self.width;
        let force = [c, c * b * (a + half)];
        let gradient = [-S::one(), back];
        (mass, damping, force, gradient)
    }
}

impl<S: ModelScalar> Strip<S> {
    /// What the checks shared with the wing read.
    fn surface(&self) -> Surface<'_, S> {
        Surface {
            kind: "strip",
            item: &self.name,
            body: &self.body,
            axes: [&self.forward, &self.down],
            airspeed: self.airspeed.as_ref(),
        }
    }

    /// The rows of the point's lift-direction displacement z and pitch rotation φ.
    fn rows(&self, cx: &Assembly<'_, S>) -> [ItemRow<S>; 2] {
        let (up, pitch) = self.lift_and_pitch_axes();
        let mut p = Point::new();
        p.bodies = [self.body.clone(), name(GROUND)];
        p.location = self.location;
        p.forces = 1;
        p.axis = up;
        let (z, _) = cx.point(&p, "strip", &self.name);
        p.forces = 0;
        p.moments = 1;
        p.axis = pitch;
        let (phi, _) = cx.point(&p, "strip", &self.name);
        [z.rows[0], phi.rows[0]]
    }
}

impl<S: ModelScalar> Physics<S> for Strip<S> {
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        let positive = [
            ("semichord", &self.semichord, "semichord"),
            ("width", &self.width, "span width"),
            ("lift_slope", &self.lift_slope, "lift slope"),
            ("density", &self.density, "air density"),
        ];
        self.surface().check(&positive, cx)
    }

    /// The added mass and damping on the point's (z, φ), and the circulatory force: directly
    /// (quasi-steady) or through Jones' two lag states.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let body = cx.body(&self.body);
        let velocity = body.map_or(zero3(), |k| cx.bodies[k].velocity);
        let u = self.airspeed_with(&velocity);
        let (mass, damping, force, gradient) = self.coefficients(u);
        let rows = self.rows(cx);
        let block = |m: [[S; 2]; 2]| -> Vec<Vec<S>> { m.iter().map(|r| r.to_vec()).collect() };
        cx.add_rows_block(Term::ItemMass, &rows, &block(mass));
        cx.add_rows_block(Term::Damping, &rows, &block(damping));
        // The downwash from the body's rotation θ in a moving stream: (up × v_air)·θ.
        let (up, _) = self.lift_and_pitch_axes();
        let turn = cross(&up, &self.air_velocity(&velocity));
        let direct = match self.unsteady {
            Unsteady::QuasiSteady => S::one(),
            Unsteady::Auto => {
                cx.warn(super::unsteady::auto_assembled("strip", &self.name));
                S::one()
            }
            Unsteady::Jones => S::from_f64(JONES_DIRECT),
        };
        // The direct part of the circulatory force, f·direct·w, on the left-hand side.
        let circulation: Vec<Vec<S>> = (0..2)
            .map(|i| (0..2).map(|j| -(force[i] * direct * gradient[j])).collect())
            .collect();
        cx.add_rows_block(Term::Damping, &rows, &circulation);
        if let Some(k) = body {
            for (i, row) in rows.iter().enumerate() {
                for (c, t) in turn.iter().enumerate() {
                    if t.is_zero() {
                        continue;
                    }
                    let g = -(force[i] * direct * *t);
                    for &(j, x) in row {
                        cx.add(Term::LoadStiffness, j, 6 * k + 3 + c, x * g);
                    }
                }
            }
        }
        if self.unsteady == Unsteady::Jones {
            self.lag_states(cx, &rows, u, force, gradient, &turn, body);
        }
        Ok(())
    }
}

impl<S: ModelScalar> Strip<S> {
    /// Jones' states `ẋᵢ = −βᵢ xᵢ + w`, `βᵢ = β̄ᵢ U/b`, and their force `f·Aᵢβᵢ·xᵢ`.
    #[allow(clippy::too_many_arguments)]
    fn lag_states(
        &self,
        cx: &mut Assembly<'_, S>,
        rows: &[ItemRow<S>; 2],
        u: S,
        force: [S; 2],
        gradient: [S; 2],
        turn: &Vec3<S>,
        body: Option<usize>,
    ) {
        let rate = u / self.semichord;
        for (s, gain) in surface::jones_states(cx, &self.name, rate, body, turn) {
            for (i, row) in rows.iter().enumerate() {
                for &(j, x) in row {
                    cx.add_lag(LagTerm::Velocity, s, j, gradient[i] * x);
                    cx.add_lag(LagTerm::Force, j, s, x * force[i] * gain);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Degeneracy;

    fn model_with(strip: Strip<f64>) -> crate::Model<f64> {
        let mut m = crate::Model::new("m");
        m.add(crate::Body::new("b").mass(1.0).moments([1.0; 3]));
        m.add(strip);
        m
    }

    #[test]
    fn bad_input_is_an_error_naming_the_strip_and_field() {
        let s = || Strip::new("root").on("b").airspeed(10.0);
        let error = |strip| model_with(strip).validate().expect_err("invalid");
        for (strip, want, quantity) in [
            (s().semichord(0.0), "semichord", "semichord"),
            (s().width(-1.0), "width", "span width"),
            (s().lift_slope(0.0), "lift_slope", "lift slope"),
        ] {
            let e = error(strip);
            assert!(
                matches!(&e, ModelError::NotPositive { item, field, quantity: q, .. }
                    if item.kind == "strip" && item.name == "root" && field == want && *q == quantity),
                "{e:?}"
            );
        }
        let e = error(s().on("ground"));
        assert!(
            matches!(&e, ModelError::OnGround { item } if item.kind == "strip"),
            "{e:?}"
        );
        let e = error(Strip::new("root").on("b"));
        assert!(
            matches!(&e, ModelError::NoAirspeed { body, .. } if body == "b"),
            "{e:?}"
        );
        let e = error(s().axes([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]));
        assert!(
            matches!(&e, ModelError::Degenerate { field, shape: Degeneracy::NotPerpendicular { .. }, .. } if field == "down"),
            "{e:?}"
        );
    }
}
