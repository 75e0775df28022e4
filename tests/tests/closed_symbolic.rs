//! Closed forms (`eom_sym::closed`) of the built-in models against their references: the
//! characteristic polynomials of docs/references.md, the numeric characteristic polynomial at
//! random parameter points, and the numeric stability of the eigenvalues.

use eom_model::{Linearizer, Method, Model};
use eom_sym::closed::{CharacteristicPolynomial, ClosedForms};
use eom_sym::{Expr, Tape};
use nalgebra::DMatrix;
use num_complex::Complex64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn symbolic_a(m: &Model) -> DMatrix<Expr> {
    Linearizer::new(m)
        .symbolic()
        .expect("symbolic")
        .state_space()
        .a
        .clone()
}

/// Values of `exprs` at the point `values` (in the order of the model's parameters).
fn eval(m: &Model, exprs: &[Expr], values: &[f64]) -> Vec<f64> {
    Tape::new(exprs, &m.scope.params())
        .expect("tape")
        .eval_vec(values)
        .expect("finite")
}

/// Each parameter drawn uniformly within ±`spread` of its nominal value (relative).
fn random_point(m: &Model, rng: &mut StdRng, spread: f64) -> Vec<f64> {
    m.scope
        .nominal_values()
        .iter()
        .map(|&v| {
            let f = 1.0 + spread * (2.0 * rng.random::<f64>() - 1.0);
            if v == 0.0 { f - 1.0 } else { v * f }
        })
        .collect()
}

/// Monic coefficients (ascending) of `Π (s − λ)` from the numeric eigenvalues of A at a point.
fn numeric_charpoly(m: &Model, values: &[f64]) -> Vec<f64> {
    let named: Vec<(String, f64)> = m
        .scope
        .names()
        .into_iter()
        .zip(values.iter().copied())
        .collect();
    let at: Vec<(&str, f64)> = named.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    let ss = Linearizer::new(m)
        .at(&at)
        .method(Method::Numeric)
        .run()
        .expect("numeric")
        .state_space;
    let eig = eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues");
    let mut p = vec![Complex64::new(1.0, 0.0)];
    for l in eig {
        let mut q = vec![Complex64::new(0.0, 0.0); p.len() + 1];
        for (k, &c) in p.iter().enumerate() {
            q[k + 1] += c;
            q[k] -= l * c;
        }
        p = q;
    }
    p.iter().map(|c| c.re).collect()
}

/// The closed form's coefficients at a point, made monic, with the zero roots restored.
fn closed_monic(m: &Model, p: &CharacteristicPolynomial, values: &[f64]) -> Vec<f64> {
    let c = eval(m, &p.polynomial.coefficients, values);
    let lead = *c.last().expect("a coefficient");
    let mut out = vec![0.0; p.zero_roots];
    out.extend(c.iter().map(|x| x / lead));
    out
}

fn assert_same_polynomial(m: &Model, p: &CharacteristicPolynomial, values: &[f64], tol: f64) {
    let got = closed_monic(m, p, values);
    let want = numeric_charpoly(m, values);
    assert_eq!(got.len(), want.len(), "degree at {values:?}");
    let scale = want.iter().fold(1.0f64, |a, x| a.max(x.abs()));
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert!(
            (g - w).abs() <= tol * scale,
            "{}: coefficient of s^{k}: closed form {g}, numeric {w} at {values:?}",
            m.name
        );
    }
}

#[test]
fn spring_mass_damper_is_m_s2_plus_c_s_plus_k() {
    let m = models::build("smd", &[]).expect("smd");
    let p = ClosedForms::default()
        .characteristic_polynomial(&symbolic_a(&m))
        .expect("charpoly");
    let [mass, c, k] = ["m", "c", "k"].map(|n| m.scope.get(n).expect("param"));
    assert!(p.normalized);
    assert_eq!(p.polynomial.coefficients, vec![k, c, mass]);
    assert_eq!(p.scale, mass);
    let so = ClosedForms::default()
        .second_order(&p)
        .expect("second order")
        .expect("degree 2");
    let at = m.scope.nominal_values();
    let v = eval(&m, &[so.natural_frequency, so.damping_ratio], &at);
    let value = |n: &str| at[m.scope.names().iter().position(|x| x == n).expect("param")];
    let (mm, cc, kk) = (value("m"), value("c"), value("k"));
    assert!((v[0] - (kk / mm).sqrt()).abs() < 1e-14);
    assert!((v[1] - cc / (2.0 * (kk * mm).sqrt())).abs() < 1e-14);
}

/// The shimmy's cubic `(I + m a²) s³ + m a u s² + k l² s + k l u` with `a = x l`
/// (docs/references.md §B), symbolically and at 1 000 random points.
#[test]
fn shimmy_cubic_and_its_stability_conditions() {
    let m = models::build("shimmy", &[]).expect("shimmy");
    let cf = ClosedForms::default();
    let p = cf
        .characteristic_polynomial(&symbolic_a(&m))
        .expect("charpoly");
    let [mass, i, k, l, x, u] = ["m", "I", "k", "l", "x", "u"].map(|n| m.scope.get(n).expect("p"));
    let a = x * l;
    let reference = [k * l * u, k * l * l, mass * a * u, i + mass * a * a];
    assert!(p.normalized);
    assert_eq!(p.zero_roots, 0);
    for (got, want) in p.polynomial.coefficients.iter().zip(&reference) {
        assert!(
            eom_sym::zero::is_identically_zero(*got - *want),
            "{got} is not {want}"
        );
    }
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..1000 {
        let at = random_point(&m, &mut rng, 0.5);
        assert_same_polynomial(&m, &p, &at, 1e-11);
    }

    // Stability: u > 0, x > 0 and m x (1 − x) l² > I, in some form.
    let conds = cf.stability_conditions(&p).expect("conditions");
    let target = mass * x * (1i64 - x) * l * l - i;
    assert!(
        conds
            .iter()
            .any(|c| eom_sym::zero::is_identically_zero(c.expression - target)),
        "{:?}",
        conds
            .iter()
            .map(|c| c.expression.to_string())
            .collect::<Vec<_>>()
    );
    // The boundary in closed form: x = 1/2 ∓ √(1/4 − I/(m l²)).
    let quad = conds
        .iter()
        .find_map(|c| {
            cf.solve_boundary(c.expression, x)
                .ok()
                .flatten()
                .filter(|b| b.roots.len() == 2)
        })
        .expect("a quadratic boundary");
    let rho = (Expr::rational(1, 4).expect("1/4") - i / (mass * l * l)).sqrt();
    let half = Expr::rational(1, 2).expect("1/2");
    let want = [half - rho, half + rho];
    let radicand = Tape::new(&[rho * rho], &m.scope.params()).expect("tape");
    let mut checked = 0;
    while checked < 100 {
        let at = random_point(&m, &mut rng, 0.3);
        if radicand.eval_vec(&at).expect("radicand")[0] < 0.0 {
            continue; // no stable interval at this point
        }
        checked += 1;
        let got = eval(&m, &quad.roots, &at);
        let w = eval(&m, &want, &at);
        for (g, w) in got.iter().zip(&w) {
            assert!((g - w).abs() < 1e-13, "{g} vs {w}");
        }
    }
}

/// The conditions agree with the sign of the largest real part of the numeric eigenvalues at
/// 10 000 random points (where that is not within 1e-9 of zero).
#[test]
fn shimmy_conditions_agree_with_the_eigenvalues() {
    let m = models::build("shimmy", &[]).expect("shimmy");
    let cf = ClosedForms::default();
    let p = cf
        .characteristic_polynomial(&symbolic_a(&m))
        .expect("charpoly");
    let conds = cf.stability_conditions(&p).expect("conditions");
    let exprs: Vec<Expr> = conds.iter().map(|c| c.expression).collect();
    let tape = Tape::new(&exprs, &m.scope.params()).expect("tape");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let mut rng = StdRng::seed_from_u64(11);
    let (mut stable, mut unstable) = (0, 0);
    for _ in 0..10_000 {
        let mut at = random_point(&m, &mut rng, 0.9);
        // x over [−0.5, 1.5] and u of either sign: both sides of every condition.
        at[4] = 2.0 * rng.random::<f64>() - 0.5;
        at[5] = 20.0 * rng.random::<f64>() - 5.0;
        let ss = sym.evaluate(&at).expect("evaluate");
        let eig = eom_num::modes::eigenvalues(&ss.a).expect("eig");
        let max_re = eig.iter().map(|l| l.re).fold(f64::NEG_INFINITY, f64::max);
        if max_re.abs() < 1e-9 {
            continue;
        }
        let v = tape.eval_vec(&at).expect("conditions");
        let holds = v.iter().all(|&c| c > 0.0);
        assert_eq!(
            holds,
            max_re < 0.0,
            "at {at:?}: conditions {v:?}, max Re λ {max_re}"
        );
        if holds { stable += 1 } else { unstable += 1 }
    }
    assert!(
        stable > 1000 && unstable > 1000,
        "{stable} stable, {unstable} unstable"
    );
}

/// The quarter car's quartic `det(M s² + C s + K)/(ms mu)` and its transfer functions against
/// the numeric `C (sI − A)⁻¹ B + D`.
#[test]
fn quarter_car_polynomial_and_transfer_functions() {
    let m = models::build("quarter_car", &[]).expect("quarter car");
    let cf = ClosedForms::default();
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let ss = sym.state_space();
    let p = cf.characteristic_polynomial(&ss.a).expect("charpoly");
    let [ms, mu, ks, kt, cs, ct] =
        ["ms", "mu", "ks", "kt", "cs", "ct"].map(|n| m.scope.get(n).expect("p"));
    let reference = [
        ks * kt,
        ks * ct + kt * cs,
        ms * ks + ms * kt + mu * ks + cs * ct,
        ms * cs + ms * ct + mu * cs,
        ms * mu,
    ];
    for (got, want) in p.polynomial.coefficients.iter().zip(&reference) {
        assert!(
            eom_sym::zero::is_identically_zero(*got - *want),
            "{got} is not {want}"
        );
    }
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..1000 {
        let at = random_point(&m, &mut rng, 0.5);
        assert_same_polynomial(&m, &p, &at, 1e-11);
    }
    for out in 0..ss.c.nrows() {
        for inp in 0..ss.b.ncols() {
            let tf = cf
                .transfer_function([&ss.a, &ss.b, &ss.c, &ss.d], out, inp)
                .expect("transfer function");
            assert!(tf.normalized);
            for _ in 0..50 {
                let at = random_point(&m, &mut rng, 0.5);
                let num = eval(&m, &tf.numerator.coefficients, &at);
                let den = eval(&m, &tf.denominator.coefficients, &at);
                let n = sym.evaluate(&at).expect("evaluate");
                let s = Complex64::new(0.3 * rng.random::<f64>(), 30.0 * rng.random::<f64>());
                let horner = |c: &[f64]| {
                    c.iter()
                        .rev()
                        .fold(Complex64::new(0.0, 0.0), |a, &x| a * s + x)
                };
                let g = horner(&num) / horner(&den);
                let want = numeric_tf(&n, out, inp, s);
                assert!(
                    (g - want).norm() <= 1e-9 * want.norm().max(1e-12),
                    "G[{out},{inp}]({s}) = {g}, numeric {want}"
                );
            }
        }
    }
}

/// `C (sI − A)⁻¹ B + D` at one `s`, entry (out, inp).
fn numeric_tf(ss: &eom_num::StateSpace<f64>, out: usize, inp: usize, s: Complex64) -> Complex64 {
    let n = ss.a.nrows();
    let m = DMatrix::from_fn(n, n, |i, j| {
        let a = Complex64::new(-ss.a[(i, j)], 0.0);
        if i == j { a + s } else { a }
    });
    let b = DMatrix::from_fn(n, 1, |i, _| Complex64::new(ss.b[(i, inp)], 0.0));
    let x = m.lu().solve(&b).expect("regular");
    (0..n).fold(Complex64::new(ss.d[(out, inp)], 0.0), |acc, j| {
        acc + x[(j, 0)] * ss.c[(out, j)]
    })
}

/// The bicycle with all 27 parameters symbolic: `s² ·` a quartic, at 1 000 random points.
#[test]
fn bicycle_polynomial_at_random_points() {
    let m = models::build("bicycle", &[]).expect("bicycle");
    let p = ClosedForms::default()
        .characteristic_polynomial(&symbolic_a(&m))
        .expect("charpoly");
    assert_eq!(p.zero_roots, 2, "heading and lateral position");
    assert_eq!(p.polynomial.degree(), 4);
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..1000 {
        let at = random_point(&m, &mut rng, 0.1);
        assert_same_polynomial(&m, &p, &at, 1e-9);
    }
    // From the descriptor pencil (no nested divisions by the mass matrix): the same polynomial.
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let (e, f) = sym.pencil();
    let q = ClosedForms::default()
        .pencil_polynomial(Some(&e), &f)
        .expect("pencil polynomial");
    assert_eq!(q.zero_roots, 2);
    // Both forms are of a size: 560 and 547 operations since the pivots keep the rear
    // frame's coordinates independent (before, the pencil's was the smaller).
    let (pencil_ops, a_ops) = (
        Expr::op_count(&q.polynomial.coefficients).total(),
        Expr::op_count(&p.polynomial.coefficients).total(),
    );
    assert!(
        pencil_ops < 2 * a_ops && a_ops < 2 * pencil_ops,
        "{pencil_ops} {a_ops}"
    );
    for _ in 0..1000 {
        let at = random_point(&m, &mut rng, 0.1);
        assert_same_polynomial(&m, &q, &at, 1e-9);
        // and det(sI − A) = s² p(s)/scale: the scale is det(M) times the normal form's factor.
        let lead = eval(&m, &[q.polynomial.coefficients[4], q.scale], &at);
        assert!(
            (lead[0] / lead[1] - 1.0).abs() < 1e-9,
            "det(sI − A) is monic: {lead:?}"
        );
    }
}

/// The spring-mass-damper under a wing (docs/references.md §D): the polynomial is
/// m s² + (c + ρVS(CLα + CD)/2) s + k symbolically, and agrees with the numeric eigenvalues at
/// 1 000 random points; the damping ratio is the seed paper's eq. 13 and the only stability
/// condition is the total damping.
#[test]
fn spring_mass_wing_is_the_closed_form_of_eq_13() {
    let m = models::build("smd_wing", &[]).expect("smd_wing");
    let cf = ClosedForms::default();
    let p = cf
        .characteristic_polynomial(&symbolic_a(&m))
        .expect("charpoly");
    let s = |n: &str| m.scope.get(n).expect("param");
    let damping = s("c") + s("rho") * s("V") * s("S") * (s("CLa") + s("CD")) / 2i64;
    let coefficients = &p.polynomial.coefficients;
    assert_eq!(coefficients.len(), 3);
    // Up to the common factor the normalisation chose: p(s)/lead = s² + damping/m s + k/m.
    let lead = coefficients[2];
    let zero = eom_sym::zero::is_identically_zero;
    assert!(
        zero(coefficients[1] * s("m") - damping * lead),
        "{coefficients:?}"
    );
    assert!(
        zero(coefficients[0] * s("m") - s("k") * lead),
        "{coefficients:?}"
    );
    let mut rng = StdRng::seed_from_u64(13);
    for _ in 0..1000 {
        let at = random_point(&m, &mut rng, 0.5);
        assert_same_polynomial(&m, &p, &at, 1e-12);
    }
    let so = cf
        .second_order(&p)
        .expect("second order")
        .expect("degree 2");
    let want = damping / (2i64 * Expr::sqrt(s("m") * s("k")));
    assert!(zero(so.damping_ratio - want), "{}", so.damping_ratio);
    let conditions = cf.stability_conditions(&p).expect("conditions");
    assert_eq!(conditions.len(), 1, "{conditions:?}");
    // The condition is the damping times a positive constant: the same ratio everywhere.
    let ratio = conditions[0].expression / damping;
    let mut first = None;
    for _ in 0..100 {
        let r = eval(&m, &[ratio], &random_point(&m, &mut rng, 0.5))[0];
        assert!(r > 0.0, "{}", conditions[0].expression);
        let r0 = *first.get_or_insert(r);
        assert!((r - r0).abs() <= 1e-14 * r0, "{}", conditions[0].expression);
    }
}
