//! [`Beam`]: an Euler–Bernoulli beam between two bodies, bending in two planes.

use super::Validation;
use super::{GROUND, ModelScalar, Name, Physics, Vec3, item, name, zero3};
use crate::assemble::RowLabel;
use crate::assemble::{Assembly, ItemRow, Reaction, Rows, Term};
use crate::error::{Degeneracy, ItemRef, ModelError};
use crate::geometry::{self, cross, scale, sub, unit};
use eom_sym::scalar::Scalar;

item! {
    /// An Euler–Bernoulli beam between two bodies (bending in two planes, no torsion or axial
    /// stiffness).
    pub struct Beam<S>: "beam", "beam"
        (bodies: bodies, supports: true)
    {
        /// `[body 1, body 2]`.
        pub bodies: [Name; 2] = [name(GROUND), name(GROUND)] => bodies(between, "between"),
        /// End points.
        pub ends: [Vec3<S>; 2] = [zero3(), zero3()] => ends(ends, "ends"),
        /// Bending stiffness `[EI₁, EI₂]` towards the two bending directions.
        pub stiffness: [S; 2] = [S::zero(), S::zero()] => pair(stiffness, "stiffness"),
        /// Mass per unit length.
        pub mpul: S = S::zero() => scalar(mpul, "mpul"),
        /// A vector that with the axis defines bending plane 1 (not parallel to the axis).
        pub perp: Vec3<S> = zero3() => vector(perp, "perp", Polar),
    }
    /// A beam with zero properties.
    pub fn new;
}

impl<S: ModelScalar> Physics<S> for Beam<S> {
    /// A nonzero length, and a bending-plane vector not parallel to the axis.
    fn validate(&self, _cx: &mut Validation<'_, S>) -> Result<(), ModelError> {
        let t = geometry::sub(&self.ends[1], &self.ends[0]);
        let tn: Vec<f64> = t.iter().map(|x| x.nominal()).collect();
        if tn.iter().all(|&x| x == 0.0) {
            return Err(ModelError::Degenerate {
                item: ItemRef::new("beam", &self.name),
                field: "ends".into(),
                shape: Degeneracy::CoincidentEnds { direction: false },
            });
        }
        let p: Vec<f64> = self.perp.iter().map(|x| x.nominal()).collect();
        let c = [
            tn[1] * p[2] - tn[2] * p[1],
            tn[2] * p[0] - tn[0] * p[2],
            tn[0] * p[1] - tn[1] * p[0],
        ];
        if c.iter().map(|x| x * x).sum::<f64>()
            <= 1e-24
                * tn.iter().map(|x| x * x).sum::<f64>()
                * p.iter().map(|x| x * x).sum::<f64>().max(1e-300)
        {
            return Err(ModelError::Degenerate {
                item: ItemRef::new("beam", &self.name),
                field: "perp".into(),
                shape: Degeneracy::ParallelPerp,
            });
        }
        Ok(())
    }

    /// Eight elastic rows (two bending directions, displacement and rotation, at each end)
    /// with the bending stiffness and consistent mass blocks; the multipliers are the end
    /// loads, reported as zero preloads without geometric stiffness.
    fn assemble<'m>(&'m self, cx: &mut Assembly<'m, S>) -> Result<(), ModelError> {
        let (rows, kb, mb) = beam_rows(cx, self);
        cx.add_rows_block(Term::Stiffness, &rows.rows, &kb);
        cx.add_rows_block(Term::ItemMass, &rows.rows, &mb);
        cx.elastic("beam", &self.name, rows, kb, Reaction::Unreported);
        Ok(())
    }
}

/// The 8 rows of a beam and its stiffness and mass blocks.
type BeamParts<S> = (Rows<S>, Vec<Vec<S>>, Vec<Vec<S>>);
fn beam_rows<S: Scalar>(cx: &Assembly<'_, S>, bm: &Beam<S>) -> BeamParts<S> {
    let b = [cx.body(&bm.bodies[0]), cx.body(&bm.bodies[1])];
    let t = sub(&bm.ends[1], &bm.ends[0]);
    let l = geometry::norm(&t);
    let u = scale(l.recip(), &t);
    let e2 = unit(&cross(&u, &bm.perp));
    let e1 = scale(-S::one(), &cross(&u, &e2));
    let r = [
        sub(&bm.ends[0], &cx.mass_centre(b[0])),
        sub(&bm.ends[1], &cx.mass_centre(b[1])),
    ];
    let z = zero3::<S>();
    let mut rows = Vec::new();
    for (body, rad) in b.iter().zip(&r) {
        for e in [&e1, &e2] {
            let mut row = ItemRow::new();
            row.push_body(*body, e, &cross(rad, e), true);
            rows.push(row.sorted());
        }
        for e in [&e1, &e2] {
            let mut row = ItemRow::new();
            row.push_body(*body, &z, e, true);
            rows.push(row.sorted());
        }
    }
    let labels = (1..=8)
        .map(|k| RowLabel {
            kind: "beam",
            item: bm.name.clone(),
            part: "end row",
            index: k,
        })
        .collect();
    // The bending stiffness K = Dᵀ diag(kd) D / L and the consistent mass M = Eᵀ diag(md) E ·
    // μL/432 of the Euler–Bernoulli beam in two planes, on the end rows
    // [e1·δx1, e2·δx1, e1·θ1, e2·θ1, e1·δx2, e2·δx2, e1·θ2, e2·θ2].
    let s = |x: i64| S::from_i64(x);
    let two_l = s(2) / l;
    let o = S::zero();
    let dmat: [[S; 8]; 4] = [
        [o, o, o, -s(1), o, o, o, s(1)],
        [two_l, o, o, s(1), -two_l, o, o, s(1)],
        [o, o, -s(1), o, o, o, s(1), o],
        [o, two_l, -s(1), o, o, -two_l, -s(1), o],
    ];
    let [ei1, ei2] = bm.stiffness;
    let kd = [ei1, s(3) * ei1, ei2, s(3) * ei2];
    let il = l.recip();
    let emat: [[S; 8]; 4] = [
        [s(6), o, o, l, s(6), o, o, -l],
        [s(8), o, o, l, -s(8), o, o, l],
        [o, s(6), -l, o, o, s(6), l, o],
        [o, s(8), -l, o, o, -s(8), -l, o],
    ];
    let md = [s(3), s(1), s(3), s(1)];
    let mscale = bm.mpul * l / s(432);
    let quad = |m: &[[S; 8]; 4], dg: &[S; 4], c: S| -> Vec<Vec<S>> {
        (0..8)
            .map(|i| {
                (0..8)
                    .map(|j| {
                        let terms: Vec<S> = (0..4)
                            .filter(|&k| {
                                !m[k][i].is_zero() && !m[k][j].is_zero() && !dg[k].is_zero()
                            })
                            .map(|k| m[k][i] * dg[k] * m[k][j])
                            .collect();
                        let v = S::sum(&terms);
                        if v.is_zero() || c.is_zero() {
                            S::zero()
                        } else {
                            c * v
                        }
                    })
                    .collect()
            })
            .collect()
    };
    (
        Rows { rows, labels },
        quad(&dmat, &kd, il),
        quad(&emat, &md, mscale),
    )
}
