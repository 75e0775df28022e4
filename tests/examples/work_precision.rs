//! Work-precision benchmark of every way eom offers to get eigenvalues (issue 19, build 1):
//! writes `work_precision.csv`, `work_precision.md` and `work_precision.svg` into DIR.
//!
//! cargo run --release -p tests --example work_precision -- -o DIR [--points N] [MODEL…]

use std::path::PathBuf;
use std::time::Instant;
use tests::work_precision::{MODELS, Options, WorkPrecisionError, chart, output, run_model};

fn main() {
    if let Err(e) = run() {
        eprintln!("work_precision: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), WorkPrecisionError> {
    let mut dir = PathBuf::from(".");
    let mut opts = Options::default();
    let mut models: Vec<String> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "-o" | "--out" => dir = PathBuf::from(args.next().unwrap_or_default()),
            "--points" => {
                let v = args.next().unwrap_or_default();
                opts.points = v.parse().map_err(|_| {
                    WorkPrecisionError::Reference(format!("--points {v}: not a count"))
                })?;
            }
            m => models.push(m.to_string()),
        }
    }
    if models.is_empty() {
        models = MODELS.iter().map(|m| m.to_string()).collect();
    }
    std::fs::create_dir_all(&dir)
        .map_err(|e| WorkPrecisionError::Io(dir.display().to_string(), e))?;
    let mut rows = Vec::new();
    for m in &models {
        let t = Instant::now();
        let r = run_model(m, &opts)?;
        eprintln!("{m}: {:.1} s", t.elapsed().as_secs_f64());
        rows.extend(r);
    }
    let write = |name: &str, text: String| -> Result<(), WorkPrecisionError> {
        let p = dir.join(name);
        std::fs::write(&p, text).map_err(|e| WorkPrecisionError::Io(p.display().to_string(), e))
    };
    let md = output::markdown(&rows, 1e-12);
    print!("{md}");
    write("work_precision.csv", output::csv(&rows))?;
    write("work_precision.md", md)?;
    write("work_precision.svg", chart::svg(&rows)?)?;
    Ok(())
}
