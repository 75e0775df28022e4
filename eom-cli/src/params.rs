//! Models and parameters on the command line: resolving a model name or file, parsing `--set
//! NAME=VALUE` and `--param NAME=START:STOP:COUNT`, the full parameter list of a model.

use crate::error::CliError;
use eom_model::Model;
use eom_model::file::ParamSpec;
use models::CatalogueError;
use std::path::{Path, PathBuf};

/// A model chosen on the command line: a built-in by name (`chain50` resolves to the `chainN`
/// entry with size 50) or a model file (a path ending in `.toml`, or any existing file).
#[derive(Clone, Debug)]
pub struct ModelChoice {
    /// The name as given (`chain50`, `cars/my_car.toml`).
    pub name: String,
    /// Where the model comes from.
    pub source: Source,
    /// The parameters with defaults, units, descriptions and ranges, in declaration order.
    pub params: Vec<ParamSpec>,
}

/// Where a model comes from.
#[derive(Clone, Debug)]
pub enum Source {
    /// A built-in model of the catalogue.
    Builtin,
    /// A model file.
    File(PathBuf),
}

/// Whether a model argument names a file rather than a built-in model: a path ending in
/// `.toml` or holding a `/`, or an existing file whose name is not a built-in model's (a
/// built-in's name wins over a file of the same name in the working directory, which
/// [`ModelChoice::resolve`] says; `./NAME` is the file).
pub fn is_file_argument(name: &str) -> bool {
    name.ends_with(".toml")
        || name.contains('/')
        || (Path::new(name).is_file() && models::find(name).is_err())
}

impl ModelChoice {
    /// Looks the model up: a file is loaded (and so checked) at its defaults; an unknown name
    /// is [`CatalogueError::UnknownModel`], which lists the models.
    pub fn resolve(name: &str) -> Result<ModelChoice, CliError> {
        if is_file_argument(name) {
            let loaded = eom_model::file::load(Path::new(name), &[])?;
            return Ok(ModelChoice {
                name: name.to_string(),
                source: Source::File(PathBuf::from(name)),
                params: loaded.params,
            });
        }
        let (info, _) = models::find(name)?;
        if Path::new(name).exists() {
            // Printed at once: the choice matters before any result.
            eprintln!(
                "note: `{}` is a built-in model and also a file in the working directory: the \
                 built-in model is used (write ./{} for the file)",
                eom_text::shown(name),
                eom_text::shown(name)
            );
        }
        Ok(ModelChoice {
            name: name.to_string(),
            source: Source::Builtin,
            params: info.params,
        })
    }

    /// The model with `overrides` replacing the defaults (values are checked against the
    /// parameters' ranges).
    pub fn build(&self, overrides: &[(String, f64)]) -> Result<Model, CliError> {
        let ov: Vec<(&str, f64)> = overrides.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        match &self.source {
            Source::Builtin => Ok(models::build(&self.name, &ov)?),
            Source::File(path) => Ok(eom_model::file::load(path, &ov)?.model),
        }
    }

    /// The parameter names, in declaration order.
    pub fn param_names(&self) -> Vec<String> {
        self.params.iter().map(|p| p.name.clone()).collect()
    }

    /// A parameter, or [`CatalogueError::UnknownParameter`] listing them.
    pub fn param(&self, name: &str) -> Result<&ParamSpec, CliError> {
        self.params.iter().find(|p| p.name == name).ok_or_else(|| {
            CliError::Catalogue(CatalogueError::UnknownParameter {
                model: self.name.clone(),
                name: name.to_string(),
                known: self.param_names(),
            })
        })
    }

    /// Every parameter with its value: the override where given, else the default.
    pub fn values(&self, overrides: &[(String, f64)]) -> Vec<(String, f64)> {
        self.params
            .iter()
            .map(|p| {
                let v = overrides
                    .iter()
                    .find(|(k, _)| *k == p.name)
                    .map_or(p.default, |o| o.1);
                (p.name.clone(), v)
            })
            .collect()
    }

    /// Parses the `--set NAME=VALUE` arguments. Errors name the argument and list the
    /// parameters of the model.
    pub fn parse_sets(&self, sets: &[String]) -> Result<Vec<(String, f64)>, CliError> {
        let mut out: Vec<(String, f64)> = Vec::with_capacity(sets.len());
        for s in sets {
            let bad = |problem: String| CliError::BadArgument {
                argument: format!("--set {}", abbreviate(s)),
                problem: format!(
                    "{problem}; the parameters of model `{}` are: {}",
                    self.name,
                    self.param_names().join(", ")
                ),
            };
            let Some((name, value)) = s.split_once('=') else {
                return Err(bad("expected NAME=VALUE (e.g. --set u=1)".into()));
            };
            let name = name.trim();
            if name.is_empty() {
                return Err(bad("the parameter name before `=` is missing".into()));
            }
            self.param(name)?;
            let value = parse_number(value).map_err(bad)?;
            if out.iter().any(|(k, _)| k == name) {
                return Err(bad(format!("parameter `{name}` is set more than once")));
            }
            out.push((name.to_string(), value));
        }
        Ok(out)
    }
}

/// Parses a finite number; the error says what was found: a value that overflowed to ±∞ or
/// underflowed to 0 when converted to `f64` says so (rather than going on with ∞ or 0).
pub fn parse_number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let shown = abbreviate(t);
    match t.parse::<f64>() {
        Ok(v) if v.is_infinite() && has_digit(t) => Err(format!(
            "the value `{shown}` overflows: the largest finite number is about {:e}",
            f64::MAX
        )),
        Ok(v) if !v.is_finite() => Err(format!(
            "the value `{shown}` is {v}, a finite number is needed"
        )),
        Ok(v) if v == 0.0 && has_nonzero_mantissa(t) => Err(format!(
            "the value `{shown}` underflows to 0: the smallest positive number is about {:e}",
            f64::from_bits(1)
        )),
        Ok(v) => Ok(v),
        Err(_) if t.is_empty() => Err("the value is missing".into()),
        Err(_) => Err(format!("`{shown}` is not a number")),
    }
}

/// Longest argument text repeated in a message; longer text is cut in the middle.
const SHOWN_CHARS: usize = 40;

/// `text` itself when short, else its first and last characters and its length; control
/// characters escaped (`eom_text::shown_within`).
pub fn abbreviate(text: &str) -> String {
    eom_text::shown_within(text, SHOWN_CHARS)
}

fn has_digit(t: &str) -> bool {
    t.bytes().any(|b| b.is_ascii_digit())
}

/// Whether the mantissa (before any exponent) has a nonzero digit: then a parsed 0 is an
/// underflow, not a zero.
fn has_nonzero_mantissa(t: &str) -> bool {
    t.split(['e', 'E'])
        .next()
        .is_some_and(|m| m.bytes().any(|b| (b'1'..=b'9').contains(&b)))
}

/// Sets the memory limit of the analyses ([`eom_num::budget`]) from the environment variable
/// `EOM_MEMORY_LIMIT`: bytes, or a number with the suffix K, M, G or T (binary units).
pub fn memory_limit_from_env() -> Result<(), CliError> {
    let Ok(text) = std::env::var("EOM_MEMORY_LIMIT") else {
        return Ok(());
    };
    let bad = || CliError::BadArgument {
        argument: format!("EOM_MEMORY_LIMIT={}", abbreviate(&text)),
        problem: "expected a number of bytes, optionally with K, M, G or T (e.g. 32G)".into(),
    };
    let t = text.trim();
    let (digits, shift) = match t.char_indices().last() {
        Some((i, c)) if c.is_ascii_alphabetic() => {
            let shift = match c.to_ascii_uppercase() {
                'K' => 10,
                'M' => 20,
                'G' => 30,
                'T' => 40,
                _ => return Err(bad()),
            };
            (&t[..i], shift)
        }
        _ => (t, 0),
    };
    let n: usize = digits.trim().parse().map_err(|_| bad())?;
    let bytes = n
        .checked_shl(shift)
        .filter(|b| b >> shift == n)
        .ok_or_else(bad)?;
    eom_num::budget::set_limit(bytes);
    Ok(())
}

/// Largest number of values of a sweep (`--param NAME=START:STOP:COUNT`).
pub const MAX_SWEEP_COUNT: usize = 1_000_000;

/// Largest number of frequencies of `--points` (the library's own limit of a grid).
pub const MAX_FREQ_POINTS: usize = eom_num::freq::MAX_POINTS;

/// A parameter sweep `NAME=START:STOP:COUNT`.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSpec {
    /// The swept parameter.
    pub name: String,
    /// First value.
    pub start: f64,
    /// Last value.
    pub stop: f64,
    /// Number of equally spaced values, both ends included.
    pub count: usize,
}

impl SweepSpec {
    /// Parses `--param NAME=START:STOP:COUNT` (the name is checked against the model later).
    pub fn parse(text: &str) -> Result<SweepSpec, CliError> {
        SweepSpec::parse_option("--param", text)
    }

    /// Parses `NAME=START:STOP:COUNT` given to `option` (`--param`, `--sweep`), which the
    /// errors name.
    pub fn parse_option(option: &str, text: &str) -> Result<SweepSpec, CliError> {
        let bad = |problem: String| CliError::BadArgument {
            argument: format!("{option} {}", abbreviate(text)),
            problem,
        };
        let Some((name, range)) = text.split_once('=') else {
            return Err(bad(format!(
                "expected NAME=START:STOP:COUNT (e.g. {option} v=0:10:101)"
            )));
        };
        let name = name.trim();
        if name.is_empty() {
            return Err(bad("the parameter name before `=` is missing".into()));
        }
        let parts: Vec<&str> = range.split(':').collect();
        let [start, stop, count] = parts[..] else {
            return Err(bad(format!(
                "expected START:STOP:COUNT after `{name}=`, found {} field(s) in `{range}`",
                parts.len()
            )));
        };
        let start = parse_number(start).map_err(|e| bad(format!("START: {e}")))?;
        let stop = parse_number(stop).map_err(|e| bad(format!("STOP: {e}")))?;
        let count: usize = count.trim().parse().map_err(|e: std::num::ParseIntError| {
            if *e.kind() == std::num::IntErrorKind::PosOverflow {
                bad(format!(
                    "COUNT: `{}` is too large (the limit is {MAX_SWEEP_COUNT} values)",
                    abbreviate(count.trim())
                ))
            } else {
                bad(format!(
                    "COUNT: `{}` is not a whole number ≥ 1",
                    abbreviate(count.trim())
                ))
            }
        })?;
        if count == 0 {
            return Err(bad("COUNT must be at least 1".into()));
        }
        if count > MAX_SWEEP_COUNT {
            return Err(bad(format!(
                "COUNT = {count} exceeds the limit of {MAX_SWEEP_COUNT} values (the stability \
                 boundaries are located to 1e-10 between grid points anyway); sweep a narrower \
                 range or split it into several runs"
            )));
        }
        if count > 1 && start == stop {
            return Err(bad(format!(
                "START and STOP are both {start:?}: {count} points need two different ends"
            )));
        }
        if !(stop - start).is_finite() {
            return Err(bad(format!(
                "the range {start:?} … {stop:?} is wider than the largest finite number \
                 (about {:e}): the grid spacing would overflow",
                f64::MAX
            )));
        }
        Ok(SweepSpec {
            name: name.to_string(),
            start,
            stop,
            count,
        })
    }

    /// Smallest and largest value of the sweep.
    pub fn bounds(&self) -> (f64, f64) {
        (self.start.min(self.stop), self.start.max(self.stop))
    }
}

/// Parses a frequency range `LOW:HIGH` in Hz (`0 < LOW < HIGH`).
pub fn parse_freq_range(text: &str) -> Result<(f64, f64), CliError> {
    let bad = |problem: String| CliError::BadArgument {
        argument: format!("--freq-range {}", abbreviate(text)),
        problem,
    };
    let Some((lo, hi)) = text.split_once(':') else {
        return Err(bad(
            "expected LOW:HIGH in Hz (e.g. --freq-range 0.1:100)".into()
        ));
    };
    let lo = parse_number(lo).map_err(|e| bad(format!("LOW: {e}")))?;
    let hi = parse_number(hi).map_err(|e| bad(format!("HIGH: {e}")))?;
    if !(lo > 0.0 && hi > lo) {
        return Err(bad(format!(
            "need 0 < LOW < HIGH (a logarithmic grid), got LOW = {lo:?}, HIGH = {hi:?}"
        )));
    }
    Ok((lo, hi))
}

/// `LOW:HIGH` in Hz for `--band` (0 ≤ LOW ≤ HIGH, both finite).
pub fn parse_band(text: &str) -> Result<(f64, f64), String> {
    let (lo, hi) = text
        .split_once(':')
        .ok_or_else(|| "expected LOW:HIGH in Hz (e.g. --band 0.5:2)".to_string())?;
    let lo = parse_number(lo).map_err(|e| format!("LOW: {e}"))?;
    let hi = parse_number(hi).map_err(|e| format!("HIGH: {e}"))?;
    if !(lo >= 0.0 && hi >= lo) {
        return Err(format!(
            "need 0 ≤ LOW ≤ HIGH, got LOW = {lo:?}, HIGH = {hi:?}"
        ));
    }
    Ok((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sweep_spec_accepts_negative_ends_and_rejects_bad_fields() {
        let s = SweepSpec::parse("c=-1.2:-0.8:21").unwrap();
        assert_eq!(
            (s.name.as_str(), s.start, s.stop, s.count),
            ("c", -1.2, -0.8, 21)
        );
        for bad in [
            "v",
            "v=0:10",
            "v=0:10:0",
            "v=a:1:3",
            "v=1:1:3",
            "=0:1:2",
            "v=0:1:2.5",
            "v=0:1:1000001",
            "v=0:1:99999999999999999999999",
            "v=-1e308:1e308:3",
            "v=1e400:1:3",
        ] {
            assert!(
                matches!(SweepSpec::parse(bad), Err(CliError::BadArgument { .. })),
                "{bad}"
            );
        }
    }

    #[test]
    fn set_errors_name_the_argument_and_list_the_parameters() {
        let m = ModelChoice::resolve("smd").unwrap();
        let e = m.parse_sets(&["k".into()]).unwrap_err().to_string();
        assert!(e.contains("--set k") && e.contains("m, k, c"), "{e}");
        let e = m.parse_sets(&["q=1".into()]).unwrap_err().to_string();
        assert!(e.contains("`q`") && e.contains("m, k, c"), "{e}");
        let e = m.parse_sets(&["k=inf".into()]).unwrap_err().to_string();
        assert!(e.contains("finite"), "{e}");
        assert_eq!(
            m.parse_sets(&["k=2".into(), " c = 0.5".into()]).unwrap(),
            vec![("k".to_string(), 2.0), ("c".to_string(), 0.5)]
        );
    }

    #[test]
    fn values_that_overflow_or_underflow_say_so_in_short_form() {
        let e = parse_number("1e-400").unwrap_err();
        assert!(e.contains("underflows to 0") && e.contains("5e-324"), "{e}");
        let e = parse_number("-2e999").unwrap_err();
        assert!(
            e.contains("overflows") && e.contains("1.7976931348623157e308"),
            "{e}"
        );
        assert_eq!(parse_number("0e-400"), Ok(0.0));
        assert_eq!(parse_number("0.000"), Ok(0.0));
        let long = "1".repeat(5000);
        let e = parse_number(&format!("{long}x")).unwrap_err();
        assert!(e.len() < 200 && e.contains("5001 characters"), "{e}");
        let e = SweepSpec::parse("v=-1e308:1e308:3")
            .unwrap_err()
            .to_string();
        assert!(e.contains("-1e308") && !e.contains("000000000"), "{e}");
    }
}
