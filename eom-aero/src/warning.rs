//! What the readers of AVL output files have to say about derivatives they cannot recover,
//! as data (docs/diagnostics.md lists the variants).

use std::fmt;

/// A derivative (a column or row of the body-axis matrix) that an AVL stability-axis (`.st`)
/// file does not determine, set to 0. `Display` gives the message.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum AeroWarning {
    /// The u column (CXu … Cnu): not in stability-axis files.
    UColumnMissing,
    /// The w column at α = 0 needs the trim totals (CXtot … Cntot), absent from the file.
    WColumnNeedsTotals,
    /// The w column at α ≠ 0: the file's α column mixes the u and w derivatives.
    WColumnMixed {
        /// The file's angle of attack, degrees.
        alpha_deg: f64,
    },
    /// The CX row needs the CD rows, absent from the file (AVL before 3.4x).
    CxRowNeedsDrag,
    /// The CZ row at α ≠ 0 needs the CD rows, absent from the file.
    CzRowNeedsDrag {
        /// The file's angle of attack, degrees.
        alpha_deg: f64,
    },
}

impl AeroWarning {
    /// The kind, as the CLI's JSON names it (`"st_u_column"`).
    pub fn kind(&self) -> &'static str {
        match self {
            AeroWarning::UColumnMissing => "st_u_column",
            AeroWarning::WColumnNeedsTotals => "st_w_column_totals",
            AeroWarning::WColumnMixed { .. } => "st_w_column_mixed",
            AeroWarning::CxRowNeedsDrag => "st_cx_row",
            AeroWarning::CzRowNeedsDrag { .. } => "st_cz_row",
        }
    }
}

impl fmt::Display for AeroWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AeroWarning::UColumnMissing => f.write_str(
                "the u column (CXu ... Cnu) is not in stability-axis (ST) files: set to 0; \
                 use an SB file for it",
            ),
            AeroWarning::WColumnNeedsTotals => f.write_str(
                "the w column needs the trim totals (CXtot ... Cntot), absent: set to 0",
            ),
            AeroWarning::WColumnMixed { alpha_deg } => write!(
                f,
                "the w column at alpha = {alpha_deg} deg mixes the u and w derivatives in ST \
                 files: set to 0; use an SB file for it"
            ),
            AeroWarning::CxRowNeedsDrag => f.write_str(
                "the CX row needs the CD rows (x force CD), absent in this ST file: set to 0",
            ),
            AeroWarning::CzRowNeedsDrag { alpha_deg } => write!(
                f,
                "the CZ row at alpha = {alpha_deg} deg needs the CD rows, absent: set to 0"
            ),
        }
    }
}

/// As its message (the form the JSON of a [`crate::BodyDerivatives`] has always had).
impl serde::Serialize for AeroWarning {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}
