//! The body-axis derivatives of a wing file, whatever its kind: an AVL geometry (`.avl`,
//! solved by the vortex lattice) or AVL's own output (`.sb` body axes, `.st` stability axes,
//! read). One entry point for `eom aero` and the Python package's `eom.aero`.

use crate::{AeroError, AvlOutput, AvlOutputKind, Derivatives, Result, SolverOptions};
use std::path::Path;

/// What a wing file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WingFileKind {
    /// An AVL geometry (`.avl`), solved by the vortex lattice.
    Geometry,
    /// AVL's body-axis derivatives (`.sb`).
    BodyAxes,
    /// AVL's stability-axis derivatives (`.st`), rotated to body axes.
    StabilityAxes,
}

impl WingFileKind {
    /// How `eom aero` names it: `geometry (vortex lattice)`, `body-axis derivatives (SB)`,
    /// `stability-axis derivatives (ST)`.
    pub fn description(self) -> &'static str {
        match self {
            WingFileKind::Geometry => "geometry (vortex lattice)",
            WingFileKind::BodyAxes => "body-axis derivatives (SB)",
            WingFileKind::StabilityAxes => "stability-axis derivatives (ST)",
        }
    }

    /// The kind of a file by its extension (case-insensitive), `None` for another one.
    pub fn of_path(path: &Path) -> Option<WingFileKind> {
        let ext = path.extension()?.to_str()?.to_lowercase();
        match ext.as_str() {
            "avl" => Some(WingFileKind::Geometry),
            "sb" => Some(WingFileKind::BodyAxes),
            "st" => Some(WingFileKind::StabilityAxes),
            _ => None,
        }
    }
}

/// The derivatives of a wing file.
#[derive(Clone, Debug, PartialEq)]
pub struct WingFileDerivatives {
    /// What the file holds.
    pub kind: WingFileKind,
    /// The body-axis derivatives (AVL's standard axes) with the reference quantities.
    pub derivatives: Derivatives,
    /// Angle of attack of the trim state, degrees.
    pub alpha_deg: f64,
    /// The AVL names of the entries an `.st` file cannot give (reported as 0).
    pub unknown: Vec<&'static str>,
    /// What the reader had to say.
    pub warnings: Vec<crate::AeroWarning>,
}

/// Reads or solves the wing file at `path`. `alpha_deg` (default 0) and `reference` (the
/// moment reference point in AVL geometry axes; default the file's) apply to an `.avl`
/// geometry only: given for an `.sb`/`.st` file they are an [`AeroError::Option`] error, since
/// such a file holds the derivatives of one run case about one point. Another extension is
/// an [`AeroError::FileKind`] error. An `.sb`/`.st` file's kind is what its text says.
pub fn read_wing_file(
    path: &str,
    alpha_deg: Option<f64>,
    reference: Option<[f64; 3]>,
) -> Result<WingFileDerivatives> {
    let Some(kind) = WingFileKind::of_path(Path::new(path)) else {
        return Err(AeroError::FileKind {
            file: path.to_string(),
        });
    };
    if kind == WingFileKind::Geometry {
        let mut config = crate::read_avl(path)?;
        if let Some(p) = reference {
            config.reference.point = p;
        }
        let opts = SolverOptions {
            alpha_deg: alpha_deg.unwrap_or(0.0),
            ..SolverOptions::default()
        };
        let sol = crate::solve(&config, &opts)?;
        return Ok(WingFileDerivatives {
            kind,
            derivatives: sol.derivatives,
            alpha_deg: sol.alpha_deg,
            unknown: Vec::new(),
            warnings: Vec::new(),
        });
    }
    for (given, option) in [
        (alpha_deg.is_some(), "alpha"),
        (reference.is_some(), "reference point"),
    ] {
        if given {
            return Err(AeroError::Option {
                option,
                reason: format!(
                    "applies to an AVL geometry (.avl) only: {path} is an AVL output file, \
                     which holds the derivatives of one run case about one point"
                ),
            });
        }
    }
    let out = AvlOutput::read(path)?;
    let body = out.derivatives()?;
    let names = Derivatives::names();
    let unknown = (0..36)
        .filter(|k| !body.known[k / 6][k % 6])
        .map(|k| names[k / 6][k % 6])
        .collect();
    Ok(WingFileDerivatives {
        kind: match out.kind {
            AvlOutputKind::Body => WingFileKind::BodyAxes,
            AvlOutputKind::Stability => WingFileKind::StabilityAxes,
        },
        derivatives: body.derivatives,
        alpha_deg: out.alpha_deg,
        unknown,
        warnings: body.warnings,
    })
}
