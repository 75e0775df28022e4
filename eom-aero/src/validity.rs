//! Validity of the quasi-steady derivatives.
//!
//! A vortex lattice gives the loads of a steady flow. Using them in dynamics assumes the
//! wake adjusts instantly, which holds when the motion is slow against the time the air
//! takes to pass a chord: the reduced frequency β = ω c / V must be small (the usual
//! aerodynamic reduced frequency is k = ω c / 2V = β/2, with quasi-steady theory good for
//! k ≲ 0.05, i.e. β ≲ 0.1; Theodorsen's function departs from 1 by a few percent there).
//! The straight trailing legs also assume small flow angles and rates; AVL's user guide
//! gives |p b/2V| < 0.1, |q c/2V| < 0.03 and |r b/2V| < 0.25.

use serde::Serialize;

/// Reduced frequency β = ω c / V above which quasi-steady derivatives deserve a warning.
pub const REDUCED_FREQUENCY_LIMIT: f64 = 0.1;
/// Limit of |p b / 2V|.
pub const ROLL_RATE_LIMIT: f64 = 0.10;
/// Limit of |q c / 2V|.
pub const PITCH_RATE_LIMIT: f64 = 0.03;
/// Limit of |r b / 2V|.
pub const YAW_RATE_LIMIT: f64 = 0.25;

/// Reduced frequency β = |Im λ| · c / V of an eigenvalue λ with imaginary part
/// `eigen_imag` (rad/s), for chord `chord` (m) and airspeed `speed` (m/s). Infinite for
/// zero airspeed with nonzero frequency, NaN never: zero frequency gives 0.
pub fn reduced_frequency(eigen_imag: f64, chord: f64, speed: f64) -> f64 {
    let w = eigen_imag.abs();
    if w == 0.0 {
        0.0
    } else {
        w * chord / speed.abs()
    }
}

/// Whether a reduced frequency exceeds [`REDUCED_FREQUENCY_LIMIT`].
pub fn reduced_frequency_too_high(beta: f64) -> bool {
    beta > REDUCED_FREQUENCY_LIMIT
}

/// Normalised rates p b/2V, q c/2V, r b/2V and which of them exceed their limits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RateCheck {
    /// p·b/2V, q·c/2V, r·b/2V.
    pub normalised: [f64; 3],
    /// Limits 0.10, 0.03, 0.25.
    pub limits: [f64; 3],
    /// `exceeded[k]` is true if `|normalised[k]| ≥ limits[k]` (or it is NaN).
    pub exceeded: [bool; 3],
}

impl RateCheck {
    /// Whether all three rates are within their limits.
    pub fn ok(&self) -> bool {
        !self.exceeded.iter().any(|&e| e)
    }
}

/// Normalises body rates `p, q, r` (rad/s) with span `span`, chord `chord` and airspeed
/// `speed`, and compares them with the limits.
pub fn check_rates(p: f64, q: f64, r: f64, span: f64, chord: f64, speed: f64) -> RateCheck {
    let v2 = 2.0 * speed.abs();
    let normalised = [p * span / v2, q * chord / v2, r * span / v2];
    let limits = [ROLL_RATE_LIMIT, PITCH_RATE_LIMIT, YAW_RATE_LIMIT];
    // NaN rates count as exceeded
    let exceeded = std::array::from_fn(|k| {
        normalised[k].abs().partial_cmp(&limits[k]) != Some(std::cmp::Ordering::Less)
    });
    RateCheck {
        normalised,
        limits,
        exceeded,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shimmy_example_is_borderline() {
        // ω = 2.3 rad/s, c = 0.5 m, V = 10 m/s → β = 0.115
        let b = reduced_frequency(-2.3, 0.5, 10.0);
        assert!((b - 0.115).abs() < 1e-12);
        assert!(reduced_frequency_too_high(b));
        assert!(!reduced_frequency_too_high(reduced_frequency(
            1.0, 0.5, 10.0
        )));
        assert!(reduced_frequency(1.0, 0.5, 0.0).is_infinite());
    }

    #[test]
    fn rate_limits() {
        let c = check_rates(1.0, 0.5, 2.0, 1.0, 0.5, 10.0);
        assert_eq!(c.normalised, [0.05, 0.0125, 0.1]);
        assert!(c.ok());
        let c = check_rates(0.0, 2.0, 0.0, 1.0, 0.5, 10.0);
        assert_eq!(c.exceeded, [false, true, false]);
        assert!(!check_rates(f64::NAN, 0.0, 0.0, 1.0, 1.0, 1.0).ok());
    }
}
