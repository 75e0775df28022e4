//! What a lifting surface (a [`Wing`](super::Wing) or [`Strip`](super::Strip)) shares: its
//! fields (`surface_fields!`), the checks of its axes, positive quantities and airspeed, its
//! air velocity and Jones' lag states.

use super::unsteady::JONES;
use super::{GROUND, ModelScalar, Name, Validation, Vec3, zero3};
use crate::assemble::{Assembly, LagTerm};
use crate::error::{Degeneracy, ItemRef, ModelError};
use crate::geometry::dot;
use eom_sym::scalar::Scalar;

/// What the shared checks read of a lifting surface.
pub(crate) struct Surface<'a, S> {
    /// `wing` or `strip`.
    pub kind: &'static str,
    /// The item's name.
    pub item: &'a str,
    /// The body it is on.
    pub body: &'a Name,
    /// Its forward and down axes.
    pub axes: [&'a Vec3<S>; 2],
    /// The given airspeed.
    pub airspeed: Option<&'a S>,
}

impl<S: ModelScalar> Surface<'_, S> {
    /// On a body, not the ground; the quantities `positive` (field, value, what) positive;
    /// the axes orthonormal; the airspeed positive, given or not.
    pub(crate) fn check(
        &self,
        positive: &[(&str, &S, &'static str)],
        cx: &Validation<'_, S>,
    ) -> Result<(), ModelError> {
        let (kind, item) = (self.kind, self.item);
        if &**self.body == GROUND {
            return Err(ModelError::OnGround {
                item: ItemRef::new(kind, item),
            });
        }
        for (field, x, what) in positive {
            check_positive(kind, item, field, *x, what)?;
        }
        check_axes(kind, item, self.axes[0], self.axes[1])?;
        let velocity = cx.body(self.body).map_or(zero3(), |b| b.velocity);
        let along = airspeed_with(self.airspeed.copied(), self.axes[0], &velocity);
        check_airspeed(kind, item, self.airspeed, self.body, along)
    }
}

/// Relative tolerance of the orthonormality of the axes at the nominal point.
const AXES_TOLERANCE: f64 = 1e-9;

/// The airspeed used: the given one, else the component of `velocity` (the body's nominal
/// velocity) along the forward axis.
pub(crate) fn airspeed_with<S: Scalar>(
    airspeed: Option<S>,
    forward: &Vec3<S>,
    velocity: &Vec3<S>,
) -> S {
    airspeed.unwrap_or_else(|| dot(forward, velocity))
}

/// The nominal velocity of the air for a body moving at `velocity`: zero (still air) without
/// a given airspeed, else `velocity − V·forward` (a zero product left out, so that symbolic
/// entries keep no `x − 0` or `V·1`).
pub(crate) fn air_velocity<S: Scalar>(
    airspeed: Option<S>,
    forward: &Vec3<S>,
    velocity: &Vec3<S>,
) -> Vec3<S> {
    match airspeed {
        None => zero3(),
        Some(v) => std::array::from_fn(|k| {
            let flow = if v.is_zero() || forward[k].is_zero() {
                S::zero()
            } else if forward[k].is_one() {
                v
            } else {
                v * forward[k]
            };
            if flow.is_zero() {
                velocity[k]
            } else {
                velocity[k] - flow
            }
        }),
    }
}

/// A positive quantity.
fn check_positive<S: Scalar>(
    kind: &'static str,
    item: &str,
    field: &str,
    x: &S,
    what: &'static str,
) -> Result<(), ModelError> {
    let v = x.nominal();
    if v > 0.0 {
        return Ok(());
    }
    Err(ModelError::NotPositive {
        item: ItemRef::new(kind, item),
        field: field.into(),
        quantity: what,
        value: v,
    })
}

/// Forward and down are unit vectors, perpendicular, at the nominal point.
fn check_axes<S: Scalar>(
    kind: &'static str,
    item: &str,
    forward: &Vec3<S>,
    down: &Vec3<S>,
) -> Result<(), ModelError> {
    let n = |v: &Vec3<S>| -> [f64; 3] { [v[0].nominal(), v[1].nominal(), v[2].nominal()] };
    let (f, d) = (n(forward), n(down));
    let dotf = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (field, v) in [("forward", f), ("down", d)] {
        let len = dotf(v, v).sqrt();
        if (len - 1.0).abs() > AXES_TOLERANCE {
            return Err(ModelError::Degenerate {
                item: ItemRef::new(kind, item),
                field: field.into(),
                shape: Degeneracy::NotUnit { length: len },
            });
        }
    }
    let c = dotf(f, d);
    if c.abs() > AXES_TOLERANCE {
        return Err(ModelError::Degenerate {
            item: ItemRef::new(kind, item),
            field: "down".into(),
            shape: Degeneracy::NotPerpendicular { dot: c },
        });
    }
    Ok(())
}

/// A given airspeed is positive; without one, the nominal velocity of `body` along the
/// forward axis (`along`) must be.
fn check_airspeed<S: Scalar>(
    kind: &'static str,
    item: &str,
    airspeed: Option<&S>,
    body: &Name,
    along: S,
) -> Result<(), ModelError> {
    match airspeed {
        Some(v) => check_positive(kind, item, "airspeed", v, "airspeed"),
        None => {
            let v = along.nominal();
            // finite: the fields were checked before the items
            if v <= 0.0 {
                return Err(ModelError::NoAirspeed {
                    item: ItemRef::new(kind, item),
                    body: body.to_string(),
                    along: v,
                });
            }
            Ok(())
        }
    }
}

/// R. T. Jones' two lag states of the surface `name` ([`JONES`]), `<name>.lag1` and
/// `<name>.lag2`: `ẋᵢ = −βᵢ xᵢ + …` with `βᵢ = β̄ᵢ·rate` (rate = airspeed/semichord), plus
/// the part `turn·θ` that the body's rotation θ adds by turning a given air stream (on the
/// rotation coordinates of body `k`, `6k + 3 …`; none without a given airspeed, `body`
/// `None`). Gives each state with its gain `Aᵢβᵢ`; the kind adds its own inputs and forces.
pub(crate) fn jones_states<S: ModelScalar>(
    cx: &mut Assembly<'_, S>,
    name: &str,
    rate: S,
    body: Option<usize>,
    turn: &Vec3<S>,
) -> [(usize, S); 2] {
    std::array::from_fn(|n| {
        let (a, beta) = JONES[n];
        let s = cx.lag_state(format!("{name}.lag{}", n + 1));
        let beta = S::from_f64(beta) * rate;
        cx.add_lag(LagTerm::Rate, s, s, -beta);
        if let Some(k) = body {
            for (c, t) in turn.iter().enumerate() {
                if !t.is_zero() {
                    cx.add_lag(LagTerm::Position, s, 6 * k + 3 + c, *t);
                }
            }
        }
        (s, S::from_f64(a) * beta)
    })
}

/// The fields a lifting surface (a [`Wing`](super::Wing) or [`Strip`](super::Strip)) shares,
/// declared once: a field group of `item!` (see `declare.rs`), listed in a kind's
/// declaration as `..surface_fields!(mount),` (the body, the reference point and the axes)
/// and `..surface_fields!(air),` (the air's density and speed).
macro_rules! surface_fields {
    ((mount) [$($head:tt)*] [$($done:tt)*] [$($rest:tt)*] $($new:tt)*) => {
        $crate::items::item!(@fields [$($head)*] [$($done)*
            /// The body the surface is fixed to (its forces act relative to the ground).
            pub body: $crate::geometry::Name = $crate::geometry::name($crate::geometry::GROUND)
                => body(on, "body"),
            /// The reference point: the moment reference (a wing's derivatives', usually the
            /// quarter chord; a strip's elastic axis, the reference of its plunge and pitch).
            pub location: $crate::geometry::Vec3<S> = $crate::geometry::zero3()
                => vector(at, "at", Polar),
            /// The forward axis in model axes (a wing's AVL x; a strip's chordwise axis
            /// towards the leading edge), a unit vector.
            pub forward: $crate::geometry::Vec3<S> = [S::one(), S::zero(), S::zero()]
                => vector("forward", Polar),
            /// The down axis in model axes (a wing's AVL z; the lift acts along `−down`), a
            /// unit vector perpendicular to `forward`; the right (pitch) axis is
            /// `down × forward`.
            pub down: $crate::geometry::Vec3<S> = [S::zero(), S::zero(), -S::one()]
                => vector("down", Polar),
        ] [$($rest)*] $($new)*);
    };
    ((air) [$($head:tt)*] [$($done:tt)*] [$($rest:tt)*] $($new:tt)*) => {
        $crate::items::item!(@fields [$($head)*] [$($done)*
            /// Air density ρ.
            pub density: S = S::from_f64(1.225) => scalar(density, "density"),
            /// Airspeed (a wing's V, a strip's U); `None`: the body's nominal velocity along
            /// `forward`.
            pub airspeed: Option<S> = None => optional(airspeed, "airspeed"),
        ] [$($rest)*] $($new)*);
    };
}
pub(crate) use surface_fields;
