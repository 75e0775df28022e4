//! The smart constructors: sums, products, powers and functions in canonical form (the
//! identities of the table in the [`pool`](super) module).

use super::*;
use crate::func::Parity;

impl PoolData {
    // ---------------------------------------------------------------- sums

    /// `Σ items`, canonical.
    pub(crate) fn add_n(&mut self, items: &[Id]) -> Id {
        if let Some(bad) = self.first_invalid(items) {
            return bad;
        }
        match items {
            [] => return ZERO,
            [a] => return *a,
            [a, b] if *a == ZERO => return *b,
            [a, b] if *b == ZERO => return *a,
            _ => {}
        }
        let mut c0 = Number::Rat(Rational::ZERO);
        let mut terms = std::mem::take(&mut self.terms_buf);
        terms.clear();
        let mut id = None;
        for &it in items {
            if let Err(e) = self.collect_add(it, &Number::Rat(Rational::ONE), &mut c0, &mut terms) {
                id = Some(self.invalid(e));
                break;
            }
        }
        let id = id.unwrap_or_else(|| self.finish_add(c0, &mut terms));
        terms.clear();
        self.terms_buf = terms;
        id
    }

    /// Push `scale·item` into a sum under construction.
    fn collect_add(
        &mut self,
        item: Id,
        scale: &Number,
        c0: &mut Number,
        terms: &mut Vec<(Id, Number)>,
    ) -> Result<(), SymError> {
        match &self.nodes[item as usize] {
            Node::Num(_) | Node::Float(_) => {
                let v = self.number(item).expect("number");
                *c0 = c0.add(&v.mul(scale)?)?;
            }
            Node::Add(s, l) => {
                let (s, l) = (*s, *l);
                let a0 = self.args[s as usize];
                let v = self.number(a0).expect("sum constant");
                *c0 = c0.add(&v.mul(scale)?)?;
                for k in 0..(l as usize - 1) / 2 {
                    let t = self.args[s as usize + 1 + 2 * k];
                    let c = self
                        .number(self.args[s as usize + 2 + 2 * k])
                        .expect("coefficient");
                    terms.push((t, c.mul(scale)?));
                }
            }
            Node::Mul(s, l) => {
                let (s, l) = (*s, *l);
                let coef = self.number(self.args[s as usize]).expect("coefficient");
                if coef.is_one() {
                    terms.push((item, scale.clone()));
                } else {
                    let unit = self.unit_product(item);
                    let _ = l;
                    terms.push((unit, coef.mul(scale)?));
                }
            }
            _ => terms.push((item, scale.clone())),
        }
        Ok(())
    }

    /// `(q, s)` with `b = q·s` and the first coefficient of the sum `s` one, when `b` is an
    /// exact sum (no float coefficients: dividing those would round) whose first coefficient
    /// is not already one.
    fn primitive_sum(&mut self, b: Id) -> Option<(Rational, Id)> {
        let (c0, pairs) = self.add_parts(b)?;
        let q = match &self.nodes[pairs[1] as usize] {
            Node::Num(q) if !q.is_one() => q.clone(),
            _ => return None,
        };
        let exact = matches!(self.nodes[c0 as usize], Node::Num(_))
            && pairs
                .chunks_exact(2)
                .all(|p| matches!(self.nodes[p[1] as usize], Node::Num(_)));
        if !exact {
            return None;
        }
        let inv = Number::Rat(q.recip()?);
        let mut c = Number::Rat(Rational::ZERO);
        let mut terms = Vec::with_capacity(pairs.len() / 2);
        self.collect_add(b, &inv, &mut c, &mut terms).ok()?;
        let s = self.finish_add(c, &mut terms);
        matches!(self.nodes[s as usize], Node::Add(..)).then_some((q, s))
    }

    /// The product with its numeric coefficient replaced by one.
    fn unit_product(&mut self, id: Id) -> Id {
        let (_, pairs) = self.mul_parts(id).expect("product");
        if pairs.len() == 2 && pairs[1] == ONE {
            return pairs[0];
        }
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(ONE);
        key.extend_from_slice(self.mul_parts(id).expect("product").1);
        let id = self.intern(Shape::Mul(&key));
        self.key_buf = key;
        id
    }

    /// The canonical sum `c0 + Σ terms`. `terms` is consumed (left in an unspecified state).
    fn finish_add(&mut self, c0: Number, terms: &mut Vec<(Id, Number)>) -> Id {
        // Stable sort: the coefficients of equal terms are added in a fixed order.
        terms.sort_by_key(|t| t.0);
        // Merge equal terms in place.
        let mut w = 0;
        for i in 0..terms.len() {
            if w > 0 && terms[w - 1].0 == terms[i].0 {
                match terms[w - 1].1.add(&terms[i].1) {
                    Ok(s) => terms[w - 1].1 = s,
                    Err(e) => return self.invalid(e),
                }
            } else {
                terms.swap(w, i);
                w += 1;
            }
        }
        terms.truncate(w);
        terms.retain(|(_, c)| !c.is_zero());
        let c0 = match self.pythagoras(terms, c0) {
            Ok(c) => c,
            Err(e) => return self.invalid(e),
        };
        if terms.is_empty() {
            return self.num(c0);
        }
        if c0.is_zero() && terms.len() == 1 {
            let (t, c) = terms.pop().expect("one term");
            return self.scale(t, c);
        }
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(self.num(c0));
        for (t, c) in terms.drain(..) {
            key.push(t);
            let cid = self.num(c);
            key.push(cid);
        }
        let id = self.intern(Shape::Add(&key));
        self.key_buf = key;
        id
    }

    /// `c·sin²x + c·cos²x → c` (always safe). Terms are `(sin x)²` / `(cos x)²` products.
    fn pythagoras(
        &mut self,
        terms: &mut Vec<(Id, Number)>,
        mut c0: Number,
    ) -> Result<Number, SymError> {
        let square_of = |p: &Self, t: Id, f: Func| -> Option<Id> {
            let (c, pairs) = p.mul_parts(t)?;
            if c != ONE || pairs.len() != 2 || p.rational_of(pairs[1])?.to_i64() != Some(2) {
                return None;
            }
            match p.node(pairs[0]) {
                Node::Func(g, x) if *g == f => Some(*x),
                _ => None,
            }
        };
        let mut i = 0;
        while i < terms.len() {
            if let Some(x) = square_of(self, terms[i].0, Func::Sin) {
                let cos_term = terms.iter().position(|(t, c)| {
                    *c == terms[i].1 && square_of(self, *t, Func::Cos) == Some(x)
                });
                if let Some(j) = cos_term {
                    c0 = c0.add(&terms[i].1)?;
                    let (hi, lo) = (i.max(j), i.min(j));
                    terms.remove(hi);
                    terms.remove(lo);
                    continue;
                }
            }
            i += 1;
        }
        Ok(c0)
    }

    /// `c·t` for a term `t` of a sum (not a number, not a sum, unit coefficient).
    fn scale(&mut self, t: Id, c: Number) -> Id {
        if c.is_one() {
            return t;
        }
        let cid = self.num(c);
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(cid);
        match self.mul_parts(t) {
            Some((_, pairs)) => key.extend_from_slice(pairs),
            None => {
                key.push(t);
                key.push(ONE);
            }
        }
        let id = self.intern(Shape::Mul(&key));
        self.key_buf = key;
        id
    }

    // ---------------------------------------------------------------- products

    /// `Π items`, canonical.
    pub(crate) fn mul_n(&mut self, items: &[Id]) -> Id {
        if let Some(bad) = self.first_invalid(items) {
            return bad;
        }
        match items {
            [] => return ONE,
            [a] => return *a,
            [a, b] if *a == ONE => return *b,
            [a, b] if *b == ONE => return *a,
            _ => {}
        }
        let mut coef = Number::Rat(Rational::ONE);
        let mut factors = std::mem::take(&mut self.factors_buf);
        factors.clear();
        let id = self.mul_items(items, &mut coef, &mut factors);
        let id = id.unwrap_or_else(|| {
            if coef.is_zero() {
                ZERO
            } else {
                self.finish_mul(coef, &mut factors)
            }
        });
        factors.clear();
        self.factors_buf = factors;
        id
    }

    /// Flatten the factors of `items` into `coef` and `factors`; `Some(invalid)` on an error.
    fn mul_items(
        &mut self,
        items: &[Id],
        coef: &mut Number,
        factors: &mut Vec<(Id, Rational)>,
    ) -> Option<Id> {
        for &it in items {
            match &self.nodes[it as usize] {
                Node::Num(_) | Node::Float(_) => {
                    let v = self.number(it).expect("number");
                    match coef.mul(&v) {
                        Ok(c) => *coef = c,
                        Err(e) => return Some(self.invalid(e)),
                    }
                }
                Node::Mul(s, l) => {
                    let (s, l) = (*s as usize, *l as usize);
                    let c = self.number(self.args[s]).expect("coefficient");
                    match coef.mul(&c) {
                        Ok(c) => *coef = c,
                        Err(e) => return Some(self.invalid(e)),
                    }
                    for k in 0..(l - 1) / 2 {
                        let b = self.args[s + 1 + 2 * k];
                        let e = self
                            .rational_of(self.args[s + 2 + 2 * k])
                            .expect("exp")
                            .clone();
                        factors.push((b, e));
                    }
                }
                _ => factors.push((it, Rational::ONE)),
            }
        }
        None
    }

    /// The canonical product `coef·Π factors`. `factors` is consumed (left in an unspecified
    /// state).
    fn finish_mul(&mut self, mut coef: Number, factors: &mut Vec<(Id, Rational)>) -> Id {
        if let Err(invalid) = self.primitive_sum_factors(&mut coef, factors) {
            return invalid;
        }
        if let Err(invalid) = self.merge_equal_bases(factors) {
            return invalid;
        }
        // Fold numeric bases with integer exponents into the coefficient; drop x^0. The kept
        // factors are compacted in place; expansions (rare) go to `extra`.
        let mut kept = 0;
        let mut extra: Vec<(Id, Rational)> = Vec::new();
        let mut expanded = false;
        for i in 0..factors.len() {
            let b = factors[i].0;
            let e = std::mem::replace(&mut factors[i].1, Rational::ZERO);
            if e.is_zero() {
                continue;
            }
            if e.is_integer() && matches!(self.nodes[b as usize], Node::Mul(..)) {
                // A product base whose fractional powers merged to an integer one, e.g.
                // (2x²)^(1/2)·(2x²)^(1/2) = (2x²)^1: products are flat, so expand it exactly
                // (integer power of a product) and merge again. Without this, a·a and a²
                // were different nodes.
                let p = self.pow_rational(b, e);
                match &self.nodes[p as usize] {
                    Node::Invalid(_) => return p,
                    Node::Num(_) | Node::Float(_) => {
                        let v = self.number(p).expect("number");
                        match coef.mul(&v) {
                            Ok(c) => coef = c,
                            Err(err) => return self.invalid(err),
                        }
                    }
                    Node::Mul(..) => {
                        let (c, pairs) = self.mul_parts(p).expect("product");
                        let pairs: Vec<u32> = pairs.to_vec();
                        match coef.mul(&self.number(c).expect("coefficient")) {
                            Ok(c) => coef = c,
                            Err(err) => return self.invalid(err),
                        }
                        for q in pairs.chunks_exact(2) {
                            extra.push((q[0], self.rational_of(q[1]).expect("exp").clone()));
                        }
                    }
                    _ => extra.push((p, Rational::ONE)),
                }
                expanded = true;
                continue;
            }
            if self.is_number(b) && e.is_integer() {
                let v = self.pow_number(b, &e);
                match v {
                    Ok(v) => match coef.mul(&v) {
                        Ok(c) => coef = c,
                        Err(err) => return self.invalid(err),
                    },
                    Err(err) => return self.invalid(err),
                }
                continue;
            }
            factors[kept] = (b, e);
            kept += 1;
        }
        factors.truncate(kept);
        if expanded {
            // The expansion brought new factors (possibly equal to kept ones): merge again.
            factors.append(&mut extra);
            return self.finish_mul(coef, factors);
        }
        // A second pass may have produced adjacent equal bases with opposite signs whose
        // cancellation is allowed: handled above; re-sort for the canonical order.
        factors.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.signum().cmp(&a.1.signum())));
        let kept = factors;
        if kept.is_empty() {
            return self.num(coef);
        }
        if kept.len() == 1 && kept[0].1.is_one() {
            let b = kept[0].0;
            if coef.is_one() {
                return b;
            }
            if matches!(self.nodes[b as usize], Node::Add(..)) {
                // Distribute a numeric coefficient over a sum (canonical sums).
                let mut c0 = Number::Rat(Rational::ZERO);
                let mut terms = std::mem::take(&mut self.terms_buf);
                terms.clear();
                let id = match self.collect_add(b, &coef, &mut c0, &mut terms) {
                    Ok(()) => Some(self.finish_add(c0, &mut terms)),
                    // A term's coefficient would underflow: keep the product undistributed.
                    Err(SymError::Underflow { .. }) => None,
                    Err(e) => Some(self.invalid(e)),
                };
                terms.clear();
                self.terms_buf = terms;
                if let Some(id) = id {
                    return id;
                }
            }
        }
        let mut key = std::mem::take(&mut self.key_buf);
        key.clear();
        key.push(self.num(coef));
        for (b, e) in kept.drain(..) {
            key.push(b);
            let eid = self.rational(e);
            key.push(eid);
        }
        let id = self.intern(Shape::Mul(&key));
        self.key_buf = key;
        id
    }

    /// Sum bases with integer exponents made primitive (first coefficient one), the content
    /// going into `coef`; `Err` holds the invalid node of a failure.
    fn primitive_sum_factors(
        &mut self,
        coef: &mut Number,
        factors: &mut [(Id, Rational)],
    ) -> Result<(), Id> {
        // Sum bases with integer exponents are made primitive (first coefficient one), the
        // content going into the coefficient: `(2a + 2b)·x` and `2·((a + b)·x)` must be the
        // same node although `2·(a + b)` alone is distributed. A lone sum to the first power
        // is left alone: it is distributed below anyway.
        if !(factors.len() == 1 && factors[0].1.is_one()) {
            for f in factors.iter_mut() {
                let Some(k) = f.1.to_i64().filter(|_| f.1.is_integer()) else {
                    continue;
                };
                let Some((q, s)) = self.primitive_sum(f.0) else {
                    continue;
                };
                match q.powi(k) {
                    Some(Ok(qk)) => match coef.mul(&Number::Rat(qk)) {
                        Ok(c) => *coef = c,
                        // The content would underflow the coefficient: keep the sum as it is.
                        Err(SymError::Underflow { .. }) => continue,
                        Err(err) => return Err(self.invalid(err)),
                    },
                    _ => return Err(self.invalid(SymError::RationalOverflow)),
                }
                f.0 = s;
            }
        }
        Ok(())
    }

    /// Factors sorted by base and equal bases merged (where no division is cancelled);
    /// `Err` holds the invalid node of a failure.
    fn merge_equal_bases(&mut self, factors: &mut Vec<(Id, Rational)>) -> Result<(), Id> {
        // Sort by base, positive exponents before negative ones.
        factors.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.signum().cmp(&a.1.signum())));
        // Merge equal bases in place.
        let mut w = 0;
        for i in 0..factors.len() {
            if w > 0 {
                let (b, lb) = (factors[i].0, factors[w - 1].0);
                let same_sign = factors[w - 1].1.signum() == factors[i].1.signum();
                if lb == b && (same_sign || self.sign(b).is_nonzero()) {
                    match factors[w - 1].1.add(&factors[i].1) {
                        Ok(s) => factors[w - 1].1 = s,
                        Err(_) => return Err(self.invalid(SymError::RationalOverflow)),
                    }
                    continue;
                }
                // Same base, opposite sign, base may vanish: keep a second entry so that
                // no division is cancelled (see the table in the module docs).
            }
            factors.swap(w, i);
            w += 1;
        }
        factors.truncate(w);
        Ok(())
    }

    /// A numeric base to an integer power.
    fn pow_number(&self, b: Id, e: &Rational) -> Result<Number, SymError> {
        let k = e.to_i64().ok_or(SymError::RationalOverflow)?;
        match self.number(b).expect("number") {
            Number::Rat(r) => match r.powi(k) {
                None => Err(SymError::DivisionByZero {
                    context: "0 to a negative power".into(),
                }),
                Some(Err(_)) => Err(SymError::RationalOverflow),
                Some(Ok(v)) => Ok(Number::Rat(v)),
            },
            Number::Float(f) => {
                if f == 0.0 && k < 0 {
                    return Err(SymError::DivisionByZero {
                        context: "0 to a negative power".into(),
                    });
                }
                finite(f.powi(k.clamp(i32::MIN as i64, i32::MAX as i64) as i32))
            }
        }
    }

    // ---------------------------------------------------------------- powers

    /// `base ^ exp`, canonical.
    pub(crate) fn pow(&mut self, base: Id, exp: Id) -> Id {
        if let Some(bad) = self.first_invalid(&[base, exp]) {
            return bad;
        }
        match &self.nodes[exp as usize] {
            Node::Num(r) => {
                let r = r.clone();
                self.pow_rational(base, r)
            }
            Node::Float(f) => {
                let f = *f;
                if let Some(bv) = self.number(base) {
                    let v = bv.to_f64().powf(f);
                    if v.is_finite() {
                        return self.float(v);
                    }
                    return self.invalid(SymError::NotReal {
                        what: format!("{} ^ {f}", bv.to_f64()),
                    });
                }
                self.intern(Shape::Pow([base, exp]))
            }
            _ => {
                if base == ONE {
                    return ONE;
                }
                self.intern(Shape::Pow([base, exp]))
            }
        }
    }

    pub(crate) fn pow_rational(&mut self, base: Id, r: Rational) -> Id {
        // Invalid nodes absorb every operation, `x^0` included: without this, `(1/0)^2`
        // became a valid-looking product over an invalid base that `check` did not see.
        if self.invalid_of(base).is_some() {
            return base;
        }
        if r.is_zero() {
            return ONE;
        }
        if r.is_one() {
            return base;
        }
        if base == ZERO && r.is_negative() {
            return self.invalid(SymError::DivisionByZero {
                context: "division by a structural zero".into(),
            });
        }
        // Numeric base.
        if let Some(bv) = self.number(base) {
            if r.is_integer() {
                return match self.pow_number(base, &r) {
                    Ok(v) => self.num(v),
                    Err(e) => self.invalid(e),
                };
            }
            return match bv {
                Number::Float(f) => {
                    let v = match r.as_small() {
                        // An odd root of a negative number is real: (−a)^(p/q) = (−1)^p·a^(p/q)
                        // for odd q (`powf` would give NaN).
                        Some((p, q)) if f < 0.0 && q % 2 == 1 => {
                            let m = (-f).powf(r.to_f64());
                            if p % 2 == 0 { m } else { -m }
                        }
                        _ => f.powf(r.to_f64()),
                    };
                    if v.is_finite() {
                        self.float(v)
                    } else {
                        self.invalid(SymError::NotReal {
                            what: format!("{f} ^ {r}"),
                        })
                    }
                }
                Number::Rat(b) => {
                    let (p, q) = match r.as_small() {
                        Some(pq) => pq,
                        None => return self.invalid(SymError::RationalOverflow),
                    };
                    if b.is_negative() && q % 2 == 0 {
                        return self.invalid(SymError::NotReal {
                            what: format!("({b}) ^ ({r}), an even root of a negative number"),
                        });
                    }
                    if let Some(root) = u32::try_from(q).ok().and_then(|q| b.exact_root(q)) {
                        let rid = self.rational(root);
                        return self.pow_rational(rid, Rational::int(p));
                    }
                    if b.is_negative() {
                        // An odd root of a negative constant is real (the even case was refused
                        // above): (−a)^(p/q) = (−1)^p·a^(p/q). Written with a positive base so
                        // that evaluation (`powf`), the nominal value and the sign analysis
                        // agree with it; a negative base would evaluate to NaN.
                        let pos = self.rational(b.neg());
                        let m = self.pow_rational(pos, r);
                        return if p % 2 == 0 {
                            m
                        } else {
                            self.mul_n(&[MINUS_ONE, m])
                        };
                    }
                    let e = self.rational(r);
                    self.intern(Shape::Mul(&[ONE, base, e]))
                }
            };
        }
        let base_sign = self.sign(base);
        if let Some((coef, pairs)) = self.mul_parts(base) {
            let pairs: Vec<u32> = pairs.to_vec();
            if r.is_integer() {
                // (c·Π bᵢ^eᵢ)^n = cⁿ·Π bᵢ^(eᵢn): exact for integer n.
                let mut items = Vec::with_capacity(pairs.len() / 2 + 1);
                let cp = self.pow_rational(coef, r.clone());
                items.push(cp);
                for p in pairs.chunks_exact(2) {
                    let e = self.rational_of(p[1]).expect("exp").clone();
                    let ne = match e.mul(&r) {
                        Ok(v) => v,
                        Err(_) => return self.invalid(SymError::RationalOverflow),
                    };
                    let f = self.factor(p[0], ne);
                    items.push(f);
                }
                return self.mul_n(&items);
            }
            // Non-integer power of a single power: (b^e)^r.
            if pairs.len() == 2 && coef == ONE {
                let (b, e) = (pairs[0], self.rational_of(pairs[1]).expect("exp").clone());
                let er = match e.mul(&r) {
                    Ok(v) => v,
                    Err(_) => return self.invalid(SymError::RationalOverflow),
                };
                if self.sign(b).is_nonneg() {
                    return self.factor(b, er);
                }
                if e.is_integer() && e.to_i64().is_some_and(|k| k % 2 == 0) {
                    // (b^(2k))^r = |b|^(2k·r) for real b.
                    let ab = self.func(Func::Abs, b);
                    return self.pow_rational(ab, er);
                }
            }
            // (c·Π)^r with every factor non-negative splits.
            if base_sign.is_nonneg()
                && self.number(coef).is_some_and(|c| !c.is_negative())
                && pairs.chunks_exact(2).all(|p| self.sign(p[0]).is_nonneg())
            {
                let mut items = Vec::with_capacity(pairs.len() / 2 + 1);
                let cp = self.pow_rational(coef, r.clone());
                items.push(cp);
                for p in pairs.chunks_exact(2) {
                    let e = self.rational_of(p[1]).expect("exp").clone();
                    let ne = match e.mul(&r) {
                        Ok(v) => v,
                        Err(_) => return self.invalid(SymError::RationalOverflow),
                    };
                    let f = self.factor(p[0], ne);
                    items.push(f);
                }
                return self.mul_n(&items);
            }
        }
        self.factor(base, r)
    }

    /// `b^e` as a one-factor product (no further simplification of `b`).
    fn factor(&mut self, b: Id, e: Rational) -> Id {
        if e.is_zero() {
            return ONE;
        }
        if e.is_one() {
            return b;
        }
        if self.is_number(b) || matches!(self.nodes[b as usize], Node::Mul(..)) {
            // Numbers and products must go through the general rules.
            if self.is_number(b) || e.is_integer() {
                return self.pow_rational(b, e);
            }
        }
        if e.is_integer() {
            // Same canonical form as `finish_mul`: `(2a − 2b)^n = 2ⁿ·(a − b)^n`.
            if let Some((q, s)) = self.primitive_sum(b) {
                let qk = match e.to_i64().and_then(|k| q.powi(k)) {
                    Some(Ok(v)) => v,
                    _ => return self.invalid(SymError::RationalOverflow),
                };
                let mut f = vec![(s, e)];
                return self.finish_mul(Number::Rat(qk), &mut f);
            }
        }
        let eid = self.rational(e);
        self.intern(Shape::Mul(&[ONE, b, eid]))
    }

    // ---------------------------------------------------------------- functions

    /// `f(a)`, canonical.
    pub(crate) fn func(&mut self, f: Func, a: Id) -> Id {
        if self.invalid_of(a).is_some() {
            return a;
        }
        // Exact numeric folding.
        if let Some(r) = self.rational_of(a).cloned() {
            match (f, r.is_zero(), r.is_one()) {
                (Func::Sin | Func::Tan, true, _) => return ZERO,
                (Func::Cos | Func::Exp, true, _) => return ONE,
                (Func::Ln, _, true) => return ZERO,
                (Func::Abs, _, _) => return self.rational(r.abs()),
                (Func::Ln, true, _) => {
                    return self.invalid(SymError::NotReal {
                        what: "ln(0)".into(),
                    });
                }
                (Func::Ln, _, _) if r.is_negative() => {
                    return self.invalid(SymError::NotReal {
                        what: format!("ln({r})"),
                    });
                }
                _ => {}
            }
        }
        if let Node::Float(x) = self.nodes[a as usize] {
            let v = f.eval_f64(x);
            if v.is_finite() {
                return self.float(v);
            }
            return self.invalid(SymError::NotReal {
                what: format!("{}({x})", f.name()),
            });
        }
        // Multiples of π.
        if let Some(k) = self.pi_multiple(a) {
            if f.has_pole_at_pi_times(&k) {
                return self.invalid(SymError::DivisionByZero {
                    context: format!("{}({k}·π) is a pole of {}", f.name(), f.name()),
                });
            }
            if let Some(v) = exact_trig(f, &k) {
                return self.rational(v);
            }
        }
        // Odd and even functions of a negated argument.
        if let Some(pos) = self.negated(a) {
            match f.parity() {
                Parity::Even => return self.func(f, pos),
                Parity::Odd => {
                    let v = self.func(f, pos);
                    return self.mul_n(&[MINUS_ONE, v]);
                }
                Parity::None => {}
            }
        }
        match f {
            Func::Abs => {
                let s = self.sign(a);
                if s.is_nonneg() {
                    return a;
                }
                if s.is_nonpos() {
                    return self.mul_n(&[MINUS_ONE, a]);
                }
            }
            Func::Exp => {
                if let Node::Func(Func::Ln, x) = self.nodes[a as usize] {
                    return x;
                }
            }
            Func::Ln => {
                if let Node::Func(Func::Exp, x) = self.nodes[a as usize] {
                    return x;
                }
            }
            _ => {}
        }
        self.intern(Shape::Func(f, [a]))
    }

    /// If `a = k·π` with rational `k`, return `k`.
    fn pi_multiple(&self, a: Id) -> Option<Rational> {
        match &self.nodes[a as usize] {
            Node::Const(Constant::Pi) => Some(Rational::ONE),
            Node::Mul(..) => {
                let (c, pairs) = self.mul_parts(a)?;
                if pairs.len() == 2
                    && pairs[1] == ONE
                    && matches!(self.nodes[pairs[0] as usize], Node::Const(Constant::Pi))
                {
                    self.rational_of(c).cloned()
                } else {
                    None
                }
            }
            _ => None,
        }
    }

    /// If `a` is written with a negative numeric coefficient, return `−a` (cheaply).
    fn negated(&mut self, a: Id) -> Option<Id> {
        let (c, _) = self.mul_parts(a)?;
        let cv = self.number(c)?;
        if cv.is_negative() {
            Some(self.mul_n(&[MINUS_ONE, a]))
        } else {
            None
        }
    }

    /// `atan2(y, x)`.
    pub(crate) fn atan2(&mut self, y: Id, x: Id) -> Id {
        if let Some(bad) = self.first_invalid(&[y, x]) {
            return bad;
        }
        if y == ZERO && self.sign(x).is_positive() {
            return ZERO;
        }
        if let (Node::Float(a), Node::Float(b)) = (&self.nodes[y as usize], &self.nodes[x as usize])
        {
            let v = a.atan2(*b);
            return self.float(v);
        }
        self.intern(Shape::Atan2([y, x]))
    }
}

/// Exact values of trigonometric functions at rational multiples `k` of π (only the cases that
/// are rational: multiples of π/2 for sin and cos, of π for tan).
fn exact_trig(f: Func, k: &Rational) -> Option<Rational> {
    let (n, d) = k.as_small()?;
    match (f, d) {
        (Func::Sin, 1) | (Func::Tan, 1) => Some(Rational::ZERO),
        (Func::Cos, 1) => Some(if n.rem_euclid(2) == 0 {
            Rational::ONE
        } else {
            Rational::MINUS_ONE
        }),
        (Func::Sin, 2) => Some(if n.rem_euclid(4) == 1 {
            Rational::ONE
        } else {
            Rational::MINUS_ONE
        }),
        (Func::Cos, 2) => Some(Rational::ZERO),
        _ => None,
    }
}

/// Integers and dyadic fractions with a denominator up to 2^20 are exact rationals.
pub(crate) fn dyadic(x: f64) -> Option<Rational> {
    // Every integer-valued double below 2^63 is an exact `i64` (the scaled test below alone
    // left integers above ~8.6e9, such as 1e10, as floats).
    if x.fract() == 0.0 && x.abs() < 9_223_372_036_854_775_808.0 {
        return Some(Rational::int(x as i64));
    }
    let scaled = x * (1u64 << 20) as f64;
    if scaled.fract() == 0.0 && scaled.abs() < 9.0e15 {
        Rational::new(scaled as i64, 1 << 20)
    } else {
        None
    }
}
