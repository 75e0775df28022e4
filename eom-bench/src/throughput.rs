//! Throughput of a parameter sweep on one machine (`eom bench throughput`): the bicycle's
//! generated `f64` code (`eval_ab`, compiled into this crate by `build.rs`) and the eigenvalues
//! of its A at many random parameter points, in parallel with rayon — the basis for
//! estimating what a sweep needs when it outgrows one machine. The eigenvalues come from the
//! stack kernel `eom_num::small_eigen` with the structural zeros found once, at the nominal
//! point, and checked and deflated at every point (`eigenvalues_small_known`).
//!
//! The same points also go through the generated batch verdict `stability_many` (eom-codegen's
//! `--stability`: the Liénard–Chipart conditions of the closed-form characteristic polynomial
//! with their rounding-error bounds, no eigenvalues; its first stage four points at a time),
//! timed on its own, and its verdict is compared with the eigenvalues': the undecided points
//! and any disagreement are counted.
//!
//! The points: every one of the 27 parameters drawn uniformly within nominal × (1 ± spread)
//! (the speed too, so that with the default ±20 % the sweep crosses the weave and the capsize
//! speeds and both stable and unstable points occur). Point `k` depends only on the seed and `k`
//! ([`point`]: a counter-based generator), so the result does not depend on the number of
//! threads and a plain loop can reproduce it.
//!
//! Each thread takes chunks of points and times three phases per chunk: drawing the points,
//! evaluating A, and the eigenvalues — by the wall clock and by the thread's CPU time
//! ([`thread_cpu_time`], Linux), so that on a shared machine, where a thread waits for a core,
//! the per-point costs and the points per CPU second still say what the code costs. The summary (how many points are stable, the extremes of
//! the largest real part) is what the work produces, so none of it can be optimised away.

use crate::work_precision::generated::bicycle64 as model;
use eom_num::small_eigen::{KnownZeros, eigenvalues_small, eigenvalues_small_known};
use num_complex::Complex64;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Number of parameters of the swept model.
pub const N_PARAMS: usize = model::N_PARAMS;

/// Points per chunk: a thread's unit of work (large enough that timing it costs nothing).
const CHUNK: usize = 4096;

/// What can go wrong.
#[derive(Debug, thiserror::Error)]
pub enum ThroughputError {
    /// The thread pool could not be built.
    #[error("thread pool: {0}")]
    Pool(String),
}

/// Options of [`run`].
#[derive(Clone, Debug)]
pub struct Options {
    /// Number of parameter points.
    pub points: usize,
    /// Worker threads (at least 1).
    pub threads: usize,
    /// Each parameter is drawn uniformly within nominal × (1 ± spread).
    pub spread: f64,
    /// Seed of the points.
    pub seed: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            points: 1_000_000,
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            spread: 0.2,
            seed: 20261121,
        }
    }
}

/// What the sweep found and how long it took.
#[derive(Clone, Debug, PartialEq)]
pub struct Throughput {
    /// Points asked for.
    pub points: usize,
    /// Worker threads used.
    pub threads: usize,
    /// Wall-clock time of the sweep (points, generated code, eigenvalues).
    pub wall: Duration,
    /// Wall-clock time of the second pass: the generated verdicts of the same points.
    pub verdict_wall: Duration,
    /// Thread time spent drawing the points (summed over threads).
    pub sample: Duration,
    /// Thread time spent in the generated code.
    pub eval: Duration,
    /// Thread time spent in the eigenvalues.
    pub eigen: Duration,
    /// Thread time spent in the generated stability verdict.
    pub verdict: Duration,
    /// The same four phases by the threads' CPU time (drawing, generated code, eigenvalues,
    /// verdict; summed over threads), where the platform tells it ([`thread_cpu_time`]).
    pub cpu: Option<[Duration; 4]>,
    /// The summary of the results.
    pub summary: Summary,
}

/// What the sweep computed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    /// Points where the generated code reported leaving its validity region.
    pub eval_failures: usize,
    /// Points where the eigenvalues failed.
    pub eigen_failures: usize,
    /// Points where every non-zero eigenvalue has a negative real part (the two structural
    /// zeros, heading and lateral position, are exactly 0 and do not feed back).
    pub stable: usize,
    /// Smallest, over the points, of the largest real part of the non-zero eigenvalues.
    pub min_max_re: f64,
    /// Largest, over the points, of the largest real part of the non-zero eigenvalues.
    pub max_max_re: f64,
    /// Points the generated verdict calls stable.
    pub verdict_stable: usize,
    /// Points the generated verdict leaves undecided (a condition within its rounding bound
    /// of zero).
    pub verdict_undecided: usize,
    /// Points where the generated verdict failed (outside the validity region).
    pub verdict_failures: usize,
    /// Points where the generated verdict is decided and differs from the eigenvalues'.
    pub disagreements: usize,
}

impl Summary {
    fn empty() -> Self {
        Summary {
            min_max_re: f64::INFINITY,
            max_max_re: f64::NEG_INFINITY,
            ..Summary::default()
        }
    }

    /// Adds the eigenvalues of one point; whether they say it is stable.
    pub fn add(&mut self, eigenvalues: &[Complex64]) -> bool {
        let re = largest_real_part(eigenvalues);
        if re < 0.0 {
            self.stable += 1;
        }
        self.min_max_re = self.min_max_re.min(re);
        self.max_max_re = self.max_max_re.max(re);
        re < 0.0
    }

    /// Adds the generated verdict of a point whose eigenvalues said `stable` (`None`: they
    /// failed).
    fn add_verdict(&mut self, verdict: Verdicted, stable: Option<bool>) {
        match verdict {
            Err(_) => self.verdict_failures += 1,
            Ok(model::Verdict::Undecided) => self.verdict_undecided += 1,
            Ok(v) => {
                let says = v == model::Verdict::Stable;
                self.verdict_stable += usize::from(says);
                if stable.is_some_and(|s| s != says) {
                    self.disagreements += 1;
                }
            }
        }
    }

    fn merge(mut self, o: Summary) -> Summary {
        self.eval_failures += o.eval_failures;
        self.eigen_failures += o.eigen_failures;
        self.stable += o.stable;
        self.min_max_re = self.min_max_re.min(o.min_max_re);
        self.max_max_re = self.max_max_re.max(o.max_max_re);
        self.verdict_stable += o.verdict_stable;
        self.verdict_undecided += o.verdict_undecided;
        self.verdict_failures += o.verdict_failures;
        self.disagreements += o.disagreements;
        self
    }
}

/// The largest real part of the eigenvalues that are not exactly 0 (−∞ if there are none).
pub fn largest_real_part(eigenvalues: &[Complex64]) -> f64 {
    eigenvalues
        .iter()
        .filter(|z| **z != Complex64::new(0.0, 0.0))
        .fold(f64::NEG_INFINITY, |m, z| m.max(z.re))
}

impl Throughput {
    /// Points per second over the whole sweep (wall clock).
    pub fn points_per_second(&self) -> f64 {
        self.points as f64 / self.wall.as_secs_f64().max(1e-9)
    }

    /// Points per second and thread.
    pub fn points_per_second_per_thread(&self) -> f64 {
        self.points_per_second() / self.threads as f64
    }

    /// Generated verdicts per second of thread time.
    pub fn verdicts_per_thread_second(&self) -> f64 {
        self.points as f64 / self.verdict.as_secs_f64().max(1e-12)
    }

    /// Points per second of one thread's CPU time (drawing, generated code and eigenvalues),
    /// where the CPU time is known: what one core gets through when it is not shared.
    pub fn points_per_cpu_second(&self) -> Option<f64> {
        let [a, b, c, _] = self.cpu?;
        Some(self.points as f64 / (a + b + c).as_secs_f64().max(1e-12))
    }

    /// Generated verdicts per second of one thread's CPU time, where it is known.
    pub fn verdicts_per_cpu_second(&self) -> Option<f64> {
        let [.., v] = self.cpu?;
        Some(self.points as f64 / v.as_secs_f64().max(1e-12))
    }

    /// Thread time per point of a phase, in ns.
    pub fn ns_per_point(&self, phase: Duration) -> f64 {
        phase.as_secs_f64() * 1e9 / self.points.max(1) as f64
    }
}

/// The parameter names of the swept model (the bicycle's, in the order of [`point`]).
pub fn parameter_names() -> &'static [&'static str; N_PARAMS] {
    &model::PARAM_NAMES
}

/// SplitMix64 (Steele, Lea & Flood 2014): a counter-based generator, so that point `k` is a
/// function of the seed and `k` alone.
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Parameter point `k` of the sweep: parameter `j` is nominal × (1 + spread·(2u − 1)) with `u`
/// uniform in [0, 1) from (seed, k, j).
pub fn point(seed: u64, spread: f64, k: u64) -> [f64; N_PARAMS] {
    let base = splitmix64(seed ^ splitmix64(k));
    core::array::from_fn(|j| {
        let u = (splitmix64(base.wrapping_add(j as u64)) >> 11) as f64 / (1u64 << 53) as f64;
        model::NOMINAL[j] * (1.0 + spread * (2.0 * u - 1.0))
    })
}

/// Per-thread scratch: the chunk's parameters and matrices, the eigenvalues of one point.
struct Scratch {
    params: Vec<[f64; N_PARAMS]>,
    mats: Vec<[f64; model::A_LEN]>,
    ok: Vec<bool>,
    eig: Vec<Complex64>,
    /// Per point of the chunk: the eigenvalues' verdict (`None`: no eigenvalues).
    stable: Vec<Option<bool>>,
    verdicts: Vec<Verdicted>,
}

impl Scratch {
    fn new() -> Self {
        Scratch {
            params: Vec::with_capacity(CHUNK),
            mats: Vec::with_capacity(CHUNK),
            ok: Vec::with_capacity(CHUNK),
            eig: vec![Complex64::new(0.0, 0.0); model::N_STATES],
            stable: Vec::with_capacity(CHUNK),
            verdicts: Vec::with_capacity(CHUNK),
        }
    }
}

/// The structural zeros of the bicycle's A (heading and lateral position), found at the
/// nominal point (`None` if A cannot be evaluated there: every point then searches for its
/// own).
fn known_zeros() -> Option<KnownZeros> {
    let (mut a, mut b, mut w) = (
        [0.0; model::A_LEN],
        [0.0; model::B_LEN],
        [0.0; model::WORK_LEN],
    );
    model::eval_ab(&model::NOMINAL, &mut a, &mut b, &mut w)
        .ok()
        .and_then(|()| KnownZeros::of(&a, model::N_STATES).ok())
}

/// The CPU time the calling thread has used (Linux: `/proc/thread-self/schedstat`, in ns);
/// `None` elsewhere. Unlike the wall clock it does not count the time a thread waits for a
/// core, which is most of the time on a machine shared with other jobs. The kernel brings the
/// figure up to date only at its scheduler ticks and context switches, so over a phase of a
/// chunk (a few ms) it is a sample: summed over many chunks it is unbiased, the total exact,
/// but a short phase (drawing the points) carries tens of per cent of sampling noise at 10⁵
/// points.
pub fn thread_cpu_time() -> Option<Duration> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = text.split_whitespace().next()?.parse().ok()?;
    Some(Duration::from_nanos(ns))
}

/// The differences of consecutive CPU time readings (`None` if one is missing).
fn cpu_phases<const N: usize, const M: usize>(t: [Option<Duration>; M]) -> Option<[Duration; N]> {
    let mut out = [Duration::ZERO; N];
    for (k, o) in out.iter_mut().enumerate() {
        *o = t[k + 1]?.saturating_sub(t[k]?);
    }
    Some(out)
}

/// Times (drawing, generated code, eigenvalues) by the wall clock and by the thread's CPU
/// time, summary and the eigenvalues' verdict per point (`None`: no eigenvalues) of one chunk.
type ChunkResult = (
    [Duration; 3],
    Option<[Duration; 3]>,
    Summary,
    Vec<Option<bool>>,
);

fn chunk(s: &mut Scratch, known: Option<&KnownZeros>, opts: &Options, c: usize) -> ChunkResult {
    let (start, end) = (c * CHUNK, ((c + 1) * CHUNK).min(opts.points));
    let mut summary = Summary::empty();
    let (t0, c0) = (Instant::now(), thread_cpu_time());
    s.params.clear();
    s.params
        .extend((start..end).map(|k| point(opts.seed, opts.spread, k as u64)));
    let (t1, c1) = (Instant::now(), thread_cpu_time());
    s.mats.clear();
    s.ok.clear();
    let (mut b, mut w) = ([0.0; model::B_LEN], [0.0; model::WORK_LEN]);
    for p in &s.params {
        let mut a = [0.0; model::A_LEN];
        let ok = model::eval_ab(p, &mut a, &mut b, &mut w).is_ok();
        s.mats.push(a);
        s.ok.push(ok);
    }
    std::hint::black_box(&b);
    let (t2, c2) = (Instant::now(), thread_cpu_time());
    s.stable.clear();
    for (a, &ok) in s.mats.iter().zip(&s.ok) {
        if !ok {
            summary.eval_failures += 1;
            s.stable.push(None);
            continue;
        }
        let found = match known {
            Some(k) => eigenvalues_small_known(a, model::N_STATES, k, &mut s.eig),
            None => eigenvalues_small(a, model::N_STATES, &mut s.eig),
        };
        match found {
            Ok(_) => s.stable.push(Some(summary.add(&s.eig))),
            Err(_) => {
                summary.eigen_failures += 1;
                s.stable.push(None);
            }
        }
    }
    let (t3, c3) = (Instant::now(), thread_cpu_time());
    (
        [t1 - t0, t2 - t1, t3 - t2],
        cpu_phases([c0, c1, c2, c3]),
        summary,
        s.stable.clone(),
    )
}

/// The generated verdicts of the points of chunk `c`, and the thread time they took (wall
/// clock, CPU).
type VerdictChunk = (Duration, Option<Duration>, Vec<Verdicted>);

fn verdict_chunk(s: &mut Scratch, opts: &Options, c: usize) -> VerdictChunk {
    let (start, end) = (c * CHUNK, ((c + 1) * CHUNK).min(opts.points));
    s.params.clear();
    s.params
        .extend((start..end).map(|k| point(opts.seed, opts.spread, k as u64)));
    let (t0, c0) = (Instant::now(), thread_cpu_time());
    s.verdicts.clear();
    s.verdicts
        .resize(s.params.len(), Ok(model::Verdict::Undecided));
    model::stability_many(std::hint::black_box(&s.params), &mut s.verdicts);
    let (wall, c1) = (t0.elapsed(), thread_cpu_time());
    let cpu = cpu_phases::<1, 2>([c0, c1]).map(|[d]| d);
    (wall, cpu, s.verdicts.clone())
}

/// A generated verdict.
type Verdicted = Result<model::Verdict, model::Error>;

/// Sweeps `opts.points` random points of the bicycle on `opts.threads` threads.
pub fn run(opts: &Options) -> Result<Throughput, ThroughputError> {
    let threads = opts.threads.max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| ThroughputError::Pool(e.to_string()))?;
    let chunks = opts.points.div_ceil(CHUNK);
    let known = known_zeros();
    let start = Instant::now();
    let chunked: Vec<ChunkResult> = pool.install(|| {
        (0..chunks)
            .into_par_iter()
            .map_init(Scratch::new, |s, c| chunk(s, known.as_ref(), opts, c))
            .collect()
    });
    let wall = start.elapsed();
    // The verdicts without eigenvalues: a second pass over the same points.
    let start = Instant::now();
    let verdicts: Vec<VerdictChunk> = pool.install(|| {
        (0..chunks)
            .into_par_iter()
            .map_init(Scratch::new, |s, c| verdict_chunk(s, opts, c))
            .collect()
    });
    let verdict_wall = start.elapsed();
    let (mut times, mut summary, mut verdict) =
        ([Duration::ZERO; 3], Summary::empty(), Duration::ZERO);
    let mut cpu = Some([Duration::ZERO; 4]);
    for ((t, tc, sum, stable), (tv, vc, v)) in chunked.into_iter().zip(verdicts) {
        for k in 0..3 {
            times[k] += t[k];
        }
        verdict += tv;
        cpu = match (cpu, tc, vc) {
            (Some(mut acc), Some(tc), Some(vc)) => {
                for k in 0..3 {
                    acc[k] += tc[k];
                }
                acc[3] += vc;
                Some(acc)
            }
            _ => None,
        };
        let mut sum = sum;
        for (v, st) in v.into_iter().zip(stable) {
            sum.add_verdict(v, st);
        }
        summary = summary.merge(sum);
    }
    Ok(Throughput {
        points: opts.points,
        threads,
        wall,
        verdict_wall,
        sample: times[0],
        eval: times[1],
        eigen: times[2],
        verdict,
        cpu,
        summary,
    })
}

/// The report as text.
pub fn to_text(t: &Throughput) -> String {
    let s = &t.summary;
    let evaluated = t.points - s.eval_failures - s.eigen_failures;
    let decided = t.points - s.verdict_undecided - s.verdict_failures;
    let cpu = match (
        t.cpu,
        t.points_per_cpu_second(),
        t.verdicts_per_cpu_second(),
    ) {
        (Some([a, b, c, v]), Some(pps), Some(vps)) => format!(
            "thread CPU time per point: {:.1} ns drawing the point, {:.1} ns generated code, \
             {:.1} ns eigenvalues ({:.1}× the generated code), {:.1} ns verdict; \
             {:.0} points and {:.0} verdicts per CPU second\n",
            t.ns_per_point(a),
            t.ns_per_point(b),
            t.ns_per_point(c),
            c.as_secs_f64() / b.as_secs_f64().max(1e-12),
            t.ns_per_point(v),
            pps,
            vps,
        ),
        _ => String::new(),
    };
    format!(
        "Throughput: bicycle, generated f64 code (eval_ab) + eigenvalues, {} random points \
         (27 parameters within ±20 % of nominal), {} thread(s)\n\
         wall time: {:.3} s\n\
         points/s: {:.0} total, {:.0} per thread\n\
         thread time per point: {:.1} ns drawing the point, {:.1} ns generated code, \
         {:.1} ns eigenvalues ({:.1}× the generated code)\n\
         {}\
         generated code failures: {}\n\
         eigenvalue failures: {}\n\
         stable points: {} of {} ({:.2} %)\n\
         largest real part of the non-zero eigenvalues: from {:.6e} to {:.6e} 1/s\n\
         stability verdict without eigenvalues (generated `stability_many`): {:.1} ns per point, \
         {:.0} verdicts/s per thread\n\
         verdicts: {} stable, {} unstable, {} undecided (a condition within its rounding \
         bound of zero), {} failed; {} of the {} decided differ from the eigenvalues' verdict\n",
        t.points,
        t.threads,
        t.wall.as_secs_f64(),
        t.points_per_second(),
        t.points_per_second_per_thread(),
        t.ns_per_point(t.sample),
        t.ns_per_point(t.eval),
        t.ns_per_point(t.eigen),
        t.eigen.as_secs_f64() / t.eval.as_secs_f64().max(1e-12),
        cpu,
        s.eval_failures,
        s.eigen_failures,
        s.stable,
        evaluated,
        100.0 * s.stable as f64 / evaluated.max(1) as f64,
        s.min_max_re,
        s.max_max_re,
        t.ns_per_point(t.verdict),
        t.verdicts_per_thread_second(),
        s.verdict_stable,
        decided - s.verdict_stable,
        s.verdict_undecided,
        s.verdict_failures,
        s.disagreements,
        decided,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_phases_are_the_differences_of_the_readings() {
        let ms = |k| Some(Duration::from_millis(k));
        assert_eq!(
            cpu_phases::<3, 4>([ms(1), ms(3), ms(6), ms(10)]),
            Some([2, 3, 4].map(Duration::from_millis))
        );
        assert_eq!(cpu_phases::<3, 4>([ms(1), None, ms(6), ms(10)]), None);
        // On Linux the thread's CPU time is known and does not go back.
        if cfg!(target_os = "linux") {
            let a = thread_cpu_time().expect("schedstat");
            let b = thread_cpu_time().expect("schedstat");
            assert!(b >= a, "{a:?} then {b:?}");
        }
    }

    #[test]
    fn points_are_within_the_spread_and_reproducible() {
        for k in [0u64, 1, 4095, 4096, 999_999] {
            let p = point(7, 0.2, k);
            assert_eq!(p, point(7, 0.2, k));
            for (x, n) in p.iter().zip(model::NOMINAL) {
                let f = x / n;
                assert!((0.8..=1.2).contains(&f), "point {k}: {x} vs nominal {n}");
            }
        }
        assert_ne!(point(7, 0.2, 0), point(7, 0.2, 1));
        assert_ne!(point(7, 0.2, 0), point(8, 0.2, 0));
    }

    #[test]
    fn the_result_does_not_depend_on_the_threads() {
        let opts = |threads| Options {
            points: 3 * CHUNK + 17,
            threads,
            ..Options::default()
        };
        let one = run(&opts(1)).expect("sweep");
        let two = run(&opts(2)).expect("sweep");
        assert_eq!(one.summary, two.summary);
        assert_eq!(one.summary.eval_failures + one.summary.eigen_failures, 0);
        assert!(one.summary.stable > 0 && one.summary.stable < one.points);
        // The verdict without eigenvalues agrees wherever it decides.
        assert_eq!(one.summary.disagreements, 0);
        assert_eq!(one.summary.verdict_failures, 0);
    }
}
