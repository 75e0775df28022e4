//! The static preloads `eom analyze` and `eom report` show: for every constraint and elastic
//! item, the force and moment it exerts on its first body at the equilibrium the model's
//! geometry describes (a spring's tension, a joint's reaction), in model axes, and whether
//! the statics determines it.

use crate::format::g;
use eom_model::{Assembled, Item, Statics};
use serde::Serialize;

/// Values smaller than this fraction of the largest of their kind (force or moment) are
/// printed and reported as 0: the statics solves the equilibrium to about this relative
/// accuracy, and smaller values are its rounding.
pub const ROUNDING: f64 = 1e-12;

/// All preloads and how they were found.
#[derive(Clone, Debug, Serialize)]
pub struct Preloads {
    /// `unloaded` (no loads: every preload is 0), `determinate` (force balance alone) or
    /// `indeterminate` (with the elastic compatibility; or minimum norm, see `unique`).
    pub statics: &'static str,
    /// One entry per constraint or elastic item, constraints first.
    pub items: Vec<PreloadReport>,
}

/// The preload of one item.
#[derive(Clone, Debug, Serialize)]
pub struct PreloadReport {
    /// The item, e.g. ``spring `front suspension` ``.
    pub item: String,
    /// The item's first body: the one the force and moment act on.
    pub body: String,
    /// Force on the item's first body, model axes, in N.
    pub force: [f64; 3],
    /// Moment on the item's first body about the item's point (a line item: its end on that
    /// body), model axes, in N m.
    pub moment: [f64; 3],
    /// A line item's tension (positive pulls its ends together; a twist item: the torque).
    pub tension: Option<f64>,
    /// `false` when the statics does not determine it (redundant rigid constraints: any
    /// multiple of their self-stress balances the loads too; the minimum-norm preloads are
    /// used and reported).
    pub unique: bool,
    /// `false` for an item whose preload is not computed (a beam's end loads): the numbers
    /// are then 0 and mean nothing.
    pub computed: bool,
}

/// The columns of the preload table (text and report), in the order of `rows()`' cells.
pub const COLUMNS: [&str; 6] = [
    "item",
    "on body",
    "force [N]",
    "moment [N m]",
    "tension",
    "note",
];

impl Preloads {
    /// The preloads of the assembled `model`, rounding noise set to 0 (see [`ROUNDING`]).
    pub fn of(model: &eom_model::Model<f64>, a: &Assembled<f64>) -> Preloads {
        let first_body = |label: &str| {
            model
                .items()
                .iter()
                .find(|i| format!("{} `{}`", i.kind(), i.name()) == label)
                .and_then(|i| i.bodies().first())
                .map_or_else(String::new, |b| b.to_string())
        };
        let largest = |f: &dyn Fn(&eom_model::Preload<f64>) -> [f64; 3]| {
            a.preloads
                .iter()
                .flat_map(f)
                .fold(0.0f64, |m, x| m.max(x.abs()))
        };
        let fmax = largest(&|p| p.force);
        let mmax = largest(&|p| p.moment);
        let clean =
            |v: [f64; 3], top: f64| v.map(|x| if x.abs() <= ROUNDING * top { 0.0 } else { x });
        Preloads {
            statics: match a.statics {
                Statics::Unloaded => "unloaded",
                Statics::Determinate => "determinate",
                Statics::Indeterminate => "indeterminate",
            },
            items: a
                .preloads
                .iter()
                .map(|p| PreloadReport {
                    item: p.item.clone(),
                    body: first_body(&p.item),
                    force: clean(p.force, fmax),
                    moment: clean(p.moment, mmax),
                    tension: p.tension.map(|t| {
                        if t.abs() <= ROUNDING * fmax.max(mmax) {
                            0.0
                        } else {
                            t
                        }
                    }),
                    unique: p.unique,
                    computed: p.computed,
                })
                .collect(),
        }
    }

    /// The table of the text output: every item that carries a preload (or whose preload is
    /// not unique or not computed), and a count of the others.
    pub fn to_text(&self) -> String {
        let mut t = String::from(
            "Static preloads (force and moment on each item's first body at the given geometry, \
             model axes)\n",
        );
        if self.statics == "unloaded" {
            t.push_str("  none: no loads act on the model\n\n");
            return t;
        }
        let (rows, quiet) = self.rows();
        if rows.is_empty() {
            t.push_str("  every item carries no preload\n");
        } else {
            t.push_str(&crate::format::table(&COLUMNS, &rows, 2));
        }
        if quiet > 0 {
            t.push_str(&format!("  {quiet} other item(s) carry no preload\n"));
        }
        if self.items.iter().any(|p| !p.unique) {
            t.push_str(
                "  not unique: redundant rigid constraints; the minimum-norm preloads are shown \
                 (any multiple of their self-stress balances the loads too)\n",
            );
        }
        t.push('\n');
        t
    }

    /// The rows of the items worth showing, and how many others carry nothing.
    pub fn rows(&self) -> (Vec<Vec<String>>, usize) {
        let mut rows = Vec::new();
        let mut quiet = 0;
        for p in &self.items {
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
}

fn triple(v: &[f64; 3]) -> String {
    format!("({}, {}, {})", g(v[0], 6), g(v[1], 6), g(v[2], 6))
}
