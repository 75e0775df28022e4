//! The additive decomposition `G = G_kept + G_stable`: the modes a reduction must keep whole
//! (structural zeros, other zero, marginal and unstable modes) split off from the stable part
//! by a change of coordinates `x = T v`, `v = [v_kept; v_stable]`, that makes A block diagonal.
//!
//! 1. The structural zeros (states on which nothing depends, pairs that act only through their
//!    difference: [`crate::deflate`]) by the exact integer changes of coordinates that make
//!    their columns zero. Ordered in the order they were found, they form a strictly upper
//!    triangular block: their eigenvalues stay exactly zero in the reduced model.
//! 2. The remaining block, balanced, in real Schur form, reordered so that the eigenvalues
//!    [`crate::modes::Modes`] calls zero, marginal or unstable come first.
//! 3. The coupling of the two diagonal blocks removed by the Sylvester equation
//!    `A_kept X − X A_stable = −A_coupling` (Bartels–Stewart), whose solution is bounded as
//!    long as the two spectra are apart: its norm is reported.

use nalgebra::DMatrix;

use super::schur::{RealSchur, blocks, eigenvalues};
use super::sylvester;
use crate::NumError;
use crate::deflate::{Combine, combine_columns, deflate_in_place};
use crate::linalg::balance_in_place;
use crate::modes::{ModeOptions, Modes, Stability};
use crate::statespace::StateSpace;

/// The system in the split coordinates.
#[derive(Clone, Debug)]
pub(crate) struct Split {
    /// `x = to_x · v` (n × n).
    pub to_x: DMatrix<f64>,
    /// `v = from_x · x` (n × n), the inverse of `to_x`.
    pub from_x: DMatrix<f64>,
    /// The kept part (structural zeros first): A, B, C.
    pub a_u: DMatrix<f64>,
    pub b_u: DMatrix<f64>,
    pub c_u: DMatrix<f64>,
    /// The stable part, A in real Schur form.
    pub a_s: DMatrix<f64>,
    pub b_s: DMatrix<f64>,
    pub c_s: DMatrix<f64>,
    /// States of the kept part that are structural zeros.
    pub structural: usize,
    /// Names of the kept states: the original state of each structural zero, then `kept k`.
    pub kept_names: Vec<String>,
    /// ‖X‖_F of the decoupling Sylvester equation (large: the spectra nearly touch).
    pub coupling: f64,
    /// Whether the Sylvester equation was singular to working precision.
    pub coupling_singular: bool,
}

impl Split {
    pub(crate) fn kept(&self) -> usize {
        self.a_u.nrows()
    }
}

/// `T` of the structural changes of coordinates (`x = T x̃`) and its inverse.
fn structural_transforms(combos: &[Combine], n: usize) -> (DMatrix<f64>, DMatrix<f64>) {
    let mut t = DMatrix::identity(n, n);
    combine_columns(combos, &mut t);
    // T⁻¹: for each change in order, row j gains s·row i (as T⁻¹B is formed).
    let mut ti = DMatrix::identity(n, n);
    for k in combos {
        for col in 0..n {
            ti[(k.j, col)] += k.s * ti[(k.i, col)];
        }
    }
    (t, ti)
}

/// Splits `ss` (validated by the caller).
pub(crate) fn split(ss: &StateSpace<f64>) -> Result<Split, NumError> {
    let n = ss.states();
    // 1. Structural zeros.
    let mut at = ss.a.clone();
    let (mut removed, mut order, mut combos, mut keys) = (vec![false; n], vec![], vec![], vec![]);
    deflate_in_place(
        at.as_mut_slice(),
        n,
        &mut removed,
        &mut order,
        &mut combos,
        &mut keys,
    );
    let (t, ti) = structural_transforms(&combos, n);
    let nr = order.len();
    let kept_idx: Vec<usize> = (0..n).filter(|i| !removed[*i]).collect();
    let nk = kept_idx.len();

    // How many of the rest to keep whole: the modes' own classification.
    let modes = Modes::compute_with(
        ss,
        &ModeOptions {
            shapes: false,
            ..ModeOptions::default()
        },
    )?;
    let not_stable = modes
        .modes
        .iter()
        .filter(|m| m.stability != Stability::Stable)
        .count();
    let keep_more = not_stable.saturating_sub(nr);

    // 2. The rest: balanced, Schur, reordered.
    let mut akk = DMatrix::from_fn(nk, nk, |i, j| at[(kept_idx[i], kept_idx[j])]);
    let mut scale = vec![1.0; nk];
    balance_in_place(akk.as_mut_slice(), nk, &mut scale);
    let mut schur = RealSchur::new(&akk)?;
    let mut ev = eigenvalues(&schur.t);
    ev.sort_by(|a, b| b.re.total_cmp(&a.re));
    let n1 = if keep_more == 0 || nk == 0 {
        0
    } else {
        let threshold = ev[keep_more.min(nk) - 1].re;
        schur.reorder(|z| z.re >= threshold)?
    };

    // G = T Pᵀ blkdiag(I, D Z): the columns of the structural states, then D Z embedded.
    let mut g = DMatrix::zeros(n, n);
    for (k, &r) in order.iter().enumerate() {
        g.set_column(k, &t.column(r));
    }
    let dz = DMatrix::from_fn(nk, nk, |i, j| scale[i] * schur.z[(i, j)]);
    let mut embed = DMatrix::zeros(n, nk);
    for (i, &r) in kept_idx.iter().enumerate() {
        embed.set_row(r, &dz.row(i));
    }
    g.view_mut((0, nr), (n, nk)).copy_from(&(&t * embed));
    // G⁻¹ = blkdiag(I, Zᵀ D⁻¹) P T⁻¹.
    let mut gi = DMatrix::zeros(n, n);
    for (k, &r) in order.iter().enumerate() {
        gi.set_row(k, &ti.row(r));
    }
    let tk = DMatrix::from_fn(nk, n, |i, j| ti[(kept_idx[i], j)] / scale[i]);
    gi.view_mut((nr, 0), (nk, n))
        .copy_from(&(schur.z.transpose() * tk));

    // The upper block triangular matrix in w = G⁻¹ x.
    let mut aw = DMatrix::zeros(n, n);
    for (a, &ra) in order.iter().enumerate() {
        for (b, &rb) in order.iter().enumerate() {
            aw[(a, b)] = at[(ra, rb)];
        }
    }
    let ark = DMatrix::from_fn(nr, nk, |a, j| at[(order[a], kept_idx[j])]);
    aw.view_mut((0, nr), (nr, nk)).copy_from(&(ark * &dz));
    aw.view_mut((nr, nr), (nk, nk)).copy_from(&schur.t);

    // 3. Decoupling: U X − X T₂₂ = −Y.
    let nu = nr + n1;
    let ns = n - nu;
    let u = aw.view((0, 0), (nu, nu)).clone_owned();
    let y = aw.view((0, nu), (nu, ns)).clone_owned();
    let t22 = aw.view((nu, nu), (ns, ns)).clone_owned();
    let (x, singular) = sylvester::solve(&u, &blocks(&u), &t22, &blocks(&t22), &(-y));
    let mut to_x = g.clone();
    let gu = g.view((0, 0), (n, nu)).clone_owned();
    let shift = gu * &x;
    let mut right = to_x.view_mut((0, nu), (n, ns));
    right += shift;
    let mut from_x = gi.clone();
    let shift = &x * gi.view((nu, 0), (ns, n));
    let mut top = from_x.view_mut((0, 0), (nu, n));
    top -= shift;

    let b = &from_x * &ss.b;
    let c = &ss.c * &to_x;
    let mut kept_names: Vec<String> = order
        .iter()
        .map(|&r| {
            ss.names
                .states
                .get(r)
                .cloned()
                .unwrap_or_else(|| format!("x{}", r + 1))
        })
        .collect();
    kept_names.extend((1..=n1).map(|k| format!("kept {k}")));
    Ok(Split {
        a_u: u,
        b_u: b.rows(0, nu).clone_owned(),
        c_u: c.columns(0, nu).clone_owned(),
        a_s: t22,
        b_s: b.rows(nu, ns).clone_owned(),
        c_s: c.columns(nu, ns).clone_owned(),
        structural: nr,
        kept_names,
        coupling: x.norm(),
        coupling_singular: singular,
        to_x,
        from_x,
    })
}
