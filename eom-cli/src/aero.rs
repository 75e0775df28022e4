//! `eom aero FILE`: the body-axis stability derivatives of a wing (AVL names, AVL's standard
//! axes x forward, y right, z down) and their dimensional 6×6, from an AVL geometry (`.avl`,
//! by eom-aero's vortex lattice) or from AVL's own output (`.sb` body axes, `.st` stability
//! axes).

use crate::analyze::SIG;
use crate::error::CliError;
use crate::format::{g, table};
use crate::shown_warning::ShownWarning;
use eom_aero::{Derivatives, WingFileKind};
use serde::{Serialize, Serializer};
use std::path::Path;

/// What `eom aero` was asked.
#[derive(Clone, Debug, PartialEq)]
pub struct AeroRequest {
    /// Angle of attack of the trim state (degrees; `.avl` files only).
    pub alpha_deg: Option<f64>,
    /// Moment reference point (AVL geometry axes; `.avl` files only).
    pub reference: Option<[f64; 3]>,
    /// Air density for the dimensional matrix.
    pub density: f64,
    /// Airspeed for the dimensional matrix.
    pub speed: f64,
}

/// The report, serialized as the JSON output.
#[derive(Clone, Debug, Serialize)]
pub struct AeroReport {
    /// The file as given.
    pub file: String,
    /// `geometry (vortex lattice)`, `body-axis derivatives (SB)` or `stability-axis
    /// derivatives (ST)`.
    pub source: &'static str,
    /// Sref, Cref, Bref and the moment reference point (AVL geometry axes).
    pub reference: eom_aero::Reference,
    /// Angle of attack, degrees.
    pub alpha_deg: f64,
    /// The 36 derivatives by AVL name, in the order CXu … Cnr.
    #[serde(serialize_with = "ordered_map")]
    pub derivatives: Vec<(String, f64)>,
    /// Entries an ST file cannot give (reported as 0).
    pub unknown: Vec<String>,
    /// Air density and airspeed of the dimensional matrix.
    pub density: f64,
    /// Airspeed.
    pub speed: f64,
    /// ∂F/∂x in SI (= (ρVS/2)·M; the wing item's damping is its negative), AVL's standard
    /// axes: rows X, Y, Z, L, M, N; columns u, v, w, p, q, r.
    pub dimensional: [[f64; 6]; 6],
    /// What the reader or solver had to say (JSON: objects with `kind`, `item` and `message`).
    pub warnings: Vec<ShownWarning>,
}

fn ordered_map<S: Serializer>(v: &[(String, f64)], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(v.iter().map(|(k, x)| (k, x)))
}

fn bad(argument: String, problem: &str) -> CliError {
    CliError::BadArgument {
        argument,
        problem: problem.into(),
    }
}

/// Runs `eom aero`.
pub fn aero(file: &str, req: &AeroRequest) -> Result<AeroReport, CliError> {
    for (name, v) in [("--rho", req.density), ("--speed", req.speed)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(bad(format!("{name} {v}"), "must be a positive number"));
        }
    }
    // The CLI's own wording for the options that do not apply (named as the user typed them).
    let kind = WingFileKind::of_path(Path::new(file)).ok_or_else(|| {
        bad(
            file.into(),
            "expected an AVL geometry (.avl) or an AVL derivative file (.sb, .st)",
        )
    })?;
    if kind != WingFileKind::Geometry {
        for (given, opt) in [
            (req.alpha_deg.is_some(), "--alpha"),
            (req.reference.is_some(), "--ref"),
        ] {
            if given {
                return Err(bad(
                    opt.into(),
                    "applies to an AVL geometry (.avl) only: an AVL output file holds the \
                     derivatives of one run case about one point",
                ));
            }
        }
    }
    let w = eom_aero::read_wing_file(file, req.alpha_deg, req.reference)?;
    let d = w.derivatives;
    let names = Derivatives::names();
    Ok(AeroReport {
        file: file.to_string(),
        source: w.kind.description(),
        reference: d.reference,
        alpha_deg: w.alpha_deg,
        derivatives: (0..36)
            .map(|k| {
                (
                    names[k / 6][k % 6].to_string(),
                    d.coefficients[k / 6][k % 6],
                )
            })
            .collect(),
        unknown: w.unknown.iter().map(|n| n.to_string()).collect(),
        density: req.density,
        speed: req.speed,
        dimensional: d.dimensional(req.density, req.speed)?,
        warnings: w
            .warnings
            .into_iter()
            .map(|w| ShownWarning::new(w.kind(), w.to_string()))
            .collect(),
    })
}

/// Parses `--ref X,Y,Z`.
pub fn parse_reference(text: &str) -> Result<[f64; 3], CliError> {
    let v: Vec<f64> = text
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad(format!("--ref {text}"), "expected X,Y,Z (three numbers)"))?;
    match v[..] {
        [x, y, z] if v.iter().all(|x| x.is_finite()) => Ok([x, y, z]),
        _ => Err(bad(
            format!("--ref {text}"),
            "expected X,Y,Z (three finite numbers, AVL geometry axes)",
        )),
    }
}

impl AeroReport {
    /// The human-readable report.
    pub fn to_text(&self) -> String {
        let r = &self.reference;
        let mut t = format!(
            "{}: {}, alpha = {} deg\nReference: Sref = {}, Cref = {}, Bref = {}, point ({}, {}, {}) \
             (AVL geometry axes: x aft, y right, z up)\n\n",
            self.file,
            self.source,
            g(self.alpha_deg, SIG),
            g(r.sref, SIG),
            g(r.cref, SIG),
            g(r.bref, SIG),
            g(r.point[0], SIG),
            g(r.point[1], SIG),
            g(r.point[2], SIG),
        );
        t.push_str(
            "Body-axis derivatives (AVL's standard axes: x forward, y right, z down; columns per \
             u/V, v/V, w/V, pb/2V, qc/2V, rb/2V)\n",
        );
        let rows: Vec<Vec<String>> = self
            .derivatives
            .chunks(6)
            .map(|row| {
                row.iter()
                    .map(|(n, v)| {
                        if self.unknown.contains(n) {
                            format!("{n} = ?")
                        } else {
                            format!("{n} = {}", g(*v, SIG))
                        }
                    })
                    .collect()
            })
            .collect();
        t.push_str(&table(&["u", "v", "w", "p", "q", "r"], &rows, 2));
        if !self.unknown.is_empty() {
            t.push_str("  ? : not given by a stability-axis file (taken as 0)\n");
        }
        t.push_str(&format!(
            "\nDimensional dF/dx at rho = {} kg/m^3, V = {} m/s (AVL's standard axes; a wing's \
             damping L is its negative)\n",
            g(self.density, SIG),
            g(self.speed, SIG)
        ));
        let rows: Vec<Vec<String>> = self
            .dimensional
            .iter()
            .zip(["X [N]", "Y [N]", "Z [N]", "L [N m]", "M [N m]", "N [N m]"])
            .map(|(r, n)| {
                std::iter::once(n.to_string())
                    .chain(r.iter().map(|x| g(*x, SIG)))
                    .collect()
            })
            .collect();
        t.push_str(&table(
            &[
                "",
                "u [m/s]",
                "v [m/s]",
                "w [m/s]",
                "p [rad/s]",
                "q [rad/s]",
                "r [rad/s]",
            ],
            &rows,
            2,
        ));
        if !self.warnings.is_empty() {
            t.push_str("\nWarnings\n");
            for w in &self.warnings {
                t.push_str(&format!("  - {w}\n"));
            }
        }
        t
    }
}
