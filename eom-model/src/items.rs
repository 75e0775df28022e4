//! The items a model is made of (eom-method §1), with builders that read like the model.
//!
//! Every numeric field is a scalar `S` — an [`Expr`](eom_sym::Expr) in a symbolic model, `f64`
//! (or [`Dd`](eom_sym::Dd)) in a numeric one — and every builder method takes anything that
//! converts into it (`Expr`, `f64`, `i32`). Vectors are `[S; 3]` in global axes (x forward,
//! y left, z up by default); build them with [`vec3`].
//!
//! Items name the bodies they connect; `"ground"` is the fixed frame and the default.

use eom_sym::scalar::Scalar;
use std::sync::Arc;

/// The name of the ground (the fixed frame). Reserved: no body may be called this.
pub const GROUND: &str = "ground";

/// A shared item or body name.
pub type Name = Arc<str>;

/// A 3-vector.
pub type Vec3<S> = [S; 3];

/// A 3-vector from three components of any convertible type.
pub fn vec3<S>(x: impl Into<S>, y: impl Into<S>, z: impl Into<S>) -> Vec3<S> {
    [x.into(), y.into(), z.into()]
}

/// The zero vector.
pub fn zero3<S: Scalar>() -> Vec3<S> {
    [S::zero(), S::zero(), S::zero()]
}

/// The global x axis.
pub fn x_axis<S: Scalar>() -> Vec3<S> {
    [S::one(), S::zero(), S::zero()]
}
/// The global y axis.
pub fn y_axis<S: Scalar>() -> Vec3<S> {
    [S::zero(), S::one(), S::zero()]
}
/// The global z axis.
pub fn z_axis<S: Scalar>() -> Vec3<S> {
    [S::zero(), S::zero(), S::one()]
}

fn name(s: &str) -> Name {
    Arc::from(s)
}

/// A rigid body: mass, inertia about its mass centre (global axes), and the nominal motion
/// about which the equations are linearized.
#[derive(Clone, Debug, PartialEq)]
pub struct Body<S> {
    /// Unique name.
    pub name: Name,
    /// Mass centre location.
    pub location: Vec3<S>,
    /// Mass (zero is allowed: a massless body).
    pub mass: S,
    /// `[Ixx, Iyy, Izz]` about the mass centre.
    pub moments: Vec3<S>,
    /// `[Ixy, Iyz, Izx]` as positive integrals (∫xy dm, …); they enter the tensor with a minus
    /// sign.
    pub products: Vec3<S>,
    /// Nominal velocity of the mass centre.
    pub velocity: Vec3<S>,
    /// Nominal angular velocity (spin).
    pub angular_velocity: Vec3<S>,
}

impl<S: Scalar> Body<S> {
    /// A body with zero mass and inertia at the origin, at rest.
    pub fn new(n: &str) -> Self {
        Body {
            name: name(n),
            location: zero3(),
            mass: S::zero(),
            moments: zero3(),
            products: zero3(),
            velocity: zero3(),
            angular_velocity: zero3(),
        }
    }
    /// Mass centre location.
    pub fn at(mut self, location: Vec3<S>) -> Self {
        self.location = location;
        self
    }
    /// Mass.
    pub fn mass(mut self, m: impl Into<S>) -> Self {
        self.mass = m.into();
        self
    }
    /// Moments of inertia `[Ixx, Iyy, Izz]`.
    pub fn moments(mut self, i: Vec3<S>) -> Self {
        self.moments = i;
        self
    }
    /// Products of inertia `[Ixy, Iyz, Izx]` (positive integrals).
    pub fn products(mut self, p: Vec3<S>) -> Self {
        self.products = p;
        self
    }
    /// Nominal velocity.
    pub fn velocity(mut self, v: Vec3<S>) -> Self {
        self.velocity = v;
        self
    }
    /// Nominal angular velocity.
    pub fn angular_velocity(mut self, w: Vec3<S>) -> Self {
        self.angular_velocity = w;
        self
    }
}

/// A constant applied force and moment. `frame` names the body whose axes the direction is
/// fixed to: the ground for a dead load (gravity), the loaded body itself for a follower load.
#[derive(Clone, Debug, PartialEq)]
pub struct Load<S> {
    /// Unique name.
    pub name: Name,
    /// Loaded body.
    pub body: Name,
    /// Point of application.
    pub location: Vec3<S>,
    /// Force (global components at the nominal configuration).
    pub force: Vec3<S>,
    /// Moment.
    pub moment: Vec3<S>,
    /// The frame that carries the load's direction.
    pub frame: Name,
}

impl<S: Scalar> Load<S> {
    /// A zero dead load on `body`.
    pub fn new(n: &str, body: &str) -> Self {
        Load {
            name: name(n),
            body: name(body),
            location: zero3(),
            force: zero3(),
            moment: zero3(),
            frame: name(GROUND),
        }
    }
    /// Weight of a body: force `m·g` along `−z` (pass a negative `g` for a z-down model),
    /// applied at its mass centre.
    pub fn weight(body: &Body<S>, g: impl Into<S>) -> Self {
        let g = g.into();
        Load {
            name: name(&format!("{} weight", body.name)),
            body: body.name.clone(),
            location: body.location,
            force: [S::zero(), S::zero(), -(body.mass * g)],
            moment: zero3(),
            frame: name(GROUND),
        }
    }
    /// Point of application.
    pub fn at(mut self, location: Vec3<S>) -> Self {
        self.location = location;
        self
    }
    /// Force.
    pub fn force(mut self, f: Vec3<S>) -> Self {
        self.force = f;
        self
    }
    /// Moment.
    pub fn moment(mut self, m: Vec3<S>) -> Self {
        self.moment = m;
        self
    }
    /// Make it a follower load whose direction is fixed in `frame` (a body name).
    pub fn frame(mut self, frame: &str) -> Self {
        self.frame = name(frame);
        self
    }
}

/// Fields shared by the two-point ("line") items: links, springs, actuators and sensors.
#[derive(Clone, Debug, PartialEq)]
pub struct Line<S> {
    /// `[body 1, body 2]`.
    pub bodies: [Name; 2],
    /// `[end 1 (on body 1), end 2 (on body 2)]`.
    pub ends: [Vec3<S>; 2],
    /// `false`: acts along the line (force, elongation); `true`: torsional about the line.
    pub twist: bool,
}

impl<S: Scalar> Line<S> {
    fn new() -> Self {
        Line {
            bodies: [name(GROUND), name(GROUND)],
            ends: [zero3(), zero3()],
            twist: false,
        }
    }
}

macro_rules! line_builders {
    ($t:ident) => {
        impl<S: Scalar> $t<S> {
            /// The two bodies (end 1 on `b1`, end 2 on `b2`).
            pub fn between(mut self, b1: &str, b2: &str) -> Self {
                self.line.bodies = [name(b1), name(b2)];
                self
            }
            /// The two end points.
            pub fn ends(mut self, p1: Vec3<S>, p2: Vec3<S>) -> Self {
                self.line.ends = [p1, p2];
                self
            }
            /// Act about the line (torsion) instead of along it.
            pub fn twist(mut self) -> Self {
                self.line.twist = true;
                self
            }
        }
    };
}

/// An inextensible rigid link.
#[derive(Clone, Debug, PartialEq)]
pub struct Link<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
}
impl<S: Scalar> Link<S> {
    /// A link between ground and ground (set bodies and ends).
    pub fn new(n: &str) -> Self {
        Link {
            name: name(n),
            line: Line::new(),
        }
    }
}
line_builders!(Link);

/// A spring–damper–inerter along (or, twisted, about) a line.
#[derive(Clone, Debug, PartialEq)]
pub struct Spring<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
    /// Stiffness (N/m, or N·m/rad twisted).
    pub stiffness: S,
    /// Damping.
    pub damping: S,
    /// Inertance (force proportional to relative acceleration).
    pub inertance: S,
    /// Known tension at the given geometry; `None` = solved from equilibrium.
    pub preload: Option<S>,
}
impl<S: Scalar> Spring<S> {
    /// A spring with zero properties.
    pub fn new(n: &str) -> Self {
        Spring {
            name: name(n),
            line: Line::new(),
            stiffness: S::zero(),
            damping: S::zero(),
            inertance: S::zero(),
            preload: None,
        }
    }
    /// Stiffness.
    pub fn stiffness(mut self, k: impl Into<S>) -> Self {
        self.stiffness = k.into();
        self
    }
    /// Damping.
    pub fn damping(mut self, c: impl Into<S>) -> Self {
        self.damping = c.into();
        self
    }
    /// Inertance.
    pub fn inertance(mut self, b: impl Into<S>) -> Self {
        self.inertance = b.into();
        self
    }
    /// Known preload (tension positive).
    pub fn preload(mut self, t: impl Into<S>) -> Self {
        self.preload = Some(t.into());
        self
    }
}
line_builders!(Spring);

/// An actuator: generalized force `gain·u + rate_gain·u̇` that extends the line (or twists about
/// it).
#[derive(Clone, Debug, PartialEq)]
pub struct Actuator<S> {
    /// Unique name (the input's name).
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
    /// Gain.
    pub gain: S,
    /// Rate gain (force per input rate), e.g. a tyre damping driven by road displacement.
    pub rate_gain: S,
    /// Unit label of the input.
    pub units: String,
}
impl<S: Scalar> Actuator<S> {
    /// An actuator with gain 1.
    pub fn new(n: &str) -> Self {
        Actuator {
            name: name(n),
            line: Line::new(),
            gain: S::one(),
            rate_gain: S::zero(),
            units: "N".into(),
        }
    }
    /// Gain.
    pub fn gain(mut self, g: impl Into<S>) -> Self {
        self.gain = g.into();
        self
    }
    /// Rate gain.
    pub fn rate_gain(mut self, g: impl Into<S>) -> Self {
        self.rate_gain = g.into();
        self
    }
    /// Unit label.
    pub fn units(mut self, u: &str) -> Self {
        self.units = u.into();
        self
    }
}
line_builders!(Actuator);

/// What a sensor measures: the elongation (or twist) of its line, or its first or second
/// derivative.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensorOrder {
    /// Displacement.
    Displacement,
    /// Velocity.
    Velocity,
    /// Acceleration.
    Acceleration,
}

/// The frame in which a sensor's velocity or acceleration is taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SensorFrame {
    /// Global (rates of the global displacement).
    Global,
    /// Body-fixed (perturbation velocities in the axes of the moving bodies; accelerations as
    /// felt by the body: `δv̇ + δω × v`).
    Local,
}

/// A sensor: output `gain × elongation` (or its rate / acceleration) of its line.
#[derive(Clone, Debug, PartialEq)]
pub struct Sensor<S> {
    /// Unique name (the output's name).
    pub name: Name,
    /// Geometry.
    pub line: Line<S>,
    /// Gain.
    pub gain: S,
    /// Displacement, velocity or acceleration.
    pub order: SensorOrder,
    /// Global or body frame.
    pub frame: SensorFrame,
    /// An actuator whose input is fed through to this output.
    pub actuator: Option<Name>,
    /// Coefficient of that feedthrough (default −1).
    pub actuator_gain: S,
    /// Unit label.
    pub units: String,
}
impl<S: Scalar> Sensor<S> {
    /// A displacement sensor with gain 1.
    pub fn new(n: &str) -> Self {
        Sensor {
            name: name(n),
            line: Line::new(),
            gain: S::one(),
            order: SensorOrder::Displacement,
            frame: SensorFrame::Global,
            actuator: None,
            actuator_gain: -S::one(),
            units: "m".into(),
        }
    }
    /// Gain.
    pub fn gain(mut self, g: impl Into<S>) -> Self {
        self.gain = g.into();
        self
    }
    /// Measure the velocity.
    pub fn velocity(mut self) -> Self {
        self.order = SensorOrder::Velocity;
        self
    }
    /// Measure the acceleration.
    pub fn acceleration(mut self) -> Self {
        self.order = SensorOrder::Acceleration;
        self
    }
    /// Take rates in the body frame.
    pub fn local(mut self) -> Self {
        self.frame = SensorFrame::Local;
        self
    }
    /// Feed the input of `actuator` through with coefficient `gain`.
    pub fn feedthrough(mut self, actuator: &str, gain: impl Into<S>) -> Self {
        self.actuator = Some(name(actuator));
        self.actuator_gain = gain.into();
        self
    }
    /// Unit label.
    pub fn units(mut self, u: &str) -> Self {
        self.units = u.into();
        self
    }
}
line_builders!(Sensor);

/// An Euler–Bernoulli beam between two bodies (bending in two planes, no torsion or axial
/// stiffness).
#[derive(Clone, Debug, PartialEq)]
pub struct Beam<S> {
    /// Unique name.
    pub name: Name,
    /// `[body 1, body 2]`.
    pub bodies: [Name; 2],
    /// End points.
    pub ends: [Vec3<S>; 2],
    /// Bending stiffness `[EI₁, EI₂]` towards the two bending directions.
    pub stiffness: [S; 2],
    /// Mass per unit length.
    pub mpul: S,
    /// A vector that with the axis defines bending plane 1 (not parallel to the axis).
    pub perp: Vec3<S>,
}
impl<S: Scalar> Beam<S> {
    /// A beam with zero properties.
    pub fn new(n: &str) -> Self {
        Beam {
            name: name(n),
            bodies: [name(GROUND), name(GROUND)],
            ends: [zero3(), zero3()],
            stiffness: [S::zero(), S::zero()],
            mpul: S::zero(),
            perp: zero3(),
        }
    }
    /// The two bodies.
    pub fn between(mut self, b1: &str, b2: &str) -> Self {
        self.bodies = [name(b1), name(b2)];
        self
    }
    /// End points.
    pub fn ends(mut self, p1: Vec3<S>, p2: Vec3<S>) -> Self {
        self.ends = [p1, p2];
        self
    }
    /// Bending stiffnesses.
    pub fn stiffness(mut self, ei1: impl Into<S>, ei2: impl Into<S>) -> Self {
        self.stiffness = [ei1.into(), ei2.into()];
        self
    }
    /// Mass per unit length.
    pub fn mpul(mut self, mu: impl Into<S>) -> Self {
        self.mpul = mu.into();
        self
    }
    /// Bending plane vector.
    pub fn perp(mut self, p: Vec3<S>) -> Self {
        self.perp = p;
        self
    }
}

/// Fields shared by the point items (rigid, flexible and nonholonomic points).
#[derive(Clone, Debug, PartialEq)]
pub struct Point<S> {
    /// `[body 1, body 2]`.
    pub bodies: [Name; 2],
    /// The point.
    pub location: Vec3<S>,
    /// Number of constrained translational directions: 3 all, 2 perpendicular to `axis`,
    /// 1 along `axis`, 0 none.
    pub forces: u8,
    /// Number of constrained rotational directions (same meaning).
    pub moments: u8,
    /// Axis for `forces`/`moments` of 1 or 2.
    pub axis: Vec3<S>,
    /// Rolling axis (nonzero: a rolling contact; body 1 rolls on body 2).
    pub rolling_axis: Vec3<S>,
}
impl<S: Scalar> Point<S> {
    fn new() -> Self {
        Point {
            bodies: [name(GROUND), name(GROUND)],
            location: zero3(),
            forces: 0,
            moments: 0,
            axis: zero3(),
            rolling_axis: zero3(),
        }
    }
}

macro_rules! point_builders {
    ($t:ident) => {
        impl<S: Scalar> $t<S> {
            /// The two bodies.
            pub fn between(mut self, b1: &str, b2: &str) -> Self {
                self.point.bodies = [name(b1), name(b2)];
                self
            }
            /// The point.
            pub fn at(mut self, location: Vec3<S>) -> Self {
                self.point.location = location;
                self
            }
            /// Number of constrained translational directions.
            pub fn forces(mut self, n: u8) -> Self {
                self.point.forces = n;
                self
            }
            /// Number of constrained rotational directions.
            pub fn moments(mut self, n: u8) -> Self {
                self.point.moments = n;
                self
            }
            /// Axis for 1- or 2-direction constraints.
            pub fn axis(mut self, a: Vec3<S>) -> Self {
                self.point.axis = a;
                self
            }
            /// Rolling axis (makes it a rolling contact).
            pub fn rolling_axis(mut self, a: Vec3<S>) -> Self {
                self.point.rolling_axis = a;
                self
            }
        }
    };
}

/// A holonomic joint.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidPoint<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub point: Point<S>,
}
impl<S: Scalar> RigidPoint<S> {
    /// A joint between ground and ground (set bodies and directions).
    pub fn new(n: &str) -> Self {
        RigidPoint {
            name: name(n),
            point: Point::new(),
        }
    }
}
point_builders!(RigidPoint);

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

/// A nonholonomic constraint on relative velocity (e.g. a no-slip tyre).
#[derive(Clone, Debug, PartialEq)]
pub struct NhPoint<S> {
    /// Unique name.
    pub name: Name,
    /// Geometry.
    pub point: Point<S>,
}
impl<S: Scalar> NhPoint<S> {
    /// A constraint between ground and ground (set bodies and directions).
    pub fn new(n: &str) -> Self {
        NhPoint {
            name: name(n),
            point: Point::new(),
        }
    }
}
point_builders!(NhPoint);
