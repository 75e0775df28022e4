//! Soak: many random `analyze` and `sweep` runs of the library entry points — random models
//! of the catalogue (chains of random length among them), random parameter values inside
//! and outside their ranges (negative, zero, huge, tiny, non-finite), random reduction
//! methods, random sweep bounds (some overflowing) — under a memory cap
//! ([`eom_num::budget::set_limit`]). Every run must end with a result or a typed error (a
//! panic fails the test, naming the run), within its time budget, and the bytes allocated
//! and not freed (counted by a wrapper around the system allocator) must stay flat across
//! the run.
//!
//! ```text
//! cargo test -p tests --release --test soak                   # 2 000 runs (CI, < 30 s)
//! EOM_SOAK_COUNT=10000 cargo test -p tests --release --test soak -- --nocapture   # the full soak
//! EOM_SOAK_SEED=7 …                                           # another random sequence
//! ```

use std::alloc::{GlobalAlloc, Layout, System};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicIsize, Ordering};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};

use eom_model::{Linearizer, Method};
use eom_num::freq::{FreqOptions, FrequencyResponse};
use eom_num::gain::steady_state_gain;
use eom_num::minreal::{MinrealOptions, minimal_realization};
use eom_num::modes::Modes;
use eom_num::sweep::Sweep;
use eom_num::zeros::transmission_zeros;
use models::ModelInfo;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Bytes allocated and not yet freed, by every thread.
static LIVE: AtomicIsize = AtomicIsize::new(0);

/// The system allocator, counting live bytes.
struct Counting;

// SAFETY: every call is forwarded unchanged to the system allocator; only a counter is added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE.fetch_add(layout.size() as isize, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size() as isize, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LIVE.fetch_add(
            new_size as isize - layout.size() as isize,
            Ordering::Relaxed,
        );
        // SAFETY: the caller's contract is passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Runs in CI; `EOM_SOAK_COUNT` sets another count (10 000 for the full soak).
const CI_COUNT: usize = 2000;

/// The memory cap of one analysis step during the soak.
const MEMORY_CAP: usize = 256 << 20;

/// Longest time one run may take (a run is at most a chain of 40 masses).
const RUN_BUDGET: Duration = Duration::from_secs(20);

fn env_usize(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(default)
}

/// A random value for a parameter whose default is `d`: mostly within a decade or two of it,
/// sometimes outside any sensible range.
fn value(rng: &mut StdRng, d: f64) -> f64 {
    let scale = if d == 0.0 { 1.0 } else { d.abs() };
    match rng.random_range(0..20) {
        0 => -scale,
        1 => 0.0,
        2 => 1e308,
        3 => 1e-310,
        4 => f64::NAN,
        5 => f64::INFINITY,
        6 => scale * 1e12,
        7 => scale * 1e-12,
        _ => d * 10f64.powf(rng.random_range(-1.5..1.5)),
    }
}

/// One random model name and parameter point.
fn pick(rng: &mut StdRng, catalogue: &[ModelInfo]) -> (String, Vec<(String, f64)>) {
    let entry = &catalogue[rng.random_range(0..catalogue.len())];
    // A family (`chainN`, `chainpN`) at a random size (the generator drawn only for one).
    let size = if entry.is_family() {
        rng.random_range(1..=40)
    } else {
        0
    };
    let name = entry.name_at(size);
    let (info, _) = models::find(&name).expect("a catalogue name");
    let mut at = Vec::new();
    for p in &info.params {
        if rng.random_bool(0.4) {
            at.push((p.name.clone(), value(rng, p.default)));
        }
    }
    (name, at)
}

fn method(rng: &mut StdRng) -> Method {
    [Method::Symbolic, Method::Numeric, Method::Robust][rng.random_range(0..3)]
}

/// `eom analyze`'s steps through the library. `Ok` with a count of results, or the first
/// typed error (as text).
fn analyze(name: &str, at: &[(&str, f64)], method: Method) -> Result<usize, String> {
    let m = models::build(name, at).map_err(|e| e.to_string())?;
    let lin = Linearizer::new(&m)
        .at(at)
        .method(method)
        .run()
        .map_err(|e| e.to_string())?;
    let ss = &lin.state_space;
    let modes = Modes::compute(ss).map_err(|e| e.to_string())?;
    let (ssm, _) =
        minimal_realization(ss, &MinrealOptions::default()).map_err(|e| e.to_string())?;
    let gains = steady_state_gain(&ssm).map_err(|e| e.to_string());
    let zeros = transmission_zeros(&ssm).map_err(|e| e.to_string());
    let fr = FrequencyResponse::compute(&ssm, &FreqOptions::default()).map_err(|e| e.to_string());
    Ok(modes.modes.len()
        + usize::from(gains.is_ok())
        + usize::from(zeros.is_ok())
        + usize::from(fr.is_ok()))
}

/// `eom sweep` through the library: one parameter from `lo` to `hi`, `count` values.
fn sweep(
    name: &str,
    at: &[(&str, f64)],
    param: &str,
    (lo, hi, count): (f64, f64, usize),
) -> Result<usize, String> {
    let m = models::build(name, at).map_err(|e| e.to_string())?;
    let r = Sweep::linspace(lo, hi, count)
        .with_param_name(param)
        .run(|x| {
            let mut point: Vec<(&str, f64)> = at.iter().filter(|p| p.0 != param).copied().collect();
            point.push((param, x));
            Linearizer::new(&m)
                .at(&point)
                .method(Method::Numeric)
                .run()
                .map(|l| l.state_space.a)
        })
        .map_err(|e| e.to_string())?;
    Ok(r.points.len())
}

/// One invocation.
#[derive(Debug)]
enum Job {
    Analyze {
        name: String,
        at: Vec<(String, f64)>,
        method: Method,
    },
    Sweep {
        name: String,
        at: Vec<(String, f64)>,
        param: String,
        bounds: (f64, f64, usize),
    },
}

fn job(rng: &mut StdRng, catalogue: &[ModelInfo]) -> Job {
    let (name, at) = pick(rng, catalogue);
    if !rng.random_bool(0.3) {
        return Job::Analyze {
            name,
            at,
            method: method(rng),
        };
    }
    let (info, _) = models::find(&name).expect("a catalogue name");
    let p = &info.params[rng.random_range(0..info.params.len())];
    let d = if p.default == 0.0 { 1.0 } else { p.default };
    let bounds = match rng.random_range(0..10) {
        0 => (-1e308, 1e308, 5),
        1 => (d, d, 3),
        _ => (
            d * rng.random_range(0.2..1.0),
            d * rng.random_range(1.0..5.0),
            rng.random_range(1..6),
        ),
    };
    Job::Sweep {
        name,
        at,
        param: p.name.clone(),
        bounds,
    }
}

/// A parameter point as the library takes it.
fn borrowed(at: &[(String, f64)]) -> Vec<(&str, f64)> {
    at.iter().map(|(k, v)| (k.as_str(), *v)).collect()
}

fn run_job(job: &Job) -> Result<usize, String> {
    match job {
        Job::Analyze { name, at, method } => analyze(name, &borrowed(at), *method),
        Job::Sweep {
            name,
            at,
            param,
            bounds,
        } => sweep(name, &borrowed(at), param, *bounds),
    }
}

#[test]
fn random_analyses_and_sweeps_end_cleanly_with_flat_memory() {
    let count = env_usize("EOM_SOAK_COUNT", CI_COUNT);
    let seed = env_usize("EOM_SOAK_SEED", 20261121) as u64;
    eom_num::budget::set_limit(MEMORY_CAP);
    let mut rng = StdRng::seed_from_u64(seed);
    let catalogue = models::catalogue();
    let (mut ok, mut refused) = (0usize, 0usize);
    let mut baseline: Option<isize> = None;
    let mut peak_growth = 0isize;
    // One long-lived worker thread runs the jobs (as one long-running process would), so
    // that a run that never ends fails the test by its budget instead of hanging it.
    let (jobs, inbox) = mpsc::channel::<Arc<Job>>();
    let (outbox, results) = mpsc::channel();
    std::thread::spawn(move || {
        for job in inbox {
            let outcome = catch_unwind(AssertUnwindSafe(|| run_job(&job)));
            drop(job);
            if outbox.send(outcome).is_err() {
                return;
            }
        }
    });
    let t0 = Instant::now();
    for run in 0..count {
        let job = Arc::new(job(&mut rng, &catalogue));
        let start = Instant::now();
        jobs.send(Arc::clone(&job)).expect("the worker is alive");
        let outcome = results
            .recv_timeout(RUN_BUDGET)
            .unwrap_or_else(|_| panic!("run {run} ({job:?}) did not end within {RUN_BUDGET:?}"));
        let took = start.elapsed();
        match outcome {
            Ok(Ok(_)) => ok += 1,
            Ok(Err(msg)) => {
                assert!(
                    !msg.is_empty() && msg.len() < 4000,
                    "run {run} ({job:?}): {msg}"
                );
                refused += 1;
            }
            Err(_) => panic!("run {run} ({job:?}) panicked"),
        }
        assert!(took < RUN_BUDGET, "run {run} ({job:?}) took {took:?}");
        let live = LIVE.load(Ordering::Relaxed);
        if run == count / 2 {
            baseline = Some(live);
        }
        if let Some(b) = baseline {
            peak_growth = peak_growth.max(live - b);
        }
        if std::env::var_os("EOM_SOAK_TRACE").is_some() && run % (count / 20).max(1) == 0 {
            eprintln!("run {run}: {live} bytes live");
        }
    }
    eprintln!(
        "soak: {count} runs (seed {seed}) in {:.1} s: {ok} results, {refused} typed errors; \
         live memory grew by at most {} bytes over the second half",
        t0.elapsed().as_secs_f64(),
        peak_growth
    );
    assert!(ok > count / 10, "most runs should succeed: {ok} of {count}");
    assert!(
        refused > 0,
        "the random values outside the ranges must be refused"
    );
    // Flat: no growth over the second half of the runs beyond an allowance for one-time
    // allocations of what a run meets first late in a short soak (the expressions of a model
    // or chain length not built before, kept by the pools); a leak grows with the runs. The
    // full soak stays within kilobytes once every model has been seen.
    assert!(
        peak_growth < 16 << 20,
        "live memory grew by {peak_growth} bytes over {count} runs"
    );
}
