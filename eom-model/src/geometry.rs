//! The geometry every layer above shares: names of bodies and items, 3-vectors and the
//! global axes, the point and line shapes of the items ([`Point`], [`Line`]), and small
//! generic 3-D algebra over any [`Scalar`]: cross products, skew matrices, unit vectors, and
//! the deterministic direction basis of point and line items.

mod line;
mod point;

pub use line::Line;
pub(crate) use line::line_builders;
pub use point::Point;
pub(crate) use point::point_builders;

use eom_sym::scalar::Scalar;
use std::sync::Arc;

/// The name of the ground (the fixed frame). Reserved: no body may be called this.
pub const GROUND: &str = "ground";

/// A shared item or body name.
pub type Name = Arc<str>;

/// A shared name from text.
pub(crate) fn name(s: &str) -> Name {
    Arc::from(s)
}

/// A 3-vector.
pub type Vec3<S> = [S; 3];

/// A 3-vector from three components of any convertible type.
pub fn vec3<S>(x: impl Into<S>, y: impl Into<S>, z: impl Into<S>) -> Vec3<S> {
    [x.into(), y.into(), z.into()]
}

/// The zero vector.
pub fn zero3<S: Scalar>() -> Vec3<S> {
    [S::zero(), S::zero(), S::zero()]
}

/// The global x axis.
pub fn x_axis<S: Scalar>() -> Vec3<S> {
    [S::one(), S::zero(), S::zero()]
}
/// The global y axis.
pub fn y_axis<S: Scalar>() -> Vec3<S> {
    [S::zero(), S::one(), S::zero()]
}
/// The global z axis.
pub fn z_axis<S: Scalar>() -> Vec3<S> {
    [S::zero(), S::zero(), S::one()]
}

/// Vector `v` converted with `f`.
pub(crate) fn map3<S, T>(v: &Vec3<S>, f: &mut dyn FnMut(&S) -> T) -> Vec3<T> {
    [f(&v[0]), f(&v[1]), f(&v[2])]
}

/// A 3×3 matrix, row-major.
pub type Mat3<S> = [[S; 3]; 3];

/// `a · b`.
pub fn dot<S: Scalar>(a: &Vec3<S>, b: &Vec3<S>) -> S {
    S::dot(a, b)
}

/// `a × b`.
pub fn cross<S: Scalar>(a: &Vec3<S>, b: &Vec3<S>) -> Vec3<S> {
    let m = |x: S, y: S| {
        if x.is_zero() || y.is_zero() {
            S::zero()
        } else {
            x * y
        }
    };
    let d = |p: S, q: S| {
        if q.is_zero() {
            p
        } else if p.is_zero() {
            -q
        } else {
            p - q
        }
    };
    [
        d(m(a[1], b[2]), m(a[2], b[1])),
        d(m(a[2], b[0]), m(a[0], b[2])),
        d(m(a[0], b[1]), m(a[1], b[0])),
    ]
}

/// `a − b`.
pub fn sub<S: Scalar>(a: &Vec3<S>, b: &Vec3<S>) -> Vec3<S> {
    let d = |p: S, q: S| {
        if q.is_zero() {
            p
        } else if p.is_zero() {
            -q
        } else {
            p - q
        }
    };
    [d(a[0], b[0]), d(a[1], b[1]), d(a[2], b[2])]
}

/// `c · a`.
pub fn scale<S: Scalar>(c: S, a: &Vec3<S>) -> Vec3<S> {
    let m = |x: S| if x.is_zero() { S::zero() } else { c * x };
    [m(a[0]), m(a[1]), m(a[2])]
}

/// Is the vector structurally zero?
pub fn is_zero<S: Scalar>(a: &Vec3<S>) -> bool {
    a.iter().all(Scalar::is_zero)
}

/// Euclidean norm (structural zeros skipped, so an axis-aligned vector has norm `|a_k|`).
pub fn norm<S: Scalar>(a: &Vec3<S>) -> S {
    let mut nz = a.iter().filter(|x| !x.is_zero());
    match (nz.next(), nz.next()) {
        (None, _) => S::zero(),
        (Some(x), None) => x.abs(),
        _ => dot(a, a).sqrt(),
    }
}

/// `a / |a|` (the caller has checked that `a` is not zero).
pub fn unit<S: Scalar>(a: &Vec3<S>) -> Vec3<S> {
    let n = norm(a);
    if n.is_one() {
        return *a;
    }
    let inv = n.recip();
    scale(inv, a)
}

/// The skew matrix `[a]×` with `[a]× b = a × b`.
pub fn skew<S: Scalar>(a: &Vec3<S>) -> Mat3<S> {
    let z = S::zero();
    let n = |x: S| if x.is_zero() { x } else { -x };
    [[z, n(a[2]), a[1]], [a[2], z, n(a[0])], [n(a[1]), a[0], z]]
}

/// `A · B` for 3×3 matrices.
pub fn mat_mul<S: Scalar>(a: &Mat3<S>, b: &Mat3<S>) -> Mat3<S> {
    let mut c = [[S::zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = S::dot(&a[i], &[b[0][j], b[1][j], b[2][j]]);
        }
    }
    c
}

/// `A + B` (structural zeros kept).
pub fn mat_add<S: Scalar>(a: &Mat3<S>, b: &Mat3<S>) -> Mat3<S> {
    let mut c = *a;
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = match (a[i][j].is_zero(), b[i][j].is_zero()) {
                (_, true) => a[i][j],
                (true, false) => b[i][j],
                _ => a[i][j] + b[i][j],
            };
        }
    }
    c
}

/// `c · A` (structural zeros kept).
pub fn mat_scale<S: Scalar>(c: S, a: &Mat3<S>) -> Mat3<S> {
    let mut m = *a;
    for row in m.iter_mut() {
        for v in row.iter_mut() {
            if !v.is_zero() {
                *v = c * *v;
            }
        }
    }
    m
}

/// `A · v`.
pub fn mat_vec<S: Scalar>(a: &Mat3<S>, v: &Vec3<S>) -> Vec3<S> {
    [S::dot(&a[0], v), S::dot(&a[1], v), S::dot(&a[2], v)]
}

/// `Aᵀ`.
pub fn transpose<S: Scalar>(a: &Mat3<S>) -> Mat3<S> {
    let mut t = *a;
    for (i, row) in a.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            t[j][i] = v;
        }
    }
    t
}

/// `a bᵀ`.
pub fn outer<S: Scalar>(a: &Vec3<S>, b: &Vec3<S>) -> Mat3<S> {
    let m = |x: S, y: S| {
        if x.is_zero() || y.is_zero() {
            S::zero()
        } else {
            x * y
        }
    };
    let mut c = [[S::zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = m(a[i], b[j]);
        }
    }
    c
}

/// An orthonormal pair `(ν₁, ν₂)` perpendicular to the unit vector `a`, with `(a, ν₁, ν₂)`
/// right-handed. Deterministic (an SVD null space would depend on rounding and on the LAPACK
/// implementation, and so would the labels of the item's rows): `ν₁` is the
/// normalised `a × e_k` for the global axis `e_k` least aligned with `a` at the nominal point
/// (the first one on ties), `ν₂ = a × ν₁`. For an axis-aligned `a` the pair is axis-aligned:
/// `a = z` gives `ν = (y, −x)`.
pub fn perpendicular_basis<S: Scalar>(a: &Vec3<S>) -> [Vec3<S>; 2] {
    let mut k = 0;
    for i in 1..3 {
        if a[i].nominal().abs() < a[k].nominal().abs() {
            k = i;
        }
    }
    let mut e = [S::zero(); 3];
    e[k] = S::one();
    let n1 = unit(&cross(a, &e));
    let n2 = cross(a, &n1);
    [n1, n2]
}
