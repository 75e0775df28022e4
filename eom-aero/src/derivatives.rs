//! Non-dimensional stability derivatives in AVL's naming and normalisation, and their
//! dimensional form.

use crate::error::AeroError;
use serde::Serialize;

/// Reference quantities of the non-dimensional coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reference {
    /// Reference area S.
    pub sref: f64,
    /// Reference chord c (pitching moment and pitch rate q·c/2V).
    pub cref: f64,
    /// Reference span b (rolling and yawing moments, rates p·b/2V, r·b/2V).
    pub bref: f64,
    /// Moment reference point (AVL's Xref, Yref, Zref, in geometry axes: x aft, y right,
    /// z up).
    pub point: [f64; 3],
}

impl Reference {
    /// Reference area, chord, span and point.
    pub fn new(sref: f64, cref: f64, bref: f64, point: [f64; 3]) -> Self {
        Reference {
            sref,
            cref,
            bref,
            point,
        }
    }

    /// The rules every source of derivatives obeys (a geometry, an SB or ST file): Sref,
    /// Cref and Bref finite and positive, the point finite. `Err((field, why))`.
    pub fn check(&self) -> std::result::Result<(), (&'static str, String)> {
        for (field, v) in [
            ("Sref", self.sref),
            ("Cref", self.cref),
            ("Bref", self.bref),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err((field, format!("must be positive, is {v}")));
            }
        }
        if !self.point.iter().all(|x| x.is_finite()) {
            return Err((
                "Xref/Yref/Zref",
                format!("must be finite, is {:?}", self.point),
            ));
        }
        Ok(())
    }

    /// Row scales of the coefficients: forces by q·S, roll and yaw by q·S·b, pitch by q·S·c
    /// (the factor after q·S).
    pub(crate) fn row_lengths(&self) -> [f64; 6] {
        [1.0, 1.0, 1.0, self.bref, self.cref, self.bref]
    }

    /// Column lengths: the normalised state is x̂_j = x_j · len_j / V with len = 1 for the
    /// velocities and b/2, c/2, b/2 for the rates.
    pub(crate) fn column_lengths(&self) -> [f64; 6] {
        [
            1.0,
            1.0,
            1.0,
            0.5 * self.bref,
            0.5 * self.cref,
            0.5 * self.bref,
        ]
    }
}

/// A number for a message: plain where that is short, else in exponent form (`1e308`).
fn short(x: f64) -> String {
    if x == 0.0 || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Row names (AVL): forces CX, CY, CZ and moments Cl, Cm, Cn.
pub const ROWS: [&str; 6] = ["CX", "CY", "CZ", "Cl", "Cm", "Cn"];
/// Column names (AVL): velocities u, v, w and rates p, q, r.
pub const COLUMNS: [&str; 6] = ["u", "v", "w", "p", "q", "r"];

const NAMES: [[&str; 6]; 6] = [
    ["CXu", "CXv", "CXw", "CXp", "CXq", "CXr"],
    ["CYu", "CYv", "CYw", "CYp", "CYq", "CYr"],
    ["CZu", "CZv", "CZw", "CZp", "CZq", "CZr"],
    ["Clu", "Clv", "Clw", "Clp", "Clq", "Clr"],
    ["Cmu", "Cmv", "Cmw", "Cmp", "Cmq", "Cmr"],
    ["Cnu", "Cnv", "Cnw", "Cnp", "Cnq", "Cnr"],
];

/// Body-axis derivatives in AVL's standard axes (x forward, y right, z down).
///
/// The normalised state is x̂ = (u/V, v/V, w/V, p·b/2V, q·c/2V, r·b/2V) and the coefficients
/// are CX, CY, CZ = force/(q S), Cl, Cn = moment/(q S b), Cm = moment/(q S c), about the
/// reference point, q = ½ρV². This is exactly the layout of AVL's SB ("Geometry-axis
/// derivatives") table and of the EoM wing matrix.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Derivatives {
    /// Reference quantities of the normalisation.
    pub reference: Reference,
    /// `coefficients[i][j]` = ∂C_i/∂x̂_j; rows CX, CY, CZ, Cl, Cm, Cn; columns û, v̂, ŵ, p̂, q̂, r̂.
    pub coefficients: [[f64; 6]; 6],
}

impl Derivatives {
    /// The AVL name of each entry: `names()[i][j]` is e.g. `"CYr"` for i = 1, j = 5.
    pub fn names() -> [[&'static str; 6]; 6] {
        NAMES
    }

    /// The row and column of an AVL derivative name (`"CXu"` … `"Cnr"`), case-sensitive
    /// because AVL's CL (lift) and Cl (roll) differ only in case.
    pub fn index_of(name: &str) -> Option<(usize, usize)> {
        NAMES
            .iter()
            .enumerate()
            .find_map(|(i, row)| row.iter().position(|&n| n == name).map(|j| (i, j)))
    }

    /// The value of an AVL-named derivative, e.g. `get("Cnr")`.
    pub fn get(&self, name: &str) -> Option<f64> {
        Derivatives::index_of(name).map(|(i, j)| self.coefficients[i][j])
    }

    /// ∂F/∂x in SI: F = (X, Y, Z, L, M, N) [N, N·m] about the reference point,
    /// x = (u, v, w, p, q, r) [m/s, rad/s], same axes; = (qS/V)·build_mtx with q = ½ρV²
    /// (so −L of the EoM convention is this matrix).
    ///
    /// Errors: [`AeroError::OutOfRange`] for a density or airspeed that is not a positive
    /// number, and for an entry that overflows (`rho = 1e308`, a derivative of −1e308).
    pub fn dimensional(&self, rho: f64, speed: f64) -> crate::Result<[[f64; 6]; 6]> {
        for (what, v) in [("the air density", rho), ("the airspeed", speed)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(AeroError::OutOfRange {
                    what: what.into(),
                    reason: format!("must be a positive number, is {v}"),
                });
            }
        }
        // q·S/V = ρ·V·S/2, without forming V² (which overflows long before the result).
        let q_s_per_v = 0.5 * rho * speed * self.reference.sref;
        if !q_s_per_v.is_finite() {
            return Err(AeroError::OutOfRange {
                what: "the dimensional derivatives".into(),
                reason: format!(
                    "ρ·V·S/2 overflows with ρ = {}, V = {}, S = {}",
                    short(rho),
                    short(speed),
                    short(self.reference.sref)
                ),
            });
        }
        let rows = self.reference.row_lengths();
        let cols = self.reference.column_lengths();
        let mut d = [[0.0; 6]; 6];
        for i in 0..6 {
            for j in 0..6 {
                d[i][j] = q_s_per_v * rows[i] * cols[j] * self.coefficients[i][j];
                if !d[i][j].is_finite() {
                    return Err(AeroError::OutOfRange {
                        what: format!("the dimensional derivative of {}", NAMES[i][j]),
                        reason: format!(
                            "{} = {} times ρ·V·S/2 = {} (ρ = {}, V = {}, S = {}) and the \
                             reference lengths overflows",
                            NAMES[i][j],
                            short(self.coefficients[i][j]),
                            short(q_s_per_v),
                            short(rho),
                            short(speed),
                            short(self.reference.sref)
                        ),
                    });
                }
            }
        }
        Ok(d)
    }

    /// The derivatives in the stability-axis form of AVL's ST file at angle of attack
    /// `alpha_deg` and zero sideslip, given the trim force and moment coefficients
    /// `totals` = (CX, CY, CZ, Cl, Cm, Cn) in the same body axes (needed because the
    /// stability axes turn with α).
    pub fn to_stability_axes(&self, alpha_deg: f64, totals: [f64; 6]) -> StabilityDerivatives {
        crate::stability::from_body(self, alpha_deg, totals)
    }
}

/// Stability-axis derivatives as in AVL's ST file, at zero sideslip.
///
/// Rows CL (lift), CY, Cl' (roll about the stability x axis), Cm, Cn' (yaw about the
/// stability z axis), CD (drag); columns α, β (per radian), p'·b/2V, q·c/2V, r'·b/2V with
/// p', r' the stability-axis rates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StabilityDerivatives {
    /// Angle of attack of the stability axes, degrees.
    pub alpha_deg: f64,
    /// Reference quantities.
    pub reference: Reference,
    /// `coefficients[i][j]`: rows CL, CY, Cl', Cm, Cn', CD; columns α, β, p', q', r'.
    pub coefficients: [[f64; 5]; 6],
}

const ST_NAMES: [[&str; 5]; 6] = [
    ["CLa", "CLb", "CLp", "CLq", "CLr"],
    ["CYa", "CYb", "CYp", "CYq", "CYr"],
    ["Cla", "Clb", "Clp", "Clq", "Clr"],
    ["Cma", "Cmb", "Cmp", "Cmq", "Cmr"],
    ["Cna", "Cnb", "Cnp", "Cnq", "Cnr"],
    ["CDa", "CDb", "CDp", "CDq", "CDr"],
];

impl StabilityDerivatives {
    /// The names AVL prints for each entry (its ST file drops the primes of Cl', Cn' and
    /// of p', r' in the names).
    pub fn names() -> [[&'static str; 5]; 6] {
        ST_NAMES
    }

    /// The value of an ST-named derivative, e.g. `get("CLa")`.
    pub fn get(&self, name: &str) -> Option<f64> {
        ST_NAMES.iter().enumerate().find_map(|(i, row)| {
            row.iter()
                .position(|&n| n == name)
                .map(|j| self.coefficients[i][j])
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_36_distinct_and_indexed() {
        let mut all: Vec<_> = NAMES.iter().flatten().collect();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), 36);
        assert_eq!(Derivatives::index_of("CYr"), Some((1, 5)));
        assert_eq!(Derivatives::index_of("cyr"), None);
    }
}
