//! `eom bench`: the benchmarks of `eom-bench` on the user's machine. `accuracy` is the
//! work-precision comparison of every way eom offers to get eigenvalues; `throughput` the
//! points per second of a parallel parameter sweep of the bicycle.

use crate::error::CliError;
use crate::output::{status_line, write_chosen};
use crate::progress::Progress;
use eom_bench::work_precision::{self, MODELS, Options, WorkPrecisionError, entries};
use std::path::Path;
use std::time::Duration;

/// What `eom bench accuracy` was asked for.
pub struct AccuracyRequest {
    /// Models (default: the benchmark's list).
    pub models: Vec<String>,
    /// Random parameter points per model.
    pub points: usize,
    /// Minimum time spent timing each method, in milliseconds.
    pub min_time_ms: u64,
    /// Random parameter points of the generated code's entry errors.
    pub entry_points: usize,
    /// Output directory (created if missing).
    pub dir: Option<std::path::PathBuf>,
}

/// The largest number of random points per model (each costs a double-double reference).
pub const MAX_POINTS: usize = 10_000;

/// The heading of the entry errors' table in the printed Markdown.
const ENTRIES_HEADING: &str = "Rounding error of the symbolic formulas' entries of A and B, \
    evaluated on the tape and by the generated code, against double-double (entry-wise: \
    |Δ|/|ref|; row-scaled: |Δ| / largest |ref| of the row of [A B]):";

/// Run the work-precision benchmark; returns the Markdown table, and writes the CSV, the
/// table and the chart into the directory when one is given (a note per file on `stderr`).
pub fn accuracy(
    req: &AccuracyRequest,
    quiet: bool,
    stderr: &mut String,
) -> Result<String, CliError> {
    for (flag, n) in [
        ("--points", req.points),
        ("--entry-points", req.entry_points),
    ] {
        if n == 0 || n > MAX_POINTS {
            return Err(CliError::BadArgument {
                argument: format!("{flag} {n}"),
                problem: format!("between 1 and {MAX_POINTS} random points per model"),
            });
        }
    }
    let models: Vec<String> = if req.models.is_empty() {
        MODELS.iter().map(|m| m.to_string()).collect()
    } else {
        req.models.clone()
    };
    for m in &models {
        if !MODELS.contains(&m.as_str()) {
            return Err(CliError::BadArgument {
                argument: m.clone(),
                problem: format!(
                    "not a model of the accuracy benchmark (its generated code is compiled \
                     in): {}",
                    MODELS.join(", ")
                ),
            });
        }
    }
    let opts = Options {
        points: req.points,
        min_time: Duration::from_millis(req.min_time_ms),
        ..Options::default()
    };
    let bar = Progress::new(quiet, models.len() as u64, "bench accuracy");
    let (mut rows, mut entry_rows) = (Vec::new(), Vec::new());
    for m in &models {
        bar.stage(m);
        rows.extend(work_precision::run_model(m, &opts).map_err(bench_error)?);
        entry_rows.extend(
            entries::entry_errors(m, req.entry_points, opts.spread, opts.seed)
                .map_err(bench_error)?,
        );
    }
    bar.finish();
    let md = format!(
        "{}\n{ENTRIES_HEADING}\n\n{}",
        work_precision::output::markdown(&rows, 1e-12),
        entries::markdown(&entry_rows)
    );
    if let Some(dir) = &req.dir {
        std::fs::create_dir_all(dir).map_err(|e| CliError::Io {
            path: dir.display().to_string(),
            source: e,
        })?;
        let chart = work_precision::chart::svg(&rows).map_err(bench_error)?;
        for (name, text) in [
            ("work_precision.csv", work_precision::output::csv(&rows)),
            ("work_precision.md", md.clone()),
            ("work_precision.svg", chart),
            ("generated_entries.csv", entries::csv(&entry_rows)),
        ] {
            note(&dir.join(name), &text, stderr)?;
        }
    }
    Ok(md)
}

fn note(path: &Path, text: &str, stderr: &mut String) -> Result<(), CliError> {
    stderr.push_str(&status_line(path, write_chosen(path, text)?));
    Ok(())
}

/// A benchmark failure as a CLI error (model and numeric errors keep their type).
fn bench_error(e: WorkPrecisionError) -> CliError {
    match e {
        WorkPrecisionError::Model(e) => CliError::Model(e),
        WorkPrecisionError::Num(e) => CliError::Num(e),
        WorkPrecisionError::Sym(e) => CliError::Sym(e),
        other => CliError::Bench(other.to_string()),
    }
}

/// The largest number of points of `eom bench throughput`.
pub const MAX_THROUGHPUT_POINTS: usize = 1_000_000_000;

/// Run the throughput sweep of the bicycle (`eom bench throughput`); returns the report.
pub fn throughput(points: usize, threads: Option<usize>) -> Result<String, CliError> {
    use eom_bench::throughput::{self as tp, Options};
    if points == 0 || points > MAX_THROUGHPUT_POINTS {
        return Err(CliError::BadArgument {
            argument: format!("--points {points}"),
            problem: format!("between 1 and {MAX_THROUGHPUT_POINTS} points"),
        });
    }
    if threads == Some(0) {
        return Err(CliError::BadArgument {
            argument: "--threads 0".into(),
            problem: "at least one thread".into(),
        });
    }
    let defaults = Options::default();
    let opts = Options {
        points,
        threads: threads.unwrap_or(defaults.threads),
        ..defaults
    };
    let t = tp::run(&opts).map_err(|e| CliError::Bench(e.to_string()))?;
    Ok(tp::to_text(&t))
}

/// What `eom bench stress` was asked for.
pub struct StressRequest {
    /// The reduced grid (a few points per region, seconds).
    pub quick: bool,
    /// Output directory (created if missing).
    pub dir: Option<std::path::PathBuf>,
}

/// Run the failure map; returns the Markdown table of counts, and writes the cells
/// (`stress.csv`), the counts (`stress_counts.csv`), the table (`stress.md`) and the map
/// (`stress.svg`) into the directory when one is given (a note per file on `stderr`).
pub fn stress(req: &StressRequest, quiet: bool, stderr: &mut String) -> Result<String, CliError> {
    use eom_bench::stress;
    let regions = stress::regions::regions(req.quick).len();
    let bar = Progress::new(quiet, regions as u64, "bench stress");
    let map = stress::run(req.quick, &mut |r| bar.stage(r))
        .map_err(|e| CliError::Bench(e.to_string()))?;
    bar.finish();
    let md = stress::output::markdown(&map);
    if let Some(dir) = &req.dir {
        std::fs::create_dir_all(dir).map_err(|e| CliError::Io {
            path: dir.display().to_string(),
            source: e,
        })?;
        for (name, text) in [
            ("stress.csv", stress::output::cells_csv(&map)),
            ("stress_counts.csv", stress::output::counts_csv(&map)),
            ("stress.md", md.clone()),
            ("stress.svg", stress::output::svg(&map)),
        ] {
            note(&dir.join(name), &text, stderr)?;
        }
    }
    Ok(md)
}
