//! Biot–Savart kernels of unit-strength vortex lines (Katz & Plotkin, *Low-Speed
//! Aerodynamics*, 2nd ed., §2.13 and §10.4.5), and small 3-vector helpers.

use std::f64::consts::PI;

/// A 3-vector.
pub(crate) type Vec3 = [f64; 3];

pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn scale(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(crate) fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}

/// Points closer to a vortex line than this fraction of the line's length (or of the
/// distance along a semi-infinite leg) are on the line: the self-induced velocity of a
/// straight filament is zero, and this is also how a force point on its own bound segment
/// is excluded.
const ON_LINE: f64 = 1e-10;

/// Velocity at `p` induced by the straight segment a → b of unit circulation:
/// (r₁×r₂)/(4π|r₁×r₂|²) · r₀·(r₁/|r₁| − r₂/|r₂|), r₁ = p − a, r₂ = p − b, r₀ = b − a.
pub(crate) fn segment(p: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    let r1 = sub(p, a);
    let r2 = sub(p, b);
    let r0 = sub(b, a);
    let c = cross(r1, r2);
    let c2 = dot(c, c);
    let l2 = dot(r0, r0);
    if c2 <= ON_LINE * ON_LINE * l2 * l2 {
        return [0.0; 3];
    }
    let (n1, n2) = (norm(r1), norm(r2));
    let k = (dot(r0, r1) / n1 - dot(r0, r2) / n2) / (4.0 * PI * c2);
    scale(c, k)
}

/// Velocity at `p` induced by the semi-infinite line of unit circulation that starts at `a`
/// and runs to x = +∞ along +x: (x̂×r)/(4π|r|(|r| − x̂·r)), r = p − a.
pub(crate) fn trailing_leg(p: Vec3, a: Vec3) -> Vec3 {
    let r = sub(p, a);
    let h2 = r[1] * r[1] + r[2] * r[2];
    let len = norm(r);
    if h2 <= ON_LINE * ON_LINE * len * len {
        return [0.0; 3];
    }
    // |r| − r_x written without cancellation downstream of the start point
    let gap = if r[0] > 0.0 {
        h2 / (len + r[0])
    } else {
        len - r[0]
    };
    let k = 1.0 / (4.0 * PI * len * gap);
    [0.0, -r[2] * k, r[1] * k]
}

/// [`segment`] with a finite core of radius `rc` (the n = 2 Vatistas core of
/// [`crate::vortex_core`]): |r₁|, |r₂| become (|r·|⁴ + rc⁴)^¼ and |r₁×r₂|² becomes
/// √(|r₁×r₂|⁴ + |r₀|⁴ rc⁴). Points on the line's axis get zero, as by symmetry.
pub(crate) fn segment_cored(p: Vec3, a: Vec3, b: Vec3, rc: f64) -> Vec3 {
    let r1 = sub(p, a);
    let r2 = sub(p, b);
    let r0 = sub(b, a);
    let c = cross(r1, r2);
    let c2 = dot(c, c);
    let (s1, s2) = (dot(r1, r1), dot(r2, r2));
    if c2 == 0.0 || s1 == 0.0 || s2 == 0.0 {
        return [0.0; 3];
    }
    let rc4 = rc.powi(4);
    let l2 = dot(r0, r0);
    let (n1, n2) = ((s1 * s1 + rc4).sqrt().sqrt(), (s2 * s2 + rc4).sqrt().sqrt());
    let k = (dot(r0, r1) / n1 - dot(r0, r2) / n2) / (4.0 * PI * (c2 * c2 + l2 * l2 * rc4).sqrt());
    scale(c, k)
}

/// [`trailing_leg`] with a finite core of radius `rc`: the distance² h² from the leg
/// becomes √(h⁴ + rc⁴) in (x̂×r)(1 + r_x/|r|)/(4π h²).
pub(crate) fn trailing_leg_cored(p: Vec3, a: Vec3, rc: f64) -> Vec3 {
    let r = sub(p, a);
    let h2 = r[1] * r[1] + r[2] * r[2];
    let len = norm(r);
    if h2 == 0.0 {
        return [0.0; 3];
    }
    // 1 + r_x/|r| written without cancellation upstream of the start point
    let f = if r[0] >= 0.0 {
        1.0 + r[0] / len
    } else {
        h2 / (len * (len - r[0]))
    };
    let k = f / (4.0 * PI * (h2 * h2 + rc.powi(4)).sqrt());
    [0.0, -r[2] * k, r[1] * k]
}

/// Velocity at `p` induced by the horseshoe vortex of unit circulation: from x = +∞ along
/// the leg into `a`, the bound segment a → b, and out along the leg from `b` to x = +∞.
/// (The solver assembles the same sum with legs shared between neighbours.)
#[cfg(test)]
pub(crate) fn horseshoe(p: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    let s = segment(p, a, b);
    let la = trailing_leg(p, a);
    let lb = trailing_leg(p, b);
    [
        s[0] + lb[0] - la[0],
        s[1] + lb[1] - la[1],
        s[2] + lb[2] - la[2],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_segment_approaches_infinite_line() {
        // infinite line along +y through the origin, point at x = 1: |v| = 1/(2π·1), along −z
        let v = segment([1.0, 0.0, 0.0], [0.0, -1e6, 0.0], [0.0, 1e6, 0.0]);
        assert!((v[2] + 1.0 / (2.0 * PI)).abs() < 1e-9, "{v:?}");
        assert!(v[0].abs() < 1e-15 && v[1].abs() < 1e-15);
    }

    #[test]
    fn leg_abeam_its_start_is_half_an_infinite_line() {
        let v = trailing_leg([0.0, 0.0, 2.0], [0.0, 0.0, 0.0]);
        assert!((v[1] + 1.0 / (4.0 * PI * 2.0)).abs() < 1e-15, "{v:?}");
        // the leg equals a long segment in the same direction
        let s = segment([0.3, 0.2, 0.5], [0.0; 3], [1e7, 0.0, 0.0]);
        let l = trailing_leg([0.3, 0.2, 0.5], [0.0; 3]);
        for i in 0..3 {
            assert!((s[i] - l[i]).abs() < 1e-9);
        }
    }

    #[test]
    fn zero_core_gives_the_singular_kernels() {
        let (p, a, b) = ([0.3, -0.2, 0.45], [0.0, 0.1, 0.0], [0.1, 1.0, 0.2]);
        let (s, sc) = (segment(p, a, b), segment_cored(p, a, b, 0.0));
        let (l, lc) = (trailing_leg(p, a), trailing_leg_cored(p, a, 0.0));
        // upstream of the leg's start too
        let q = [-2.0, 0.3, 0.1];
        let (u, uc) = (trailing_leg(q, a), trailing_leg_cored(q, a, 0.0));
        for i in 0..3 {
            assert!((s[i] - sc[i]).abs() < 1e-15 * (1.0 + s[i].abs()));
            assert!((l[i] - lc[i]).abs() < 1e-15 * (1.0 + l[i].abs()));
            assert!((u[i] - uc[i]).abs() < 1e-15 * (1.0 + u[i].abs()));
        }
    }

    #[test]
    fn cored_infinite_line_follows_the_n2_profile() {
        // Γ/(2π) · r/√(r⁴ + rc⁴) abeam a long segment and twice a leg's value abeam its start
        let rc: f64 = 0.2;
        for r in [0.01f64, 0.1, 0.2, 0.5, 3.0] {
            let exact = r / (2.0 * PI * (r.powi(4) + rc.powi(4)).sqrt());
            let v = segment_cored([0.0, 0.0, r], [-1e5, 0.0, 0.0], [1e5, 0.0, 0.0], rc);
            assert!((v[1].abs() / exact - 1.0).abs() < 1e-9, "{r}: {v:?}");
            let l = trailing_leg_cored([0.0, 0.0, r], [0.0; 3], rc);
            assert!((2.0 * l[1].abs() / exact - 1.0).abs() < 1e-12, "{r}: {l:?}");
        }
        // far from the core the core does not matter
        let (p, a, b) = ([3.0, 2.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]);
        let (s, sc) = (segment(p, a, b), segment_cored(p, a, b, 0.01));
        assert!((sc[0] / s[0] - 1.0).abs() < 1e-9);
        // and on the axis the velocity is zero, not NaN
        assert_eq!(trailing_leg_cored([4.0, 0.0, 0.0], [0.0; 3], 0.1), [0.0; 3]);
    }

    #[test]
    fn points_on_the_line_get_zero() {
        assert_eq!(
            segment([0.5, 0.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]),
            [0.0; 3]
        );
        assert_eq!(
            segment([2.0, 0.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]),
            [0.0; 3]
        );
        assert_eq!(trailing_leg([3.0, 0.0, 0.0], [0.0; 3]), [0.0; 3]);
        assert_eq!(trailing_leg([0.0; 3], [0.0; 3]), [0.0; 3]);
    }
}
