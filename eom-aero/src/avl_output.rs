//! Readers of AVL's derivative files: SB (body axes, "Geometry-axis derivatives...") and ST
//! (stability axes, "Stability-axis derivatives...").
//!
//! The files are read by name, not by position, with a scanner of `name = value` pairs:
//! AVL versions add or drop rows (the `x force CD` row of ST files appeared after 3.32), so
//! positions are not stable. The first occurrence of a name wins. A pair whose name is
//! part of an expression with ` / ` (the spiral-stability line `Clb Cnr / Clr Cnb = …`) is
//! skipped, or it would overwrite `Cnb`. Values that AVL could not print (`***`), that are
//! not finite, or that are missing are errors naming the file, line and field, whenever the
//! field is needed.

use crate::derivatives::{Derivatives, Reference, StabilityDerivatives};
use crate::error::{AeroError, Result};
use crate::stability::{BodyDerivatives, to_body};
use serde::Serialize;
use std::path::Path;

/// Which derivative table the file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum AvlOutputKind {
    /// ST: stability-axis derivatives w.r.t. α, β, p', q', r'.
    Stability,
    /// SB: body-axis derivatives w.r.t. u, v, w, p, q, r.
    Body,
}

/// One `name = value` pair as found in the file.
#[derive(Debug, Clone, PartialEq, Serialize)]
struct Entry {
    name: String,
    line: usize,
    text: String,
}

/// A parsed AVL ST or SB file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AvlOutput {
    /// The file name given to the reader (used in errors).
    pub file: String,
    /// ST or SB.
    pub kind: AvlOutputKind,
    /// The configuration title (AVL truncates it).
    pub configuration: String,
    /// The run case's name.
    pub run_case: String,
    /// Sref, Cref, Bref and Xref, Yref, Zref.
    pub reference: Reference,
    /// Angle of attack, degrees.
    pub alpha_deg: f64,
    /// Sideslip, degrees.
    pub beta_deg: f64,
    /// Mach number.
    pub mach: f64,
    /// Control variables in the order of their columns (d01, d02, …): their names.
    pub controls: Vec<String>,
    #[serde(skip)]
    entries: Vec<Entry>,
}

const SB_HINT: &str = "the file may be truncated, or from an AVL version with another layout";

impl AvlOutput {
    /// Reads an ST or SB file.
    pub fn read(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let text = eom_text::read_limited(path, eom_text::MAX_FILE_BYTES).map_err(|source| {
            AeroError::Io {
                file: file.clone(),
                source,
            }
        })?;
        AvlOutput::parse(&text, &file)
    }

    /// Parses the text of an ST or SB file; `file` names it in errors. All fields needed
    /// for [`AvlOutput::derivatives`] are checked here.
    pub fn parse(text: &str, file: &str) -> Result<Self> {
        let scan = Scan::new(text);
        let kind = match (
            scan.find_line("Geometry-axis derivatives"),
            scan.find_line("Body-axis derivatives"),
            scan.find_line("Stability-axis derivatives"),
        ) {
            (Some(_), _, _) | (_, Some(_), _) => AvlOutputKind::Body,
            (_, _, Some(_)) => AvlOutputKind::Stability,
            _ => {
                return Err(AeroError::MissingField {
                    file: file.into(),
                    field: "the derivative table ('Stability-axis derivatives...' or 'Geometry-axis derivatives...')".into(),
                    hint: "not an AVL ST or SB file, or truncated".into(),
                });
            }
        };
        check_orientation(&scan, file)?;
        let mut out = AvlOutput {
            file: file.into(),
            kind,
            configuration: scan.after_colon("Configuration:").unwrap_or_default(),
            run_case: scan.after_colon("Run case:").unwrap_or_default(),
            reference: Reference::new(0.0, 0.0, 0.0, [0.0; 3]),
            alpha_deg: 0.0,
            beta_deg: 0.0,
            mach: 0.0,
            controls: scan.controls(),
            entries: scan.entries,
        };
        let g = |name: &str| out.required(name);
        let reference = Reference::new(
            g("Sref")?,
            g("Cref")?,
            g("Bref")?,
            [g("Xref")?, g("Yref")?, g("Zref")?],
        );
        let (alpha, beta, mach) = (g("Alpha")?, g("Beta")?, g("Mach")?);
        // The same rules as for a geometry: a zero area gives an all-zero matrix, a negative
        // one turns damping into anti-damping.
        if let Err((field, reason)) = reference.check() {
            let name = field.split('/').next().unwrap_or(field);
            let line = out.entry(name).map_or(0, |e| e.line);
            return Err(AeroError::Parse {
                file: out.file.clone(),
                line,
                message: format!("{field} {reason}"),
            });
        }
        out.reference = reference;
        (out.alpha_deg, out.beta_deg, out.mach) = (alpha, beta, mach);
        match kind {
            AvlOutputKind::Body => {
                out.body_table()?;
            }
            AvlOutputKind::Stability => {
                out.stability_table()?;
            }
        }
        Ok(out)
    }

    fn entry(&self, name: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.name == name)
    }

    /// The value of `name` (e.g. `"CYv"`, `"CLtot"`, `"CLd01"`): `Ok(None)` if the file has
    /// no such field, an error if the field is there but unusable.
    pub fn value(&self, name: &str) -> Result<Option<f64>> {
        let Some(e) = self.entry(name) else {
            return Ok(None);
        };
        let bad = |reason: &str| AeroError::BadValue {
            file: self.file.clone(),
            line: e.line,
            field: e.name.clone(),
            text: e.text.clone(),
            reason: reason.into(),
        };
        if e.text.is_empty() {
            return Err(bad("no value after '=' (truncated file?)"));
        }
        if e.text.starts_with('*') {
            return Err(bad("the value overflowed AVL's print format"));
        }
        match e.text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            Ok(_) => Err(bad("the value is not finite")),
            Err(_) => Err(bad("not a number")),
        }
    }

    fn required(&self, name: &str) -> Result<f64> {
        self.value(name)?.ok_or_else(|| AeroError::MissingField {
            file: self.file.clone(),
            field: name.into(),
            hint: SB_HINT.into(),
        })
    }

    fn body_table(&self) -> Result<Derivatives> {
        let mut c = [[0.0; 6]; 6];
        for (i, row) in Derivatives::names().iter().enumerate() {
            for (j, name) in row.iter().enumerate() {
                c[i][j] = self.required(name)?;
            }
        }
        Ok(Derivatives {
            reference: self.reference,
            coefficients: c,
        })
    }

    /// The ST table, and whether it has the CD rows (AVL versions after 3.32).
    fn stability_table(&self) -> Result<(StabilityDerivatives, bool)> {
        let names = StabilityDerivatives::names();
        let has_drag = self.entry("CDa").is_some();
        let mut c = [[0.0; 5]; 6];
        for (i, row) in names.iter().enumerate() {
            if i == 5 && !has_drag {
                continue;
            }
            for (j, name) in row.iter().enumerate() {
                c[i][j] = self.required(name)?;
            }
        }
        let st = StabilityDerivatives {
            alpha_deg: self.alpha_deg,
            reference: self.reference,
            coefficients: c,
        };
        Ok((st, has_drag))
    }

    /// The ST file's stability-axis table (`None` for an SB file). Without the CD rows
    /// (AVL 3.32 files) the CD row is 0.
    pub fn stability_derivatives(&self) -> Result<Option<StabilityDerivatives>> {
        match self.kind {
            AvlOutputKind::Stability => Ok(Some(self.stability_table()?.0)),
            AvlOutputKind::Body => Ok(None),
        }
    }

    /// The trim coefficients CXtot, CYtot, CZtot, Cltot, Cmtot, Cntot (body axes), if all
    /// are present.
    pub fn totals(&self) -> Result<Option<[f64; 6]>> {
        let mut t = [0.0; 6];
        for (k, name) in ["CXtot", "CYtot", "CZtot", "Cltot", "Cmtot", "Cntot"]
            .iter()
            .enumerate()
        {
            match self.value(name)? {
                Some(v) => t[k] = v,
                None => return Ok(None),
            }
        }
        Ok(Some(t))
    }

    /// Body-axis derivatives: all 36 from an SB file; from an ST file those that its
    /// stability-axis table determines at the file's α, with warnings for the rest (the u
    /// column always, the w column away from α = 0, the CX row without CD rows). An ST
    /// file with sideslip is refused, since the axis relations hold at β = 0.
    pub fn derivatives(&self) -> Result<BodyDerivatives> {
        match self.kind {
            AvlOutputKind::Body => Ok(BodyDerivatives {
                derivatives: self.body_table()?,
                known: [[true; 6]; 6],
                warnings: Vec::new(),
            }),
            AvlOutputKind::Stability => {
                if self.beta_deg != 0.0 {
                    let line = self.entry("Beta").map_or(0, |e| e.line);
                    return Err(AeroError::Parse {
                        file: self.file.clone(),
                        line,
                        message: format!(
                            "Beta = {}: stability-axis files are converted at zero sideslip only",
                            self.beta_deg
                        ),
                    });
                }
                let (st, has_drag) = self.stability_table()?;
                Ok(to_body(&st, has_drag, self.totals()?))
            }
        }
    }
}

fn check_orientation(scan: &Scan, file: &str) -> Result<()> {
    match scan.find_line("axis orientation") {
        Some((line, text)) if text.trim_start().starts_with("Standard") => {
            let _ = line;
            Ok(())
        }
        Some((line, text)) => Err(AeroError::Parse {
            file: file.into(),
            line,
            message: format!(
                "`{}`: only AVL's standard axes (X fwd, Z down) are read; rerun AVL with standard axes",
                eom_text::shown(text.trim())
            ),
        }),
        None => Err(AeroError::MissingField {
            file: file.into(),
            field: "the axis-orientation line ('Standard axis orientation, X fwd, Z down')".into(),
            hint: SB_HINT.into(),
        }),
    }
}

/// The scanned file: its lines and its `name = value` pairs.
struct Scan<'a> {
    lines: Vec<&'a str>,
    entries: Vec<Entry>,
}

fn is_name_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '\'' || c == '/' || c == '_'
}

impl<'a> Scan<'a> {
    fn new(text: &'a str) -> Self {
        let lines: Vec<&str> = text.lines().collect();
        let mut entries: Vec<Entry> = Vec::new();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_start();
            if t.starts_with("Configuration:") || t.starts_with("Run case:") {
                continue;
            }
            for (name, text) in pairs(line) {
                if !entries.iter().any(|e| e.name == name) {
                    entries.push(Entry {
                        name,
                        line: i + 1,
                        text,
                    });
                }
            }
        }
        Scan { lines, entries }
    }

    fn find_line(&self, needle: &str) -> Option<(usize, &'a str)> {
        self.lines
            .iter()
            .enumerate()
            .find(|(_, l)| l.contains(needle))
            .map(|(i, l)| (i + 1, *l))
    }

    fn after_colon(&self, label: &str) -> Option<String> {
        self.lines.iter().find_map(|l| {
            let t = l.trim_start();
            t.strip_prefix(label).map(|rest| rest.trim().to_string())
        })
    }

    /// Control names from the column headers `name d01  name d02 …` (lines without `=`).
    fn controls(&self) -> Vec<String> {
        let mut out: Vec<(usize, String)> = Vec::new();
        for l in self.lines.iter().filter(|l| !l.contains('=')) {
            let toks: Vec<&str> = l.split_whitespace().collect();
            for w in toks.windows(2) {
                let tag = w[1];
                let numbered = tag.len() > 1
                    && tag.starts_with('d')
                    && tag[1..].chars().all(|c| c.is_ascii_digit());
                if numbered {
                    let index: usize = tag[1..].parse().unwrap_or(0);
                    if !out.iter().any(|(k, _)| *k == index) {
                        out.push((index, w[0].to_string()));
                    }
                }
            }
        }
        out.sort_by_key(|(k, _)| *k);
        out.into_iter().map(|(_, n)| n).collect()
    }
}

/// The `name = value` pairs of one line. The name is the word before `=`; the value the
/// word after it (empty if the line ends there).
fn pairs(line: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut segment_start = 0;
    for (eq, _) in line.match_indices('=') {
        let before = line[..eq].trim_end();
        let name_start = before
            .char_indices()
            .rev()
            .find(|&(_, c)| !is_name_char(c))
            .map_or(0, |(i, c)| i + c.len_utf8());
        let name = &before[name_start..];
        let after = line[eq + 1..].trim_start();
        let value = after.split_whitespace().next().unwrap_or("");
        let value_end = line.len() - after.len() + value.len();
        let composite = line[segment_start.min(name_start)..name_start].contains(" / ");
        if !name.is_empty() && !composite {
            out.push((name.to_string(), value.to_string()));
        }
        segment_start = value_end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_read_names_with_primes_and_slashes_and_skip_the_spiral_ratio() {
        let p = pairs("  Alpha =   5.00000     pb/2V =  -0.00000     p'b/2V =  -0.00000");
        let names: Vec<_> = p.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["Alpha", "pb/2V", "p'b/2V"]);
        assert_eq!(p[0].1, "5.00000");
        assert!(
            pairs(" Clb Cnr / Clr Cnb  =  -3.108476    (  > 1 if spirally stable )").is_empty()
        );
        assert_eq!(pairs(" CYu =")[0].1, "");
    }
}
