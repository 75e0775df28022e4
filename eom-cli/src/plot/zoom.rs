//! The zoom on the real parts near zero (`eom sweep … --plot FILE.svg --zoom[=HALF]`): a
//! third panel between the real parts and the frequencies, `−HALF ≤ Re λ ≤ HALF`, where the
//! crossings of the imaginary axis can be read (the seed paper's Figure 4 beside its
//! Figure 3).

use super::clip_to_band;
use crate::error::CliError;
use crate::params::parse_number;
use eom_num::sweep::SweepResult;

/// The band of the zoomed panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Zoom {
    /// `±AUTO_FRACTION` of the largest |Re λ| drawn.
    Auto,
    /// `±` this many 1/s.
    HalfWidth(f64),
}

/// The automatic band: this fraction of the largest drawn |Re λ|.
pub const AUTO_FRACTION: f64 = 0.05;

impl Zoom {
    /// Parses `auto` or a positive half-width in 1/s.
    pub fn parse(text: &str) -> Result<Zoom, CliError> {
        if text.trim() == "auto" {
            return Ok(Zoom::Auto);
        }
        let bad = |problem: String| CliError::BadArgument {
            argument: format!("--zoom {text}"),
            problem,
        };
        let x = parse_number(text).map_err(bad)?;
        if !(x.is_finite() && x > 0.0) {
            return Err(bad(
                "the half-width of the band must be a positive number of 1/s".into(),
            ));
        }
        Ok(Zoom::HalfWidth(x))
    }

    /// The half-width for the sweeps drawn: the given one, or [`AUTO_FRACTION`] of the
    /// largest finite |Re λ| of their non-neutral branches (1 when there is none).
    pub fn half_width(self, results: &[&SweepResult]) -> f64 {
        match self {
            Zoom::HalfWidth(h) => h,
            Zoom::Auto => {
                let largest = results
                    .iter()
                    .flat_map(|r| {
                        r.branches.iter().filter(|b| !b.neutral).flat_map(|b| {
                            r.points
                                .iter()
                                .filter_map(move |p| p.eigenvalues.get(b.index))
                        })
                    })
                    .map(|z| z.re.abs())
                    .filter(|x| super::plottable(*x))
                    .fold(0.0f64, f64::max);
                if largest > 0.0 {
                    AUTO_FRACTION * largest
                } else {
                    1.0
                }
            }
        }
    }
}

/// The pieces of the runs inside the band `±half`.
pub(crate) fn clipped(runs: &[super::Series], half: f64) -> Vec<super::Series> {
    runs.iter()
        .flat_map(|r| clip_to_band(r, -half, half))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zoom_arguments_are_checked() {
        assert_eq!(Zoom::parse("auto").unwrap(), Zoom::Auto);
        assert_eq!(Zoom::parse("0.5").unwrap(), Zoom::HalfWidth(0.5));
        for bad in ["0", "-1", "x", "inf"] {
            let e = Zoom::parse(bad).unwrap_err();
            assert!(e.to_string().contains("--zoom"), "{e}");
        }
    }
}
