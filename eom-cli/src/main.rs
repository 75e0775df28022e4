//! `eom` — linearized equations of motion of the built-in multibody models: list them,
//! analyse one at a point, sweep a parameter for stability boundaries, generate Rust code.
//!
//! Exit codes: 0 success; 2 unknown model or parameter, malformed argument (the message on
//! standard error lists the valid names); 1 any other failure (e.g. a point outside the
//! validity region of the symbolic reduction with `--method symbolic`).

#![warn(missing_docs)]
#![forbid(unsafe_code)]

mod aero;
mod analyze;
mod analyze_text;
mod args;
#[cfg(feature = "bench")]
mod bench;
mod check;
mod codegen;
mod error;
mod format;
mod list;
mod matrices;
mod output;
mod params;
mod pictures;
mod plot;
mod preloads;
mod progress;
mod reduce;
mod report;
mod shown_warning;
mod sweep;
mod symbolic;
mod timing;
mod wings;

use crate::analyze::{AnalyzeOptions, FreqRequest};
use crate::args::{
    AnalyzeArgs, BenchCommand, Cli, Command, Format, ReduceArgs, ReduceMethodArg, SweepArgs,
    SweepFormat, SymbolicFormat,
};
use crate::codegen::CodegenRequest;
use crate::error::CliError;
use crate::params::{ModelChoice, SweepSpec, parse_freq_range};
use clap::Parser;
use std::io::{IsTerminal, Write};
use std::path::Path;
use std::process::ExitCode;

/// Where the output goes: standard output, or a note on standard error.
struct Output {
    stdout: String,
    stderr: String,
}

fn json<T: serde::Serialize>(v: &T) -> Result<String, CliError> {
    let mut s = serde_json::to_string_pretty(v)?;
    s.push('\n');
    Ok(s)
}

/// `eom bench …`: the benchmarks' output (notes of written files on `stderr`).
#[cfg(feature = "bench")]
fn run_bench(b: BenchCommand, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    Ok(match b {
        BenchCommand::Accuracy(b) => {
            let req = bench::AccuracyRequest {
                models: b.models,
                points: b.points,
                min_time_ms: b.min_time,
                entry_points: b.entry_points,
                dir: b.output,
            };
            bench::accuracy(&req, quiet, stderr)?
        }
        BenchCommand::Throughput(t) => bench::throughput(t.points, t.threads)?,
        BenchCommand::Stress(b) => {
            let req = bench::StressRequest {
                quick: b.quick,
                dir: b.output,
            };
            bench::stress(&req, quiet, stderr)?
        }
    })
}

/// Without the `bench` feature: `eom bench` says that this build does not include it.
#[cfg(not(feature = "bench"))]
fn run_bench(_: BenchCommand, _: bool, _: &mut String) -> Result<String, CliError> {
    Err(CliError::Unavailable(
        "the benchmarks are not available in this build of eom (built without the cargo \
         feature `bench`, which links the eom-bench crate). Rebuild with \
         `cargo build -p eom-cli --features bench`."
            .into(),
    ))
}

fn run(cli: Cli) -> Result<Output, CliError> {
    let mut stderr = String::new();
    let stdout = match cli.command {
        Command::List { format } => {
            let e = list::entries();
            match format {
                Format::Text => list::to_text(&e),
                Format::Json => json(&e)?,
            }
        }
        Command::Analyze(a) => run_analyze(&a, &mut stderr)?,
        Command::Reduce(r) => run_reduce(&r, &mut stderr)?,
        Command::Sweep(s) if s.compare.is_some() => sweep_compare(&s, cli.quiet, &mut stderr)?,
        Command::Sweep(s) => run_sweep(&s, cli.quiet, &mut stderr)?,
        Command::Report(r) => {
            let choice = ModelChoice::resolve(&r.model)?;
            let overrides = choice.parse_sets(&r.set)?;
            let spec = r
                .sweep
                .as_deref()
                .map(|s| SweepSpec::parse_option("--sweep", s))
                .transpose()?;
            let w = report::write_report(&choice, &overrides, spec.as_ref(), &r.output, cli.quiet)?;
            if w.created_dir {
                stderr.push_str(&format!("created directory {}\n", r.output.display()));
            }
            stderr.push_str(&output::status_line(&w.path, w.written));
            String::new()
        }
        Command::Codegen(c) => {
            let choice = ModelChoice::resolve(&c.model)?;
            let overrides = choice.parse_sets(&c.set)?;
            let req = CodegenRequest {
                f32: c.f32,
                no_std: c.no_std,
                simplify: c.simplify,
                simplify_always: c.simplify_always,
                module: c.module,
                stability: c.stability,
                reduce: c.reduce,
                reduce_modal: c.reduce_modal,
                discrete: c.discrete,
            };
            // The summary is a status: standard error (the output may be `/dev/stdout`).
            stderr.push_str(&codegen::codegen(&choice, &overrides, &req, &c.output)?);
            String::new()
        }
        Command::Check { model, format } => {
            let choice = ModelChoice::resolve(&model)?;
            let r = check::check(&choice)?;
            match format {
                Format::Text => r.to_text(),
                Format::Json => json(&r)?,
            }
        }
        Command::New { name } => check::starter(&name)?,
        Command::Bench(b) => run_bench(b, cli.quiet, &mut stderr)?,
        Command::Export { model, set, output } => {
            let choice = ModelChoice::resolve(&model)?;
            let overrides = choice.parse_sets(&set)?;
            let text = eom_model::file::to_toml(&choice.build(&overrides)?);
            match output {
                None => text,
                Some(path) => {
                    stderr.push_str(&output::status_line(
                        &path,
                        output::write_output(&path, &text)?,
                    ));
                    String::new()
                }
            }
        }
        Command::Aero(a) => {
            let req = aero::AeroRequest {
                alpha_deg: a.alpha,
                reference: a
                    .reference
                    .as_deref()
                    .map(aero::parse_reference)
                    .transpose()?,
                density: a.rho,
                speed: a.speed,
            };
            let r = aero::aero(&a.file, &req)?;
            match a.format {
                Format::Text => r.to_text(),
                Format::Json => json(&r)?,
            }
        }
        Command::Symbolic(a) => {
            let choice = ModelChoice::resolve(&a.model)?;
            // Checked as numbers (names, finiteness), kept as text for exact substitution.
            choice.parse_sets(&a.set)?;
            let texts: Vec<(String, String)> = a
                .set
                .iter()
                .filter_map(|s| s.split_once('='))
                .map(|(k, v)| (k.trim().to_string(), v.trim().to_string()))
                .collect();
            let req = symbolic::SymbolicRequest {
                stability: a.stability,
                solve_for: a.solve_for,
                transfer: a.transfer,
                max_states: a.max_states,
            };
            if let Some(name) = &req.solve_for {
                choice.param(name)?;
            }
            if let Some(n) = req
                .max_states
                .filter(|&n| n == 0 || n > eom_sym::closed::MAX_CLOSED_FORM_STATES)
            {
                return Err(CliError::BadArgument {
                    argument: format!("--max-states {n}"),
                    problem: format!(
                        "closed forms are derived for 1 to {} states",
                        eom_sym::closed::MAX_CLOSED_FORM_STATES
                    ),
                });
            }
            let r = symbolic::symbolic(&choice, &texts, &req)?;
            match a.format {
                SymbolicFormat::Text => r.to_text(),
                SymbolicFormat::Latex => r.to_latex(),
                SymbolicFormat::Json => json(&r)?,
            }
        }
    };
    Ok(Output { stdout, stderr })
}

/// `eom analyze`: the analysis, printed, and the plots asked for.
fn run_analyze(a: &AnalyzeArgs, stderr: &mut String) -> Result<String, CliError> {
    let choice = ModelChoice::resolve(&a.model)?;
    let overrides = choice.parse_sets(&a.set)?;
    let range = a.freq_range.as_deref().map(parse_freq_range).transpose()?;
    if a.points == Some(0) {
        return Err(CliError::BadArgument {
            argument: "--points 0".into(),
            problem: "at least one frequency is needed".into(),
        });
    }
    if let Some(n) = a.points.filter(|&n| n > params::MAX_FREQ_POINTS) {
        return Err(CliError::BadArgument {
            argument: format!("--points {n}"),
            problem: format!(
                "more than the limit of {} frequencies (a Bode plot needs a few hundred per \
                 decade at most)",
                params::MAX_FREQ_POINTS
            ),
        });
    }
    let plots = analyze_plots(a)?;
    if let Some(path) = &a.matrices {
        matrices::format_of("--matrices", path)?;
    }
    let bode = a.plot.is_some();
    let freq = (a.freq || range.is_some() || a.points.is_some() || bode).then_some(FreqRequest {
        range,
        points: a.points,
    });
    let opts = AnalyzeOptions {
        method: a.method.into(),
        freq,
        sensitivity: a.sensitivity,
    };
    let lin = analyze::linearize(&choice, &overrides, opts.method)?;
    let r = analyze::analyze_linearized(&choice, &overrides, &opts, &lin)?;
    let reduced =
        match &a.reduce {
            None => None,
            Some(text) => {
                let order =
                    match text.as_str() {
                        "default" => None,
                        t => Some(t.trim().parse::<usize>().map_err(|_| {
                            CliError::BadArgument {
                    argument: format!("--reduce {}", params::abbreviate(t)),
                    problem: "expected a number of states (or nothing, for the default order)"
                        .into(),
                }
                        })?),
                    };
                let req = reduce::ReduceRequest {
                    method: reduce_method(a.reduce_method.unwrap_or(ReduceMethodArg::Balanced)),
                    order,
                    tol: None,
                    band: None,
                    linearization: opts.method,
                };
                Some(reduce::report_of(&choice, &overrides, &lin, &req)?.0)
            }
        };
    for (option, path) in plots {
        let plot = match option {
            "--plot" => plot::bode::bode_of(&r)?,
            "--plot-poles" => plot::poles::pole_map_of(&r)?,
            _ => analyze_picture(a, option, &choice, &overrides, &lin)?,
        };
        plot.write(option, path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    if let Some(path) = &a.matrices {
        let written = matrices::write_matrices("--matrices", path, &r.matrices.named())?;
        stderr.push_str(&output::status_line(path, written));
    }
    Ok(match (a.format, reduced) {
        (Format::Text, None) => r.to_text(),
        (Format::Text, Some(red)) => format!("{}\n{}", r.to_text(), red.to_text()),
        (Format::Json, None) => json(&r)?,
        (Format::Json, Some(red)) => {
            let mut v = serde_json::to_value(&r)?;
            if let Some(map) = v.as_object_mut() {
                map.insert("reduction".into(), serde_json::to_value(&red)?);
            }
            json(&v)?
        }
    })
}

/// `eom reduce`: the reduction, printed, and its plot.
fn run_reduce(a: &ReduceArgs, stderr: &mut String) -> Result<String, CliError> {
    let choice = ModelChoice::resolve(&a.model)?;
    let overrides = choice.parse_sets(&a.set)?;
    if let Some(path) = &a.plot {
        plot::check_target("--plot", path)?;
    }
    if let Some(path) = &a.matrices {
        matrices::format_of("--matrices", path)?;
    }
    let band = a
        .band
        .as_deref()
        .map(|b| {
            params::parse_band(b).map_err(|problem| CliError::BadArgument {
                argument: format!("--band {}", params::abbreviate(b)),
                problem,
            })
        })
        .transpose()?;
    let method = reduce_method(a.method);
    let req = reduce::ReduceRequest {
        method,
        order: a.order,
        tol: a.tol,
        band,
        linearization: a.linearize.into(),
    };
    let (r, _) = reduce::reduce(&choice, &overrides, &req)?;
    if let Some(path) = &a.plot {
        let plot = plot::hankel::hankel_plot(&r)?;
        plot.write("--plot", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    if let Some(path) = &a.matrices {
        let written = matrices::write_matrices("--matrices", path, &r.matrices.named())?;
        stderr.push_str(&output::status_line(path, written));
    }
    Ok(match a.format {
        Format::Text => r.to_text(),
        Format::Json => json(&r)?,
    })
}

/// The reducer's method for a command-line choice.
fn reduce_method(m: ReduceMethodArg) -> eom_num::model_reduction::ReductionMethod {
    use eom_num::model_reduction::ReductionMethod;
    match m {
        ReduceMethodArg::Balanced => ReductionMethod::Balanced,
        ReduceMethodArg::Matchdc => ReductionMethod::MatchDc,
        ReduceMethodArg::Modal => ReductionMethod::Modal,
    }
}

/// The time-response and mode-shape pictures of `eom analyze`.
fn analyze_picture(
    a: &AnalyzeArgs,
    option: &str,
    choice: &ModelChoice,
    overrides: &[(String, f64)],
    lin: &eom_model::Linearization,
) -> Result<plot::Plot, CliError> {
    let ss = &lin.state_space;
    let modes = pictures::modes_of(ss, lin.structural_zeros.len())?;
    let name = &choice.name;
    match option {
        "--plot-step" => pictures::step_impulse_plot(name, ss),
        "--plot-initial" => {
            let k = match a.mode {
                Some(k) => k,
                None => pictures::default_mode(&modes).ok_or_else(|| {
                    CliError::NothingToDraw(format!("the model `{name}` has no nonzero mode"))
                })?,
            };
            pictures::initial_plot(name, ss, &modes, k)
        }
        _ => {
            let model = choice.build(overrides)?.nominal()?;
            let which = match a.mode {
                Some(k) => vec![k],
                None => pictures::drawable_modes(&modes),
            };
            if which.is_empty() {
                return Err(CliError::NothingToDraw(format!(
                    "no mode of `{name}` moves a body: nothing to draw"
                )));
            }
            let parts = which
                .iter()
                .map(|k| pictures::mode_shape_svg(name, &model, ss, &modes, *k))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(plot::Plot {
                svg: pictures::stack_svgs(&parts),
                notes: Vec::new(),
            })
        }
    }
}

/// `eom sweep MODEL`: the sweep, printed, and its plots.
fn run_sweep(s: &SweepArgs, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    let choice = ModelChoice::resolve(&s.model)?;
    let spec = SweepSpec::parse(&s.param)?;
    choice.param(&spec.name)?;
    let overrides = choice.parse_sets(&s.set)?;
    let zoom = sweep_plot_options(s, &spec)?;
    let bar = progress::Progress::new(quiet, spec.count as u64, &format!("sweep {}", s.model));
    let r = sweep::sweep_with(&choice, &spec, &overrides, &|| bar.tick())?;
    bar.finish();
    let unit = choice.param(&spec.name)?.unit.clone();
    if let Some(path) = &s.plot {
        let plot = plot::sweep::sweep_plot(&r.model, &r.result, &unit, zoom)?;
        plot.write("--plot", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    if let Some(path) = &s.plot_locus {
        let plot = plot::locus::locus_plot(&r.model, &r.result, &unit)?;
        plot.write("--plot-locus", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    Ok(match s.format {
        SweepFormat::Text => r.to_text(),
        SweepFormat::Json => json(&r)?,
        SweepFormat::Csv => {
            // Keep the CSV clean; the evaluation note goes to standard error.
            stderr.push_str(&r.evaluation_note());
            r.to_csv()
        }
    })
}

/// Checks the plot options of `eom sweep` before the sweep runs; returns the zoom.
fn sweep_plot_options(
    s: &SweepArgs,
    spec: &SweepSpec,
) -> Result<Option<plot::zoom::Zoom>, CliError> {
    if let Some(path) = &s.plot {
        check_sweep_plot(&s.param, spec, path)?;
    }
    if let Some(path) = &s.plot_locus {
        plot::check_target("--plot-locus", path)?;
        if let Some(p) = &s.plot {
            plot::check_distinct(("--plot", p), ("--plot-locus", path))?;
        }
    }
    let zoom = s.zoom.as_deref().map(plot::zoom::Zoom::parse).transpose()?;
    if zoom.is_some() && s.plot.is_none() {
        return Err(CliError::BadArgument {
            argument: "--zoom".into(),
            problem: "the zoom is a panel of the --plot FILE.svg: give --plot too".into(),
        });
    }
    Ok(zoom)
}

/// `eom sweep A --compare B`: both sweeps over the same grid, reported one after the other
/// (JSON: `{"sweeps": [A, B]}`), drawn in one plot with `--plot`.
fn sweep_compare(s: &SweepArgs, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    let other = s.compare.as_deref().unwrap_or_default();
    if s.format == SweepFormat::Csv {
        return Err(CliError::BadArgument {
            argument: format!("--compare {other}"),
            problem: "not with --format csv (one table per model): use text or json".into(),
        });
    }
    let spec = SweepSpec::parse(&s.param)?;
    let zoom = sweep_plot_options(s, &spec)?;
    if s.plot_locus.is_some() {
        return Err(CliError::BadArgument {
            argument: format!("--compare {other}"),
            problem: "not with --plot-locus (one locus per model): sweep each model".into(),
        });
    }
    let mut reports = Vec::new();
    for name in [s.model.as_str(), other] {
        let choice = ModelChoice::resolve(name)?;
        choice.param(&spec.name)?;
        let overrides = choice.parse_sets(&s.set)?;
        let bar = progress::Progress::new(quiet, spec.count as u64, &format!("sweep {name}"));
        reports.push((
            sweep::sweep_with(&choice, &spec, &overrides, &|| bar.tick())?,
            choice,
        ));
        bar.finish();
    }
    let (a, b) = (&reports[0], &reports[1]);
    if let Some(path) = &s.plot {
        let unit = a.1.param(&spec.name)?.unit.clone();
        let plot = plot::compare::compare_plot(
            (&a.0.model, &a.0.result),
            (&b.0.model, &b.0.result),
            &unit,
            zoom,
        )?;
        plot.write("--plot", path)?;
        stderr.push_str(&plot.notes_text(path));
    }
    Ok(match s.format {
        SweepFormat::Json => json(&serde_json::json!({ "sweeps": [&a.0, &b.0] }))?,
        _ => format!(
            "{}
{}",
            a.0.to_text(),
            b.0.to_text()
        ),
    })
}

/// The plot files asked of `eom analyze`, checked before the analysis runs.
fn analyze_plots(a: &AnalyzeArgs) -> Result<Vec<(&'static str, &Path)>, CliError> {
    let plots: Vec<(&'static str, &Path)> = [
        ("--plot", a.plot.as_deref()),
        ("--plot-poles", a.plot_poles.as_deref()),
        ("--plot-step", a.plot_step.as_deref()),
        ("--plot-initial", a.plot_initial.as_deref()),
        ("--plot-modes", a.plot_modes.as_deref()),
    ]
    .into_iter()
    .filter_map(|(o, p)| p.map(|p| (o, p)))
    .collect();
    for (option, path) in &plots {
        plot::check_target(option, path)?;
    }
    for (k, first) in plots.iter().enumerate() {
        for second in &plots[k + 1..] {
            plot::check_distinct(*first, *second)?;
        }
    }
    if a.mode.is_some() && a.plot_initial.is_none() && a.plot_modes.is_none() {
        return Err(CliError::BadArgument {
            argument: "--mode".into(),
            problem: "it chooses the mode of --plot-initial or --plot-modes: give one of them"
                .into(),
        });
    }
    Ok(plots)
}

/// Checks `eom sweep --plot` before the sweep runs: the file, and a parameter range of
/// nonzero width (a single value has no axis to draw the branches along).
fn check_sweep_plot(param: &str, spec: &SweepSpec, path: &Path) -> Result<(), CliError> {
    plot::check_target("--plot", path)?;
    let (lo, hi) = spec.bounds();
    if spec.count < 2 || lo == hi {
        return Err(CliError::BadArgument {
            argument: format!("--param {param}"),
            problem: "--plot needs a range of nonzero width: at least two values \
                      (COUNT ≥ 2) with START ≠ STOP"
                .into(),
        });
    }
    Ok(())
}

fn write_all(mut w: impl Write, text: &str, what: &str) -> Result<(), CliError> {
    match w.write_all(text.as_bytes()).and_then(|_| w.flush()) {
        // A closed pipe (`eom … | head`) is the reader's choice, not a failure.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => r.map_err(|source| CliError::Io {
            path: what.into(),
            source,
        }),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = params::memory_limit_from_env()
        .and_then(|_| run(cli))
        .and_then(|out| {
            // Messages and statuses may quote names and file text: never raw control
            // characters on a terminal. Standard output is left as it is unless it is a
            // terminal (it may be a file that must stay byte-exact, JSON for instance).
            let stderr = eom_text::for_terminal(&out.stderr);
            write_all(std::io::stderr().lock(), &stderr, "standard error")?;
            let stdout = std::io::stdout();
            if stdout.is_terminal() {
                write_all(
                    stdout.lock(),
                    &eom_text::for_terminal(&out.stdout),
                    "standard output",
                )
            } else {
                write_all(stdout.lock(), &out.stdout, "standard output")
            }
        });
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // Nothing more can be done if standard error is closed too.
            let message = e.to_string();
            let _ = writeln!(
                std::io::stderr(),
                "error: {}",
                eom_text::for_terminal(&message)
            );
            ExitCode::from(e.exit_code())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_definition_is_consistent() {
        Cli::command().debug_assert();
    }
}
