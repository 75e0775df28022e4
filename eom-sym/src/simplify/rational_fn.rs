//! Rational-function normal form `P/Q` for small closed forms.

use super::poly::{Budget, Poly, gcd};
use crate::error::SymError;
use crate::expr::{Expr, ExprView};
use crate::rational::Rational;
use hashbrown::{HashMap, HashSet};

/// Which bound of a [`RationalNormalizer`] was reached.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WorkLimit {
    /// An intermediate polynomial had more terms than allowed.
    Terms,
    /// An exponent exceeded the degree bound.
    Degree,
    /// The number of elementary term operations exceeded the work bound.
    Work,
    /// An exact coefficient grew wider than [`MAX_BITS`](crate::rational::MAX_BITS).
    Coefficients,
    /// The time limit was reached.
    Time,
    /// The expression has more atoms (parameters and opaque subterms) than allowed.
    Atoms,
}

/// `coefficient · numerator / denominator` with coprime polynomials.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalForm {
    /// The numerator, including its numeric coefficient (a polynomial in the atoms, with its
    /// monomial content factored out as a product when it has one).
    pub numerator: Expr,
    /// The denominator: monic (leading coefficient 1 in lexicographic order of the atoms by
    /// pool id), `1` when the expression is a polynomial.
    pub denominator: Expr,
}

impl RationalForm {
    /// `numerator / denominator` as one expression.
    pub fn to_expr(&self) -> Expr {
        if self.denominator.is_one() {
            self.numerator
        } else {
            self.numerator * self.denominator.recip()
        }
    }
}

/// The result of [`RationalNormalizer::normalize`].
#[derive(Clone, Debug, PartialEq)]
pub enum Normalized {
    /// The normal form.
    Form(RationalForm),
    /// A bound was reached; the input should be used unchanged.
    TooLarge(WorkLimit),
}

/// Rational-function normal form with explicit bounds (builder).
///
/// An expression built from sums, products and integer powers of *atoms* — parameters,
/// named constants, floating-point constants and every other subterm (functions, `atan2`,
/// general powers), which is treated as an opaque symbol — is written as `P/Q` with `P`, `Q`
/// polynomials over ℚ in the atoms, their gcd cancelled, `Q` monic. A rational power
/// `x^(p/q)` is the `p`-th power of the atom `x^(1/q)`.
///
/// # Semantics: where the denominator is nonzero
///
/// This is the standard rational-function semantics of computer algebra: `(a² − b²)/(a − b)`
/// **is** `a + b`, although the left side is undefined at `a = b`. The normal form agrees
/// with the input wherever the input is defined, and it may be defined at more points (where a
/// cancelled common factor vanishes). That is unlike the pool's smart constructors and the
/// [`Simplifier`](super::Simplifier), which never cancel a factor that may vanish. Use it for
/// closed forms whose denominators are known to be nonzero (masses, lengths, determinants of
/// regular matrices).
///
/// # Bounds
///
/// Expansion can blow up (`(a + b + c)^20`), so terms per polynomial, exponents and the total
/// number of elementary term operations are bounded; reaching a bound gives
/// [`Normalized::TooLarge`] promptly instead of hanging.
#[derive(Clone, Debug)]
pub struct RationalNormalizer {
    max_terms: usize,
    max_degree: u32,
    max_work: u64,
    max_atoms: usize,
    max_time: Option<std::time::Duration>,
}

impl Default for RationalNormalizer {
    /// 2 000 terms per polynomial, exponents up to 64, 5 million term operations, 64 atoms.
    fn default() -> Self {
        RationalNormalizer {
            max_terms: 2_000,
            max_degree: 64,
            max_work: 5_000_000,
            max_atoms: 64,
            max_time: None,
        }
    }
}

impl RationalNormalizer {
    /// Most terms any intermediate polynomial may have.
    pub fn with_max_terms(mut self, n: usize) -> Self {
        self.max_terms = n;
        self
    }
    /// Largest exponent of one atom.
    pub fn with_max_degree(mut self, d: u32) -> Self {
        self.max_degree = d;
        self
    }
    /// Most elementary term operations (multiplications and additions of terms).
    pub fn with_max_work(mut self, w: u64) -> Self {
        self.max_work = w;
        self
    }
    /// Most atoms (variables of the polynomials).
    pub fn with_max_atoms(mut self, n: usize) -> Self {
        self.max_atoms = n;
        self
    }
    /// A wall-clock bound on one normalisation (none by default).
    pub fn with_time_limit(mut self, t: std::time::Duration) -> Self {
        self.max_time = Some(t);
        self
    }

    /// The normal form of `e`. Errors: `e` is invalid, or a denominator is identically zero as
    /// a rational function (e.g. `1/((a+b)² − a² − 2ab − b²)`), which means the input is
    /// nowhere defined.
    pub fn normalize(&self, e: Expr) -> Result<Normalized, SymError> {
        let field = match RationalField::new(&[e], self)? {
            Ok(f) => f,
            Err(l) => return Ok(Normalized::TooLarge(l)),
        };
        let mut field = field;
        let rf = match field.value(e) {
            Ok(r) => r,
            Err(Fail::Limit(l)) => return Ok(Normalized::TooLarge(l)),
            Err(Fail::ZeroDenominator) => return Err(zero_denominator()),
        };
        Ok(match field.render(&rf) {
            Ok(f) => Normalized::Form(f),
            Err(l) => Normalized::TooLarge(l),
        })
    }
}

/// Expressions as rational functions over one shared set of atoms: every sum and product
/// reachable from the roots is converted once (bottom-up), so that several results (the
/// coefficients of a polynomial, the entries of a matrix) can be combined exactly.
pub(crate) struct RationalField {
    atoms: Vec<Expr>,
    var: HashMap<Expr, usize>,
    lcm: HashMap<Expr, i64>,
    opaque: HashSet<Expr>,
    memo: HashMap<Expr, Rf>,
    pub(crate) budget: Budget,
}

impl RationalField {
    /// The atoms of `roots` and the values of all their inner nodes. The outer error is an
    /// invalid root or a denominator that is identically zero; the inner one a bound.
    pub(crate) fn new(
        roots: &[Expr],
        limits: &RationalNormalizer,
    ) -> Result<Result<RationalField, WorkLimit>, SymError> {
        for e in roots {
            e.check().map_err(|err| SymError::Invalid(Box::new(err)))?;
        }
        let (inner, opaque, lcm) = match walk(roots, limits) {
            Ok(w) => w,
            Err(l) => return Ok(Err(l)),
        };
        // An opaque x that also appears as x^(p/q) is written (x^(1/L))^L, L the lcm of those q:
        // x ≥ 0 wherever the input is defined (a rational power of a negative number has no
        // real value in the pool's evaluation), and there the identity holds.
        let mut atoms: Vec<Expr> = opaque
            .iter()
            .map(|&x| lcm.get(&x).map_or(x, |&l| root(x, l)))
            .collect();
        atoms.sort();
        atoms.dedup();
        let var: HashMap<Expr, usize> = atoms.iter().enumerate().map(|(i, &a)| (a, i)).collect();
        let mut field = RationalField {
            atoms,
            var,
            lcm,
            opaque,
            memo: HashMap::new(),
            budget: Budget {
                max_terms: limits.max_terms,
                max_degree: limits.max_degree,
                max_work: limits.max_work,
                work: 0,
                deadline: limits.max_time.map(|t| std::time::Instant::now() + t),
            },
        };
        // 2. Bottom-up in pool order (children before parents).
        let mut order: Vec<Expr> = inner.into_iter().collect();
        order.sort();
        for x in order {
            match field.step(x) {
                Ok(r) => {
                    field.memo.insert(x, r);
                }
                Err(Fail::Limit(l)) => return Ok(Err(l)),
                Err(Fail::ZeroDenominator) => return Err(zero_denominator()),
            }
        }
        Ok(Ok(field))
    }

    /// The atoms, in variable order.
    pub(crate) fn atoms(&self) -> &[Expr] {
        &self.atoms
    }

    /// `x^(p/q)` for an opaque `x`: `(x^(1/L))^(p·L/q)` when x carries root denominators
    /// (q divides L), the atom `x^(1/q)` to the `p` otherwise (only for q = 1 or a
    /// non-opaque base under a root, which is its own atom).
    fn atom_power(&mut self, x: Expr, p: i64, q: i64) -> Result<Rf, Fail> {
        let (a, k) = match self.lcm.get(&x) {
            Some(&l) => (
                root(x, l),
                p.checked_mul(l / q).ok_or(Fail::Limit(WorkLimit::Degree))?,
            ),
            None => (root(x, q), p),
        };
        let n = self.atoms.len();
        let i = *self.var.get(&a).ok_or(Fail::Limit(WorkLimit::Atoms))?;
        Rf {
            num: Poly::var(n, i),
            den: Poly::one(n),
        }
        .powi(k, &mut self.budget)
    }

    /// The value of `x`: a number, an atom, or an inner node already converted.
    pub(crate) fn value(&mut self, x: Expr) -> Result<Rf, Fail> {
        let n = self.atoms.len();
        if let Some(r) = self.memo.get(&x) {
            return Ok(r.clone());
        }
        if let Some(r) = x.as_rational() {
            return Ok(Rf {
                num: Poly::constant(n, r),
                den: Poly::one(n),
            });
        }
        if self.opaque.contains(&x) {
            return self.atom_power(x, 1, 1);
        }
        // Every inner node is evaluated after its children (pool ids are topological).
        Err(Fail::Limit(WorkLimit::Work))
    }

    fn step(&mut self, x: Expr) -> Result<Rf, Fail> {
        match x.view() {
            ExprView::Sum { constant, terms } => {
                let mut acc = self.value(constant)?;
                for (t, c) in terms {
                    let term = self.value(t)?.mul(&self.value(c)?, &mut self.budget)?;
                    acc = acc.add(&term, &mut self.budget)?;
                }
                Ok(acc)
            }
            ExprView::Product { coef, factors } => {
                let mut acc = self.value(coef)?;
                for (b, r) in factors {
                    let (p, q) = r.as_small().ok_or(Fail::Limit(WorkLimit::Degree))?;
                    let f = if is_opaque(b) {
                        self.atom_power(b, p, q)?
                    } else if q == 1 {
                        self.value(b)?.powi(p, &mut self.budget)?
                    } else {
                        self.atom_power(root(b, q), p, 1)?
                    };
                    acc = acc.mul(&f, &mut self.budget)?;
                }
                Ok(acc)
            }
            _ => Err(Fail::Limit(WorkLimit::Work)),
        }
    }

    /// `rf` as a [`RationalForm`] through the pool.
    pub(crate) fn render(&mut self, rf: &Rf) -> Result<RationalForm, WorkLimit> {
        rf.to_form(&self.atoms, &mut self.budget)
    }

    /// A polynomial of the field as an expression.
    pub(crate) fn poly_expr(&self, p: &Poly) -> Expr {
        poly_expr(p, &self.atoms)
    }
}

/// 1. The rational structure of `roots`: inner nodes (sums, products), opaque atoms, and for
///    every atom the lcm of the denominators of the rational exponents it carries.
#[allow(clippy::type_complexity)]
fn walk(
    roots: &[Expr],
    limits: &RationalNormalizer,
) -> Result<(HashSet<Expr>, HashSet<Expr>, HashMap<Expr, i64>), WorkLimit> {
    let mut inner: HashSet<Expr> = HashSet::new();
    let mut opaque: HashSet<Expr> = HashSet::new();
    let mut lcm: HashMap<Expr, i64> = HashMap::new();
    let mut stack = roots.to_vec();
    while let Some(x) = stack.pop() {
        if inner.contains(&x) || opaque.contains(&x) {
            continue;
        }
        match x.view() {
            ExprView::Rational(_) => {}
            ExprView::Sum { constant, terms } => {
                inner.insert(x);
                stack.push(constant);
                for (t, c) in terms {
                    stack.push(t);
                    stack.push(c);
                }
            }
            ExprView::Product { coef, factors } => {
                inner.insert(x);
                stack.push(coef);
                for (b, r) in factors {
                    let q = match r.as_small() {
                        Some((_, q)) => q,
                        None => return Err(WorkLimit::Degree),
                    };
                    if q > 1 && !is_opaque(b) {
                        // A sum, product or number under a root: the root is the atom.
                        opaque.insert(root(b, q));
                    } else {
                        stack.push(b);
                    }
                    if q > 1 && is_opaque(b) {
                        let l = lcm.entry(b).or_insert(1);
                        *l = num_integer::lcm(*l, q);
                        if *l > i64::from(limits.max_degree) {
                            return Err(WorkLimit::Degree);
                        }
                    }
                }
            }
            _ => {
                opaque.insert(x);
            }
        }
        if opaque.len() > limits.max_atoms {
            return Err(WorkLimit::Atoms);
        }
    }
    Ok((inner, opaque, lcm))
}

/// Parameters, constants, floats, functions, `atan2` and general powers: the symbols of the
/// polynomials.
fn is_opaque(x: Expr) -> bool {
    !matches!(
        x.view(),
        ExprView::Rational(_) | ExprView::Sum { .. } | ExprView::Product { .. }
    )
}

/// `x^(1/q)` through the pool.
fn root(x: Expr, q: i64) -> Expr {
    match Rational::new(1, q) {
        Some(r) => x.pow_rational(r),
        None => x,
    }
}

fn zero_denominator() -> SymError {
    SymError::DivisionByZero {
        context: "a denominator is identically zero as a rational function".into(),
    }
}

/// Rational-function normal form with the default bounds; the input comes back unchanged when
/// a bound is reached. See [`RationalNormalizer`] for the semantics (cancellation is valid
/// where the denominator is nonzero).
///
/// ```
/// use eom_sym::{Expr, simplify::normalize_rational};
/// let a = Expr::param("a", 1.0).unwrap();
/// let b = Expr::param("b", 2.0).unwrap();
/// let e = (a.powi(2) - b.powi(2)) / (a - b);
/// assert_eq!(normalize_rational(e).unwrap(), a + b);
/// ```
pub fn normalize_rational(e: Expr) -> Result<Expr, SymError> {
    match RationalNormalizer::default().normalize(e)? {
        Normalized::Form(f) => Ok(f.to_expr()),
        Normalized::TooLarge(_) => Ok(e),
    }
}

pub(crate) enum Fail {
    Limit(WorkLimit),
    ZeroDenominator,
}

impl From<WorkLimit> for Fail {
    fn from(l: WorkLimit) -> Fail {
        Fail::Limit(l)
    }
}

/// `num/den`, coprime, `den` monic.
#[derive(Clone, Debug)]
pub(crate) struct Rf {
    pub(crate) num: Poly,
    pub(crate) den: Poly,
}

impl Rf {
    /// A polynomial as a rational function.
    pub(crate) fn of(p: Poly) -> Rf {
        let n = p.nvars;
        Rf {
            num: p,
            den: Poly::one(n),
        }
    }

    /// `−self`.
    pub(crate) fn neg(&self) -> Rf {
        Rf {
            num: self.num.neg(),
            den: self.den.clone(),
        }
    }

    pub(crate) fn zero(n: usize) -> Rf {
        Rf {
            num: Poly::zero(n),
            den: Poly::one(n),
        }
    }

    fn exact(p: &Poly, d: &Poly, b: &mut Budget) -> Result<Poly, Fail> {
        if d.is_one() {
            return Ok(p.clone());
        }
        // `d` divides `p` by construction (it is a gcd): failure would be a bug, reported as a
        // work limit so the caller falls back to the input.
        p.div_exact(d, b)?.ok_or(Fail::Limit(WorkLimit::Work))
    }

    /// Henrici: with `g = gcd(q₁, q₂)`, `n = p₁·(q₂/g) + p₂·(q₁/g)`, the only common factor
    /// of `n` and `q₁q₂/g` divides `g`.
    pub(crate) fn add(&self, o: &Rf, b: &mut Budget) -> Result<Rf, Fail> {
        if self.num.is_zero() {
            return Ok(o.clone());
        }
        if o.num.is_zero() {
            return Ok(self.clone());
        }
        let g = gcd(&self.den, &o.den, b)?;
        let q1g = Rf::exact(&self.den, &g, b)?;
        let q2g = Rf::exact(&o.den, &g, b)?;
        let num = self.num.mul(&q2g, b)?.add(&o.num.mul(&q1g, b)?, b)?;
        if num.is_zero() {
            return Ok(Rf::zero(self.num.nvars));
        }
        let h = gcd(&num, &g, b)?;
        let num = Rf::exact(&num, &h, b)?;
        let den = q1g.mul(&Rf::exact(&o.den, &h, b)?, b)?;
        Rf { num, den }.normalised(b)
    }

    /// Cross-cancellation: `(p₁/q₁)(p₂/q₂)` with `gcd(p₁, q₂)` and `gcd(p₂, q₁)` removed.
    pub(crate) fn mul(&self, o: &Rf, b: &mut Budget) -> Result<Rf, Fail> {
        let n = self.num.nvars;
        if self.num.is_zero() || o.num.is_zero() {
            return Ok(Rf::zero(n));
        }
        let g1 = gcd(&self.num, &o.den, b)?;
        let g2 = gcd(&o.num, &self.den, b)?;
        let num = Rf::exact(&self.num, &g1, b)?.mul(&Rf::exact(&o.num, &g2, b)?, b)?;
        let den = Rf::exact(&self.den, &g2, b)?.mul(&Rf::exact(&o.den, &g1, b)?, b)?;
        Rf { num, den }.normalised(b)
    }

    pub(crate) fn powi(&self, k: i64, b: &mut Budget) -> Result<Rf, Fail> {
        let base = if k < 0 {
            if self.num.is_zero() {
                return Err(Fail::ZeroDenominator);
            }
            Rf {
                num: self.den.clone(),
                den: self.num.clone(),
            }
            .normalised(b)?
        } else {
            self.clone()
        };
        let k = u32::try_from(k.unsigned_abs()).map_err(|_| Fail::Limit(WorkLimit::Degree))?;
        // Powers of coprime polynomials stay coprime.
        Ok(Rf {
            num: base.num.pow(k, b)?,
            den: base.den.pow(k, b)?,
        })
    }

    /// Make the denominator monic.
    fn normalised(self, b: &mut Budget) -> Result<Rf, Fail> {
        let lc = self.den.lc();
        if lc.is_zero() {
            return Err(Fail::ZeroDenominator);
        }
        if lc.is_one() {
            return Ok(self);
        }
        let inv = lc.recip().ok_or(Fail::ZeroDenominator)?;
        Ok(Rf {
            num: self.num.scale(&inv, b)?,
            den: self.den.scale(&inv, b)?,
        })
    }

    /// Rebuild through the pool: `c · m_N · N / (m_D · D)` with the monomial contents
    /// `m_N`, `m_D` factored out and `N` monic.
    fn to_form(&self, atoms: &[Expr], b: &mut Budget) -> Result<RationalForm, WorkLimit> {
        if self.num.is_zero() {
            return Ok(RationalForm {
                numerator: Expr::zero(),
                denominator: Expr::one(),
            });
        }
        let mono = |m: &[u32]| monomial_expr(m, atoms);
        let poly = |p: &Poly| poly_expr(p, atoms);
        let c = self.num.lc();
        let num = self.num.monic(b)?;
        let mn = num.monomial_content();
        let md = self.den.monomial_content();
        let numerator = Expr::product([
            Expr::from_rational(c),
            mono(&mn),
            poly(&num.div_monomial(&mn)),
        ]);
        let denominator = Expr::product([mono(&md), poly(&self.den.div_monomial(&md))]);
        Ok(RationalForm {
            numerator,
            denominator,
        })
    }
}

/// `Π atomᵢ^mᵢ` through the pool.
pub(crate) fn monomial_expr(m: &[u32], atoms: &[Expr]) -> Expr {
    Expr::product(
        m.iter()
            .zip(atoms)
            .filter(|(k, _)| **k > 0)
            .map(|(k, a)| a.powi(*k as i64)),
    )
}

/// A polynomial in `atoms` through the pool.
pub(crate) fn poly_expr(p: &Poly, atoms: &[Expr]) -> Expr {
    Expr::sum(
        p.terms
            .iter()
            .map(|(e, k)| Expr::from_rational(k.clone()) * monomial_expr(e, atoms)),
    )
}
