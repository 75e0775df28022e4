//! The vortex-lattice solution: flow tangency, one LU for seven right-hand sides,
//! Kutta–Joukowski forces and their exact linearisation in the six body-axis states.

use crate::derivatives::{Derivatives, StabilityDerivatives};
use crate::error::{AeroError, Result};
use crate::geometry::{Configuration, Symmetry};
use crate::kernel::{Vec3, add, cross, dot, scale, segment, sub, trailing_leg};
use crate::lattice::{self, Lattice, Panel};
use faer::Mat;
use faer::linalg::solvers::Solve;
use serde::Serialize;
use std::collections::HashMap;

/// How to solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SolverOptions {
    /// Angle of attack of the trim state, degrees.
    pub alpha_deg: f64,
    /// Sideslip angle of the trim state, degrees (β > 0: wind from the right, v > 0).
    pub beta_deg: f64,
    /// Also apply Kutta–Joukowski forces to the parts of the trailing legs that lie on the
    /// surface (from the bound vortex to the trailing edge), with the free stream and
    /// rotation velocity only. Default `true`, as AVL 3.3x does: those chordwise segments
    /// are bound vorticity of the lattice and carry load like the spanwise ones; AVL 3.4x and
    /// later leave them out. It matters only for lifting surfaces in sideslip or roll/yaw,
    /// e.g. Clv of a lifting wing.
    pub trailing_leg_forces: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            alpha_deg: 0.0,
            beta_deg: 0.0,
            trailing_leg_forces: true,
        }
    }
}

/// Force and moment coefficients at the trim state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Totals {
    /// CX, CY, CZ, Cl, Cm, Cn in standard body axes (x forward, y right, z down), about the
    /// reference point, normalised like the derivatives.
    pub body: [f64; 6],
    /// Lift coefficient CL = −CZ cos α + CX sin α.
    pub lift: f64,
    /// Induced drag coefficient (near field), along the free stream:
    /// CD = −(CX cos α cos β + CY sin β + CZ sin α cos β).
    pub drag: f64,
}

/// Sizes of the lattice that was solved (mirrored copies included, as AVL counts them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct LatticeSize {
    /// Surfaces.
    pub surfaces: usize,
    /// Spanwise strips.
    pub strips: usize,
    /// Horseshoe vortices.
    pub vortices: usize,
}

/// The result of [`solve`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Solution {
    /// Body-axis derivatives at the trim state.
    pub derivatives: Derivatives,
    /// Trim coefficients.
    pub totals: Totals,
    /// Angle of attack, degrees.
    pub alpha_deg: f64,
    /// Sideslip, degrees.
    pub beta_deg: f64,
    /// Mach number of the Prandtl–Glauert correction.
    pub mach: f64,
    /// The lattice's size.
    pub lattice: LatticeSize,
}

impl Solution {
    /// The derivatives in stability axes (AVL's ST form) at this solution's α; requires
    /// zero sideslip, since ST files are defined there.
    pub fn stability_derivatives(&self) -> Result<StabilityDerivatives> {
        if self.beta_deg != 0.0 {
            return Err(AeroError::Option {
                option: "beta_deg",
                reason: "stability-axis derivatives are defined here at zero sideslip".into(),
            });
        }
        Ok(self
            .derivatives
            .to_stability_axes(self.alpha_deg, self.totals.body))
    }
}

/// Air velocity relative to the body at `r` (geometry axes, relative to the reference point)
/// per unit of each standard-axis state u, v, w, p, q, r: the free stream (u, −v, w) in
/// geometry axes, minus ω × r with ω = (−p, q, −r) in geometry axes.
fn unit_velocities(r: Vec3) -> [Vec3; 6] {
    [
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, -r[2], r[1]],
        [-r[2], 0.0, r[0]],
        [-r[1], r[0], 0.0],
    ]
}

/// Air velocity at `r` in the trim state, and per unit state; a `NOALBE` panel sees only the
/// axial free stream.
fn velocities(r: Vec3, trim: &[f64; 6], sees_flow_angles: bool) -> [Vec3; 7] {
    let e = unit_velocities(r);
    let mut out = [[0.0; 3]; 7];
    if sees_flow_angles {
        out[..6].copy_from_slice(&e);
        out[6] = (0..6).fold([0.0; 3], |acc, s| add(acc, scale(e[s], trim[s])));
    } else {
        out[0] = e[0];
        out[6] = [1.0, 0.0, 0.0];
    }
    out
}

fn check_options(o: &SolverOptions) -> Result<()> {
    for (option, v) in [("alpha_deg", o.alpha_deg), ("beta_deg", o.beta_deg)] {
        if !v.is_finite() || v.abs() >= 90.0 {
            return Err(AeroError::Option {
                option,
                reason: format!("must be a finite angle below 90 degrees, is {v}"),
            });
        }
    }
    Ok(())
}

/// Solves the vortex lattice of `config` at the trim state of `options` and returns the
/// body-axis derivatives and trim coefficients.
pub fn solve(config: &Configuration, options: &SolverOptions) -> Result<Solution> {
    config.validate()?;
    check_options(options)?;
    let lattice = lattice::build(config)?;
    let n = lattice.panels.len();
    let (alpha, beta) = (
        options.alpha_deg.to_radians(),
        options.beta_deg.to_radians(),
    );
    let trim = [
        alpha.cos() * beta.cos(),
        beta.sin(),
        alpha.sin() * beta.cos(),
        0.0,
        0.0,
        0.0,
    ];
    let field = Field::new(&lattice, config.mach, &config.symmetry);
    let reference = config.reference.point;
    // The influence matrix and its LU factors, and the 7 right-hand sides with their
    // solutions.
    eom_num::budget::check(
        "the vortex-lattice influence matrix",
        eom_num::budget::product(&[n, n + 7, 2 * 8]),
    )
    .map_err(|e| AeroError::OutOfRange {
        what: format!("the lattice of {n} panels"),
        reason: e.to_string(),
    })?;
    let mut influence = Mat::<f64>::zeros(n, n);
    let (mut legs, mut v) = (Vec::new(), Vec::new());
    for (i, p) in lattice.panels.iter().enumerate() {
        field.induced_all(p.control, &mut legs, &mut v);
        for (j, vj) in v.iter().enumerate() {
            influence[(i, j)] = dot(p.normal, *vj);
        }
    }
    let rhs = Mat::<f64>::from_fn(n, 7, |i, s| {
        let p = &lattice.panels[i];
        -dot(
            velocities(sub(p.control, reference), &trim, p.sees_flow_angles)[s],
            p.normal,
        )
    });
    check_reference_point(config, &rhs)?;
    let lu = influence.partial_piv_lu();
    check_pivots(lu.U(), n)?;
    let gamma = lu.solve(&rhs);
    let g: Vec<[f64; 7]> = (0..n)
        .map(|k| std::array::from_fn(|s| gamma[(k, s)]))
        .collect();
    if g.iter().flatten().any(|x| !x.is_finite()) {
        return Err(AeroError::Singular {
            panels: n,
            reason: "the circulations are not finite".into(),
        });
    }
    let loads = Loads::compute(&lattice, &field, &g, &trim, reference, options);
    Ok(finish(config, options, &lattice, &loads))
}

/// Rejects a moment reference point so far from the panels that the rotation velocities about
/// it (the right-hand sides of p, q, r) exceed `eom_num::MAX_ENTRY`: the circulations would
/// overflow, which is not a fault of the lattice.
fn check_reference_point(config: &Configuration, rhs: &Mat<f64>) -> Result<()> {
    let largest = (0..rhs.nrows())
        .flat_map(|i| (0..rhs.ncols()).map(move |s| (i, s)))
        .map(|(i, s)| rhs[(i, s)].abs())
        .fold(0.0, f64::max);
    if largest.is_finite() && largest <= eom_num::MAX_ENTRY {
        return Ok(());
    }
    Err(AeroError::Configuration {
        config: config.title.clone(),
        field: "Xref/Yref/Zref",
        reason: format!(
            "{:?} lies so far from the panels that the velocities of a unit rotation about it \
             reach {largest:e}: the circulations would overflow (give a point near the geometry)",
            config.reference.point
        ),
    })
}

/// Rejects a factorisation whose pivots span more than 1e13: the lattice has coincident
/// or overlapping vortices and the circulations would be meaningless.
fn check_pivots(u: faer::MatRef<'_, f64>, n: usize) -> Result<()> {
    let piv: Vec<f64> = (0..n).map(|i| u[(i, i)].abs()).collect();
    let max = piv.iter().cloned().fold(0.0, f64::max);
    let min = piv.iter().cloned().fold(f64::INFINITY, f64::min);
    if !(max.is_finite() && min > 1e-13 * max) {
        return Err(AeroError::Singular {
            panels: n,
            reason: format!("pivots range from {min:e} to {max:e} (coincident panels?)"),
        });
    }
    Ok(())
}

/// The induced-velocity field of the lattice, with the Prandtl–Glauert stretch x' = x/β
/// applied to the geometry and 1/β to the induced x velocity (Göthert's rule: the
/// perturbation potential of the stretched geometry is incompressible). Adjacent strips
/// share the end points of their bound segments, so each trailing leg is evaluated once per
/// field point and used by both horseshoes that start or end there.
///
/// A z image plane adds to every horseshoe its mirror image about z = zsym: with the
/// circulation reversed for a solid wall (iZsym = +1: the normal velocity cancels on the
/// plane, ground effect), kept for a constant-pressure plane (iZsym = −1).
struct Field {
    beta: f64,
    nodes: Vec<Vec3>,
    a: Vec<usize>,
    b: Vec<usize>,
    /// Image horseshoes (node indices) and the sign of their circulation, if any.
    image: Option<(Vec<usize>, Vec<usize>, f64)>,
}

impl Field {
    fn new(lattice: &Lattice, mach: f64, symmetry: &Symmetry) -> Self {
        let beta = (1.0 - mach * mach).sqrt();
        // + 0.0 turns −0.0 into 0.0, so that mirrored root points meet their originals
        let stretch = |v: Vec3| [v[0] / beta + 0.0, v[1] + 0.0, v[2] + 0.0];
        let mut index: HashMap<[u64; 3], usize> = HashMap::new();
        let mut nodes = Vec::new();
        let mut intern = |v: Vec3| {
            let v = stretch(v);
            *index.entry(v.map(f64::to_bits)).or_insert_with(|| {
                nodes.push(v);
                nodes.len() - 1
            })
        };
        let (a, b) = lattice
            .panels
            .iter()
            .map(|p| (intern(p.a), intern(p.b)))
            .unzip();
        let image = (symmetry.izsym != 0).then(|| {
            let z0 = symmetry.zsym;
            let reflect = |v: Vec3| [v[0], v[1], 2.0 * z0 - v[2]];
            let (ia, ib) = lattice
                .panels
                .iter()
                .map(|p| (intern(reflect(p.a)), intern(reflect(p.b))))
                .unzip();
            (ia, ib, -f64::from(symmetry.izsym.signum()))
        });
        Field {
            beta,
            nodes,
            a,
            b,
            image,
        }
    }

    /// Velocities at `p` (physical coordinates) induced by every horseshoe of unit
    /// circulation (with its image), into `out`; `legs` is scratch space.
    fn induced_all(&self, p: Vec3, legs: &mut Vec<Vec3>, out: &mut Vec<Vec3>) {
        let ps = [p[0] / self.beta, p[1], p[2]];
        legs.clear();
        legs.extend(self.nodes.iter().map(|&n| trailing_leg(ps, n)));
        let horseshoe = |ia: usize, ib: usize| {
            let s = segment(ps, self.nodes[ia], self.nodes[ib]);
            let (la, lb) = (legs[ia], legs[ib]);
            [
                s[0] + lb[0] - la[0],
                s[1] + lb[1] - la[1],
                s[2] + lb[2] - la[2],
            ]
        };
        out.clear();
        out.extend(
            self.a
                .iter()
                .zip(&self.b)
                .map(|(&ia, &ib)| horseshoe(ia, ib)),
        );
        if let Some((ia, ib, sign)) = &self.image {
            for (k, v) in out.iter_mut().enumerate() {
                *v = add(*v, scale(horseshoe(ia[k], ib[k]), *sign));
            }
        }
        for v in out.iter_mut() {
            v[0] /= self.beta;
        }
    }
}

/// Forces and moments (geometry axes, about the reference point, ρ = V = 1) at the trim
/// state and their derivatives per unit state.
struct Loads {
    /// [state 0..6 derivative, 6 = trim value] of force and moment.
    force: [Vec3; 7],
    moment: [Vec3; 7],
}

impl Loads {
    fn compute(
        lattice: &Lattice,
        field: &Field,
        g: &[[f64; 7]],
        trim: &[f64; 6],
        reference: Vec3,
        options: &SolverOptions,
    ) -> Self {
        let mut loads = Loads {
            force: [[0.0; 3]; 7],
            moment: [[0.0; 3]; 7],
        };
        let (mut legs, mut v) = (Vec::new(), Vec::new());
        for (k, p) in lattice.panels.iter().enumerate() {
            if !p.loaded {
                continue;
            }
            let arm = sub(p.force_point, reference);
            let mut w = velocities(arm, trim, p.sees_flow_angles);
            field.induced_all(p.force_point, &mut legs, &mut v);
            for (vj, gj) in v.iter().zip(g) {
                for s in 0..7 {
                    w[s] = add(w[s], scale(*vj, gj[s]));
                }
            }
            loads.add_segment(arm, sub(p.b, p.a), &g[k], &w);
            if options.trailing_leg_forces {
                loads.add_legs(p, &g[k], trim, reference);
            }
        }
        loads
    }

    /// Adds Γ (W × l) at `arm` and its linearisation ∂Γ (W₀ × l) + Γ₀ (∂W × l).
    fn add_segment(&mut self, arm: Vec3, l: Vec3, g: &[f64; 7], w: &[Vec3; 7]) {
        let base = cross(w[6], l);
        for s in 0..7 {
            let f = if s == 6 {
                scale(base, g[6])
            } else {
                add(scale(base, g[s]), scale(cross(w[s], l), g[6]))
            };
            self.force[s] = add(self.force[s], f);
            self.moment[s] = add(self.moment[s], cross(arm, f));
        }
    }

    /// The on-surface parts of the two trailing legs: from the trailing edge into `a`
    /// (against +x) and from `b` to the trailing edge (along +x), loaded at their midpoints.
    fn add_legs(&mut self, p: &Panel, g: &[f64; 7], trim: &[f64; 6], reference: Vec3) {
        let legs = [(p.a, p.a[0] - p.te_a), (p.b, p.te_b - p.b[0])];
        for (start, signed_len) in legs {
            let mid = [start[0] + 0.5 * signed_len.abs(), start[1], start[2]];
            let arm = sub(mid, reference);
            let w = velocities(arm, trim, p.sees_flow_angles);
            self.add_segment(arm, [signed_len, 0.0, 0.0], g, &w);
        }
    }
}

fn finish(
    config: &Configuration,
    options: &SolverOptions,
    lattice: &Lattice,
    loads: &Loads,
) -> Solution {
    let r = config.reference;
    let q_s = 0.5 * r.sref;
    let rows = r.row_lengths();
    let cols = r.column_lengths();
    // geometry → standard axes: x and z change sign, for forces and for moments alike
    let standard = |f: Vec3, m: Vec3| [-f[0], f[1], -f[2], -m[0], m[1], -m[2]];
    let mut coefficients = [[0.0; 6]; 6];
    for s in 0..6 {
        let fm = standard(loads.force[s], loads.moment[s]);
        for i in 0..6 {
            coefficients[i][s] = fm[i] / (q_s * rows[i] * cols[s]);
        }
    }
    let fm = standard(loads.force[6], loads.moment[6]);
    let body: [f64; 6] = std::array::from_fn(|i| fm[i] / (q_s * rows[i]));
    let (alpha, beta) = (
        options.alpha_deg.to_radians(),
        options.beta_deg.to_radians(),
    );
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let totals = Totals {
        body,
        lift: -body[2] * ca + body[0] * sa,
        drag: -(body[0] * ca * cb + body[1] * sb + body[2] * sa * cb),
    };
    Solution {
        derivatives: Derivatives {
            reference: r,
            coefficients,
        },
        totals,
        alpha_deg: options.alpha_deg,
        beta_deg: options.beta_deg,
        mach: config.mach,
        lattice: LatticeSize {
            surfaces: lattice.surfaces,
            strips: lattice.strips,
            vortices: lattice.panels.len(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::horseshoe;
    use crate::{Reference, Surface};

    #[test]
    fn shared_legs_give_the_plain_horseshoe_sum() {
        let c = Configuration::new("c", Reference::new(1.0, 1.0, 1.0, [0.0; 3]))
            .surface(Surface::wing("W", 2.0, 1.0, 0.5, 20.0, 5.0).lattice(3, 1.0, 4, 1.0));
        let lattice = lattice::build(&c).unwrap();
        let mach: f64 = 0.5;
        let beta = (1.0 - mach * mach).sqrt();
        let field = Field::new(&lattice, mach, &Symmetry::default());
        // the mirror shares the root nodes: fewer nodes than 2 per panel
        assert!(field.nodes.len() < lattice.panels.len() + 3 * 3);
        let p = [0.3, 0.7, 0.2];
        let (mut legs, mut v) = (Vec::new(), Vec::new());
        field.induced_all(p, &mut legs, &mut v);
        let s = |q: Vec3| [q[0] / beta, q[1], q[2]];
        for (j, panel) in lattice.panels.iter().enumerate() {
            let h = horseshoe(s(p), s(panel.a), s(panel.b));
            let h = [h[0] / beta, h[1], h[2]];
            for k in 0..3 {
                assert!((h[k] - v[j][k]).abs() < 1e-14, "{j} {k}");
            }
        }
    }
}
