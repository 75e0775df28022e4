//! The generated modules (eom-codegen, compiled by `build.rs` for every built-in model) behind
//! one interface: the state matrix A at a point, and the median time of `eval_ab` per call.

use super::timing::median_batch_ns;
use nalgebra::DMatrix;
use std::time::Duration;

#[allow(missing_docs, clippy::all)]
mod code {
    include!(concat!(env!("OUT_DIR"), "/generated.rs"));
}

/// The bicycle's generated `f64` module (for the throughput sweep).
pub(crate) use code::gen64::bicycle as bicycle64;

/// The stability verdict without eigenvalues of a built-in model's generated `f64` module
/// (`eom codegen --stability`, compiled by `build.rs`).
#[derive(Clone, Copy)]
pub struct GenVerdict {
    /// The parameters, in the order [`GenVerdict::verdict`] takes their values.
    pub names: &'static [&'static str],
    /// `stability(p)`: `1` stable, `-1` unstable (or marginal), `0` undecided; `None` outside
    /// the validity region of the reduction's rank decisions.
    pub verdict: fn(&[f64]) -> Option<i8>,
    /// The verdicts of many points at once (`stability_many`: the first stage in packed
    /// lanes), as `verdict` gives them one by one; a point of the wrong length gets `None`.
    pub many: fn(&[Vec<f64>]) -> Vec<Option<i8>>,
}

macro_rules! verdict {
    ($m:path) => {{
        use $m as g;
        fn verdict(p: &[f64]) -> Option<i8> {
            let p: &[f64; g::N_PARAMS] = p.try_into().ok()?;
            g::stability(p).ok().map(|v| v as i8)
        }
        fn many(points: &[Vec<f64>]) -> Vec<Option<i8>> {
            let arrays: Vec<Option<[f64; g::N_PARAMS]>> = points
                .iter()
                .map(|p| p.as_slice().try_into().ok())
                .collect();
            let valid: Vec<[f64; g::N_PARAMS]> = arrays.iter().flatten().copied().collect();
            let mut out = vec![Ok(g::Verdict::Undecided); valid.len()];
            g::stability_many(&valid, &mut out);
            let mut verdicts = out.into_iter().map(|v| v.ok().map(|v| v as i8));
            arrays
                .iter()
                .map(|a| a.and_then(|_| verdicts.next().flatten()))
                .collect()
        }
        GenVerdict {
            names: &g::PARAM_NAMES,
            verdict,
            many,
        }
    }};
}

/// The generated stability verdict of a built-in model, where `build.rs` makes one (the
/// models of at most 16 states).
pub fn stability(model: &str) -> Option<GenVerdict> {
    use code::gen64;
    // One arm per model of `STABILITY`, written by build.rs.
    Some(include!(concat!(env!("OUT_DIR"), "/stability_match.rs")))
}

/// A and B (column-major, converted to `f64`).
pub type Ab = (DMatrix<f64>, DMatrix<f64>);

/// One generated module of one model.
#[derive(Clone, Copy)]
pub struct GenKernel {
    /// The method's label ("generated f64", …).
    pub label: &'static str,
    /// A (column-major, converted to `f64`) at a point, `None` outside the validity region.
    pub a: fn(&[f64]) -> Option<DMatrix<f64>>,
    /// A and B (converted to `f64`) at a point, `None` outside the validity region.
    pub ab: fn(&[f64]) -> Option<Ab>,
    /// Median time per `eval_ab` call in ns over the given points, repeated for at least the
    /// given duration (parameters converted to the module's type before the clock starts).
    pub time: fn(&[Vec<f64>], Duration) -> f64,
}

macro_rules! kernel {
    ($label:expr, $m:path, $ty:ty) => {{
        use $m as g;
        fn typed(p: &[f64]) -> [$ty; g::N_PARAMS] {
            core::array::from_fn(|k| p[k] as $ty)
        }
        fn ab(p: &[f64]) -> Option<$crate::work_precision::generated::Ab> {
            let (mut a, mut b, mut w) = ([0.0; g::A_LEN], [0.0; g::B_LEN], [0.0; g::WORK_LEN]);
            g::eval_ab(&typed(p), &mut a, &mut b, &mut w).ok()?;
            let (n, m) = (g::N_STATES, g::N_INPUTS);
            Some((
                DMatrix::from_iterator(n, n, a.iter().map(|&x| x as f64)),
                DMatrix::from_iterator(n, m, b.iter().map(|&x| x as f64)),
            ))
        }
        fn a(p: &[f64]) -> Option<DMatrix<f64>> {
            ab(p).map(|(a, _)| a)
        }
        fn time(points: &[Vec<f64>], min: Duration) -> f64 {
            type Kernel = fn(
                &[$ty; g::N_PARAMS],
                &mut [$ty; g::A_LEN],
                &mut [$ty; g::B_LEN],
                &mut [$ty; g::WORK_LEN],
            ) -> Result<(), g::Error>;
            let pts: Vec<[$ty; g::N_PARAMS]> = points.iter().map(|p| typed(p)).collect();
            let (mut a, mut b, mut w) = ([0.0; g::A_LEN], [0.0; g::B_LEN], [0.0; g::WORK_LEN]);
            // Through a function pointer hidden from the optimiser, as a separately compiled
            // object would be called.
            let f: Kernel = std::hint::black_box(g::eval_ab);
            median_batch_ns(pts.len(), min, || {
                for p in std::hint::black_box(&pts) {
                    let _ = std::hint::black_box(f(p, &mut a, &mut b, &mut w));
                }
                std::hint::black_box((&a, &b));
            })
        }
        GenKernel {
            label: $label,
            a,
            ab,
            time,
        }
    }};
}

/// The generated modules of a model: `f64`, `f32`, and the egg-simplified `f64` variant where
/// `build.rs` makes one. Empty for a model `build.rs` does not generate.
pub fn kernels(model: &str) -> Vec<GenKernel> {
    use code::{gen32, gen64};
    const F64: &str = "generated f64";
    const F32: &str = "generated f32";
    const EGG: &str = "generated f64 egg";
    // One arm per model of `MODELS`, written by build.rs.
    include!(concat!(env!("OUT_DIR"), "/kernels_match.rs"))
}
