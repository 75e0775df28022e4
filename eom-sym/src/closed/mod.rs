//! Closed forms of a symbolic state-space model: the characteristic polynomial, transfer
//! functions, the Hurwitz (Liénard–Chipart) stability conditions, stability boundaries solved
//! for a parameter, and the natural frequency and damping of second-order models.
//!
//! Everything is exact. Determinants are expanded by minors over the structural non-zeros
//! (memoised on the set of columns used, so an `n × n` determinant costs at most `n·2ⁿ`
//! products — fine for the small models closed forms are for), then brought into the
//! rational-function normal form of [`simplify`](crate::simplify) over the model's parameters
//! and the variable `s`: common factors cancel exactly, coefficients are polynomials in the
//! parameters. Cancellation uses rational-function semantics (see
//! [`RationalNormalizer`](crate::simplify::RationalNormalizer)): a factor such as a mass or a
//! determinant of the mass matrix, nonzero wherever the model is defined, is divided out.
//!
//! ```
//! use eom_sym::{Expr, closed::ClosedForms};
//! use nalgebra::DMatrix;
//! // Spring–mass–damper: A = [[0, 1], [−k/m, −c/m]].
//! let m = Expr::param("m", 1.0).unwrap();
//! let c = Expr::param("c", 0.1).unwrap();
//! let k = Expr::param("k", 10.0).unwrap();
//! let a = DMatrix::from_row_slice(2, 2, &[Expr::zero(), Expr::one(), -k / m, -c / m]);
//! let p = ClosedForms::default().characteristic_polynomial(&a).unwrap();
//! // det(sI − A) = (m s² + c s + k)/m
//! assert_eq!(p.polynomial.coefficients, vec![k, c, m]);
//! assert_eq!(p.scale, m);
//! ```
//!
//! When a bound of the normal form is reached (large models with many symbolic parameters),
//! the coefficients are still exact expressions — the derivatives of the determinant at
//! `s = 0` — but not normalised, and [`CharacteristicPolynomial::normalized`] says so.

mod constant_sign;
mod det;
mod hurwitz;
mod modal;
mod summary;
mod transfer;

pub use hurwitz::{Boundary, ConditionSource, StabilityCondition, hurwitz_minor};
pub use modal::SecondOrder;
pub use summary::{
    ConditionSummary, Summary, SummaryRequest, latex_boundary, latex_polynomial, shown_matrix,
};
pub use transfer::TransferFunction;

use crate::error::SymError;
use crate::expr::Expr;
use crate::simplify::RationalNormalizer;
use crate::simplify::poly::{Poly, gcd};
pub(crate) use crate::simplify::rational_fn::Rf;
use crate::simplify::rational_fn::{Fail, RationalField};
use nalgebra::DMatrix;

/// A polynomial in `s` with expression coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct SPolynomial {
    /// The coefficients of `s⁰, s¹, …, sⁿ`.
    pub coefficients: Vec<Expr>,
}

impl SPolynomial {
    /// The degree (the number of coefficients less one; `0` for a constant).
    pub fn degree(&self) -> usize {
        self.coefficients.len().saturating_sub(1)
    }

    /// The polynomial as one expression in `s`.
    pub fn to_expr(&self, s: Expr) -> Expr {
        Expr::sum(
            self.coefficients
                .iter()
                .enumerate()
                .filter(|(_, c)| !c.is_zero())
                .map(|(k, &c)| c * s.powi(k as i64)),
        )
    }
}

/// `det(sI − A) = s^zero_roots · polynomial(s) / scale`.
#[derive(Clone, Debug, PartialEq)]
pub struct CharacteristicPolynomial {
    /// The factor left when the structural zero roots and the common factor are divided out;
    /// its leading coefficient is positive wherever the parameters' declared signs decide it.
    pub polynomial: SPolynomial,
    /// The number of roots at zero that the structure proves (a factor `s^k`).
    pub zero_roots: usize,
    /// The common factor divided out of every coefficient (`1` when none was).
    pub scale: Expr,
    /// Whether the coefficients are in normal form (polynomials in the parameters, common
    /// factors cancelled); `false` when a bound was reached and the coefficients are exact
    /// but unsimplified expressions.
    pub normalized: bool,
}

/// The largest model whose closed forms [`ClosedForms::with_max_states`] can allow.
pub const MAX_CLOSED_FORM_STATES: usize = 24;

/// Closed forms with explicit bounds on the exact algebra (builder).
#[derive(Clone, Debug)]
pub struct ClosedForms {
    limits: RationalNormalizer,
    max_states: usize,
}

impl Default for ClosedForms {
    /// Polynomials of up to 20 000 terms, 5 million term operations and 30 ms per normal form,
    /// 64 atoms; models of up to 12 states.
    fn default() -> Self {
        ClosedForms {
            limits: RationalNormalizer::default()
                .with_max_terms(20_000)
                .with_max_work(5_000_000)
                .with_time_limit(std::time::Duration::from_millis(30)),
            max_states: 12,
        }
    }
}

impl ClosedForms {
    /// The bounds of the rational-function normal form.
    pub fn with_limits(mut self, limits: RationalNormalizer) -> Self {
        self.limits = limits;
        self
    }

    /// The largest model accepted, in states (the expansion by minors grows as `n·2ⁿ`; at
    /// most [`MAX_CLOSED_FORM_STATES`]).
    pub fn with_max_states(mut self, n: usize) -> Self {
        self.max_states = n;
        self
    }

    /// Refuses a model of more than `max_states` states (at most [`MAX_CLOSED_FORM_STATES`]).
    fn check_size(&self, n: usize, what: &str) -> Result<(), SymError> {
        let limit = self.max_states.min(MAX_CLOSED_FORM_STATES);
        if n > limit {
            return Err(SymError::TooManyStates {
                what: what.to_string(),
                states: n,
                limit,
            });
        }
        Ok(())
    }

    /// `det(sI − A)` in closed form.
    pub fn characteristic_polynomial(
        &self,
        a: &DMatrix<Expr>,
    ) -> Result<CharacteristicPolynomial, SymError> {
        self.pencil_polynomial(None, a)
    }

    /// `det(sI − A)` for `A = E⁻¹F`, computed as `det(sE − F)/det(E)` (`E = I` when `e` is
    /// `None`). For the descriptor form of a mechanical model (`E = diag(I, M)`) the
    /// coefficients of `det(sE − F)` have no nested divisions by the mass matrix: the closed
    /// form to show for larger models; `det(E)` goes into the scale.
    pub fn pencil_polynomial(
        &self,
        e: Option<&DMatrix<Expr>>,
        f: &DMatrix<Expr>,
    ) -> Result<CharacteristicPolynomial, SymError> {
        let n = f.nrows();
        let square = |m: &DMatrix<Expr>| m.nrows() == n && m.ncols() == n;
        if !square(f) || e.is_some_and(|e| !square(e)) {
            return Err(SymError::Dimension(format!(
                "the characteristic polynomial needs square matrices of one size, not {}×{}{}",
                f.nrows(),
                f.ncols(),
                e.map_or(String::new(), |e| format!(
                    " and {}×{}",
                    e.nrows(),
                    e.ncols()
                ))
            )));
        }
        self.check_size(n, "the characteristic polynomial")?;
        let entries: Vec<Expr> = f.iter().chain(e.into_iter().flatten()).copied().collect();
        crate::expr::in_pool_of(&entries, || {
            let coeffs = det::det_in_s(&det::pencil(e, f));
            let (mut coeffs, mut scale, normalized) = match self.normalize_coeffs(&coeffs)? {
                Some((c, scale)) => (c, scale, true),
                None => (coeffs, Expr::one(), false),
            };
            if let Some(e) = e {
                let rows: Vec<Vec<Expr>> = (0..n)
                    .map(|i| (0..n).map(|j| e[(i, j)]).collect())
                    .collect();
                let det_e = det::det(&rows);
                let product = scale * det_e;
                scale = crate::simplify::normalize_rational(product).unwrap_or(product);
            }
            let zero_roots = coeffs
                .iter()
                .take_while(|c| c.is_zero() || crate::zero::is_identically_zero(**c))
                .count()
                .min(coeffs.len().saturating_sub(1));
            coeffs.drain(..zero_roots);
            if coeffs
                .last()
                .is_some_and(|c| c.sign().is_nonpos() && !c.is_zero())
            {
                coeffs = coeffs.into_iter().map(|c| -c).collect();
                scale = -scale;
            }
            Ok(CharacteristicPolynomial {
                polynomial: SPolynomial {
                    coefficients: coeffs,
                },
                zero_roots,
                scale,
                normalized,
            })
        })
    }

    /// `cₖ = Pₖ / scale` with polynomials `Pₖ` free of common factors (`None` when a bound of
    /// the normal form is reached).
    fn normalize_coeffs(&self, coeffs: &[Expr]) -> Result<Option<(Vec<Expr>, Expr)>, SymError> {
        let Some((mut f, rfs)) = self.in_field(coeffs)? else {
            return Ok(None);
        };
        let n = f.atoms().len();
        let budget = &mut f.budget;
        // L = lcm of the denominators; Nₖ = numₖ·L/denₖ; G = gcd of the Nₖ.
        let mut lcm = Poly::one(n);
        for r in &rfs {
            let Ok(g) = gcd(&lcm, &r.den, budget) else {
                return Ok(None);
            };
            let Ok(Some(q)) = r.den.div_exact(&g, budget) else {
                return Ok(None);
            };
            let Ok(l) = lcm.mul(&q, budget) else {
                return Ok(None);
            };
            lcm = l;
        }
        let mut nums = Vec::with_capacity(rfs.len());
        let mut content = Poly::zero(n);
        for r in &rfs {
            let Ok(Some(q)) = lcm.div_exact(&r.den, budget) else {
                return Ok(None);
            };
            let Ok(x) = r.num.mul(&q, budget) else {
                return Ok(None);
            };
            let Ok(g) = gcd(&content, &x, budget) else {
                return Ok(None);
            };
            content = g;
            nums.push(x);
        }
        if content.is_zero() {
            content = Poly::one(n);
        }
        let mut out = Vec::with_capacity(nums.len());
        for x in &nums {
            let Ok(Some(p)) = x.div_exact(&content, &mut f.budget) else {
                return Ok(None);
            };
            out.push(render_poly(&mut f, &p));
        }
        let b = &mut f.budget;
        let scale = match Rf::of(content)
            .powi(-1, b)
            .and_then(|g| Rf::of(lcm).mul(&g, b))
        {
            Ok(r) => r,
            Err(_) => return Ok(None),
        };
        let scale = match f.render(&scale) {
            Ok(x) => x.to_expr(),
            Err(_) => return Ok(None),
        };
        Ok(Some((out, scale)))
    }

    /// `exprs` as rational functions over one field (`None` when a bound is reached).
    fn in_field(&self, exprs: &[Expr]) -> Result<Option<(RationalField, Vec<Rf>)>, SymError> {
        let mut field = match RationalField::new(exprs, &self.limits)? {
            Ok(f) => f,
            Err(_) => return Ok(None),
        };
        let mut out = Vec::with_capacity(exprs.len());
        for &e in exprs {
            match field.value(e) {
                Ok(r) => out.push(r),
                Err(Fail::Limit(_)) => return Ok(None),
                Err(Fail::ZeroDenominator) => {
                    return Err(SymError::DivisionByZero {
                        context: "a denominator of the model is identically zero".into(),
                    });
                }
            }
        }
        Ok(Some((field, out)))
    }

    /// The rational functions of `exprs` over one field whose atoms include `s` (`None` when a
    /// bound is reached).
    fn in_s(&self, exprs: &[Expr], s: Expr) -> Result<Option<(FieldIn, Vec<Rf>)>, SymError> {
        let Some((field, out)) = self.in_field(exprs)? else {
            return Ok(None);
        };
        let var = field.atoms().iter().position(|&x| x == s);
        Ok(Some((FieldIn { field, s: var }, out)))
    }
}

/// A polynomial of the field as an expression, its monomial content factored out.
fn render_poly(f: &mut RationalField, p: &Poly) -> Expr {
    match f.render(&Rf::of(p.clone())) {
        Ok(x) => x.to_expr(),
        Err(_) => f.poly_expr(p),
    }
}

/// A rational field and the variable index of `s` in it (`None`: `s` does not occur).
pub(crate) struct FieldIn {
    pub field: RationalField,
    pub s: Option<usize>,
}

impl FieldIn {
    /// The coefficients of the powers of `s` of a polynomial of the field.
    pub(crate) fn coeffs(&self, p: &Poly) -> Vec<Poly> {
        match self.s {
            Some(v) => p.coeffs_in(v),
            None => vec![p.clone()],
        }
    }

    /// A polynomial (without `s`) as an expression, its monomial content factored out.
    pub(crate) fn render(&mut self, p: &Poly) -> Expr {
        render_poly(&mut self.field, p)
    }
}

/// A fresh parameter `s` in the current pool (the Laplace variable).
fn variable_s() -> Result<Expr, SymError> {
    Expr::param("s", 0.0)
}
