//! The error type of eom-model, and how its messages name an item.

use std::fmt;

use eom_num::NumError;
use eom_sym::SymError;

/// An item as errors and warnings name it: its kind (`"spring"`) and name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ItemRef {
    /// The kind, as messages name it (`"flex point"`).
    pub kind: &'static str,
    /// The item's name.
    pub name: String,
}

impl ItemRef {
    /// The item `name` of kind `kind`.
    pub fn new(kind: &'static str, name: &str) -> Self {
        ItemRef {
            kind,
            name: name.to_string(),
        }
    }
}

impl fmt::Display for ItemRef {
    /// ``spring `front` `` (the name shown with [`eom_text::shown`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&label(self.kind, &self.name))
    }
}

/// Everything that can go wrong while building, assembling or reducing a model. Messages name
/// the item, field or parameter at fault; each variant holds them, and the values at fault,
/// as data (docs/diagnostics.md lists the variants).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// The model's own name is not a valid name.
    #[error("the model, field `name`: {problem}")]
    ModelName {
        /// What is wrong with it (from [`eom_text::name_problem`]).
        problem: String,
    },
    /// A body's or item's name is missing, duplicated, reserved or not a valid name.
    #[error("{item}, field `name`: {}", problem.describe(item.kind))]
    Name {
        /// The body or item (its name as given).
        item: ItemRef,
        /// What is wrong with the name.
        problem: NameProblem,
    },
    /// A model without bodies.
    #[error("model `{model}`, field `bodies`: the model has no bodies")]
    NoBodies {
        /// The model's name.
        model: String,
    },
    /// A body that no joint, spring, link or beam attaches to.
    #[error(
        "{body}: nothing constrains or supports it (no joint, spring, link or beam attaches to it)"
    )]
    Unattached {
        /// The body.
        body: ItemRef,
    },
    /// A field names a body that does not exist.
    #[error("{item}, field `{field}`: unknown body `{body}`; bodies are: {}", known.join(", "))]
    UnknownBody {
        /// The item.
        item: ItemRef,
        /// The field.
        field: String,
        /// The name given.
        body: String,
        /// The bodies of the model (and the ground).
        known: Box<[String]>,
    },
    /// A field names an item that does not exist.
    #[error(
        "{item}, field `{field}`: unknown {kind} `{name}`{}",
        known_items(kind, known)
    )]
    UnknownItem {
        /// The item whose field it is.
        item: ItemRef,
        /// The field.
        field: &'static str,
        /// The kind of item it must name (`actuator`).
        kind: &'static str,
        /// The name given.
        name: String,
        /// The items of that kind (`None` where the message does not list them).
        known: Option<Box<[String]>>,
    },
    /// A wing's derivative that is not one of the known derivatives.
    #[error(
        "{item}, field `derivatives`: unknown derivative `{name}`; the derivatives are (AVL's \
         body-axis names): {}",
        known.iter().map(|r| r.join(" ")).collect::<Vec<_>>().join(", ")
    )]
    UnknownDerivative {
        /// The wing.
        item: ItemRef,
        /// The name given.
        name: String,
        /// The known derivatives, by row.
        known: &'static [[&'static str; 6]],
    },
    /// An item connects a body to itself.
    #[error("{item}, field `bodies`: connects `{body}` to itself")]
    SelfConnection {
        /// The item.
        item: ItemRef,
        /// The body.
        body: String,
    },
    /// A surface (wing, strip) placed on the ground.
    #[error("{item}, field `body`: a {} must be on a body, not on the ground", item.kind)]
    OnGround {
        /// The surface.
        item: ItemRef,
    },
    /// A wing whose body is not among the bodies of the state space it is evaluated with.
    #[error("{item}, field `body`: body `{body}` is not among the state space's bodies")]
    NotInStateSpace {
        /// The wing.
        item: ItemRef,
        /// Its body.
        body: String,
    },
    /// A body with a negative mass.
    #[error("{item}, field `mass`: negative mass {mass}")]
    NegativeMass {
        /// The body.
        item: ItemRef,
        /// The mass.
        mass: f64,
    },
    /// A value given that is not finite (NaN or infinite).
    #[error("{item}{}: value {value} is not finite", field_part(field))]
    NotFinite {
        /// The body or item.
        item: ItemRef,
        /// The field (may be empty).
        field: String,
        /// The value.
        value: f64,
    },
    /// A field whose expression is not finite at the parameter values given.
    #[error(
        "{item}{}: evaluates to {value} at the given parameter values",
        field_part(field)
    )]
    NotFiniteAt {
        /// The body or item.
        item: ItemRef,
        /// The field (may be empty).
        field: String,
        /// The value.
        value: f64,
    },
    /// A field whose expression is invalid (the expression layer's error).
    #[error("{item}{}: {source}", field_part(field))]
    Expression {
        /// The body or item.
        item: ItemRef,
        /// The field (may be empty).
        field: String,
        /// What is wrong with the expression (boxed: the error stays small).
        #[source]
        source: Box<SymError>,
    },
    /// A quantity that must be positive is not (at the nominal point).
    #[error("{item}, field `{field}`: the {quantity} must be positive (nominal value {value})")]
    NotPositive {
        /// The item.
        item: ItemRef,
        /// The field.
        field: String,
        /// What the field is (`reference area`).
        quantity: &'static str,
        /// Its nominal value.
        value: f64,
    },
    /// A surface without an airspeed whose body's nominal velocity along its forward axis is
    /// not positive.
    #[error(
        "{item}, field `airspeed`: not given, and the nominal velocity of body `{body}` along \
         the {}'s forward axis is {along}: give the airspeed (positive)",
        item.kind
    )]
    NoAirspeed {
        /// The surface.
        item: ItemRef,
        /// Its body.
        body: String,
        /// The body's nominal velocity along the forward axis.
        along: f64,
    },
    /// A count outside its range (a point's `forces`, `moments`).
    #[error("{item}, field `{field}`: {value} is out of range {min}..={max}")]
    OutOfRange {
        /// The item.
        item: ItemRef,
        /// The field.
        field: String,
        /// The value given.
        value: i64,
        /// The smallest allowed.
        min: i64,
        /// The largest allowed.
        max: i64,
    },
    /// Geometry without a defined direction or frame (coinciding ends, a zero axis, axes that
    /// are not orthonormal).
    #[error("{item}, field `{field}`: {shape}")]
    Degenerate {
        /// The item.
        item: ItemRef,
        /// The field.
        field: String,
        /// What is degenerate.
        shape: Degeneracy,
    },
    /// A matrix field of the wrong size.
    #[error("{item}, field `{field}`: must be {n}×{n} (forces + moments)")]
    MatrixSize {
        /// The item.
        item: ItemRef,
        /// The field.
        field: String,
        /// The size it must have.
        n: usize,
    },
    /// A body's inertia tensor with a non-finite entry.
    #[error("{item}, field `{field}`: inertia tensor {tensor:?} is not finite")]
    InertiaNotFinite {
        /// The body.
        item: ItemRef,
        /// The field at fault (`moments` or `products`).
        field: String,
        /// The tensor.
        tensor: Box<nalgebra::Matrix3<f64>>,
    },
    /// A body's inertia tensor (with products) that is not positive semidefinite.
    #[error(
        "{item}, field `{field}`: the inertia tensor (moments {:?}, products {:?}) is not \
         positive semidefinite: its principal moments are {:.6?}, one negative; no body has \
         this inertia",
        inertia.moments, inertia.products, inertia.principal
    )]
    IndefiniteInertia {
        /// The body.
        item: ItemRef,
        /// The field at fault (`moments` or `products`).
        field: String,
        /// The inertia (boxed: the error stays small).
        inertia: Box<Inertia>,
    },
    /// A spinning body whose spin axis is not a principal axis of inertia.
    #[error(
        "{item}, field `angular_velocity`: the spin axis is not a principal axis of inertia: the \
         linearization about a steady spin does not exist"
    )]
    SpinNotPrincipal {
        /// The body.
        item: ItemRef,
    },
    /// A spinning body whose spin axis is a principal axis but not an axis of symmetry.
    #[error(
        "{item}, field `angular_velocity`: spins about a principal axis that is not an axis of \
         symmetry (unequal transverse inertias): the gyroscopic terms would be periodic, not \
         constant"
    )]
    SpinNotSymmetric {
        /// The body.
        item: ItemRef,
    },
    /// A wing derivative whose damping (ρVS/2 times the derivative) overflows the analysis.
    #[error(
        "{item}, field `derivatives`: `{derivative}` = {value:e} gives a damping of {damping:e} \
         (ρVS/2 times the derivative, with the reference lengths), beyond {limit:e}: the \
         analysis would overflow (check the derivative and its units)"
    )]
    DampingOverflow {
        /// The wing.
        item: ItemRef,
        /// The derivative (`Clp`).
        derivative: &'static str,
        /// Its value.
        value: f64,
        /// The damping it gives.
        damping: f64,
        /// The largest entry the analysis accepts.
        limit: f64,
    },
    /// A parameter override of a derived parameter.
    #[error("parameter `{name}`: is derived (= {definition}); set the parameters it is made of")]
    DerivedParameter {
        /// The parameter.
        name: String,
        /// Its definition.
        definition: String,
    },
    /// The model is not in static equilibrium at its given geometry: the force or moment
    /// equation with a residual beyond the tolerance.
    #[error(
        "not in equilibrium: {equation}: residual {residual:.6e} (of terms summing to \
         {magnitude:.6e} in magnitude; {ratio:.1e} of the body's largest {}). The given geometry \
         is not an equilibrium with these constraints (eom uses the given geometry as the loaded \
         equilibrium: add a support, or give spring preloads that balance the loads)",
        if *length == 1.0 { "force or moment" } else { "force, or moment over the model's length scale" }
    )]
    Equilibrium {
        /// The equation (``body `frame` x force``, `known preload 2`).
        equation: String,
        /// Its residual.
        residual: f64,
        /// The sum of the magnitudes of its terms.
        magnitude: f64,
        /// The residual relative to the body's largest force or moment.
        ratio: f64,
        /// The model's length scale (moments are divided by it).
        length: f64,
    },
    /// A decision the reduction recorded (a pivot, a rank) does not hold at the nominal point
    /// (pivots chosen at the point).
    #[error("singular: at the nominal point: {check}")]
    NominalCheckFails {
        /// The check that fails, as `CheckLabel` displays it (a string: `CheckLabel` lives in a
        /// layer above this one).
        check: String,
    },
    /// The robust method's velocity complement (a least-squares solve on the constraint
    /// blocks) has no solution.
    #[error("singular: velocity complement: {why}")]
    VelocityComplement {
        /// Why the solve failed (nalgebra's words).
        why: &'static str,
    },
    /// The position and velocity constraints have different ranks: a redundant constraint is
    /// inconsistent at the velocity level.
    #[error(
        "singular: the position and velocity constraints have different ranks ({position} and \
         {velocity}): a redundant constraint is inconsistent at the velocity level"
    )]
    ConstraintRanksDiffer {
        /// The rank of the position-level constraints.
        position: usize,
        /// The rank of the velocity-level constraints.
        velocity: usize,
    },
    /// A statically indeterminate model whose elastic compatibility equations are singular:
    /// the preloads of its redundant rigid constraints cannot be determined.
    #[error(
        "singular: the model is statically indeterminate (rank {rank} of {unknowns} unknown \
         preloads) and its elastic compatibility equations are singular: the preloads of \
         redundant rigid constraints cannot be determined (add compliance, or remove a redundant \
         joint among: {})",
        joints.join(", ")
    )]
    IndeterminatePreloads {
        /// The rank of the constraint rows.
        rank: usize,
        /// The number of unknown preloads.
        unknowns: usize,
        /// The rigid constraint rows among which one is redundant, as `RowLabel` displays
        /// them.
        joints: Box<[String]>,
    },
    /// The non-unique preloads of redundant constraint rows (a self-stress of rigid parts): the
    /// symbolic reduction cannot choose among them for every parameter value.
    #[error(
        "not supported: the preloads of the redundant constraint rows are not unique (a \
         self-stress of rigid parts, {moved:.1e} of the largest preload): the symbolic reduction \
         cannot choose among them for every parameter value (the numeric and robust methods \
         take the minimum-norm preloads)"
    )]
    NonUniquePreloads {
        /// How far the minimum-norm preloads move from the given ones, relative to the largest.
        moved: f64,
    },
    /// An elimination plan names a pivot that is out of range or already taken.
    #[error("singular: invalid pivot ({row}, {col}) in an elimination plan")]
    InvalidPivot {
        /// The pivot's row.
        row: usize,
        /// The pivot's column.
        col: usize,
    },
    /// An elimination plan names a pivot whose entry is a structural zero.
    #[error("singular: planned pivot ({row}, {col}) is a structural zero")]
    StructuralZeroPivot {
        /// The pivot's row.
        row: usize,
        /// The pivot's column.
        col: usize,
    },
    /// A pivot recorded in the symbolic elimination plan broke down at the evaluation point:
    /// the symbolic result is not valid there (the numeric and robust methods reduce at the point).
    #[error(
        "outside the validity region of the symbolic reduction: {check} (value {value:.3e}, \
         largest entry of its row {row_max:.3e})"
    )]
    PivotBreakdown {
        /// The check that fails, as `CheckLabel` displays it (a string: `CheckLabel` lives in a
        /// layer above this one).
        check: String,
        /// The pivot's value at the point.
        value: f64,
        /// The largest magnitude among the other entries of its row.
        row_max: f64,
    },
    /// A reduced mass matrix singular at the nominal point (massless motion) on a path that
    /// needs every independent velocity to carry inertia.
    #[error(
        "not supported: the reduced mass matrix is singular at the nominal point (massless \
         motion of {}): this reduction needs every independent velocity to carry inertia (the \
         robust method, with orthonormal bases and a descriptor reduction, handles index-1 \
         descriptor models)",
        coordinates.join(", ")
    )]
    MasslessMotion {
        /// The coordinates whose motion carries no inertia.
        coordinates: Box<[String]>,
    },
    /// An acceleration sensor that feeds an input's rate straight through: its acceleration
    /// contains the input's second derivative.
    #[error(
        "not supported: acceleration sensor `{output}` responds to the rate of input `{input}` \
         instantly (its velocity jumps with the input): its acceleration contains the input's \
         second derivative, which a state-space model cannot represent; measure the velocity \
         instead, or remove the rate gain"
    )]
    InputRateInAcceleration {
        /// The sensor (output).
        output: String,
        /// The input.
        input: String,
    },
    /// An unknown name of unsteady aerodynamics.
    #[error(
        "not supported: unknown unsteady aerodynamics `{given}`: expected \"quasi-steady\", \
         \"jones\" or \"auto\""
    )]
    UnknownUnsteady {
        /// The name given.
        given: String,
    },
    /// An error of the expression layer (a parameter, an expression, an evaluation).
    #[error(transparent)]
    Sym(#[from] SymError),
    /// An error of the numeric layer.
    #[error(transparent)]
    Num(#[from] NumError),
}

impl ModelError {
    /// The body or item the error is about, where it is about one.
    pub fn item(&self) -> Option<&ItemRef> {
        use ModelError::*;
        match self {
            Name { item, .. }
            | UnknownBody { item, .. }
            | UnknownItem { item, .. }
            | UnknownDerivative { item, .. }
            | SelfConnection { item, .. }
            | OnGround { item }
            | NotInStateSpace { item, .. }
            | NegativeMass { item, .. }
            | NotFinite { item, .. }
            | NotFiniteAt { item, .. }
            | Expression { item, .. }
            | NotPositive { item, .. }
            | NoAirspeed { item, .. }
            | OutOfRange { item, .. }
            | Degenerate { item, .. }
            | MatrixSize { item, .. }
            | InertiaNotFinite { item, .. }
            | IndefiniteInertia { item, .. }
            | SpinNotPrincipal { item }
            | SpinNotSymmetric { item }
            | DampingOverflow { item, .. } => Some(item),
            Unattached { body } => Some(body),
            _ => None,
        }
    }

    /// Whether the error is one of a reduction method rather than of the model (a singular
    /// matrix, a symbolic pivot that vanishes at the point, a feature the method does not
    /// support): another method may succeed where this one failed.
    pub fn is_method_failure(&self) -> bool {
        use ModelError::*;
        matches!(
            self,
            NominalCheckFails { .. }
                | VelocityComplement { .. }
                | ConstraintRanksDiffer { .. }
                | IndeterminatePreloads { .. }
                | NonUniquePreloads { .. }
                | InvalidPivot { .. }
                | StructuralZeroPivot { .. }
                | PivotBreakdown { .. }
                | MasslessMotion { .. }
                | InputRateInAcceleration { .. }
        )
    }
}

/// A body's inertia as an error reports it.
#[derive(Debug, Clone, PartialEq)]
pub struct Inertia {
    /// The moments (x, y, z).
    pub moments: [f64; 3],
    /// The products (xy, yz, zx).
    pub products: [f64; 3],
    /// The principal moments, ascending.
    pub principal: [f64; 3],
}

/// What is wrong with a body's or item's name.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum NameProblem {
    /// No name given.
    Missing,
    /// The name of another body (for a body) or item (for an item).
    Duplicate,
    /// `ground`, reserved for the fixed frame (bodies only).
    Reserved,
    /// Not a valid name (from [`eom_text::name_problem`]).
    Invalid(String),
}

impl NameProblem {
    /// The message, for a body (`kind` `"body"`) or another item.
    fn describe(&self, kind: &str) -> String {
        let what = if kind == "body" { "body" } else { "item" };
        match self {
            NameProblem::Missing if what == "body" => "a body needs a name".into(),
            NameProblem::Missing => "an item needs a name".into(),
            NameProblem::Duplicate => format!("duplicate {what} name"),
            NameProblem::Reserved => "`ground` is reserved for the fixed frame".into(),
            NameProblem::Invalid(p) => p.clone(),
        }
    }
}

/// What is degenerate about an item's geometry.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Degeneracy {
    /// The two ends of a line or beam coincide; `direction`: the item needs the line's
    /// direction (the message says it is undefined).
    CoincidentEnds {
        /// Whether the item uses the direction.
        direction: bool,
    },
    /// A beam's bending-plane vector is zero or parallel to its axis.
    ParallelPerp,
    /// A point's axis is zero, but its forces / moments (1 or 2) need a direction.
    ZeroAxis {
        /// The point's `forces`.
        forces: u8,
        /// The point's `moments`.
        moments: u8,
    },
    /// An axis that is not a unit vector.
    NotUnit {
        /// Its length at the nominal point.
        length: f64,
    },
    /// A `down` axis not perpendicular to `forward`.
    NotPerpendicular {
        /// Their dot product at the nominal point.
        dot: f64,
    },
}

impl fmt::Display for Degeneracy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Degeneracy::CoincidentEnds { direction } => {
                f.write_str("the two ends coincide: zero length")?;
                if *direction {
                    f.write_str(" (the direction is undefined)")?;
                }
                Ok(())
            }
            Degeneracy::ParallelPerp => f.write_str("zero or parallel to the beam axis"),
            Degeneracy::ZeroAxis { forces, moments } => write!(
                f,
                "is zero, but forces = {forces} / moments = {moments} need a direction"
            ),
            Degeneracy::NotUnit { length } => write!(
                f,
                "must be a unit vector; its length is {length} at the nominal point"
            ),
            Degeneracy::NotPerpendicular { dot } => write!(
                f,
                "must be perpendicular to `forward`; their dot product is {dot}"
            ),
        }
    }
}

/// `, field `NAME`` (nothing for an empty field name).
fn field_part(field: &str) -> String {
    if field.is_empty() {
        String::new()
    } else {
        format!(", field `{field}`")
    }
}

/// `; actuators are: a, b` (nothing when the message does not list them).
fn known_items(kind: &str, known: &Option<Box<[String]>>) -> String {
    match known {
        Some(k) => format!("; {kind}s are: {}", k.join(", ")),
        None => String::new(),
    }
}

/// The label of an item in messages: ``spring `front` ``. Built directly rather than by
/// `format!`: every reacting item's preload is labelled on every assembly.
pub(crate) fn label(kind: &str, name: &str) -> String {
    let name = eom_text::shown(name);
    let mut s = String::with_capacity(kind.len() + name.len() + 3);
    s.push_str(kind);
    s.push_str(" `");
    s.push_str(&name);
    s.push('`');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Small enough that `Result<_, ModelError>` stays cheap (clippy's `result_large_err`
    /// limit is 128 bytes).
    #[test]
    fn error_is_small() {
        let size = std::mem::size_of::<ModelError>();
        assert!(size < 128, "{size} bytes");
    }

    /// The messages read as they did when they were built from strings (formatting only:
    /// what users see is checked by the CLI's and the Python package's tests).
    #[test]
    fn display_gives_the_messages() {
        let it = |k: &'static str, n: &str| ItemRef::new(k, n);
        let cases = [
            (
                ModelError::Name {
                    item: it("body", ""),
                    problem: NameProblem::Missing,
                },
                "body ``, field `name`: a body needs a name",
            ),
            (
                ModelError::Name {
                    item: it("spring", "k"),
                    problem: NameProblem::Duplicate,
                },
                "spring `k`, field `name`: duplicate item name",
            ),
            (
                ModelError::Unattached {
                    body: it("body", "b"),
                },
                "body `b`: nothing constrains or supports it (no joint, spring, link or beam \
                 attaches to it)",
            ),
            (
                ModelError::UnknownItem {
                    item: it("sensor", "s"),
                    field: "actuator",
                    kind: "actuator",
                    name: "a".into(),
                    known: None,
                },
                "sensor `s`, field `actuator`: unknown actuator `a`",
            ),
            (
                ModelError::UnknownItem {
                    item: it("sensor", "s"),
                    field: "actuator",
                    kind: "actuator",
                    name: "a".into(),
                    known: Some(vec!["u".into(), "v".into()].into()),
                },
                "sensor `s`, field `actuator`: unknown actuator `a`; actuators are: u, v",
            ),
            (
                ModelError::UnknownDerivative {
                    item: it("wing", "w"),
                    name: "CLa".into(),
                    known: &[
                        ["a", "b", "c", "d", "e", "f"],
                        ["g", "h", "i", "j", "k", "l"],
                    ],
                },
                "wing `w`, field `derivatives`: unknown derivative `CLa`; the derivatives are \
                 (AVL's body-axis names): a b c d e f, g h i j k l",
            ),
            (
                ModelError::OutOfRange {
                    item: it("rigid point", "p"),
                    field: "forces".into(),
                    value: 4,
                    min: 0,
                    max: 3,
                },
                "rigid point `p`, field `forces`: 4 is out of range 0..=3",
            ),
            (
                ModelError::Degenerate {
                    item: it("link", "l"),
                    field: "ends".into(),
                    shape: Degeneracy::CoincidentEnds { direction: true },
                },
                "link `l`, field `ends`: the two ends coincide: zero length (the direction is \
                 undefined)",
            ),
            (
                ModelError::Degenerate {
                    item: it("rigid point", "p"),
                    field: "axis".into(),
                    shape: Degeneracy::ZeroAxis {
                        forces: 1,
                        moments: 0,
                    },
                },
                "rigid point `p`, field `axis`: is zero, but forces = 1 / moments = 0 need a \
                 direction",
            ),
            (
                ModelError::IndefiniteInertia {
                    item: it("body", "b"),
                    field: "products".into(),
                    inertia: Box::new(Inertia {
                        moments: [1.0, 1.0, 1.0],
                        products: [2.0, 0.0, 0.0],
                        principal: [-1.0, 1.0, 3.0],
                    }),
                },
                "body `b`, field `products`: the inertia tensor (moments [1.0, 1.0, 1.0], \
                 products [2.0, 0.0, 0.0]) is not positive semidefinite: its principal moments \
                 are [-1.000000, 1.000000, 3.000000], one negative; no body has this inertia",
            ),
            (
                ModelError::DampingOverflow {
                    item: it("wing", "w"),
                    derivative: "Clp",
                    value: -0.5,
                    damping: 2e300,
                    limit: 1e300,
                },
                "wing `w`, field `derivatives`: `Clp` = -5e-1 gives a damping of 2e300 (ρVS/2 \
                 times the derivative, with the reference lengths), beyond 1e300: the analysis \
                 would overflow (check the derivative and its units)",
            ),
            (
                ModelError::DerivedParameter {
                    name: "b".into(),
                    definition: "l - a".into(),
                },
                "parameter `b`: is derived (= l - a); set the parameters it is made of",
            ),
        ];
        for (e, want) in cases {
            assert_eq!(e.to_string(), want, "{e:?}");
        }
    }
}
