//! [`Wing`]: a lifting surface on a body, as the quasi-steady aerodynamic damping of its
//! stability derivatives.
//!
//! A wing moving through still air at airspeed V feels, to first order in the perturbation
//! velocities of its reference point, the force and moment `F = (q̄S/V)·M·x` with
//! `x = (u, v, w, p, q, r)` in the wing's own axes (AVL's standard body axes: x forward,
//! y right, z down), `q̄ = ½ρV²` and
//!
//! ```text
//! M_ij = row_i · col_j · C_ij,   row = (1, 1, 1, b, c, b),   col = (1, 1, 1, b/2, c/2, b/2)
//! ```
//!
//! where `C_ij` are the non-dimensional body-axis derivatives by AVL's names (CXu … Cnr: rows
//! CX, CY, CZ per q̄S, Cl, Cn per q̄Sb, Cm per q̄Sc; columns u/V, v/V, w/V, pb/2V, qc/2V,
//! rb/2V). This is the matrix of the EoM software's wing ("build_mtx", there with 18 of the
//! 36 entries). The wing's damping block is `L = −(q̄S/V)·M = −(ρVS/2)·M` (so V never
//! divides), rotated into model axes by the 6×6 block rotation `diag(Q, Q)` whose rows are the
//! wing's forward, right and down axes, and attached to the body through the Jacobian of its
//! point with all three forces and moments relative to ground: a non-symmetric damping
//! block, which every reduction path and the generated code carry like any other.
//!
//! **Airspeed and air stream.** Without a given airspeed the air is still and the wing flies
//! at its body's nominal velocity: V is that velocity's component along the forward axis, and
//! the body-axis velocity perturbations of the point are exactly the air-relative ones (a
//! rotated body sees its own velocity along new axes, which tilts the relative wind). With a
//! given airspeed the air moves at `v_air = v_body − V·forward` (a wind tunnel: a body at rest
//! in a stream V), and a rotation θ of the body turns that stream in the body's axes by
//! `θ × v_air`: the wing then adds the stiffness block `Jᵀ·L[:, u v w]·(−[v_air]×)` on the
//! body's rotations (to the load stiffness), so that, e.g., a car modelled at rest on a moving
//! road sees the angle of attack of its pitch attitude. (When `v_air` is zero, as when the
//! given airspeed is the body's own speed along the forward axis, nothing is added.)
//!
//! **Unsteady lift.** With [`Unsteady::Jones`] the response to the wing's normal velocity
//! (the w column: angle of attack) passes through R. T. Jones' two-state approximation of
//! Wagner's function with the semichord c/2 (docs/unsteady-aerodynamics.md): the block keeps
//! ½ of that column, and two lag states carry the rest.
//!
//! The default orientation is forward = +x, down = −z: AVL's x forward, y right, z down are
//! the model's x forward, y left, z up turned by π about x (entry `(i, j)` of the block
//! changes sign by `sᵢsⱼ`, `s = (+, −, −, +, −, −)`).

use super::Validation;
use super::surface::{self, Surface};
use super::unsteady::{JONES_DIRECT, Unsteady};
use super::zero3;
use super::{GROUND, ModelScalar, Physics, Vec3, item, name};
use crate::assemble::{Assembly, ItemRow, LagTerm, Term};
use crate::error::ModelError;
use crate::geometry::Point;
use crate::geometry::{cross, skew};
use crate::warning::{ItemRef, Warning};
use eom_sym::scalar::Scalar;

/// The 36 derivative names in AVL's body-axis layout: `WING_DERIVATIVES[i][j]` is row i
/// (CX, CY, CZ, Cl, Cm, Cn) and column j (u, v, w, p, q, r).
pub const WING_DERIVATIVES: [[&str; 6]; 6] = [
    ["CXu", "CXv", "CXw", "CXp", "CXq", "CXr"],
    ["CYu", "CYv", "CYw", "CYp", "CYq", "CYr"],
    ["CZu", "CZv", "CZw", "CZp", "CZq", "CZr"],
    ["Clu", "Clv", "Clw", "Clp", "Clq", "Clr"],
    ["Cmu", "Cmv", "Cmw", "Cmp", "Cmq", "Cmr"],
    ["Cnu", "Cnv", "Cnw", "Cnp", "Cnq", "Cnr"],
];

/// The row and column of a derivative name (case-sensitive: AVL's `Cl` is roll).
pub fn wing_derivative_index(name: &str) -> Option<(usize, usize)> {
    WING_DERIVATIVES
        .iter()
        .enumerate()
        .find_map(|(i, row)| row.iter().position(|n| *n == name).map(|j| (i, j)))
}

/// The acceleration derivatives' names: rows CX … Cn per `ẇ c/(2V²)` (α̇ c/2V with
/// α̇ = ẇ/V), the aerodynamic mass of the w column.
pub const WING_ACCELERATION_DERIVATIVES: [&str; 6] =
    ["CXwd", "CYwd", "CZwd", "Clwd", "Cmwd", "Cnwd"];

item! {
    /// A wing: quasi-steady aerodynamic damping at a point of a body, from stability
    /// derivatives.
    pub struct Wing<S>: "wing", "wing"
        (bodies: body, supports: in_free_flight())
    {
        ..surface_fields!(mount),
        /// Reference area S.
        pub area: S = S::one() => scalar(area, "area"),
        /// Reference chord c (pitch moment, pitch rate).
        pub chord: S = S::one() => scalar(chord, "chord"),
        /// Reference span b (roll and yaw moments, roll and yaw rates).
        pub span: S = S::one() => scalar(span, "span"),
        ..surface_fields!(air),
        /// The derivatives `C_ij` by [`WING_DERIVATIVES`]; those not given are zero (a model
        /// file gives them as a table, `derivatives`, or from an AVL file, `avl`).
        pub derivatives: [[S; 6]; 6] = [[S::zero(); 6]; 6]
            => named_rows(WING_DERIVATIVES, "derivatives", "avl"),
        /// The acceleration derivatives by [`WING_ACCELERATION_DERIVATIVES`] (zero: none).
        pub acceleration: [S; 6] = [S::zero(); 6] => named(WING_ACCELERATION_DERIVATIVES),
        /// The circulatory lag: with [`Unsteady::Jones`] the forces and moments of the w
        /// column (the response to the normal velocity of the reference point: the angle of
        /// attack, and the angle that a rotation in a given air stream adds) pass through
        /// R. T. Jones' approximation of Wagner's function with the semichord `c/2` (two lag
        /// states, `<name>.lag1`, `<name>.lag2`); the other columns stay quasi-steady.
        pub unsteady: Unsteady = Unsteady::QuasiSteady
            => choice(unsteady, "unsteady", unless_default),
        /// Names given to [`Wing::derivative`] that are not derivative names (reported by the
        /// validation, since a builder cannot fail).
        unknown: Vec<String> = Vec::new() => hidden(),
    }
    /// A wing on the ground with unit reference quantities, ρ = 1.225, the default
    /// orientation (forward +x, down −z) and all derivatives zero.
    pub fn new;
}

impl<S: Scalar> Wing<S> {
    /// Whether the wing supports its body: aerodynamic forces hold a body up in free flight
    /// only: a wing without a given airspeed (its body flies at its nominal velocity through
    /// still air) supports its body; a wing in an air stream (a wind tunnel) leaves it to the
    /// structure.
    fn in_free_flight(&self) -> bool {
        self.airspeed.is_none()
    }

    /// A wing with the reference area, chord, span and the 36 derivatives of `d` (computed
    /// by eom-aero's vortex lattice or read from an AVL file). The reference point stays the
    /// caller's: put the wing [`at`](Wing::at) the model point of `d.reference.point`.
    pub fn from_derivatives(n: &str, d: &eom_aero::Derivatives) -> Self {
        let mut w = Wing::new(n)
            .area(S::from_f64(d.reference.sref))
            .chord(S::from_f64(d.reference.cref))
            .span(S::from_f64(d.reference.bref));
        for (i, row) in d.coefficients.iter().enumerate() {
            for (j, &c) in row.iter().enumerate() {
                w.derivatives[i][j] = S::from_f64(c);
            }
        }
        w
    }

    /// The wing's forward and down axes in model axes (orthonormal at the nominal point).
    pub fn axes(mut self, forward: Vec3<S>, down: Vec3<S>) -> Self {
        self.forward = forward;
        self.down = down;
        self
    }
    /// One derivative by its AVL name (`"CYv"`, `"Cnr"`, …); an unknown name is reported
    /// by the validation.
    pub fn derivative(mut self, n: &str, value: impl Into<S>) -> Self {
        match (
            wing_derivative_index(n),
            WING_ACCELERATION_DERIVATIVES.iter().position(|x| *x == n),
        ) {
            (Some((i, j)), _) => self.derivatives[i][j] = value.into(),
            (None, Some(i)) => self.acceleration[i] = value.into(),
            (None, None) => self.unknown.push(n.to_string()),
        }
        self
    }

    /// The aerodynamic mass block in model axes at the point, `T_a = −(ρSc/4)·Tᵀ·A·T` with `A`
    /// the acceleration derivatives in the w column, rows scaled by (1, 1, 1, b, c, b): the
    /// force of the acceleration derivatives is `−T_a` times the point's acceleration.
    pub fn added_mass(&self) -> [[S; 6]; 6] {
        let (b, c) = (self.span, self.chord);
        let row = [S::one(), S::one(), S::one(), b, c, b];
        let k = -(self.density * self.area * self.chord * S::from_f64(0.25));
        let q = self.rotation();
        let t = |a: usize, i: usize| block_rotation(&q, a, i);
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let terms: Vec<S> = (0..6)
                    .filter(|&a| !self.acceleration[a].is_zero() && !t(a, i).is_zero())
                    .map(|a| times(times(t(a, i), times(self.acceleration[a], row[a])), t(2, j)))
                    .filter(|x| !x.is_zero())
                    .collect();
                let s = S::sum(&terms);
                if s.is_zero() { s } else { times(k, s) }
            })
        })
    }

    /// The airspeed used: the given one, else the component of `velocity` (the body's
    /// nominal velocity) along the forward axis.
    pub fn airspeed_with(&self, velocity: &Vec3<S>) -> S {
        surface::airspeed_with(self.airspeed, &self.forward, velocity)
    }

    /// The nominal velocity of the air for a body moving at `velocity`: zero (still air)
    /// without a given airspeed, else `velocity − V·forward`.
    pub fn air_velocity(&self, velocity: &Vec3<S>) -> Vec3<S> {
        surface::air_velocity(self.airspeed, &self.forward, velocity)
    }

    /// The rows of the rotation `Q` from model axes to the wing's axes: forward, right
    /// (`down × forward`), down.
    pub fn rotation(&self) -> [Vec3<S>; 3] {
        [self.forward, cross(&self.down, &self.forward), self.down]
    }

    /// `M = build_mtx`: the derivatives with rows scaled by (1, 1, 1, b, c, b) and columns
    /// by (1, 1, 1, b/2, c/2, b/2), in the wing's axes.
    pub fn scaled_derivatives(&self) -> [[S; 6]; 6] {
        let (b, c) = (self.span, self.chord);
        let half = S::from_f64(0.5);
        let row = [S::one(), S::one(), S::one(), b, c, b];
        let col = [S::one(), S::one(), S::one(), half * b, half * c, half * b];
        let mut m = [[S::zero(); 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                let d = self.derivatives[i][j];
                if !d.is_zero() {
                    m[i][j] = times(times(d, row[i]), col[j]);
                }
            }
        }
        m
    }

    /// The damping block `L = −(ρVS/2)·diag(Q,Q)ᵀ·M·diag(Q,Q)` in model axes at the wing's
    /// point, rows (X, Y, Z, L, M, N), columns (u, v, w, p, q, r), for airspeed `v`: the
    /// aerodynamic force on the body is `−L` times the point's velocity.
    pub fn damping(&self, v: S) -> [[S; 6]; 6] {
        let m = self.scaled_derivatives();
        let k = -(self.density * v * self.area * S::from_f64(0.5));
        let q = self.rotation();
        let t = |a: usize, i: usize| block_rotation(&q, a, i);
        // M·T first (6×6), then Tᵀ·(M·T), skipping structural zeros.
        let mt: [[S; 6]; 6] = std::array::from_fn(|a| {
            std::array::from_fn(|i| {
                let terms: Vec<S> = (0..6)
                    .filter(|&b| !m[a][b].is_zero() && !t(b, i).is_zero())
                    .map(|b| times(m[a][b], t(b, i)))
                    .collect();
                S::sum(&terms)
            })
        });
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let terms: Vec<S> = (0..6)
                    .filter(|&a| !t(a, i).is_zero() && !mt[a][j].is_zero())
                    .map(|a| times(t(a, i), mt[a][j]))
                    .collect();
                let s = S::sum(&terms);
                if s.is_zero() { s } else { times(k, s) }
            })
        })
    }
}

impl<S: Scalar> Wing<S> {
    /// The w column of the damping block in model axes, `w_L = −(ρVS/2)·Tᵀ·M[:, w]`, and the
    /// row that takes the wing's normal velocity from the point's, `(down, 0)`: the block's
    /// part from the normal velocity is `w_L ⊗ (down, 0)`.
    pub fn normal_column(&self, v: S) -> ([S; 6], [S; 6]) {
        let m = self.scaled_derivatives();
        let k = -(self.density * v * self.area * S::from_f64(0.5));
        let q = self.rotation();
        let col: [S; 6] = std::array::from_fn(|i| {
            let terms: Vec<S> = (0..6)
                .filter(|&a| a / 3 == i / 3 && !m[a][2].is_zero() && !q[a % 3][i % 3].is_zero())
                .map(|a| times(q[a % 3][i % 3], m[a][2]))
                .collect();
            let s = S::sum(&terms);
            if s.is_zero() { s } else { times(k, s) }
        });
        let d = self.down;
        (col, [d[0], d[1], d[2], S::zero(), S::zero(), S::zero()])
    }
}

/// Entry (a, i) of diag(Q, Q): wing row `a` from model column `i` (forces, then moments).
fn block_rotation<S: Scalar>(q: &[Vec3<S>; 3], a: usize, i: usize) -> S {
    if a / 3 == i / 3 {
        q[a % 3][i % 3]
    } else {
        S::zero()
    }
}

/// `a·b` without building a product by one.
fn times<S: Scalar>(a: S, b: S) -> S {
    if a.is_one() {
        b
    } else if b.is_one() {
        a
    } else {
        a * b
    }
}

impl<S: ModelScalar> Wing<S> {
    /// The damping of each derivative at the nominal point, ρVS/2 times the scaled derivative,
    /// must be a number the analysis can use: an overflow (or an entry beyond
    /// `eom_num::MAX_ENTRY`) is named here, by wing and derivative, rather than found later as
    /// a non-finite entry of A.
    fn check_damping_magnitude(&self, cx: &Validation<'_, S>) -> Result<(), ModelError> {
        let velocity = cx.body(&self.body).map_or(zero3(), |b| b.velocity);
        let q = (self.density * self.airspeed_with(&velocity) * self.area).nominal() * 0.5;
        for (i, row) in self.scaled_derivatives().iter().enumerate() {
            for (j, d) in row.iter().enumerate() {
                let value = q * d.nominal();
                if value.is_nan() || value.abs() > eom_num::MAX_ENTRY {
                    return Err(ModelError::DampingOverflow {
                        item: ItemRef::new("wing", &self.name),
                        derivative: WING_DERIVATIVES[i][j],
                        value: self.derivatives[i][j].nominal(),
                        damping: value,
                        limit: eom_num::MAX_ENTRY,
                    });
                }
            }
        }
        Ok(())
    }
}

impl<S: ModelScalar> Physics<S> for Wing<S> {
    fn validate(&self, cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        if let Some(n) = self.unknown.first() {
            return Err(ModelError::UnknownDerivative {
                item: ItemRef::new("wing", &self.name),
                name: n.to_string(),
                known: &WING_DERIVATIVES,
            });
        }
        let positive = [
            ("area", &self.area, "reference area"),
            ("chord", &self.chord, "reference chord"),
            ("span", &self.span, "reference span"),
            ("density", &self.density, "air density"),
        ];
        let surface = Surface {
            kind: "wing",
            item: &self.name,
            body: &self.body,
            axes: [&self.forward, &self.down],
            airspeed: self.airspeed.as_ref(),
        };
        surface.check(&positive, cx)?;
        self.check_damping_magnitude(cx)?;
        if self.derivatives.iter().flatten().all(|d| d.is_zero())
            && self.acceleration.iter().all(|d| d.is_zero())
        {
            cx.warn(Warning::NoDerivatives {
                item: ItemRef::new("wing", &self.name),
            });
        }
        Ok(())
    }

    /// The damping block at the point, on all six relative directions.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let velocity = cx
            .body(&self.body)
            .map_or(zero3(), |k| cx.bodies[k].velocity);
        let airspeed = self.airspeed_with(&velocity);
        let mut block = self.damping(airspeed);
        if self.unsteady == Unsteady::Auto {
            cx.warn(super::unsteady::auto_assembled("wing", &self.name));
        }
        let normal = (self.unsteady == Unsteady::Jones).then(|| self.normal_column(airspeed));
        if let Some((col, row)) = &normal {
            // The direct part ½ of Jones' C on the w column: the other ½ through the states.
            let lagged = S::from_f64(1.0 - JONES_DIRECT);
            for (i, c) in col.iter().enumerate() {
                for (j, r) in row.iter().enumerate() {
                    if !c.is_zero() && !r.is_zero() {
                        block[i][j] = block[i][j] - lagged * *c * *r;
                    }
                }
            }
        }
        let point = Point {
            bodies: [self.body.clone(), name(GROUND)],
            location: self.location,
            forces: 3,
            moments: 3,
            axis: zero3(),
            rolling_axis: zero3(),
        };
        let (rows, geometry) = cx.point(&point, "wing", &self.name);
        let props: Vec<Vec<S>> = block.iter().map(|r| r.to_vec()).collect();
        cx.add_rows_block(Term::Damping, &rows.rows, &props);
        if self.acceleration.iter().any(|d| !d.is_zero()) {
            let mass: Vec<Vec<S>> = self.added_mass().iter().map(|r| r.to_vec()).collect();
            cx.add_rows_block(Term::ItemMass, &rows.rows, &mass);
        }
        let air = self.air_velocity(&velocity);
        if let Some((col, row)) = &normal {
            self.lag_states(cx, &rows.rows, airspeed, col, row, &air, geometry.bodies[0]);
        }
        if let (Some(k), false) = (geometry.bodies[0], air.iter().all(|x| x.is_zero())) {
            // The stream turned by the body's rotation θ: Δ = θ × v_air = −[v_air]× θ at
            // every point; its force −L[:, u v w]·Δ is a stiffness on θ.
            let sk = skew(&air);
            for (a, row) in rows.rows.iter().enumerate() {
                for c in 0..3 {
                    let terms: Vec<S> = (0..3)
                        .zip(&sk)
                        .filter(|&(t, s)| !block[a][t].is_zero() && !s[c].is_zero())
                        .map(|(t, s)| -times(block[a][t], s[c]))
                        .collect();
                    if terms.is_empty() {
                        continue;
                    }
                    let g = S::sum(&terms);
                    for &(i, x) in row {
                        cx.add(Term::LoadStiffness, i, 6 * k + 3 + c, times(x, g));
                    }
                }
            }
        }
        Ok(())
    }
}

impl<S: ModelScalar> Wing<S> {
    /// Jones' states on the wing's normal velocity `w_n = (down, 0)·v` (and, in a given air
    /// stream, the normal velocity `θ·(v_air × down)` that a rotation θ adds):
    /// `ẋᵢ = −βᵢ xᵢ + w_n`, `βᵢ = β̄ᵢ V/(c/2)`, force `−w_L·Aᵢβᵢ xᵢ` at the point.
    #[allow(clippy::too_many_arguments)]
    fn lag_states(
        &self,
        cx: &mut Assembly<'_, S>,
        rows: &[ItemRow<S>],
        v: S,
        col: &[S; 6],
        row: &[S; 6],
        air: &Vec3<S>,
        body: Option<usize>,
    ) {
        let rate = v / (self.chord * S::from_f64(0.5));
        let turn = cross(air, &self.down);
        for (s, gain) in surface::jones_states(cx, &self.name, rate, body, &turn) {
            for (i, r) in rows.iter().enumerate() {
                for &(j, x) in r {
                    if !row[i].is_zero() {
                        cx.add_lag(LagTerm::Velocity, s, j, row[i] * x);
                    }
                    if !col[i].is_zero() {
                        cx.add_lag(LagTerm::Force, j, s, -(x * col[i] * gain));
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Model;
    use crate::error::Degeneracy;
    use crate::items::tests::Counter;

    /// A body on a slider moving at `speed` with `wing` on it.
    fn model_with(wing: Wing<f64>, speed: f64) -> Model<f64> {
        let mut m = Model::new("m");
        m.add(
            crate::Body::new("b")
                .mass(1.0)
                .moments([1.0; 3])
                .velocity([speed, 0.0, 0.0]),
        );
        m.add(
            crate::RigidPoint::new("slider")
                .between("b", "ground")
                .forces(2)
                .moments(3)
                .axis([0.0, 0.0, 1.0]),
        );
        m.add(wing);
        m
    }

    fn error(wing: Wing<f64>, speed: f64) -> ModelError {
        model_with(wing, speed).validate().expect_err("invalid")
    }

    /// The field of a [`ModelError::NotPositive`] or [`ModelError::Degenerate`] of wing `fin`.
    fn fin_field(e: &ModelError) -> Option<&str> {
        match e {
            ModelError::NotPositive { item, field, .. }
            | ModelError::Degenerate { item, field, .. }
                if item.kind == "wing" && item.name == "fin" =>
            {
                Some(field)
            }
            _ => None,
        }
    }

    #[test]
    fn bad_input_is_an_error_naming_the_wing_and_field() {
        let w = || Wing::new("fin").on("b").derivative("CZw", -2.0);
        assert!(model_with(w(), 10.0).validate().is_ok());
        let e = error(w().area(0.0), 10.0);
        assert!(
            matches!(&e, ModelError::NotPositive { quantity: "reference area", value, .. } if *value == 0.0)
                && fin_field(&e) == Some("area"),
            "{e:?}"
        );
        for (wing, field) in [(w().chord(-1.0), "chord"), (w().span(0.0), "span")] {
            let e = error(wing, 10.0);
            assert!(
                matches!(e, ModelError::NotPositive { .. }) && fin_field(&e) == Some(field),
                "{e:?}"
            );
        }
        let e = error(w().derivative("CLa", 1.0), 10.0);
        assert!(
            matches!(&e, ModelError::UnknownDerivative { name, known, .. } if name == "CLa" && known[0][0] == "CXu"),
            "{e:?}"
        );
        let e = error(w().on("nobody"), 10.0);
        assert!(
            matches!(&e, ModelError::UnknownBody { item, field, body, .. } if item.name == "fin" && field == "body" && body == "nobody"),
            "{e:?}"
        );
        let e = error(w().on("ground"), 10.0);
        assert!(
            matches!(&e, ModelError::OnGround { item } if item.kind == "wing"),
            "{e:?}"
        );
        let e = error(w(), 0.0);
        assert!(
            matches!(&e, ModelError::NoAirspeed { body, along, .. } if body == "b" && *along == 0.0),
            "{e:?}"
        );
        let e = error(w().airspeed(0.0), 10.0);
        assert!(
            matches!(
                e,
                ModelError::NotPositive {
                    quantity: "airspeed",
                    ..
                }
            ) && fin_field(&e) == Some("airspeed"),
            "{e:?}"
        );
        let e = error(w().axes([1.0, 0.0, 0.0], [0.6, 0.0, -0.8]), 10.0);
        assert!(
            matches!(&e, ModelError::Degenerate { shape: Degeneracy::NotPerpendicular { dot }, .. } if (*dot - 0.6).abs() < 1e-15)
                && fin_field(&e) == Some("down"),
            "{e:?}"
        );
        let e = error(w().axes([2.0, 0.0, 0.0], [0.0, 0.0, -1.0]), 10.0);
        assert!(
            matches!(&e, ModelError::Degenerate { shape: Degeneracy::NotUnit { length }, .. } if *length == 2.0)
                && fin_field(&e) == Some("forward"),
            "{e:?}"
        );
    }

    #[test]
    fn a_wing_without_derivatives_is_a_warning() {
        let w = model_with(Wing::new("fin").on("b"), 10.0)
            .validate()
            .unwrap();
        assert!(
            w.iter().any(|x| matches!(
                x,
                crate::Warning::NoDerivatives { item } if item.name == "fin"
            )),
            "{w:?}"
        );
    }

    /// The default axes turn AVL's (x forward, y right, z down) into the model's (x forward,
    /// y left, z up): entry (i, j) changes sign by sᵢsⱼ, s = (+, −, −, +, −, −); any other
    /// orientation is the same block turned.
    #[test]
    #[allow(clippy::needless_range_loop)] // index arithmetic reads like the formula
    fn the_block_is_the_avl_block_turned_into_model_axes() {
        let mut w = Wing::new("w")
            .on("b")
            .area(0.7)
            .chord(0.3)
            .span(2.0)
            .density(1.1);
        let c = Counter::default();
        for row in WING_DERIVATIVES {
            for n in row {
                w = w.derivative(n, c.x() - 18.0);
            }
        }
        let v = 12.0;
        let avl = eom_aero::Derivatives {
            reference: eom_aero::Reference::new(0.7, 0.3, 2.0, [0.0; 3]),
            coefficients: w.derivatives,
        }
        .dimensional(1.1, v)
        .unwrap();
        let l = w.damping(v);
        let s = [1.0, -1.0, -1.0, 1.0, -1.0, -1.0];
        for i in 0..6 {
            for j in 0..6 {
                let want = -s[i] * s[j] * avl[i][j];
                assert!(
                    (l[i][j] - want).abs() <= 1e-12 * want.abs().max(1.0),
                    "({i}, {j})"
                );
            }
        }
        // A fin mounted on its side (forward +x, down +y): rows/columns permute.
        let q = w.clone().axes([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let r = q.rotation();
        let l2 = q.damping(v);
        for i in 0..6 {
            for j in 0..6 {
                let mut want = 0.0;
                for a in 0..6 {
                    for b in 0..6 {
                        let t =
                            |x: usize, y: usize| if x / 3 == y / 3 { r[x % 3][y % 3] } else { 0.0 };
                        want -= t(a, i) * avl[a][b] * t(b, j);
                    }
                }
                assert!(
                    (l2[i][j] - want).abs() <= 1e-12 * want.abs().max(1.0),
                    "({i}, {j})"
                );
            }
        }
        assert_eq!(r[1], [0.0, 0.0, -1.0], "right = down × forward");
    }

    #[test]
    fn names_are_those_of_eom_aero() {
        assert_eq!(WING_DERIVATIVES, eom_aero::Derivatives::names());
        assert_eq!(wing_derivative_index("Cnr"), Some((5, 5)));
        assert_eq!(wing_derivative_index("CLa"), None);
    }
}
