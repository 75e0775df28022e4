//! `chainpN`: the chain of `chainN` with its own mass, stiffness and damping per element —
//! `m1 … mN`, `k1 … kN`, `c1 … cN`, 3N parameters (150 for 50 masses), the chain that other
//! tools' code generators are benchmarked on. At the defaults (every element 1 kg, 1 N/m,
//! 0.1 N s/m) it is `chainN` at its defaults.

use crate::CatalogueError;
use crate::catalogue::{MAX_CHAIN, ModelInfo, ParamSpec, p};
use eom_model::Model;
use eom_sym::Expr;
use std::sync::OnceLock;

/// The catalogue entry: the pattern, with its parameters shown as `mI`, `kI`, `cI` (`find`
/// numbers them for a size).
pub(crate) fn entry() -> ModelInfo {
    ModelInfo::new(
        "chainpN",
        "chainN with its own mass, stiffness and damping per element: 3N parameters (chainp50 has 150)",
        vec![
            p("mI", 1.0, "kg", "mass of body I (m1 … mN)"),
            p(
                "kI",
                1.0,
                "N/m",
                "stiffness of link I (k1 … kN; link 1 to ground)",
            ),
            p("cI", 0.1, "N s/m", "damping of link I (c1 … cN)"),
        ],
        build,
    )
}

/// The numbered names and descriptions (`m7`, "mass of body 7"), made once for the largest
/// chain: the catalogue's parameter specifications hold `&'static str`.
struct Numbered {
    names: Vec<String>,
    descriptions: Vec<String>,
}

/// The stems of the parameters, in order, with what each is.
const STEMS: [(&str, &str); 3] = [
    ("m", "mass of body"),
    ("k", "stiffness of link"),
    ("c", "damping of link"),
];

fn numbered() -> &'static Numbered {
    static TABLE: OnceLock<Numbered> = OnceLock::new();
    TABLE.get_or_init(|| {
        let (mut names, mut descriptions) = (Vec::new(), Vec::new());
        for (stem, what) in STEMS {
            for i in 1..=MAX_CHAIN {
                names.push(format!("{stem}{i}"));
                descriptions.push(format!("{what} {i}"));
            }
        }
        Numbered {
            names,
            descriptions,
        }
    })
}

/// The parameters of the chain of `n` elements (at most [`MAX_CHAIN`]): `m1 … mn`, then
/// `k1 … kn`, then `c1 … cn`.
pub(crate) fn params(n: usize) -> Vec<ParamSpec> {
    let table = numbered();
    let pattern = entry().params;
    let mut out = Vec::with_capacity(3 * n);
    for (s, spec) in pattern.iter().enumerate() {
        out.extend((0..n.min(MAX_CHAIN)).map(|i| ParamSpec {
            name: &table.names[s * MAX_CHAIN + i],
            description: &table.descriptions[s * MAX_CHAIN + i],
            ..spec.clone()
        }));
    }
    out
}

fn build(md: &mut Model<Expr>, ps: &[Expr], n: usize) -> Result<(), CatalogueError> {
    let elements: Vec<(Expr, Expr, Expr)> =
        (0..n).map(|i| (ps[i], ps[n + i], ps[2 * n + i])).collect();
    crate::catalogue::chain_items(md, &elements);
    Ok(())
}
