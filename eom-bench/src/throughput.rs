//! Throughput of a parameter sweep on one machine (`eom bench throughput`): the bicycle's
//! generated `f64` code (`eval_ab`, compiled into this crate by `build.rs`) and the eigenvalues
//! of its A at many random parameter points, in parallel with rayon — the basis for
//! estimating what a sweep needs when it outgrows one machine. The eigenvalues come from the
//! stack kernel `eom_num::small_eigen` with the structural zeros found once, at the nominal
//! point, and checked and deflated at every point (`eigenvalues_small_known`).
//!
//! The points: every one of the 27 parameters drawn uniformly within nominal × (1 ± spread)
//! (the speed too, so that with the default ±20 % the sweep crosses the weave and the capsize
//! speeds and both stable and unstable points occur). Point `k` depends only on the seed and `k`
//! ([`point`]: a counter-based generator), so the result does not depend on the number of
//! threads and a plain loop can reproduce it.
//!
//! Each thread takes chunks of points and times three phases per chunk: drawing the points,
//! evaluating A, and the eigenvalues. The summary (how many points are stable, the extremes of
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
    /// Wall-clock time of the whole sweep.
    pub wall: Duration,
    /// Thread time spent drawing the points (summed over threads).
    pub sample: Duration,
    /// Thread time spent in the generated code.
    pub eval: Duration,
    /// Thread time spent in the eigenvalues.
    pub eigen: Duration,
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
}

impl Summary {
    fn empty() -> Self {
        Summary {
            min_max_re: f64::INFINITY,
            max_max_re: f64::NEG_INFINITY,
            ..Summary::default()
        }
    }

    /// Adds the eigenvalues of one point.
    pub fn add(&mut self, eigenvalues: &[Complex64]) {
        let re = largest_real_part(eigenvalues);
        if re < 0.0 {
            self.stable += 1;
        }
        self.min_max_re = self.min_max_re.min(re);
        self.max_max_re = self.max_max_re.max(re);
    }

    fn merge(mut self, o: Summary) -> Summary {
        self.eval_failures += o.eval_failures;
        self.eigen_failures += o.eigen_failures;
        self.stable += o.stable;
        self.min_max_re = self.min_max_re.min(o.min_max_re);
        self.max_max_re = self.max_max_re.max(o.max_max_re);
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
}

impl Scratch {
    fn new() -> Self {
        Scratch {
            params: Vec::with_capacity(CHUNK),
            mats: Vec::with_capacity(CHUNK),
            ok: Vec::with_capacity(CHUNK),
            eig: vec![Complex64::new(0.0, 0.0); model::N_STATES],
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

/// Times and summary of one chunk.
type ChunkResult = (Duration, Duration, Duration, Summary);

fn chunk(s: &mut Scratch, known: Option<&KnownZeros>, opts: &Options, c: usize) -> ChunkResult {
    let (start, end) = (c * CHUNK, ((c + 1) * CHUNK).min(opts.points));
    let mut summary = Summary::empty();
    let t0 = Instant::now();
    s.params.clear();
    s.params
        .extend((start..end).map(|k| point(opts.seed, opts.spread, k as u64)));
    let t1 = Instant::now();
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
    let t2 = Instant::now();
    for (a, &ok) in s.mats.iter().zip(&s.ok) {
        if !ok {
            summary.eval_failures += 1;
            continue;
        }
        let found = match known {
            Some(k) => eigenvalues_small_known(a, model::N_STATES, k, &mut s.eig),
            None => eigenvalues_small(a, model::N_STATES, &mut s.eig),
        };
        match found {
            Ok(_) => summary.add(&s.eig),
            Err(_) => summary.eigen_failures += 1,
        }
    }
    let t3 = Instant::now();
    (t1 - t0, t2 - t1, t3 - t2, summary)
}

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
    let zero = (
        Duration::ZERO,
        Duration::ZERO,
        Duration::ZERO,
        Summary::empty(),
    );
    let (sample, eval, eigen, summary) = pool.install(|| {
        (0..chunks)
            .into_par_iter()
            .map_init(Scratch::new, |s, c| chunk(s, known.as_ref(), opts, c))
            .reduce(
                || zero.clone(),
                |x, y| (x.0 + y.0, x.1 + y.1, x.2 + y.2, x.3.merge(y.3)),
            )
    });
    Ok(Throughput {
        points: opts.points,
        threads,
        wall: start.elapsed(),
        sample,
        eval,
        eigen,
        summary,
    })
}

/// The report as text.
pub fn to_text(t: &Throughput) -> String {
    let s = &t.summary;
    let evaluated = t.points - s.eval_failures - s.eigen_failures;
    format!(
        "Throughput: bicycle, generated f64 code (eval_ab) + eigenvalues, {} random points \
         (27 parameters within ±20 % of nominal), {} thread(s)\n\
         wall time: {:.3} s\n\
         points/s: {:.0} total, {:.0} per thread\n\
         thread time per point: {:.1} ns drawing the point, {:.1} ns generated code, \
         {:.1} ns eigenvalues\n\
         generated code failures: {}\n\
         eigenvalue failures: {}\n\
         stable points: {} of {} ({:.2} %)\n\
         largest real part of the non-zero eigenvalues: from {:.6e} to {:.6e} 1/s\n",
        t.points,
        t.threads,
        t.wall.as_secs_f64(),
        t.points_per_second(),
        t.points_per_second_per_thread(),
        t.ns_per_point(t.sample),
        t.ns_per_point(t.eval),
        t.ns_per_point(t.eigen),
        s.eval_failures,
        s.eigen_failures,
        s.stable,
        evaluated,
        100.0 * s.stable as f64 / evaluated.max(1) as f64,
        s.min_max_re,
        s.max_max_re,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }
}
