//! The closed-form reference of the chain (an independent one: no assembly, no reduction):
//! the eigenvalues `±i ω` of the undamped fixed-free chain, `ω²` the eigenvalues of the
//! symmetric tridiagonal `M^{-1/2} K M^{-1/2}`, found by bisection on Sturm counts in
//! double-double arithmetic (each `ω²` to about 1e-30 relative). A massless interior body is
//! the limit of the chain: its two springs act in series and it has no state.

use eom_sym::Dd;
use num_complex::Complex64;

/// The eigenvalues of the chain with these masses (body i between springs i and i+1, the
/// first spring to the ground, the last body free) and spring stiffnesses.
pub fn eigenvalues(masses: &[f64], springs: &[f64]) -> Vec<Complex64> {
    let (m, k) = without_massless(masses, springs);
    let n = m.len();
    // K: diagonal k_i + k_{i+1}, off-diagonal −k_{i+1}; scaled by the masses.
    let diag: Vec<Dd> = (0..n)
        .map(|i| {
            let next = if i + 1 < n {
                k[i + 1]
            } else {
                Dd::from_f64(0.0)
            };
            (k[i] + next) / m[i]
        })
        .collect();
    let off2: Vec<Dd> = (0..n.saturating_sub(1))
        .map(|i| k[i + 1] * k[i + 1] / (m[i] * m[i + 1]))
        .collect();
    // Gershgorin: every ω² is below the largest row sum of |entries|.
    let mut upper = Dd::from_f64(0.0);
    for i in 0..n {
        let mut s = diag[i];
        if i > 0 {
            s += off2[i - 1].sqrt();
        }
        if i + 1 < n {
            s += off2[i].sqrt();
        }
        if s > upper {
            upper = s;
        }
    }
    let upper = upper * Dd::from_f64(1.01);
    let mut out = Vec::with_capacity(2 * n);
    for j in 0..n {
        let w2 = bisect(&diag, &off2, j, upper);
        let w = w2.sqrt().to_f64();
        out.push(Complex64::new(0.0, w));
        out.push(Complex64::new(0.0, -w));
    }
    out
}

/// Masses and springs as double-double, an interior massless body removed (its springs in
/// series).
fn without_massless(masses: &[f64], springs: &[f64]) -> (Vec<Dd>, Vec<Dd>) {
    let mut m = Vec::new();
    let mut k: Vec<Dd> = Vec::new();
    let mut carry: Option<Dd> = None;
    for (i, (&mi, &ki)) in masses.iter().zip(springs).enumerate() {
        let ki = Dd::from_f64(ki);
        // The spring into body i, in series with the spring carried over a massless body.
        let into = match carry.take() {
            Some(c) => c * ki / (c + ki),
            None => ki,
        };
        if mi == 0.0 && i + 1 < masses.len() {
            carry = Some(into);
            continue;
        }
        m.push(Dd::from_f64(mi));
        k.push(into);
    }
    (m, k)
}

/// Number of eigenvalues below `x` (Sturm count of the LDLᵀ factorisation of T − x I).
fn count_below(diag: &[Dd], off2: &[Dd], x: Dd) -> usize {
    let tiny = Dd::from_f64(1e-300);
    let zero = Dd::from_f64(0.0);
    let mut count = 0;
    let mut d = diag[0] - x;
    for i in 0..diag.len() {
        if i > 0 {
            d = diag[i] - x - off2[i - 1] / d;
        }
        if d == zero {
            d = tiny;
        }
        if d < zero {
            count += 1;
        }
    }
    count
}

/// The `j`-th smallest eigenvalue (0-based), in [0, upper].
fn bisect(diag: &[Dd], off2: &[Dd], j: usize, upper: Dd) -> Dd {
    let (mut lo, mut hi) = (Dd::from_f64(0.0), upper);
    let half = Dd::from_f64(0.5);
    for _ in 0..400 {
        let mid = (lo + hi) * half;
        if count_below(diag, off2, mid) > j {
            hi = mid;
        } else {
            lo = mid;
        }
        if (hi - lo) <= hi * Dd::from_f64(1e-31) {
            break;
        }
    }
    (lo + hi) * half
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_masses_match_the_quadratic_formula() {
        // m = 1, 1; k = 1, 1: ω² = (3 ∓ √5)/2.
        let e = eigenvalues(&[1.0, 1.0], &[1.0, 1.0]);
        let mut w: Vec<f64> = e.iter().filter(|z| z.im > 0.0).map(|z| z.im).collect();
        w.sort_by(f64::total_cmp);
        let s5 = 5f64.sqrt();
        assert!((w[0] - ((3.0 - s5) / 2.0).sqrt()).abs() < 1e-15);
        assert!((w[1] - ((3.0 + s5) / 2.0).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn a_massless_body_puts_its_springs_in_series() {
        // Body 2 massless between springs 2 and 3 (k = 2, 2: 1 in series): a chain of two
        // unit masses with unit springs.
        let e = eigenvalues(&[1.0, 0.0, 1.0], &[1.0, 2.0, 2.0]);
        let want = eigenvalues(&[1.0, 1.0], &[1.0, 1.0]);
        assert_eq!(e.len(), 4);
        for (a, b) in e.iter().zip(&want) {
            assert!((a - b).norm() < 1e-15, "{e:?} {want:?}");
        }
    }
}
