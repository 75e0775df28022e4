//! # eom-model — the multibody model
//!
//! A [`Model`] holds parameters, bodies and the items connecting them (springs, links, joints,
//! rolling contacts, beams, loads, actuators, sensors). Every numeric field is a scalar `S`: in a
//! symbolic model (`Model<Expr>`, the default) fields are expressions over the model's
//! parameters; [`Model::evaluate`] turns it into a numeric `Model<f64>` at given parameter values,
//! and [`Model::map`] into any other scalar (e.g. double-double).
//!
//! The data flow is one algorithm written once for every scalar type:
//!
//! 1. [`assemble`]: mass, stiffness (with the tangent stiffness of the static preloads), damping
//!    (with the gyroscopic and momentum terms), the holonomic and nonholonomic constraint
//!    Jacobians, inputs and outputs;
//! 2. [`reduce`]: structure-first symbolic-numeric elimination of the constraints, with pivots
//!    chosen at the nominal point and recorded as validity checks; or [`reduce_robust`], the
//!    orthonormal-complement reduction that is the independent numeric reference;
//! 3. [`Linearizer`] reaches all of them in one call; [`compiled`] evaluates a symbolic state
//!    space quickly at many points.
//!
//! The method and where eom deliberately differs from the EoM software are described in
//! `docs/method.md` of the repository.
//!
//! ```
//! use eom_model::*;
//!
//! // A swivel wheel (Schwab & Meijaard's shimmy): a body pulled at speed u, a lateral spring
//! // ahead of its mass centre, a tyre that cannot slip sideways behind it.
//! let mut m = Model::new("shimmy");
//! let mass = m.param("m", 5.0).unwrap();
//! let iz = m.param("I", 1.05).unwrap();
//! let k = m.param("k", 1.5).unwrap();
//! let a = m.param("a", 0.5).unwrap();
//! let b = m.param("b", 0.5).unwrap();
//! let u = m.param("u", 10.0).unwrap();
//! m.add(Body::new("chassis").mass(mass).moments(vec3(0, 0, iz)).velocity(vec3(u, 0, 0)));
//! m.add(FlexPoint::new("spring").between("chassis", "ground").at(vec3(b, 0, 0)).forces(1).axis(y_axis()).stiffness(k, 0));
//! m.add(NhPoint::new("tyre").between("chassis", "ground").at(vec3(-a, 0, 0)).forces(1).axis(y_axis()));
//! m.add(RigidPoint::new("road").between("chassis", "ground").forces(1).moments(2).axis(z_axis()));
//! m.add(RigidPoint::new("speed").between("chassis", "ground").forces(1).axis(x_axis()));
//!
//! // Symbolic: the state matrix as expressions (3 states: y, ψ and the yaw rate — the four
//! // pinned coordinates were removed before any algebra).
//! let sym = Linearizer::new(&m).symbolic().unwrap();
//! let ss = sym.state_space();
//! assert_eq!(ss.a.nrows(), 3);
//! assert_eq!(ss.a[(2, 2)], -(mass * a * u) / (iz + mass * a * a));
//!
//! // Numeric: evaluated at other parameter values.
//! let at = m.scope.values_with(&[("u", 1.0)]).unwrap();
//! let num = sym.evaluate(&at).unwrap();
//! let eig = eom_num::modes::eigenvalues(&num.a).unwrap();
//! // The characteristic polynomial (I + m a²)s³ + m a u s² + k l² s + k l u has the root
//! // −1.0548225773209977 at these values (Schwab & Meijaard 2003; docs/references.md).
//! assert!((eig[0].re + 1.0548225773209977).abs() < 1e-12);
//! ```

#![warn(missing_docs)]

pub mod assemble;
pub mod eliminate;
pub mod error;
pub mod file;
pub mod geometry;
pub mod items;
pub mod linearize;
pub mod reduce;
pub mod robust;
pub mod sensitivity;

pub use assemble::{Assembled, RowLabel, assemble};
pub use error::ModelError;
pub use items::*;
pub use linearize::{Linearization, Linearizer, Method};
pub use reduce::{
    CheckLabel, CompiledStateSpace, Coord, EvalWorkspace, MatrixSize, NATIVE_AFTER, Reduction,
    ReductionPlan, ReductionReport, SymbolicStateSpace, ValidityCheck, reduce,
};
pub use robust::{ConstrainedDescriptor, RobustReport, constrained_descriptor, reduce_robust};
pub use sensitivity::{Sensitivities, sensitivities};

use eom_sym::ExprPool;
use eom_sym::expr::Expr;
use eom_sym::pool::ParamInfo;
use eom_sym::scalar::Scalar;
use eom_sym::scope::Scope;
use eom_sym::tape::Tape;
use hashbrown::HashSet;

/// Any item, for [`Model::add`].
#[derive(Clone, Debug, PartialEq)]
#[allow(missing_docs)]
pub enum Item<S> {
    Body(Body<S>),
    Load(Load<S>),
    Link(Link<S>),
    Spring(Spring<S>),
    Beam(Beam<S>),
    RigidPoint(RigidPoint<S>),
    FlexPoint(FlexPoint<S>),
    NhPoint(NhPoint<S>),
    Actuator(Actuator<S>),
    Sensor(Sensor<S>),
}

macro_rules! item_from {
    ($($t:ident),*) => {$(
        impl<S> From<$t<S>> for Item<S> {
            fn from(x: $t<S>) -> Item<S> {
                Item::$t(x)
            }
        }
    )*};
}
item_from!(
    Body, Load, Link, Spring, Beam, RigidPoint, FlexPoint, NhPoint, Actuator, Sensor
);

/// A multibody model: parameters, bodies and items.
#[derive(Clone, Debug)]
pub struct Model<S = Expr> {
    /// Name of the model.
    pub name: String,
    /// Parameters (symbolic models).
    pub scope: Scope,
    /// Bodies (the ground is implicit).
    pub bodies: Vec<Body<S>>,
    /// Applied loads.
    pub loads: Vec<Load<S>>,
    /// Rigid links.
    pub links: Vec<Link<S>>,
    /// Springs.
    pub springs: Vec<Spring<S>>,
    /// Beams.
    pub beams: Vec<Beam<S>>,
    /// Holonomic joints.
    pub rigid_points: Vec<RigidPoint<S>>,
    /// Bushings.
    pub flex_points: Vec<FlexPoint<S>>,
    /// Nonholonomic constraints.
    pub nh_points: Vec<NhPoint<S>>,
    /// Inputs.
    pub actuators: Vec<Actuator<S>>,
    /// Outputs.
    pub sensors: Vec<Sensor<S>>,
}

impl<S: Scalar> Model<S> {
    /// An empty model. A symbolic model gets a new expression pool of its own, made current on
    /// this thread (so that the expressions built for it land there), and freed when the model
    /// and everything built from it are dropped.
    pub fn new(name: &str) -> Self {
        let scope = if S::SYMBOLIC {
            let pool = ExprPool::new();
            pool.make_current();
            Scope::in_pool(pool)
        } else {
            Scope::new()
        };
        Model {
            name: name.to_string(),
            scope,
            bodies: Vec::new(),
            loads: Vec::new(),
            links: Vec::new(),
            springs: Vec::new(),
            beams: Vec::new(),
            rigid_points: Vec::new(),
            flex_points: Vec::new(),
            nh_points: Vec::new(),
            actuators: Vec::new(),
            sensors: Vec::new(),
        }
    }

    /// Add an item (validated later, by [`Model::validate`] or the assembly).
    pub fn add(&mut self, item: impl Into<Item<S>>) -> &mut Self {
        match item.into() {
            Item::Body(x) => self.bodies.push(x),
            Item::Load(x) => self.loads.push(x),
            Item::Link(x) => self.links.push(x),
            Item::Spring(x) => self.springs.push(x),
            Item::Beam(x) => self.beams.push(x),
            Item::RigidPoint(x) => self.rigid_points.push(x),
            Item::FlexPoint(x) => self.flex_points.push(x),
            Item::NhPoint(x) => self.nh_points.push(x),
            Item::Actuator(x) => self.actuators.push(x),
            Item::Sensor(x) => self.sensors.push(x),
        }
        self
    }

    /// The body called `name`.
    pub fn body(&self, name: &str) -> Option<&Body<S>> {
        self.bodies.iter().find(|b| &*b.name == name)
    }

    /// Index of a body by name (`None` for the ground).
    pub(crate) fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| &*b.name == name)
    }

    /// Visit every field in the order of [`Model::map`], without building anything.
    pub fn for_each_field(&self, f: &mut dyn FnMut(&S)) {
        let v3 = |a: &Vec3<S>, f: &mut dyn FnMut(&S)| {
            for x in a {
                f(x)
            }
        };
        let line = |l: &Line<S>, f: &mut dyn FnMut(&S)| {
            v3(&l.ends[0], f);
            v3(&l.ends[1], f);
        };
        let point = |p: &Point<S>, f: &mut dyn FnMut(&S)| {
            v3(&p.location, f);
            v3(&p.axis, f);
            v3(&p.rolling_axis, f);
        };
        for b in &self.bodies {
            v3(&b.location, f);
            f(&b.mass);
            v3(&b.moments, f);
            v3(&b.products, f);
            v3(&b.velocity, f);
            v3(&b.angular_velocity, f);
        }
        for l in &self.loads {
            v3(&l.location, f);
            v3(&l.force, f);
            v3(&l.moment, f);
        }
        for l in &self.links {
            line(&l.line, f);
        }
        for s in &self.springs {
            line(&s.line, f);
            f(&s.stiffness);
            f(&s.damping);
            f(&s.inertance);
            if let Some(p) = &s.preload {
                f(p);
            }
        }
        for b in &self.beams {
            v3(&b.ends[0], f);
            v3(&b.ends[1], f);
            f(&b.stiffness[0]);
            f(&b.stiffness[1]);
            f(&b.mpul);
            v3(&b.perp, f);
        }
        for r in &self.rigid_points {
            point(&r.point, f);
        }
        for r in &self.flex_points {
            point(&r.point, f);
            f(&r.stiffness[0]);
            f(&r.stiffness[1]);
            f(&r.damping[0]);
            f(&r.damping[1]);
            for m in [&r.stiffness_matrix, &r.damping_matrix]
                .into_iter()
                .flatten()
            {
                for x in m.iter().flatten() {
                    f(x);
                }
            }
        }
        for r in &self.nh_points {
            point(&r.point, f);
        }
        for a in &self.actuators {
            line(&a.line, f);
            f(&a.gain);
            f(&a.rate_gain);
        }
        for s in &self.sensors {
            line(&s.line, f);
            f(&s.gain);
            f(&s.actuator_gain);
        }
    }

    /// Convert every field with `f`, visiting fields in a fixed order.
    pub fn map<T: Scalar>(&self, f: &mut dyn FnMut(&S) -> T) -> Model<T> {
        let v = |a: &Vec3<S>, f: &mut dyn FnMut(&S) -> T| [f(&a[0]), f(&a[1]), f(&a[2])];
        let line = |l: &Line<S>, f: &mut dyn FnMut(&S) -> T| Line {
            bodies: l.bodies.clone(),
            ends: [v(&l.ends[0], f), v(&l.ends[1], f)],
            twist: l.twist,
        };
        let point = |p: &Point<S>, f: &mut dyn FnMut(&S) -> T| Point {
            bodies: p.bodies.clone(),
            location: v(&p.location, f),
            forces: p.forces,
            moments: p.moments,
            axis: v(&p.axis, f),
            rolling_axis: v(&p.rolling_axis, f),
        };
        let mat = |m: &Option<Vec<Vec<S>>>, f: &mut dyn FnMut(&S) -> T| {
            m.as_ref()
                .map(|m| m.iter().map(|r| r.iter().map(&mut *f).collect()).collect())
        };
        Model {
            name: self.name.clone(),
            scope: self.scope.clone(),
            bodies: self
                .bodies
                .iter()
                .map(|b| Body {
                    name: b.name.clone(),
                    location: v(&b.location, f),
                    mass: f(&b.mass),
                    moments: v(&b.moments, f),
                    products: v(&b.products, f),
                    velocity: v(&b.velocity, f),
                    angular_velocity: v(&b.angular_velocity, f),
                })
                .collect(),
            loads: self
                .loads
                .iter()
                .map(|l| Load {
                    name: l.name.clone(),
                    body: l.body.clone(),
                    location: v(&l.location, f),
                    force: v(&l.force, f),
                    moment: v(&l.moment, f),
                    frame: l.frame.clone(),
                })
                .collect(),
            links: self
                .links
                .iter()
                .map(|l| Link {
                    name: l.name.clone(),
                    line: line(&l.line, f),
                })
                .collect(),
            springs: self
                .springs
                .iter()
                .map(|s| Spring {
                    name: s.name.clone(),
                    line: line(&s.line, f),
                    stiffness: f(&s.stiffness),
                    damping: f(&s.damping),
                    inertance: f(&s.inertance),
                    preload: s.preload.as_ref().map(&mut *f),
                })
                .collect(),
            beams: self
                .beams
                .iter()
                .map(|b| Beam {
                    name: b.name.clone(),
                    bodies: b.bodies.clone(),
                    ends: [v(&b.ends[0], f), v(&b.ends[1], f)],
                    stiffness: [f(&b.stiffness[0]), f(&b.stiffness[1])],
                    mpul: f(&b.mpul),
                    perp: v(&b.perp, f),
                })
                .collect(),
            rigid_points: self
                .rigid_points
                .iter()
                .map(|r| RigidPoint {
                    name: r.name.clone(),
                    point: point(&r.point, f),
                })
                .collect(),
            flex_points: self
                .flex_points
                .iter()
                .map(|r| FlexPoint {
                    name: r.name.clone(),
                    point: point(&r.point, f),
                    stiffness: [f(&r.stiffness[0]), f(&r.stiffness[1])],
                    damping: [f(&r.damping[0]), f(&r.damping[1])],
                    stiffness_matrix: mat(&r.stiffness_matrix, f),
                    damping_matrix: mat(&r.damping_matrix, f),
                })
                .collect(),
            nh_points: self
                .nh_points
                .iter()
                .map(|r| NhPoint {
                    name: r.name.clone(),
                    point: point(&r.point, f),
                })
                .collect(),
            actuators: self
                .actuators
                .iter()
                .map(|a| Actuator {
                    name: a.name.clone(),
                    line: line(&a.line, f),
                    gain: f(&a.gain),
                    rate_gain: f(&a.rate_gain),
                    units: a.units.clone(),
                })
                .collect(),
            sensors: self
                .sensors
                .iter()
                .map(|s| Sensor {
                    name: s.name.clone(),
                    line: line(&s.line, f),
                    gain: f(&s.gain),
                    order: s.order,
                    frame: s.frame,
                    actuator: s.actuator.clone(),
                    actuator_gain: f(&s.actuator_gain),
                    units: s.units.clone(),
                })
                .collect(),
        }
    }

    /// Every field with its item and field name, in the order [`Model::map`] visits them.
    pub fn fields(&self) -> Vec<(String, S)> {
        // Map into a model that records the visit order, then label from the structure.
        let mut vals = Vec::new();
        self.for_each_field(&mut |x: &S| vals.push(*x));
        let labels = self.field_labels();
        debug_assert_eq!(labels.len(), vals.len());
        labels.into_iter().zip(vals).collect()
    }

    fn field_labels(&self) -> Vec<String> {
        let mut l = Vec::new();
        let v = |l: &mut Vec<String>, item: &str, f: &str| {
            for c in ["x", "y", "z"] {
                l.push(format!("{item}.{f}[{c}]"));
            }
        };
        for b in &self.bodies {
            let n = format!("body `{}`", b.name);
            v(&mut l, &n, "location");
            l.push(format!("{n}.mass"));
            v(&mut l, &n, "moments");
            v(&mut l, &n, "products");
            v(&mut l, &n, "velocity");
            v(&mut l, &n, "angular_velocity");
        }
        for x in &self.loads {
            let n = format!("load `{}`", x.name);
            v(&mut l, &n, "location");
            v(&mut l, &n, "force");
            v(&mut l, &n, "moment");
        }
        let line = |l: &mut Vec<String>, n: &str| {
            v(l, n, "ends[1]");
            v(l, n, "ends[2]");
        };
        for x in &self.links {
            line(&mut l, &format!("link `{}`", x.name));
        }
        for x in &self.springs {
            let n = format!("spring `{}`", x.name);
            line(&mut l, &n);
            for f in ["stiffness", "damping", "inertance"] {
                l.push(format!("{n}.{f}"));
            }
            if x.preload.is_some() {
                l.push(format!("{n}.preload"));
            }
        }
        for x in &self.beams {
            let n = format!("beam `{}`", x.name);
            v(&mut l, &n, "ends[1]");
            v(&mut l, &n, "ends[2]");
            l.push(format!("{n}.stiffness[1]"));
            l.push(format!("{n}.stiffness[2]"));
            l.push(format!("{n}.mpul"));
            v(&mut l, &n, "perp");
        }
        let point = |l: &mut Vec<String>, n: &str| {
            v(l, n, "location");
            v(l, n, "axis");
            v(l, n, "rolling_axis");
        };
        for x in &self.rigid_points {
            point(&mut l, &format!("rigid point `{}`", x.name));
        }
        for x in &self.flex_points {
            let n = format!("flex point `{}`", x.name);
            point(&mut l, &n);
            l.push(format!("{n}.stiffness[1]"));
            l.push(format!("{n}.stiffness[2]"));
            l.push(format!("{n}.damping[1]"));
            l.push(format!("{n}.damping[2]"));
            for (m, f) in [
                (&x.stiffness_matrix, "stiffness_matrix"),
                (&x.damping_matrix, "damping_matrix"),
            ] {
                if let Some(m) = m {
                    for (i, r) in m.iter().enumerate() {
                        for j in 0..r.len() {
                            l.push(format!("{n}.{f}[{}][{}]", i + 1, j + 1));
                        }
                    }
                }
            }
        }
        for x in &self.nh_points {
            point(&mut l, &format!("nh point `{}`", x.name));
        }
        for x in &self.actuators {
            let n = format!("actuator `{}`", x.name);
            line(&mut l, &n);
            l.push(format!("{n}.gain"));
            l.push(format!("{n}.rate_gain"));
        }
        for x in &self.sensors {
            let n = format!("sensor `{}`", x.name);
            line(&mut l, &n);
            l.push(format!("{n}.gain"));
            l.push(format!("{n}.actuator_gain"));
        }
        l
    }

    /// Check names, references, geometry and values. Errors name the item and field.
    /// Warnings (physically dubious but computable input) are returned.
    pub fn validate(&self) -> Result<Vec<String>, ModelError> {
        let mut warnings = Vec::new();
        let err = |item: String, field: &str, problem: String| ModelError::Model {
            item,
            field: field.to_string(),
            problem,
        };
        // Values (labels are built only to report a bad one).
        let mut bad = None;
        let mut k = 0;
        self.for_each_field(&mut |x: &S| {
            if bad.is_none() && !x.nominal().is_finite() {
                bad = Some((k, x.nominal()));
            }
            k += 1;
        });
        if let Some((k, v)) = bad {
            let label = &self.field_labels()[k];
            let (item, field) = label.split_once('.').unwrap_or((label, ""));
            return Err(err(
                item.to_string(),
                field,
                format!("value {v} is not finite"),
            ));
        }
        // Names.
        // Borrowed names, sized up front: no reference counting, no rehashing.
        let mut bodies: HashSet<&str> = HashSet::with_capacity(self.bodies.len());
        for b in &self.bodies {
            if b.name.is_empty() {
                return Err(err("body ``".into(), "name", "a body needs a name".into()));
            }
            if &*b.name == GROUND {
                return Err(err(
                    format!("body `{}`", b.name),
                    "name",
                    "`ground` is reserved for the fixed frame".into(),
                ));
            }
            if !bodies.insert(&b.name) {
                return Err(err(
                    format!("body `{}`", b.name),
                    "name",
                    "duplicate body name".into(),
                ));
            }
            if b.mass.nominal() < 0.0 {
                return Err(err(
                    format!("body `{}`", b.name),
                    "mass",
                    format!("negative mass {}", b.mass.nominal()),
                ));
            }
            let i: Vec<f64> = b.moments.iter().map(|x| x.nominal()).collect();
            let triangle = i[0] + i[1] < i[2] || i[1] + i[2] < i[0] || i[0] + i[2] < i[1];
            if i.iter().any(|&x| x < 0.0) || (i.iter().all(|&x| x > 0.0) && triangle) {
                warnings.push(format!(
                    "body `{}`: moments of inertia {i:?} are not those of a physical body (negative, or violating the triangle inequality)",
                    b.name
                ));
            }
        }
        let mut items: HashSet<&str> = HashSet::with_capacity(
            self.loads.len()
                + self.links.len()
                + self.springs.len()
                + self.beams.len()
                + self.rigid_points.len()
                + self.flex_points.len()
                + self.nh_points.len()
                + self.actuators.len()
                + self.sensors.len(),
        );
        let all_names = self
            .loads
            .iter()
            .map(|x| ("load", &x.name))
            .chain(self.links.iter().map(|x| ("link", &x.name)))
            .chain(self.springs.iter().map(|x| ("spring", &x.name)))
            .chain(self.beams.iter().map(|x| ("beam", &x.name)))
            .chain(self.rigid_points.iter().map(|x| ("rigid point", &x.name)))
            .chain(self.flex_points.iter().map(|x| ("flex point", &x.name)))
            .chain(self.nh_points.iter().map(|x| ("nh point", &x.name)))
            .chain(self.actuators.iter().map(|x| ("actuator", &x.name)))
            .chain(self.sensors.iter().map(|x| ("sensor", &x.name)));
        for (kind, n) in all_names {
            if n.is_empty() {
                return Err(err(
                    format!("{kind} ``"),
                    "name",
                    "an item needs a name".into(),
                ));
            }
            if !items.insert(n) {
                return Err(err(
                    format!("{kind} `{n}`"),
                    "name",
                    "duplicate item name".into(),
                ));
            }
        }
        let known = |b: &str| b == GROUND || bodies.contains(b);
        let body_list = || {
            let mut v: Vec<String> = self.bodies.iter().map(|b| b.name.to_string()).collect();
            v.push(GROUND.into());
            v.join(", ")
        };
        let check_bodies = |kind: &str, n: &str, bs: &[Name]| -> Result<(), ModelError> {
            for (k, b) in bs.iter().enumerate() {
                if !known(b) {
                    return Err(err(
                        format!("{kind} `{n}`"),
                        if bs.len() == 1 {
                            "body"
                        } else if k == 0 {
                            "body[1]"
                        } else {
                            "body[2]"
                        },
                        format!("unknown body `{b}`; bodies are: {}", body_list()),
                    ));
                }
            }
            if bs.len() == 2 && bs[0] == bs[1] {
                return Err(err(
                    format!("{kind} `{n}`"),
                    "bodies",
                    format!("connects `{}` to itself", bs[0]),
                ));
            }
            Ok(())
        };
        for l in &self.loads {
            check_bodies("load", &l.name, std::slice::from_ref(&l.body))?;
            if !known(&l.frame) {
                return Err(err(
                    format!("load `{}`", l.name),
                    "frame",
                    format!("unknown body `{}`; bodies are: {}", l.frame, body_list()),
                ));
            }
        }
        let lines = self
            .links
            .iter()
            .map(|x| ("link", &x.name, &x.line))
            .chain(self.springs.iter().map(|x| ("spring", &x.name, &x.line)))
            .chain(
                self.actuators
                    .iter()
                    .map(|x| ("actuator", &x.name, &x.line)),
            )
            .chain(self.sensors.iter().map(|x| ("sensor", &x.name, &x.line)));
        for (kind, n, line) in lines {
            check_bodies(kind, n, &line.bodies)?;
            let t = geometry::sub(&line.ends[1], &line.ends[0]);
            let len2: f64 = t.iter().map(|x| x.nominal() * x.nominal()).sum();
            if len2 == 0.0 {
                return Err(err(
                    format!("{kind} `{n}`"),
                    "ends",
                    "the two ends coincide: zero length (the direction is undefined)".into(),
                ));
            }
        }
        for b in &self.beams {
            check_bodies("beam", &b.name, &b.bodies)?;
            let t = geometry::sub(&b.ends[1], &b.ends[0]);
            let tn: Vec<f64> = t.iter().map(|x| x.nominal()).collect();
            if tn.iter().all(|&x| x == 0.0) {
                return Err(err(
                    format!("beam `{}`", b.name),
                    "ends",
                    "the two ends coincide: zero length".into(),
                ));
            }
            let p: Vec<f64> = b.perp.iter().map(|x| x.nominal()).collect();
            let c = [
                tn[1] * p[2] - tn[2] * p[1],
                tn[2] * p[0] - tn[0] * p[2],
                tn[0] * p[1] - tn[1] * p[0],
            ];
            if c.iter().map(|x| x * x).sum::<f64>()
                <= 1e-24
                    * tn.iter().map(|x| x * x).sum::<f64>()
                    * p.iter().map(|x| x * x).sum::<f64>().max(1e-300)
            {
                return Err(err(
                    format!("beam `{}`", b.name),
                    "perp",
                    "zero or parallel to the beam axis".into(),
                ));
            }
        }
        let points = self
            .rigid_points
            .iter()
            .map(|x| ("rigid point", &x.name, &x.point))
            .chain(
                self.flex_points
                    .iter()
                    .map(|x| ("flex point", &x.name, &x.point)),
            )
            .chain(
                self.nh_points
                    .iter()
                    .map(|x| ("nh point", &x.name, &x.point)),
            );
        for (kind, n, p) in points {
            check_bodies(kind, n, &p.bodies)?;
            for (f, v) in [("forces", p.forces), ("moments", p.moments)] {
                if v > 3 {
                    return Err(err(
                        format!("{kind} `{n}`"),
                        f,
                        format!("{v} is out of range 0..=3"),
                    ));
                }
            }
            let axis_zero = p.axis.iter().all(|x| x.nominal() == 0.0);
            if axis_zero && (matches!(p.forces, 1 | 2) || matches!(p.moments, 1 | 2)) {
                return Err(err(
                    format!("{kind} `{n}`"),
                    "axis",
                    format!(
                        "is zero, but forces = {} / moments = {} need a direction",
                        p.forces, p.moments
                    ),
                ));
            }
            if p.forces + p.moments == 0 {
                warnings.push(format!(
                    "{kind} `{n}` constrains nothing (forces = moments = 0)"
                ));
            }
        }
        for f in &self.flex_points {
            let n = (f.point.forces + f.point.moments) as usize;
            for (m, field) in [
                (&f.stiffness_matrix, "stiffness_matrix"),
                (&f.damping_matrix, "damping_matrix"),
            ] {
                if let Some(m) = m
                    && (m.len() != n || m.iter().any(|r| r.len() != n))
                {
                    return Err(err(
                        format!("flex point `{}`", f.name),
                        field,
                        format!("must be {n}×{n} (forces + moments)"),
                    ));
                }
            }
        }
        for s in &self.sensors {
            if let Some(a) = &s.actuator
                && !self.actuators.iter().any(|x| &x.name == a)
            {
                let names: Vec<&str> = self.actuators.iter().map(|x| &*x.name).collect();
                return Err(err(
                    format!("sensor `{}`", s.name),
                    "actuator",
                    format!(
                        "unknown actuator `{a}`; actuators are: {}",
                        names.join(", ")
                    ),
                ));
            }
        }
        // Bodies that nothing constrains or supports.
        let mut supported: HashSet<&str> = HashSet::new();
        for l in self
            .links
            .iter()
            .map(|x| &x.line)
            .chain(self.springs.iter().map(|x| &x.line))
        {
            supported.extend(l.bodies.iter().map(|b| &**b));
        }
        for b in &self.beams {
            supported.extend(b.bodies.iter().map(|b| &**b));
        }
        for p in self
            .rigid_points
            .iter()
            .map(|x| &x.point)
            .chain(self.flex_points.iter().map(|x| &x.point))
            .chain(self.nh_points.iter().map(|x| &x.point))
        {
            if p.forces + p.moments > 0 {
                supported.extend(p.bodies.iter().map(|b| &**b));
            }
        }
        for b in &self.bodies {
            if !supported.contains(&*b.name) {
                return Err(err(
                    format!("body `{}`", b.name),
                    "",
                    "nothing constrains or supports it (no joint, spring, link or beam attaches to it)".into(),
                ));
            }
        }
        if self.bodies.is_empty() {
            return Err(err(
                format!("model `{}`", self.name),
                "bodies",
                "the model has no bodies".into(),
            ));
        }
        Ok(warnings)
    }
}

impl Model<Expr> {
    /// The model's expression pool.
    pub fn pool(&self) -> ExprPool {
        self.scope.pool().cloned().unwrap_or_else(ExprPool::current)
    }

    /// Runs `f` with the model's pool current (new constants and parameters go there).
    pub fn in_pool<R>(&self, f: impl FnOnce() -> R) -> R {
        match self.scope.pool() {
            Some(p) => p.enter(f),
            None => f(),
        }
    }

    /// Declare a parameter of the model.
    pub fn param(&mut self, name: &str, nominal: f64) -> Result<Expr, ModelError> {
        Ok(self.scope.declare(name, nominal)?)
    }

    /// Declare a parameter with full metadata.
    pub fn param_info(&mut self, info: ParamInfo) -> Result<Expr, ModelError> {
        Ok(self.scope.declare_info(info)?)
    }

    /// The numeric model at the given parameter values (in the order of `scope.params()`).
    pub fn evaluate(&self, values: &[f64]) -> Result<Model<f64>, ModelError> {
        let fields: Vec<Expr> = self.fields().into_iter().map(|(_, e)| e).collect();
        let labels: Vec<String> = self.fields().into_iter().map(|(l, _)| l).collect();
        for (e, l) in fields.iter().zip(&labels) {
            e.check().map_err(|x| ModelError::Model {
                item: l.split_once('.').map_or(l.clone(), |s| s.0.to_string()),
                field: l.split_once('.').map_or(String::new(), |s| s.1.to_string()),
                problem: x.to_string(),
            })?;
        }
        let tape = Tape::new(&fields, &self.scope.params())?;
        let mut vals = vec![0.0; fields.len()];
        let mut work = vec![0.0; tape.work_len()];
        tape.eval_into(values, &mut vals, &mut work)?;
        if let Some(k) = vals.iter().position(|v| !v.is_finite()) {
            let l = &labels[k];
            return Err(ModelError::Model {
                item: l.split_once('.').map_or(l.clone(), |s| s.0.to_string()),
                field: l.split_once('.').map_or(String::new(), |s| s.1.to_string()),
                problem: format!("evaluates to {} at the given parameter values", vals[k]),
            });
        }
        let mut k = 0;
        Ok(self.map(&mut |_| {
            k += 1;
            vals[k - 1]
        }))
    }

    /// The numeric model at the nominal parameter values.
    pub fn nominal(&self) -> Result<Model<f64>, ModelError> {
        self.evaluate(&self.scope.nominal_values())
    }
}
