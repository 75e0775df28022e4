//! Rounding error of the generated code's entries of A and B against a double-double
//! evaluation of the same symbolic formulas, over random points: the measure by which the
//! peers' generated code is compared (`bench/pydy/accuracy.py` measures PyDy's C the same
//! way).
//!
//! Three figures, over every entry that is not a structural zero and every point:
//! * entry-wise, of A and of B separately: `|Δ| / |ref|`, leaving out entries whose reference
//!   is below 1e-20 of their row (zero in exact arithmetic, rounding noise in any code);
//! * row-scaled: `|Δ| / max |ref|` over the entry's row of `[A B]` — the error relative to the
//!   size of the equation the entry belongs to, which is what the state derivative sees.
//!
//! Entry-wise figures are dominated by entries whose value passes near zero inside the box;
//! the row-scaled one is the meaningful comparison of two codes' formulas.

use super::generated::Ab;
use super::reference::ReferenceModel;
use super::{WorkPrecisionError, points};
use eom_model::Linearizer;
use eom_sym::Dd;
use std::fmt::Write;

/// The rounding error of one generated module over the points.
#[derive(Clone, Debug, PartialEq)]
pub struct EntryErrors {
    /// Model name.
    pub model: String,
    /// The module's label ("generated f64", …).
    pub method: String,
    /// Largest entry-wise relative error of A.
    pub a_entrywise: f64,
    /// Largest entry-wise relative error of B (0 for a model without inputs).
    pub b_entrywise: f64,
    /// Largest row-scaled error of `[A B]`.
    pub row_scaled: f64,
    /// Where the row-scaled error is largest: `("A" or "B", row, column)`.
    pub worst: (&'static str, usize, usize),
    /// Where the entry-wise error of A is largest, and the reference value there.
    pub worst_a: (usize, usize, f64),
    /// Points compared (the module's reported failures are left out).
    pub points: usize,
}

/// The entry errors of the symbolic reduction on the tape and of every generated module of
/// `model` at `n` random points within
/// ±`spread` of nominal (the work-precision benchmark's points for the same seed).
pub fn entry_errors(
    model: &str,
    n: usize,
    spread: f64,
    seed: u64,
) -> Result<Vec<EntryErrors>, WorkPrecisionError> {
    let built = models::build(model, &[])
        .map_err(|e| WorkPrecisionError::Catalogue(model.into(), e.to_string()))?;
    let sym = Linearizer::new(&built).symbolic()?;
    let refm = ReferenceModel::new(&sym);
    let pts = points(&built.scope.nominal_values(), n, spread, seed);
    let refs: Vec<RefAb> = pts
        .iter()
        .map(|p| Ok((refm.a_dd(p)?, refm.b_dd(p)?)))
        .collect::<Result<_, WorkPrecisionError>>()?;
    let ss = sym.state_space();
    let nz_a: Vec<(usize, usize)> = nonzeros(ss.a.nrows(), ss.a.ncols(), |i, j| ss.a[(i, j)]);
    let nz_b: Vec<(usize, usize)> = nonzeros(ss.b.nrows(), ss.b.ncols(), |i, j| ss.b[(i, j)]);
    let tape = |p: &[f64]| sym.evaluate(p).ok().map(|ss| (ss.a, ss.b));
    let mut rows = vec![measure(
        model,
        "symbolic (tape)",
        &tape,
        &pts,
        &refs,
        &nz_a,
        &nz_b,
    )];
    for k in super::generated::kernels(model) {
        rows.push(measure(model, k.label, &k.ab, &pts, &refs, &nz_a, &nz_b));
    }
    Ok(rows)
}

/// A and B at a point, `None` for a reported failure.
type AbAt<'a> = dyn Fn(&[f64]) -> Option<Ab> + 'a;

/// The double-double A and B at one point, as rows.
type RefAb = (Vec<Vec<Dd>>, Vec<Vec<Dd>>);

fn nonzeros(
    rows: usize,
    cols: usize,
    at: impl Fn(usize, usize) -> eom_sym::Expr,
) -> Vec<(usize, usize)> {
    (0..cols)
        .flat_map(|j| (0..rows).map(move |i| (i, j)))
        .filter(|&(i, j)| !at(i, j).is_zero())
        .collect()
}

fn measure(
    model: &str,
    label: &str,
    ab: &AbAt<'_>,
    pts: &[Vec<f64>],
    refs: &[RefAb],
    nz_a: &[(usize, usize)],
    nz_b: &[(usize, usize)],
) -> EntryErrors {
    let mut out = EntryErrors {
        model: model.into(),
        method: label.into(),
        a_entrywise: 0.0,
        b_entrywise: 0.0,
        row_scaled: 0.0,
        worst: ("A", 0, 0),
        worst_a: (0, 0, 0.0),
        points: 0,
    };
    for (p, (ra, rb)) in pts.iter().zip(refs) {
        let Some((a, b)) = ab(p) else { continue };
        out.points += 1;
        let entries = nz_a
            .iter()
            .map(|&(i, j)| ("A", i, j, a[(i, j)], ra[i][j]))
            .chain(nz_b.iter().map(|&(i, j)| ("B", i, j, b[(i, j)], rb[i][j])));
        let rowmax = |i: usize| {
            nz_a.iter()
                .filter(|e| e.0 == i)
                .map(|&(_, j)| ra[i][j].to_f64().abs())
                .chain(
                    nz_b.iter()
                        .filter(|e| e.0 == i)
                        .map(|&(_, j)| rb[i][j].to_f64().abs()),
                )
                .fold(0.0f64, f64::max)
        };
        for (mat, i, j, got, want) in entries {
            let scale = rowmax(i);
            let d = (Dd::from_f64(got) - want).to_f64().abs();
            if scale > 0.0 && d / scale > out.row_scaled {
                out.row_scaled = d / scale;
                out.worst = (mat, i, j);
            }
            let w = want.to_f64().abs();
            if w > 1e-20 * scale {
                if mat == "B" {
                    out.b_entrywise = out.b_entrywise.max(d / w);
                } else if d / w > out.a_entrywise {
                    out.a_entrywise = d / w;
                    out.worst_a = (i, j, want.to_f64());
                }
            }
        }
    }
    out
}

/// A Markdown table of the entry errors.
pub fn markdown(rows: &[EntryErrors]) -> String {
    let mut s = String::from(
        "| model | code | A entry-wise | (at, value there) | B entry-wise | row-scaled [A B] | (at) | points |\n\
         |---|---|---:|---|---:|---:|---|---:|\n",
    );
    for r in rows {
        writeln!(
            s,
            "| {} | {} | {:.1e} | A[{}, {}] = {:.3} | {:.1e} | {:.1e} | {}[{}, {}] | {} |",
            r.model,
            r.method,
            r.a_entrywise,
            r.worst_a.0,
            r.worst_a.1,
            r.worst_a.2,
            r.b_entrywise,
            r.row_scaled,
            r.worst.0,
            r.worst.1,
            r.worst.2,
            r.points
        )
        .expect("write to a String");
    }
    s
}

/// The entry errors as CSV (one row per model and code).
pub fn csv(rows: &[EntryErrors]) -> String {
    let mut s =
        String::from("model,method,a_entrywise,b_entrywise,row_scaled,worst_row_scaled,points\n");
    for r in rows {
        writeln!(
            s,
            "{},{},{:e},{:e},{:e},{}[{} {}],{}",
            r.model,
            r.method,
            r.a_entrywise,
            r.b_entrywise,
            r.row_scaled,
            r.worst.0,
            r.worst.1,
            r.worst.2,
            r.points
        )
        .expect("write to a String");
    }
    s
}
