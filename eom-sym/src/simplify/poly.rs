//! Sparse multivariate polynomials over ℚ with exact arithmetic, exact division and a
//! recursive primitive-PRS gcd.
//!
//! A polynomial is a list of `(exponent vector, coefficient)` terms sorted in decreasing
//! lexicographic order (variable 0 most significant), without zero coefficients. Every
//! operation draws on a [`Budget`]: term counts, degrees and the number of elementary term
//! operations are bounded, and exceeding a bound is a [`WorkLimit`], never a hang. Rational
//! coefficients are exact ([`Rational`] promotes to big integers and refuses results wider
//! than [`MAX_BITS`](crate::rational::MAX_BITS): that is a limit too).
//!
//! The gcd is the classical one over a UFD `R[x]`, `R = ℚ[other variables]`:
//! `gcd(A, B) = gcd(cont A, cont B) · pp(last nonzero term of the primitive PRS)`, where the
//! contents are gcds of coefficients in `R` (recursion on fewer variables) and the primitive
//! PRS replaces each pseudo-remainder by its primitive part, which keeps coefficients from
//! growing exponentially. Results are made monic (leading coefficient 1) so that they are
//! unique.

use super::rational_fn::WorkLimit;
use crate::rational::Rational;
use hashbrown::HashMap;
use std::cmp::Ordering;

/// Bounds on the work of one normalisation.
#[derive(Clone, Debug)]
pub(crate) struct Budget {
    pub max_terms: usize,
    pub max_degree: u32,
    pub max_work: u64,
    pub work: u64,
    /// A wall-clock bound, checked every few thousand term operations (the term count alone
    /// under-weights gcds of large polynomials).
    pub deadline: Option<std::time::Instant>,
}

impl Budget {
    fn tick(&mut self, n: usize) -> Result<(), WorkLimit> {
        let before = self.work;
        self.work = self.work.saturating_add(n as u64);
        if self.work > self.max_work {
            return Err(WorkLimit::Work);
        }
        if self.work >> 12 != before >> 12
            && self.deadline.is_some_and(|d| std::time::Instant::now() > d)
        {
            return Err(WorkLimit::Time);
        }
        Ok(())
    }
    fn check(&self, p: &Poly) -> Result<(), WorkLimit> {
        if p.terms.len() > self.max_terms {
            return Err(WorkLimit::Terms);
        }
        if p.terms
            .iter()
            .any(|(e, _)| e.iter().any(|&k| k > self.max_degree))
        {
            return Err(WorkLimit::Degree);
        }
        Ok(())
    }
}

type Exps = Box<[u32]>;

fn cmp_lex(a: &[u32], b: &[u32]) -> Ordering {
    a.cmp(b)
}

fn ov<T>(r: Result<T, crate::rational::RationalOverflow>) -> Result<T, WorkLimit> {
    r.map_err(|_| WorkLimit::Coefficients)
}

/// A polynomial in `nvars` variables.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Poly {
    pub nvars: usize,
    pub terms: Vec<(Exps, Rational)>,
}

impl Poly {
    pub(crate) fn zero(nvars: usize) -> Poly {
        Poly {
            nvars,
            terms: Vec::new(),
        }
    }
    pub(crate) fn constant(nvars: usize, c: Rational) -> Poly {
        if c.is_zero() {
            return Poly::zero(nvars);
        }
        Poly {
            nvars,
            terms: vec![(vec![0; nvars].into(), c)],
        }
    }
    pub(crate) fn one(nvars: usize) -> Poly {
        Poly::constant(nvars, Rational::ONE)
    }
    /// `x_i`.
    pub(crate) fn var(nvars: usize, i: usize) -> Poly {
        let mut e = vec![0; nvars];
        e[i] = 1;
        Poly {
            nvars,
            terms: vec![(e.into(), Rational::ONE)],
        }
    }
    pub(crate) fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }
    pub(crate) fn is_constant(&self) -> bool {
        self.terms.is_empty() || (self.terms.len() == 1 && self.terms[0].0.iter().all(|&k| k == 0))
    }
    pub(crate) fn is_one(&self) -> bool {
        self.is_constant() && !self.is_zero() && self.terms[0].1.is_one()
    }
    /// Leading coefficient (lexicographic order); zero for the zero polynomial.
    pub(crate) fn lc(&self) -> Rational {
        self.terms.first().map_or(Rational::ZERO, |t| t.1.clone())
    }

    fn from_unsorted(nvars: usize, map: HashMap<Exps, Rational>) -> Poly {
        let mut terms: Vec<(Exps, Rational)> =
            map.into_iter().filter(|(_, c)| !c.is_zero()).collect();
        terms.sort_unstable_by(|a, b| cmp_lex(&b.0, &a.0));
        Poly { nvars, terms }
    }

    pub(crate) fn add(&self, o: &Poly, b: &mut Budget) -> Result<Poly, WorkLimit> {
        b.tick(self.terms.len() + o.terms.len())?;
        let mut out = Vec::with_capacity(self.terms.len() + o.terms.len());
        let (mut i, mut j) = (0, 0);
        while i < self.terms.len() || j < o.terms.len() {
            let ord = match (self.terms.get(i), o.terms.get(j)) {
                (Some(a), Some(c)) => cmp_lex(&a.0, &c.0),
                (Some(_), None) => Ordering::Greater,
                _ => Ordering::Less,
            };
            match ord {
                Ordering::Greater => {
                    out.push(self.terms[i].clone());
                    i += 1;
                }
                Ordering::Less => {
                    out.push(o.terms[j].clone());
                    j += 1;
                }
                Ordering::Equal => {
                    let c = ov(self.terms[i].1.add(&o.terms[j].1))?;
                    if !c.is_zero() {
                        out.push((self.terms[i].0.clone(), c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        let p = Poly {
            nvars: self.nvars,
            terms: out,
        };
        b.check(&p)?;
        Ok(p)
    }

    pub(crate) fn neg(&self) -> Poly {
        Poly {
            nvars: self.nvars,
            terms: self
                .terms
                .iter()
                .map(|(e, c)| (e.clone(), c.neg()))
                .collect(),
        }
    }

    pub(crate) fn sub(&self, o: &Poly, b: &mut Budget) -> Result<Poly, WorkLimit> {
        self.add(&o.neg(), b)
    }

    pub(crate) fn scale(&self, c: &Rational, b: &mut Budget) -> Result<Poly, WorkLimit> {
        if c.is_zero() {
            return Ok(Poly::zero(self.nvars));
        }
        b.tick(self.terms.len())?;
        let terms = self
            .terms
            .iter()
            .map(|(e, x)| Ok((e.clone(), ov(x.mul(c))?)))
            .collect::<Result<_, WorkLimit>>()?;
        Ok(Poly {
            nvars: self.nvars,
            terms,
        })
    }

    /// `self · x^e · c`.
    fn mul_term(&self, e: &[u32], c: &Rational, b: &mut Budget) -> Result<Poly, WorkLimit> {
        b.tick(self.terms.len())?;
        let mut terms = Vec::with_capacity(self.terms.len());
        for (x, k) in &self.terms {
            let ex: Exps = x.iter().zip(e).map(|(a, b)| a + b).collect();
            terms.push((ex, ov(k.mul(c))?));
        }
        // Adding the same exponent to every term keeps the lexicographic order.
        let p = Poly {
            nvars: self.nvars,
            terms,
        };
        b.check(&p)?;
        Ok(p)
    }

    pub(crate) fn mul(&self, o: &Poly, b: &mut Budget) -> Result<Poly, WorkLimit> {
        if self.is_zero() || o.is_zero() {
            return Ok(Poly::zero(self.nvars));
        }
        if o.terms.len() == 1 {
            return self.mul_term(&o.terms[0].0, &o.terms[0].1, b);
        }
        if self.terms.len() == 1 {
            return o.mul_term(&self.terms[0].0, &self.terms[0].1, b);
        }
        b.tick(self.terms.len().saturating_mul(o.terms.len()))?;
        let mut map: HashMap<Exps, Rational> =
            HashMap::with_capacity(self.terms.len() * o.terms.len());
        for (ea, ca) in &self.terms {
            for (eb, cb) in &o.terms {
                let e: Exps = ea.iter().zip(eb.iter()).map(|(x, y)| x + y).collect();
                let c = ov(ca.mul(cb))?;
                match map.get_mut(&e) {
                    Some(v) => *v = ov(v.add(&c))?,
                    None => {
                        map.insert(e, c);
                    }
                }
            }
        }
        let p = Poly::from_unsorted(self.nvars, map);
        b.check(&p)?;
        Ok(p)
    }

    pub(crate) fn pow(&self, k: u32, b: &mut Budget) -> Result<Poly, WorkLimit> {
        let d = (0..self.nvars).map(|v| self.deg_in(v)).max().unwrap_or(0);
        if k.saturating_mul(d) > b.max_degree {
            return Err(WorkLimit::Degree);
        }
        let mut result = Poly::one(self.nvars);
        let mut base = self.clone();
        let mut k = k;
        while k > 0 {
            if k & 1 == 1 {
                result = result.mul(&base, b)?;
            }
            k >>= 1;
            if k > 0 {
                base = base.mul(&base, b)?;
            }
        }
        Ok(result)
    }

    /// Degree in variable `v` (0 for the zero polynomial).
    pub(crate) fn deg_in(&self, v: usize) -> u32 {
        self.terms.iter().map(|(e, _)| e[v]).max().unwrap_or(0)
    }

    /// Which variables occur.
    pub(crate) fn vars(&self) -> Vec<bool> {
        let mut seen = vec![false; self.nvars];
        for (e, _) in &self.terms {
            for (s, &k) in seen.iter_mut().zip(e.iter()) {
                *s |= k > 0;
            }
        }
        seen
    }

    /// Coefficients in variable `v` (index = degree; each has `v`'s exponent zeroed).
    pub(crate) fn coeffs_in(&self, v: usize) -> Vec<Poly> {
        let d = self.deg_in(v) as usize;
        let mut out: Vec<Vec<(Exps, Rational)>> = vec![Vec::new(); d + 1];
        for (e, c) in &self.terms {
            let mut ex = e.clone();
            let k = ex[v] as usize;
            ex[v] = 0;
            out[k].push((ex, c.clone()));
        }
        // Zeroing one variable keeps the relative order of terms with the same exponent of v.
        out.into_iter()
            .map(|terms| Poly {
                nvars: self.nvars,
                terms,
            })
            .collect()
    }

    /// The coefficient of the highest power of `v`, and that power.
    fn lead_in(&self, v: usize) -> (Poly, u32) {
        let d = self.deg_in(v);
        let mut terms = Vec::new();
        for (e, c) in &self.terms {
            if e[v] == d {
                let mut ex = e.clone();
                ex[v] = 0;
                terms.push((ex, c.clone()));
            }
        }
        (
            Poly {
                nvars: self.nvars,
                terms,
            },
            d,
        )
    }

    /// The largest monomial dividing every term.
    pub(crate) fn monomial_content(&self) -> Vec<u32> {
        let mut m: Option<Vec<u32>> = None;
        for (e, _) in &self.terms {
            match &mut m {
                None => m = Some(e.to_vec()),
                Some(m) => {
                    for (a, &b) in m.iter_mut().zip(e.iter()) {
                        *a = (*a).min(b);
                    }
                }
            }
        }
        m.unwrap_or_else(|| vec![0; self.nvars])
    }

    /// `self / x^m` for a monomial dividing every term.
    pub(crate) fn div_monomial(&self, m: &[u32]) -> Poly {
        let terms = self
            .terms
            .iter()
            .map(|(e, c)| (e.iter().zip(m).map(|(a, b)| a - b).collect(), c.clone()))
            .collect();
        Poly {
            nvars: self.nvars,
            terms,
        }
    }

    /// `self / d` if `d` divides `self` exactly, otherwise `None`.
    pub(crate) fn div_exact(&self, d: &Poly, b: &mut Budget) -> Result<Option<Poly>, WorkLimit> {
        if d.is_zero() {
            return Ok(None);
        }
        if self.is_zero() {
            return Ok(Some(Poly::zero(self.nvars)));
        }
        if (0..self.nvars).any(|v| d.deg_in(v) > self.deg_in(v)) {
            return Ok(None);
        }
        let (de, dc) = (&d.terms[0].0, &d.terms[0].1);
        let mut r = self.clone();
        let mut q: Vec<(Exps, Rational)> = Vec::new();
        while let Some((re, rc)) = r.terms.first() {
            if !re.iter().zip(de.iter()).all(|(a, b)| a >= b) {
                return Ok(None);
            }
            let te: Exps = re.iter().zip(de.iter()).map(|(a, b)| a - b).collect();
            let tc = match rc.div(dc) {
                Some(x) => ov(x)?,
                None => return Ok(None),
            };
            let t = d.mul_term(&te, &tc, b)?;
            q.push((te, tc));
            r = r.sub(&t, b)?;
        }
        // Leading terms of the remainder strictly decrease, so `q` is already sorted.
        Ok(Some(Poly {
            nvars: self.nvars,
            terms: q,
        }))
    }

    /// `∂self/∂x_v` (lowering the exponent of `v` keeps the lexicographic order of the terms
    /// that remain).
    pub(crate) fn derivative(&self, v: usize, b: &mut Budget) -> Result<Poly, WorkLimit> {
        b.tick(self.terms.len())?;
        let mut terms = Vec::with_capacity(self.terms.len());
        for (e, c) in &self.terms {
            if e[v] == 0 {
                continue;
            }
            let mut ex = e.clone();
            ex[v] -= 1;
            terms.push((ex, ov(c.mul(&Rational::int(i64::from(e[v]))))?));
        }
        Ok(Poly {
            nvars: self.nvars,
            terms,
        })
    }

    /// Divide by the leading coefficient.
    pub(crate) fn monic(&self, b: &mut Budget) -> Result<Poly, WorkLimit> {
        let lc = self.lc();
        if lc.is_zero() || lc.is_one() {
            return Ok(self.clone());
        }
        let inv = lc.recip().ok_or(WorkLimit::Coefficients)?;
        self.scale(&inv, b)
    }
}

/// `gcd(a, b)`, monic (the zero polynomial only if both are zero).
pub(crate) fn gcd(a: &Poly, b: &Poly, bud: &mut Budget) -> Result<Poly, WorkLimit> {
    bud.tick(1)?;
    let n = a.nvars;
    if a.is_zero() {
        return b.monic(bud);
    }
    if b.is_zero() {
        return a.monic(bud);
    }
    if a.is_constant() || b.is_constant() {
        return Ok(Poly::one(n));
    }
    // Monomial contents first: cheap, and they make single-term arguments trivial.
    let (ma, mb) = (a.monomial_content(), b.monomial_content());
    if ma.iter().chain(mb.iter()).any(|&k| k > 0) {
        let m: Vec<u32> = ma.iter().zip(&mb).map(|(x, y)| *x.min(y)).collect();
        let g = gcd(&a.div_monomial(&ma), &b.div_monomial(&mb), bud)?;
        return g.mul_term(&m, &Rational::ONE, bud);
    }
    let (va, vb) = (a.vars(), b.vars());
    // A variable in only one argument cannot occur in the gcd: reduce that argument to its
    // content with respect to the variable.
    if let Some(v) = (0..n).find(|&v| va[v] && !vb[v]) {
        let c = content_in(a, v, bud)?;
        return gcd(&c, b, bud);
    }
    if let Some(v) = (0..n).find(|&v| vb[v] && !va[v]) {
        let c = content_in(b, v, bud)?;
        return gcd(a, &c, bud);
    }
    // Main variable: the common one of smallest degree (shortest remainder sequence).
    let v = (0..n)
        .filter(|&v| va[v])
        .min_by_key(|&v| a.deg_in(v).max(b.deg_in(v)))
        .ok_or(WorkLimit::Work)?;
    let ca = content_in(a, v, bud)?;
    let cb = content_in(b, v, bud)?;
    let pa = a.div_exact(&ca, bud)?.ok_or(WorkLimit::Work)?;
    let pb = b.div_exact(&cb, bud)?.ok_or(WorkLimit::Work)?;
    let c = gcd(&ca, &cb, bud)?;
    let g = prs(pa, pb, v, bud)?;
    c.mul(&g, bud)?.monic(bud)
}

/// The square-free decomposition of `p` (Yun's algorithm in the variable `v`): `(f, k)` with
/// `p = c · Π fᵏ`, the `f` monic, square-free and pairwise coprime (`c` a constant). Every
/// factor of `p` must involve `v` (its content in `v` a constant), which holds for the
/// primitive part left after the contents in every variable are divided out.
pub(crate) fn square_free(
    p: &Poly,
    v: usize,
    bud: &mut Budget,
) -> Result<Vec<(Poly, u32)>, WorkLimit> {
    let dp = p.derivative(v, bud)?;
    let a0 = gcd(p, &dp, bud)?;
    let divide = |x: &Poly, y: &Poly, bud: &mut Budget| -> Result<Poly, WorkLimit> {
        x.div_exact(y, bud)?.ok_or(WorkLimit::Work)
    };
    let mut b = divide(p, &a0, bud)?;
    let mut c = divide(&dp, &a0, bud)?;
    let mut d = c.sub(&b.derivative(v, bud)?, bud)?;
    let mut out = Vec::new();
    let mut k = 1;
    while !b.is_constant() {
        let a = gcd(&b, &d, bud)?;
        if !a.is_constant() {
            out.push((a.monic(bud)?, k));
        }
        b = divide(&b, &a, bud)?;
        c = divide(&d, &a, bud)?;
        d = c.sub(&b.derivative(v, bud)?, bud)?;
        k += 1;
    }
    Ok(out)
}

/// The gcd of the coefficients with respect to `v`, monic.
pub(crate) fn content_in(p: &Poly, v: usize, bud: &mut Budget) -> Result<Poly, WorkLimit> {
    let mut g: Option<Poly> = None;
    for c in p.coeffs_in(v).into_iter().rev().filter(|c| !c.is_zero()) {
        let next = match &g {
            None => c.monic(bud)?,
            Some(g) => gcd(g, &c, bud)?,
        };
        if next.is_one() {
            return Ok(next);
        }
        g = Some(next);
    }
    Ok(g.unwrap_or_else(|| Poly::one(p.nvars)))
}

/// Primitive part with respect to `v`.
fn pp_in(p: &Poly, v: usize, bud: &mut Budget) -> Result<Poly, WorkLimit> {
    let c = content_in(p, v, bud)?;
    if c.is_one() {
        return Ok(p.clone());
    }
    p.div_exact(&c, bud)?.ok_or(WorkLimit::Work)
}

/// Pseudo-remainder of `f` by `g` in `v` (without the final power of the leading
/// coefficient, which only changes the content, and the content is removed next).
fn prem(f: &Poly, g: &Poly, v: usize, bud: &mut Budget) -> Result<Poly, WorkLimit> {
    let (lg, dg) = g.lead_in(v);
    let mut r = f.clone();
    while !r.is_zero() && r.deg_in(v) >= dg {
        let (lr, dr) = r.lead_in(v);
        let mut shift = vec![0; r.nvars];
        shift[v] = dr - dg;
        let t = lr.mul(g, bud)?.mul_term(&shift, &Rational::ONE, bud)?;
        r = lg.mul(&r, bud)?.sub(&t, bud)?;
    }
    Ok(r)
}

/// Primitive polynomial remainder sequence of two primitive polynomials in `v`.
fn prs(a: Poly, b: Poly, v: usize, bud: &mut Budget) -> Result<Poly, WorkLimit> {
    let (mut f, mut g) = if a.deg_in(v) >= b.deg_in(v) {
        (a, b)
    } else {
        (b, a)
    };
    loop {
        let r = prem(&f, &g, v, bud)?;
        if r.is_zero() {
            return pp_in(&g, v, bud);
        }
        if r.deg_in(v) == 0 {
            return Ok(Poly::one(f.nvars));
        }
        f = g;
        g = pp_in(&r, v, bud)?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn budget() -> Budget {
        Budget {
            max_terms: 10_000,
            max_degree: 100,
            max_work: 10_000_000,
            work: 0,
            deadline: None,
        }
    }
    fn q(n: i64) -> Rational {
        Rational::int(n)
    }

    #[test]
    fn gcd_of_products_recovers_the_common_factor() {
        let b = &mut budget();
        let (x, y, z) = (Poly::var(3, 0), Poly::var(3, 1), Poly::var(3, 2));
        // f = x + 2y − z, g = x·y + 3, h = z² − x
        let f = x
            .add(&y.scale(&q(2), b).unwrap(), b)
            .unwrap()
            .sub(&z, b)
            .unwrap();
        let g = x
            .mul(&y, b)
            .unwrap()
            .add(&Poly::constant(3, q(3)), b)
            .unwrap();
        let h = z.mul(&z, b).unwrap().sub(&x, b).unwrap();
        let a = f.mul(&g, b).unwrap().mul(&g, b).unwrap();
        let c = f.mul(&h, b).unwrap().mul(&g, b).unwrap();
        let d = gcd(&a, &c, b).unwrap();
        let expect = f.mul(&g, b).unwrap().monic(b).unwrap();
        assert_eq!(d, expect);
        // coprime
        assert!(gcd(&g, &h, b).unwrap().is_one());
        // exact division both ways
        assert_eq!(a.div_exact(&f, b).unwrap().unwrap(), g.mul(&g, b).unwrap());
        assert!(g.div_exact(&h, b).unwrap().is_none());
    }

    #[test]
    fn limits_are_reported_not_exceeded() {
        let mut b = Budget {
            max_terms: 50,
            max_degree: 100,
            max_work: 1_000_000,
            work: 0,
            deadline: None,
        };
        let s = (0..4).fold(Poly::zero(4), |acc, i| {
            acc.add(&Poly::var(4, i), &mut b).unwrap()
        });
        assert_eq!(s.pow(12, &mut b), Err(WorkLimit::Terms));
    }
}
