//! `chainpN`: the chain of `chainN` with its own mass, stiffness and damping per element —
//! `m1 … mN`, `k1 … kN`, `c1 … cN`, 3N parameters (150 for 50 masses), the chain that other
//! tools' code generators are benchmarked on. At the defaults (every element 1 kg, 1 N/m,
//! 0.1 N s/m) it is `chainN` at its defaults.

use crate::CatalogueError;
use crate::catalogue::{ModelInfo, param};
use eom_model::Model;
use eom_model::file::{ParamRange, ParamSpec};
use eom_sym::Expr;

/// The stems of the parameters, in order: stem, default, unit, what each is.
const STEMS: [(&str, f64, &str, &str); 3] = [
    ("m", 1.0, "kg", "mass of body"),
    ("k", 1.0, "N/m", "stiffness of link"),
    ("c", 0.1, "N s/m", "damping of link"),
];

/// A parameter of the family: `name` with the stem's default, unit and range.
fn spec(stem: usize, name: String, description: String) -> ParamSpec {
    let (_, default, unit, _) = STEMS[stem];
    ParamSpec {
        name,
        value: default,
        default,
        unit: unit.into(),
        description,
        range: ParamRange::Positive,
    }
}

/// The catalogue entry: for a size, with its parameters numbered; without, the pattern with
/// its parameters shown as `mI`, `kI`, `cI`.
pub(crate) fn entry(size: Option<usize>) -> ModelInfo {
    let shown = [
        "mass of body I (m1 … mN)",
        "stiffness of link I (k1 … kN; link 1 to ground)",
        "damping of link I (c1 … cN)",
    ];
    let params = match size {
        Some(n) => params(n),
        None => (0..3)
            .map(|s| spec(s, format!("{}I", STEMS[s].0), shown[s].into()))
            .collect(),
    };
    ModelInfo::family(
        "chainpN",
        "chainN with its own mass, stiffness and damping per element: 3N parameters (chainp50 has 150)",
        params,
        build,
    )
}

/// The parameters of the chain of `n` elements: `m1 … mn`, then `k1 … kn`, then `c1 … cn`.
fn params(n: usize) -> Vec<ParamSpec> {
    let mut out = Vec::with_capacity(3 * n);
    for (s, (stem, _, _, what)) in STEMS.iter().enumerate() {
        out.extend((1..=n).map(|i| spec(s, format!("{stem}{i}"), format!("{what} {i}"))));
    }
    out
}

fn build(md: &mut Model<Expr>, n: usize) -> Result<(), CatalogueError> {
    let p = |stem: usize, i: usize| param(md, &format!("{}{i}", STEMS[stem].0));
    let elements = (1..=n)
        .map(|i| Ok((p(0, i)?, p(1, i)?, p(2, i)?)))
        .collect::<Result<Vec<_>, CatalogueError>>()?;
    crate::catalogue::chain_items(md, &elements);
    Ok(())
}
