//! `eom report MODEL -o DIR`: one self-contained HTML page about a model at a point (and,
//! with `--sweep`, over a parameter): the analyses of `eom analyze` and `eom sweep` and the
//! closed forms of `eom symbolic`, computed by the same library code, with every picture
//! inline as SVG and the formulas as MathML.

pub mod html;
pub mod mathml;
mod sections;

use crate::analyze::{self, AnalyzeOptions, FreqRequest};
use crate::error::CliError;
use crate::output;
use crate::params::{ModelChoice, SweepSpec};
use crate::progress::Progress;
use crate::sweep::SweepReport;
use eom_model::Method;
use std::path::{Path, PathBuf};

/// Largest number of states for which the closed forms are shown (beyond, they are long
/// and slow to derive).
pub const CLOSED_FORM_STATES: usize = 4;

/// Stages of the progress bar.
const STAGES: u64 = 7;

/// What [`write_report`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Written {
    /// The page, `DIR/NAME.html`.
    pub path: PathBuf,
    /// Whether the output directory was created (it was missing, its parent was not).
    pub created_dir: bool,
    /// Whether the page was written or already held exactly this text.
    pub written: output::Written,
}

/// Computes everything and writes `DIR/NAME.html` by [`output::write_chosen`] (a name eom
/// chose: a symbolic link there is replaced, not followed; a FIFO or a device is not blocked
/// on, an unchanged page is left as it is). A missing `DIR` is created
/// when its parent exists; a missing parent is an error, checked before the work starts.
pub fn write_report(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    sweep: Option<&SweepSpec>,
    dir: &Path,
    quiet: bool,
) -> Result<Written, CliError> {
    if let Some(spec) = sweep {
        choice.param(&spec.name)?;
        let (lo, hi) = spec.bounds();
        if spec.count < 2 || lo == hi {
            return Err(CliError::BadArgument {
                argument: format!("--sweep {}", spec.name),
                problem: "a sweep needs at least two values (COUNT ≥ 2) with START ≠ STOP".into(),
            });
        }
    }
    let created_dir = output::check_output_dir(dir)?;
    let bar = Progress::new(
        quiet,
        STAGES + sweep.map_or(0, |s| s.count as u64),
        &format!("report {}", choice.name),
    );
    let html = page(choice, overrides, sweep, &bar)?;
    bar.finish();
    let stem = Path::new(&choice.name)
        .file_stem()
        .map_or_else(|| "model".to_string(), |s| s.to_string_lossy().into_owned());
    let path = dir.join(format!("{stem}.html"));
    if created_dir {
        output::create_output_dir(dir)?;
    }
    let written = output::write_chosen(&path, &html)?;
    Ok(Written {
        path,
        created_dir,
        written,
    })
}

/// The page.
fn page(
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    sweep: Option<&SweepSpec>,
    bar: &Progress,
) -> Result<String, CliError> {
    let opts = AnalyzeOptions {
        method: Method::Numeric,
        freq: Some(FreqRequest {
            range: None,
            points: None,
        }),
        sensitivity: false,
    };
    bar.stage("linearize");
    let lin = analyze::linearize(choice, overrides, opts.method)?;
    bar.stage("analyze");
    let analysis = analyze::analyze_linearized(choice, overrides, &opts, &lin)?;
    let model = choice.build(overrides)?.nominal()?;
    // A sweep that fails is said in its section; the rest of the page stands.
    let swept: Option<Result<SweepReport, CliError>> = sweep.map(|spec| {
        bar.stage("sweep");
        let others: Vec<(String, f64)> = overrides
            .iter()
            .filter(|(k, _)| k != &spec.name)
            .cloned()
            .collect();
        crate::sweep::sweep_with(choice, spec, &others, &|| bar.tick())
    });
    let mut p = html::Page::default();
    let cx = sections::Context {
        choice,
        analysis: &analysis,
        lin: &lin,
        model: &model,
    };
    bar.stage("model and modes");
    sections::model(&mut p, &cx);
    sections::preloads(&mut p, &cx);
    p.part("modes", "Modes", |p| sections::modes(p, &cx));
    bar.stage("responses");
    sections::io_view(&mut p, &cx);
    p.part("bode", "Frequency response", |p| {
        sections::responses(p, &cx)
    });
    if let (Some(s), Some(spec)) = (&swept, sweep) {
        p.part("sweep", &format!("Sweep of {}", spec.name), |p| match s {
            Ok(s) => sections::sweep(p, &cx, s, spec).map_err(|e| e.to_string()),
            Err(e) => Err(format!("the sweep failed: {e}")),
        });
    }
    bar.stage("reduction");
    sections::reduction(&mut p, &cx, overrides)?;
    bar.stage("closed forms");
    p.part("closed", "Closed forms", |p| sections::closed_forms(p, &cx));
    sections::warnings(&mut p, &cx);
    let intro = format!(
        "{} states, {} inputs, {} outputs; {} at this point. Written by eom {}; every picture \
         is inline SVG, every formula MathML (with its LaTeX beside it), nothing is loaded \
         from elsewhere.",
        analysis.states,
        analysis.inputs.len(),
        analysis.outputs.len(),
        analysis.stability,
        env!("CARGO_PKG_VERSION")
    );
    Ok(p.finish(&format!("eom report: {}", choice.name), &intro))
}
