//! The CSV and Markdown outputs of the work-precision benchmark.

use super::Row;
use std::fmt::Write;

fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3e}")
    } else {
        String::new()
    }
}

/// `model,method,time_ns,matrix_err,eig_err,nonzero_eig_err,published_err,failures,points`;
/// empty fields where a value does not apply.
pub fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "model,method,time_ns,matrix_err,eig_err,nonzero_eig_err,published_err,failures,points\n",
    );
    for r in rows {
        writeln!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            r.model,
            r.method,
            num(r.time_ns),
            r.matrix_err.map(num).unwrap_or_default(),
            num(r.eig_err),
            num(r.nonzero_eig_err),
            r.published_err.map(num).unwrap_or_default(),
            r.failures,
            r.points
        )
        .expect("write to a String");
    }
    s
}

/// A time in ns with a readable unit.
pub fn time(ns: f64) -> String {
    if !ns.is_finite() {
        "—".into()
    } else if ns < 1e3 {
        format!("{ns:.0} ns")
    } else if ns < 1e6 {
        format!("{:.1} µs", ns / 1e3)
    } else {
        format!("{:.1} ms", ns / 1e6)
    }
}

fn err(x: Option<f64>) -> String {
    match x {
        Some(x) if x.is_finite() => format!("{x:.1e}"),
        Some(_) => "failed".into(),
        None => "—".into(),
    }
}

/// A Markdown table of every row, then the fastest method within `tol` per model.
pub fn markdown(rows: &[Row], tol: f64) -> String {
    let mut s = String::from(
        "| model | method | time per A | A error | eigenvalue error | without structural zeros | published error | failures / points |\n\
         |---|---|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in rows {
        let eig = |x: f64| {
            if r.points == 0 {
                "—".into()
            } else {
                err(Some(x))
            }
        };
        writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            r.model,
            r.method,
            time(r.time_ns),
            err(r.matrix_err),
            eig(r.eig_err),
            eig(r.nonzero_eig_err),
            err(r.published_err),
            if r.points == 0 && r.failures == 0 {
                "—".to_string()
            } else {
                format!("{} / {}", r.failures, r.failures + r.points)
            }
        )
        .expect("write to a String");
    }
    writeln!(
        s,
        "\nFastest method with eigenvalue error within {tol:.0e}:\n"
    )
    .expect("write");
    writeln!(s, "| model | method | time per A |\n|---|---|---:|").expect("write");
    let models: Vec<&str> = rows.iter().fold(Vec::new(), |mut v, r| {
        if !v.contains(&r.model.as_str()) {
            v.push(r.model.as_str());
        }
        v
    });
    let best = super::fastest_within(rows, tol);
    for m in models {
        match best.iter().find(|r| r.model == m) {
            Some(r) => writeln!(s, "| {m} | {} | {} |", r.method, time(r.time_ns)),
            None => writeln!(s, "| {m} | none | — |"),
        }
        .expect("write");
    }
    s
}
