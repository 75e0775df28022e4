//! `eom analyze` of a large model on one thread and on two, in the same run: the dense steps
//! (modes, minimal realization, zeros) use faer's parallel kernels on the threads of the rayon
//! pool (`RAYON_NUM_THREADS`) from `eom_num::linalg::PARALLEL_MIN` states on. Prints the wall
//! times of alternating runs, their ratio, and for each run its CPU time and the CPU time
//! other processes used meanwhile (the machine may be shared: a ratio is only meaningful
//! while the other cores are idle, i.e. the others' CPU is near zero).
//!
//! `cargo bench -p eom-cli --bench threads` (chain1000; `EOM_THREADS_MODEL=chain300` for a
//! quicker run, `EOM_THREADS_ROUNDS=N` rounds, default 2; `EOM_THREADS=1,2,16` the thread
//! counts, default 1,2).

use std::process::Command;
use std::time::Instant;

/// Clock ticks per second of `/proc`'s CPU times (`USER_HZ`, 100 on Linux).
const TICKS: f64 = 100.0;

/// CPU seconds of the machine (all cores, busy) and of this process's waited-for children,
/// from `/proc/stat` and `/proc/self/stat` (Linux; `None` elsewhere).
fn cpu_readings() -> Option<(f64, f64)> {
    let stat = std::fs::read_to_string("/proc/stat").ok()?;
    let fields: Vec<f64> = stat
        .lines()
        .next()?
        .split_whitespace()
        .skip(1)
        .map(|v| v.parse().unwrap_or(0.0))
        .collect();
    // user nice system idle iowait irq softirq steal …: busy is all but idle and iowait.
    let busy: f64 = fields.iter().take(8).sum::<f64>() - fields.get(3)? - fields.get(4)?;
    let own = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (which may hold spaces) in parentheses.
    let rest: Vec<&str> = own.rsplit_once(')')?.1.split_whitespace().collect();
    // cutime and cstime are fields 16 and 17 of the line, 14 and 15 after the name.
    let children = rest.get(13)?.parse::<f64>().ok()? + rest.get(14)?.parse::<f64>().ok()?;
    Some((busy / TICKS, children / TICKS))
}

fn main() {
    let model = std::env::var("EOM_THREADS_MODEL").unwrap_or_else(|_| "chain1000".into());
    let rounds: usize = std::env::var("EOM_THREADS_ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2);
    let threads: Vec<usize> = std::env::var("EOM_THREADS")
        .unwrap_or_else(|_| "1,2".into())
        .split(',')
        .map(|s| s.trim().parse().expect("a thread count"))
        .collect();
    let mut best = vec![f64::INFINITY; threads.len()];
    for round in 0..rounds {
        for (k, &t) in threads.iter().enumerate() {
            let before = cpu_readings();
            let start = Instant::now();
            let out = Command::new(env!("CARGO_BIN_EXE_eom"))
                .args(["analyze", &model, "--quiet"])
                .env("RAYON_NUM_THREADS", t.to_string())
                .output()
                .expect("eom runs");
            let secs = start.elapsed().as_secs_f64();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            best[k] = best[k].min(secs);
            let cpu = match (before, cpu_readings()) {
                (Some((b0, c0)), Some((b1, c1))) => format!(
                    "{:.2} s CPU, other processes {:.2} s CPU meanwhile",
                    c1 - c0,
                    (b1 - b0) - (c1 - c0)
                ),
                _ => "CPU unknown".into(),
            };
            println!(
                "round {} {model}, {t} thread(s): {secs:.2} s wall, {cpu}",
                round + 1
            );
        }
    }
    for (k, &t) in threads.iter().enumerate() {
        println!(
            "{model}, {t} thread(s): best {:.2} s, {:.2}× the one-thread time",
            best[k],
            best[0] / best[k]
        );
    }
}
