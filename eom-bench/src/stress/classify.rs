//! How one method's result at one point is classed: accurate, reported failure, or silently
//! wrong; the eigenvalue error measure and the stability verdict behind it.

use crate::compare::match_eigenvalues;
use num_complex::Complex64;

/// Largest relative eigenvalue error still classed accurate.
pub const TOLERANCE: f64 = 1e-6;

/// Eigenvalues smaller than this fraction of the spectral radius are measured against
/// `FLOOR × radius` instead of their own magnitude: below it an eigenvalue is zero to the
/// accuracy asked of the others (an absolute error of 1e-12 of the spectral radius, about
/// 4500 ε, is accepted on it).
pub const FLOOR: f64 = 1e-6;

/// The outcome of one method at one point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Outcome {
    /// Eigenvalues within [`TOLERANCE`] of the reference and the same stability verdict.
    Accurate,
    /// The method returned an error, or a warning saying its result is doubtful.
    Reported,
    /// Neither accurate nor reported: wrong eigenvalues or verdict, and no word of it.
    SilentlyWrong,
    /// No reference at this point (none could be formed and no two independent methods
    /// agree): not classed.
    Unchecked,
}

impl Outcome {
    /// All outcomes, in table order.
    pub const ALL: [Outcome; 4] = [
        Outcome::Accurate,
        Outcome::Reported,
        Outcome::SilentlyWrong,
        Outcome::Unchecked,
    ];

    /// The label used in the CSV and the tables.
    pub fn label(self) -> &'static str {
        match self {
            Outcome::Accurate => "accurate",
            Outcome::Reported => "reported",
            Outcome::SilentlyWrong => "silently wrong",
            Outcome::Unchecked => "unchecked",
        }
    }
}

/// The stability verdict of a set of eigenvalues.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every eigenvalue decays.
    Stable,
    /// None grows, some neither decay nor grow.
    Marginal,
    /// Some eigenvalue grows.
    Unstable,
}

/// The reference's verdict where it is decisive: an eigenvalue with `Re λ > 1e-6 R` (R the
/// spectral radius) makes it unstable; all with `Re λ < −1e-6 R` stable; all with
/// `Re λ < −1e-6 R` or `|Re λ| ≤ 1e-12 R` (structural zeros, undamped modes) marginal; any
/// other real part is within the accuracy asked of the methods of the boundary and leaves the
/// verdict undecided (`None`: not compared).
pub fn reference_verdict(eigenvalues: &[Complex64]) -> Option<Verdict> {
    let r = radius(eigenvalues);
    let decisive = TOLERANCE * r;
    if eigenvalues.iter().any(|z| z.re > decisive) {
        return Some(Verdict::Unstable);
    }
    if eigenvalues.iter().all(|z| z.re < -decisive) {
        return Some(Verdict::Stable);
    }
    if eigenvalues
        .iter()
        .all(|z| z.re < -decisive || z.re.abs() <= 1e-12 * r)
    {
        return Some(Verdict::Marginal);
    }
    None
}

/// Largest modulus, at least the smallest positive normal number.
pub fn radius(eigenvalues: &[Complex64]) -> f64 {
    eigenvalues
        .iter()
        .fold(0.0f64, |m, z| m.max(z.norm()))
        .max(f64::MIN_POSITIVE)
}

/// The error of `got` against the reference `want`: the largest `|Δλ| / max(|λ|, FLOOR·R)`
/// over eigenvalues paired so that the largest distance is least (R the reference's spectral
/// radius); infinite when the counts differ or a value is not finite.
pub fn eigenvalue_error(got: &[Complex64], want: &[Complex64]) -> f64 {
    if got.len() != want.len() || got.iter().any(|z| !(z.re.is_finite() && z.im.is_finite())) {
        return f64::INFINITY;
    }
    let floor = FLOOR * radius(want);
    match_eigenvalues(got, want)
        .iter()
        .map(|(g, e)| (g - e).norm() / e.norm().max(floor))
        .fold(0.0, f64::max)
}

/// What a method returned at a point.
#[derive(Clone, Debug)]
pub enum MethodResult {
    /// An error (its message).
    Failed(String),
    /// Eigenvalues, the verdict the method's user gets, and the warnings that say the result
    /// is doubtful.
    Done {
        /// Eigenvalues.
        eigenvalues: Vec<Complex64>,
        /// The stability verdict (`eom analyze`'s modes).
        verdict: Verdict,
        /// Warnings saying the result is doubtful (empty when none).
        doubts: Vec<String>,
    },
}

/// Class one result against the reference eigenvalues (`None`: no reference). Returns the
/// outcome and the eigenvalue error where one was measured.
pub fn classify(result: &MethodResult, reference: Option<&[Complex64]>) -> (Outcome, Option<f64>) {
    let (eigenvalues, verdict, doubts) = match result {
        MethodResult::Failed(_) => return (Outcome::Reported, None),
        MethodResult::Done {
            eigenvalues,
            verdict,
            doubts,
        } => (eigenvalues, verdict, doubts),
    };
    let Some(want) = reference else {
        let o = if doubts.is_empty() {
            Outcome::Unchecked
        } else {
            Outcome::Reported
        };
        return (o, None);
    };
    let err = eigenvalue_error(eigenvalues, want);
    let verdict_ok = reference_verdict(want).is_none_or(|v| v == *verdict);
    let outcome = if err <= TOLERANCE && verdict_ok {
        Outcome::Accurate
    } else if !doubts.is_empty() {
        Outcome::Reported
    } else {
        Outcome::SilentlyWrong
    };
    (outcome, Some(err))
}

/// The verdict from per-mode stabilities (as `eom analyze` reports them).
pub fn verdict_of(stabilities: impl IntoIterator<Item = eom_num::modes::Stability>) -> Verdict {
    use eom_num::modes::Stability;
    let mut out = Verdict::Stable;
    for s in stabilities {
        match s {
            Stability::Unstable => return Verdict::Unstable,
            Stability::Marginal => out = Verdict::Marginal,
            Stability::Stable => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    fn done(e: Vec<Complex64>, verdict: Verdict) -> MethodResult {
        MethodResult::Done {
            eigenvalues: e,
            verdict,
            doubts: Vec::new(),
        }
    }

    #[test]
    fn a_wrong_eigenvalue_set_is_silently_wrong() {
        let want = [c(-1.0, 2.0), c(-1.0, -2.0), c(-0.5, 0.0)];
        let wrong = vec![c(-1.0, 2.0), c(-1.0, -2.0), c(-0.5 * (1.0 + 1e-5), 0.0)];
        let (o, err) = classify(&done(wrong.clone(), Verdict::Stable), Some(&want));
        assert_eq!(o, Outcome::SilentlyWrong);
        assert!((err.unwrap() - 1e-5).abs() < 1e-9);
        // The same with a doubt: reported.
        let doubted = MethodResult::Done {
            eigenvalues: wrong,
            verdict: Verdict::Stable,
            doubts: vec!["reduction: 1 redundant row".into()],
        };
        assert_eq!(classify(&doubted, Some(&want)).0, Outcome::Reported);
        // Close enough: accurate.
        let near = vec![c(-1.0, 2.0), c(-1.0, -2.0), c(-0.5 * (1.0 + 1e-8), 0.0)];
        assert_eq!(
            classify(&done(near, Verdict::Stable), Some(&want)).0,
            Outcome::Accurate
        );
    }

    #[test]
    fn a_missing_eigenvalue_or_wrong_verdict_is_silently_wrong() {
        let want = [c(0.3, 0.0), c(-2.0, 0.0)];
        let (o, err) = classify(&done(vec![c(0.3, 0.0)], Verdict::Unstable), Some(&want));
        assert_eq!((o, err), (Outcome::SilentlyWrong, Some(f64::INFINITY)));
        // Right values, wrong verdict.
        let (o, _) = classify(&done(want.to_vec(), Verdict::Stable), Some(&want));
        assert_eq!(o, Outcome::SilentlyWrong);
        assert_eq!(
            classify(&MethodResult::Failed("x".into()), Some(&want)).0,
            Outcome::Reported
        );
    }

    #[test]
    fn small_eigenvalues_are_measured_against_the_floor() {
        let want = [c(-1e-9, 0.0), c(-1.0, 0.0)];
        // 1e-13 off on an eigenvalue of 1e-9: 1e-4 of it but 1e-7 of the floor.
        let got = vec![c(-1e-9 - 1e-13, 0.0), c(-1.0, 0.0)];
        assert!(eigenvalue_error(&got, &want) <= 1.01e-7);
    }

    #[test]
    fn verdicts() {
        assert_eq!(
            reference_verdict(&[c(-1.0, 0.0), c(0.0, 0.0)]),
            Some(Verdict::Marginal)
        );
        assert_eq!(
            reference_verdict(&[c(-1.0, 0.0), c(1e-3, 1.0)]),
            Some(Verdict::Unstable)
        );
        assert_eq!(reference_verdict(&[c(-1.0, 0.0), c(-1e-9, 1.0)]), None);
    }
}
