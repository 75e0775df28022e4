//! The sections of the report, each from the results the CLI commands print.

use super::CLOSED_FORM_STATES;
use super::html::Page;
use crate::analyze::{Analysis, ModeReport};
use crate::error::CliError;
use crate::format::{ReIm, eigenvalue, g};
use crate::params::{ModelChoice, SweepSpec};
use crate::pictures;
use crate::plot;
use crate::sweep::SweepReport;
use eom_model::items::Item;
use eom_model::{Linearization, Model};
use num_complex::Complex64;

/// Significant digits in the tables.
const SIG: usize = 6;

/// What every section reads.
pub struct Context<'a> {
    pub choice: &'a ModelChoice,
    pub analysis: &'a Analysis,
    pub lin: &'a Linearization,
    pub model: &'a Model<f64>,
}

fn z(r: &ReIm) -> Complex64 {
    Complex64::new(r.re, r.im)
}

fn opt(x: Option<f64>, none: &str) -> String {
    x.map_or_else(|| none.to_string(), |v| g(v, SIG))
}

/// Parameters, bodies, items and the picture of the model.
pub fn model(p: &mut Page, cx: &Context<'_>) {
    let a = cx.analysis;
    p.section("parameters", "Parameters");
    let rows: Vec<Vec<String>> = a
        .parameters
        .iter()
        .zip(&a.parameter_units)
        .map(|((n, v), (_, u))| vec![n.clone(), g(*v, 10), u.clone()])
        .collect();
    p.table(&["parameter", "value", "unit"], &rows, 1);
    p.section("items", "Bodies and items");
    let bodies: Vec<Vec<String>> = cx
        .model
        .bodies
        .iter()
        .map(|b| {
            let l = b.location;
            vec![
                b.name.to_string(),
                g(b.mass, SIG),
                format!("({}, {}, {})", g(l[0], 4), g(l[1], 4), g(l[2], 4)),
            ]
        })
        .collect();
    p.table(&["body", "mass [kg]", "mass centre [m]"], &bodies, 1);
    let items: Vec<Vec<String>> = cx
        .model
        .items()
        .iter()
        .map(|i| {
            let between: Vec<String> = i.bodies().iter().map(|b| b.to_string()).collect();
            vec![
                i.kind().to_string(),
                i.name().to_string(),
                between.join(" – "),
            ]
        })
        .collect();
    p.table(&["item", "name", "between"], &items, 3);
    let sig = |s: &[crate::analyze::Signal]| {
        s.iter()
            .map(|x| crate::plot::with_unit(&x.name, &x.unit))
            .collect::<Vec<_>>()
            .join(", ")
    };
    p.text(&format!(
        "inputs: {}; outputs: {}",
        or_none(&sig(&a.inputs)),
        or_none(&sig(&a.outputs))
    ));
    p.section("picture", "The model");
    p.figure(
        &pictures::model_svg(&cx.choice.name, cx.model),
        "The model from its geometry: mass centres (dots, named), the bodies' points of \
         attachment (lines from the mass centre), line items (lighter lines), ground points \
         (triangles).",
    );
}

/// The static preloads: every item's force and moment on its first body.
pub fn preloads(p: &mut Page, cx: &Context<'_>) {
    p.section("preloads", "Static preloads");
    let Some(pre) = &cx.analysis.preloads else {
        p.note("Not computed (see the warnings).");
        return;
    };
    if pre.statics == "unloaded" {
        p.text("None: no loads act on the model.");
        return;
    }
    p.text(&format!(
        "The force and moment each constraint and elastic item exerts on its first body at the \
         equilibrium the model's geometry describes, in model axes (moments about the item's \
         point; a spring's tension positive when it pulls). The statics is {}.",
        pre.statics
    ));
    let (rows, quiet) = crate::preloads::rows(pre);
    if !rows.is_empty() {
        p.table(&crate::preloads::COLUMNS, &rows, 2);
    }
    if quiet > 0 {
        p.text(&format!("{quiet} other item(s) carry no preload."));
    }
    if pre.items.iter().any(|x| !x.unique) {
        p.note(
            "Not unique: the model has redundant rigid constraints, and any multiple of their \
             self-stress balances the loads too; the minimum-norm preloads are shown.",
        );
    }
}

fn or_none(s: &str) -> String {
    if s.is_empty() {
        "none".into()
    } else {
        s.into()
    }
}

fn mode_rows(modes: &[ModeReport]) -> Vec<Vec<String>> {
    modes
        .iter()
        .filter(|m| !(m.kind == "oscillatory" && m.eigenvalue.im < 0.0))
        .enumerate()
        .map(|(k, m)| {
            vec![
                (k + 1).to_string(),
                eigenvalue(crate::analyze_text::shown(m), SIG, m.kind == "oscillatory"),
                g(m.natural_frequency_hz, SIG),
                opt(m.damping_ratio, "–"),
                opt(m.time_constant, "∞"),
                opt(m.period, "–"),
                m.kind.to_string(),
                m.stability.to_string(),
            ]
        })
        .collect()
}

const MODE_HEAD: [&str; 8] = [
    "#",
    "eigenvalue [1/s]",
    "frequency [Hz]",
    "damping ratio",
    "time constant [s]",
    "period [s]",
    "kind",
    "stability",
];

/// The modes table, the pole map and every mode's shape.
pub fn modes(p: &mut Page, cx: &Context<'_>) -> Result<(), CliError> {
    let a = cx.analysis;
    p.section("modes", "Modes");
    p.table(&MODE_HEAD, &mode_rows(&a.modes), 1);
    for s in &a.structural_zeros {
        p.text(&format!("structural zero eigenvalue: {s}"));
    }
    p.figure(
        &plot::poles::pole_map_of(a)?.svg,
        "Poles and transmission zeros in the complex plane.",
    );
    let ss = &cx.lin.state_space;
    let modes = pictures::modes_of(ss, cx.lin.structural_zeros.len())?;
    let drawable = pictures::drawable_modes(&modes);
    if ss.phys.nrows() == 0 || drawable.is_empty() {
        p.note("No mode moves a body (or the model has no map to the bodies' coordinates): no mode shapes.");
        return Ok(());
    }
    p.section("shapes", "Mode shapes");
    p.text(
        "Each mode drawn from the model's geometry: grey at rest, blue at the two extremes of \
         the motion (solid and dashed), red animated through one cycle; red rings with a cross \
         mark the centres of rotation in each view. Amplitudes are scaled for the drawing.",
    );
    for k in drawable {
        let svg = pictures::mode_shape_svg(&cx.choice.name, cx.model, ss, &modes, k)?;
        let m = pictures::mode_at(&modes, k, "mode")?;
        p.figure(&svg, &pictures::mode_heading(k, m));
    }
    Ok(())
}

/// The minimal realization, steady-state gains and transmission zeros.
pub fn io_view(p: &mut Page, cx: &Context<'_>) {
    let a = cx.analysis;
    p.section("io", "Modes seen from the inputs and outputs");
    match &a.minimal {
        Some(m) => {
            p.text(&format!(
                "The minimal realization has {} of the {} states.",
                m.states, a.states
            ));
            p.table(&MODE_HEAD, &mode_rows(&m.modes), 1);
            let removed: Vec<Vec<String>> = m
                .removed
                .iter()
                .map(|r| {
                    vec![
                        eigenvalue(z(&r.eigenvalue), SIG, false),
                        r.reason.to_string(),
                        r.stability.to_string(),
                        r.note.clone(),
                    ]
                })
                .collect();
            if !removed.is_empty() {
                p.table(
                    &["removed eigenvalue", "reason", "stability", "meaning"],
                    &removed,
                    4,
                );
            }
        }
        None => match &a.minimal_note {
            Some(note) => p.note(&format!("Minimal realization: {note}.")),
            None => p.note("The minimal realization could not be computed (see the warnings)."),
        },
    }
    p.section("gains", "Steady-state gains");
    match &a.steady_state_gain {
        Some(gains) => {
            let rows: Vec<Vec<String>> = gains
                .iter()
                .map(|e| {
                    let value = match (e.shown(), &e.integrating) {
                        (Some((v, None)), _) => g(v, SIG),
                        (Some((v, Some(err))), _) => format!(
                            "{} (computed {}, within its error estimate {})",
                            g(v, SIG),
                            g(e.value.unwrap_or(v), 3),
                            g(err, 2)
                        ),
                        (None, Some(i)) => format!(
                            "integrating (order {}, slope {})",
                            i.order,
                            g(i.coefficient, SIG)
                        ),
                        _ => "–".into(),
                    };
                    vec![e.output.clone(), e.input.clone(), value, e.unit.clone()]
                })
                .collect();
            p.table(&["output", "input", "gain", "unit"], &rows, 2);
        }
        None => p.note("Not computed (see the warnings)."),
    }
    p.section("zeros", "Transmission zeros");
    match &a.zeros {
        Some(zs) if zs.is_empty() => p.text("none"),
        Some(zs) => {
            let rows: Vec<Vec<String>> = zs
                .iter()
                .map(|r| vec![eigenvalue(z(r), SIG, false)])
                .collect();
            p.table(&["zero [1/s]"], &rows, 0);
        }
        None => p.text("not defined (no inputs or no outputs) or not computed"),
    }
}

/// Bode plot and time responses.
pub fn responses(p: &mut Page, cx: &Context<'_>) -> Result<(), CliError> {
    let a = cx.analysis;
    let ss = &cx.lin.state_space;
    if ss.inputs() == 0 || ss.outputs() == 0 {
        return Ok(());
    }
    p.section("bode", "Frequency response");
    p.figure(
        &plot::bode::bode_of(a)?.svg,
        "Magnitude and phase of every output/input pair.",
    );
    p.section("time", "Time responses");
    let st = pictures::step_impulse_plot(&cx.choice.name, ss)?;
    p.figure(
        &st.svg,
        "Unit step and impulse responses (exact zero-order-hold discretisation; the span from \
         the slowest mode).",
    );
    let modes = pictures::modes_of(ss, cx.lin.structural_zeros.len())?;
    if let Some(k) = pictures::default_mode(&modes) {
        let plot = pictures::initial_plot(&cx.choice.name, ss, &modes, k)?;
        p.figure(
            &plot.svg,
            &format!(
                "Free response started in mode {k} alone (x₀ = Re v, v its eigenvector): {}",
                pictures::mode_heading(k, pictures::mode_at(&modes, k, "mode")?)
            ),
        );
    }
    Ok(())
}

/// Above this many states the report leaves the reduction out (its Gramian factors cost
/// O(n³) with a large constant; `eom reduce` still does it).
const REDUCTION_STATES: usize = 400;

/// A reduced model (balanced truncation to the default order): the Hankel singular values with
/// the bound per order, the error, the modes kept.
pub fn reduction(
    p: &mut Page,
    cx: &Context<'_>,
    overrides: &[(String, f64)],
) -> Result<(), CliError> {
    let ss = &cx.lin.state_space;
    if ss.inputs() == 0 || ss.outputs() == 0 || ss.states() == 0 {
        return Ok(());
    }
    p.section("reduction", "Reduced model");
    if ss.states() > REDUCTION_STATES {
        p.note(&format!(
            "{} states: the reduction is left out of the report (eom reduce does it).",
            ss.states()
        ));
        return Ok(());
    }
    let req = crate::reduce::ReduceRequest {
        method: eom_num::model_reduction::ReductionMethod::Balanced,
        order: None,
        tol: None,
        band: None,
        linearization: cx.lin.method,
    };
    let (r, _) = crate::reduce::report_of(cx.choice, overrides, cx.lin, &req)?;
    p.text(&format!(
        "Balanced truncation of the stable part ({} kept whole: zero, marginal and unstable \
         modes, {} structural zeros) to the smallest order whose bound 2·Σσ is below \
         1e-3 σ₁: {} of {} states. Bound {}, error measured on {} frequencies {} (at {} Hz), \
         steady-state gain error {}.",
        r.kept_whole,
        r.structural_zeros,
        r.states,
        r.full_states,
        r.bound.map_or("none".into(), |b| g(b, SIG)),
        r.measured.points,
        g(r.measured.hinf, SIG),
        g(r.measured.at_hz, SIG),
        g(r.measured.dc, SIG)
    ));
    if !r.hankel_singular_values.is_empty() {
        p.figure(
            &plot::hankel::hankel_plot(&r)?.svg,
            "Hankel singular values of the stable part, at the order that keeps each, and the \
             bound 2·Σσ beyond every order.",
        );
    }
    let (head, rows) = r.modes_table();
    p.table(&head, &rows, 1);
    Ok(())
}

/// The sweep: eigenvalues over the parameter with the zoom, boundaries, root locus.
pub fn sweep(
    p: &mut Page,
    cx: &Context<'_>,
    s: &SweepReport,
    spec: &SweepSpec,
) -> Result<(), CliError> {
    let unit = cx.choice.param(&spec.name)?.unit.clone();
    p.section("sweep", &format!("Sweep of {}", spec.name));
    p.text(&format!(
        "{} values of {} from {} to {}; the other parameters as above.",
        spec.count,
        spec.name,
        g(spec.start, SIG),
        g(spec.stop, SIG)
    ));
    let rows: Vec<Vec<String>> = s
        .result
        .boundaries
        .iter()
        .map(|b| {
            vec![
                g(b.value, 10),
                format!("{:?}", b.crossing).to_lowercase(),
                eigenvalue(b.eigenvalue, SIG, false),
            ]
        })
        .collect();
    if rows.is_empty() {
        p.text(
            "No stability boundary between the grid points (two crossings inside one grid step \
             are not seen: a finer grid may find them).",
        );
    } else {
        p.table(
            &[&format!("boundary {}", spec.name), "crossing", "eigenvalue"],
            &rows,
            0,
        );
    }
    let intervals: Vec<String> = s
        .result
        .stable_intervals
        .iter()
        .map(|i| crate::sweep::interval_text(&s.result, i, |x| g(x, SIG)))
        .collect();
    p.text(&format!(
        "stable for {} in {}",
        spec.name,
        if intervals.is_empty() {
            "no interval".to_string()
        } else {
            intervals.join(", ")
        }
    ));
    let zoom = Some(plot::zoom::Zoom::Auto);
    let plot = plot::sweep::sweep_plot(&s.model, &s.result, &unit, zoom)?;
    p.figure(
        &plot.svg,
        "Real parts, real parts near zero, and damped frequencies over the parameter; stable \
         intervals shaded, boundaries dashed.",
    );
    let locus = plot::locus::locus_plot(&s.model, &s.result, &unit)?;
    p.figure(
        &locus.svg,
        "Root locus: the eigenvalues' paths as the parameter grows; rings mark the crossings.",
    );
    Ok(())
}

/// The closed forms of small models, as MathML with the LaTeX beside.
pub fn closed_forms(p: &mut Page, cx: &Context<'_>) -> Result<(), CliError> {
    let n = cx.analysis.states;
    p.section("closed", "Closed forms");
    if n > CLOSED_FORM_STATES {
        p.text(&format!(
            "The model has {n} states; closed forms are shown up to {CLOSED_FORM_STATES} \
             (`eom symbolic` derives them for larger models)."
        ));
        return Ok(());
    }
    // Every parameter symbolic: the forms hold for any values.
    let req = crate::symbolic::SymbolicRequest {
        stability: true,
        solve_for: None,
        transfer: true,
        max_states: Some(CLOSED_FORM_STATES),
    };
    let r = crate::symbolic::symbolic(cx.choice, &[], &req)?;
    let (m, l) = (&r.mathml, &r.latex);
    if let (Some(mp), Some(lp)) = (&m.polynomial, &l.polynomial) {
        let zero = r
            .characteristic_polynomial
            .as_ref()
            .map_or(0, |c| c.zero_roots);
        let label = if zero > 0 {
            format!("det(sI − A) = s^{zero} · p(s) up to a positive factor, p(s) =")
        } else {
            "det(sI − A) ∝".to_string()
        };
        p.formula(&label, mp, lp);
    }
    if let (Some((wm, zm)), Some((wl, zl))) = (&m.second_order, &l.second_order) {
        p.formula("ωn =", wm, wl);
        p.formula("ζ =", zm, zl);
    }
    match r.stability_verdict.as_deref() {
        Some(v) if v.starts_with("never: ") => {
            p.text(&format!(
                "Never asymptotically stable: {}.",
                v.trim_start_matches("never: ")
            ));
        }
        Some("always") => p.text(
            "Asymptotically stable for all parameter values: every condition holds by the \
             parameters' declared signs.",
        ),
        _ => {
            p.text("Asymptotically stable exactly when all of these hold:");
            for (cm, cl) in m.conditions.iter().zip(&l.conditions) {
                p.formula("", cm, cl);
            }
        }
    }
    for ((o, i, tm), (_, _, tl)) in m.transfer.iter().zip(&l.transfer) {
        p.formula(&format!("{o} / {i} ="), tm, tl);
    }
    for note in &r.notes {
        p.note(note);
    }
    Ok(())
}

/// The warnings of the analyses.
pub fn warnings(p: &mut Page, cx: &Context<'_>) {
    if cx.analysis.warnings.is_empty() {
        return;
    }
    p.section("warnings", "Warnings");
    for w in &cx.analysis.warnings {
        p.note(&w.message);
    }
}
