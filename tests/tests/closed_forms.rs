//! Built-in models against closed-form results (docs/references.md §D, §E), evaluated here at
//! many parameter values, by the symbolic, numeric and robust paths. The reference numbers of
//! each model (at its defaults and elsewhere) live beside it in `models/NAME.ref.toml`, checked
//! through the command line by eom-cli/tests/references.rs.

use eom_model::{Linearizer, Method};
use eom_num::StateSpace;
use num_complex::Complex64;
use tests::{max_relative_error, nonzero};

const METHODS: [Method; 3] = [Method::Symbolic, Method::Numeric, Method::Robust];

fn state_space(model: &str, at: &[(&str, f64)], method: Method) -> StateSpace<f64> {
    let m = models::build(model, &[]).unwrap();
    Linearizer::new(&m)
        .at(at)
        .method(method)
        .run()
        .unwrap()
        .state_space
}

fn eig(ss: &StateSpace<f64>) -> Vec<Complex64> {
    eom_num::modes::eigenvalues(&ss.a).unwrap()
}

fn c(re: f64, im: f64) -> Complex64 {
    Complex64::new(re, im)
}

/// m z'' + c z' + k z = f: s = −c/2m ± i√(k/m − c²/4m²) (docs/references.md §E; the EoM sample `input_ex_smd`).
#[test]
fn spring_mass_damper() {
    for &(m, k, cc) in &[
        (1.0f64, 10.0, 0.1),
        (2.5, 40.0, 3.0),
        (0.3, 0.7, 0.05),
        (1.0, 50.0, 0.2),
    ] {
        let wd = (k / m - cc * cc / (4.0 * m * m)).sqrt();
        let exp = [c(-cc / (2.0 * m), wd), c(-cc / (2.0 * m), -wd)];
        for method in METHODS {
            let ss = state_space("smd", &[("m", m), ("k", k), ("c", cc)], method);
            assert_eq!(ss.states(), 2);
            let err = max_relative_error(&eig(&ss), &exp, 1e-300);
            assert!(err < 1e-13, "m {m} k {k} c {cc} {method:?}: {err:e}");
        }
    }
}

/// (Ix + m r²) φ'' + m g r φ = … : s = ±i √(m g r/(Ix + m r²)) (docs/references.md §E). The
/// EoM sample's defaults (Ix = 5.5 − m r² = −4.5, unphysical as a centroidal inertia) give
/// ±4.2226661117011242i, and are accepted with a warning.
#[test]
fn pendulum() {
    for &(m, r, ix, g) in &[
        (10.0f64, 1.0, -4.5, 9.807),
        (10.0, 1.0, 1.0, 9.807),
        (2.0, 0.4, 0.05, 9.81),
        (7.0, 2.0, 3.0, 1.62),
    ] {
        let w = (m * g * r / (ix + m * r * r)).sqrt();
        for method in METHODS {
            let ss = state_space(
                "pendulum",
                &[("m", m), ("r", r), ("Ix", ix), ("g", g)],
                method,
            );
            let err = max_relative_error(&eig(&ss), &[c(0.0, w), c(0.0, -w)], 1e-300);
            assert!(err < 1e-13, "{method:?} Ix {ix}: {err:e}");
        }
    }
    let model = models::build("pendulum", &[("Ix", -4.5)]).unwrap();
    let lin = Linearizer::new(&model).run().unwrap();
    assert!(
        lin.warnings
            .iter()
            .any(|w| matches!(w, eom_model::Warning::NegativeMoments { .. })),
        "{:?}",
        lin.warnings
    );
}

/// Heavy symmetric top on a fixed point: (I_p s² − m g h)² + (I_a r s)² = 0 with
/// I_p = I_t + m h², plus two zero eigenvalues (rotation about the vertical and its rate).
/// Stable (purely imaginary) above r = 2√(I_p m g h)/I_a (5.568 rad/s at the defaults).
#[test]
fn spinning_top() {
    let (m, h, it, ia, g) = (0.01, 0.04, 3e-4, 4e-4, 9.81);
    let ip = it + m * h * h;
    let mgh = m * g * h;
    for &r in &[1.0, 5.0, 8.0, 10.0] {
        let d = Complex64::new(4.0 * ip * mgh - ia * ia * r * r, 0.0).sqrt();
        let iar = c(0.0, ia * r);
        let exp = [
            (d + iar) / (2.0 * ip),
            (-d + iar) / (2.0 * ip),
            (d - iar) / (2.0 * ip),
            (-d - iar) / (2.0 * ip),
        ];
        for method in METHODS {
            let ss = state_space("top", &[("r", r)], method);
            assert_eq!(ss.states(), 6);
            let e = eig(&ss);
            let zeros = e.iter().filter(|z| z.norm() < 1e-6).count();
            assert_eq!(zeros, 2, "{e:?}");
            let err = max_relative_error(&nonzero(&e, 1e-6), &exp, 1e-300);
            assert!(err < 1e-12, "r {r} {method:?}: {err:e}");
        }
    }
}

/// Uniform disk rolling upright: eliminating the yaw rate from the linearized equations gives
/// (A + m r²) φ'' + (3 m u² − m g r) φ = 0 with A = m r²/4, i.e. s² = 4(g r − 3u²)/(5 r²):
/// stable above u = √(g r/3) (1.2787 m/s for r = 0.5). The other four
/// eigenvalues are zero (heading, rolling angle, lateral and longitudinal position).
#[test]
fn rolling_disk() {
    let (r, g) = (0.5, 9.81);
    for &u in &[0.1, 0.5, 1.0, 1.5, 3.0] {
        let s2 = 4.0 * (g * r - 3.0 * u * u) / (5.0 * r * r);
        let s = Complex64::new(s2, 0.0).sqrt();
        for method in METHODS {
            let ss = state_space("disk", &[("u", u)], method);
            let e = eig(&ss);
            // The four zero eigenvalues form Jordan blocks; in the robust path's orthonormal
            // basis rounding splits them by ε^(1/3) ≈ 1e-5.
            let big = nonzero(&e, 1e-4);
            assert_eq!(big.len(), 2, "u {u} {method:?}: {e:?}");
            let err = max_relative_error(&big, &[s, -s], 1e-300);
            assert!(err < 1e-12, "u {u} {method:?}: {err:e}");
        }
    }
}

/// N equal masses in a fixed–free chain, spring k and damper c in every link: M = m I,
/// K = k T, C = c T with T = tridiag(−1, 2, −1) except T_NN = 1, whose eigenvalues are
/// μ_j = 4 sin²((2j − 1)π / (2(2N + 1))). Each mode: m s² + c μ s + k μ = 0.
#[test]
fn chain_of_masses() {
    for &n in &[1usize, 2, 5, 10, 30] {
        let (m, k, cc) = (1.3, 2.0, 0.07);
        let mut exp = Vec::new();
        for j in 1..=n {
            let mu = 4.0
                * ((2 * j - 1) as f64 * std::f64::consts::PI / (2.0 * (2 * n + 1) as f64))
                    .sin()
                    .powi(2);
            let b = cc * mu / m;
            let disc = Complex64::new(b * b / 4.0 - k * mu / m, 0.0).sqrt();
            exp.push(-b / 2.0 + disc);
            exp.push(-b / 2.0 - disc);
        }
        for method in METHODS {
            let ss = state_space(
                &format!("chain{n}"),
                &[("m", m), ("k", k), ("c", cc)],
                method,
            );
            assert_eq!(ss.states(), 2 * n);
            let err = max_relative_error(&eig(&ss), &exp, 1e-300);
            assert!(err < 1e-11, "chain{n} {method:?}: {err:e}");
        }
    }
}

/// The chain with its own m, k, c per element (`chainpN`): at the defaults its eigenvalues
/// are those of `chainN` (and of the closed form above); at per-element values they are those of
/// [0 I; −M⁻¹K −M⁻¹C] with M = diag(m_i) and K, C the tridiagonal link matrices written out
/// here (link i between masses i − 1 and i, link 1 to ground).
#[test]
fn chain_with_parameters_per_element() {
    let nominal = |name: &str| {
        let m = models::build(name, &[]).unwrap();
        let ss = Linearizer::new(&m)
            .method(Method::Numeric)
            .run()
            .unwrap()
            .state_space;
        eig(&ss)
    };
    let p50 = models::build("chainp50", &[]).unwrap();
    assert_eq!(p50.scope.names().len(), 150);
    let err = max_relative_error(&nominal("chainp50"), &nominal("chain50"), 1e-300);
    assert!(err < 1e-12, "chainp50 vs chain50 at the defaults: {err:e}");

    let n = 7;
    let value = |stem: &str, i: usize| 0.5 + 0.1 * i as f64 + if stem == "k" { 1.0 } else { 0.0 };
    let (mut at, mut m, mut k, mut c) = (Vec::new(), vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for i in 0..n {
        m[i] = value("m", i);
        k[i] = value("k", i) * (1.0 + 0.3 * (i % 3) as f64);
        c[i] = 0.02 * (i + 1) as f64;
        at.push((format!("m{}", i + 1), m[i]));
        at.push((format!("k{}", i + 1), k[i]));
        at.push((format!("c{}", i + 1), c[i]));
    }
    // Link i joins mass i − 1 (ground for i = 0) and mass i.
    let link = |x: &[f64]| {
        nalgebra::DMatrix::from_fn(n, n, |r, s| {
            let mut v = 0.0;
            if r == s {
                v += x[r] + if r + 1 < n { x[r + 1] } else { 0.0 };
            } else if r + 1 == s {
                v -= x[s];
            } else if s + 1 == r {
                v -= x[r];
            }
            v
        })
    };
    let minv = nalgebra::DMatrix::from_fn(n, n, |r, s| if r == s { 1.0 / m[r] } else { 0.0 });
    let mut a = nalgebra::DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, n), (n, n))
        .copy_from(&nalgebra::DMatrix::identity(n, n));
    a.view_mut((n, 0), (n, n)).copy_from(&(-&minv * link(&k)));
    a.view_mut((n, n), (n, n)).copy_from(&(-&minv * link(&c)));
    let want = eom_num::modes::eigenvalues(&a).unwrap();
    let at: Vec<(&str, f64)> = at.iter().map(|(s, v)| (s.as_str(), *v)).collect();
    for method in METHODS {
        let ss = state_space(&format!("chainp{n}"), &at, method);
        let err = max_relative_error(&eig(&ss), &want, 1e-300);
        assert!(err < 1e-11, "chainp{n} {method:?}: {err:e}");
    }
}

/// Quarter car: det(M s² + C s + K) with M = diag(ms, mu), C = [[cs, −cs], [−cs, cs + ct]],
/// K = [[ks, −ks], [−ks, ks + kt]] — the closed-form quartic, whose roots (companion matrix)
/// are compared with the model's eigenvalues.
#[test]
fn quarter_car_eigenvalues() {
    for &(ms, mu, ks, kt, cs, ct) in &[
        (500.0, 50.0, 18000.0, 180000.0, 1500.0, 500.0),
        (500.0, 65.0, 18000.0, 200000.0, 1500.0, 100.0),
        (320.0, 40.0, 25000.0, 150000.0, 900.0, 0.0),
    ] {
        // (ms s² + cs s + ks)(mu s² + (cs+ct) s + ks + kt) − (cs s + ks)²
        let p1 = [ks, cs, ms];
        let p2 = [ks + kt, cs + ct, mu];
        let mut poly = [0.0; 5];
        for i in 0..3 {
            for j in 0..3 {
                poly[i + j] += p1[i] * p2[j];
            }
        }
        poly[0] -= ks * ks;
        poly[1] -= 2.0 * cs * ks;
        poly[2] -= cs * cs;
        let lead = poly[4];
        let comp = nalgebra::DMatrix::from_fn(4, 4, |i, j| {
            if i == 0 {
                -poly[3 - j] / lead
            } else if i == j + 1 {
                1.0
            } else {
                0.0
            }
        });
        let exp = eom_num::modes::eigenvalues(&comp).unwrap();
        for method in METHODS {
            let ss = state_space(
                "quarter_car",
                &[
                    ("ms", ms),
                    ("mu", mu),
                    ("ks", ks),
                    ("kt", kt),
                    ("cs", cs),
                    ("ct", ct),
                ],
                method,
            );
            let err = max_relative_error(&eig(&ss), &exp, 1e-300);
            assert!(err < 1e-11, "{method:?}: {err:e}");
        }
    }
}
