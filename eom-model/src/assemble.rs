//! Generic assembly of the linearized equations (eom-method §2–§4), written once for every
//! [`Scalar`].
//!
//! Coordinates: per body six, `p = [δx, δy, δz, θx, θy, θz]` (small global displacement of the
//! mass centre and small global rotation), and the perturbation velocities `w` in body axes.
//! The result is the set of sparse matrices of the first-order descriptor model
//! (eom-method §5) before any constraint elimination; [`reduce`](super::reduce) takes it from
//! there.
//!
//! Deliberate differences from the reference EoM.jl (eom-method §13), each documented where it
//! happens:
//! * direction bases of 2-direction items are deterministic, not LAPACK's (§13.15);
//! * the equilibrium check is relative per equation, not an absolute sum of squares (§13.10);
//! * a statically indeterminate structure uses the elastic compatibility equations and reports
//!   the indeterminacy; a singular compatibility system is an error, not a minimum-norm guess;
//! * a body spinning about an axis that is not an axis of symmetry is an error (the
//!   constant-coefficient linearization in the non-spinning frame does not exist), instead of a
//!   silently incomplete gyroscopic term (§13.12);
//! * a twist spring or link carrying a preload torque gets the geometric stiffness of a torque
//!   carried by the mean frame of its two bodies (like a constant-velocity joint), not the
//!   line-tension terms with the torque used as a tension (§13.10);
//! * a rolling contact is recognised by a nonzero rolling axis, without exact floating-point
//!   tests on its norm (§13.14).

use super::Model;
use super::eliminate::{Row, RowStore, rref};
use super::geometry::{self, Mat3, cross, mat_mul, outer, scale, skew, sub, unit};
use super::items::*;
use crate::error::ModelError;
use eom_sym::matrix::{SparseMatrix, Triplets};
use eom_sym::scalar::Scalar;

/// Which row of an item a constraint or elastic row is (formatted only when displayed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RowLabel {
    /// Item kind, e.g. "rigid point".
    pub kind: &'static str,
    /// Item name.
    pub item: Name,
    /// "force", "moment", "end row" or "" for a line item's single row.
    pub part: &'static str,
    /// 1-based index within the part (0 for a single row).
    pub index: usize,
}

impl std::fmt::Display for RowLabel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} `{}`", self.kind, self.item)?;
        if !self.part.is_empty() {
            write!(f, " {} {}", self.part, self.index)?;
        }
        Ok(())
    }
}

/// Static force carried by an item at the nominal configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Preload<S> {
    /// The item, e.g. ``rigid point `road` ``.
    pub item: String,
    /// Force exerted on body 1 by the item (global axes).
    pub force: Vec3<S>,
    /// Moment exerted on body 1 by the item.
    pub moment: Vec3<S>,
    /// For line items: the tension (twist items: the torque).
    pub tension: Option<S>,
}

/// How the static preloads were obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Statics {
    /// No loads and no known preloads: all preloads are zero.
    Unloaded,
    /// Statically determinate: preloads from force balance alone.
    Determinate,
    /// Statically indeterminate: preloads from force balance and elastic compatibility.
    Indeterminate,
}

/// The assembled (unreduced) linearized model.
#[derive(Clone, Debug)]
pub struct Assembled<S> {
    /// Model name.
    pub name: String,
    /// Body names, six coordinates each.
    pub bodies: Vec<String>,
    /// Mass-centre locations (for reports and mode shapes).
    pub locations: Vec<Vec3<S>>,
    /// `M_tot` (d × d).
    pub mass: SparseMatrix<S>,
    /// `K_tot = K_e + K_T + K_L` (d × d).
    pub stiffness: SparseMatrix<S>,
    /// `C_tot = C_e + MV` (d × d): damping plus momentum and gyroscopic terms.
    pub damping: SparseMatrix<S>,
    /// The kinematic velocity matrix `V` (`ṗ = w − V p`).
    pub velocity: SparseMatrix<S>,
    /// Holonomic constraint Jacobian `J` (q × d).
    pub holonomic: SparseMatrix<S>,
    /// Label of each row of `J`.
    pub holonomic_rows: Vec<RowLabel>,
    /// Nonholonomic constraint Jacobian `N` (t × d), acting on `w`.
    pub nonholonomic: SparseMatrix<S>,
    /// Label of each row of `N`.
    pub nonholonomic_rows: Vec<RowLabel>,
    /// Input force matrix `F_u` (d × m).
    pub input_force: SparseMatrix<S>,
    /// Input rate force matrix `G_u` (d × m).
    pub input_rate_force: SparseMatrix<S>,
    /// Sensor rows `C_s = −diag(gain)·J_s` (p × d).
    pub sensor_rows: SparseMatrix<S>,
    /// What each sensor measures.
    pub sensor_kinds: Vec<(SensorOrder, SensorFrame)>,
    /// Feedthrough from sensor–actuator pairing (p × m).
    pub feedthrough: SparseMatrix<S>,
    /// Input names and units.
    pub inputs: Vec<(String, String)>,
    /// Output names and units.
    pub outputs: Vec<(String, String)>,
    /// Applied generalized forces `F` (d).
    pub applied: Vec<S>,
    /// Preloads of the constraint and elastic items.
    pub preloads: Vec<Preload<S>>,
    /// Which branch of the statics was used.
    pub statics: Statics,
    /// Warnings from validation and assembly.
    pub warnings: Vec<String>,
}

impl<S: Scalar> Assembled<S> {
    /// Number of physical coordinates (6 per body).
    pub fn dim(&self) -> usize {
        6 * self.bodies.len()
    }
}

/// A point item's rows, its force and moment directions, bodies and radii.
type PointParts<S> = (
    Rows<S>,
    Vec<Vec3<S>>,
    Vec<Vec3<S>>,
    [Option<usize>; 2],
    [Vec3<S>; 2],
);
/// A line item's row, unit vector, length, bodies and radii.
type LineParts<S> = (Rows<S>, Vec3<S>, S, [Option<usize>; 2], [Vec3<S>; 2]);

/// A point or line item's Jacobian rows on the bodies' coordinates.
struct Rows<S> {
    rows: Vec<ItemRow<S>>,
    labels: Vec<RowLabel>,
}

/// Entries of an item row at most: six coordinates of each of two bodies.
const ITEM_ROW: usize = 12;

/// An item's Jacobian row, `(coordinate, value)` sorted by coordinate, stored inline: an
/// item row never has more than [`ITEM_ROW`] entries, and a model has many rows, each of
/// which would otherwise be an allocation of its own.
#[derive(Clone, Copy, Debug)]
struct ItemRow<S> {
    len: usize,
    entries: [(usize, S); ITEM_ROW],
}

impl<S: Scalar> ItemRow<S> {
    fn new() -> Self {
        ItemRow {
            len: 0,
            entries: [(0, S::zero()); ITEM_ROW],
        }
    }

    fn push(&mut self, e: (usize, S)) {
        self.entries[self.len] = e;
        self.len += 1;
    }
}

impl<S> std::ops::Deref for ItemRow<S> {
    type Target = [(usize, S)];
    fn deref(&self) -> &[(usize, S)] {
        &self.entries[..self.len]
    }
}

impl<S> std::ops::DerefMut for ItemRow<S> {
    fn deref_mut(&mut self) -> &mut [(usize, S)] {
        &mut self.entries[..self.len]
    }
}

impl<S> AsRef<[(usize, S)]> for ItemRow<S> {
    fn as_ref(&self) -> &[(usize, S)] {
        self
    }
}

impl<'a, S> IntoIterator for &'a ItemRow<S> {
    type Item = &'a (usize, S);
    type IntoIter = std::slice::Iter<'a, (usize, S)>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

fn push_entries<S: Scalar>(
    row: &mut ItemRow<S>,
    body: Option<usize>,
    trans: &Vec3<S>,
    rot: &Vec3<S>,
    sign: bool,
) {
    if let Some(k) = body {
        for (i, v) in trans.iter().chain(rot.iter()).enumerate() {
            if !v.is_zero() {
                row.push((6 * k + i, if sign { *v } else { -*v }));
            }
        }
    }
}

fn make_row<S: Scalar>(mut row: ItemRow<S>) -> ItemRow<S> {
    row.sort_by_key(|e| e.0);
    row
}

/// Rows of a point item: translational directions `fdirs`, rotational `mdirs`, at radii
/// `r1`, `r2` from the mass centres of `b1`, `b2`: body 1 gets `[f, r₁ × f]`, body 2
/// `−[f, r₂ × f]`; rotations `[0, g]` and `−[0, g]`.
fn point_rows<S: Scalar>(
    b: [Option<usize>; 2],
    r: [Vec3<S>; 2],
    fdirs: &[Vec3<S>],
    mdirs: &[Vec3<S>],
) -> Vec<ItemRow<S>> {
    let z = zero3::<S>();
    let mut out = Vec::with_capacity(fdirs.len() + mdirs.len());
    for f in fdirs {
        let mut row = ItemRow::new();
        push_entries(&mut row, b[0], f, &cross(&r[0], f), true);
        push_entries(&mut row, b[1], f, &cross(&r[1], f), false);
        out.push(make_row(row));
    }
    for g in mdirs {
        let mut row = ItemRow::new();
        push_entries(&mut row, b[0], &z, g, true);
        push_entries(&mut row, b[1], &z, g, false);
        out.push(make_row(row));
    }
    out
}

/// The deterministic direction rows of a point item with `n` constrained directions.
fn directions<S: Scalar>(n: u8, axis: &Vec3<S>) -> Vec<Vec3<S>> {
    match n {
        3 => vec![x_axis(), y_axis(), z_axis()],
        2 => {
            let u = unit(axis);
            geometry::perpendicular_basis(&u).to_vec()
        }
        1 => vec![unit(axis)],
        _ => Vec::new(),
    }
}

struct Ctx<'a, S> {
    model: &'a Model<S>,
}

impl<S: Scalar> Ctx<'_, S> {
    fn idx(&self, name: &str) -> Option<usize> {
        if name == GROUND {
            None
        } else {
            self.model.body_index(name)
        }
    }
    fn cg(&self, k: Option<usize>) -> Vec3<S> {
        k.map_or(zero3(), |k| self.model.bodies[k].location)
    }
    fn point(&self, p: &Point<S>, kind: &'static str, name: &Name) -> PointParts<S> {
        let b = [self.idx(&p.bodies[0]), self.idx(&p.bodies[1])];
        let r = [
            sub(&p.location, &self.cg(b[0])),
            sub(&p.location, &self.cg(b[1])),
        ];
        let f = directions(p.forces, &p.axis);
        let m = directions(p.moments, &p.axis);
        let rows = point_rows(b, r, &f, &m);
        let mut labels = Vec::with_capacity(f.len() + m.len());
        for k in 0..f.len() {
            labels.push(RowLabel {
                kind,
                item: name.clone(),
                part: "force",
                index: k + 1,
            });
        }
        for k in 0..m.len() {
            labels.push(RowLabel {
                kind,
                item: name.clone(),
                part: "moment",
                index: k + 1,
            });
        }
        (Rows { rows, labels }, f, m, b, r)
    }
    /// Line item: rows (1), unit vector, length, bodies, radii.
    fn line(&self, l: &Line<S>, kind: &'static str, name: &Name) -> LineParts<S> {
        let b = [self.idx(&l.bodies[0]), self.idx(&l.bodies[1])];
        let t = sub(&l.ends[1], &l.ends[0]);
        let len = geometry::norm(&t);
        let u = if len.is_one() {
            t
        } else {
            scale(len.recip(), &t)
        };
        let r = [
            sub(&l.ends[0], &self.cg(b[0])),
            sub(&l.ends[1], &self.cg(b[1])),
        ];
        let rows = if l.twist {
            point_rows(b, r, &[], std::slice::from_ref(&u))
        } else {
            point_rows(b, r, std::slice::from_ref(&u), &[])
        };
        (
            Rows {
                rows,
                labels: vec![RowLabel {
                    kind,
                    item: name.clone(),
                    part: "",
                    index: 0,
                }],
            },
            u,
            len,
            b,
            r,
        )
    }
}

fn rows_to_matrix<S: Scalar>(rows: &[ItemRow<S>], ncols: usize) -> SparseMatrix<S> {
    SparseMatrix::from_sparse_rows(rows, ncols)
}

/// Add a 3×3 block at (row offset, col offset) of body blocks (ground dropped).
fn add_block<S: Scalar>(
    m: &mut Triplets<S>,
    bi: Option<usize>,
    ri: usize,
    bj: Option<usize>,
    rj: usize,
    blk: &Mat3<S>,
    sign: f64,
) {
    let (Some(bi), Some(bj)) = (bi, bj) else {
        return;
    };
    for (i, row) in blk.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            if !v.is_zero() {
                m.push(
                    6 * bi + ri + i,
                    6 * bj + rj + j,
                    if sign > 0.0 { v } else { -v },
                );
            }
        }
    }
}

fn add_rows_block<S: Scalar>(
    m: &mut Triplets<S>,
    rows: &[ItemRow<S>],
    props: &[Vec<S>],
) -> Result<(), ModelError> {
    // m += Rᵀ P R for the item's rows R and property block P.
    let n = rows.len();
    for a in 0..n {
        for b in 0..n {
            let p = props[a][b];
            if p.is_zero() {
                continue;
            }
            for &(i, x) in &rows[a] {
                for &(j, y) in &rows[b] {
                    let v = if p.is_one() { x * y } else { p * x * y };
                    m.push(i, j, v);
                }
            }
        }
    }
    Ok(())
}

fn diag<S: Scalar>(v: &[S]) -> Vec<Vec<S>> {
    let n = v.len();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i == j { v[i] } else { S::zero() })
                .collect()
        })
        .collect()
}

/// Assemble the linearized model.
pub fn assemble<S: Scalar>(model: &Model<S>) -> Result<Assembled<S>, ModelError> {
    let mut warnings = model.validate()?;
    let cx = Ctx { model };
    let nb = model.bodies.len();
    let d = 6 * nb;

    // Room for a few 3×3 blocks per body in each matrix, so that filling rarely reallocates.
    let cap = 4 * d;

    // ---------------------------------------------------------------- mass (§4.1)
    let mut mass = Triplets::with_capacity(d, d, cap);
    let mut mv = Triplets::with_capacity(d, d, cap);
    let mut vel = Triplets::with_capacity(d, d, cap);
    for (k, b) in model.bodies.iter().enumerate() {
        for i in 0..3 {
            mass.push(6 * k + i, 6 * k + i, b.mass);
        }
        let inertia = inertia_tensor(b);
        add_block(&mut mass, Some(k), 3, Some(k), 3, &inertia, 1.0);
        // Gyroscopic and momentum terms (§4.4 centngyro), with the axisymmetry check.
        let w0 = b.angular_velocity;
        if !geometry::is_zero(&w0) {
            check_spin(b, &inertia)?;
            let h = geometry::mat_vec(&inertia, &w0);
            add_block(&mut mv, Some(k), 3, Some(k), 3, &skew(&h), -1.0);
        }
        if !geometry::is_zero(&b.velocity) {
            let mvv = scale(b.mass, &b.velocity);
            add_block(&mut mv, Some(k), 0, Some(k), 3, &skew(&mvv), -1.0);
            add_block(&mut vel, Some(k), 0, Some(k), 3, &skew(&b.velocity), 1.0);
        }
    }

    // ---------------------------------------------------------------- loads (§4.2)
    let mut applied = vec![S::zero(); d];
    let mut k_load = Triplets::with_capacity(d, d, cap);
    for l in &model.loads {
        let (Some(p1), p2) = (cx.idx(&l.body), cx.idx(&l.frame)) else {
            warnings.push(format!(
                "load `{}` acts on the ground and has no effect",
                l.name
            ));
            continue;
        };
        let r = sub(&l.location, &cx.cg(Some(p1)));
        let mom = geometry::sub(&l.moment, &scale(-S::one(), &cross(&r, &l.force)));
        for i in 0..3 {
            let f = l.force[i];
            if !f.is_zero() {
                applied[6 * p1 + i] = applied[6 * p1 + i] + f;
            }
            if !mom[i].is_zero() {
                applied[6 * p1 + 3 + i] = applied[6 * p1 + 3 + i] + mom[i];
            }
        }
        if p2 == Some(p1) {
            continue; // follower load fixed in its own body: the terms cancel exactly
        }
        let f0 = skew(&l.force);
        let rf = mat_add(&mat_mul(&skew(&r), &f0), &skew(&l.moment));
        add_block(&mut k_load, Some(p1), 0, Some(p1), 3, &f0, -1.0);
        add_block(&mut k_load, Some(p1), 0, p2, 3, &f0, 1.0);
        add_block(&mut k_load, Some(p1), 3, Some(p1), 3, &rf, -1.0);
        add_block(&mut k_load, Some(p1), 3, p2, 3, &rf, 1.0);
    }

    // ---------------------------------------------------------------- elastic items (§4.3)
    let mut h_rows: Vec<ItemRow<S>> = Vec::new();
    let mut h_labels: Vec<RowLabel> = Vec::new();
    let mut k_el = Triplets::with_capacity(d, d, cap);
    let mut c_el = Triplets::with_capacity(d, d, cap);
    let mut m_el = Triplets::with_capacity(d, d, cap);
    // Per elastic row: stiffness blocks for the compatibility equations.
    let mut stiff_blocks: Vec<(usize, Vec<Vec<S>>)> = Vec::new();
    let mut spring_geo = Vec::new();
    for s in &model.springs {
        let (rows, u, len, b, r) = cx.line(&s.line, "spring", &s.name);
        let start = h_rows.len();
        add_rows_block(&mut k_el, &rows.rows, &[vec![s.stiffness]])?;
        add_rows_block(&mut c_el, &rows.rows, &[vec![s.damping]])?;
        add_rows_block(&mut m_el, &rows.rows, &[vec![s.inertance]])?;
        stiff_blocks.push((start, vec![vec![s.stiffness]]));
        h_rows.extend(rows.rows);
        h_labels.extend(rows.labels);
        spring_geo.push((u, len, b, r, s.line.twist));
    }
    let mut flex_geo = Vec::new();
    for f in &model.flex_points {
        let (rows, fd, md, b, r) = cx.point(&f.point, "flex point", &f.name);
        let kdiag: Vec<S> = fd
            .iter()
            .map(|_| f.stiffness[0])
            .chain(md.iter().map(|_| f.stiffness[1]))
            .collect();
        let cdiag: Vec<S> = fd
            .iter()
            .map(|_| f.damping[0])
            .chain(md.iter().map(|_| f.damping[1]))
            .collect();
        let kb = f.stiffness_matrix.clone().unwrap_or_else(|| diag(&kdiag));
        let cb = f.damping_matrix.clone().unwrap_or_else(|| diag(&cdiag));
        let start = h_rows.len();
        add_rows_block(&mut k_el, &rows.rows, &kb)?;
        add_rows_block(&mut c_el, &rows.rows, &cb)?;
        stiff_blocks.push((start, kb));
        h_rows.extend(rows.rows);
        h_labels.extend(rows.labels);
        flex_geo.push((fd, md, b, r));
    }
    for bm in &model.beams {
        let (rows, kb, mb) = beam_rows(&cx, bm)?;
        let start = h_rows.len();
        add_rows_block(&mut k_el, &rows.rows, &kb)?;
        add_rows_block(&mut m_el, &rows.rows, &mb)?;
        stiff_blocks.push((start, kb));
        h_rows.extend(rows.rows);
        h_labels.extend(rows.labels);
    }

    // ---------------------------------------------------------------- constraints (§4.4)
    let mut j_rows: Vec<ItemRow<S>> = Vec::new();
    let mut j_labels: Vec<RowLabel> = Vec::new();
    let mut link_geo = Vec::new();
    for l in &model.links {
        let (rows, u, len, b, r) = cx.line(&l.line, "link", &l.name);
        j_rows.extend(rows.rows);
        j_labels.extend(rows.labels);
        link_geo.push((u, len, b, r, l.line.twist));
    }
    let mut rigid_geo = Vec::new();
    for p in &model.rigid_points {
        let (rows, fd, md, b, r) = cx.point(&p.point, "rigid point", &p.name);
        j_rows.extend(rows.rows);
        j_labels.extend(rows.labels);
        rigid_geo.push((fd, md, b, r));
    }
    let mut n_rows: Vec<ItemRow<S>> = Vec::new();
    let mut n_labels: Vec<RowLabel> = Vec::new();
    for p in &model.nh_points {
        let (rows, ..) = cx.point(&p.point, "nh point", &p.name);
        n_rows.extend(rows.rows);
        n_labels.extend(rows.labels);
    }

    // ---------------------------------------------------------------- statics (§4.5)
    let known: Vec<(usize, S, S)> = model
        .springs
        .iter()
        .enumerate()
        .filter_map(|(i, s)| s.preload.map(|p| (i, p, s.stiffness)))
        .collect();
    let k_el = k_el.build();
    let (lambda_c, lambda_e, statics) = solve_statics(
        d,
        &j_rows,
        &h_rows,
        &applied,
        &known,
        &stiff_blocks,
        &k_el,
        &j_labels,
        &model.bodies,
    )?;

    // ---------------------------------------------------------------- tangent stiffness (§4.6)
    let mut k_t = Triplets::with_capacity(d, d, cap);
    let mut preloads = Vec::new();
    let mut jc = 0;
    for (l, (u, len, b, r, twist)) in model.links.iter().zip(&link_geo) {
        let t = lambda_c[jc];
        jc += 1;
        line_tangent(&mut k_t, t, u, *len, *b, r, *twist);
        preloads.push(line_preload(format!("link `{}`", l.name), t, u, *twist));
    }
    for (p, (fd, md, b, r)) in model.rigid_points.iter().zip(&rigid_geo) {
        let n = fd.len() + md.len();
        let lam = &lambda_c[jc..jc + n];
        jc += n;
        let (f, m) = point_force(lam, fd, md);
        point_tangent(&mut k_t, &p.point, &f, &m, *b, r);
        preloads.push(Preload {
            item: format!("rigid point `{}`", p.name),
            force: f,
            moment: m,
            tension: None,
        });
    }
    let mut je = 0;
    for (s, (u, len, b, r, twist)) in model.springs.iter().zip(&spring_geo) {
        let t = lambda_e[je];
        je += 1;
        line_tangent(&mut k_t, t, u, *len, *b, r, *twist);
        preloads.push(line_preload(format!("spring `{}`", s.name), t, u, *twist));
    }
    for (p, (fd, md, b, r)) in model.flex_points.iter().zip(&flex_geo) {
        let n = fd.len() + md.len();
        let lam = &lambda_e[je..je + n];
        je += n;
        let (f, m) = point_force(lam, fd, md);
        point_tangent(&mut k_t, &p.point, &f, &m, *b, r);
        preloads.push(Preload {
            item: format!("flex point `{}`", p.name),
            force: f,
            moment: m,
            tension: None,
        });
    }
    for bm in &model.beams {
        // Beams carry end loads but contribute no geometric stiffness (eom-method §13.10).
        let lam = &lambda_e[je..je + 8];
        je += 8;
        let _ = lam;
        preloads.push(Preload {
            item: format!("beam `{}`", bm.name),
            force: zero3(),
            moment: zero3(),
            tension: None,
        });
    }

    // ---------------------------------------------------------------- inputs and outputs
    let nin = model.actuators.len();
    let mut f_u = Triplets::new(d, nin);
    let mut g_u = Triplets::new(d, nin);
    for (a, act) in model.actuators.iter().enumerate() {
        let (rows, ..) = cx.line(&act.line, "actuator", &act.name);
        for &(i, v) in &rows.rows[0] {
            f_u.push(i, a, -(act.gain * v));
            if !act.rate_gain.is_zero() {
                g_u.push(i, a, -(act.rate_gain * v));
            }
        }
    }
    let nout = model.sensors.len();
    let mut c_s = Triplets::new(nout, d);
    let mut d_s = Triplets::new(nout, nin);
    let mut kinds = Vec::new();
    for (o, sen) in model.sensors.iter().enumerate() {
        let (rows, ..) = cx.line(&sen.line, "sensor", &sen.name);
        for &(j, v) in &rows.rows[0] {
            c_s.push(o, j, -(sen.gain * v));
        }
        kinds.push((sen.order, sen.frame));
        if let Some(a) = &sen.actuator {
            let k = model
                .actuators
                .iter()
                .position(|x| &x.name == a)
                .expect("validated");
            d_s.push(o, k, sen.actuator_gain);
        }
    }

    let stiffness = k_el.add(&k_t.build())?.add(&k_load.build())?;
    Ok(Assembled {
        name: model.name.clone(),
        bodies: model.bodies.iter().map(|b| b.name.to_string()).collect(),
        locations: model.bodies.iter().map(|b| b.location).collect(),
        mass: mass.build().add(&m_el.build())?,
        stiffness,
        damping: c_el.build().add(&mv.build())?,
        velocity: vel.build(),
        holonomic: rows_to_matrix(&j_rows, d),
        holonomic_rows: j_labels,
        nonholonomic: rows_to_matrix(&n_rows, d),
        nonholonomic_rows: n_labels,
        input_force: f_u.build(),
        input_rate_force: g_u.build(),
        sensor_rows: c_s.build(),
        sensor_kinds: kinds,
        feedthrough: d_s.build(),
        inputs: model
            .actuators
            .iter()
            .map(|a| (a.name.to_string(), a.units.clone()))
            .collect(),
        outputs: model
            .sensors
            .iter()
            .map(|s| (s.name.to_string(), s.units.clone()))
            .collect(),
        applied,
        preloads,
        statics,
        warnings,
    })
}

fn mat_add<S: Scalar>(a: &Mat3<S>, b: &Mat3<S>) -> Mat3<S> {
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

fn mat_scale<S: Scalar>(c: S, a: &Mat3<S>) -> Mat3<S> {
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

/// The inertia tensor; products enter with a minus sign, ordered (xy, yz, zx).
fn inertia_tensor<S: Scalar>(b: &Body<S>) -> Mat3<S> {
    let n = |x: S| if x.is_zero() { x } else { -x };
    let [ixx, iyy, izz] = b.moments;
    let [ixy, iyz, izx] = b.products;
    [
        [ixx, n(ixy), n(izx)],
        [n(ixy), iyy, n(iyz)],
        [n(izx), n(iyz), izz],
    ]
}

/// A spinning body must spin about an axis of symmetry (at the nominal point): the
/// linearization in the non-spinning (Resal) frame has constant coefficients only then.
fn check_spin<S: Scalar>(b: &Body<S>, inertia: &Mat3<S>) -> Result<(), ModelError> {
    let w: Vec<f64> = b.angular_velocity.iter().map(|x| x.nominal()).collect();
    let i: Vec<Vec<f64>> = inertia
        .iter()
        .map(|r| r.iter().map(|x| x.nominal()).collect())
        .collect();
    let wn = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    if wn == 0.0 {
        return Ok(());
    }
    let a = [w[0] / wn, w[1] / wn, w[2] / wn];
    let ia: Vec<f64> = (0..3)
        .map(|r| (0..3).map(|c| i[r][c] * a[c]).sum())
        .collect();
    let scale = i
        .iter()
        .flatten()
        .map(|x| x.abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let c = [
        a[1] * ia[2] - a[2] * ia[1],
        a[2] * ia[0] - a[0] * ia[2],
        a[0] * ia[1] - a[1] * ia[0],
    ];
    let cn = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    let item = format!("body `{}`", b.name);
    if cn > 1e-9 * scale {
        return Err(ModelError::Model {
            item,
            field: "angular_velocity".into(),
            problem: "the spin axis is not a principal axis of inertia: the linearization about a steady spin does not exist".into(),
        });
    }
    // Transverse inertia: I projected on the plane ⊥ a must be isotropic.
    let axial = a.iter().zip(&ia).map(|(x, y)| x * y).sum::<f64>();
    let tr = i[0][0] + i[1][1] + i[2][2] - axial;
    let half = tr / 2.0;
    // Check vᵀ I v = half for two perpendicular unit vectors.
    let k = (0..3)
        .min_by(|&x, &y| a[x].abs().partial_cmp(&a[y].abs()).expect("finite"))
        .expect("3");
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let mut v1 = [
        a[1] * e[2] - a[2] * e[1],
        a[2] * e[0] - a[0] * e[2],
        a[0] * e[1] - a[1] * e[0],
    ];
    let n1 = (v1[0] * v1[0] + v1[1] * v1[1] + v1[2] * v1[2]).sqrt();
    v1.iter_mut().for_each(|x| *x /= n1);
    let q: f64 = (0..3)
        .map(|r| (0..3).map(|c| v1[r] * i[r][c] * v1[c]).sum::<f64>())
        .sum();
    if (q - half).abs() > 1e-9 * scale {
        return Err(ModelError::Model {
            item,
            field: "angular_velocity".into(),
            problem: "spins about a principal axis that is not an axis of symmetry (unequal transverse inertias): the gyroscopic terms would be periodic, not constant (eom-method §13.12)".into(),
        });
    }
    Ok(())
}

/// The 8 rows of a beam and its stiffness and mass blocks.
type BeamParts<S> = (Rows<S>, Vec<Vec<S>>, Vec<Vec<S>>);
fn beam_rows<S: Scalar>(cx: &Ctx<'_, S>, bm: &Beam<S>) -> Result<BeamParts<S>, ModelError> {
    let b = [cx.idx(&bm.bodies[0]), cx.idx(&bm.bodies[1])];
    let t = sub(&bm.ends[1], &bm.ends[0]);
    let l = geometry::norm(&t);
    let u = scale(l.recip(), &t);
    let e2 = unit(&cross(&u, &bm.perp));
    let e1 = scale(-S::one(), &cross(&u, &e2));
    let r = [
        sub(&bm.ends[0], &cx.cg(b[0])),
        sub(&bm.ends[1], &cx.cg(b[1])),
    ];
    let z = zero3::<S>();
    let mut rows = Vec::new();
    for (k, (body, rad)) in b.iter().zip(&r).enumerate() {
        for e in [&e1, &e2] {
            let mut row = ItemRow::new();
            push_entries(&mut row, *body, e, &cross(rad, e), true);
            rows.push(make_row(row));
        }
        for e in [&e1, &e2] {
            let mut row = ItemRow::new();
            push_entries(&mut row, *body, &z, e, true);
            rows.push(make_row(row));
        }
        let _ = k;
    }
    let labels = (1..=8)
        .map(|k| RowLabel {
            kind: "beam",
            item: bm.name.clone(),
            part: "end row",
            index: k,
        })
        .collect();
    // D and E of eom-method §4.3 on [e1·δx1, e2·δx1, e1·θ1, e2·θ1, e1·δx2, e2·δx2, e1·θ2, e2·θ2].
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
    Ok((
        Rows { rows, labels },
        quad(&dmat, &kd, il),
        quad(&emat, &md, mscale),
    ))
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
        }
    } else {
        Preload {
            item,
            force: scale(t, u),
            moment: zero3(),
            tension: Some(t),
        }
    }
}

/// Geometric stiffness of a line item with tension `t` (eom-method §4.6).
fn line_tangent<S: Scalar>(
    k: &mut Triplets<S>,
    t: S,
    u: &Vec3<S>,
    len: S,
    b: [Option<usize>; 2],
    r: &[Vec3<S>; 2],
    twist: bool,
) {
    if t.is_zero() {
        return;
    }
    if twist {
        // A preload torque about the line, carried by the mean frame of the two bodies.
        let g = mat_scale(
            S::from_rational(&eom_sym::Rational::new(1, 2).expect("1/2")),
            &skew(&scale(t, u)),
        );
        add_block(k, b[0], 3, b[0], 3, &g, -1.0);
        add_block(k, b[0], 3, b[1], 3, &g, 1.0);
        add_block(k, b[1], 3, b[1], 3, &g, 1.0);
        add_block(k, b[1], 3, b[0], 3, &g, -1.0);
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
                    add_block(k, bi, ri, bj, rj, &m, 1.0);
                }
            }
        }
    }
    // −T tᵢᵀ into the rotation columns of body i (rotation of the force into body axes).
    for &(bi, ti) in &blocks {
        add_block(
            k,
            bi,
            0,
            bi,
            3,
            &mat_scale(t, &geometry::transpose(&ti.0)),
            -1.0,
        );
        add_block(
            k,
            bi,
            3,
            bi,
            3,
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
    b: [Option<usize>; 2],
    r: &[Vec3<S>; 2],
) {
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
        add_block(k, p1, 0, p1, 3, &f0, -1.0);
        add_block(k, p1, 0, p3, 3, &f0, 1.0);
        add_block(k, p2, 0, p2, 3, &f0, 1.0);
        add_block(k, p2, 0, p3, 3, &f0, -1.0);
        add_block(k, p1, 3, p1, 3, &f1, -1.0);
        add_block(k, p1, 3, p3, 3, &f1, 1.0);
        add_block(k, p2, 3, p2, 3, &f2, 1.0);
        add_block(k, p2, 3, p3, 3, &f2, -1.0);
        // The contact point is fixed in body 1: body 2's moment arm changes with relative motion.
        add_block(k, p2, 3, p1, 0, &f0, -1.0);
        add_block(k, p2, 3, p2, 0, &f0, 1.0);
        add_block(k, p2, 3, p1, 3, &geometry::transpose(&f1), 1.0);
        add_block(k, p2, 3, p2, 3, &geometry::transpose(&f2), -1.0);
        if rolling {
            let ra = unit(&p.rolling_axis);
            let g = mat_scale(
                -S::one(),
                &mat_mul(&geometry::transpose(&f1), &outer(&ra, &ra)),
            );
            add_block(k, p1, 3, p1, 3, &g, -1.0);
            add_block(k, p1, 3, p2, 3, &g, 1.0);
            add_block(k, p2, 3, p2, 3, &g, -1.0);
            add_block(k, p2, 3, p1, 3, &g, 1.0);
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
        add_block(k, p1, 3, p1, 3, &g, -1.0);
        add_block(k, p2, 3, p2, 3, &g, 1.0);
    } else if p.moments == 1 {
        let g = mat_scale(
            S::from_rational(&eom_sym::Rational::new(1, 2).expect("1/2")),
            &skew(mm),
        );
        add_block(k, p1, 3, p1, 3, &g, -1.0);
        add_block(k, p1, 3, p2, 3, &g, 1.0);
        add_block(k, p2, 3, p2, 3, &g, 1.0);
        add_block(k, p2, 3, p1, 3, &g, -1.0);
    }
}

type StaticsResult<S> = (Vec<S>, Vec<S>, Statics);

/// Solve the static preloads: `Jᵀλ_c + Hᵀλ_e = −F` with known spring preloads; determinate by
/// force balance, otherwise by elastic compatibility (eom-method §4.5).
#[allow(clippy::too_many_arguments)]
fn solve_statics<S: Scalar>(
    d: usize,
    j_rows: &[ItemRow<S>],
    h_rows: &[ItemRow<S>],
    f: &[S],
    known: &[(usize, S, S)],
    stiff_blocks: &[(usize, Vec<Vec<S>>)],
    k_el: &SparseMatrix<S>,
    j_labels: &[RowLabel],
    bodies: &[Body<S>],
) -> Result<StaticsResult<S>, ModelError> {
    let q = j_rows.len();
    let s = h_rows.len();
    let zero_c = vec![S::zero(); q];
    let zero_e = vec![S::zero(); s];
    if f.iter().all(Scalar::is_zero) && known.iter().all(|k| k.1.is_zero()) {
        return Ok((zero_c, zero_e, Statics::Unloaded));
    }
    let nu = q + s;
    // Rows of [Jᵀ Hᵀ | −F] (d rows) and [0 S | preload] (known rows).
    let mut len = vec![1usize; d];
    for &(i, _) in j_rows.iter().chain(h_rows.iter()).flatten() {
        len[i] += 1;
    }
    let mut rows = RowStore::with_lengths(&len, nu + 1);
    for (c, r) in j_rows.iter().chain(h_rows.iter()).enumerate() {
        for &(i, v) in r {
            rows.push(i, (c, v));
        }
    }
    for (i, &fi) in f.iter().enumerate().take(d) {
        if !fi.is_zero() {
            rows.push(i, (nu, -fi));
        }
    }
    for &(spring, p, _) in known {
        let one = (q + spring, S::one());
        if p.is_zero() {
            rows.push_row(&[one]);
        } else {
            rows.push_row(&[one, (nu, p)]);
        }
    }
    let coord_label = |i: usize| -> String {
        if i < d {
            let comp = [
                "x force", "y force", "z force", "x moment", "y moment", "z moment",
            ][i % 6];
            format!("body `{}` {comp}", bodies[i / 6].name)
        } else {
            format!("known preload {}", i - d + 1)
        }
    };
    let red = rref(rows, nu, &[], None)?;
    let rank = red.plan.pivots.len();
    let (lc, le, kind) = if rank == nu {
        let mut sol = vec![S::zero(); nu];
        for &(r, c) in &red.plan.pivots {
            sol[c] = red.rows[r]
                .iter()
                .find(|e| e.0 == nu)
                .map_or(S::zero(), |e| e.1);
        }
        (sol[..q].to_vec(), sol[q..].to_vec(), Statics::Determinate)
    } else {
        // Indeterminate: z = [μ; x; δ₀] from the compatibility equations.
        let p = known.len();
        let n = q + d + p;
        let mut trows: Vec<Row<S>> = vec![Vec::new(); n];
        for (i, r) in j_rows.iter().enumerate() {
            for &(c, v) in r {
                trows[i].push((q + c, v));
                trows[q + c].push((i, v));
            }
        }
        for (i, j, v) in k_el.iter() {
            trows[q + i].push((q + j, v));
        }
        for (kk, &(spring, pre, ks)) in known.iter().enumerate() {
            for &(c, v) in &h_rows[spring] {
                // Hᵀ Sᵀ k_s column and k_s S H row.
                trows[q + c].push((q + d + kk, ks * v));
                trows[q + d + kk].push((q + c, ks * v));
            }
            trows[q + d + kk].push((q + d + kk, ks));
            if !pre.is_zero() {
                trows[q + d + kk].push((n, pre));
            }
        }
        for i in 0..d {
            if !f[i].is_zero() {
                trows[q + i].push((n, -f[i]));
            }
        }
        let trows: Vec<Row<S>> = trows
            .into_iter()
            .map(|mut r| {
                r.sort_by_key(|e| e.0);
                // merge duplicates
                let mut m: Row<S> = Vec::with_capacity(r.len());
                for (c, v) in r {
                    match m.last_mut() {
                        Some(l) if l.0 == c => l.1 = l.1 + v,
                        _ => m.push((c, v)),
                    }
                }
                m.retain(|e| !e.1.is_zero());
                m
            })
            .collect();
        let tr = rref(RowStore::from_rows(&trows, n + 1), n, &[], None)?;
        if tr.plan.pivots.len() < n {
            return Err(ModelError::Singular(format!(
                "the model is statically indeterminate (rank {rank} of {nu} unknown preloads) and its elastic compatibility equations are singular: the preloads of redundant rigid constraints cannot be determined (add compliance, or remove a redundant joint among: {})",
                j_labels
                    .iter()
                    .map(|l| l.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        let mut z = vec![S::zero(); n];
        for &(r, c) in &tr.plan.pivots {
            z[c] = tr.rows[r]
                .iter()
                .find(|e| e.0 == n)
                .map_or(S::zero(), |e| e.1);
        }
        let mu = z[..q].to_vec();
        let x = &z[q..q + d];
        // Elastic forces: stiff·H·x (+ k_s δ₀ for known-preload springs).
        let mut le = vec![S::zero(); s];
        let hx: Vec<S> = h_rows
            .iter()
            .map(|r| S::sum(&r.iter().map(|&(c, v)| v * x[c]).collect::<Vec<_>>()))
            .collect();
        for (start, blk) in stiff_blocks {
            for (a, row) in blk.iter().enumerate() {
                let terms: Vec<S> = row
                    .iter()
                    .enumerate()
                    .filter(|(_, v)| !v.is_zero())
                    .map(|(b, v)| *v * hx[start + b])
                    .collect();
                le[start + a] = S::sum(&terms);
            }
        }
        for (kk, &(spring, _, ks)) in known.iter().enumerate() {
            le[spring] = le[spring] + ks * z[q + d + kk];
        }
        (mu, le, Statics::Indeterminate)
    };
    // Relative equilibrium check per equation: |F_i + Σ T_ij λ_j| ≤ tol · (|F_i| + Σ |T_ij λ_j|).
    let lam: Vec<S> = lc.iter().chain(le.iter()).copied().collect();
    // Accumulated from the item rows (the columns of Tᵀ) in the order of λ, so each equation
    // sums its terms in the same order as a walk along its row would.
    let mut res: Vec<f64> = f.iter().map(|x| x.nominal()).collect();
    let mut mag: Vec<f64> = res.iter().map(|x| x.abs()).collect();
    for (c, r) in j_rows.iter().chain(h_rows.iter()).enumerate() {
        let l = lam[c].nominal();
        for &(i, v) in r {
            let t = v.nominal() * l;
            res[i] += t;
            mag[i] += t.abs();
        }
    }
    for (i, (&res, &mag)) in res.iter().zip(&mag).enumerate() {
        if res.is_nan() || res.abs() > 1e-9 * mag + 1e-300 {
            return Err(ModelError::Equilibrium(format!(
                "{}: residual {res:.6e} (of terms summing to {mag:.6e} in magnitude). The given geometry is not an equilibrium with these constraints (eom uses the given geometry as the loaded equilibrium: add a support, or give spring preloads that balance the loads)",
                coord_label(i)
            )));
        }
    }
    Ok((lc, le, kind))
}
