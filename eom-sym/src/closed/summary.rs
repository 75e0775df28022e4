//! Everything the closed forms say about one model in one call: the characteristic
//! polynomial (its coefficients also factored for display), ωₙ and ζ of a second-order model,
//! the stability conditions with the boundaries solved for a parameter and the reason a
//! condition can never hold, and the transfer functions. The one home of this pipeline for
//! `eom symbolic` and the Python package, which only present it.

use super::{
    Boundary, CharacteristicPolynomial, ClosedForms, ConditionSource, SecondOrder,
    StabilityCondition, TransferFunction,
};
use crate::display::Latex;
use crate::error::SymError;
use crate::expr::{Expr, ExprView};
use crate::simplify::{Simplifier, normalize_rational};
use nalgebra::DMatrix;
use std::fmt;

/// What [`ClosedForms::summary`] computes besides the characteristic polynomial.
#[derive(Clone, Copy, Debug, Default)]
pub struct SummaryRequest {
    /// The Liénard–Chipart stability conditions.
    pub stability: bool,
    /// Solve each condition for this parameter where it is of degree ≤ 2 in it (implies
    /// `stability`).
    pub solve_for: Option<Expr>,
    /// The transfer functions of every output/input pair.
    pub transfer: bool,
}

/// One stability condition `condition.expression > 0`, as shown.
#[derive(Clone, Debug, PartialEq)]
pub struct ConditionSummary {
    /// The condition.
    pub condition: StabilityCondition,
    /// Why the model is never asymptotically stable (only when the condition can never hold).
    pub never: Option<String>,
    /// The condition's boundary solved for the requested parameter, where it allows it.
    pub boundary: Option<Boundary>,
}

/// The closed forms of a model (see [`ClosedForms::summary`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// `det(sI − A)` from the descriptor pencil.
    pub polynomial: CharacteristicPolynomial,
    /// The coefficients of `polynomial`, `s⁰` first, each factored where it factors (for
    /// display: `kf*kr*(a + b)^2`, not the expansion).
    pub shown: Vec<Expr>,
    /// ωₙ and ζ of a degree-2 polynomial.
    pub second_order: Option<SecondOrder>,
    /// The stability conditions, when requested (empty: always stable by the parameters'
    /// declared signs).
    pub conditions: Option<Vec<ConditionSummary>>,
    /// Every output/input pair's transfer function (outputs outer), coefficients factored,
    /// when requested.
    pub transfer_functions: Vec<TransferFunction>,
}

impl Summary {
    /// The stability verdict in words: `always`, `never: …`, `undecided: …` (a condition is
    /// a constant too close to zero for its sign to be decided in double precision) or `when
    /// all conditions hold` (`None` when the conditions were not requested).
    ///
    /// Conditions that are constants (every parameter substituted) are decided when they are
    /// built, by an enclosure of their exact value: a positive one is dropped, a negative one
    /// makes the verdict `never`; only a constant whose enclosure holds zero stays.
    pub fn verdict(&self) -> Option<String> {
        let conds = self.conditions.as_ref()?;
        let undecided = conds
            .iter()
            .find(|c| c.never.is_none() && c.condition.expression.params().is_empty());
        Some(match conds.iter().find_map(|c| c.never.as_deref()) {
            Some(never) => format!("never: {never}"),
            None if conds.is_empty() => "always".into(),
            None => match undecided {
                Some(c) => format!(
                    "undecided: the {} condition is a constant (≈ {:.3e}) too close to zero \
                     to decide its sign in double precision",
                    c.condition.source,
                    c.condition.expression.nominal()
                ),
                None => "when all conditions hold".into(),
            },
        })
    }
}

impl fmt::Display for ConditionSource {
    /// `coefficient k` or `hurwitz k`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConditionSource::Coefficient(k) => write!(f, "coefficient {k}"),
            ConditionSource::HurwitzMinor(k) => write!(f, "hurwitz {k}"),
        }
    }
}

impl ClosedForms {
    /// The closed forms of the model `A = E⁻¹F` with input, output and feedthrough matrices
    /// `b`, `c`, `d`: the polynomial from the pencil `(E, F)` (no nested divisions by the
    /// mass matrix), the transfer functions from `a`, `b`, `c`, `d`.
    pub fn summary(
        &self,
        (e, f): (&DMatrix<Expr>, &DMatrix<Expr>),
        [a, b, c, d]: [&DMatrix<Expr>; 4],
        req: &SummaryRequest,
    ) -> Result<Summary, SymError> {
        let p = self.pencil_polynomial(Some(e), f)?;
        let shown = self.factored_all(&p.polynomial.coefficients);
        let second_order = self.second_order(&p)?;
        let conditions = if req.stability || req.solve_for.is_some() {
            let coefficients = &p.polynomial.coefficients;
            let mut out = Vec::new();
            for condition in self.stability_conditions(&p)? {
                if !condition.satisfiable {
                    out.push(ConditionSummary {
                        never: Some(never_reason(&condition, coefficients)),
                        condition,
                        boundary: None,
                    });
                    continue;
                }
                let boundary = match req.solve_for {
                    Some(x) => self.solve_boundary(condition.expression, x)?,
                    None => None,
                };
                out.push(ConditionSummary {
                    condition,
                    never: None,
                    boundary,
                });
            }
            Some(out)
        } else {
            None
        };
        let mut transfer_functions = Vec::new();
        if req.transfer {
            for out in 0..c.nrows() {
                for inp in 0..b.ncols() {
                    let mut tf = self.transfer_function([a, b, c, d], out, inp)?;
                    tf.numerator.coefficients = self.factored_all(&tf.numerator.coefficients);
                    tf.denominator.coefficients = self.factored_all(&tf.denominator.coefficients);
                    transfer_functions.push(tf);
                }
            }
        }
        Ok(Summary {
            polynomial: p,
            shown,
            second_order,
            conditions,
            transfer_functions,
        })
    }

    /// Each expression factored where it factors.
    pub fn factored_all(&self, c: &[Expr]) -> Vec<Expr> {
        c.iter().map(|&x| self.factored(x).unwrap_or(x)).collect()
    }
}

/// Why a condition that can never hold fails, in words.
fn never_reason(c: &StabilityCondition, coefficients: &[Expr]) -> String {
    match c.source {
        ConditionSource::Coefficient(k) if c.expression.is_zero() => {
            // A mechanical system without damping has only even powers of s.
            let undamped = coefficients
                .iter()
                .enumerate()
                .all(|(j, x)| j % 2 == 0 || x.is_zero());
            format!(
                "the s^{k} coefficient vanishes{}",
                if undamped { " (no damping)" } else { "" }
            )
        }
        ConditionSource::Coefficient(k) => {
            format!("the s^{k} coefficient is negative for all parameter values")
        }
        ConditionSource::HurwitzMinor(k) => {
            format!("the Hurwitz determinant Δ{k} is negative for all parameter values")
        }
    }
}

/// A matrix of closed forms as shown: `map` substituted (parameters fixed at exact values),
/// then the bounded e-graph simplification, and per entry the rational normal form where it
/// is shorter still.
pub fn shown_matrix(m: &DMatrix<Expr>, map: &[(Expr, Expr)]) -> Result<DMatrix<Expr>, SymError> {
    let entries: Vec<Expr> = m.iter().copied().collect();
    let substituted = if map.is_empty() {
        entries
    } else {
        crate::subs::subs_many(&entries, map)?
    };
    let simplified = if substituted.iter().all(|e| e.is_number() || e.is_zero()) {
        substituted
    } else {
        let egg = Simplifier::default().run(&substituted)?.roots;
        egg.into_iter()
            .map(|e| match normalize_rational(e) {
                Ok(r) if Expr::op_count(&[r]).total() < Expr::op_count(&[e]).total() => r,
                _ => e,
            })
            .collect()
    };
    Ok(DMatrix::from_column_slice(
        m.nrows(),
        m.ncols(),
        &simplified,
    ))
}

/// `cₙ sⁿ + … + c₀` in LaTeX, highest power first (`c` holds `s⁰` first).
pub fn latex_polynomial(c: &[Expr]) -> String {
    let mut t = String::new();
    for (k, &x) in c.iter().enumerate().rev() {
        if x.is_zero() {
            continue;
        }
        let (neg, x) = if x.sign().is_nonpos() && x.as_f64().is_some() {
            (true, -x)
        } else {
            (false, x)
        };
        let coef = Latex(x).to_string();
        let coef = if k > 0 && x.is_one() {
            String::new()
        } else if k > 0 && matches!(x.view(), ExprView::Sum { .. }) {
            format!("\\left({coef}\\right)")
        } else {
            coef
        };
        let power = match k {
            0 => String::new(),
            1 => "s".to_string(),
            _ => format!("s^{{{k}}}"),
        };
        let sep = if coef.is_empty() || power.is_empty() {
            ""
        } else {
            " "
        };
        let sign = match (t.is_empty(), neg) {
            (true, true) => "-",
            (true, false) => "",
            (false, true) => " - ",
            (false, false) => " + ",
        };
        t.push_str(&format!("{sign}{coef}{sep}{power}"));
    }
    if t.is_empty() { "0".into() } else { t }
}

/// The boundary `x ∈ {r₁, r₂}` in LaTeX.
pub fn latex_boundary(b: &Boundary) -> String {
    let roots: Vec<String> = b.roots.iter().map(|r| Latex(*r).to_string()).collect();
    format!("{} \\in \\{{{}\\}}", Latex(b.parameter), roots.join(", "))
}
