//! [`Assembly`]: what an item kind sees of the assembly. An item reads the bodies (their
//! indices and mass centres), builds the Jacobian rows of its geometry ([`Assembly::line`],
//! [`Assembly::point`]) and adds its terms: 3×3 blocks and `Rᵀ P R` property blocks to the
//! mass, stiffness and damping terms, holonomic, elastic or nonholonomic rows with the reaction
//! their multipliers carry, known preloads, applied loads, inputs and outputs.

use super::{OutputKind, RowLabel};
use crate::geometry::{self, GROUND, Line, Mat3, Name, Point, Vec3, cross, scale, sub, unit};
use crate::geometry::{x_axis, y_axis, z_axis, zero3};
use crate::warning::Warning;
use eom_sym::matrix::Triplets;
use eom_sym::scalar::Scalar;
use hashbrown::HashMap;

/// The term of the equations a block is added to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Term {
    /// The bodies' mass and inertia.
    Mass,
    /// Mass of the items (inertance, distributed mass), added to [`Term::Mass`].
    ItemMass,
    /// Elastic stiffness `K_e`.
    Stiffness,
    /// Damping `C_e`.
    Damping,
    /// Momentum and gyroscopic terms `MV`, added to the damping.
    Momentum,
    /// The kinematic velocity matrix `V` (`ṗ = w − V p`).
    Velocity,
    /// Stiffness of the applied loads `K_L`.
    LoadStiffness,
}

/// Entries of an item row at most: six coordinates of each of two bodies.
pub const ITEM_ROW: usize = 12;

/// An item's Jacobian row, `(coordinate, value)` sorted by coordinate, stored inline: an
/// item row never has more than [`ITEM_ROW`] entries, and a model has many rows, each of
/// which would otherwise be an allocation of its own.
#[derive(Clone, Copy, Debug)]
pub struct ItemRow<S> {
    len: usize,
    entries: [(usize, S); ITEM_ROW],
}

impl<S: Scalar> ItemRow<S> {
    /// An empty row.
    pub fn new() -> Self {
        ItemRow {
            len: 0,
            entries: [(0, S::zero()); ITEM_ROW],
        }
    }

    fn push(&mut self, e: (usize, S)) {
        self.entries[self.len] = e;
        self.len += 1;
    }

    /// Add the translational part `trans` and rotational part `rot` on the six coordinates
    /// of `body` (nothing for the ground), negated unless `positive`.
    pub fn push_body(
        &mut self,
        body: Option<usize>,
        trans: &Vec3<S>,
        rot: &Vec3<S>,
        positive: bool,
    ) {
        if let Some(k) = body {
            for (i, v) in trans.iter().chain(rot.iter()).enumerate() {
                if !v.is_zero() {
                    self.push((6 * k + i, if positive { *v } else { -*v }));
                }
            }
        }
    }

    /// The row with its entries sorted by coordinate.
    pub fn sorted(mut self) -> Self {
        self.sort_by_key(|e| e.0);
        self
    }
}

impl<S: Scalar> Default for ItemRow<S> {
    fn default() -> Self {
        Self::new()
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

/// An item's Jacobian rows on the bodies' coordinates, with their labels.
#[derive(Clone, Debug)]
pub struct Rows<S> {
    /// The rows.
    pub rows: Vec<ItemRow<S>>,
    /// One label per row (a line item's single row, or the directions of a point item).
    pub labels: Vec<RowLabel>,
}

/// The geometry of a line item: unit vector from end 1 to end 2, length, bodies and the
/// radii of its ends from their bodies' mass centres.
#[derive(Clone, Debug)]
pub struct LineGeometry<S> {
    /// Unit vector from end 1 to end 2.
    pub unit: Vec3<S>,
    /// Length.
    pub length: S,
    /// Body indices (`None`: ground).
    pub bodies: [Option<usize>; 2],
    /// End 1 from body 1's mass centre, end 2 from body 2's.
    pub radii: [Vec3<S>; 2],
    /// Torsional about the line.
    pub twist: bool,
}

/// The geometry of a point item: its force and moment directions, bodies and the radii of
/// the point from their mass centres.
#[derive(Clone, Debug)]
pub struct PointGeometry<S> {
    /// Constrained translational directions (rows `force 1…`).
    pub forces: Vec<Vec3<S>>,
    /// Constrained rotational directions (rows `moment 1…`).
    pub moments: Vec<Vec3<S>>,
    /// Body indices (`None`: ground).
    pub bodies: [Option<usize>; 2],
    /// The point from body 1's and body 2's mass centre.
    pub radii: [Vec3<S>; 2],
}

/// What the multipliers of an item's holonomic or elastic rows are, for the preload it reports
/// and the geometric stiffness of that preload.
#[derive(Clone, Debug)]
pub enum Reaction<'m, S> {
    /// The tension (twisted: the torque) of a line item; one row.
    Line(LineGeometry<S>),
    /// The force and moment of a point item; one row per direction.
    Point(&'m Point<S>, PointGeometry<S>),
    /// Reactions that add no geometric stiffness and are reported as zero (a beam's end
    /// loads).
    Unreported,
}

/// The rows of one item in a row set, with the reaction of their multipliers.
#[derive(Clone, Debug)]
pub(crate) struct Reacting<'m, S> {
    pub(crate) kind: &'static str,
    pub(crate) name: Name,
    pub(crate) rows: usize,
    pub(crate) reaction: Reaction<'m, S>,
}

/// Rows of one kind (holonomic, elastic or nonholonomic) in the order the items added them.
#[derive(Clone, Debug)]
pub(crate) struct RowSet<'m, S> {
    pub(crate) rows: Vec<ItemRow<S>>,
    pub(crate) labels: Vec<RowLabel>,
    pub(crate) reactions: Vec<Reacting<'m, S>>,
}

impl<S> RowSet<'_, S> {
    /// An empty set with room for the reactions of `items` items.
    fn new(items: usize) -> Self {
        RowSet {
            rows: Vec::new(),
            labels: Vec::new(),
            reactions: Vec::with_capacity(items),
        }
    }
}

/// A spring with a known preload: its elastic row, the preload and its stiffness.
pub(crate) type KnownPreload<S> = (usize, S, S);

/// Inputs and outputs, as entries of matrices whose sizes are known at the end.
#[derive(Clone, Debug, Default)]
pub(crate) struct Signals<S> {
    pub(crate) inputs: Vec<(String, String)>,
    pub(crate) input_force: Vec<(usize, usize, S)>,
    pub(crate) input_rate_force: Vec<(usize, usize, S)>,
    pub(crate) outputs: Vec<(String, String)>,
    pub(crate) sensor_rows: Vec<(usize, usize, S)>,
    pub(crate) output_kinds: Vec<OutputKind>,
    pub(crate) feedthrough: Vec<(usize, usize, S)>,
}

/// Which block of the lag-state equations an entry goes to (see
/// [`Lags`](super::Lags)): `ẋ_a = A_a x_a + P_a p + W_a w` and the force `F_a x_a` on the
/// bodies' equations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LagTerm {
    /// `A_a` (lag state × lag state).
    Rate,
    /// `P_a` (lag state × coordinate): the lag driven by displacements.
    Position,
    /// `W_a` (lag state × coordinate): the lag driven by velocities.
    Velocity,
    /// `F_a` (coordinate × lag state): the generalized force of the lag states.
    Force,
}

/// The lag states' names and entries, as triplets whose sizes are known at the end.
#[derive(Clone, Debug)]
pub(crate) struct LagTerms<S> {
    pub(crate) names: Vec<String>,
    pub(crate) rate: Vec<(usize, usize, S)>,
    pub(crate) position: Vec<(usize, usize, S)>,
    pub(crate) velocity: Vec<(usize, usize, S)>,
    pub(crate) force: Vec<(usize, usize, S)>,
}

impl<S> Default for LagTerms<S> {
    fn default() -> Self {
        LagTerms {
            names: Vec::new(),
            rate: Vec::new(),
            position: Vec::new(),
            velocity: Vec::new(),
            force: Vec::new(),
        }
    }
}

/// Bodies above which [`Assembly::body`] looks names up in a hash map rather than by a scan.
const BODY_MAP_AFTER: usize = 8;

/// A body as the assembly sees it: its name and its mass centre.
#[derive(Clone, Copy, Debug)]
pub struct BodyFrame<'m, S> {
    /// The body's name.
    pub name: &'m Name,
    /// Its mass centre.
    pub location: Vec3<S>,
    /// The nominal velocity of its mass centre.
    pub velocity: Vec3<S>,
}

/// The assembly context: the bodies, and every term the items add to.
pub struct Assembly<'m, S> {
    pub(crate) bodies: Vec<BodyFrame<'m, S>>,
    /// Body indices by name, for models with many bodies.
    body_map: Option<HashMap<&'m str, usize>>,
    pub(crate) mass: Triplets<S>,
    pub(crate) item_mass: Triplets<S>,
    pub(crate) stiffness: Triplets<S>,
    pub(crate) damping: Triplets<S>,
    pub(crate) momentum: Triplets<S>,
    pub(crate) velocity: Triplets<S>,
    pub(crate) load_stiffness: Triplets<S>,
    pub(crate) applied: Vec<S>,
    pub(crate) holonomic: RowSet<'m, S>,
    pub(crate) elastic: RowSet<'m, S>,
    pub(crate) nonholonomic: RowSet<'m, S>,
    /// Stiffness block of each elastic item: its first elastic row and the block.
    pub(crate) stiffness_blocks: Vec<(usize, Vec<Vec<S>>)>,
    pub(crate) known: Vec<KnownPreload<S>>,
    pub(crate) signals: Signals<S>,
    pub(crate) lags: LagTerms<S>,
    pub(crate) warnings: Vec<Warning>,
}

impl<'m, S: Scalar> Assembly<'m, S> {
    /// An empty assembly over `bodies`, for `items` items, with `warnings` so far.
    pub(crate) fn new(bodies: Vec<BodyFrame<'m, S>>, items: usize, warnings: Vec<Warning>) -> Self {
        let d = 6 * bodies.len();
        // Room for a few 3×3 blocks per body in each matrix, so that filling rarely
        // reallocates.
        let cap = 4 * d;
        let square = || Triplets::with_capacity(d, d, cap);
        let body_map = (bodies.len() > BODY_MAP_AFTER).then(|| {
            let mut map = HashMap::with_capacity(bodies.len());
            for (k, b) in bodies.iter().enumerate() {
                map.entry(&**b.name).or_insert(k);
            }
            map
        });
        Assembly {
            bodies,
            body_map,
            mass: square(),
            item_mass: square(),
            stiffness: square(),
            damping: square(),
            momentum: square(),
            velocity: square(),
            load_stiffness: square(),
            applied: vec![S::zero(); d],
            // Room for the reactions of a moderate model without growing (a large one grows).
            holonomic: RowSet::new(items.min(32)),
            elastic: RowSet::new(items.min(32)),
            nonholonomic: RowSet::new(0),
            stiffness_blocks: Vec::new(),
            known: Vec::new(),
            signals: Signals {
                inputs: Vec::new(),
                input_force: Vec::new(),
                input_rate_force: Vec::new(),
                outputs: Vec::new(),
                sensor_rows: Vec::new(),
                output_kinds: Vec::new(),
                feedthrough: Vec::new(),
            },
            lags: LagTerms::default(),
            warnings,
        }
    }

    /// Number of coordinates (6 per body).
    pub fn dim(&self) -> usize {
        6 * self.bodies.len()
    }

    /// Index of a body by name (`None` for the ground).
    pub fn body(&self, name: &str) -> Option<usize> {
        if name == GROUND {
            return None;
        }
        match &self.body_map {
            Some(map) => map.get(name).copied(),
            None => self.bodies.iter().position(|b| &**b.name == name),
        }
    }

    /// Mass centre of a body (the origin for the ground).
    pub fn mass_centre(&self, body: Option<usize>) -> Vec3<S> {
        body.map_or(zero3(), |k| self.bodies[k].location)
    }

    /// The rows and geometry of a point item: translational directions first (`force 1…`),
    /// then rotational (`moment 1…`).
    pub fn point(
        &self,
        p: &Point<S>,
        kind: &'static str,
        name: &Name,
    ) -> (Rows<S>, PointGeometry<S>) {
        let b = [self.body(&p.bodies[0]), self.body(&p.bodies[1])];
        let r = [
            sub(&p.location, &self.mass_centre(b[0])),
            sub(&p.location, &self.mass_centre(b[1])),
        ];
        let f = directions(p.forces, &p.axis);
        let m = directions(p.moments, &p.axis);
        let rows = point_rows(b, &r, &f, &m);
        let mut labels = Vec::with_capacity(f.len() + m.len());
        for (part, n) in [("force", f.len()), ("moment", m.len())] {
            for k in 0..n {
                labels.push(RowLabel {
                    kind,
                    item: name.clone(),
                    part,
                    index: k + 1,
                });
            }
        }
        let geometry = PointGeometry {
            forces: f,
            moments: m,
            bodies: b,
            radii: r,
        };
        (Rows { rows, labels }, geometry)
    }

    /// The row and geometry of a line item: the elongation (twisted: the rotation about the
    /// line) of end 2 relative to end 1.
    pub fn line(&self, l: &Line<S>, kind: &'static str, name: &Name) -> (Rows<S>, LineGeometry<S>) {
        let b = [self.body(&l.bodies[0]), self.body(&l.bodies[1])];
        let t = sub(&l.ends[1], &l.ends[0]);
        let len = geometry::norm(&t);
        let u = if len.is_one() {
            t
        } else {
            scale(len.recip(), &t)
        };
        let r = [
            sub(&l.ends[0], &self.mass_centre(b[0])),
            sub(&l.ends[1], &self.mass_centre(b[1])),
        ];
        let rows = if l.twist {
            point_rows(b, &r, &[], std::slice::from_ref(&u))
        } else {
            point_rows(b, &r, std::slice::from_ref(&u), &[])
        };
        let labels = vec![RowLabel {
            kind,
            item: name.clone(),
            part: "",
            index: 0,
        }];
        let geometry = LineGeometry {
            unit: u,
            length: len,
            bodies: b,
            radii: r,
            twist: l.twist,
        };
        (Rows { rows, labels }, geometry)
    }

    fn term(&mut self, term: Term) -> &mut Triplets<S> {
        match term {
            Term::Mass => &mut self.mass,
            Term::ItemMass => &mut self.item_mass,
            Term::Stiffness => &mut self.stiffness,
            Term::Damping => &mut self.damping,
            Term::Momentum => &mut self.momentum,
            Term::Velocity => &mut self.velocity,
            Term::LoadStiffness => &mut self.load_stiffness,
        }
    }

    /// Add `v` at coordinates `(i, j)` of `term`.
    pub fn add(&mut self, term: Term, i: usize, j: usize, v: S) {
        self.term(term).push(i, j, v);
    }

    /// Add `sign · block` at rows `6·body + offset …` and columns likewise (nothing when either
    /// body is the ground).
    pub fn add_block(
        &mut self,
        term: Term,
        row: (Option<usize>, usize),
        col: (Option<usize>, usize),
        block: &Mat3<S>,
        sign: f64,
    ) {
        add_block(self.term(term), row, col, block, sign);
    }

    /// Add `Rᵀ P R` for an item's rows `R` and its property block `P` (one row and column per
    /// row of `R`; any square matrix, not necessarily symmetric).
    pub fn add_rows_block(&mut self, term: Term, rows: &[ItemRow<S>], props: &[Vec<S>]) {
        let m = self.term(term);
        for (a, ra) in rows.iter().enumerate() {
            for (b, rb) in rows.iter().enumerate() {
                let p = props[a][b];
                if p.is_zero() {
                    continue;
                }
                for &(i, x) in ra {
                    for &(j, y) in rb {
                        let v = if p.is_one() { x * y } else { p * x * y };
                        m.push(i, j, v);
                    }
                }
            }
        }
    }

    /// Add an applied generalized force `v` on coordinate `i`.
    pub fn add_applied(&mut self, i: usize, v: S) {
        self.applied[i] = self.applied[i] + v;
    }

    /// Add holonomic constraint rows (`J`); their multipliers are `reaction`.
    pub fn holonomic(
        &mut self,
        kind: &'static str,
        name: &Name,
        rows: Rows<S>,
        reaction: Reaction<'m, S>,
    ) {
        push_rows(&mut self.holonomic, kind, name, rows, reaction);
    }

    /// Add elastic rows (`H`) with their stiffness block (for the compatibility equations of
    /// an indeterminate structure); their multipliers are `reaction`. Returns the index of the
    /// first row.
    pub fn elastic(
        &mut self,
        kind: &'static str,
        name: &Name,
        rows: Rows<S>,
        stiffness: Vec<Vec<S>>,
        reaction: Reaction<'m, S>,
    ) -> usize {
        let start = self.elastic.rows.len();
        self.stiffness_blocks.push((start, stiffness));
        push_rows(&mut self.elastic, kind, name, rows, reaction);
        start
    }

    /// Add nonholonomic constraint rows (`N`, acting on the velocities).
    pub fn nonholonomic(&mut self, rows: Rows<S>) {
        self.nonholonomic.rows.extend(rows.rows);
        self.nonholonomic.labels.extend(rows.labels);
    }

    /// The multiplier of elastic row `row` (a spring's tension) is known: `preload`, with
    /// stiffness `stiffness`.
    pub fn known_preload(&mut self, row: usize, preload: S, stiffness: S) {
        self.known.push((row, preload, stiffness));
    }

    /// A new input (a column of `F_u`, `G_u`); returns its index.
    pub fn input(&mut self, name: &Name, units: &str) -> usize {
        self.signals
            .inputs
            .push((name.to_string(), units.to_string()));
        self.signals.inputs.len() - 1
    }

    /// The index of an input added before.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.signals.inputs.iter().position(|x| x.0 == name)
    }

    /// Add `v` to the input force matrix `F_u` at coordinate `i`, input `input`.
    pub fn add_input_force(&mut self, i: usize, input: usize, v: S) {
        self.signals.input_force.push((i, input, v));
    }

    /// Add `v` to the input rate force matrix `G_u` at coordinate `i`, input `input`.
    pub fn add_input_rate_force(&mut self, i: usize, input: usize, v: S) {
        self.signals.input_rate_force.push((i, input, v));
    }

    /// A new output (a row of `C_s`, `D_s`) measuring `kind`; returns its index.
    pub fn output(&mut self, name: &Name, units: &str, kind: OutputKind) -> usize {
        self.signals
            .outputs
            .push((name.to_string(), units.to_string()));
        self.signals.output_kinds.push(kind);
        self.signals.outputs.len() - 1
    }

    /// Add `v` to the sensor rows `C_s` at output `output`, coordinate `j`.
    pub fn add_output(&mut self, output: usize, j: usize, v: S) {
        self.signals.sensor_rows.push((output, j, v));
    }

    /// Add `v` to the feedthrough `D_s` at output `output`, input `input`.
    pub fn add_feedthrough(&mut self, output: usize, input: usize, v: S) {
        self.signals.feedthrough.push((output, input, v));
    }

    /// A new first-order lag state (an unsteady-aerodynamics state, say) called `name`;
    /// returns its index among the lag states. Its equation and its force on the bodies are
    /// added by [`Assembly::add_lag`].
    pub fn lag_state(&mut self, name: String) -> usize {
        self.lags.names.push(name);
        self.lags.names.len() - 1
    }

    /// Add `v` at `(i, j)` of the lag-state block `term` (indices: lag states from
    /// [`Assembly::lag_state`], coordinates `6·body + dof`).
    pub fn add_lag(&mut self, term: LagTerm, i: usize, j: usize, v: S) {
        let t = match term {
            LagTerm::Rate => &mut self.lags.rate,
            LagTerm::Position => &mut self.lags.position,
            LagTerm::Velocity => &mut self.lags.velocity,
            LagTerm::Force => &mut self.lags.force,
        };
        t.push((i, j, v));
    }

    /// Report a warning.
    pub fn warn(&mut self, warning: Warning) {
        self.warnings.push(warning);
    }
}

fn push_rows<'m, S>(
    set: &mut RowSet<'m, S>,
    kind: &'static str,
    name: &Name,
    rows: Rows<S>,
    reaction: Reaction<'m, S>,
) {
    set.reactions.push(Reacting {
        kind,
        name: name.clone(),
        rows: rows.rows.len(),
        reaction,
    });
    set.rows.extend(rows.rows);
    set.labels.extend(rows.labels);
}

/// Add `sign · block` at body blocks `row`, `col` of `m` (nothing when either is the ground).
pub(crate) fn add_block<S: Scalar>(
    m: &mut Triplets<S>,
    (bi, ri): (Option<usize>, usize),
    (bj, rj): (Option<usize>, usize),
    block: &Mat3<S>,
    sign: f64,
) {
    let (Some(bi), Some(bj)) = (bi, bj) else {
        return;
    };
    for (i, row) in block.iter().enumerate() {
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

/// Rows of a point item: translational directions `fdirs`, rotational `mdirs`, at radii
/// `r1`, `r2` from the mass centres of `b1`, `b2`: body 1 gets `[f, r₁ × f]`, body 2
/// `−[f, r₂ × f]`; rotations `[0, g]` and `−[0, g]`.
fn point_rows<S: Scalar>(
    b: [Option<usize>; 2],
    r: &[Vec3<S>; 2],
    fdirs: &[Vec3<S>],
    mdirs: &[Vec3<S>],
) -> Vec<ItemRow<S>> {
    let z = zero3::<S>();
    let mut out = Vec::with_capacity(fdirs.len() + mdirs.len());
    for f in fdirs {
        let mut row = ItemRow::new();
        row.push_body(b[0], f, &cross(&r[0], f), true);
        row.push_body(b[1], f, &cross(&r[1], f), false);
        out.push(row.sorted());
    }
    for g in mdirs {
        let mut row = ItemRow::new();
        row.push_body(b[0], &z, g, true);
        row.push_body(b[1], &z, g, false);
        out.push(row.sorted());
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
