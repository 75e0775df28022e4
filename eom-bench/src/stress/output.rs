//! The outputs of the failure map: the cells as CSV, the counts per region and method as CSV
//! and Markdown, and the SVG map (one panel per method, a row per region, a square per
//! point, coloured by outcome).

use super::classify::Outcome;
use super::{METHODS, StressMap};
use std::fmt::Write;

/// One line per cell: `region,point,value,method,outcome,error,reference,note`.
pub fn cells_csv(map: &StressMap) -> String {
    let mut s = String::from("region,point,value,method,outcome,error,reference,note\n");
    for c in &map.cells {
        let err = c.error.map(|e| format!("{e:.3e}")).unwrap_or_default();
        let _ = writeln!(
            s,
            "{},{},{:e},{},{},{err},{},{}",
            c.region,
            c.point,
            c.value,
            c.method,
            c.outcome.label(),
            c.reference.replace(',', " "),
            c.note
        );
    }
    s
}

/// Counts per region and method: `region,method,accurate,reported,silently_wrong,unchecked`
/// (only the methods that apply to the region).
pub fn counts_csv(map: &StressMap) -> String {
    let mut s = String::from("region,method,accurate,reported,silently_wrong,unchecked\n");
    for r in &map.regions {
        for m in applicable(map, r.name) {
            let c: Vec<String> = Outcome::ALL
                .iter()
                .map(|&o| map.count(r.name, m, o).to_string())
                .collect();
            let _ = writeln!(s, "{},{m},{}", r.name, c.join(","));
        }
    }
    s
}

fn applicable<'a>(map: &StressMap, region: &str) -> Vec<&'a str> {
    METHODS
        .iter()
        .copied()
        .filter(|m| {
            map.cells
                .iter()
                .any(|c| c.region == region && c.method == *m)
        })
        .collect()
}

/// The Markdown table: per region and method, accurate / reported / silently wrong (and
/// unchecked where any), then the regions' descriptions and references.
pub fn markdown(map: &StressMap) -> String {
    let mut s = String::from(
        "Per region and method: accurate / reported failure / **silently wrong** \
         (+ unchecked: no reference). — : method not applicable.\n\n\
         | region | points |",
    );
    for m in METHODS {
        let _ = write!(s, " {m} |");
    }
    s.push_str("\n|---|---:|");
    s.push_str(&"---|".repeat(METHODS.len()));
    s.push('\n');
    let mut totals = vec![[0usize; 4]; METHODS.len()];
    for r in &map.regions {
        let _ = write!(s, "| {} | {} |", r.name, r.values.len());
        for (k, m) in METHODS.iter().enumerate() {
            if !applicable(map, r.name).contains(m) {
                s.push_str(" — |");
                continue;
            }
            let c: Vec<usize> = Outcome::ALL
                .iter()
                .map(|&o| map.count(r.name, m, o))
                .collect();
            for (t, x) in totals[k].iter_mut().zip(&c) {
                *t += x;
            }
            let _ = write!(s, " {}", counts(&c));
        }
        s.push('\n');
    }
    s.push_str("| **total** | |");
    for t in &totals {
        let _ = write!(s, " {}", counts(t));
    }
    s.push_str("\n\n| region | parameter | values | what | reference |\n|---|---|---|---|---|\n");
    for r in &map.regions {
        let (lo, hi) = (r.values[0], r.values[r.values.len() - 1]);
        let _ = writeln!(
            s,
            "| {} | `{}` | {lo:.3e} … {hi:.3e} | {} | {} |",
            r.name,
            r.param,
            r.what,
            r.reference.describe()
        );
    }
    s
}

fn counts(c: &[usize]) -> String {
    let wrong = if c[2] > 0 {
        format!("**{}**", c[2])
    } else {
        "0".into()
    };
    let unchecked = if c[3] > 0 {
        format!(" (+{})", c[3])
    } else {
        String::new()
    };
    format!("{} / {} / {wrong}{unchecked} |", c[0], c[1])
}

/// Colour of an outcome in the map.
fn colour(o: Outcome) -> &'static str {
    match o {
        Outcome::Accurate => "#4caf50",
        Outcome::Reported => "#ffb300",
        Outcome::SilentlyWrong => "#d32f2f",
        Outcome::Unchecked => "#bdbdbd",
    }
}

/// Row height, panel width (a region's points share it), label column width, header height.
const ROW: f64 = 18.0;
const PANEL: f64 = 260.0;
const LABEL: f64 = 300.0;
const TOP: f64 = 50.0;

/// The SVG map: a panel per method, a row per region, a cell per point (left to right in
/// the order of the swept values, the region's points sharing the panel's width), coloured by
/// outcome; each cell's tooltip gives the value, the error and the note.
pub fn svg(map: &StressMap) -> String {
    let panel = PANEL + 20.0;
    let width = LABEL + METHODS.len() as f64 * panel + 10.0;
    let height = TOP + map.regions.len() as f64 * ROW + 40.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         font-family=\"sans-serif\" font-size=\"11\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <text x=\"4\" y=\"16\" font-size=\"13\">eom failure map: each cell a point (swept \
         value increasing to the right), each panel a method</text>\n"
    );
    for (i, r) in map.regions.iter().enumerate() {
        let y = TOP + i as f64 * ROW;
        let (lo, hi) = (r.values[0], r.values[r.values.len() - 1]);
        let range = if lo == hi {
            format!("{lo:e}")
        } else {
            format!("{lo:.0e} … {hi:.0e}")
        };
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}: {} = {range}</text>",
            LABEL - 6.0,
            y + ROW - 5.0,
            r.name,
            r.param
        );
    }
    for (k, m) in METHODS.iter().enumerate() {
        let x0 = LABEL + k as f64 * panel;
        let _ = writeln!(
            s,
            "<text x=\"{x0}\" y=\"{}\" font-weight=\"bold\">{m}</text>",
            TOP - 8.0
        );
        for (i, r) in map.regions.iter().enumerate() {
            let y = TOP + i as f64 * ROW;
            let cell = PANEL / r.values.len() as f64;
            for c in map
                .cells
                .iter()
                .filter(|c| c.region == r.name && c.method == *m)
            {
                let x = x0 + c.point as f64 * cell;
                let err = c
                    .error
                    .map(|e| format!(", error {e:.2e}"))
                    .unwrap_or_default();
                let _ = writeln!(
                    s,
                    "<rect x=\"{x:.1}\" y=\"{y}\" width=\"{:.1}\" height=\"{}\" fill=\"{}\" \
                     stroke=\"white\" stroke-width=\"0.5\"><title>{} {} = {:e}: {}{err} {}</title></rect>",
                    cell,
                    ROW,
                    colour(c.outcome),
                    r.name,
                    r.param,
                    c.value,
                    c.outcome.label(),
                    escape(&c.note)
                );
            }
        }
    }
    let y = TOP + map.regions.len() as f64 * ROW + 20.0;
    let mut x = LABEL;
    for o in Outcome::ALL {
        let _ = writeln!(
            s,
            "<rect x=\"{x}\" y=\"{}\" width=\"12\" height=\"12\" fill=\"{}\"/>\
             <text x=\"{}\" y=\"{y}\">{}</text>",
            y - 10.0,
            colour(o),
            x + 16.0,
            o.label()
        );
        x += 130.0;
    }
    s.push_str("</svg>\n");
    s
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
