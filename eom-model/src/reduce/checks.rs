//! The validity checks of a reduction and their labels: which pivot or rank decision each
//! guards, and the coordinate names they speak of.

use super::{PIVOT_TOLERANCE, RANK_TOLERANCE};
use crate::assemble::RowLabel;
use crate::eliminate::{PivotRecord, RankRecord, Rref};
use crate::error::ModelError;
use crate::geometry::Name;
use eom_sym::matrix::SparseMatrix;
use eom_sym::scalar::Scalar;

/// A coordinate or velocity of a body (formatted only when displayed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Coord {
    /// Body name.
    pub body: Name,
    /// 0..6: x, y, z, rx, ry, rz.
    pub dof: usize,
    /// The perturbation velocity (vx … wz) instead of the displacement.
    pub velocity: bool,
}

impl std::fmt::Display for Coord {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&coord_text(&self.body, self.dof, self.velocity))
    }
}

/// The text of a [`Coord`] (`body.x`, `body.vx`, …), built in one allocation: state names
/// are made on every reduction, and formatting machinery would grow the string piecewise.
pub(super) fn coord_text(body: &str, dof: usize, velocity: bool) -> String {
    let n = if velocity { VELO[dof] } else { COORD[dof] };
    let mut s = String::with_capacity(body.len() + 1 + n.len());
    s.push_str(body);
    s.push('.');
    s.push_str(n);
    s
}

/// What a validity check guards (formatted only when displayed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CheckLabel {
    /// A pivot of the position-constraint elimination.
    PositionPivot {
        /// The dependent coordinate.
        coord: Coord,
        /// The constraint row.
        row: RowLabel,
    },
    /// A position-constraint row declared redundant.
    PositionRank {
        /// The row.
        row: RowLabel,
    },
    /// A pivot of the velocity-constraint elimination.
    VelocityPivot {
        /// The dependent velocity.
        coord: Coord,
        /// The constraint row.
        row: RowLabel,
    },
    /// A velocity-constraint row declared redundant.
    VelocityRank {
        /// The row.
        row: RowLabel,
    },
    /// The right-hand side of a redundant velocity row must vanish.
    VelocityConsistency {
        /// The row.
        row: RowLabel,
    },
    /// A pivot of the reduced mass matrix.
    MassPivot {
        /// The eliminated velocity.
        state: Coord,
        /// The equation row.
        row: Coord,
    },
    /// A reduced-mass row declared singular.
    MassRank {
        /// The row.
        row: Coord,
    },
}

impl std::fmt::Display for CheckLabel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CheckLabel::PositionPivot { coord, row } => {
                write!(f, "pivot on {coord} in position constraint {row}")
            }
            CheckLabel::PositionRank { row } => {
                write!(f, "redundancy of position constraint {row}")
            }
            CheckLabel::VelocityPivot { coord, row } => write!(
                f,
                "pivot on the velocity of {coord} in velocity constraint {row}"
            ),
            CheckLabel::VelocityRank { row } => {
                write!(f, "redundancy of velocity constraint {row}")
            }
            CheckLabel::VelocityConsistency { row } => {
                write!(f, "consistency of redundant velocity constraint {row}")
            }
            CheckLabel::MassPivot { state, row } => {
                write!(f, "reduced mass pivot of {state} (row {row})")
            }
            CheckLabel::MassRank { row } => write!(f, "redundancy of reduced mass row {row}"),
        }
    }
}

/// One condition for a symbolic result to be valid at an evaluation point.
#[derive(Clone, Debug)]
pub enum ValidityCheck<S> {
    /// `|value| ≥ PIVOT_TOLERANCE · max(|value|, |row entries|)`.
    Pivot {
        /// What the pivot eliminates.
        what: CheckLabel,
        /// The pivot.
        value: S,
        /// The other entries of its row.
        row: Vec<S>,
    },
    /// `|value| ≤ RANK_TOLERANCE · max |scale entries|`.
    Negligible {
        /// Which rank decision.
        what: CheckLabel,
        /// The entry that must stay negligible.
        value: S,
        /// The entries that set its scale.
        scale: Vec<S>,
    },
}

impl<S: Scalar> ValidityCheck<S> {
    /// Description of the check.
    pub fn what(&self) -> String {
        self.label().to_string()
    }

    /// What the check guards.
    pub fn label(&self) -> &CheckLabel {
        match self {
            ValidityCheck::Pivot { what, .. } | ValidityCheck::Negligible { what, .. } => what,
        }
    }

    /// Test the check on numeric values (the check's expressions evaluated at a point).
    pub fn holds(value: f64, others: &[f64], pivot: bool) -> bool {
        let m = others.iter().fold(value.abs(), |a, b| a.max(b.abs()));
        if pivot {
            value.is_finite() && value.abs() >= PIVOT_TOLERANCE * m && m > 0.0
        } else {
            let s = others.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            value.abs() <= RANK_TOLERANCE * s || value == 0.0
        }
    }

    pub(super) fn holds_nominal(&self) -> bool {
        match self {
            ValidityCheck::Pivot { value, row, .. } => {
                let o: Vec<f64> = row.iter().map(|x| x.nominal()).collect();
                Self::holds(value.nominal(), &o, true)
            }
            ValidityCheck::Negligible { value, scale, .. } => {
                let o: Vec<f64> = scale.iter().map(|x| x.nominal()).collect();
                Self::holds(value.nominal(), &o, false)
            }
        }
    }
}

pub(super) const COORD: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

pub(super) const VELO: [&str; 6] = ["vx", "vy", "vz", "wx", "wy", "wz"];

pub(super) fn record_checks<S: Scalar>(
    r: &Rref<S>,
    pivot_label: &dyn Fn(usize, usize) -> CheckLabel,
    rank_label: &dyn Fn(usize) -> CheckLabel,
    out: &mut Vec<ValidityCheck<S>>,
) {
    for PivotRecord {
        row,
        col,
        value,
        row_entries,
    } in &r.pivot_records
    {
        if value.is_one()
            || (row_entries.is_empty() && value.nominal() != 0.0 && is_constant(value))
        {
            continue;
        }
        out.push(ValidityCheck::Pivot {
            what: pivot_label(*row, *col),
            value: *value,
            row: row_entries.clone(),
        });
    }
    for RankRecord {
        row,
        value,
        scale_entries,
    } in &r.rank_records
    {
        out.push(ValidityCheck::Negligible {
            what: rank_label(*row),
            value: *value,
            scale: scale_entries.clone(),
        });
    }
}

/// A scalar that cannot change with the parameters (for f64 every value; for expressions the
/// numeric constants). Constant pivots need no runtime check.
pub(super) fn is_constant<S: Scalar>(v: &S) -> bool {
    // A value equal to its own nominal for every type: numbers. For expressions the only way to
    // tell is through the f64 round trip of `from_f64(nominal) == v`.
    S::from_f64(v.nominal()) == *v
}

pub(super) fn rate_check<S: Scalar>(
    cg: &SparseMatrix<S>,
    output: &str,
    inputs: &[(String, String)],
) -> Result<(), ModelError> {
    if let Some((_, j, _)) = cg.iter().find(|(_, _, v)| v.nominal() != 0.0) {
        return Err(ModelError::InputRateInAcceleration {
            output: output.to_string(),
            input: inputs[j].0.clone(),
        });
    }
    Ok(())
}
