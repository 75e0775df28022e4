//! Stability conditions in closed form (Liénard–Chipart) and boundaries solved for a parameter.

use super::{CharacteristicPolynomial, ClosedForms, det};
use crate::error::SymError;
use crate::expr::Expr;
use crate::rational::Rational;
use crate::simplify::poly::{Poly, content_in, square_free};
use crate::simplify::rational_fn::{Fail, RationalField, Rf};

/// Where a stability condition comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConditionSource {
    /// The coefficient of `sᵏ` must be positive; where the declared signs leave the leading
    /// coefficient's sign open, it must have the leading coefficient's sign (the condition is
    /// the product of the two).
    Coefficient(usize),
    /// The Hurwitz determinant `Δₖ` must be positive.
    HurwitzMinor(usize),
}

/// One condition `expression > 0` of asymptotic stability.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityCondition {
    /// Positive exactly where the condition holds (together with the conditions before it).
    pub expression: Expr,
    /// The coefficient or Hurwitz determinant it comes from.
    pub source: ConditionSource,
    /// Factors of known sign that were divided out: by the parameters' declared signs, or
    /// because an earlier condition makes them positive.
    pub divided_out: Vec<Expr>,
    /// `false` when the condition can never hold (the polynomial is unstable for every value
    /// of the parameters); `expression` is then `−1`.
    pub satisfiable: bool,
}

/// The values of a parameter where a condition changes sign.
#[derive(Clone, Debug, PartialEq)]
pub struct Boundary {
    /// The parameter solved for.
    pub parameter: Expr,
    /// One root (a condition linear in the parameter) or two (`centre ∓ √radius²`).
    pub roots: Vec<Expr>,
}

impl ClosedForms {
    /// The Liénard–Chipart conditions of asymptotic stability of `p.polynomial`: every
    /// coefficient positive, and the Hurwitz determinants `Δₙ₋₁, Δₙ₋₃, …` positive. Together
    /// they hold exactly where every root of the polynomial has a negative real part (the roots
    /// at zero that the structure proves, `p.zero_roots`, are not part of it).
    ///
    /// Each condition is simplified: its factors whose sign the parameters' declared ranges
    /// fix (`m > 0`, …) are divided out, and so are factors that an earlier condition proves
    /// positive (once `u > 0` is a condition, a later factor `u` is dropped).
    pub fn stability_conditions(
        &self,
        p: &CharacteristicPolynomial,
    ) -> Result<Vec<StabilityCondition>, SymError> {
        let a = &p.polynomial.coefficients;
        let n = a.len().saturating_sub(1);
        // A coefficient that vanishes identically (below the leading one) can never be
        // positive: no parameter values make the polynomial stable, and that is all to say.
        if let Some(k) = (0..n).find(|&k| a[k].is_zero()) {
            return Ok(vec![StabilityCondition {
                expression: Expr::zero(),
                source: ConditionSource::Coefficient(k),
                divided_out: Vec::new(),
                satisfiable: false,
            }]);
        }
        let mut raw: Vec<(ConditionSource, Expr)> = Vec::new();
        for k in (0..=n).rev() {
            raw.push((ConditionSource::Coefficient(k), a[k]));
        }
        let mut k = n.saturating_sub(1);
        while k >= 2 {
            raw.push((ConditionSource::HurwitzMinor(k), hurwitz_minor(a, k)));
            k = k.saturating_sub(2);
        }
        let exprs: Vec<Expr> = raw.iter().map(|(_, e)| *e).collect();
        crate::expr::in_pool_of(&exprs, || {
            let mut field = RationalField::new(&exprs, &self.limits)?.ok();
            let mut factored: Vec<(ConditionSource, Vec<Factor>)> = raw
                .into_iter()
                .map(|(source, e)| {
                    let f = match field.as_mut() {
                        Some(f) => factors_of(f, e).unwrap_or_else(|| vec![Factor::of(e)]),
                        None => vec![Factor::of(e)],
                    };
                    (source, f)
                })
                .collect();
            scale_by_leading(&mut factored, n);
            // Simplest first, so that a condition such as `u > 0` is established before the
            // longer ones that carry the factor `u`.
            factored.sort_by_key(|(_, f)| {
                let open: Vec<Expr> = f
                    .iter()
                    .filter(|x| x.sign != Some(true))
                    .map(|x| x.expr)
                    .collect();
                (open.len(), Expr::dag_size(&open))
            });
            let mut known: Vec<Expr> = Vec::new();
            let mut out: Vec<StabilityCondition> = Vec::new();
            for (source, factors) in factored {
                if let Some(c) = condition(source, factors, &mut known)
                    && !out.iter().any(|o| o.expression == c.expression)
                {
                    out.push(c);
                }
            }
            Ok(out)
        })
    }

    /// `e` as the product of its factors: the numeric content, the parameters dividing every
    /// term, the contents with respect to each parameter and the square-free parts, each
    /// power once (`kf*kr*(a + b)^2`, not its expansion). `e` itself when nothing factors or
    /// a bound of the exact algebra is reached.
    pub fn factored(&self, e: Expr) -> Result<Expr, SymError> {
        if e.is_number() || e.param_index().is_some() {
            return Ok(e);
        }
        crate::expr::in_pool_of(&[e], || {
            let Ok(mut field) = RationalField::new(&[e], &self.limits)? else {
                return Ok(e);
            };
            Ok(match factors_of(&mut field, e) {
                Some(f) if f.len() > 1 => Expr::product(f.iter().map(|x| x.expr)),
                _ => e,
            })
        })
    }

    /// Where `condition` changes sign as a function of the parameter `x`, when its numerator
    /// is a polynomial of degree 1 or 2 in `x` (`None` otherwise).
    pub fn solve_boundary(&self, condition: Expr, x: Expr) -> Result<Option<Boundary>, SymError> {
        if x.param_index().is_none() {
            return Err(SymError::BadParameter {
                name: x.to_string(),
                problem: "a boundary is solved for a parameter".into(),
            });
        }
        crate::expr::in_pool_of(&[condition, x], || {
            let Ok(mut field) = RationalField::new(&[condition, x], &self.limits)? else {
                return Ok(None);
            };
            let Ok(rf) = field.value(condition) else {
                return Ok(None);
            };
            let Some(v) = field.atoms().iter().position(|&a| a == x) else {
                return Ok(None);
            };
            let c = rf.num.coeffs_in(v);
            let roots = match c.len() {
                2 => linear_root(&mut field, &c),
                3 => quadratic_roots(&mut field, &c),
                _ => None,
            };
            Ok(roots.map(|roots| Boundary {
                parameter: x,
                roots,
            }))
        })
    }
}

/// Where the declared signs leave the leading coefficient `aₙ`'s sign open, the conditions
/// are those of the polynomial divided by `aₙ`: `aₖ/aₙ > 0` becomes `aₖ·aₙ > 0`, and
/// `Δₖ(a/aₙ) = Δₖ(a)/aₙᵏ > 0` becomes `Δₖ·aₙ > 0` for odd `k` (even `k` keep `Δₖ > 0`);
/// `aₙ > 0` itself is no condition (`m s² + c s + k` is as stable with `m, c, k < 0`). A factor
/// of `aₙ` already in a condition cancels (`x·x > 0` only excludes `x = 0`, where the degree
/// drops). Where `aₙ`'s sign is known nothing changes.
fn scale_by_leading(factored: &mut Vec<(ConditionSource, Vec<Factor>)>, n: usize) {
    let Some(at) = factored
        .iter()
        .position(|(s, _)| *s == ConditionSource::Coefficient(n))
    else {
        return;
    };
    if n == 0 || factored[at].1.iter().all(|f| f.sign.is_some()) {
        return;
    }
    let (_, lead) = factored.remove(at);
    for (source, factors) in factored.iter_mut() {
        if matches!(source, ConditionSource::HurwitzMinor(k) if *k % 2 == 0) {
            continue;
        }
        for f in &lead {
            match factors.iter().position(|x| x.expr == f.expr) {
                Some(i) => {
                    factors.remove(i);
                }
                None => factors.push(*f),
            }
        }
        if factors.is_empty() {
            factors.push(Factor::of(Expr::one()));
        }
    }
}

/// The Hurwitz determinant `Δₖ` of `a₀ + a₁s + … + aₙsⁿ` (`a` lowest first): the leading
/// `k × k` minor of the matrix with entries `H[i][j] = a(n − 2j + i)` (1-based, zero outside
/// `0..=n`), expanded by minors, unsimplified (the form code generation evaluates).
pub fn hurwitz_minor(a: &[Expr], k: usize) -> Expr {
    let n = a.len() as i64 - 1;
    let entry = |i: usize, j: usize| -> Expr {
        let idx = n - 2 * (j as i64 + 1) + (i as i64 + 1);
        if (0..=n).contains(&idx) {
            a[idx as usize]
        } else {
            Expr::zero()
        }
    };
    let m: Vec<Vec<Expr>> = (0..k)
        .map(|i| (0..k).map(|j| entry(i, j)).collect())
        .collect();
    det::det(&m)
}

/// A factor of a condition, with its sign when its terms fix it.
#[derive(Clone, Copy, Debug)]
struct Factor {
    expr: Expr,
    /// `Some(true)`: positive for all parameter values allowed (every term a product of
    /// positive atoms with a positive coefficient, or its sign known otherwise);
    /// `Some(false)`: negative likewise; `None`: not known.
    sign: Option<bool>,
}

impl Factor {
    fn of(expr: Expr) -> Factor {
        let s = expr.sign();
        let sign = if s.is_positive() {
            Some(true)
        } else if s.is_nonpos() && s.is_nonzero() {
            Some(false)
        } else {
            // A constant (every parameter substituted) by its enclosure.
            super::constant_sign::constant_sign(expr)
        };
        Factor { expr, sign }
    }
}

/// The factors of `e` (numerator and denominator): numeric content, atoms of the monomial
/// content, contents with respect to each variable, and the square-free parts of the
/// primitive rest, a factor of multiplicity k given k times (`None` when a bound is reached).
fn factors_of(f: &mut RationalField, e: Expr) -> Option<Vec<Factor>> {
    let rf = match f.value(e) {
        Ok(r) => r,
        Err(Fail::Limit(_) | Fail::ZeroDenominator) => return None,
    };
    let mut polys = Vec::new();
    split(f, &rf.num, &mut polys)?;
    if !rf.den.is_constant() {
        split(f, &rf.den, &mut polys)?;
    }
    let positive: Vec<bool> = f.atoms().iter().map(|a| a.sign().is_positive()).collect();
    Some(
        polys
            .iter()
            .map(|p| {
                let mut x = Factor::of(render(f, p));
                // Every term a product of positive atoms: the sign of the coefficients.
                if x.sign.is_none() && p.vars().iter().zip(&positive).all(|(&v, &pos)| !v || pos) {
                    if p.terms.iter().all(|t| t.1.signum() > 0) {
                        x.sign = Some(true);
                    } else if p.terms.iter().all(|t| t.1.is_negative()) {
                        x.sign = Some(false);
                    }
                }
                x
            })
            .collect(),
    )
}

/// Appends the factors of `p` to `out`.
fn split(f: &mut RationalField, p: &Poly, out: &mut Vec<Poly>) -> Option<()> {
    let n = p.nvars;
    if p.is_zero() {
        out.push(p.clone());
        return Some(());
    }
    let lc = p.lc();
    if !lc.is_one() {
        out.push(Poly::constant(n, lc));
    }
    let p = p.monic(&mut f.budget).ok()?;
    let m = p.monomial_content();
    for (v, &k) in m.iter().enumerate() {
        for _ in 0..k {
            out.push(Poly::var(n, v));
        }
    }
    let mut rest = p.div_monomial(&m);
    for v in 0..n {
        if !rest.vars()[v] {
            continue;
        }
        let c = content_in(&rest, v, &mut f.budget).ok()?;
        if !c.is_constant() {
            rest = rest.div_exact(&c, &mut f.budget).ok()??;
            split(f, &c, out)?;
        }
    }
    if let Some(v) = (0..n).find(|&v| rest.vars()[v]) {
        // Every factor left involves every variable of `rest`: its square-free parts.
        for (q, k) in square_free(&rest, v, &mut f.budget).ok()? {
            for _ in 0..k {
                out.push(q.clone());
            }
        }
    }
    Some(())
}

fn render(f: &mut RationalField, p: &Poly) -> Expr {
    let rf = Rf {
        num: p.clone(),
        den: Poly::one(p.nvars),
    };
    match f.render(&rf) {
        Ok(x) => x.to_expr(),
        Err(_) => f.poly_expr(p),
    }
}

/// The condition `Π factors > 0` with the factors of known sign divided out (`None` when
/// nothing is left to require).
fn condition(
    source: ConditionSource,
    factors: Vec<Factor>,
    known: &mut Vec<Expr>,
) -> Option<StabilityCondition> {
    let mut negative = false;
    let mut kept = Vec::new();
    let mut dropped = Vec::new();
    for Factor { expr: x, sign } in factors {
        if sign == Some(true) || known.contains(&x) {
            dropped.push(x);
        } else if sign == Some(false) || known.contains(&-x) {
            negative = !negative;
            dropped.push(x);
        } else {
            kept.push(x);
        }
    }
    if kept.is_empty() {
        return negative.then(|| StabilityCondition {
            expression: Expr::int(-1),
            source,
            divided_out: dropped,
            satisfiable: false,
        });
    }
    let mut expression = Expr::product(kept.iter().copied());
    if negative {
        expression = -expression;
    }
    if kept.len() == 1 && !negative && kept[0].param_index().is_some() {
        known.push(kept[0]);
    }
    Some(StabilityCondition {
        expression,
        source,
        divided_out: dropped,
        satisfiable: true,
    })
}

/// `x = −c₀/c₁`.
fn linear_root(f: &mut RationalField, c: &[Poly]) -> Option<Vec<Expr>> {
    let n = c[0].nvars;
    let b = &mut f.budget;
    let r = Rf {
        num: c[0].neg(),
        den: Poly::one(n),
    }
    .mul(&Rf::of(c[1].clone()).powi(-1, b).ok()?, b)
    .ok()?;
    Some(vec![render_rf(f, &r)])
}

/// `x = −c₁/(2c₂) ∓ √((c₁² − 4c₂c₀)/(4c₂²))`.
fn quadratic_roots(f: &mut RationalField, c: &[Poly]) -> Option<Vec<Expr>> {
    let n = c[0].nvars;
    let two = Rf::of(Poly::constant(n, Rational::int(2)));
    let four = Rf::of(Poly::constant(n, Rational::int(4)));
    let (c0, c1, c2) = (
        Rf::of(c[0].clone()),
        Rf::of(c[1].clone()),
        Rf::of(c[2].clone()),
    );
    let b = &mut f.budget;
    let inv_2c2 = two.mul(&c2, b).ok()?.powi(-1, b).ok()?;
    let centre = c1.neg().mul(&inv_2c2, b).ok()?;
    let disc = c1
        .mul(&c1, b)
        .ok()?
        .add(&four.mul(&c2, b).ok()?.mul(&c0, b).ok()?.neg(), b)
        .ok()?;
    let radius2 = disc.mul(&inv_2c2, b).ok()?.mul(&inv_2c2, b).ok()?;
    let centre = render_rf(f, &centre);
    let radius = render_rf(f, &radius2).sqrt();
    Some(vec![centre - radius, centre + radius])
}

fn render_rf(f: &mut RationalField, r: &Rf) -> Expr {
    match f.render(r) {
        Ok(x) => x.to_expr(),
        Err(_) => f.poly_expr(&r.num) / f.poly_expr(&r.den),
    }
}
