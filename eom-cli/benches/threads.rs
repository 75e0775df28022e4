//! `eom analyze` of a large model on one thread and on two, in the same run: the dense steps
//! (modes, minimal realization, zeros) use faer's parallel kernels on the threads of the rayon
//! pool (`RAYON_NUM_THREADS`) from `eom_num::linalg::PARALLEL_MIN` states on. Prints the wall
//! times of alternating runs, their ratio, and the load average before each run (the machine
//! may be shared: a ratio is only meaningful while the other cores are idle).
//!
//! `cargo bench -p eom-cli --bench threads` (chain1000; `EOM_THREADS_MODEL=chain300` for a
//! quicker run, `EOM_THREADS_ROUNDS=N` rounds, default 2; `EOM_THREADS=1,2,16` the thread
//! counts, default 1,2).

use std::process::Command;
use std::time::Instant;

fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".into())
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
            let before = load();
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
            println!(
                "round {} {model}, {t} thread(s): {secs:.2} s wall (load average before: {before})",
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
