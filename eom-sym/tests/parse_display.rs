//! Parser, plain-text display, LaTeX and matrix display.
//!
//! The central property: for every valid expression `e`, `parse(&e.to_string(), &scope)`
//! returns the very same node (`==` compares node ids of the hash-consed pool).

mod common;

use eom_sym::{
    Assumption, Expr, ExprView, ParamInfo, Rational, Scope, SparseMatrix, SymError, display_matrix,
    latex_matrix, parse,
};
use nalgebra::DMatrix;
use proptest::prelude::*;

fn scope_of(params: &[Expr]) -> Scope {
    let mut s = Scope::new();
    for &p in params {
        s.insert(p).unwrap();
    }
    s
}

fn r(n: i64, d: i64) -> Rational {
    Rational::new(n, d).unwrap()
}

/// No node anywhere in the DAG is invalid: the precondition of the round-trip property, stated
/// exactly. `Expr::check` looks at the root only; invalid nodes are meant to absorb every
/// operation, but `pow_rational` once let them hide under `sqrt`/`powi`.
fn fully_valid(e: Expr) -> bool {
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![e];
    while let Some(n) = stack.pop() {
        if !seen.insert(n.id()) {
            continue;
        }
        if n.is_invalid() {
            return false;
        }
        stack.extend(n.children());
    }
    true
}

/// `text` must parse back to exactly `e`.
fn assert_round_trip(e: Expr, scope: &Scope) -> Result<(), TestCaseError> {
    let text = e.to_string();
    match parse(&text, scope) {
        Ok(back) => prop_assert!(
            back == e,
            "round trip changed the node:\n  text  {text}\n  back  {back}\n  views {:?}\n     vs {:?}",
            e.view(),
            back.view()
        ),
        Err(err) => prop_assert!(false, "`{text}` does not parse: {err}"),
    }
    // Negative coefficients are written as subtraction.
    prop_assert!(!text.contains("+ -") && !text.contains("- -"), "{text}");
    Ok(())
}

proptest! {
    // Random expressions are sometimes invalid (division by a structural zero) and skipped.
    #![proptest_config(ProptestConfig {
        cases: 3000,
        max_global_rejects: 30_000,
        ..ProptestConfig::default()
    })]

    /// Parameters without sign assumptions.
    #[test]
    fn display_parses_back_to_the_same_node(rec in common::recipe()) {
        let p = common::params();
        let e = common::build(&rec, &p);
        prop_assume!(fully_valid(e));
        assert_round_trip(e, &scope_of(&p))?;
    }

    /// Positive parameters take other canonical paths (roots split, `abs` removed, `x/x → 1`).
    #[test]
    fn display_parses_back_with_positive_parameters(rec in common::recipe(), seed in 0u64..1000) {
        let p = eom_sym::testing::params(common::N_PARAMS, seed, true);
        let e = common::build(&rec, &p);
        prop_assume!(fully_valid(e));
        assert_round_trip(e, &scope_of(&p))?;
    }

    /// The shared recipes only build integer powers and square roots; compose them with
    /// symbolic exponents, rational exponents and powers of powers.
    #[test]
    fn display_parses_back_for_general_powers(
        r1 in common::recipe(),
        r2 in common::recipe(),
        (p1, q1, p2, q2) in (-4i64..5, 1i64..5, -3i64..4, 1i64..4),
        op in 0..5u8,
    ) {
        let p = common::params();
        let (a, b) = (common::build(&r1, &p), common::build(&r2, &p));
        let (ra, rb) = (r(p1, q1), r(p2, q2));
        let e = match op {
            0 => a.pow(b),
            1 => a.pow_rational(ra),
            2 => a.pow_rational(ra).pow_rational(rb),
            3 => (a.pow_rational(ra) * b).pow_rational(rb),
            _ => a.pow(b).pow_rational(ra) - b.pow(a),
        };
        prop_assume!(fully_valid(e));
        assert_round_trip(e, &scope_of(&p))?;
    }

    /// LaTeX of random expressions is well formed: braces and `\left`/`\right` balance.
    #[test]
    fn latex_is_balanced(rec in common::recipe()) {
        let p = common::params();
        let e = common::build(&rec, &p);
        prop_assume!(fully_valid(e));
        let t = e.to_latex();
        let mut depth = 0i64;
        for c in t.chars() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                _ => {}
            }
            prop_assert!(depth >= 0, "{t}");
        }
        prop_assert_eq!(depth, 0, "{}", t);
        prop_assert_eq!(t.matches("\\left").count(), t.matches("\\right").count(), "{}", t);
        prop_assert!(!t.contains("+ -"), "{}", t);
    }

    /// Arbitrary input never panics; a syntax error points inside the input or just past it.
    #[test]
    fn parser_survives_arbitrary_input(input in "[pq0-9 ().,+*/^e$-]{0,24}|(sin|atan2|float|ln|sqrt|[(),.0-9+*/^ -]|p0|q){0,12}") {
        let s = scope_of(&common::params());
        match parse(&input, &s) {
            Ok(e) => prop_assert!(e.check().is_ok()),
            Err(SymError::Parse { column, caret, .. }) => {
                prop_assert!(column >= 1 && column <= input.chars().count() + 1, "{column}");
                prop_assert_eq!(caret.chars().count(), column);
            }
            Err(SymError::DivisionByZero { .. } | SymError::NotReal { .. }
                | SymError::RationalOverflow | SymError::NonFinite { .. }) => {}
            Err(other) => prop_assert!(false, "{input:?}: unexpected error {other:?}"),
        }
    }
}

/// Parameters for the hand-written cases.
struct Names {
    s: Scope,
    a: Expr,
    b: Expr,
    c: Expr,
    x: Expr,
    y: Expr,
    z: Expr,
    m: Expr,
    k: Expr,
}

fn names() -> Names {
    let mut s = Scope::new();
    let mut d = |n: &str, v: f64| s.declare(n, v).unwrap();
    let (a, b, c, x, y, z) = (
        d("a", 1.0),
        d("b", 2.0),
        d("c", 3.0),
        d("x", 0.5),
        d("y", 1.5),
        d("z", 2.5),
    );
    let m = s
        .declare_info(ParamInfo {
            name: "m".into(),
            nominal: 2.0,
            unit: Some("kg".into()),
            description: None,
            assume: Assumption::Positive,
        })
        .unwrap();
    let k = s.declare("k", 8.0).unwrap();
    Names {
        s,
        a,
        b,
        c,
        x,
        y,
        z,
        m,
        k,
    }
}

/// Exact text, and the text parses back to the node.
fn shows(e: Expr, text: &str, scope: &Scope) {
    assert_eq!(e.to_string(), text);
    assert_eq!(parse(text, scope).unwrap(), e, "{text}");
}

#[test]
fn display_is_minimal_and_re_parsable() {
    let Names {
        s,
        a,
        b,
        c,
        x,
        y,
        z,
        ..
    } = names();
    let i = Expr::int;
    let q = |n, d| Expr::rational(n, d).unwrap();
    shows(a - 2 * b, "a - 2*b", &s);
    shows(b - a, "b - a", &s);
    shows(-a - b, "-a - b", &s);
    shows(a + q(3, 4), "a + 3/4", &s);
    shows(a - q(1, 2), "a - 1/2", &s);
    shows(x * (a + b), "x*(a + b)", &s);
    shows(2 * (a + b), "2*a + 2*b", &s);
    shows(x * (a + b) * (a - b), "x*(a + b)*(a - b)", &s);
    shows(x.recip(), "1/x", &s);
    shows(x.sqrt(), "sqrt(x)", &s);
    shows(x.sqrt().recip(), "1/sqrt(x)", &s);
    shows(x.pow_rational(r(1, 3)), "x^(1/3)", &s);
    shows(x.pow_rational(r(-2, 3)), "1/x^(2/3)", &s);
    shows(x.powi(-2) / y, "1/(x^2*y)", &s);
    shows(-x.powi(2), "-x^2", &s);
    shows(3 * x / 4, "3*x/4", &s);
    shows(-x / 2, "-x/2", &s);
    shows(q(-3, 4), "-3/4", &s);
    shows(i(-2).pow(x), "(-2)^x", &s);
    shows(q(-1, 2).pow(x), "(-1/2)^x", &s);
    shows(q(2, 3).pow_rational(r(1, 3)), "(2/3)^(1/3)", &s);
    shows(q(1, 2).pow(x), "(1/2)^x", &s);
    shows(i(2).pow(x), "2^x", &s);
    shows(i(2).sqrt(), "sqrt(2)", &s);
    shows(3 * i(2).sqrt(), "3*sqrt(2)", &s);
    shows((x * y).pow_rational(r(1, 3)), "(x*y)^(1/3)", &s);
    shows((-x).pow_rational(r(1, 3)), "(-x)^(1/3)", &s);
    shows(x.pow(y), "x^y", &s);
    shows(x.pow(y + 1), "x^(y + 1)", &s);
    shows(x.pow(-y), "x^(-y)", &s);
    shows(x.pow(y).pow(z), "(x^y)^z", &s);
    shows(x.pow(y.pow(z)), "x^y^z", &s);
    shows(x.pow(y).powi(2), "(x^y)^2", &s);
    shows(x.pow(y).powi(-2), "1/(x^y)^2", &s);
    shows(
        x.pow_rational(r(1, 3)).pow_rational(r(1, 3)),
        "(x^(1/3))^(1/3)",
        &s,
    );
    shows(x.sqrt().pow(y), "sqrt(x)^y", &s);
    shows(x.pow(Expr::float(0.3).unwrap()), "x^float(0.3)", &s);
    shows(Expr::float(0.3).unwrap().pow(x), "float(0.3)^x", &s);
    shows(x.sin().powi(2), "sin(x)^2", &s);
    shows((-x).exp(), "exp(-x)", &s);
    shows(y.atan2(x), "atan2(y, x)", &s);
    shows((Expr::pi() / 10i64).sin(), "sin(pi/10)", &s);
    shows(Expr::e().pow(x), "e^x", &s);
    shows(Expr::float(0.1).unwrap() * x, "float(0.1)*x", &s);
    shows(x - Expr::float(0.1).unwrap(), "x - float(0.1)", &s);
    shows(-Expr::float(1e-7).unwrap(), "-float(1e-7)", &s);
    shows(x.ln() + c.abs(), "ln(x) + abs(c)", &s);
}

/// A numeric coefficient times a lone sum is distributed by the pool, so these products are
/// laid out to never build that intermediate (module docs of `display`).
#[test]
fn coefficients_next_to_sums_keep_the_node() {
    let Names {
        s, a, b, c, x, y, ..
    } = names();
    // Built in an order that keeps the coefficient outside the sum.
    let e = (a + b) / x * 3i64;
    assert!(matches!(e.view(), ExprView::Product { .. }));
    shows(e, "(a + b)/x*3", &s);
    shows((a + b) * x / y * 3, "3*x*(a + b)/y", &s);
    shows(x / (a + b) / 4, "x/(a + b)/4", &s);
    shows(x / (y * (a + b)) / 4, "x/(4*y*(a + b))", &s);
    shows((a + b) * (a - c) * 3, "(a + b)*(a - c)*3", &s);
    shows(x / ((a + b) * (b + c)) / 4, "x/((a + b)*(b + c))/4", &s);
    shows((a + b) / (b + c) * 3 / 4, "(a + b)/(b + c)/4*3", &s);
    shows(-((a + b) / x), "-(a + b)/x", &s);
    shows(
        Expr::float(0.3).unwrap() * ((a + b) / x),
        "(a + b)/x*float(0.3)",
        &s,
    );
}

#[test]
fn parser_builds_what_users_mean() {
    let Names {
        s, a, b, m, k, x, ..
    } = names();
    let q = |n, d| Expr::rational(n, d).unwrap();
    let p = |t: &str| parse(t, &s).unwrap();
    assert_eq!(p("0.21*m*(a+b)^2"), q(21, 100) * m * (a + b).powi(2));
    assert_eq!(p("sin(pi/10)"), (Expr::pi() / 10i64).sin());
    assert_eq!(p("sin(π/10)"), (Expr::pi() / 10i64).sin());
    assert_eq!(p("-k/m"), -k / m);
    assert_eq!(p("1.5e3*k"), 1500 * k);
    assert_eq!(p("2E-4"), q(1, 5000));
    assert_eq!(p(".5*x"), x / 2);
    assert_eq!(p("x^-2"), x.powi(-2));
    assert_eq!(p("x^(1/2)"), x.sqrt());
    assert_eq!(p("x^(1/2)"), p("sqrt(x)"));
    assert_eq!(p("x^(-1/2)"), x.sqrt().recip());
    assert_eq!(p("-x^2"), -(x.powi(2)));
    assert_eq!(p("2^3^2"), Expr::int(512));
    assert_eq!(p("log(x)"), x.ln());
    assert_eq!(p("e"), Expr::e());
    assert_eq!(p("exp(1)"), Expr::one().exp());
    assert_eq!(p("abs(a) + atan2(a, b)"), a.abs() + a.atan2(b));
    assert_eq!(p("m/m"), Expr::one(), "m is declared positive");
    assert_eq!(p("a*-b"), -(a * b));
    assert_eq!(p("a - -b"), a + b);
}

#[test]
fn unicode_names_and_shadowing() {
    let mut s = Scope::new();
    let delta = s.declare("δ", 0.1).unwrap();
    let psi = s.declare("ψ_f", 0.2).unwrap();
    let ixx = s.declare("Ixx", 3.0).unwrap();
    let e = parse("δ*ψ_f/Ixx", &s).unwrap();
    assert_eq!(e, delta * psi / ixx);
    assert_eq!(parse(&e.to_string(), &s).unwrap(), e);
    assert_eq!(parse("π", &s).unwrap(), Expr::pi());
    // A parameter called π shadows the constant; both print so that they re-parse.
    let pi_param = s.declare("π", 3.0).unwrap();
    assert_eq!(parse("π", &s).unwrap(), pi_param);
    let both = pi_param * Expr::pi();
    assert_eq!(parse(&both.to_string(), &s).unwrap(), both);
    // A parameter called `float` or `log` stays usable; `name(` is always the function.
    let f = s.declare("float", 1.0).unwrap();
    let lg = s.declare("log", 1.0).unwrap();
    let g = f * (lg + delta);
    assert_eq!(g.to_string(), "float*(δ + log)");
    assert_eq!(parse(&g.to_string(), &s).unwrap(), g);
    assert_eq!(parse("log(float)", &s).unwrap(), f.ln());
}

#[test]
fn invalid_nodes_display_but_do_not_parse() {
    let Names { s, x, .. } = names();
    let bad = x / Expr::zero();
    let text = bad.to_string();
    assert!(text.starts_with("<invalid: division by zero"), "{text}");
    assert!(matches!(
        parse(&text, &s),
        Err(SymError::Parse { column: 1, .. })
    ));
}

#[test]
fn latex_snapshots() {
    let mut s = Scope::new();
    let mut d = |n: &str| s.declare(n, 1.5).unwrap();
    let (a, b, x, y, z, m, k) = (d("a"), d("b"), d("x"), d("y"), d("z"), d("m"), d("k"));
    let (delta, psi, ixx, x1) = (d("δ"), d("psi_f"), d("Ixx"), d("x_1"));
    let q = |n, d| Expr::rational(n, d).unwrap();
    let cases: Vec<(Expr, &str)> = vec![
        (-k / m, "-\\frac{k}{m}"),
        (
            q(21, 100) * m * (a + b).powi(2),
            "\\frac{21 m \\left(a + b\\right)^{2}}{100}",
        ),
        (a - 2 * b, "a - 2 b"),
        (x / (a + b), "\\frac{x}{a + b}"),
        (x * (a + b) / y, "\\frac{x \\left(a + b\\right)}{y}"),
        (x.sqrt(), "\\sqrt{x}"),
        (x.sqrt().recip(), "\\frac{1}{\\sqrt{x}}"),
        (x.pow_rational(r(1, 3)), "x^{\\frac{1}{3}}"),
        (
            (x * y).pow_rational(r(1, 3)),
            "\\left(x y\\right)^{\\frac{1}{3}}",
        ),
        (
            (Expr::pi() / 10i64).sin(),
            "\\sin\\left(\\frac{\\pi}{10}\\right)",
        ),
        (x.sin().powi(2), "\\sin^{2}\\left(x\\right)"),
        (x.abs(), "\\left|x\\right|"),
        (y.atan2(x), "\\operatorname{atan2}\\left(y, x\\right)"),
        ((-x).exp(), "\\exp\\left(-x\\right)"),
        (x.pow(y.pow(z)), "x^{y^{z}}"),
        (x.pow(y).pow(z), "\\left(x^{y}\\right)^{z}"),
        (Expr::e().pow(x), "e^{x}"),
        (
            2 * Expr::int(3).pow_rational(r(1, 3)),
            "2 \\cdot 3^{\\frac{1}{3}}",
        ),
        (2 * Expr::int(3).sqrt(), "2 \\sqrt{3}"),
        (q(-3, 4), "-\\frac{3}{4}"),
        (Expr::float(1.5e-7).unwrap(), "1.5 \\cdot 10^{-7}"),
        (Expr::float(0.1).unwrap() * x, "0.1 x"),
        (delta * psi * ixx, "\\delta \\psi_{f} \\mathit{Ixx}"),
        (x1.powi(2), "x_{1}^{2}"),
        (x.powi(-2) / y, "\\frac{1}{x^{2} y}"),
    ];
    for (e, want) in cases {
        assert_eq!(e.to_latex(), want, "{e}");
        assert_eq!(eom_sym::Latex(e).to_string(), want);
    }
}

#[test]
fn matrices_as_text_and_latex() {
    let mut s = Scope::new();
    let m = s.declare("m", 1.0).unwrap();
    let k = s.declare("k", 4.0).unwrap();
    let c = s.declare("c", 0.1).unwrap();
    let delta = s.declare("δ", 0.1).unwrap();
    let rows = vec![vec![Expr::zero(), Expr::one()], vec![-k / m, -c / m]];
    let sparse = SparseMatrix::from_rows(&rows).unwrap();
    let dense = DMatrix::from_row_slice(2, 2, &[rows[0][0], rows[0][1], rows[1][0], rows[1][1]]);
    let text = "[ 0     1    ]\n[ -k/m  -c/m ]";
    assert_eq!(display_matrix(&sparse), text);
    assert_eq!(display_matrix(&dense), text);
    let tex = "\\begin{pmatrix}\n0 & 1 \\\\\n-\\frac{k}{m} & -\\frac{c}{m}\n\\end{pmatrix}";
    assert_eq!(latex_matrix(&sparse), tex);
    assert_eq!(latex_matrix(&dense), tex);
    // Widths count characters, not bytes.
    let g = SparseMatrix::from_rows(&[vec![delta, m], vec![Expr::int(10), delta]]).unwrap();
    assert_eq!(display_matrix(&g), "[ δ   m ]\n[ 10  δ ]");
    assert_eq!(
        display_matrix(&SparseMatrix::<Expr>::zeros(0, 3)),
        "[] (0×3)"
    );
    assert_eq!(
        latex_matrix(&SparseMatrix::<Expr>::zeros(0, 0)),
        "\\begin{pmatrix}\n\\end{pmatrix}"
    );
}

#[test]
fn deep_expressions_display_without_recursion() {
    // Rendering uses an explicit stack: 20 000 nested functions print in a test thread.
    let x = Expr::param("x", 0.3).unwrap();
    let mut e = x;
    for _ in 0..20_000 {
        e = e.sin();
    }
    assert_eq!(
        e.to_string(),
        format!("{}x{}", "sin(".repeat(20_000), ")".repeat(20_000))
    );
    assert_eq!(e.to_latex().matches("\\sin").count(), 20_000);
}
