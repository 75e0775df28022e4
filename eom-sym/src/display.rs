//! Plain-text and LaTeX display of expressions and of matrices of expressions.
//!
//! # Plain text
//!
//! `impl Display for Expr` writes the syntax that [`parse`](crate::parse::parse) reads, with no more
//! parentheses than the meaning needs. Parsing the text in a scope holding the parameters gives
//! back **the same node**: `parse(&e.to_string(), &scope) == Ok(e)` for every valid expression.
//!
//! * Rationals print as fractions (`3/4`, `-1/2`), numeric coefficients as a numerator in front
//!   and a denominator behind (`3*x/4`), negative coefficients as subtraction (`a - 2*b`).
//! * Negative exponents go to the denominator: `x^-1` prints as `1/x`, `x^-2·y^-1` as
//!   `1/(x^2*y)`. `x^(1/2)` prints as `sqrt(x)` and `x^(-1/2)` as `1/sqrt(x)`; other rational
//!   exponents as `x^(1/3)`.
//! * Powers of negative numbers, of fractions and of products are parenthesised:
//!   `(-2)^(1/3)`, `(2/3)^x`, `(x*y)^(1/3)`.
//! * Floats (measured data) print as `float(0.1)`, the shortest decimal that converts back to
//!   the same `f64`. Decimal literals such as `0.1` are exact rationals, so a float needs its own
//!   syntax to re-parse as a float. The pool stores floats that land on integers or short
//!   dyadic fractions as rationals, so `float(…)` never shows such values.
//! * Invalid nodes print as `<invalid: reason>`, which does not parse (on purpose).
//!
//! A numeric coefficient times a lone sum is distributed by the pool (`3·(a + b) → 3a + 3b`),
//! so the text of a product is laid out such that the parser never builds that intermediate:
//! the factor right after a coefficient is not a bare sum (`3*x*(a + b)`), and when every
//! factor is a sum the coefficient comes last (`(a + b)/x*3`, `x/(a + b)/4`).
//!
//! # LaTeX
//!
//! [`Expr::to_latex`] (or the [`Latex`] wrapper) writes `\frac{…}{…}` for quotients and
//! fractions, `\sqrt{…}`, `x^{2}`, `\sin\left(…\right)` (`\sin^{2}\left(x\right)` for integer
//! powers of sin, cos, tan), `\left|…\right|`, `\pi`, juxtaposition for products with `\cdot`
//! only before a factor that starts with a digit, and `\left( \right)` only where needed.
//!
//! Parameter names are typeset by one rule:
//!
//! * the name is split at its first `_` into a *base* and a *subscript*;
//! * a base that is a Greek letter, written in Greek (`δ`, `ψ`) or spelled out in ASCII
//!   (`delta`, `Psi`, `varphi`), becomes the LaTeX command (`\delta`, `\Psi`, `\varphi`); a
//!   one-letter base stays as it is; any other base is set as one word: `\mathit{IBxx}`;
//! * the subscript is split at further `_` into pieces, Greek pieces become commands, and the
//!   pieces are joined by commas: `x_1` → `x_{1}`, `psi_f` → `\psi_{f}`, `k_f_r` → `k_{f,r}`,
//!   `m_alpha` → `m_{\alpha}`;
//! * a name without `_` that is a one-letter (or Greek) base followed only by digits takes
//!   the digits as its subscript: `x1` → `x_{1}`, `theta12` → `\theta_{12}`;
//! * there are no other implicit subscripts: `Ixx` is `\mathit{Ixx}` (write `I_xx` for
//!   `I_{xx}`), `IB1` is `\mathit{IB1}`.
//!
//! # Matrices
//!
//! [`display_matrix`] writes an aligned text table, [`latex_matrix`] a `pmatrix`; both accept a
//! [`SparseMatrix<Expr>`] or an `nalgebra::DMatrix<Expr>` (anything implementing
//! [`ExprMatrix`]).
//!
//! Rendering walks the expression with an explicit stack, so deep expressions cannot overflow
//! the call stack.

use crate::expr::{Expr, ExprView};
use crate::matrix::SparseMatrix;
use crate::pool::{Constant, Func};
use crate::rational::Rational;
use nalgebra::DMatrix;
use num_traits::One;
use std::fmt;

/// How tightly the outermost operator of a rendering binds. A sub-expression is parenthesised
/// when its level is below the level its position requires.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Level {
    /// `a + b`, `a - b`.
    Sum,
    /// A leading minus: `-x`, `-3/4`.
    Neg,
    /// `a*b`, `a/b`, `3/4`.
    Product,
    /// `a^b`.
    Power,
    /// Names, non-negative integers, calls, anything in parentheses.
    Atom,
}

/// One piece of output: literal text, or a sub-expression rendered at a required level.
enum Piece {
    Str(&'static str),
    Text(String),
    Node(Expr, Level),
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Style {
    Text,
    Latex,
}

/// Render `root` with an explicit stack of pieces (no recursion on the expression depth).
fn render(out: &mut dyn fmt::Write, root: Expr, style: Style) -> fmt::Result {
    let (open, close) = match style {
        Style::Text => ("(", ")"),
        Style::Latex => ("\\left(", "\\right)"),
    };
    let mut stack = vec![Piece::Node(root, Level::Sum)];
    let mut buf = Vec::new();
    while let Some(piece) = stack.pop() {
        match piece {
            Piece::Str(s) => out.write_str(s)?,
            Piece::Text(s) => out.write_str(&s)?,
            Piece::Node(e, need) => {
                let level = match style {
                    Style::Text => text_layout(e, &mut buf),
                    Style::Latex => latex_layout(e, &mut buf),
                };
                let paren = level < need;
                if paren {
                    stack.push(Piece::Str(close));
                }
                stack.extend(buf.drain(..).rev());
                if paren {
                    stack.push(Piece::Str(open));
                }
            }
        }
    }
    Ok(())
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        render(f, *self, Style::Text)
    }
}

/// Displays an expression as LaTeX (math mode, without delimiters).
///
/// ```
/// use eom_sym::{Expr, Latex};
/// let m = Expr::param("m", 1.0).unwrap();
/// let k = Expr::param("k", 4.0).unwrap();
/// assert_eq!(Latex(-k / m).to_string(), "-\\frac{k}{m}");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Latex(pub Expr);

impl fmt::Display for Latex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        render(f, self.0, Style::Latex)
    }
}

impl Expr {
    /// The expression as LaTeX (math mode, without delimiters); see the
    /// [`display`](crate::display) module for the rules.
    pub fn to_latex(&self) -> String {
        Latex(*self).to_string()
    }
}

// ------------------------------------------------------------------------ shared helpers

/// A numeric constant, read without creating nodes.
#[derive(Clone, Debug, PartialEq)]
enum Num {
    Rat(Rational),
    Float(f64),
}

impl Num {
    fn of(e: Expr) -> Num {
        match e.view() {
            ExprView::Rational(r) => Num::Rat(r),
            ExprView::Float(x) => Num::Float(x),
            // Coefficients and sum constants are always numbers; keep going rather than panic.
            _ => Num::Float(e.nominal()),
        }
    }
    fn is_negative(&self) -> bool {
        match self {
            Num::Rat(r) => r.is_negative(),
            Num::Float(x) => *x < 0.0,
        }
    }
    fn abs(&self) -> Num {
        match self {
            Num::Rat(r) => Num::Rat(r.abs()),
            Num::Float(x) => Num::Float(x.abs()),
        }
    }
    /// Numerator and denominator texts of a non-negative coefficient, `None` for 1.
    fn parts(&self, float: fn(f64) -> String) -> (Option<String>, Option<String>) {
        match self {
            Num::Rat(r) => {
                let (n, d) = r.to_big_parts();
                (
                    (!n.is_one()).then(|| n.to_string()),
                    (!d.is_one()).then(|| d.to_string()),
                )
            }
            Num::Float(x) => (Some(float(*x)), None),
        }
    }
}

fn half() -> Rational {
    Rational::new(1, 2).expect("1/2")
}

fn is_sum(e: Expr) -> bool {
    matches!(e.view(), ExprView::Sum { .. })
}

/// A bare sum factor: `(a + b)^1`.
fn is_sum1(f: &(Expr, Rational)) -> bool {
    f.1.is_one() && is_sum(f.0)
}

/// The factors of a sum term (unit coefficient), or the term itself as one factor.
fn factors_of(t: Expr) -> Factors {
    match t.view() {
        ExprView::Product { coef, factors } if coef.is_one() => factors,
        _ => vec![(t, Rational::ONE)],
    }
}

/// Sum terms as `(term, coefficient)`, a term with a non-negative coefficient first (so the
/// text starts `b - a` rather than `-a + b`).
fn ordered_terms(terms: Vec<(Expr, Expr)>) -> Vec<(Expr, Num)> {
    let mut terms: Vec<(Expr, Num)> = terms.into_iter().map(|(t, c)| (t, Num::of(c))).collect();
    if let Some(k) = terms.iter().position(|(_, c)| !c.is_negative()) {
        let t = terms.remove(k);
        terms.insert(0, t);
    }
    terms
}

/// `(base, exponent)` pairs of a product.
type Factors = Vec<(Expr, Rational)>;

/// Numerator and denominator factors (denominator exponents made positive), bare sums last.
fn split_factors(factors: &[(Expr, Rational)]) -> (Factors, Factors) {
    let mut num = Vec::new();
    let mut den = Vec::new();
    for (b, e) in factors {
        if e.is_negative() {
            den.push((*b, e.neg()));
        } else {
            num.push((*b, e.clone()));
        }
    }
    num.sort_by_key(is_sum1);
    den.sort_by_key(is_sum1);
    (num, den)
}

// ------------------------------------------------------------------------ plain text

fn float_text(x: f64) -> String {
    format!("float({x:?})")
}

/// Layout of one node in plain text; returns its level.
fn text_layout(e: Expr, out: &mut Vec<Piece>) -> Level {
    match e.view() {
        ExprView::Rational(r) => number_text(&Num::Rat(r), out),
        ExprView::Float(x) => number_text(&Num::Float(x), out),
        ExprView::Constant(c) => {
            out.push(Piece::Str(c.name()));
            Level::Atom
        }
        ExprView::Param(_, info) => {
            out.push(Piece::Text(info.name));
            Level::Atom
        }
        ExprView::Sum { constant, terms } => {
            let mut first = true;
            let mut sign = |out: &mut Vec<Piece>, neg: bool| {
                out.push(Piece::Str(match (first, neg) {
                    (true, false) => "",
                    (true, true) => "-",
                    (false, false) => " + ",
                    (false, true) => " - ",
                }));
                first = false;
            };
            for (t, c) in ordered_terms(terms) {
                sign(out, c.is_negative());
                product_text(&c.abs(), &factors_of(t), out);
            }
            if !constant.is_zero() {
                let c = Num::of(constant);
                sign(out, c.is_negative());
                number_text(&c.abs(), out);
            }
            Level::Sum
        }
        ExprView::Product { coef, factors } => {
            let c = Num::of(coef);
            if c.is_negative() {
                out.push(Piece::Str("-"));
                product_text(&c.abs(), &factors, out);
                Level::Neg
            } else {
                product_text(&c, &factors, out)
            }
        }
        ExprView::Pow(b, x) => {
            out.extend([
                Piece::Node(b, Level::Atom),
                Piece::Str("^"),
                Piece::Node(x, Level::Power),
            ]);
            Level::Power
        }
        ExprView::Func(f, a) => {
            out.extend([
                Piece::Str(f.name()),
                Piece::Str("("),
                Piece::Node(a, Level::Sum),
                Piece::Str(")"),
            ]);
            Level::Atom
        }
        ExprView::Atan2(y, x) => {
            out.extend([
                Piece::Str("atan2("),
                Piece::Node(y, Level::Sum),
                Piece::Str(", "),
                Piece::Node(x, Level::Sum),
                Piece::Str(")"),
            ]);
            Level::Atom
        }
        ExprView::Invalid(err) => {
            out.push(Piece::Text(format!("<invalid: {err}>")));
            Level::Atom
        }
    }
}

fn number_text(n: &Num, out: &mut Vec<Piece>) -> Level {
    if n.is_negative() {
        out.push(Piece::Str("-"));
        number_text(&n.abs(), out);
        return Level::Neg;
    }
    match n {
        Num::Rat(r) => {
            out.push(Piece::Text(r.to_string()));
            if r.is_integer() {
                Level::Atom
            } else {
                Level::Product
            }
        }
        Num::Float(x) => {
            out.push(Piece::Text(float_text(*x)));
            Level::Atom
        }
    }
}

/// `coef · Π factors` for a non-negative `coef`, laid out so that it parses back to the same
/// product (see the module docs); returns the level.
fn product_text(coef: &Num, factors: &[(Expr, Rational)], out: &mut Vec<Piece>) -> Level {
    let (kn, kd) = coef.parts(float_text);
    let (num, den) = split_factors(factors);
    // The parser multiplies left to right and `3*(a + b)` would be distributed before the next
    // factor arrives, so a coefficient must not meet a bare sum first. Bare sums are sorted
    // last; if every factor on a side is one, that side's coefficient goes at the very end.
    let kn_last = kn.is_some() && num.first().is_some_and(is_sum1);
    let kd_last = kd.is_some() && den.first().is_some_and(is_sum1);

    let mut items = 0;
    let mut level = Level::Product;
    if let (Some(k), false) = (&kn, kn_last) {
        out.push(Piece::Text(k.clone()));
        items += 1;
        level = Level::Atom;
    }
    for f in &num {
        if items > 0 {
            out.push(Piece::Str("*"));
        }
        level = factor_text(f, out);
        items += 1;
    }
    if items == 0 {
        out.push(Piece::Str("1"));
    }
    let lead_kd = kd.as_ref().filter(|_| !kd_last);
    let nden = den.len() + usize::from(lead_kd.is_some());
    if nden > 0 {
        out.push(Piece::Str(if nden > 1 { "/(" } else { "/" }));
        let mut j = 0;
        if let Some(k) = lead_kd {
            out.push(Piece::Text(k.clone()));
            j += 1;
        }
        for f in &den {
            if j > 0 {
                out.push(Piece::Str("*"));
            }
            factor_text(f, out);
            j += 1;
        }
        if nden > 1 {
            out.push(Piece::Str(")"));
        }
    }
    if let (Some(k), true) = (&kd, kd_last) {
        out.push(Piece::Text(format!("/{k}")));
    }
    if let (Some(k), true) = (&kn, kn_last) {
        out.push(Piece::Text(format!("*{k}")));
    }
    if items == 1 && nden == 0 && !kd_last && !kn_last {
        level
    } else {
        Level::Product
    }
}

/// `base^e` for a positive rational `e`; returns the level.
fn factor_text((b, e): &(Expr, Rational), out: &mut Vec<Piece>) -> Level {
    if e.is_one() {
        out.push(Piece::Node(*b, Level::Power));
        return Level::Power;
    }
    if *e == half() {
        out.extend([
            Piece::Str("sqrt("),
            Piece::Node(*b, Level::Sum),
            Piece::Str(")"),
        ]);
        return Level::Atom;
    }
    out.push(Piece::Node(*b, Level::Atom));
    out.push(Piece::Text(if e.is_integer() {
        format!("^{e}")
    } else {
        format!("^({e})")
    }));
    Level::Power
}

// ------------------------------------------------------------------------ LaTeX

fn latex_float(x: f64) -> String {
    let s = format!("{x:?}");
    match s.split_once('e') {
        Some((m, exp)) => format!("{m} \\cdot 10^{{{exp}}}"),
        None => s,
    }
}

/// Layout of one node in LaTeX; returns its level.
fn latex_layout(e: Expr, out: &mut Vec<Piece>) -> Level {
    match e.view() {
        ExprView::Rational(r) => latex_number(&Num::Rat(r), out),
        ExprView::Float(x) => latex_number(&Num::Float(x), out),
        ExprView::Constant(c) => {
            out.push(Piece::Str(match c {
                Constant::Pi => "\\pi",
                Constant::E => "e",
            }));
            Level::Atom
        }
        ExprView::Param(_, info) => {
            out.push(Piece::Text(latex_name(&info.name)));
            Level::Atom
        }
        ExprView::Sum { constant, terms } => {
            let mut first = true;
            let mut sign = |out: &mut Vec<Piece>, neg: bool| {
                out.push(Piece::Str(match (first, neg) {
                    (true, false) => "",
                    (true, true) => "-",
                    (false, false) => " + ",
                    (false, true) => " - ",
                }));
                first = false;
            };
            for (t, c) in ordered_terms(terms) {
                sign(out, c.is_negative());
                latex_product(&c.abs(), &factors_of(t), out);
            }
            if !constant.is_zero() {
                let c = Num::of(constant);
                sign(out, c.is_negative());
                latex_number(&c.abs(), out);
            }
            Level::Sum
        }
        ExprView::Product { coef, factors } => {
            let c = Num::of(coef);
            if c.is_negative() {
                out.push(Piece::Str("-"));
                latex_product(&c.abs(), &factors, out);
                Level::Neg
            } else {
                latex_product(&c, &factors, out)
            }
        }
        ExprView::Pow(b, x) => {
            out.extend([
                Piece::Node(b, Level::Atom),
                Piece::Str("^{"),
                Piece::Node(x, Level::Sum),
                Piece::Str("}"),
            ]);
            Level::Power
        }
        ExprView::Func(Func::Abs, a) => {
            out.extend([
                Piece::Str("\\left|"),
                Piece::Node(a, Level::Sum),
                Piece::Str("\\right|"),
            ]);
            Level::Atom
        }
        ExprView::Func(f, a) => {
            out.extend([
                Piece::Str(f.latex()),
                Piece::Str("\\left("),
                Piece::Node(a, Level::Sum),
                Piece::Str("\\right)"),
            ]);
            Level::Atom
        }
        ExprView::Atan2(y, x) => {
            out.extend([
                Piece::Str("\\operatorname{atan2}\\left("),
                Piece::Node(y, Level::Sum),
                Piece::Str(", "),
                Piece::Node(x, Level::Sum),
                Piece::Str("\\right)"),
            ]);
            Level::Atom
        }
        ExprView::Invalid(err) => {
            out.push(Piece::Text(format!(
                "\\text{{invalid: {}}}",
                latex_escape(&err.to_string())
            )));
            Level::Atom
        }
    }
}

fn latex_number(n: &Num, out: &mut Vec<Piece>) -> Level {
    if n.is_negative() {
        out.push(Piece::Str("-"));
        latex_number(&n.abs(), out);
        return Level::Neg;
    }
    match n {
        Num::Rat(r) if r.is_integer() => {
            out.push(Piece::Text(r.to_string()));
            Level::Atom
        }
        Num::Rat(r) => {
            let (p, q) = r.to_big_parts();
            out.push(Piece::Text(format!("\\frac{{{p}}}{{{q}}}")));
            Level::Product
        }
        Num::Float(x) => {
            let s = latex_float(*x);
            let level = if s.contains('\\') {
                Level::Product
            } else {
                Level::Atom
            };
            out.push(Piece::Text(s));
            level
        }
    }
}

/// An item of a juxtaposed product.
enum Item<'a> {
    Coef(String),
    Factor(&'a (Expr, Rational)),
}

/// `coef · Π factors` for a non-negative `coef`; one `\frac` when anything is divided.
fn latex_product(coef: &Num, factors: &[(Expr, Rational)], out: &mut Vec<Piece>) -> Level {
    let (kn, kd) = coef.parts(latex_float);
    let (num, den) = split_factors(factors);
    let mut top: Vec<Item> = kn.map(Item::Coef).into_iter().collect();
    top.extend(num.iter().map(Item::Factor));
    if den.is_empty() && kd.is_none() {
        let level = latex_items(&top, false, out);
        return if top.len() == 1 {
            level
        } else {
            Level::Product
        };
    }
    let mut bottom: Vec<Item> = kd.map(Item::Coef).into_iter().collect();
    bottom.extend(den.iter().map(Item::Factor));
    out.push(Piece::Str("\\frac{"));
    if top.is_empty() {
        out.push(Piece::Str("1"));
    } else {
        latex_items(&top, true, out);
    }
    out.push(Piece::Str("}{"));
    latex_items(&bottom, true, out);
    out.push(Piece::Str("}"));
    Level::Product
}

/// Juxtapose items; `grouped` when the list alone fills a `\frac` part (a lone factor then
/// needs no parentheses). Returns the level of a single item.
fn latex_items(items: &[Item], grouped: bool, out: &mut Vec<Piece>) -> Level {
    let alone = grouped && items.len() == 1;
    let mut level = Level::Product;
    for (i, item) in items.iter().enumerate() {
        match item {
            Item::Coef(k) => {
                out.push(Piece::Text(k.clone()));
                level = if k.contains('\\') {
                    Level::Product
                } else {
                    Level::Atom
                };
            }
            Item::Factor(f) => {
                if i > 0 {
                    out.push(Piece::Str(if latex_leads_with_digit(f) {
                        " \\cdot "
                    } else {
                        " "
                    }));
                }
                level = latex_factor(f, alone, out);
            }
        }
    }
    level
}

/// Does the LaTeX of factor `b^e` start with a digit (so juxtaposition would merge numbers)?
fn latex_leads_with_digit((b, e): &(Expr, Rational)) -> bool {
    if *e == half() {
        return false;
    }
    let digit_atom = |x: Expr| match x.view() {
        ExprView::Rational(r) => r.is_integer() && !r.is_negative(),
        ExprView::Float(v) => v >= 0.0,
        _ => false,
    };
    if digit_atom(*b) {
        return true;
    }
    match b.view() {
        ExprView::Pow(base, _) => e.is_one() && digit_atom(base),
        _ => false,
    }
}

fn latex_factor((b, e): &(Expr, Rational), alone: bool, out: &mut Vec<Piece>) -> Level {
    if e.is_one() {
        out.push(Piece::Node(
            *b,
            if alone { Level::Sum } else { Level::Power },
        ));
        return Level::Power;
    }
    if *e == half() {
        out.extend([
            Piece::Str("\\sqrt{"),
            Piece::Node(*b, Level::Sum),
            Piece::Str("}"),
        ]);
        return Level::Power;
    }
    let exponent = if e.is_integer() {
        e.to_string()
    } else {
        let (p, q) = e.to_big_parts();
        format!("\\frac{{{p}}}{{{q}}}")
    };
    // sin²x is written \sin^{2}\left(x\right).
    if let ExprView::Func(f @ (Func::Sin | Func::Cos | Func::Tan), a) = b.view()
        && e.is_integer()
    {
        out.extend([
            Piece::Text(format!("{}^{{{exponent}}}\\left(", f.latex())),
            Piece::Node(a, Level::Sum),
            Piece::Str("\\right)"),
        ]);
        return Level::Atom;
    }
    out.extend([
        Piece::Node(*b, Level::Atom),
        Piece::Text(format!("^{{{exponent}}}")),
    ]);
    Level::Power
}

/// Escape text for `\text{…}`.
fn latex_escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '\\' => o.push_str("\\textbackslash{}"),
            '{' | '}' | '_' | '#' | '$' | '%' | '&' => {
                o.push('\\');
                o.push(c);
            }
            '^' => o.push_str("\\^{}"),
            '~' => o.push_str("\\~{}"),
            '\n' => o.push(' '),
            _ => o.push(c),
        }
    }
    o
}

/// Greek letters: ASCII spelling, Unicode letters, LaTeX command (or a Latin capital that looks
/// the same).
const GREEK: &[(&str, &str, &str)] = &[
    ("alpha", "α", "\\alpha"),
    ("beta", "β", "\\beta"),
    ("gamma", "γ", "\\gamma"),
    ("delta", "δ", "\\delta"),
    ("epsilon", "ϵ", "\\epsilon"),
    ("varepsilon", "ε", "\\varepsilon"),
    ("zeta", "ζ", "\\zeta"),
    ("eta", "η", "\\eta"),
    ("theta", "θ", "\\theta"),
    ("vartheta", "ϑ", "\\vartheta"),
    ("iota", "ι", "\\iota"),
    ("kappa", "κ", "\\kappa"),
    ("lambda", "λ", "\\lambda"),
    ("mu", "μ", "\\mu"),
    ("nu", "ν", "\\nu"),
    ("xi", "ξ", "\\xi"),
    ("omicron", "ο", "o"),
    ("pi", "π", "\\pi"),
    ("varpi", "ϖ", "\\varpi"),
    ("rho", "ρ", "\\rho"),
    ("varrho", "ϱ", "\\varrho"),
    ("sigma", "σ", "\\sigma"),
    ("varsigma", "ς", "\\varsigma"),
    ("tau", "τ", "\\tau"),
    ("upsilon", "υ", "\\upsilon"),
    ("phi", "ϕ", "\\phi"),
    ("varphi", "φ", "\\varphi"),
    ("chi", "χ", "\\chi"),
    ("psi", "ψ", "\\psi"),
    ("omega", "ω", "\\omega"),
    ("Alpha", "Α", "A"),
    ("Beta", "Β", "B"),
    ("Gamma", "Γ", "\\Gamma"),
    ("Delta", "Δ", "\\Delta"),
    ("Epsilon", "Ε", "E"),
    ("Zeta", "Ζ", "Z"),
    ("Eta", "Η", "H"),
    ("Theta", "Θ", "\\Theta"),
    ("Iota", "Ι", "I"),
    ("Kappa", "Κ", "K"),
    ("Lambda", "Λ", "\\Lambda"),
    ("Mu", "Μ", "M"),
    ("Nu", "Ν", "N"),
    ("Xi", "Ξ", "\\Xi"),
    ("Omicron", "Ο", "O"),
    ("Pi", "Π", "\\Pi"),
    ("Rho", "Ρ", "P"),
    ("Sigma", "Σ", "\\Sigma"),
    ("Tau", "Τ", "T"),
    ("Upsilon", "Υ", "\\Upsilon"),
    ("Phi", "Φ", "\\Phi"),
    ("Chi", "Χ", "X"),
    ("Psi", "Ψ", "\\Psi"),
    ("Omega", "Ω", "\\Omega"),
];

fn greek(s: &str) -> Option<&'static str> {
    GREEK
        .iter()
        .find(|(ascii, uni, _)| *ascii == s || *uni == s)
        .map(|g| g.2)
}

/// A parameter name in LaTeX (rule in the module docs).
pub fn latex_name(name: &str) -> String {
    let (base, sub) = match name.split_once('_') {
        Some((b, s)) => (b, Some(s)),
        None => (name, None),
    };
    let pieces: Vec<&str> = sub.map(|s| s.split('_').collect()).unwrap_or_default();
    if base.is_empty() || pieces.iter().any(|p| p.is_empty()) {
        // `_x`, `x__1`, `x_`: no sensible subscript reading; set the whole name as a word.
        return format!("\\mathit{{{}}}", name.replace('_', "\\_"));
    }
    let word = |b: &str| match greek(b) {
        Some(g) => Some(g.to_string()),
        None if b.chars().count() == 1 => Some(b.to_string()),
        None => None,
    };
    // `x1`, `theta2`: a letter (or Greek name) followed only by digits, and no `_` subscript.
    let digits = base.len() - base.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    if sub.is_none() && digits > 0 && digits < base.len() {
        let (head, tail) = base.split_at(base.len() - digits);
        if let Some(h) = word(head) {
            return format!("{h}_{{{tail}}}");
        }
    }
    let mut s = word(base).unwrap_or_else(|| format!("\\mathit{{{base}}}"));
    if !pieces.is_empty() {
        let sub: Vec<String> = pieces
            .iter()
            .map(|p| greek(p).map_or_else(|| p.to_string(), str::to_string))
            .collect();
        s.push_str(&format!("_{{{}}}", sub.join(",")));
    }
    s
}

// ------------------------------------------------------------------------ matrices

/// A matrix of expressions, as [`display_matrix`] and [`latex_matrix`] read it.
pub trait ExprMatrix {
    /// `(rows, columns)`.
    fn shape(&self) -> (usize, usize);
    /// Entry `(i, j)` (structural zeros as the constant 0).
    fn entry(&self, i: usize, j: usize) -> Expr;
}

impl ExprMatrix for SparseMatrix<Expr> {
    fn shape(&self) -> (usize, usize) {
        (self.nrows(), self.ncols())
    }
    fn entry(&self, i: usize, j: usize) -> Expr {
        self.get(i, j)
    }
}

impl ExprMatrix for DMatrix<Expr> {
    fn shape(&self) -> (usize, usize) {
        (self.nrows(), self.ncols())
    }
    fn entry(&self, i: usize, j: usize) -> Expr {
        self[(i, j)]
    }
}

/// The matrix as an aligned plain-text table, one line per row, columns left-aligned and
/// separated by two spaces:
///
/// ```text
/// [ 0     1    ]
/// [ -k/m  -c/m ]
/// ```
///
/// An empty matrix prints as `[]` followed by its shape, e.g. `[] (0×3)`.
pub fn display_matrix<M: ExprMatrix + ?Sized>(m: &M) -> String {
    let (r, c) = m.shape();
    if r == 0 || c == 0 {
        return format!("[] ({r}×{c})");
    }
    let cells: Vec<Vec<String>> = (0..r)
        .map(|i| (0..c).map(|j| m.entry(i, j).to_string()).collect())
        .collect();
    let width: Vec<usize> = (0..c)
        .map(|j| {
            cells
                .iter()
                .map(|row| row[j].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut s = String::new();
    for (i, row) in cells.iter().enumerate() {
        if i > 0 {
            s.push('\n');
        }
        s.push_str("[ ");
        for (j, cell) in row.iter().enumerate() {
            if j > 0 {
                s.push_str("  ");
            }
            s.push_str(cell);
            s.extend(std::iter::repeat_n(' ', width[j] - cell.chars().count()));
        }
        s.push_str(" ]");
    }
    s
}

/// The matrix as a LaTeX `pmatrix`, one row per line:
///
/// ```text
/// \begin{pmatrix}
/// 0 & 1 \\
/// -\frac{k}{m} & -\frac{c}{m}
/// \end{pmatrix}
/// ```
pub fn latex_matrix<M: ExprMatrix + ?Sized>(m: &M) -> String {
    let (r, c) = m.shape();
    let mut s = String::from("\\begin{pmatrix}\n");
    for i in 0..r {
        let row: Vec<String> = (0..c).map(|j| m.entry(i, j).to_latex()).collect();
        s.push_str(&row.join(" & "));
        s.push_str(if i + 1 < r { " \\\\\n" } else { "\n" });
    }
    s.push_str("\\end{pmatrix}");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latex_names_follow_the_rule() {
        for (name, want) in [
            ("m", "m"),
            ("δ", "\\delta"),
            ("delta", "\\delta"),
            ("psi_f", "\\psi_{f}"),
            ("ψ_f", "\\psi_{f}"),
            ("x_1", "x_{1}"),
            ("I_xx", "I_{xx}"),
            ("Ixx", "\\mathit{Ixx}"),
            ("IBxx", "\\mathit{IBxx}"),
            ("k_f_r", "k_{f,r}"),
            ("m_alpha", "m_{\\alpha}"),
            ("Omega", "\\Omega"),
            ("Beta", "B"),
            ("φ", "\\varphi"),
            ("_x", "\\mathit{\\_x}"),
            ("x__1", "\\mathit{x\\_\\_1}"),
            ("p0", "p_{0}"),
            ("theta12", "\\theta_{12}"),
            ("δ2", "\\delta_{2}"),
            ("IB1", "\\mathit{IB1}"),
            ("x1_a", "\\mathit{x1}_{a}"),
            ("x_", "\\mathit{x\\_}"),
        ] {
            assert_eq!(latex_name(name), want, "{name}");
        }
    }

    #[test]
    fn latex_escapes_text() {
        assert_eq!(latex_escape("a_b {c} 50% ^"), "a\\_b \\{c\\} 50\\% \\^{}");
    }

    #[test]
    fn level_order_is_binding_strength() {
        assert!(Level::Sum < Level::Neg && Level::Neg < Level::Product);
        assert!(Level::Product < Level::Power && Level::Power < Level::Atom);
    }
}
