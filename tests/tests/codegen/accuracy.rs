//! Rounding error of the generated code against a double-double evaluation of the same
//! expressions, in units of their running error bound.

use super::*;

/// A value with a first-order bound of its rounding error: `v` is the exact value of the
/// formula (double-double), `e` the bound of `|fl(formula) − v|` in units of roundoff when
/// the formula is evaluated in `f64` operation by operation, as written (Higham's running
/// error bound: each operation adds its inputs' errors, propagated by its derivative, and
/// one rounding of its result). A value that cancels in the formula itself gets a large
/// bound; one that the evaluation made cancel does not.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bounded {
    v: eom_sym::Dd,
    e: f64,
}

mod bounded {
    use super::Bounded;
    use eom_sym::{Dd, Elementary, Rational, Scalar};
    use std::ops::{Add, Div, Mul, Neg, Sub};

    fn mag(x: Dd) -> f64 {
        x.to_f64().abs()
    }
    /// A result: `v` rounded once, plus the propagated error `e`.
    fn op(v: Dd, e: f64) -> Bounded {
        Bounded { v, e: e + mag(v) }
    }
    /// An exact datum (parameters and numbers that are doubles).
    fn exact(v: Dd) -> Bounded {
        Bounded { v, e: 0.0 }
    }
    /// A constant rounded once to a double (`1/3`, π).
    fn rounded(v: Dd) -> Bounded {
        let e = if v.lo == 0.0 { 0.0 } else { mag(v) };
        Bounded { v, e }
    }

    impl Add for Bounded {
        type Output = Bounded;
        fn add(self, b: Bounded) -> Bounded {
            op(self.v + b.v, self.e + b.e)
        }
    }
    impl Sub for Bounded {
        type Output = Bounded;
        fn sub(self, b: Bounded) -> Bounded {
            op(self.v - b.v, self.e + b.e)
        }
    }
    impl Mul for Bounded {
        type Output = Bounded;
        fn mul(self, b: Bounded) -> Bounded {
            op(self.v * b.v, self.e * mag(b.v) + b.e * mag(self.v))
        }
    }
    impl Div for Bounded {
        type Output = Bounded;
        fn div(self, b: Bounded) -> Bounded {
            let q = self.v / b.v;
            op(q, (self.e + mag(q) * b.e) / mag(b.v))
        }
    }
    impl Neg for Bounded {
        type Output = Bounded;
        fn neg(self) -> Bounded {
            Bounded {
                v: -self.v,
                e: self.e,
            }
        }
    }
    /// A library function with derivative `d` at the argument: one more unit for the
    /// library's own rounding.
    fn func(x: Bounded, v: Dd, d: Dd) -> Bounded {
        op(v, x.e * mag(d) + mag(v))
    }

    impl Scalar for Bounded {
        fn zero() -> Bounded {
            exact(Dd::ZERO)
        }
        fn one() -> Bounded {
            exact(Dd::ONE)
        }
        fn from_i64(n: i64) -> Bounded {
            rounded(Dd::from_i64(n))
        }
        fn from_rational(r: &Rational) -> Bounded {
            rounded(<Dd as Scalar>::from_rational(r))
        }
        fn from_f64(x: f64) -> Bounded {
            exact(Dd::from_f64(x))
        }
        fn pi() -> Bounded {
            rounded(Dd::PI)
        }
        fn sqrt(self) -> Bounded {
            let r = self.v.sqrt();
            let d = Dd::from_f64(0.5) / r;
            op(r, self.e * mag(d))
        }
        fn sin(self) -> Bounded {
            func(self, self.v.sin(), self.v.cos())
        }
        fn cos(self) -> Bounded {
            func(self, self.v.cos(), self.v.sin())
        }
        fn abs(self) -> Bounded {
            Bounded {
                v: self.v.abs(),
                e: self.e,
            }
        }
        fn nominal(&self) -> f64 {
            self.v.to_f64()
        }
        fn is_zero(&self) -> bool {
            self.v == Dd::ZERO
        }
        fn is_one(&self) -> bool {
            self.v == Dd::ONE && self.e == 0.0
        }
    }

    impl Elementary for Bounded {
        fn tan(self) -> Bounded {
            let t = self.v.tan();
            func(self, t, Dd::ONE + t * t)
        }
        fn exp(self) -> Bounded {
            let v = self.v.exp();
            func(self, v, v)
        }
        fn ln(self) -> Bounded {
            func(self, self.v.ln(), Dd::ONE / self.v)
        }
        fn atan2(self, x: Bounded) -> Bounded {
            let (y, xv) = (self.v, x.v);
            let r2 = y * y + xv * xv;
            let e = (self.e * mag(xv) + x.e * mag(y)) / mag(r2);
            op(y.atan2(xv), e + mag(y.atan2(xv)))
        }
        fn powf(self, p: Bounded) -> Bounded {
            let v = self.v.powf(p.v);
            let e = self.e * mag(p.v * v / self.v) + p.e * mag(v * self.v.ln());
            op(v, e + mag(v))
        }
    }
}

/// Accuracy of the generated code against the formula it was generated from: at points
/// within ±20 % of nominal, every entry's error against a double-double evaluation of the
/// same expressions, in units of the running error bound of evaluating those expressions in
/// `f64` as the pool holds them ([`Bounded`]). The interpreter evaluates them that way and
/// stays below one bound. The generated code evaluates a rewritten formula (sums
/// reassociated by ready time, `x·x⁻¹` cancelled, common factors pulled out), so it may
/// exceed the bound by the factor reassociation allows, but a rewrite that creates a
/// cancellation the formula does not have (an `a + b − (a + b − c)` computed as written) costs
/// many bounds. Entries that cancel in the physics (near-zero rows of the bicycle's A) have
/// a large bound and are judged fairly.
#[test]
fn generated_code_is_accurate_against_double_double() {
    use eom_sym::tape::eval_generic;
    use rand::{Rng, SeedableRng, rngs::StdRng};
    let eps = f64::EPSILON;
    // In units of the bound, which counts a full `eps` per operation where rounding costs at
    // most half of it, so a formula evaluated as written stays below 0.5 (measured: 0.50,
    // the same entries in the interpreter). Reassociating an n-term sum can multiply the bound
    // of the sum by a small factor; a cancellation the formula lacks costs thousands (checked
    // by computing every quotient's numerator as `(n + 1e8) − 1e8` in the renderer: the
    // bicycle then fails at 18 000).
    let allowed = 4.0;
    let mut report = String::new();
    for g in all_f64().into_iter().chain(variants()) {
        let r = reference(g.model);
        let ss = r.sym.state_space();
        let mats = [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys];
        let roots: Vec<eom_sym::Expr> = mats.iter().flat_map(|m| m.iter().copied()).collect();
        let pos: std::collections::HashMap<u32, usize> = r
            .sym
            .params
            .iter()
            .enumerate()
            .map(|(k, p)| (p.param_index().expect("a parameter"), k))
            .collect();
        let nominal = r.model.scope.nominal_values();
        let mut rng = StdRng::seed_from_u64(20261121);
        let points = if g.model == "chain50" { 4 } else { 48 };
        let (mut worst_gen, mut worst_int, mut done) = (0.0f64, 0.0f64, 0);
        for _ in 0..points {
            let values: Vec<f64> = nominal
                .iter()
                .map(|&x| {
                    let f = rng.random_range(0.8..1.2);
                    if x == 0.0 { f - 1.0 } else { x * f }
                })
                .collect();
            let Ok(mut got) = (g.abcd)(&values) else {
                continue;
            };
            got.extend((g.phys)(&values).expect("eval_phys after eval_abcd succeeded"));
            let interp = to_vecs(&r.sym.evaluate(&values).expect("interpreter"));
            let exact = eval_generic::<Bounded>(&roots, |i| {
                pos.get(&i).map(|&k| Bounded {
                    v: eom_sym::Dd::from_f64(values[k]),
                    e: 0.0,
                })
            })
            .expect("double-double evaluation");
            let (got, interp): (Vec<f64>, Vec<f64>) = (got.concat(), interp.concat());
            for (k, x) in exact.iter().enumerate() {
                let want = x.v.to_f64();
                // Units of the bound (in `eps`); an entry computed without rounding must be exact.
                let units = |y: f64| {
                    let d = (y - want).abs();
                    if d == 0.0 { 0.0 } else { d / (eps * x.e) }
                };
                let (ug, ui) = (units(got[k]), units(interp[k]));
                assert!(
                    ug.is_finite(),
                    "{}: entry {k} (column-major over A, B, C, D, Phys) is computed without rounding in the formula but differs by {:e}",
                    g.model,
                    got[k] - want
                );
                worst_gen = worst_gen.max(ug);
                worst_int = worst_int.max(ui);
            }
            done += 1;
        }
        assert!(done > 0, "{}: no point inside the validity region", g.model);
        report.push_str(&format!(
            "{:12} worst error in bounds: generated {worst_gen:.3}, interpreter {worst_int:.3}\n",
            g.model
        ));
        assert!(
            worst_gen <= allowed,
            "{}: generated code is {worst_gen} running-error bounds off (interpreter {worst_int})\n{report}",
            g.model
        );
    }
    eprint!("{report}");
}
