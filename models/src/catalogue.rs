//! The catalogue of built-in models: the model files shipped as `models/*.toml` (embedded in
//! the library and read by the model-file reader, so that each model has one home) and the
//! families with a size, built in Rust (`chainN`, `chainpN`).

use crate::CatalogueError;
use eom_model::file::{self, ParamRange, ParamSpec};
use eom_model::*;
use eom_sym::{Expr, ParamInfo};
use std::sync::OnceLock;

/// Builds a family's items for its size into a model that holds its parameters, which the
/// builder takes by name ([`param`]).
pub(crate) type Builder = fn(&mut Model<Expr>, usize) -> Result<(), CatalogueError>;

/// The parameter `name` of a model being built (by name, never by position): an error naming
/// the model and its parameters where it has none of that name.
pub(crate) fn param(md: &Model<Expr>, name: &str) -> Result<Expr, CatalogueError> {
    md.scope
        .get(name)
        .ok_or_else(|| CatalogueError::UnknownParameter {
            model: md.name.clone(),
            name: name.to_string(),
            known: md.scope.names(),
        })
}

/// A family of built-in models with a size N, built in Rust: the catalogue shows its pattern
/// (`chainN`), a size completes its stem into a model's name (`chain10`).
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// The name the catalogue shows: the stem followed by `N`.
    pub pattern: &'static str,
    /// The catalogue entry for a size (`chainpN` numbers its parameters for it), or as the
    /// catalogue shows it (`None`).
    entry: fn(Option<usize>) -> ModelInfo,
}

impl Family {
    /// The name that a size completes: the pattern without its `N` (`chain`).
    pub fn stem(&self) -> &'static str {
        stem(self.pattern)
    }

    /// The size that `name` gives this family (`chain50` → 50 for `chainN`; 0 for
    /// `chain0`), or `None` where `name` is not the stem and digits; `Err` for a size past
    /// [`MAX_CHAIN`].
    fn size_in(&self, name: &str) -> Option<Result<usize, CatalogueError>> {
        let digits = name.strip_prefix(self.stem())?;
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        Some(
            digits
                .parse::<usize>()
                .ok()
                .filter(|k| *k <= MAX_CHAIN)
                .ok_or_else(|| CatalogueError::ChainTooLong {
                    name: if name.len() > 40 {
                        format!("{}… ({} characters)", &name[..20], name.len())
                    } else {
                        name.to_string()
                    },
                    max: MAX_CHAIN,
                }),
        )
    }
}

/// The families, in catalogue order (after the first seven shipped files); the one
/// declaration of their names. No stem followed by digits is another's (`chainp10` is not
/// `chain` and `p10`).
pub const FAMILIES: [Family; 2] = [
    Family {
        pattern: "chainN",
        entry: chain_entry,
    },
    Family {
        pattern: "chainpN",
        entry: crate::chainp::entry,
    },
];

/// A family's stem: its pattern without the final `N` (a name built in Rust outside the
/// catalogue, such as the Goland wing's, is its own stem).
fn stem(pattern: &str) -> &str {
    pattern.strip_suffix('N').unwrap_or(pattern)
}

/// How an entry is made.
#[derive(Clone, Copy, Debug)]
enum Recipe {
    /// The text of a shipped model file.
    File(&'static str),
    /// A family built in Rust for a size.
    Family(Builder),
}

/// A built-in model.
#[derive(Clone, Debug)]
pub struct ModelInfo {
    /// Name (for a family: its pattern, `chainN`; [`ModelInfo::name_at`] names a size).
    pub name: &'static str,
    /// One-line description.
    pub description: String,
    /// Parameters with defaults, units, descriptions and ranges, in declaration order.
    pub params: Vec<ParamSpec>,
    recipe: Recipe,
}

/// The shipped model files, in the catalogue's order: name and text.
macro_rules! shipped {
    ($($name:literal),* $(,)?) => {
        [$(($name, include_str!(concat!("../", $name, ".toml")))),*]
    };
}

/// The built-in model files (`models/NAME.toml`).
const FILES: [(&str, &str); 16] = shipped!(
    "smd",
    "pendulum",
    "shimmy",
    "bicycle",
    "quarter_car",
    "top",
    "disk",
    "smd_wing",
    "shimmy_wing",
    "shimmy_fin",
    "typical_section",
    "goland_wing",
    "navion",
    "ride_wings",
    "aircraft_ground",
    "truck_trailer",
);

/// Where the families stand in the catalogue: after the first seven files.
const FAMILIES_AT: usize = 7;

/// A shipped file's description and parameters, or why it does not load.
type Declared = Result<(String, Vec<ParamSpec>), String>;

/// The entry of the shipped file `k` (its parameters read once per process).
fn file_entry(k: usize) -> Result<ModelInfo, CatalogueError> {
    static LOADED: [OnceLock<Declared>; FILES.len()] = [const { OnceLock::new() }; FILES.len()];
    let (name, text) = FILES[k];
    let loaded = LOADED[k].get_or_init(|| {
        file::load_str(text, name, &[])
            .map(|l| (l.description, l.params))
            .map_err(|e| e.to_string())
    });
    // A shipped file that does not load is a bug of the library, which the tests catch; it is
    // reported as an error rather than a panic all the same.
    let (description, params) = loaded.clone().map_err(CatalogueError::Shipped)?;
    Ok(ModelInfo {
        name,
        description,
        params,
        recipe: Recipe::File(text),
    })
}

/// A positive parameter of a family.
fn positive(name: &str, default: f64, unit: &str, description: &str) -> ParamSpec {
    ParamSpec {
        name: name.into(),
        value: default,
        default,
        unit: unit.into(),
        description: description.into(),
        range: ParamRange::Positive,
    }
}

/// The family `chainN` (its parameters do not depend on the size).
fn chain_entry(_size: Option<usize>) -> ModelInfo {
    ModelInfo {
        name: "chainN",
        description: "N equal masses in series on sliders, the first tied to ground, spring and \
                      damper in each link (chain10, chain50, ...)"
            .into(),
        params: vec![
            positive("m", 1.0, "kg", "mass of each body"),
            positive("k", 1.0, "N/m", "stiffness of each link"),
            positive("c", 0.1, "N s/m", "damping of each link"),
        ],
        recipe: Recipe::Family(chain),
    }
}

/// All built-in models: the shipped files and the families, in the order `eom list` shows.
pub fn catalogue() -> Vec<ModelInfo> {
    let files = |r: std::ops::Range<usize>| {
        r.map(|k| file_entry(k).unwrap_or_else(|e| panic!("a shipped model file: {e}")))
    };
    files(0..FAMILIES_AT)
        .chain(FAMILIES.iter().map(|f| (f.entry)(None)))
        .chain(files(FAMILIES_AT..FILES.len()))
        .collect()
}

/// The names of the built-in models, families as patterns (`chainN`), in catalogue order
/// (without reading any file).
pub fn names() -> Vec<&'static str> {
    let files = FILES.iter().map(|f| f.0);
    files
        .clone()
        .take(FAMILIES_AT)
        .chain(FAMILIES.iter().map(|f| f.pattern))
        .chain(files.skip(FAMILIES_AT))
        .collect()
}

/// The text of the shipped model file of a built-in model (`None` for a family and an
/// unknown name).
pub fn file_text(name: &str) -> Option<&'static str> {
    FILES.iter().find(|f| f.0 == name).map(|f| f.1)
}

impl ModelInfo {
    /// Whether the entry is a family with a size N (`chainN`), built in Rust.
    pub fn is_family(&self) -> bool {
        matches!(self.recipe, Recipe::Family(_))
    }

    /// The name of the model of `size` (`chain10` for `chainN` at 10); a model that is no
    /// family has its own name whatever the size.
    pub fn name_at(&self, size: usize) -> String {
        if self.is_family() {
            format!("{}{size}", stem(self.name))
        } else {
            self.name.to_string()
        }
    }

    /// An entry of a family, built in Rust.
    pub(crate) fn family(
        name: &'static str,
        description: &str,
        params: Vec<ParamSpec>,
        builder: Builder,
    ) -> Self {
        ModelInfo {
            name,
            description: description.into(),
            params,
            recipe: Recipe::Family(builder),
        }
    }

    /// Build the model with `overrides` replacing defaults (by name); `size` is a family's
    /// size, `name` the model's name (`chain50`).
    pub fn build(
        &self,
        overrides: &[(&str, f64)],
        size: usize,
        name: &str,
    ) -> Result<Model<Expr>, CatalogueError> {
        let values = self.values(overrides, name)?;
        match self.recipe {
            Recipe::File(text) => match file::load_str(text, name, overrides) {
                Ok(loaded) => Ok(loaded.model),
                // A value the overrides give: the user's error, without a file position.
                Err(file::FileError::Override(e)) => Err(CatalogueError::Model(*e)),
                Err(e) => Err(CatalogueError::Shipped(e.to_string())),
            },
            Recipe::Family(builder) => {
                let mut m = Model::new(name);
                for (spec, value) in self.params.iter().zip(values) {
                    m.param_info(ParamInfo {
                        name: spec.name.clone(),
                        nominal: value,
                        unit: Some(spec.unit.clone()),
                        description: Some(spec.description.clone()),
                        assume: spec.range.assumption(),
                    })?;
                }
                builder(&mut m, size)?;
                Ok(m)
            }
        }
    }

    /// Every parameter's value, the last override of its name or its default; an override
    /// of no parameter or out of its parameter's range is an error naming both.
    fn values(&self, overrides: &[(&str, f64)], name: &str) -> Result<Vec<f64>, CatalogueError> {
        for (k, _) in overrides {
            if !self.params.iter().any(|p| p.name == *k) {
                return Err(CatalogueError::UnknownParameter {
                    model: name.to_string(),
                    name: k.to_string(),
                    known: self.params.iter().map(|p| p.name.clone()).collect(),
                });
            }
        }
        self.params
            .iter()
            .map(|spec| {
                let value = overrides
                    .iter()
                    .rev()
                    .find(|(k, _)| *k == spec.name)
                    .map_or(spec.default, |x| x.1);
                if spec.range.contains(value) {
                    Ok(value)
                } else {
                    Err(CatalogueError::BadValue {
                        model: name.to_string(),
                        name: spec.name.clone(),
                        value,
                        problem: out_of_range(spec.range),
                    })
                }
            })
            .collect()
    }
}

/// What a value outside `range` violates.
fn out_of_range(range: ParamRange) -> String {
    match range {
        ParamRange::Positive => "must be positive".into(),
        ParamRange::Nonnegative => "must not be negative".into(),
        ParamRange::Nonzero => "must not be zero".into(),
        ParamRange::Any => "must be finite".into(),
        ParamRange::Interval { .. } => format!("must be finite and in {}", range.text()),
    }
}

/// Largest chain size accepted by name: the size whose `eom analyze` meets the time and
/// memory targets of the performance page (docs/performance.md) (every step grows as the cube of the
/// size). Longer chains can be written as model files.
pub const MAX_CHAIN: usize = 1000;

/// The catalogue entry and size for a model name (`chain50` → the chain entry, 50;
/// `chainp50` → the chain with per-element parameters, 50, its parameters numbered).
pub fn find(name: &str) -> Result<(ModelInfo, usize), CatalogueError> {
    for family in &FAMILIES {
        match family.size_in(name) {
            None | Some(Ok(0)) => continue,
            Some(Ok(size)) => return Ok(((family.entry)(Some(size)), size)),
            Some(Err(e)) => return Err(e),
        }
    }
    match FILES.iter().position(|f| f.0 == name) {
        Some(k) => Ok((file_entry(k)?, 0)),
        None => Err(CatalogueError::UnknownModel {
            name: name.to_string(),
            known: names()
                .into_iter()
                .map(|m| {
                    if FAMILIES.iter().any(|f| f.pattern == m) {
                        format!("{m} (N = 1..{MAX_CHAIN})")
                    } else {
                        m.to_string()
                    }
                })
                .collect(),
        }),
    }
}

/// Build a model by name with parameter overrides.
pub fn build(name: &str, overrides: &[(&str, f64)]) -> Result<Model<Expr>, CatalogueError> {
    let (info, size) = find(name)?;
    info.build(overrides, size, name)
}

fn chain(md: &mut Model<Expr>, n: usize) -> Result<(), CatalogueError> {
    let element = (param(md, "m")?, param(md, "k")?, param(md, "c")?);
    chain_items(md, &vec![element; n]);
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

#[cfg(test)]
mod family_tests {
    use super::*;

    #[test]
    fn each_family_is_its_pattern_and_builds_by_its_names() {
        for family in &FAMILIES {
            let shown = (family.entry)(None);
            assert_eq!(shown.name, family.pattern);
            assert!(family.pattern.ends_with('N') && shown.is_family());
            assert_eq!(shown.name_at(7), format!("{}7", family.stem()));
            let (info, size) = find(&shown.name_at(7)).expect("a size");
            assert_eq!((info.name, size), (family.pattern, 7));
            for bad in ["0", "", "x3"] {
                let name = format!("{}{bad}", family.stem());
                assert!(
                    matches!(find(&name), Err(CatalogueError::UnknownModel { .. })),
                    "{name}"
                );
            }
            let long = format!("{}{}", family.stem(), MAX_CHAIN + 1);
            assert!(matches!(
                find(&long),
                Err(CatalogueError::ChainTooLong { .. })
            ));
        }
        let files: Vec<ModelInfo> = catalogue().into_iter().filter(|m| !m.is_family()).collect();
        assert_eq!(files.len(), FILES.len());
        assert!(files.iter().all(|m| m.name_at(7) == m.name));
        assert_eq!(find("chainp4").expect("chainp4").0.params.len(), 12);
    }
}
