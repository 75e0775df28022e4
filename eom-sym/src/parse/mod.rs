//! Parser for expressions as users write them: `0.21*m*(a + b)^2`, `-k/m`, `sin(pi/10)`.
//!
//! # Grammar
//!
//! ```text
//! expr     = { "+" | "-" } product { ("+" | "-") product } ;
//! product  = operand { ("*" | "/") operand } ;
//! operand  = { "+" | "-" } primary [ "^" operand ] ;
//! primary  = number
//!          | "float" "(" [ "+" | "-" ] number ")"
//!          | function "(" expr ")"
//!          | "atan2" "(" expr "," expr ")"
//!          | name
//!          | "(" expr ")" ;
//! function = "sin" | "cos" | "tan" | "exp" | "ln" | "log" | "abs" | "sqrt" ;
//! number   = digits [ "." [ digits ] ] [ exponent ] | "." digits [ exponent ] ;
//! exponent = ( "e" | "E" ) [ "+" | "-" ] digits ;
//! name     = ( letter | "_" ) { letter | digit | "_" } ;
//! ```
//!
//! * Signs at the start of an `expr` cover the whole first product (`-a*b` is `-(a*b)`, so
//!   `-(a + b)/x` never negates the sum on its own); signs inside a product or an exponent
//!   cover one operand (`a*-b`, `x^-2`).
//! * `^` binds tighter than a sign and is right-associative: `-x^2 = -(x^2)`, `2^3^2 = 2^9`.
//! * `letter` and `digit` are Unicode letters and alphanumerics (`δ`, `ψ_f`, `Ixx`), as in
//!   parameter names; `digits` in numbers are ASCII.
//!
//! Whitespace is allowed between tokens. There is no implicit multiplication: `2m`, `2(a+b)`
//! and `a b` are errors that suggest the `*`.
//!
//! # Meaning
//!
//! * Decimal literals are **exact** rationals: `0.21` is `21/100`, `1.5e3` is `1500`, `2E-4` is
//!   `1/5000`. A literal wider than [`MAX_BITS`] is an error.
//! * `float(0.1)` is the floating-point constant nearest to 0.1 (measured data); this is the
//!   syntax the [`Display`](std::fmt::Display) of a float node uses, so floats survive a round
//!   trip through text. A float that is an integer or a short dyadic fraction (`float(0.5)`)
//!   is stored exactly, as everywhere in the pool.
//! * `x^(1/2)` and `sqrt(x)` are the same node; rational exponents are exact.
//! * `log` is the natural logarithm, an alias of `ln` (as `log` in C, numpy, MATLAB and Julia);
//!   there is no base-10 logarithm. Expressions always print `ln`.
//! * `pi` and `π` are π, `e` is Euler's number. A name is looked up in the scope first, so a
//!   parameter that happens to be called `π` shadows the constant (`pi` and `e` cannot be
//!   parameter names). A function name followed by `(` is always a call, even where a
//!   parameter has that name (`log`, `float`); any other name followed by `(` is an implicit
//!   multiplication and refused.
//!
//! # Errors
//!
//! Syntax errors are [`SymError::Parse`] with the 1-based character column, what was expected
//! and what was found (the message repeats the input with a caret under the column). An
//! unknown parameter is also a `Parse` error at its column, listing the known names and
//! suggesting the closest one; an unknown function suggests the closest known function.
//! Operations without a value (`1/0`, `ln(0)`, `(-1)^(1/2)`) return the typed error of the
//! operation ([`SymError::DivisionByZero`], [`SymError::NotReal`], …) with the column of the
//! operator or function appended to its text ([`SymError::RationalOverflow`] has no text and
//! comes as it is). Nesting deeper than [`MAX_DEPTH`] levels is an error, not a stack
//! overflow.

use crate::context::with_pool;
use crate::error::SymError;
use crate::expr::Expr;
use crate::rational::{MAX_BITS, Rational};
use crate::scope::Scope;

/// Deepest nesting of parentheses, function calls, signs and exponents the parser accepts.
pub const MAX_DEPTH: usize = 256;

/// Names that are functions when followed by `(`.
pub const FUNCTIONS: [&str; 10] = [
    "sin", "cos", "tan", "exp", "ln", "log", "abs", "sqrt", "atan2", "float",
];

/// Names of the constants (`π` too, which is not an identifier).
pub const CONSTANTS: [&str; 2] = ["pi", "e"];

/// The names no parameter may have: the constants and the elementary functions (`log` and
/// `float` stay usable as parameters: `log(`, `float(` are always the functions).
pub const RESERVED: [&str; 10] = [
    "pi", "e", "sin", "cos", "tan", "exp", "ln", "abs", "sqrt", "atan2",
];

/// Whether `name` is one of [`RESERVED`].
pub fn is_reserved(name: &str) -> bool {
    RESERVED.contains(&name)
}

/// Parse `input` with parameters resolved in `scope`.
///
/// ```
/// use eom_sym::{Scope, parse};
/// let mut scope = Scope::new();
/// let m = scope.declare("m", 2.0).unwrap();
/// let k = scope.declare("k", 8.0).unwrap();
/// assert_eq!(parse("-k/m", &scope).unwrap(), -k / m);
/// let err = parse("2m", &scope).unwrap_err();
/// assert!(err.to_string().contains("write `2*m`"));
/// ```
pub fn parse(input: &str, scope: &Scope) -> Result<Expr, SymError> {
    let mut p = Parser {
        lex: Lexer::new(input),
        peeked: None,
        last: [None, None],
        input,
        scope,
        depth: 0,
    };
    p.parse_all().map_err(|e| *e)
}

impl Parser<'_> {
    fn parse_all(&mut self) -> PResult<Expr> {
        if *self.peek_tok()? == Tok::End {
            let t = self.next()?;
            return Err(self.error(t.col, "an expression", "end of input"));
        }
        let e = self.binary(1)?;
        let t = self.next()?;
        match t.tok {
            Tok::End => Ok(e),
            Tok::RParen => Err(self.error(
                t.col,
                "an operator or the end of the input",
                "`)` without a matching `(`",
            )),
            _ => Err(self.error_at(&t, "an operator or the end of the input")),
        }
    }
}

// ------------------------------------------------------------------------ lexer

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    /// A decimal literal, as written.
    Num(String),
    Ident(String),
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
    /// A character that starts no token.
    Stray(char),
    End,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    /// 1-based column of the first character.
    col: usize,
}

impl Token {
    /// The token as written (for messages).
    fn text(&self) -> String {
        match &self.tok {
            Tok::Num(s) | Tok::Ident(s) => s.clone(),
            Tok::Plus => "+".into(),
            Tok::Minus => "-".into(),
            Tok::Star => "*".into(),
            Tok::Slash => "/".into(),
            Tok::Caret => "^".into(),
            Tok::LParen => "(".into(),
            Tok::RParen => ")".into(),
            Tok::Comma => ",".into(),
            Tok::Stray(c) => c.to_string(),
            Tok::End => String::new(),
        }
    }
}

/// A lexical error: column, expected, found.
type LexError = (usize, String, String);

struct Lexer {
    chars: Vec<char>,
    pos: usize,
}

fn ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}
fn ident_continue(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

impl Lexer {
    fn new(input: &str) -> Self {
        Lexer {
            chars: input.chars().collect(),
            pos: 0,
        }
    }
    fn at(&self, k: usize) -> Option<char> {
        self.chars.get(k).copied()
    }
    fn digits(&mut self) -> usize {
        let start = self.pos;
        while self.at(self.pos).is_some_and(|c| c.is_ascii_digit()) {
            self.pos += 1;
        }
        self.pos - start
    }
    fn next(&mut self) -> Result<Token, LexError> {
        while self.at(self.pos).is_some_and(char::is_whitespace) {
            self.pos += 1;
        }
        let start = self.pos;
        let col = start + 1;
        let Some(c) = self.at(start) else {
            return Ok(Token { tok: Tok::End, col });
        };
        let simple = match c {
            '+' => Some(Tok::Plus),
            '-' => Some(Tok::Minus),
            '*' => Some(Tok::Star),
            '/' => Some(Tok::Slash),
            '^' => Some(Tok::Caret),
            '(' => Some(Tok::LParen),
            ')' => Some(Tok::RParen),
            ',' => Some(Tok::Comma),
            _ => None,
        };
        if let Some(tok) = simple {
            self.pos += 1;
            return Ok(Token { tok, col });
        }
        let starts_number = c.is_ascii_digit()
            || (c == '.' && self.at(start + 1).is_some_and(|d| d.is_ascii_digit()));
        if starts_number {
            self.digits();
            if self.at(self.pos) == Some('.') {
                self.pos += 1;
                self.digits();
            }
            if matches!(self.at(self.pos), Some('e' | 'E')) {
                let sign = usize::from(matches!(self.at(self.pos + 1), Some('+' | '-')));
                if self
                    .at(self.pos + 1 + sign)
                    .is_some_and(|d| d.is_ascii_digit())
                {
                    self.pos += 1 + sign;
                    self.digits();
                }
            }
            let text: String = self.chars[start..self.pos].iter().collect();
            if self.at(self.pos) == Some('.') {
                return Err((
                    self.pos + 1,
                    "an operator or the end of the input".into(),
                    format!("a second `.` in the number `{text}.`"),
                ));
            }
            return Ok(Token {
                tok: Tok::Num(text),
                col,
            });
        }
        if ident_start(c) {
            while self.at(self.pos).is_some_and(ident_continue) {
                self.pos += 1;
            }
            let text: String = self.chars[start..self.pos].iter().collect();
            return Ok(Token {
                tok: Tok::Ident(text),
                col,
            });
        }
        self.pos += 1;
        Ok(Token {
            tok: Tok::Stray(c),
            col,
        })
    }
}

// ------------------------------------------------------------------------ parser

/// Errors are boxed inside the parser: small `Result`s keep the recursive frames small, so
/// deep nesting fits the stack of a test thread even in debug builds.
type PResult<T> = Result<T, Box<SymError>>;

struct Parser<'a> {
    lex: Lexer,
    peeked: Option<Token>,
    /// The last two tokens consumed, latest first (for the implicit-multiplication hint).
    last: [Option<Token>; 2],
    input: &'a str,
    scope: &'a Scope,
    depth: usize,
}

impl<'a> Parser<'a> {
    // -------------------------------------------------------------- tokens and errors

    fn peek(&mut self) -> PResult<&Token> {
        if self.peeked.is_none() {
            match self.lex.next() {
                Ok(t) => self.peeked = Some(t),
                Err((col, exp, found)) => return Err(self.error(col, &exp, &found)),
            }
        }
        Ok(self.peeked.as_ref().expect("just filled"))
    }

    fn peek_tok(&mut self) -> PResult<&Tok> {
        Ok(&self.peek()?.tok)
    }

    fn next(&mut self) -> PResult<Token> {
        self.peek()?;
        let t = self.peeked.take().expect("peeked");
        self.last = [Some(t.clone()), self.last[0].take()];
        Ok(t)
    }

    #[cold]
    #[inline(never)]
    fn error(&self, column: usize, expected: &str, found: &str) -> Box<SymError> {
        let (input, caret) = error_window(self.input, column);
        Box::new(SymError::Parse {
            column,
            expected: expected.to_string(),
            found: eom_text::escaped(found).into_owned(),
            input,
            caret,
        })
    }

    /// An error at token `t`, describing it as found.
    #[cold]
    #[inline(never)]
    fn error_at(&self, t: &Token, expected: &str) -> Box<SymError> {
        let found = self.found(t);
        self.error(t.col, expected, &found)
    }

    /// How a token (the one peeked at, or the last one consumed) is described after "found".
    fn found(&self, t: &Token) -> String {
        // The token before `t`.
        let before = match &self.last {
            [Some(cur), prev] if cur.col == t.col => prev,
            [cur, _] => cur,
        };
        match &t.tok {
            Tok::End => "end of input".into(),
            Tok::Stray(c) => format!("the character `{c}`"),
            Tok::Num(_) | Tok::Ident(_) | Tok::LParen => match before {
                // An operand right after an operand: the user meant a product.
                Some(p) if matches!(p.tok, Tok::Num(_) | Tok::Ident(_) | Tok::RParen) => format!(
                    "`{}` (implicit multiplication is not allowed: write `{}*{}`)",
                    eom_text::shown(&t.text()),
                    eom_text::shown(&p.text()),
                    eom_text::shown(&t.text())
                ),
                _ => format!("`{}`", eom_text::shown(&t.text())),
            },
            _ => format!("`{}`", eom_text::shown(&t.text())),
        }
    }

    /// Consume `want` or report what was found instead.
    fn expect(&mut self, want: Tok, expected: impl FnOnce() -> String) -> PResult<Token> {
        let t = self.next()?;
        if t.tok == want {
            Ok(t)
        } else {
            Err(self.error_at(&t, &expected()))
        }
    }

    /// The result of an operation at `col`, or its typed error with the column added.
    fn checked(&self, e: Expr, col: usize) -> PResult<Expr> {
        e.check().map_err(|err| self.locate(err, col))
    }

    #[cold]
    #[inline(never)]
    fn locate(&self, err: SymError, col: usize) -> Box<SymError> {
        let at = format!(" (at column {col} of `{}`)", self.input);
        Box::new(match err {
            SymError::DivisionByZero { context } => SymError::DivisionByZero {
                context: context + &at,
            },
            SymError::NotReal { what } => SymError::NotReal { what: what + &at },
            SymError::NonFinite { what } => SymError::NonFinite { what: what + &at },
            other => other,
        })
    }

    /// Enter one level of nesting; refuse beyond [`MAX_DEPTH`].
    fn enter(&mut self, col: usize) -> PResult<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.error(
                col,
                &format!("at most {MAX_DEPTH} levels of nesting (parentheses, calls, exponents)"),
                "one level more",
            ));
        }
        Ok(())
    }

    fn leave(&mut self) {
        self.depth -= 1;
    }

    /// Consume a run of `+`/`-` signs; true if they negate.
    fn signs(&mut self) -> PResult<bool> {
        let mut neg = false;
        loop {
            match self.peek_tok()? {
                Tok::Minus => neg = !neg,
                Tok::Plus => {}
                _ => return Ok(neg),
            }
            self.next()?;
        }
    }

    // -------------------------------------------------------------- grammar

    /// `expr = signed { ("+" | "-") product }` and `product = operand { ("*" | "/") operand }`
    /// by precedence climbing (both levels left-associative). `binary(1)` is an `expr`,
    /// `binary(2)` a `product`, `binary(3)` an `operand`.
    fn binary(&mut self, min_prec: u8) -> PResult<Expr> {
        let mut lhs = if min_prec == 1 && matches!(self.peek_tok()?, Tok::Minus | Tok::Plus) {
            // A sign at the start of a sum covers the whole first product: `-(a+b)/x`
            // negates the quotient, so the sum `a + b` is never negated on its own.
            let neg = self.signs()?;
            let v = self.binary(2)?;
            if neg { -v } else { v }
        } else {
            self.operand()?
        };
        loop {
            let t = self.peek()?;
            let prec = match t.tok {
                Tok::Plus | Tok::Minus => 1,
                Tok::Star | Tok::Slash => 2,
                _ => break,
            };
            if prec < min_prec {
                break;
            }
            let op = self.next()?;
            let rhs = self.binary(prec + 1)?;
            let e = match op.tok {
                Tok::Plus => lhs + rhs,
                Tok::Minus => lhs - rhs,
                Tok::Star => lhs * rhs,
                _ => lhs / rhs,
            };
            lhs = self.checked(e, op.col)?;
        }
        Ok(lhs)
    }

    /// `operand = { "-" | "+" } primary [ "^" operand ]`: signs bind looser than `^`
    /// (`-x^2 = -(x^2)`), `^` is right-associative (`2^3^2 = 2^9`).
    fn operand(&mut self) -> PResult<Expr> {
        let neg = self.signs()?;
        let base = self.primary()?;
        let t = self.peek()?;
        let e = if t.tok == Tok::Caret {
            let col = t.col;
            self.next()?;
            self.enter(col)?;
            let exp = self.operand()?;
            self.leave();
            let e = match exp.as_rational() {
                Some(r) => base.pow_rational(r),
                None => base.pow(exp),
            };
            self.checked(e, col)?
        } else {
            base
        };
        // An operand right after a complete operand: implicit multiplication.
        if matches!(self.peek_tok()?, Tok::Num(_) | Tok::Ident(_) | Tok::LParen) {
            return Err(self.implicit_multiplication());
        }
        Ok(if neg { -e } else { e })
    }

    #[cold]
    #[inline(never)]
    fn implicit_multiplication(&self) -> Box<SymError> {
        let t = self.peeked.as_ref().expect("peeked");
        self.error_at(t, "an operator (`+ - * / ^`) or the end of the input")
    }

    fn primary(&mut self) -> PResult<Expr> {
        let t = self.next()?;
        match t.tok {
            Tok::Num(text) => self.number(&text, t.col),
            Tok::Ident(name) => {
                if *self.peek_tok()? == Tok::LParen {
                    return self.call(&name, t.col);
                }
                self.name(&name, t.col)
            }
            Tok::LParen => {
                self.enter(t.col)?;
                let e = self.binary(1)?;
                self.expect(Tok::RParen, || {
                    format!("`)` to close the `(` at column {}", t.col)
                })?;
                self.leave();
                Ok(e)
            }
            _ => Err(self.error_at(&t, "an operand")),
        }
    }

    fn number(&self, text: &str, col: usize) -> PResult<Expr> {
        // A literal too long to repeat is cut in the middle (its length given).
        let (shown, hint) = match text.char_indices().nth(40) {
            Some(_) => (
                format!("{}…` ({} characters)", &text[..20], text.len()),
                "...".to_string(),
            ),
            None => (format!("{text}`"), text.to_string()),
        };
        match Rational::from_decimal(text) {
            Some(r) => Ok(Expr::from_rational(r)),
            None => Err(self.error(
                col,
                &format!(
                    "an exact literal of at most {MAX_BITS} bits (write `float({hint})` for a \
                     floating-point value)"
                ),
                &format!("`{shown}, which is too wide"),
            )),
        }
    }

    /// A name not followed by `(`: a parameter or a constant.
    fn name(&self, name: &str, col: usize) -> PResult<Expr> {
        if let Some(p) = self.scope.get(name) {
            return Ok(p);
        }
        match name {
            "pi" | "π" => Ok(Expr::pi()),
            "e" => Ok(Expr::e()),
            _ => Err(self.unknown_name(name, col)),
        }
    }

    #[cold]
    #[inline(never)]
    fn unknown_name(&self, name: &str, col: usize) -> Box<SymError> {
        if FUNCTIONS.contains(&name) {
            // `primary` peeked at the token after the name.
            let (at, found) = match &self.peeked {
                Some(t) if t.tok == Tok::End => (t.col, "end of input".to_string()),
                Some(t) => (t.col, format!("`{}`", t.text())),
                None => (col, String::new()),
            };
            return self.error(at, &format!("`(` after the function name `{name}`"), &found);
        }
        let known = match self.scope.lookup(name) {
            Err(SymError::UnknownParameter { known, .. }) => known,
            _ => self.scope.names(),
        };
        let expected = format!("a known parameter{}", eom_text::did_you_mean(name, &known));
        let shown = eom_text::shown(name);
        let found = if known.is_empty() {
            format!("unknown parameter `{shown}`; no parameters are declared")
        } else {
            format!(
                "unknown parameter `{shown}`; known parameters: {}",
                known.join(", ")
            )
        };
        self.error(col, &expected, &found)
    }

    /// `name(` was read up to the name (at column `col`); the `(` is next.
    fn call(&mut self, name: &str, col: usize) -> PResult<Expr> {
        if !FUNCTIONS.contains(&name) {
            return Err(self.unknown_function(name, col));
        }
        let open = self.next()?;
        self.enter(open.col)?;
        let result = if name == "float" {
            self.float_literal(col)
        } else {
            self.args(name, col)
        };
        self.leave();
        result
    }

    #[cold]
    #[inline(never)]
    fn unknown_function(&self, name: &str, col: usize) -> Box<SymError> {
        // A parameter or constant directly before `(`: implicit multiplication.
        if self.scope.get(name).is_some() || matches!(name, "pi" | "π" | "e") {
            return self.implicit_multiplication();
        }
        let hint = eom_text::did_you_mean(name, &FUNCTIONS[..]);
        self.error(
            col,
            &format!("a known function ({})", FUNCTIONS.join(", ")),
            &format!("unknown function `{name}`{hint}"),
        )
    }

    /// The arguments of function `name` (at column `col`) after its `(`.
    fn args(&mut self, name: &str, col: usize) -> PResult<Expr> {
        let two = name == "atan2";
        let takes = move || {
            if two {
                "`atan2` takes two arguments: y, x".to_string()
            } else {
                format!("`{name}` takes one argument")
            }
        };
        if *self.peek_tok()? == Tok::RParen {
            let t = self.next()?;
            return Err(self.error_at(&t, &format!("an argument ({})", takes())));
        }
        let a = self.binary(1)?;
        let e = if two {
            self.expect(Tok::Comma, || {
                format!("`,` and a second argument ({})", takes())
            })?;
            let x = self.binary(1)?;
            self.expect(Tok::RParen, || format!("`)` ({})", takes()))?;
            a.atan2(x)
        } else {
            self.expect(Tok::RParen, || format!("`)` ({})", takes()))?;
            match crate::func::Func::from_name(name) {
                Some(f) => a.apply(f),
                None => a.sqrt(),
            }
        };
        self.checked(e, col)
    }

    /// `float(` was read (the name at column `col`): `["-" | "+"] number ")"`.
    fn float_literal(&mut self, col: usize) -> PResult<Expr> {
        let expected = "a decimal literal such as `0.1` (`float(...)` takes a number)";
        let mut t = self.next()?;
        let mut negative = false;
        if matches!(t.tok, Tok::Minus | Tok::Plus) {
            negative = t.tok == Tok::Minus;
            t = self.next()?;
        }
        let Tok::Num(text) = &t.tok else {
            return Err(self.error_at(&t, expected));
        };
        // Rust's `f64` parser rounds correctly; give it the mantissa forms it accepts.
        let (mant, exp) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], &text[i..]),
            None => (text.as_str(), ""),
        };
        let mant = if mant.starts_with('.') {
            format!("0{mant}")
        } else {
            mant.to_string()
        };
        let mant = if mant.ends_with('.') {
            format!("{mant}0")
        } else {
            mant
        };
        let x: f64 = match format!("{mant}{exp}").parse() {
            Ok(x) => x,
            Err(_) => return Err(self.error_at(&t, expected)),
        };
        if !x.is_finite() {
            return Err(self.error(
                t.col,
                "a finite floating-point literal",
                &format!("`{text}`, which overflows f64"),
            ));
        }
        let x = if negative { -x } else { x };
        self.expect(Tok::RParen, || {
            format!("`)` to close the `float(` at column {col}")
        })?;
        // Straight into the pool's float constructor (finite by the check above).
        Ok(with_pool(|p| {
            let id = p.float(x);
            p.expr(id)
        }))
    }
}

#[cfg(test)]
mod tests;

/// Characters of the input a parse error repeats around its column when the input is longer
/// than that: a 10 MB expression is not echoed whole.
const ERROR_WINDOW: usize = 60;

/// The input as a parse error shows it (control characters escaped, a window of
/// [`ERROR_WINDOW`] characters around `column` when it is longer, marked by `…` and its
/// length) and the caret line under `column`.
fn error_window(input: &str, column: usize) -> (String, String) {
    let n = input.chars().count();
    let at = column.saturating_sub(1);
    let (start, end) = if n <= ERROR_WINDOW + ERROR_WINDOW / 3 {
        (0, n)
    } else {
        let start = at
            .saturating_sub(ERROR_WINDOW / 2)
            .min(n.saturating_sub(ERROR_WINDOW));
        (start, (start + ERROR_WINDOW).min(n))
    };
    let (mut shown, mut caret) = (String::new(), String::new());
    if start > 0 {
        shown.push('…');
        caret.push(' ');
    }
    let mut buf = [0u8; 4];
    for (k, c) in input.chars().enumerate().skip(start).take(end - start) {
        let text: std::borrow::Cow<'_, str> = if c == '\t' {
            "\t".into()
        } else {
            eom_text::escaped(c.encode_utf8(&mut buf))
                .into_owned()
                .into()
        };
        shown.push_str(&text);
        if k < at {
            caret.extend(text.chars().map(|x| if x == '\t' { '\t' } else { ' ' }));
        }
    }
    if end < n {
        shown.push_str(&format!("… ({n} characters)"));
    }
    caret.push('^');
    (shown, caret)
}
