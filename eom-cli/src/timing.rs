//! Per-step timings of `eom analyze` on standard error, when the environment variable
//! `EOM_TIMINGS` is set (to anything): one line per step with when it started and ended
//! (seconds since the first step began), its wall time, the CPU time of the thread that ran
//! it, the CPU time of all the process's threads over the same interval, and the peak
//! resident memory of the process so far. For profiling large models; nothing is printed
//! otherwise.
//!
//! The steps run in two concurrent chains (see `analyze_state_space`) and inside a step
//! faer's kernels use the pool's other threads: the thread's CPU is the step's own work on
//! it, the process's CPU over the interval adds what the other threads did meanwhile (the
//! helpers of this step, and the other chain's step), and start and end show which steps
//! overlapped. With one thread (`RAYON_NUM_THREADS=1`) the steps run one after the other
//! and the two CPU figures agree.

use std::sync::OnceLock;
use std::time::Instant;

/// Whether `EOM_TIMINGS` is set.
fn enabled() -> bool {
    std::env::var_os("EOM_TIMINGS").is_some()
}

/// Seconds since the first timed step began.
fn since_start() -> f64 {
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_secs_f64()
}

/// CPU time in seconds from a `schedstat` file (Linux; its first field, in nanoseconds).
fn schedstat(path: &std::path::Path) -> Option<f64> {
    let text = std::fs::read_to_string(path).ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// CPU time of the calling thread in seconds.
fn thread_cpu() -> Option<f64> {
    schedstat("/proc/thread-self/schedstat".as_ref())
}

/// CPU time of all the process's live threads in seconds.
fn process_cpu() -> Option<f64> {
    let tasks = std::fs::read_dir("/proc/self/task").ok()?;
    tasks
        .map(|t| schedstat(&t.ok()?.path().join("schedstat")))
        .sum()
}

/// Peak resident memory of the process in MB (Linux: `VmHWM` of `/proc/self/status`).
fn peak_rss_mb() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// The difference of two optional CPU readings, formatted.
fn cpu_delta(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) => format!("{:8.3} s", b - a),
        _ => "       ? s".to_string(),
    }
}

/// Runs `f` and, with `EOM_TIMINGS` set, prints how long it took.
pub(crate) fn step<R>(name: &str, f: impl FnOnce() -> R) -> R {
    if !enabled() {
        return f();
    }
    let start = since_start();
    let (wall, cpu, all) = (Instant::now(), thread_cpu(), process_cpu());
    let r = f();
    let wall = wall.elapsed().as_secs_f64();
    let cpu = cpu_delta(cpu, thread_cpu());
    let all = cpu_delta(all, process_cpu());
    let rss = peak_rss_mb().map_or_else(|| "?".to_string(), |m| format!("{m:.0}"));
    eprintln!(
        "timing: {name:<22} {start:7.3} → {:7.3} s {wall:8.3} s wall {cpu} CPU (thread) \
         {all} CPU (process)  peak {rss} MB",
        start + wall
    );
    r
}
