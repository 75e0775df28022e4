//! The tangent stiffness `K_T` of the static preloads and the preloads the items report:
//! each holonomic and elastic item's multipliers (the links' and springs' tensions, the
//! points' forces and moments) rotate with the bodies and so add geometric stiffness.

use super::Preload;
use super::context::{LineGeometry, PointGeometry, Reacting, Reaction, add_block};
use crate::error::label;
use crate::geometry::{self, Point, Vec3, mat_mul, mat_scale, outer, scale, skew, unit, zero3};
use eom_sym::matrix::Triplets;
use eom_sym::scalar::Scalar;

/// The geometric stiffness and the preload of every reacting item, `lambda` holding the
/// multipliers of their rows in order.
pub(crate) fn add_reactions<S: Scalar>(
    k: &mut Triplets<S>,
    reactions: &[Reacting<'_, S>],
    lambda: &[S],
    preloads: &mut Vec<Preload<S>>,
) {
    let mut start = 0;
    for r in reactions {
        let lam = &lambda[start..start + r.rows];
        start += r.rows;
        let item = label(r.kind, &r.name);
        let preload = match &r.reaction {
            Reaction::Line(g) => {
                let t = lam[0];
                line_tangent(k, t, g);
                line_preload(item, t, &g.unit, g.twist)
            }
            Reaction::Point(p, g) => {
                let (f, m) = point_force(lam, &g.forces, &g.moments);
                point_tangent(k, p, &f, &m, g);
                Preload {
                    item,
                    force: f,
                    moment: m,
                    tension: None,
                    unique: true,
                    computed: true,
                }
            }
            // A beam carries end loads but adds no geometric stiffness (the simplest
            // consistent choice for a beam without axial stiffness).
            Reaction::Unreported => Preload {
                item,
                force: zero3(),
                moment: zero3(),
                tension: None,
                unique: true,
                computed: false,
            },
        };
        preloads.push(preload);
    }
}

/// Global force and moment on body 1 from the multipliers of a point item.
fn point_force<S: Scalar>(lam: &[S], fd: &[Vec3<S>], md: &[Vec3<S>]) -> (Vec3<S>, Vec3<S>) {
    let comb = |dirs: &[Vec3<S>], l: &[S]| -> Vec3<S> {
        let mut v = zero3::<S>();
        for i in 0..3 {
            let terms: Vec<S> = dirs
                .iter()
                .zip(l)
                .filter(|(d, x)| !d[i].is_zero() && !x.is_zero())
                .map(|(d, x)| d[i] * *x)
                .collect();
            v[i] = S::sum(&terms);
        }
        v
    };
    (comb(fd, &lam[..fd.len()]), comb(md, &lam[fd.len()..]))
}

fn line_preload<S: Scalar>(item: String, t: S, u: &Vec3<S>, twist: bool) -> Preload<S> {
    // λ > 0 is tension: the force on body 1 points from end 1 towards end 2.
    if twist {
        Preload {
            item,
            force: zero3(),
            moment: scale(t, u),
            tension: Some(t),
            unique: true,
            computed: true,
        }
    } else {
        Preload {
            item,
            force: scale(t, u),
            moment: zero3(),
            tension: Some(t),
            unique: true,
            computed: true,
        }
    }
}

/// Geometric stiffness of a line item with tension `t`: the rotation of the line's direction
/// with the relative motion of its ends turns the tension into a transverse force.
fn line_tangent<S: Scalar>(k: &mut Triplets<S>, t: S, g: &LineGeometry<S>) {
    let (u, len, b, r) = (&g.unit, g.length, g.bodies, &g.radii);
    if t.is_zero() {
        return;
    }
    if g.twist {
        // A preload torque about the line, carried by the mean frame of the two bodies.
        let g = mat_scale(
            S::from_rational(&eom_sym::Rational::new(1, 2).expect("1/2")),
            &skew(&scale(t, u)),
        );
        add_block(k, (b[0], 3), (b[0], 3), &g, -1.0);
        add_block(k, (b[0], 3), (b[1], 3), &g, 1.0);
        add_block(k, (b[1], 3), (b[1], 3), &g, 1.0);
        add_block(k, (b[1], 3), (b[0], 3), &g, -1.0);
        return;
    }
    let ux = skew(u);
    // t1 = [−[u]×, [u]×[r1]×], t2 = [[u]×, −[u]×[r2]×] as 3×6 blocks (trans | rot).
    let t1 = (mat_scale(-S::one(), &ux), mat_mul(&ux, &skew(&r[0])));
    let t2 = (ux, mat_scale(-S::one(), &mat_mul(&ux, &skew(&r[1]))));
    let tl = t / len;
    let blocks = [(b[0], &t1), (b[1], &t2)];
    for &(bi, ti) in &blocks {
        for &(bj, tj) in &blocks {
            // (T/L) tiᵀ tj, four 3×3 sub-blocks.
            for (ri, ai) in [(0, &ti.0), (3, &ti.1)] {
                for (rj, aj) in [(0, &tj.0), (3, &tj.1)] {
                    let m = mat_scale(tl, &mat_mul(&geometry::transpose(ai), aj));
                    add_block(k, (bi, ri), (bj, rj), &m, 1.0);
                }
            }
        }
    }
    // −T tᵢᵀ into the rotation columns of body i (rotation of the force into body axes).
    for &(bi, ti) in &blocks {
        add_block(
            k,
            (bi, 0),
            (bi, 3),
            &mat_scale(t, &geometry::transpose(&ti.0)),
            -1.0,
        );
        add_block(
            k,
            (bi, 3),
            (bi, 3),
            &mat_scale(t, &geometry::transpose(&ti.1)),
            -1.0,
        );
    }
}

/// Geometric stiffness of a point item carrying force `f` and moment `mm` on body 1.
fn point_tangent<S: Scalar>(
    k: &mut Triplets<S>,
    p: &Point<S>,
    f: &Vec3<S>,
    mm: &Vec3<S>,
    g: &PointGeometry<S>,
) {
    let (b, r) = (g.bodies, &g.radii);
    let rolling = !geometry::is_zero(&p.rolling_axis);
    let p1 = b[0];
    let p2 = b[1];
    let p3 = if p.moments < 2 && matches!(p.forces, 1 | 2) && !rolling {
        p2
    } else {
        None
    };
    if !geometry::is_zero(f) {
        let f0 = skew(f);
        let f1 = mat_mul(&skew(&r[0]), &f0);
        let f2 = mat_mul(&skew(&r[1]), &f0);
        add_block(k, (p1, 0), (p1, 3), &f0, -1.0);
        add_block(k, (p1, 0), (p3, 3), &f0, 1.0);
        add_block(k, (p2, 0), (p2, 3), &f0, 1.0);
        add_block(k, (p2, 0), (p3, 3), &f0, -1.0);
        add_block(k, (p1, 3), (p1, 3), &f1, -1.0);
        add_block(k, (p1, 3), (p3, 3), &f1, 1.0);
        add_block(k, (p2, 3), (p2, 3), &f2, 1.0);
        add_block(k, (p2, 3), (p3, 3), &f2, -1.0);
        // The contact point is fixed in body 1: body 2's moment arm changes with relative motion.
        add_block(k, (p2, 3), (p1, 0), &f0, -1.0);
        add_block(k, (p2, 3), (p2, 0), &f0, 1.0);
        add_block(k, (p2, 3), (p1, 3), &geometry::transpose(&f1), 1.0);
        add_block(k, (p2, 3), (p2, 3), &geometry::transpose(&f2), -1.0);
        if rolling {
            let ra = unit(&p.rolling_axis);
            let g = mat_scale(
                -S::one(),
                &mat_mul(&geometry::transpose(&f1), &outer(&ra, &ra)),
            );
            add_block(k, (p1, 3), (p1, 3), &g, -1.0);
            add_block(k, (p1, 3), (p2, 3), &g, 1.0);
            add_block(k, (p2, 3), (p2, 3), &g, -1.0);
            add_block(k, (p2, 3), (p1, 3), &g, 1.0);
            return;
        }
    } else if rolling {
        return;
    }
    if geometry::is_zero(mm) {
        return;
    }
    if p.moments == 2 {
        let a = unit(&p.axis);
        let g = mat_mul(&skew(mm), &outer(&a, &a));
        add_block(k, (p1, 3), (p1, 3), &g, -1.0);
        add_block(k, (p2, 3), (p2, 3), &g, 1.0);
    } else if p.moments == 1 {
        let g = mat_scale(
            S::from_rational(&eom_sym::Rational::new(1, 2).expect("1/2")),
            &skew(mm),
        );
        add_block(k, (p1, 3), (p1, 3), &g, -1.0);
        add_block(k, (p1, 3), (p2, 3), &g, 1.0);
        add_block(k, (p2, 3), (p2, 3), &g, 1.0);
        add_block(k, (p2, 3), (p1, 3), &g, -1.0);
    }
}
