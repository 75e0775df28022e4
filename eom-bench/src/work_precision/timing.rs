//! Wall-clock timing: the median over repeated samples.

use std::time::{Duration, Instant};

/// Shortest sample: fast batches are repeated within one sample so that the clock's
/// resolution and overhead do not count.
const MIN_SAMPLE: Duration = Duration::from_micros(20);

/// Median time per call in ns of `batch`, which makes `calls` calls. A sample runs the batch
/// enough times to last at least 20 µs; samples are taken until `min` has passed (at least 5),
/// and the median sample time is divided by the calls it made.
pub fn median_batch_ns(calls: usize, min: Duration, mut batch: impl FnMut()) -> f64 {
    let t = Instant::now();
    batch();
    let first = t.elapsed().max(Duration::from_nanos(1));
    let inner = (MIN_SAMPLE.as_secs_f64() / first.as_secs_f64())
        .ceil()
        .max(1.0) as usize;
    let start = Instant::now();
    let mut times = Vec::new();
    while times.len() < 5 || start.elapsed() < min {
        let t = Instant::now();
        for _ in 0..inner {
            batch();
        }
        times.push(t.elapsed().as_secs_f64());
    }
    median(&mut times) * 1e9 / (inner * calls.max(1)) as f64
}

/// The median of the values (the mean of the middle two for an even count); NaN when empty.
pub fn median(x: &mut [f64]) -> f64 {
    if x.is_empty() {
        return f64::NAN;
    }
    x.sort_by(f64::total_cmp);
    let n = x.len();
    if n % 2 == 1 {
        x[n / 2]
    } else {
        0.5 * (x[n / 2 - 1] + x[n / 2])
    }
}
