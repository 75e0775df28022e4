//! Tests of the parser: grammar, errors with their columns, suggestions.

use super::*;

fn scope() -> (Scope, Expr, Expr, Expr) {
    let mut s = Scope::new();
    let m = s.declare("m", 2.0).unwrap();
    let k = s.declare("k", 8.0).unwrap();
    let c = s.declare("c", 0.5).unwrap();
    (s, m, k, c)
}

/// The `Parse` error of `input`: (column, expected, found, full message).
fn parse_err(input: &str, scope: &Scope) -> (usize, String, String, String) {
    match parse(input, scope) {
        Err(e @ SymError::Parse { .. }) => {
            let msg = e.to_string();
            let SymError::Parse {
                column,
                expected,
                found,
                input: inp,
                caret,
            } = e
            else {
                unreachable!()
            };
            let n = input.chars().count();
            if n <= 80 {
                assert_eq!(inp, input);
                assert_eq!(caret.chars().count(), column, "caret under the column");
            } else {
                // A long input is shown as a window around the column, with its length.
                assert!(inp.chars().count() < 120, "{inp}");
                assert!(
                    inp.ends_with(&format!("({n} characters)")) || column + 40 > n,
                    "{inp}"
                );
                assert!(caret.chars().count() <= 62, "{caret}");
                let at = caret.chars().count() - 1;
                let shown: Vec<char> = inp.chars().collect();
                let real: Vec<char> = input.chars().collect();
                if inp.starts_with('…') {
                    assert_eq!(
                        shown.get(at),
                        real.get(column - 1),
                        "caret under the column"
                    );
                }
            }
            assert!(caret.ends_with('^'));
            (column, expected, found, msg)
        }
        other => panic!("{input:?}: expected a parse error, got {other:?}"),
    }
}

#[test]
fn edit_distance_and_suggestions() {
    assert_eq!(
        eom_text::closest("sinn", FUNCTIONS.iter().copied()),
        Some("sin")
    );
    assert_eq!(
        eom_text::closest("sqr", FUNCTIONS.iter().copied()),
        Some("sqrt")
    );
    assert_eq!(eom_text::closest("zzzzzz", FUNCTIONS.iter().copied()), None);
}

#[test]
fn empty_input() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("", &s);
    assert_eq!(
        (col, exp.as_str(), found.as_str()),
        (1, "an expression", "end of input")
    );
    assert!(msg.starts_with("parse error at column 1: expected an expression, found end of input"));
    let (col, ..) = parse_err("   ", &s);
    assert_eq!(col, 4);
}

#[test]
fn missing_operand_at_the_end() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("2*m + ", &s);
    assert_eq!(
        (col, exp.as_str(), found.as_str()),
        (7, "an operand", "end of input")
    );
    assert!(msg.starts_with("parse error at column 7: expected an operand, found end of input"));
    assert!(msg.ends_with("\n  2*m + \n        ^"), "{msg}");
    let (col, _, found, _) = parse_err("m ^", &s);
    assert_eq!((col, found.as_str()), (4, "end of input"));
}

#[test]
fn operator_where_an_operand_belongs() {
    let (s, ..) = scope();
    let (col, exp, found, _) = parse_err("m + * k", &s);
    assert_eq!(
        (col, exp.as_str(), found.as_str()),
        (5, "an operand", "`*`")
    );
    let (col, _, found, _) = parse_err("()", &s);
    assert_eq!((col, found.as_str()), (2, "`)`"));
}

#[test]
fn unbalanced_parentheses() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("(m + k", &s);
    assert_eq!(col, 7);
    assert_eq!(exp, "`)` to close the `(` at column 1");
    assert_eq!(found, "end of input");
    assert!(msg.contains("expected `)` to close the `(` at column 1, found end of input"));
    let (col, exp, found, _) = parse_err("m + k)", &s);
    assert_eq!(col, 6);
    assert_eq!(exp, "an operator or the end of the input");
    assert_eq!(found, "`)` without a matching `(`");
    let (col, exp, _, _) = parse_err("sin((m)", &s);
    assert_eq!((col, exp.as_str()), (8, "`)` (`sin` takes one argument)"));
}

#[test]
fn unknown_function_suggests_the_closest() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("2*sinn(m)", &s);
    assert_eq!(col, 3);
    assert_eq!(
        exp,
        "a known function (sin, cos, tan, exp, ln, log, abs, sqrt, atan2, float)"
    );
    assert_eq!(found, "unknown function `sinn` (did you mean `sin`?)");
    assert!(msg.contains("found unknown function `sinn` (did you mean `sin`?)"));
    let (_, _, found, _) = parse_err("qqqqqq(m)", &s);
    assert_eq!(found, "unknown function `qqqqqq`");
}

#[test]
fn wrong_arity() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("atan2(m)", &s);
    assert_eq!(col, 8);
    assert_eq!(
        exp,
        "`,` and a second argument (`atan2` takes two arguments: y, x)"
    );
    assert_eq!(found, "`)`");
    assert!(msg.contains("at column 8: expected `,` and a second argument"));
    let (col, exp, found, _) = parse_err("sin(m, k)", &s);
    assert_eq!(
        (col, exp.as_str(), found.as_str()),
        (6, "`)` (`sin` takes one argument)", "`,`")
    );
    let (col, exp, _, _) = parse_err("cos()", &s);
    assert_eq!(
        (col, exp.as_str()),
        (5, "an argument (`cos` takes one argument)")
    );
    let (col, _, found, _) = parse_err("atan2(m, k, c)", &s);
    assert_eq!((col, found.as_str()), (11, "`,`"));
}

#[test]
fn function_name_without_call() {
    let (s, ..) = scope();
    let (col, exp, found, _) = parse_err("sin + 1", &s);
    assert_eq!(
        (col, exp.as_str(), found.as_str()),
        (5, "`(` after the function name `sin`", "`+`")
    );
    let (col, _, found, _) = parse_err("2*sqrt", &s);
    assert_eq!((col, found.as_str()), (7, "end of input"));
    let (col, _, found, _) = parse_err("sin x", &s);
    assert_eq!((col, found.as_str()), (5, "`x`"));
}

#[test]
fn stray_characters() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("m $ k", &s);
    assert_eq!(col, 3);
    assert_eq!(exp, "an operator or the end of the input");
    assert_eq!(found, "the character `$`");
    assert!(
        msg.contains("found the character `$`\n  m $ k\n    ^"),
        "{msg}"
    );
    let (col, exp, found, _) = parse_err("#m", &s);
    assert_eq!(
        (col, exp.as_str(), found.as_str()),
        (1, "an operand", "the character `#`")
    );
    let (col, exp, _, _) = parse_err("m, k", &s);
    assert_eq!(
        (col, exp.as_str()),
        (2, "an operator or the end of the input")
    );
}

#[test]
fn number_with_two_decimal_points() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("1.2.3", &s);
    assert_eq!(col, 4);
    assert_eq!(exp, "an operator or the end of the input");
    assert_eq!(found, "a second `.` in the number `1.2.`");
    assert!(msg.starts_with("parse error at column 4"));
}

#[test]
fn implicit_multiplication_is_refused_with_a_hint() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("2m", &s);
    assert_eq!(col, 2);
    assert_eq!(exp, "an operator (`+ - * / ^`) or the end of the input");
    assert_eq!(
        found,
        "`m` (implicit multiplication is not allowed: write `2*m`)"
    );
    assert!(msg.contains("write `2*m`"));
    let (col, _, found, _) = parse_err("2 (m + k)", &s);
    assert_eq!(col, 3);
    assert!(found.contains("write `2*(`"), "{found}");
    let (col, _, found, _) = parse_err("(m)(k)", &s);
    assert_eq!(col, 4);
    assert!(found.contains("write `)*(`"), "{found}");
    let (col, _, found, _) = parse_err("m k", &s);
    assert_eq!(col, 3);
    assert!(found.contains("write `m*k`"), "{found}");
    let (col, _, found, _) = parse_err("m(k)", &s);
    assert_eq!(col, 2);
    assert!(found.contains("write `m*(`"), "{found}");
    let (col, _, found, _) = parse_err("pi(2)", &s);
    assert_eq!(col, 3);
    assert!(found.contains("write `pi*(`"), "{found}");
    let (col, _, _, _) = parse_err("(2m)", &s);
    assert_eq!(col, 3);
    // `2e` is not an exponent: the constant e follows the number.
    let (col, _, found, _) = parse_err("2e", &s);
    assert_eq!(col, 2);
    assert!(found.contains("write `2*e`"), "{found}");
}

#[test]
fn unknown_parameter_has_column_and_known_names() {
    let (s, ..) = scope();
    let (col, exp, found, msg) = parse_err("m + kk", &s);
    assert_eq!(col, 5);
    assert_eq!(exp, "a known parameter (did you mean `k`?)");
    assert_eq!(found, "unknown parameter `kk`; known parameters: m, k, c");
    assert!(msg.starts_with(
        "parse error at column 5: expected a known parameter (did you mean `k`?), found \
         unknown parameter `kk`; known parameters: m, k, c"
    ));
    let (col, exp, found, _) = parse_err("x", &Scope::new());
    assert_eq!(col, 1);
    assert_eq!(exp, "a known parameter");
    assert_eq!(found, "unknown parameter `x`; no parameters are declared");
}

#[test]
fn literal_too_wide() {
    let (s, ..) = scope();
    let (col, exp, found, _) = parse_err("m + 1e99999", &s);
    assert_eq!(col, 5);
    assert!(
        exp.starts_with("an exact literal of at most 4096 bits"),
        "{exp}"
    );
    assert_eq!(found, "`1e99999`, which is too wide");
    // Four million digits are refused at once (the conversion is quadratic), the message
    // short.
    let long = "7".repeat(4_000_000);
    let t = std::time::Instant::now();
    let (_, _, found, _) = parse_err(&format!("m + {long}"), &s);
    assert!(t.elapsed().as_secs_f64() < 5.0, "{:?}", t.elapsed());
    assert_eq!(
        found,
        "`77777777777777777777…` (4000000 characters), which is too wide"
    );
}

#[test]
fn float_literal_errors() {
    let (s, ..) = scope();
    let (col, exp, found, _) = parse_err("float(m)", &s);
    assert_eq!(col, 7);
    assert_eq!(
        exp,
        "a decimal literal such as `0.1` (`float(...)` takes a number)"
    );
    assert_eq!(found, "`m`");
    let (col, exp, found, _) = parse_err("float(1e999)", &s);
    assert_eq!((col, exp.as_str()), (7, "a finite floating-point literal"));
    assert_eq!(found, "`1e999`, which overflows f64");
    let (col, exp, _, _) = parse_err("2*float(0.1", &s);
    assert_eq!(
        (col, exp.as_str()),
        (12, "`)` to close the `float(` at column 3")
    );
}

#[test]
fn nesting_is_bounded() {
    let (s, m, ..) = scope();
    let ok = format!(
        "{}m{}",
        "(".repeat(MAX_DEPTH - 1),
        ")".repeat(MAX_DEPTH - 1)
    );
    assert_eq!(parse(&ok, &s).unwrap(), m);
    let deep = format!(
        "{}m{}",
        "(".repeat(MAX_DEPTH + 1),
        ")".repeat(MAX_DEPTH + 1)
    );
    let (col, exp, _, _) = parse_err(&deep, &s);
    assert_eq!(col, MAX_DEPTH + 1);
    assert!(exp.starts_with("at most 256 levels of nesting"), "{exp}");
    // Runs of signs are read in a loop, not nested.
    let minus = format!("{}m", "-".repeat(10 * MAX_DEPTH));
    assert_eq!(parse(&minus, &s).unwrap(), m);
    let calls = format!(
        "{}m{}",
        "sin(".repeat(MAX_DEPTH + 1),
        ")".repeat(MAX_DEPTH + 1)
    );
    let (col, ..) = parse_err(&calls, &s);
    assert_eq!(col, 4 * (MAX_DEPTH + 1), "at the `(` one level too deep");
    let tower = format!("2{}", "^2".repeat(2 * MAX_DEPTH));
    assert!(matches!(parse(&tower, &s), Err(SymError::Parse { .. })));
}

#[test]
fn operations_without_value_report_the_typed_error_and_column() {
    let (s, ..) = scope();
    match parse("m + 1/0", &s) {
        Err(SymError::DivisionByZero { context }) => {
            assert!(context.ends_with("(at column 6 of `m + 1/0`)"), "{context}")
        }
        other => panic!("{other:?}"),
    }
    match parse("m/(k - k)", &s) {
        Err(SymError::DivisionByZero { context }) => {
            assert!(context.contains("at column 2"), "{context}")
        }
        other => panic!("{other:?}"),
    }
    match parse("2*ln(0)", &s) {
        Err(e @ SymError::NotReal { .. }) => {
            assert_eq!(
                e.to_string(),
                "not a real number: ln(0) (at column 3 of `2*ln(0)`)"
            )
        }
        other => panic!("{other:?}"),
    }
    match parse("(-1)^(1/2)", &s) {
        Err(SymError::NotReal { what }) => assert!(what.contains("at column 5"), "{what}"),
        other => panic!("{other:?}"),
    }
    match parse("0^-1", &s) {
        Err(SymError::DivisionByZero { context }) => {
            assert!(context.contains("at column 2"), "{context}")
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(parse("3^100000", &s), Err(SymError::RationalOverflow));
}

#[test]
fn literals_are_exact() {
    let s = Scope::new();
    let r = |n, d| Expr::rational(n, d).unwrap();
    assert_eq!(parse("0.21", &s).unwrap(), r(21, 100));
    assert_eq!(parse("1.5e3", &s).unwrap(), Expr::int(1500));
    assert_eq!(parse("2E-4", &s).unwrap(), r(1, 5000));
    assert_eq!(parse("2e+2", &s).unwrap(), Expr::int(200));
    assert_eq!(parse(".5", &s).unwrap(), r(1, 2));
    assert_eq!(parse("5.", &s).unwrap(), Expr::int(5));
    assert_eq!(parse("1/3", &s).unwrap(), r(1, 3));
    assert_eq!(parse("2^3^2", &s).unwrap(), Expr::int(512));
    assert_eq!(parse("-2^2", &s).unwrap(), Expr::int(-4));
    assert_eq!(parse("(-2)^2", &s).unwrap(), Expr::int(4));
    assert_eq!(parse("2^-2", &s).unwrap(), r(1, 4));
    assert_eq!(parse("--3", &s).unwrap(), Expr::int(3));
    assert_eq!(parse("+3", &s).unwrap(), Expr::int(3));
    assert_eq!(parse("3*-2", &s).unwrap(), Expr::int(-6));
    assert_eq!(parse(" 1 +\t2 ", &s).unwrap(), Expr::int(3));
}

#[test]
fn floats_are_floats() {
    let s = Scope::new();
    let f = parse("float(0.1)", &s).unwrap();
    assert_eq!(f.view(), crate::ExprView::Float(0.1));
    assert_eq!(parse("float(-1e-7)", &s).unwrap().as_f64(), Some(-1e-7));
    assert_eq!(parse("float(.25e1)", &s).unwrap().as_f64(), Some(2.5));
    assert_eq!(parse("float(3.)", &s).unwrap().as_f64(), Some(3.0));
    // 0.1 as a literal is exact, and differs from the float.
    assert_ne!(parse("0.1", &s).unwrap(), f);
}
