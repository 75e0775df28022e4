//! The regions of the failure map: a model, one parameter swept over values where methods
//! are expected to break, and the reference each point is checked against.

use super::{StressError, chain, models as files};
use eom_model::Model;
use eom_sym::Expr;
use num_complex::Complex64;

/// Where a region's model comes from.
#[derive(Clone, Debug)]
pub enum Source {
    /// A built-in model (`models::build`); the generated code of those `build.rs` compiles is
    /// one of the methods.
    Builtin(&'static str),
    /// A model file (text) built in code for a structural case.
    File(&'static str, String),
}

impl Source {
    /// The model with these parameter values as its nominal point.
    pub fn build(&self, overrides: &[(&str, f64)]) -> Result<Model<Expr>, StressError> {
        match self {
            Source::Builtin(name) => models::build(name, overrides)
                .map_err(|e| StressError::Model(name.to_string(), e.to_string())),
            Source::File(name, text) => eom_model::file::from_str(text, name, overrides)
                .map_err(|e| StressError::Model(name.to_string(), e.to_string())),
        }
    }

    /// The model's name.
    pub fn name(&self) -> &'static str {
        match self {
            Source::Builtin(n) | Source::File(n, _) => n,
        }
    }
}

/// What a region's points are checked against.
#[derive(Clone, Debug)]
pub enum ReferenceKind {
    /// The double-double reference of the same model with the point as its nominal (the
    /// symbolic reduction formed there, evaluated in double-double, eigenvalues refined by
    /// Newton in double-double).
    DoubleDouble,
    /// The double-double reference of another model of the same mechanism (the redundant rows
    /// removed by hand).
    DoubleDoubleOf(Source),
    /// A closed form of the swept value.
    Closed(fn(f64) -> Vec<Complex64>),
}

impl ReferenceKind {
    /// One line for the outputs.
    pub fn describe(&self) -> String {
        match self {
            ReferenceKind::DoubleDouble => "double-double, same model".into(),
            ReferenceKind::DoubleDoubleOf(s) => format!("double-double of `{}`", s.name()),
            ReferenceKind::Closed(_) => "closed form".into(),
        }
    }
}

/// One row of the map.
#[derive(Clone, Debug)]
pub struct Region {
    /// Short name.
    pub name: &'static str,
    /// What is stressed.
    pub what: &'static str,
    /// The swept parameter.
    pub param: &'static str,
    /// Its values.
    pub values: Vec<f64>,
    /// The model.
    pub source: Source,
    /// The reference.
    pub reference: ReferenceKind,
}

/// `n` values from `a` to `b`, evenly spaced in log (one value `a` when `n` is 1).
pub fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![a];
    }
    let (la, lb) = (a.log10(), b.log10());
    (0..n)
        .map(|i| 10f64.powf(la + (lb - la) * i as f64 / (n - 1) as f64))
        .collect()
}

/// Chain of the stiffness-ratio region: four unit masses, unit springs but the third.
const STIFF_MASSES: [f64; 4] = [1.0, 1.0, 1.0, 1.0];
fn stiff_springs(k3: f64) -> [f64; 4] {
    [1.0, 1.0, k3, 1.0]
}
fn stiff_reference(k3: f64) -> Vec<Complex64> {
    chain::eigenvalues(&STIFF_MASSES, &stiff_springs(k3))
}

/// Chain of the massless-body region: three bodies, the middle one of mass `m2`.
fn light_masses(m2: f64) -> [f64; 3] {
    [1.0, m2, 1.0]
}
const LIGHT_SPRINGS: [f64; 3] = [1.0, 2.0, 3.0];
fn light_reference(m2: f64) -> Vec<Complex64> {
    chain::eigenvalues(&light_masses(m2), &LIGHT_SPRINGS)
}

/// The hinges: collinear at `d = 0` (a pendulum about y: I = 0.1 + 1 · 1² about the axis,
/// ω² = 5/1.1), locked (no state) at any other tilt.
fn hinges_reference(d: f64) -> Vec<Complex64> {
    if d == 0.0 {
        let w = (5.0f64 / 1.1).sqrt();
        vec![Complex64::new(0.0, w), Complex64::new(0.0, -w)]
    } else {
        Vec::new()
    }
}

/// The Bricard linkage's one mode, `m λ² + c λ + k = 0` with its effective inertia
/// m = 2.89210019455361372887 kg m² about hinge 1 (from the null space of the six hinge
/// screws, 50 digits; `eom-model/tests/data/bricard_reference.py`) and c = 0.1 N m s/rad.
#[allow(clippy::excessive_precision)]
fn bricard_reference(k: f64) -> Vec<Complex64> {
    let (m, c) = (2.892_100_194_553_613_728_87_f64, 0.1);
    let root = Complex64::new(c * c - 4.0 * m * k, 0.0).sqrt();
    vec![(-c + root) / (2.0 * m), (-c - root) / (2.0 * m)]
}

/// The regions; `quick` takes fewer points per region (the CI grid).
pub fn regions(quick: bool) -> Vec<Region> {
    [builtin_regions(quick), structural_regions(quick)].concat()
}

/// Points per region: `full`, or `q` on the quick grid.
fn points(quick: bool, full: usize, q: usize) -> usize {
    if quick { q } else { full }
}

/// Parameter sweeps of built-in models (their generated code is one of the methods).
fn builtin_regions(quick: bool) -> Vec<Region> {
    let n = |full, q| points(quick, full, q);
    let coalescence = if quick {
        vec![0.684]
    } else {
        // Denser towards the coalescence.
        let mut v: Vec<f64> = (0..25).map(|i| 0.6 + 0.2 * i as f64 / 24.0).collect();
        v.extend([0.683, 0.6835, 0.684, 0.6845, 0.685]);
        v.sort_by(f64::total_cmp);
        v
    };
    vec![
        Region {
            name: "shimmy_speed",
            what: "forward speed to 0 with a nonholonomic contact (shimmy)",
            param: "u",
            values: logspace(1e-8, 1.0, n(25, 5)),
            source: Source::Builtin("shimmy"),
            reference: ReferenceKind::DoubleDouble,
        },
        Region {
            name: "bicycle_speed",
            what: "forward speed to 0 with nonholonomic contacts (bicycle)",
            param: "v",
            values: logspace(1e-8, 1.0, n(25, 5)),
            source: Source::Builtin("bicycle"),
            reference: ReferenceKind::DoubleDouble,
        },
        Region {
            name: "bicycle_coalescence",
            what: "coalescing weave eigenvalues of the bicycle near 0.684 m/s",
            param: "v",
            values: coalescence,
            source: Source::Builtin("bicycle"),
            reference: ReferenceKind::DoubleDouble,
        },
        Region {
            name: "far_nominal_bicycle",
            what: "rear frame mass far from the symbolic pivots' nominal 85 kg",
            param: "mB",
            values: logspace(85e-4, 85e4, n(25, 5)),
            source: Source::Builtin("bicycle"),
            reference: ReferenceKind::DoubleDouble,
        },
        Region {
            name: "far_nominal_quarter_car",
            what: "unsprung mass far from the symbolic pivots' nominal 50 kg",
            param: "mu",
            values: logspace(50e-6, 50e6, n(25, 5)),
            source: Source::Builtin("quarter_car"),
            reference: ReferenceKind::DoubleDouble,
        },
        Region {
            name: "quarter_car_stiffness",
            what: "tyre stiffness 1e-8…1e8 times nominal (ratio to the suspension 1e-7…1e9)",
            param: "kt",
            values: logspace(1.8e-3, 1.8e13, n(33, 5)),
            source: Source::Builtin("quarter_car"),
            reference: ReferenceKind::DoubleDouble,
        },
    ]
}

/// Structural cases built as model files.
fn structural_regions(quick: bool) -> Vec<Region> {
    let n = |full, q| points(quick, full, q);
    vec![
        Region {
            name: "chain_stiffness",
            what: "one spring of a four-mass chain 1e-10…1e10 times the others",
            param: "k3",
            values: logspace(1e-10, 1e10, n(41, 5)),
            source: Source::File(
                "chain_stiffness",
                files::chain(&STIFF_MASSES, &stiff_springs(1.0)),
            ),
            reference: ReferenceKind::Closed(stiff_reference),
        },
        Region {
            name: "massless_body",
            what: "the middle body of a three-mass chain nearly massless",
            param: "m2",
            values: logspace(1e-12, 1.0, n(25, 5)),
            source: Source::File(
                "massless_body",
                files::chain(&light_masses(1.0), &LIGHT_SPRINGS),
            ),
            reference: ReferenceKind::Closed(light_reference),
        },
        Region {
            name: "singular_mass",
            what: "the middle body massless: a singular mass matrix",
            param: "m2",
            values: vec![0.0],
            source: Source::File(
                "massless_body",
                files::chain(&light_masses(1.0), &LIGHT_SPRINGS),
            ),
            reference: ReferenceKind::Closed(light_reference),
        },
        Region {
            name: "string_offset",
            what: "two strings holding a block, one moved sideways by 1e-15…1e-3",
            param: "off",
            values: logspace(1e-15, 1e-3, n(25, 5)),
            source: Source::File("strings", files::strings()),
            reference: ReferenceKind::DoubleDouble,
        },
        Region {
            name: "collinear_hinges",
            what: "two hinges of a pendulum, the second axis tilted by 0 or 1e-16…1e-2 (locked)",
            param: "d",
            values: [vec![0.0], logspace(1e-16, 1e-2, n(15, 5))].concat(),
            source: Source::File("hinges", files::hinges()),
            reference: ReferenceKind::Closed(hinges_reference),
        },
        Region {
            name: "redundant_four_bar",
            what: "parallelogram four-bar in 3-D (3 redundant rows), spring swept",
            param: "k",
            values: logspace(1e-4, 1e4, n(17, 3)),
            source: Source::File("four_bar", files::four_bar(false)),
            reference: ReferenceKind::DoubleDoubleOf(Source::File(
                "four_bar_by_hand",
                files::four_bar(true),
            )),
        },
        Region {
            name: "redundant_five_bar",
            what: "planar five-bar in 3-D (3 redundant rows), springs swept",
            param: "k",
            values: logspace(1e-4, 1e4, n(17, 3)),
            source: Source::File("five_bar", files::five_bar(false)),
            reference: ReferenceKind::DoubleDoubleOf(Source::File(
                "five_bar_by_hand",
                files::five_bar(true),
            )),
        },
        Region {
            name: "redundant_bricard",
            what: "spatial Bricard 6R linkage (30 rows for 30 coordinates, one redundant), spring swept",
            param: "k",
            values: logspace(1e-4, 1e4, n(17, 3)),
            source: Source::File("bricard", files::bricard()),
            reference: ReferenceKind::Closed(bricard_reference),
        },
    ]
}
