//! Number formatting for the text tables, and the `{re, im}` form of complex numbers in JSON.

use num_complex::Complex64;
use serde::Serialize;

/// A complex number as `{"re": …, "im": …}`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ReIm {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
}

impl From<Complex64> for ReIm {
    fn from(z: Complex64) -> ReIm {
        ReIm { re: z.re, im: z.im }
    }
}

/// Converts a list of complex numbers.
pub fn re_im(v: &[Complex64]) -> Vec<ReIm> {
    v.iter().map(|&z| z.into()).collect()
}

/// `x` with `sig` significant digits, like C's `%g`: fixed notation for exponents −4 … sig−1,
/// scientific otherwise, trailing zeros removed. `inf`, `-inf`, `NaN` spelled out.
pub fn g(x: f64, sig: usize) -> String {
    if !x.is_finite() {
        return if x.is_nan() {
            "NaN".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    if x == 0.0 {
        return "0".into();
    }
    let sig = sig.max(1);
    // Round first, then decide the notation from the rounded exponent (9.9999 → 10).
    let sci = format!("{:.*e}", sig - 1, x);
    let (mantissa, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    if exp < -4 || exp >= sig as i32 {
        format!("{}e{exp}", trim_zeros(mantissa))
    } else {
        let decimals = (sig as i32 - 1 - exp).max(0) as usize;
        trim_zeros(&format!("{x:.decimals$}")).to_string()
    }
}

fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// An eigenvalue for a table: `a` for a real one, `a ± bi` for one member of a conjugate pair
/// (shown once, with `|Im|`).
pub fn eigenvalue(z: Complex64, sig: usize, pair: bool) -> String {
    if pair {
        format!("{} ± {}i", g(z.re, sig), g(z.im.abs(), sig))
    } else if z.im == 0.0 {
        g(z.re, sig)
    } else if z.im > 0.0 {
        format!("{} + {}i", g(z.re, sig), g(z.im, sig))
    } else {
        format!("{} - {}i", g(z.re, sig), g(-z.im, sig))
    }
}

/// `label` followed by the items separated by `, `, wrapped before `width` characters with
/// continuation lines indented by two spaces; ends with a newline.
pub fn wrap_list(label: &str, items: &[String], width: usize) -> String {
    let mut out = String::new();
    let mut line = label.to_string();
    for (k, it) in items.iter().enumerate() {
        let sep = if k + 1 < items.len() { "," } else { "" };
        let piece = format!("{it}{sep}");
        let fresh = line.trim().is_empty() || line == label;
        if !fresh && line.chars().count() + 1 + piece.chars().count() > width {
            out.push_str(line.trim_end());
            out.push('\n');
            line = "  ".to_string();
        } else if !line.ends_with(' ') {
            line.push(' ');
        }
        line.push_str(&piece);
    }
    out.push_str(line.trim_end());
    out.push('\n');
    out
}

/// Pads or left-aligns cells into columns separated by two spaces.
pub fn table(header: &[&str], rows: &[Vec<String>], indent: usize) -> String {
    let ncol = header.len();
    let mut width: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (k, c) in r.iter().enumerate().take(ncol) {
            width[k] = width[k].max(c.chars().count());
        }
    }
    let mut out = String::new();
    let mut line = |cells: Vec<&str>| {
        let mut l = " ".repeat(indent);
        for (k, c) in cells.iter().enumerate() {
            l.push_str(c);
            if k + 1 < cells.len() {
                l.push_str(&" ".repeat(width[k] - c.chars().count() + 2));
            }
        }
        out.push_str(l.trim_end());
        out.push('\n');
    };
    line(header.to_vec());
    for r in rows {
        line(r.iter().map(String::as_str).collect());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn g_switches_notation_like_printf() {
        assert_eq!(g(-10.864787391630745, 6), "-10.8648");
        assert_eq!(g(0.002388912880279, 6), "0.00238891");
        assert_eq!(g(1.5e-7, 4), "1.5e-7");
        assert_eq!(g(123456789.0, 6), "1.23457e8");
        assert_eq!(g(9.99999999, 4), "10");
        assert_eq!(g(1.0, 6), "1");
        assert_eq!(g(f64::INFINITY, 6), "inf");
    }

    #[test]
    fn wrap_list_breaks_between_items() {
        let items: Vec<String> = ["a = 1", "bb = 2", "ccc = 3"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        assert_eq!(
            wrap_list("P:", &items, 14),
            "P: a = 1,\n  bb = 2,\n  ccc = 3\n"
        );
        assert_eq!(wrap_list("P:", &items, 80), "P: a = 1, bb = 2, ccc = 3\n");
    }

    #[test]
    fn eigenvalue_shows_pairs_once() {
        let z = Complex64::new(-0.5, -2.0);
        assert_eq!(eigenvalue(z, 3, true), "-0.5 ± 2i");
        assert_eq!(eigenvalue(z, 3, false), "-0.5 - 2i");
        assert_eq!(eigenvalue(Complex64::new(3.0, 0.0), 3, false), "3");
    }
}
