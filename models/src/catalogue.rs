//! The catalogue of built-in models.

use crate::CatalogueError;
use eom_model::*;
use eom_sym::{Assumption, Expr, ParamInfo};

/// A parameter of a built-in model.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamSpec {
    /// Name as used in expressions and on the command line.
    pub name: &'static str,
    /// Default (nominal) value.
    pub default: f64,
    /// Unit.
    pub unit: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Sign assumption (values violating it are rejected).
    pub assume: Assumption,
}

/// A parameter that must be positive (masses, lengths, stiffnesses).
pub(crate) const fn p(
    name: &'static str,
    default: f64,
    unit: &'static str,
    description: &'static str,
) -> ParamSpec {
    ParamSpec {
        name,
        default,
        unit,
        description,
        assume: Assumption::Positive,
    }
}
/// A parameter that may take any finite value.
pub(crate) const fn real(
    name: &'static str,
    default: f64,
    unit: &'static str,
    description: &'static str,
) -> ParamSpec {
    ParamSpec {
        name,
        default,
        unit,
        description,
        assume: Assumption::Real,
    }
}

pub(crate) type Builder = fn(&mut Model<Expr>, &[Expr], usize) -> Result<(), CatalogueError>;

/// A built-in model.
#[derive(Clone, Debug)]
pub struct ModelInfo {
    /// Name (for chains: the patterns `chainN` and `chainpN`).
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Parameters with defaults.
    pub params: Vec<ParamSpec>,
    builder: Builder,
}

impl ModelInfo {
    /// An entry of the catalogue.
    pub(crate) fn new(
        name: &'static str,
        description: &'static str,
        params: Vec<ParamSpec>,
        builder: Builder,
    ) -> Self {
        ModelInfo {
            name,
            description,
            params,
            builder,
        }
    }

    /// Build the model with `overrides` replacing defaults (by name).
    pub fn build(
        &self,
        overrides: &[(&str, f64)],
        size: usize,
        name: &str,
    ) -> Result<Model<Expr>, CatalogueError> {
        for (k, _) in overrides {
            if !self.params.iter().any(|p| p.name == *k) {
                return Err(CatalogueError::UnknownParameter {
                    model: name.to_string(),
                    name: k.to_string(),
                    known: self.params.iter().map(|p| p.name.to_string()).collect(),
                });
            }
        }
        let mut m = Model::new(name);
        let mut ps = Vec::new();
        for spec in &self.params {
            let value = overrides
                .iter()
                .rev()
                .find(|(k, _)| *k == spec.name)
                .map_or(spec.default, |x| x.1);
            let bad = match spec.assume {
                Assumption::Positive => value.is_nan() || value <= 0.0 || !value.is_finite(),
                Assumption::Nonnegative => value.is_nan() || value < 0.0 || !value.is_finite(),
                Assumption::Nonzero => value == 0.0 || !value.is_finite(),
                Assumption::Real => !value.is_finite(),
            };
            if bad {
                return Err(CatalogueError::BadValue {
                    model: name.to_string(),
                    name: spec.name.to_string(),
                    value,
                    problem: match spec.assume {
                        Assumption::Positive => "must be positive".into(),
                        Assumption::Nonnegative => "must not be negative".into(),
                        Assumption::Nonzero => "must not be zero".into(),
                        Assumption::Real => "must be finite".into(),
                    },
                });
            }
            ps.push(m.param_info(ParamInfo {
                name: spec.name.to_string(),
                nominal: value,
                unit: Some(spec.unit.to_string()),
                description: Some(spec.description.to_string()),
                assume: spec.assume,
            })?);
        }
        (self.builder)(&mut m, &ps, size)?;
        Ok(m)
    }
}

/// All built-in models.
pub fn catalogue() -> Vec<ModelInfo> {
    vec![
        ModelInfo {
            name: "smd",
            description: "spring-mass-damper on a vertical slider",
            params: vec![
                p("m", 1.0, "kg", "mass"),
                p("k", 10.0, "N/m", "stiffness"),
                p("c", 0.1, "N s/m", "damping"),
            ],
            builder: smd,
        },
        ModelInfo {
            name: "pendulum",
            description: "one-degree-of-freedom pendulum hanging from a pin",
            params: vec![
                p("m", 10.0, "kg", "mass"),
                p("r", 1.0, "m", "distance from the pin to the mass centre"),
                real(
                    "Ix",
                    1.0,
                    "kg m^2",
                    "moment of inertia about the mass centre",
                ),
                p("g", 9.807, "m/s^2", "gravity"),
            ],
            builder: pendulum,
        },
        ModelInfo {
            name: "shimmy",
            description: "swivel wheel with a no-slip tyre and a lateral spring (Schwab & Meijaard 2003)",
            params: vec![
                p("m", 5.0, "kg", "mass"),
                p("I", 1.05, "kg m^2", "yaw inertia about the mass centre"),
                p("k", 1.5, "N/m", "lateral spring stiffness"),
                p(
                    "l",
                    1.0,
                    "m",
                    "distance from the tyre to the spring (a + b)",
                ),
                real(
                    "x",
                    0.5,
                    "",
                    "mass-centre position a/l behind the spring (a = x l, b = (1 - x) l)",
                ),
                real("u", 10.0, "m/s", "forward speed"),
            ],
            builder: shimmy,
        },
        ModelInfo {
            name: "bicycle",
            description: "Whipple bicycle benchmark (Meijaard, Papadopoulos, Ruina & Schwab 2007)",
            params: crate::bicycle::params(),
            builder: crate::bicycle::build,
        },
        ModelInfo {
            name: "quarter_car",
            description: "quarter car: sprung and unsprung mass, suspension and tyre with damping, road displacement input",
            params: vec![
                p("ms", 500.0, "kg", "sprung mass"),
                p("mu", 50.0, "kg", "unsprung mass"),
                p("ks", 18000.0, "N/m", "suspension stiffness"),
                p("kt", 180000.0, "N/m", "tyre stiffness"),
                p("cs", 1500.0, "N s/m", "suspension damping"),
                ParamSpec {
                    assume: Assumption::Nonnegative,
                    ..p("ct", 500.0, "N s/m", "tyre damping")
                },
            ],
            builder: quarter_car,
        },
        ModelInfo {
            name: "top",
            description: "heavy symmetric top spinning on a fixed point (Pappalardo et al. 2020)",
            params: vec![
                real("r", 1.0, "rad/s", "spin rate"),
                p("m", 0.01, "kg", "mass"),
                p("h", 0.04, "m", "height of the mass centre above the point"),
                p(
                    "It",
                    3e-4,
                    "kg m^2",
                    "transverse moment of inertia about the mass centre",
                ),
                p("Ia", 4e-4, "kg m^2", "axial moment of inertia"),
                p("g", 9.81, "m/s^2", "gravity"),
            ],
            builder: top,
        },
        ModelInfo {
            name: "disk",
            description: "uniform disk rolling upright on a plane (Schwab & Meijaard 2003)",
            params: vec![
                real("u", 0.1, "m/s", "forward speed"),
                p("m", 4.0, "kg", "mass"),
                p("r", 0.5, "m", "radius"),
                p("g", 9.81, "m/s^2", "gravity"),
            ],
            builder: disk,
        },
        ModelInfo {
            name: "chainN",
            description: "N equal masses in series on sliders, the first tied to ground, spring and damper in each link (chain10, chain50, ...)",
            params: vec![
                p("m", 1.0, "kg", "mass of each body"),
                p("k", 1.0, "N/m", "stiffness of each link"),
                p("c", 0.1, "N s/m", "damping of each link"),
            ],
            builder: chain,
        },
        crate::chainp::entry(),
    ]
    .into_iter()
    .chain(crate::wings::entries())
    .chain(crate::aeroelastic::entries())
    .chain(crate::flight::entries())
    .chain(crate::applications::entries())
    .chain(crate::vehicles::entries())
    .collect()
}

/// Largest chain size accepted by name: the size whose `eom analyze` meets the time and
/// memory targets of the performance page (docs/performance.md) (every step grows as the cube of the
/// size). Longer chains can be written as model files.
pub const MAX_CHAIN: usize = 1000;

/// The catalogue entry and size for a model name (`chain50` → the chain entry, 50;
/// `chainp50` → the chain with per-element parameters, 50, its parameters numbered).
pub fn find(name: &str) -> Result<(ModelInfo, usize), CatalogueError> {
    let cat = catalogue();
    // `chainp` before `chain`: both patterns are a stem and a size.
    for (stem, pattern) in [("chainp", "chainpN"), ("chain", "chainN")] {
        let Some(n) = name.strip_prefix(stem) else {
            continue;
        };
        if n.is_empty() || !n.bytes().all(|b| b.is_ascii_digit()) {
            continue;
        }
        let size = n.parse::<usize>().ok().filter(|k| *k <= MAX_CHAIN);
        let Some(size) = size else {
            return Err(CatalogueError::ChainTooLong {
                name: if name.len() > 40 {
                    format!("{}… ({} characters)", &name[..20], name.len())
                } else {
                    name.to_string()
                },
                max: MAX_CHAIN,
            });
        };
        if size == 0 {
            break;
        }
        let mut info = cat
            .into_iter()
            .find(|m| m.name == pattern)
            .expect("chain entry");
        if pattern == "chainpN" {
            info.params = crate::chainp::params(size);
        }
        return Ok((info, size));
    }
    match cat.iter().position(|m| m.name == name) {
        Some(i) if !is_pattern(name) => Ok((cat[i].clone(), 0)),
        _ => Err(CatalogueError::UnknownModel {
            name: name.to_string(),
            known: cat
                .iter()
                .map(|m| {
                    if is_pattern(m.name) {
                        format!("{} (N = 1..{MAX_CHAIN})", m.name)
                    } else {
                        m.name.to_string()
                    }
                })
                .collect(),
        }),
    }
}

/// Whether a catalogue name is a pattern with a size N (`chainN`, `chainpN`).
fn is_pattern(name: &str) -> bool {
    matches!(name, "chainN" | "chainpN")
}

/// Build a model by name with parameter overrides.
pub fn build(name: &str, overrides: &[(&str, f64)]) -> Result<Model<Expr>, CatalogueError> {
    let (info, size) = find(name)?;
    info.build(overrides, size, name)
}

pub(crate) fn smd(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [m, k, c] = [p[0], p[1], p[2]];
    md.add(Body::new("block").mass(m).at(vec3(0, 0, 1)));
    md.add(
        RigidPoint::new("slider")
            .between("block", "ground")
            .at(vec3(0, 0, 1))
            .forces(2)
            .moments(3)
            .axis(z_axis()),
    );
    md.add(
        FlexPoint::new("spring")
            .between("block", "ground")
            .at(vec3(0, 0, 0.5))
            .forces(1)
            .axis(z_axis())
            .stiffness(k, 0)
            .damping(c, 0),
    );
    md.add(
        Actuator::new("f")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), zero3()),
    );
    md.add(
        Sensor::new("z")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), zero3()),
    );
    md.add(
        Sensor::new("z dot")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), zero3())
            .velocity()
            .units("m/s"),
    );
    md.add(
        Sensor::new("kz")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), zero3())
            .gain(k)
            .units("N"),
    );
    Ok(())
}

fn pendulum(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [m, r, ix, g] = [p[0], p[1], p[2], p[3]];
    let body = Body::new("block")
        .mass(m)
        .at(vec3(0, 0, 1))
        .moments(vec3(ix, ix, ix));
    md.add(Load::weight(&body, g));
    md.add(body);
    md.add(
        RigidPoint::new("pin")
            .between("block", "ground")
            .at(vec3(0, 0, Expr::one() + r))
            .forces(3)
            .moments(2)
            .axis(x_axis()),
    );
    md.add(
        Actuator::new("Y")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), vec3(0, -1, 1)),
    );
    md.add(
        Actuator::new("L")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), vec3(-1, 0, 1))
            .twist()
            .units("N m"),
    );
    md.add(
        Sensor::new("y")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), vec3(0, -1, 1)),
    );
    md.add(
        Sensor::new("mgr phi")
            .between("block", "ground")
            .ends(vec3(0, 0, 1), vec3(-1, 0, 1))
            .twist()
            .gain(m * g * r)
            .units("N m"),
    );
    Ok(())
}

pub(crate) fn shimmy(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [m, i, k, l, x, u] = [p[0], p[1], p[2], p[3], p[4], p[5]];
    let a = x * l;
    let b = l - a;
    md.add(
        Body::new("chassis")
            .mass(m)
            .moments(vec3(0, 0, i))
            .velocity(vec3(u, 0, 0)),
    );
    md.add(
        FlexPoint::new("spring")
            .between("chassis", "ground")
            .at(vec3(b, 0, 0))
            .forces(1)
            .axis(y_axis())
            .stiffness(k, 0),
    );
    md.add(
        NhPoint::new("tyre")
            .between("chassis", "ground")
            .at(vec3(-a, 0, 0))
            .forces(1)
            .axis(y_axis()),
    );
    md.add(
        RigidPoint::new("road")
            .between("chassis", "ground")
            .forces(1)
            .moments(2)
            .axis(z_axis()),
    );
    md.add(
        RigidPoint::new("speed")
            .between("chassis", "ground")
            .forces(1)
            .axis(x_axis()),
    );
    md.add(
        Actuator::new("applied force")
            .between("chassis", "ground")
            .ends(zero3(), vec3(0, 0.1, 0)),
    );
    md.add(
        Sensor::new("spring force")
            .between("chassis", "ground")
            .ends(vec3(b, 0, 0), vec3(b, 0.1, 0))
            .gain(k)
            .units("N"),
    );
    md.add(
        Sensor::new("mass motion")
            .between("chassis", "ground")
            .ends(zero3(), vec3(0, 0.1, 0)),
    );
    Ok(())
}

fn quarter_car(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [ms, mu, ks, kt, cs, ct] = [p[0], p[1], p[2], p[3], p[4], p[5]];
    let g = Expr::float(9.81)?;
    let unsprung = Body::new("unsprung").mass(mu).at(vec3(0, 0, 0.3));
    let sprung = Body::new("sprung").mass(ms).at(vec3(0, 0, 0.6));
    md.add(Load::weight(&unsprung, g));
    md.add(Load::weight(&sprung, g));
    md.add(unsprung).add(sprung);
    md.add(
        FlexPoint::new("tyre")
            .between("unsprung", "ground")
            .at(vec3(0, 0, 0.15))
            .forces(1)
            .axis(z_axis())
            .stiffness(kt, 0)
            .damping(ct, 0),
    );
    md.add(
        FlexPoint::new("suspension")
            .between("sprung", "unsprung")
            .at(vec3(0, 0, 0.45))
            .forces(1)
            .axis(z_axis())
            .stiffness(ks, 0)
            .damping(cs, 0),
    );
    md.add(
        RigidPoint::new("unsprung slider")
            .between("unsprung", "ground")
            .at(vec3(0, 0, 0.3))
            .forces(2)
            .moments(3)
            .axis(z_axis()),
    );
    md.add(
        RigidPoint::new("sprung slider")
            .between("sprung", "ground")
            .at(vec3(0, 0, 0.6))
            .forces(2)
            .moments(3)
            .axis(z_axis()),
    );
    md.add(
        Actuator::new("z_g")
            .between("unsprung", "ground")
            .ends(vec3(0.05, 0, 0.3), vec3(0.05, 0, 0))
            .gain(kt)
            .rate_gain(ct)
            .units("m"),
    );
    md.add(
        Sensor::new("z_s")
            .between("sprung", "ground")
            .ends(vec3(0, 0.05, 0.6), vec3(0, 0.05, 0)),
    );
    md.add(
        Sensor::new("z_s-z_u")
            .between("unsprung", "sprung")
            .ends(vec3(0.1, 0, 0.3), vec3(0.1, 0, 0.6)),
    );
    md.add(
        Sensor::new("z_u-z_g")
            .between("unsprung", "ground")
            .ends(vec3(0.1, 0, 0.3), vec3(0.1, 0, 0))
            .feedthrough("z_g", -1),
    );
    Ok(())
}

fn top(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [r, m, h, it, ia, g] = [p[0], p[1], p[2], p[3], p[4], p[5]];
    let body = Body::new("top")
        .mass(m)
        .at(vec3(0, 0, h))
        .moments(vec3(it, it, ia))
        .angular_velocity(vec3(0, 0, r));
    md.add(Load::weight(&body, g));
    md.add(body);
    md.add(
        RigidPoint::new("contact")
            .between("top", "ground")
            .forces(3),
    );
    let mgh = m * g * h;
    md.add(
        Actuator::new("L")
            .between("top", "ground")
            .ends(vec3(0, 0, h), vec3(-1, 0, h))
            .twist()
            .units("N m"),
    );
    md.add(
        Sensor::new("mgh phi")
            .between("top", "ground")
            .ends(vec3(0, 0, h), vec3(-1, 0, h))
            .twist()
            .gain(mgh)
            .units("N m"),
    );
    md.add(
        Sensor::new("mgh theta")
            .between("top", "ground")
            .ends(vec3(0, 0, h), vec3(0, -1, h))
            .twist()
            .gain(mgh)
            .units("N m"),
    );
    Ok(())
}

fn disk(md: &mut Model<Expr>, p: &[Expr], _: usize) -> Result<(), CatalogueError> {
    let [u, m, r, g] = [p[0], p[1], p[2], p[3]];
    let a = m * r * r / 4;
    let c = m * r * r / 2;
    let body = Body::new("wheel")
        .mass(m)
        .at(vec3(0, 0, r))
        .moments(vec3(a, c, a))
        .velocity(vec3(u, 0, 0))
        .angular_velocity(vec3(0, u / r, 0));
    md.add(Load::weight(&body, g));
    md.add(body);
    md.add(
        RigidPoint::new("contact")
            .between("wheel", "ground")
            .forces(2)
            .axis(y_axis())
            .rolling_axis(y_axis()),
    );
    md.add(
        NhPoint::new("rolling")
            .between("wheel", "ground")
            .forces(1)
            .axis(y_axis()),
    );
    md.add(
        NhPoint::new("constant speed")
            .between("wheel", "ground")
            .at(vec3(0, 0, r))
            .forces(1)
            .axis(x_axis()),
    );
    md.add(
        Actuator::new("L")
            .between("wheel", "ground")
            .ends(vec3(0, 0, r), vec3(-1, 0, r))
            .twist()
            .units("N m"),
    );
    md.add(
        Sensor::new("mgr phi")
            .between("wheel", "ground")
            .ends(vec3(0, 0, r), vec3(-1, 0, r))
            .twist()
            .gain(m * g * r)
            .units("N m"),
    );
    md.add(
        Sensor::new("mgr r psi dot")
            .between("wheel", "ground")
            .ends(vec3(0, 0, r), vec3(0, 0, r - 1))
            .twist()
            .velocity()
            .gain(m * g * r * r)
            .units("N m^2/s"),
    );
    Ok(())
}

fn chain(md: &mut Model<Expr>, p: &[Expr], n: usize) -> Result<(), CatalogueError> {
    let [m, k, c] = [p[0], p[1], p[2]];
    chain_items(md, &vec![(m, k, c); n]);
    Ok(())
}

/// The items of a chain: mass i on its slider, link i (spring and damper) to mass i − 1 (link 1
/// to ground), the force on and the position of the last mass; `elements[i]` is the mass, the
/// stiffness and the damping of element i + 1.
pub(crate) fn chain_items(md: &mut Model<Expr>, elements: &[(Expr, Expr, Expr)]) {
    let n = elements.len();
    for (i, &(m, k, c)) in elements.iter().enumerate() {
        let name = format!("mass{}", i + 1);
        let x = (i + 1) as i64;
        md.add(Body::new(&name).mass(m).at(vec3(x, 0, 0)));
        md.add(
            RigidPoint::new(&format!("slider{}", i + 1))
                .between(&name, "ground")
                .at(vec3(x, 0, 0))
                .forces(2)
                .moments(3)
                .axis(x_axis()),
        );
        let prev = if i == 0 {
            "ground".to_string()
        } else {
            format!("mass{i}")
        };
        md.add(
            Spring::new(&format!("link{}", i + 1))
                .between(&name, &prev)
                .ends(vec3(x, 0, 0), vec3(x - 1, 0, 0))
                .stiffness(k)
                .damping(c),
        );
    }
    let last = format!("mass{n}");
    let x = n as i64;
    md.add(
        Actuator::new("f")
            .between(&last, "ground")
            .ends(vec3(x, 0, 0), vec3(x - 1, 0, 0)),
    );
    md.add(
        Sensor::new("x")
            .between(&last, "ground")
            .ends(vec3(x, 0, 0), vec3(x - 1, 0, 0)),
    );
}
