//! `eval_discrete`: the zero-order-hold discretisation of the generated model at a sample time
//! h, `Ad = e^{A h}` and `Bd = ∫₀ʰ e^{A t} dt B`, both from the exponential of the augmented
//! matrix `[[A h, B h], [0, 0]]` (Van Loan 1978): scaling and squaring with the diagonal Padé
//! approximant of the degree the norm needs (Higham 2005, "The scaling and squaring method for
//! the matrix exponential revisited", SIAM J. Matrix Anal. Appl. 26:1179–1193, Table 2.3: the
//! θ_m below which the degree-m approximant is accurate to the unit roundoff), the linear
//! system by LU with partial pivoting. `no_std`, no allocation: the caller owns a
//! `DiscreteWork`.

use crate::options::Precision;

/// The θ_m and degrees m of Higham (2005), Table 2.3 (double: m = 3, 5, 7, 9, 13) and the
/// single-precision values of the same paper (m = 3, 5, 7).
fn thetas(prec: Precision) -> &'static [(usize, f64)] {
    match prec {
        Precision::F64 => &[
            (3, 1.495585217958292e-2),
            (5, 2.53939833006323e-1),
            (7, 9.504178996162932e-1),
            (9, 2.097847961257068e0),
            (13, 5.371920351148152e0),
        ],
        Precision::F32 => &[
            (3, 4.258730016922831e-1),
            (5, 1.880152677804762e0),
            (7, 3.92572478313866e0),
        ],
    }
}

/// The coefficients `b_j = (2m − j)! m! / ((2m)! j! (m − j)!)` of the degree-m Padé approximant
/// of `e^x` (numerator `Σ b_j x^j`, denominator `Σ b_j (−x)^j`).
fn pade(m: usize) -> Vec<f64> {
    let mut b = vec![1.0; m + 1];
    for j in 1..=m {
        b[j] = b[j - 1] * (m + 1 - j) as f64 / ((j * (2 * m + 1 - j)) as f64);
    }
    b
}

fn lit(x: f64) -> String {
    format!("{x:e} as Real")
}

/// The Rust source of the discretisation items (inside the generated module).
pub(crate) fn source(prec: Precision) -> String {
    let table = thetas(prec);
    let mut degree_table = String::new();
    for (m, theta) in table {
        let b = pade(*m);
        let coeffs: Vec<String> = b.iter().map(|c| lit(*c)).collect();
        degree_table.push_str(&format!(
            "    ({m}, {}, &[{}]),\n",
            lit(*theta),
            coeffs.join(", ")
        ));
    }
    TEMPLATE.replace("@DEGREES@", &degree_table)
}

const TEMPLATE: &str = r#"
/// Size of the augmented matrix `[[A h, B h], [0, 0]]` of [`eval_discrete`].
pub const N_AUG: usize = N_STATES + N_INPUTS;
const AUG_LEN: usize = N_AUG * N_AUG;

/// The Padé degrees m, the norms θ_m up to which each is accurate to the unit roundoff
/// (Higham 2005, Table 2.3), and the coefficients b_0..b_m.
const PADE: &[(usize, Real, &[Real])] = &[
@DEGREES@];

/// The workspace of [`eval_discrete`]: A, B and seven matrices of the augmented size, owned by
/// the caller (in a `static`, on the stack, in a struct), so that the evaluation allocates
/// nothing.
#[derive(Clone, Debug)]
pub struct DiscreteWork {
    a: [Real; A_LEN],
    b: [Real; B_LEN],
    work: [Real; WORK_LEN],
    m: [Real; AUG_LEN],
    m2: [Real; AUG_LEN],
    power: [Real; AUG_LEN],
    u: [Real; AUG_LEN],
    v: [Real; AUG_LEN],
    t: [Real; AUG_LEN],
    piv: [usize; N_AUG],
}

impl DiscreteWork {
    /// A zeroed workspace.
    pub const fn new() -> Self {
        DiscreteWork {
            a: [0.0; A_LEN],
            b: [0.0; B_LEN],
            work: [0.0; WORK_LEN],
            m: [0.0; AUG_LEN],
            m2: [0.0; AUG_LEN],
            power: [0.0; AUG_LEN],
            u: [0.0; AUG_LEN],
            v: [0.0; AUG_LEN],
            t: [0.0; AUG_LEN],
            piv: [0; N_AUG],
        }
    }
}

impl Default for DiscreteWork {
    fn default() -> Self {
        Self::new()
    }
}

/// `out = x · y` for augmented matrices (column-major).
fn aug_mul(x: &[Real; AUG_LEN], y: &[Real; AUG_LEN], out: &mut [Real; AUG_LEN]) {
    for j in 0..N_AUG {
        for i in 0..N_AUG {
            out[i + j * N_AUG] = 0.0;
        }
        for k in 0..N_AUG {
            let ykj = y[k + j * N_AUG];
            if ykj != 0.0 {
                for i in 0..N_AUG {
                    out[i + j * N_AUG] += x[i + k * N_AUG] * ykj;
                }
            }
        }
    }
}

/// The zero-order-hold discretisation at the sample time `h` (s) and the parameters `p`:
/// `ad = e^{A h}` (column-major `N_STATES × N_STATES`), `bd = ∫₀ʰ e^{A t} dt · B`
/// (`N_STATES × N_INPUTS`), so that `x[k+1] = ad x[k] + bd u[k]` for an input held constant
/// over each step. A and B come from [`eval_ab`], so a point outside the validity region is
/// [`Error::Validity`] as there; `h` not finite or negative is [`Error::SampleTime`]; a
/// non-finite result is [`Error::NonFinite`] (matrix `Ad` or `Bd`).
///
/// Scaling and squaring with the diagonal Padé approximant of the lowest degree whose bound
/// θ_m covers `‖[A h, B h]‖₁` (degree 13 after scaling by 2⁻ˢ beyond θ₁₃; f32 code stops at
/// degree 7), then `s` squarings.
pub fn eval_discrete(
    p: &[Real; N_PARAMS],
    h: Real,
    ad: &mut [Real; A_LEN],
    bd: &mut [Real; B_LEN],
    w: &mut DiscreteWork,
) -> Result<(), Error> {
    if !(h.is_finite() && h >= 0.0) {
        return Err(Error::SampleTime);
    }
    eval_ab(p, &mut w.a, &mut w.b, &mut w.work)?;
    let n = N_STATES;
    // M = [[A h, B h], [0, 0]] and its 1-norm.
    w.m = [0.0; AUG_LEN];
    for j in 0..n {
        for i in 0..n {
            w.m[i + j * N_AUG] = w.a[i + j * n] * h;
        }
    }
    for j in 0..N_INPUTS {
        for i in 0..n {
            w.m[i + (n + j) * N_AUG] = w.b[i + j * n] * h;
        }
    }
    let mut norm: Real = 0.0;
    for j in 0..N_AUG {
        let mut col: Real = 0.0;
        for i in 0..N_AUG {
            let x = w.m[i + j * N_AUG];
            col += if x < 0.0 { -x } else { x };
        }
        if col > norm {
            norm = col;
        }
    }
    if !norm.is_finite() {
        return Err(Error::NonFinite { matrix: Matrix::Ad, row: 0, col: 0 });
    }
    // The degree, and the scaling 2^-s beyond the largest θ.
    let (mut degree, mut theta, mut coeffs) = PADE[PADE.len() - 1];
    for &(m, t, c) in PADE {
        if norm <= t {
            (degree, theta, coeffs) = (m, t, c);
            break;
        }
    }
    let mut squarings = 0u32;
    let mut scaled = norm;
    while scaled > theta {
        scaled *= 0.5;
        squarings += 1;
    }
    if squarings > 0 {
        let mut f: Real = 1.0;
        for _ in 0..squarings {
            f *= 0.5;
        }
        for x in w.m.iter_mut() {
            *x *= f;
        }
    }
    // U = M Σ b_odd M^(k−1), V = Σ b_even M^k, with the powers of M² built as needed.
    aug_mul(&w.m, &w.m, &mut w.m2);
    w.u = [0.0; AUG_LEN];
    w.v = [0.0; AUG_LEN];
    w.power = [0.0; AUG_LEN];
    for i in 0..N_AUG {
        w.power[i + i * N_AUG] = 1.0;
    }
    let mut k = 0;
    while k <= degree {
        for idx in 0..AUG_LEN {
            w.v[idx] += coeffs[k] * w.power[idx];
            if k < degree {
                w.u[idx] += coeffs[k + 1] * w.power[idx];
            }
        }
        k += 2;
        if k <= degree {
            aug_mul(&w.power, &w.m2, &mut w.t);
            w.power = w.t;
        }
    }
    aug_mul(&w.m, &w.u, &mut w.t);
    // (V − U) E = (V + U): LU of V − U with partial pivoting in `power`, E into `m`.
    for idx in 0..AUG_LEN {
        let (v, u) = (w.v[idx], w.t[idx]);
        w.power[idx] = v - u;
        w.m[idx] = v + u;
    }
    for c in 0..N_AUG {
        let mut best = c;
        let mut big: Real = 0.0;
        for r in c..N_AUG {
            let x = w.power[r + c * N_AUG];
            let x = if x < 0.0 { -x } else { x };
            if x > big {
                big = x;
                best = r;
            }
        }
        w.piv[c] = best;
        if best != c {
            for j in 0..N_AUG {
                w.power.swap(c + j * N_AUG, best + j * N_AUG);
                w.m.swap(c + j * N_AUG, best + j * N_AUG);
            }
        }
        let d = w.power[c + c * N_AUG];
        if d == 0.0 {
            return Err(Error::NonFinite { matrix: Matrix::Ad, row: c as u16, col: c as u16 });
        }
        for r in c + 1..N_AUG {
            let f = w.power[r + c * N_AUG] / d;
            if f != 0.0 {
                for j in c..N_AUG {
                    w.power[r + j * N_AUG] -= f * w.power[c + j * N_AUG];
                }
                for j in 0..N_AUG {
                    w.m[r + j * N_AUG] -= f * w.m[c + j * N_AUG];
                }
            }
        }
    }
    for j in 0..N_AUG {
        for r in (0..N_AUG).rev() {
            let mut s = w.m[r + j * N_AUG];
            for k in r + 1..N_AUG {
                s -= w.power[r + k * N_AUG] * w.m[k + j * N_AUG];
            }
            w.m[r + j * N_AUG] = s / w.power[r + r * N_AUG];
        }
    }
    for _ in 0..squarings {
        aug_mul(&w.m, &w.m, &mut w.t);
        w.m = w.t;
    }
    for j in 0..n {
        for i in 0..n {
            let x = w.m[i + j * N_AUG];
            if !x.is_finite() {
                return Err(Error::NonFinite { matrix: Matrix::Ad, row: i as u16, col: j as u16 });
            }
            ad[i + j * n] = x;
        }
    }
    for j in 0..N_INPUTS {
        for i in 0..n {
            let x = w.m[i + (n + j) * N_AUG];
            if !x.is_finite() {
                return Err(Error::NonFinite { matrix: Matrix::Bd, row: i as u16, col: j as u16 });
            }
            bd[i + j * n] = x;
        }
    }
    Ok(())
}
"#;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pade_coefficients_of_degree_3() {
        // 1, 1/2, 1/10, 1/120 (Higham 2005, the numerator of r₃).
        let b = pade(3);
        let want = [1.0, 0.5, 0.1, 1.0 / 120.0];
        for (x, y) in b.iter().zip(want) {
            assert!((x - y).abs() < 1e-16, "{b:?}");
        }
    }
}
