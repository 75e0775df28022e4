//! The static preloads' table of `eom analyze` and `eom report`: the preloads themselves
//! (for every constraint and elastic item, the force and moment it exerts on its first body
//! at the equilibrium the model's geometry describes) are `eom_model::preloads`, shared with
//! the Python package.

use crate::format::g;
pub use eom_model::preloads::Preloads;

/// The columns of the preload table (text and report), in the order of [`rows`]' cells.
pub const COLUMNS: [&str; 6] = [
    "item",
    "on body",
    "force [N]",
    "moment [N m]",
    "tension",
    "note",
];

/// The table of the text output: every item that carries a preload (or whose preload is
/// not unique or not computed), and a count of the others.
pub fn to_text(preloads: &Preloads) -> String {
    let mut t = String::from(
        "Static preloads (force and moment on each item's first body at the given geometry, \
         model axes)\n",
    );
    if preloads.statics == "unloaded" {
        t.push_str("  none: no loads act on the model\n\n");
        return t;
    }
    let (rows, quiet) = rows(preloads);
    if rows.is_empty() {
        t.push_str("  every item carries no preload\n");
    } else {
        t.push_str(&crate::format::table(&COLUMNS, &rows, 2));
    }
    if quiet > 0 {
        t.push_str(&format!("  {quiet} other item(s) carry no preload\n"));
    }
    if preloads.items.iter().any(|p| !p.unique) {
        t.push_str(
            "  not unique: redundant rigid constraints; the minimum-norm preloads are shown \
             (any multiple of their self-stress balances the loads too)\n",
        );
    }
    t.push('\n');
    t
}

/// The rows of the items worth showing, and how many others carry nothing.
pub fn rows(preloads: &Preloads) -> (Vec<Vec<String>>, usize) {
    let mut rows = Vec::new();
    let mut quiet = 0;
    for p in &preloads.items {
        let zero = p.force.iter().chain(&p.moment).all(|x| *x == 0.0);
        if zero && p.unique && p.computed {
            quiet += 1;
            continue;
        }
        let note = match (p.computed, p.unique) {
            (false, _) => "not computed (beam end loads)",
            (true, false) => "not unique (minimum norm)",
            _ => "",
        };
        rows.push(vec![
            p.item.clone(),
            p.body.clone(),
            triple(&p.force),
            triple(&p.moment),
            p.tension.map_or_else(|| "-".into(), |x| g(x, 6)),
            note.to_string(),
        ]);
    }
    (rows, quiet)
}

fn triple(v: &[f64; 3]) -> String {
    format!("({}, {}, {})", g(v[0], 6), g(v[1], 6), g(v[2], 6))
}
