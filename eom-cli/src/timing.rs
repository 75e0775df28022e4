//! Per-step timings of `eom analyze` on standard error, when the environment variable
//! `EOM_TIMINGS` is set (to anything): one line per step with its wall time, the CPU time of
//! the thread that ran it, and the peak resident memory of the process so far. For profiling
//! large models; nothing is printed otherwise.

use std::time::Instant;

/// Whether `EOM_TIMINGS` is set.
fn enabled() -> bool {
    std::env::var_os("EOM_TIMINGS").is_some()
}

/// CPU time of the calling thread in seconds (Linux: `/proc/thread-self/schedstat`).
fn thread_cpu() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// Peak resident memory of the process in MB (Linux: `VmHWM` of `/proc/self/status`).
fn peak_rss_mb() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = text.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// Runs `f` and, with `EOM_TIMINGS` set, prints how long it took.
pub(crate) fn step<R>(name: &str, f: impl FnOnce() -> R) -> R {
    if !enabled() {
        return f();
    }
    let (wall, cpu) = (Instant::now(), thread_cpu());
    let r = f();
    let wall = wall.elapsed().as_secs_f64();
    let cpu = match (cpu, thread_cpu()) {
        (Some(a), Some(b)) => format!("{:8.3} s CPU", b - a),
        _ => "       ? s CPU".to_string(),
    };
    let rss = peak_rss_mb().map_or_else(|| "?".to_string(), |m| format!("{m:.0}"));
    eprintln!("timing: {name:<22} {wall:8.3} s wall {cpu}  peak {rss} MB");
    r
}
