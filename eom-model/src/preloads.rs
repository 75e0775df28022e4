//! The static preloads as reported (by `eom analyze`, `eom report` and the Python package):
//! for every constraint and elastic item, the force and moment it exerts on its first body at
//! the equilibrium the model's geometry describes, in model axes, with the statics' rounding
//! noise set to 0, and whether the statics determines it.

use crate::Model;
use crate::assemble::{Assembled, Preload, Statics};
use crate::items::Item;
use serde::Serialize;

/// Values smaller than this fraction of the largest of their kind (force or moment) are
/// reported as 0: the statics solves the equilibrium to about this relative accuracy, and
/// smaller values are its rounding.
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

impl Preloads {
    /// The preloads of the assembled `model`, rounding noise set to 0 (see [`ROUNDING`]).
    pub fn of(model: &Model<f64>, a: &Assembled<f64>) -> Preloads {
        let first_body = |label: &str| {
            model
                .items()
                .iter()
                .find(|i| format!("{} `{}`", i.kind(), i.name()) == label)
                .and_then(|i| i.bodies().first())
                .map_or_else(String::new, |b| b.to_string())
        };
        let largest = |f: &dyn Fn(&Preload<f64>) -> [f64; 3]| {
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
}
