//! Body axes ↔ stability axes (AVL's ST form), at zero sideslip.
//!
//! The stability axes are the body axes turned by α about y. With c = cos α, s = sin α the
//! outputs are CL = −c·CZ + s·CX, CD = −c·CX − s·CZ, Cl' = c·Cl + s·Cn, Cn' = c·Cn − s·Cl
//! (CY, Cm unchanged), the columns are ∂/∂β = ∂/∂v̂, ∂/∂p' = c ∂/∂p̂ + s ∂/∂r̂,
//! ∂/∂r' = −s ∂/∂p̂ + c ∂/∂r̂, ∂/∂q' = ∂/∂q̂, and ∂/∂α = −s ∂/∂û + c ∂/∂ŵ at constant speed.
//! Because the stability axes turn with α, the α column also carries the derivative of the
//! axis rotation times the trim coefficients.

use crate::derivatives::{Derivatives, StabilityDerivatives};
use crate::warning::AeroWarning;

const U: usize = 0;
const V: usize = 1;
const W: usize = 2;
const P: usize = 3;
const Q: usize = 4;
const R: usize = 5;

/// Rows of the stability outputs (CL, CY, Cl', Cm, Cn', CD) as combinations of the body
/// outputs (CX, CY, CZ, Cl, Cm, Cn), and their α-derivative.
fn rotation(alpha: f64) -> ([[f64; 6]; 6], [[f64; 6]; 6]) {
    let (s, c) = alpha.sin_cos();
    let r = [
        [s, 0.0, -c, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, c, 0.0, s],
        [0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, -s, 0.0, c],
        [-c, 0.0, -s, 0.0, 0.0, 0.0],
    ];
    let dr = [
        [c, 0.0, s, 0.0, 0.0, 0.0],
        [0.0; 6],
        [0.0, 0.0, 0.0, -s, 0.0, c],
        [0.0; 6],
        [0.0, 0.0, 0.0, -c, 0.0, -s],
        [s, 0.0, -c, 0.0, 0.0, 0.0],
    ];
    (r, dr)
}

pub(crate) fn from_body(d: &Derivatives, alpha_deg: f64, totals: [f64; 6]) -> StabilityDerivatives {
    let alpha = alpha_deg.to_radians();
    let (s, c) = alpha.sin_cos();
    let (r, dr) = rotation(alpha);
    let b = &d.coefficients;
    // body-output derivatives w.r.t. α, β, p', q', r'
    let mut body_cols = [[0.0; 5]; 6];
    for (k, row) in b.iter().enumerate() {
        body_cols[k] = [
            -s * row[U] + c * row[W],
            row[V],
            c * row[P] + s * row[R],
            row[Q],
            -s * row[P] + c * row[R],
        ];
    }
    let mut out = [[0.0; 5]; 6];
    for i in 0..6 {
        for j in 0..5 {
            out[i][j] = (0..6).map(|k| r[i][k] * body_cols[k][j]).sum();
        }
        out[i][0] += (0..6).map(|k| dr[i][k] * totals[k]).sum::<f64>();
    }
    StabilityDerivatives {
        alpha_deg,
        reference: d.reference,
        coefficients: out,
    }
}

/// Body-axis derivatives recovered from stability-axis ones, as far as they determine them.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BodyDerivatives {
    /// The body-axis derivatives; entries that cannot be recovered are 0.
    pub derivatives: Derivatives,
    /// `known[i][j]` tells whether entry (i, j) was recovered.
    pub known: [[bool; 6]; 6],
    /// What could not be recovered, and why.
    pub warnings: Vec<AeroWarning>,
}

/// Inverts [`from_body`] where possible. `has_drag_rows` tells whether the CD row is real
/// (AVL 3.4x+ files) rather than absent; `totals` are the trim (CX, CY, CZ, Cl, Cm, Cn),
/// needed for the w column at α = 0.
pub(crate) fn to_body(
    st: &StabilityDerivatives,
    has_drag_rows: bool,
    totals: Option<[f64; 6]>,
) -> BodyDerivatives {
    let alpha = st.alpha_deg.to_radians();
    let (s, c) = alpha.sin_cos();
    let a = &st.coefficients;
    // stability rows → body rows: CX = s CL − c CD, CZ = −c CL − s CD, Cl = c Cl' − s Cn',
    // Cn = s Cl' + c Cn'
    let to_body_rows = |col: [f64; 6]| -> [f64; 6] {
        [
            s * col[0] - c * col[5],
            col[1],
            -c * col[0] - s * col[5],
            c * col[2] - s * col[4],
            col[3],
            s * col[2] + c * col[4],
        ]
    };
    let st_col = |j: usize| -> [f64; 6] { std::array::from_fn(|i| a[i][j]) };
    let mut b = [[0.0; 6]; 6];
    let mut set_col = |j: usize, v: [f64; 6]| (0..6).for_each(|i| b[i][j] = v[i]);
    let (cv, cp, cq, cr) = (st_col(1), st_col(2), st_col(3), st_col(4));
    set_col(V, to_body_rows(cv));
    set_col(Q, to_body_rows(cq));
    let pb: [f64; 6] = std::array::from_fn(|i| c * cp[i] - s * cr[i]);
    let rb: [f64; 6] = std::array::from_fn(|i| s * cp[i] + c * cr[i]);
    set_col(P, to_body_rows(pb));
    set_col(R, to_body_rows(rb));

    let mut known = [[true; 6]; 6];
    let mut warnings = vec![AeroWarning::UColumnMissing];
    (0..6).for_each(|i| known[i][U] = false);
    let alpha_zero = alpha.abs() < 1e-12;
    match (alpha_zero, totals) {
        (true, Some(t)) => {
            // at α = 0: ∂S/∂α = R ∂B/∂ŵ + R' T, so ∂B/∂ŵ = R⁻¹(∂S/∂α − R' T)
            let (_, dr) = rotation(0.0);
            let col: [f64; 6] =
                std::array::from_fn(|i| a[i][0] - (0..6).map(|k| dr[i][k] * t[k]).sum::<f64>());
            set_col(W, to_body_rows(col));
        }
        _ => {
            (0..6).for_each(|i| known[i][W] = false);
            warnings.push(if alpha_zero {
                AeroWarning::WColumnNeedsTotals
            } else {
                AeroWarning::WColumnMixed {
                    alpha_deg: st.alpha_deg,
                }
            });
        }
    }
    if !has_drag_rows {
        known[0] = [false; 6];
        warnings.push(AeroWarning::CxRowNeedsDrag);
        if !alpha_zero {
            known[2] = [false; 6];
            warnings.push(AeroWarning::CzRowNeedsDrag {
                alpha_deg: st.alpha_deg,
            });
        }
    }
    for i in 0..6 {
        for j in 0..6 {
            if !known[i][j] {
                b[i][j] = 0.0;
            }
        }
    }
    BodyDerivatives {
        derivatives: Derivatives {
            reference: st.reference,
            coefficients: b,
        },
        known,
        warnings,
    }
}
