//! MathML (Presentation MathML, drawn natively by browsers) from the expression tree: no
//! LaTeX in between. Sums show their terms with signs, products split into a fraction of the
//! factors with positive and negative exponents, square roots as roots, parameter names with
//! an underscore as subscripts (`I_xx` → I with subscript xx), Greek names as letters.

use eom_sym::{Constant, Expr, ExprView, Rational};

/// `<math display="block">…</math>` of `inner` (already MathML).
pub fn block(inner: &str) -> String {
    format!("<math display=\"block\">{inner}</math>")
}

/// The MathML of an expression (the content of a `<math>` element).
pub fn mathml(e: Expr) -> String {
    let mut out = String::new();
    write_expr(e, &mut out);
    out
}

/// `cₙ sⁿ + … + c₀` in MathML, highest power first, zero coefficients left out.
pub fn polynomial(coefficients: &[Expr], variable: &str) -> String {
    let mut out = String::from("<mrow>");
    let mut first = true;
    for (k, &c) in coefficients.iter().enumerate().rev() {
        if c.is_zero() {
            continue;
        }
        let (negative, magnitude) = match number(c) {
            Some(r) if r.is_negative() => (true, -c),
            _ => (false, c),
        };
        out.push_str(match (first, negative) {
            (true, true) => "<mo>−</mo>",
            (true, false) => "",
            (false, true) => "<mo>−</mo>",
            (false, false) => "<mo>+</mo>",
        });
        first = false;
        let power = match k {
            0 => String::new(),
            1 => format!("<mi>{variable}</mi>"),
            _ => format!("<msup><mi>{variable}</mi><mn>{k}</mn></msup>"),
        };
        if k > 0 && magnitude.is_one() {
            out.push_str(&power);
            continue;
        }
        if k > 0 && is_sum(magnitude) {
            out.push_str(&parenthesized(magnitude));
        } else {
            write_expr(magnitude, &mut out);
        }
        if k > 0 {
            out.push_str("<mo>&#x2062;</mo>");
            out.push_str(&power);
        }
    }
    if first {
        out.push_str("<mn>0</mn>");
    }
    out.push_str("</mrow>");
    out
}

fn number(e: Expr) -> Option<Rational> {
    match e.view() {
        ExprView::Rational(r) => Some(r),
        _ => None,
    }
}

fn is_sum(e: Expr) -> bool {
    matches!(e.view(), ExprView::Sum { .. })
}

fn parenthesized(e: Expr) -> String {
    format!("<mrow><mo>(</mo>{}<mo>)</mo></mrow>", mathml(e))
}

fn rational(r: &Rational, out: &mut String) {
    let (n, d) = r.to_big_parts();
    if d == 1.into() {
        out.push_str(&format!("<mn>{n}</mn>"));
    } else {
        out.push_str(&format!("<mfrac><mn>{n}</mn><mn>{d}</mn></mfrac>"));
    }
}

fn float(x: f64, out: &mut String) {
    out.push_str(&format!("<mn>{}</mn>", crate::format::g(x, 10)));
}

/// A parameter name: Greek names as letters, `a_b` as a subscript.
fn name(n: &str) -> String {
    let greek = |s: &str| -> String {
        const GREEK: [(&str, &str); 16] = [
            ("alpha", "α"),
            ("beta", "β"),
            ("gamma", "γ"),
            ("delta", "δ"),
            ("epsilon", "ε"),
            ("zeta", "ζ"),
            ("eta", "η"),
            ("theta", "θ"),
            ("kappa", "κ"),
            ("lambda", "λ"),
            ("mu", "μ"),
            ("nu", "ν"),
            ("rho", "ρ"),
            ("sigma", "σ"),
            ("tau", "τ"),
            ("omega", "ω"),
        ];
        let t = GREEK.iter().find(|(k, _)| *k == s).map_or(s, |(_, g)| *g);
        crate::plot::shape::escape(t)
    };
    match n.split_once('_') {
        Some((base, sub)) if !base.is_empty() && !sub.is_empty() => format!(
            "<msub><mi>{}</mi><mi>{}</mi></msub>",
            greek(base),
            greek(sub)
        ),
        _ => format!("<mi>{}</mi>", greek(n)),
    }
}

fn write_expr(e: Expr, out: &mut String) {
    match e.view() {
        ExprView::Rational(r) => {
            if r.is_negative() {
                out.push_str("<mrow><mo>−</mo>");
                rational(&r.abs(), out);
                out.push_str("</mrow>");
            } else {
                rational(&r, out);
            }
        }
        ExprView::Float(x) => float(x, out),
        ExprView::Constant(Constant::Pi) => out.push_str("<mi>π</mi>"),
        ExprView::Constant(Constant::E) => out.push_str("<mi>e</mi>"),
        ExprView::Param(_, info) => out.push_str(&name(&info.name)),
        ExprView::Sum { constant, terms } => sum(constant, &terms, out),
        ExprView::Product { coef, factors } => product(coef, &factors, out),
        ExprView::Pow(b, x) => {
            out.push_str("<msup>");
            operand(b, out);
            out.push_str(&format!("<mrow>{}</mrow></msup>", mathml(x)));
        }
        ExprView::Func(f, x) => {
            out.push_str(&format!(
                "<mrow><mi>{}</mi><mo>&#x2061;</mo>{}</mrow>",
                f.name(),
                parenthesized_always(x)
            ));
        }
        ExprView::Atan2(y, x) => out.push_str(&format!(
            "<mrow><mi>atan2</mi><mo>&#x2061;</mo><mrow><mo>(</mo>{}<mo>,</mo>{}<mo>)</mo></mrow></mrow>",
            mathml(y),
            mathml(x)
        )),
        ExprView::Invalid(err) => out.push_str(&format!(
            "<merror><mtext>{}</mtext></merror>",
            crate::plot::shape::escape(&err.to_string())
        )),
    }
}

fn parenthesized_always(e: Expr) -> String {
    format!("<mrow><mo>(</mo>{}<mo>)</mo></mrow>", mathml(e))
}

/// A base of a power or a factor: parenthesized when it is a sum or a product.
fn operand(e: Expr, out: &mut String) {
    match e.view() {
        ExprView::Sum { .. } | ExprView::Product { .. } => out.push_str(&parenthesized_always(e)),
        ExprView::Rational(r) if r.is_negative() || !r.is_integer() => {
            out.push_str(&parenthesized_always(e))
        }
        _ => write_expr(e, out),
    }
}

fn sum(constant: Expr, terms: &[(Expr, Expr)], out: &mut String) {
    out.push_str("<mrow>");
    let mut first = true;
    for (term, coef) in terms {
        let negative = number(*coef).is_some_and(|r| r.is_negative())
            || matches!(coef.view(), ExprView::Float(x) if x < 0.0);
        out.push_str(match (first, negative) {
            (_, true) => "<mo>−</mo>",
            (true, false) => "",
            (false, false) => "<mo>+</mo>",
        });
        first = false;
        let magnitude = if negative { -*coef } else { *coef };
        if !magnitude.is_one() {
            write_expr(magnitude, out);
            out.push_str("<mo>&#x2062;</mo>");
        }
        if is_sum(*term) {
            out.push_str(&parenthesized_always(*term));
        } else {
            write_expr(*term, out);
        }
    }
    if !constant.is_zero() || first {
        let negative = number(constant).is_some_and(|r| r.is_negative())
            || matches!(constant.view(), ExprView::Float(x) if x < 0.0);
        if negative && !first {
            out.push_str("<mo>−</mo>");
            write_expr(-constant, out);
        } else {
            if !first {
                out.push_str("<mo>+</mo>");
            }
            write_expr(constant, out);
        }
    }
    out.push_str("</mrow>");
}

/// One factor `b^e` with e > 0: a root for 1/2, a power otherwise.
fn factor(b: Expr, e: &Rational, out: &mut String) {
    if e.is_one() {
        operand(b, out);
    } else if *e == Rational::new(1, 2).unwrap_or_else(|| Rational::int(1)) {
        out.push_str(&format!("<msqrt>{}</msqrt>", mathml(b)));
    } else {
        out.push_str("<msup>");
        operand(b, out);
        let mut x = String::new();
        rational(e, &mut x);
        out.push_str(&format!("<mrow>{x}</mrow></msup>"));
    }
}

fn product(coef: Expr, factors: &[(Expr, Rational)], out: &mut String) {
    let (up, down): (Vec<_>, Vec<_>) = factors.iter().partition(|(_, e)| !e.is_negative());
    let negative = number(coef).is_some_and(|r| r.is_negative())
        || matches!(coef.view(), ExprView::Float(x) if x < 0.0);
    let magnitude = if negative { -coef } else { coef };
    // A rational coefficient p/q: p goes up, q goes down.
    let (num_c, den_c) = match number(magnitude) {
        Some(r) => {
            let (n, d) = r.to_big_parts();
            (
                (n != 1.into()).then(|| format!("<mn>{n}</mn>")),
                (d != 1.into()).then(|| format!("<mn>{d}</mn>")),
            )
        }
        None => (Some(mathml(magnitude)), None),
    };
    let row = |coefficient: Option<String>, fs: &[&(Expr, Rational)], flip: bool| {
        let mut s = String::from("<mrow>");
        let mut any = false;
        if let Some(c) = coefficient {
            s.push_str(&c);
            any = true;
        }
        for (b, e) in fs {
            if any {
                s.push_str("<mo>&#x2062;</mo>");
            }
            let e = if flip { e.abs() } else { e.clone() };
            factor(*b, &e, &mut s);
            any = true;
        }
        if !any {
            s.push_str("<mn>1</mn>");
        }
        s.push_str("</mrow>");
        s
    };
    if negative {
        out.push_str("<mrow><mo>−</mo>");
    }
    if down.is_empty() && den_c.is_none() {
        out.push_str(&row(num_c, &up, false));
    } else {
        out.push_str(&format!(
            "<mfrac>{}{}</mfrac>",
            row(num_c, &up, false),
            row(den_c, &down, true)
        ));
    }
    if negative {
        out.push_str("</mrow>");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use eom_sym::ExprPool;

    fn strip(s: &str) -> String {
        s.replace("<mrow>", "").replace("</mrow>", "")
    }

    #[test]
    fn quotients_roots_and_signs() {
        let pool = ExprPool::new();
        pool.enter(|| {
            let p = |n: &str| Expr::param(n, 1.0).unwrap();
            let (k, m) = (p("k"), p("m"));
            let ml = strip(&mathml(-k / m));
            assert_eq!(ml, "<mo>−</mo><mfrac><mi>k</mi><mi>m</mi></mfrac>");
            let root = strip(&mathml((k / m).sqrt()));
            assert!(
                root.contains("<msqrt>") || root.contains("<msup>"),
                "{root}"
            );
            let s = strip(&mathml(k - m));
            assert!(s.contains("<mo>−</mo>") && s.contains("<mi>k</mi>"), "{s}");
            let i = p("I_xx");
            assert_eq!(strip(&mathml(i)), "<msub><mi>I</mi><mi>xx</mi></msub>");
            let l = p("lambda");
            assert_eq!(strip(&mathml(l)), "<mi>λ</mi>");
            let half = strip(&mathml(Expr::rational(1, 2).unwrap()));
            assert_eq!(half, "<mfrac><mn>1</mn><mn>2</mn></mfrac>");
        });
    }
}
