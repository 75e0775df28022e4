//! The models with wings against independent references: the seed paper's damping entries of
//! the shimmy's fin, the closed form of the spring–mass–damper under a wing
//! (docs/references.md §D), the vortex-lattice fin against the paper's entries, a
//! bounce–pitch model derived by hand for the car with wings, and the three reduction paths
//! against each other.

#![allow(clippy::excessive_precision)] // reference values as published

use eom_model::{Linearizer, Method, Model, assemble};
use nalgebra::{DMatrix, Matrix6};
use num_complex::Complex64;

/// The seed paper's damping entries of the fin at ρ = 1.225, V = 10 (N·s/m, N·s, N·s,
/// N·m·s): L22, L26, L62, L66.
const PAPER_L: [((usize, usize), f64); 4] = [
    ((1, 1), 7.59895),
    ((1, 5), -2.05293),
    ((5, 1), 0.153319),
    ((5, 5), 0.224167),
];

/// The assembled damping of body 0 of `model` minus that of `without` (the same model
/// without the wing), transformed back to the point `r` (from the body's mass centre):
/// `ΔC = Jᵀ L J`, `J = [[I, R], [0, I]]` with row i of R = `r × eᵢ`.
fn assembled_block(model: &Model, without: &Model, r: [f64; 3]) -> Matrix6<f64> {
    let c = |m: &Model| {
        let a = assemble(&m.nominal().expect("nominal")).expect("assembles");
        let mut d = Matrix6::zeros();
        for (i, j, v) in a.damping.iter() {
            if i < 6 && j < 6 {
                d[(i, j)] = v;
            }
        }
        d
    };
    let dc = c(model) - c(without);
    let mut j = Matrix6::identity();
    for i in 0..3 {
        let mut e = [0.0; 3];
        e[i] = 1.0;
        let x = [
            r[1] * e[2] - r[2] * e[1],
            r[2] * e[0] - r[0] * e[2],
            r[0] * e[1] - r[1] * e[0],
        ];
        for k in 0..3 {
            j[(i, 3 + k)] = x[k];
        }
    }
    let ji = j.try_inverse().expect("invertible");
    ji.transpose() * dc * ji
}

#[test]
fn shimmy_wing_assembled_block_is_the_papers() {
    for x in [0.5, 0.2] {
        let with = models::build("shimmy_wing", &[("u", 10.0), ("x", x)]).unwrap();
        let without = models::build("shimmy", &[("u", 10.0), ("x", x)]).unwrap();
        let l = assembled_block(&with, &without, [1.0 - x, 0.0, 0.0]);
        for ((i, j), want) in PAPER_L {
            let got = l[(i, j)];
            assert!(
                ((got - want) / want).abs() <= 1e-9,
                "x = {x}: L{}{} = {got}, paper {want}",
                i + 1,
                j + 1
            );
        }
        let others = (0..6)
            .flat_map(|i| (0..6).map(move |j| (i, j)))
            .filter(|ij| !PAPER_L.iter().any(|(k, _)| k == ij))
            .map(|ij| l[ij].abs())
            .fold(0.0, f64::max);
        assert!(others <= 1e-12, "other entries up to {others}");
    }
}

#[test]
fn shimmy_wing_point_block_is_the_papers() {
    let m = models::build("shimmy_wing", &[])
        .unwrap()
        .nominal()
        .unwrap();
    let w = m.wings().next().expect("a wing");
    let l = w.damping(m.airspeed_of(w));
    for ((i, j), want) in PAPER_L {
        assert!(((l[i][j] - want) / want).abs() <= 1e-9, "{}", l[i][j]);
    }
}

/// The characteristic roots of `m s² + c s + k`.
fn quadratic_roots(m: f64, c: f64, k: f64) -> [Complex64; 2] {
    let disc = Complex64::new(c * c - 4.0 * m * k, 0.0).sqrt();
    [(-c + disc) / (2.0 * m), (-c - disc) / (2.0 * m)]
}

fn sorted(mut z: Vec<Complex64>) -> Vec<Complex64> {
    z.sort_by(|a, b| a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im)));
    z
}

fn eigenvalues(model: &Model, at: &[(&str, f64)], method: Method) -> Vec<Complex64> {
    let ss = Linearizer::new(model)
        .at(at)
        .method(method)
        .run()
        .expect("linearizes")
        .state_space;
    sorted(eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues"))
}

fn close(got: &[Complex64], want: &[Complex64], tol: f64) -> bool {
    got.len() == want.len()
        && got
            .iter()
            .zip(want)
            .all(|(g, w)| (g - w).norm() <= tol * w.norm().max(1.0))
}

#[test]
fn smd_wing_matches_the_closed_form_everywhere() {
    let model = models::build("smd_wing", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    let mut seed = 7u64;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..200 {
        let v: Vec<f64> = (0..8).map(|_| 0.1 + 3.0 * next()).collect();
        let (m, k, c, rho, vel, s, cla, cd) = (v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
        let c_tot = c + rho * vel * s * (cla + cd) / 2.0;
        let want = sorted(quadratic_roots(m, c_tot, k).to_vec());
        let a = sym.evaluate(&v).unwrap().a;
        let got = sorted(eom_num::modes::eigenvalues(&a).unwrap());
        assert!(close(&got, &want, 1e-12), "at {v:?}: {got:?} vs {want:?}");
    }
}

/// The vortex lattice's fin (8 × 16 cosine panels) is within 0.3 % of the paper's entries.
#[test]
fn shimmy_fin_is_within_three_tenths_of_a_percent_of_the_paper() {
    let with = models::build("shimmy_fin", &[("u", 10.0)]).unwrap();
    let without = models::build("shimmy", &[("u", 10.0)]).unwrap();
    let l = assembled_block(&with, &without, [0.5, 0.0, 0.0]);
    for ((i, j), want) in PAPER_L {
        let dev = (l[(i, j)] - want) / want;
        assert!(
            dev.abs() <= 3e-3,
            "L{}{} = {} is {:.3} % from the paper's {want}",
            i + 1,
            j + 1,
            l[(i, j)],
            100.0 * dev
        );
    }
}

/// The three reduction paths agree on every model with wings (each catalogue entry whose model
/// has one; a new one needs its second point here), at the defaults and at another point.
#[test]
fn every_path_agrees_on_the_wing_models() {
    let cases: [(&str, &[(&str, f64)]); 6] = [
        ("smd_wing", &[("V", 25.0)]),
        ("shimmy_wing", &[("x", 0.2), ("u", 3.0)]),
        ("shimmy_fin", &[("x", 0.8)]),
        ("ride_wings", &[("u", 60.0)]),
        ("aircraft_ground", &[("u", 25.0)]),
        ("navion", &[("V", 220.0)]),
    ];
    for info in models::catalogue() {
        let name = info.name_at(2);
        let model = models::build(&name, &[]).unwrap();
        assert!(
            model.wings().next().is_none() || cases.iter().any(|c| c.0 == name),
            "{name} has wings: give it a case here"
        );
    }
    for (name, at) in cases {
        let model = models::build(name, &[]).unwrap();
        for point in [&[][..], at] {
            let reference = eigenvalues(&model, point, Method::Robust);
            for method in [Method::Symbolic, Method::Numeric] {
                let got = eigenvalues(&model, point, method);
                // The aircraft's lateral position and heading are a double zero eigenvalue
                // (a Jordan block), which rounding splits by about √ε: compare the zeros
                // as zeros.
                let zero = |z: &Complex64| z.norm() < 1e-6;
                let nonzero =
                    |v: &[Complex64]| v.iter().filter(|z| !zero(z)).copied().collect::<Vec<_>>();
                assert_eq!(
                    got.iter().filter(|z| zero(z)).count(),
                    reference.iter().filter(|z| zero(z)).count(),
                    "{name} {point:?} {method:?}: zero eigenvalues"
                );
                assert!(
                    close(&nonzero(&got), &nonzero(&reference), 1e-8),
                    "{name} {point:?} {method:?}: {got:?} vs {reference:?}"
                );
            }
        }
    }
}

/// The car with wings derived by hand in the frame moving with the car (heave z up, pitch θ
/// about the model's y, nose down positive; the suspension acts on z − xθ and its rate), the
/// wings' forces from their derivatives: the wing at `xᵢ`, in the stream u coming from ahead,
/// sees in its own axes (x forward, z down) `w = −(ż + uθ − xᵢθ̇)` (the pitch attitude tilts
/// the stream) and `q = −θ̇`, and pushes `F_z = −Z`, `M_y = −M − xᵢ F_z`.
#[test]
fn ride_wings_matches_a_bounce_pitch_model_derived_by_hand() {
    let model = models::build("ride_wings", &[]).unwrap();
    let num = model.nominal().unwrap();
    let value = |n: &str| model.scope.get(n).unwrap().nominal();
    let (m, iy, a, b) = (value("m"), value("Iy"), value("a"), value("b"));
    let (kf, kr, cf, cr, u) = (
        value("kf"),
        value("kr"),
        value("cf"),
        value("cr"),
        value("u"),
    );
    // [z, θ] mass, damping and stiffness.
    let mm = DMatrix::from_diagonal(&nalgebra::dvector![m, iy]);
    let mut c = DMatrix::zeros(2, 2);
    let mut k = DMatrix::zeros(2, 2);
    for (x, ks, cs) in [(a, kf, cf), (-b, kr, cr)] {
        // deflection z − xθ
        let g = nalgebra::dvector![1.0, -x];
        k += ks * &g * g.transpose();
        c += cs * &g * g.transpose();
    }
    for w in num.wings() {
        let x = w.location[0];
        let q = w.density * num.airspeed_of(w) * w.area / 2.0;
        let d = &w.derivatives;
        let (zw, zq) = (q * d[2][2], q * d[2][4] * w.chord / 2.0);
        let (mw, mq) = (q * w.chord * d[4][2], q * w.chord * d[4][4] * w.chord / 2.0);
        // Z = zw·w + zq·q_w with w = −(ż + uθ − xθ̇), q_w = −θ̇; F_z = −Z.
        // F_z = zw ż + zw u θ + (−zw x + zq) θ̇
        // M_y = −M − x F_z, M = mw w + mq q_w.
        let fz = [zw, -zw * x + zq, zw * u]; // coefficients of ż, θ̇, θ
        let my = [
            mw - x * fz[0],
            (-mw * x + mq) - x * fz[1],
            mw * u - x * fz[2],
        ];
        // M ẍ + C ẋ + K x = forces → C −= ∂F/∂ẋ, K −= ∂F/∂x.
        c[(0, 0)] -= fz[0];
        c[(0, 1)] -= fz[1];
        k[(0, 1)] -= fz[2];
        c[(1, 0)] -= my[0];
        c[(1, 1)] -= my[1];
        k[(1, 1)] -= my[2];
    }
    let mi = mm.clone().try_inverse().unwrap();
    let mut a4 = DMatrix::zeros(4, 4);
    a4.view_mut((0, 2), (2, 2))
        .copy_from(&DMatrix::identity(2, 2));
    a4.view_mut((2, 0), (2, 2)).copy_from(&(-&mi * &k));
    a4.view_mut((2, 2), (2, 2)).copy_from(&(-&mi * &c));
    let want = sorted(eom_num::modes::eigenvalues(&a4).unwrap());
    for method in [Method::Symbolic, Method::Numeric, Method::Robust] {
        let got = eigenvalues(&model, &[], method);
        assert!(close(&got, &want, 1e-10), "{method:?}: {got:?} vs {want:?}");
    }
}

/// The rate check of a time response: the shimmy's yaw rate is one of its states, so the
/// normalised yaw rate of the fin is `|r|·b/2V` of that state, sample by sample.
#[test]
fn rates_of_a_response_are_checked_against_avls_limits() {
    let model = models::build("shimmy_wing", &[("u", 10.0)]).unwrap();
    let ss = Linearizer::new(&model).run().unwrap().state_space;
    let k = ss
        .names
        .states
        .iter()
        .position(|s| s == "chassis.wz")
        .expect("the yaw rate is a state");
    let num = model.nominal().unwrap();
    for (r0, exceeded) in [(1.0, false), (6.0, true)] {
        let mut x0 = nalgebra::DVector::zeros(ss.states());
        x0[k] = r0;
        let n = 400;
        let dt = 0.01;
        let u = DMatrix::zeros(ss.inputs(), n);
        let rates = eom_model::simulated_rates(&num, &ss, &u, dt, Some(&x0)).unwrap();
        // The reference: the yaw-rate state of the same response, x_k = e^{A k dt} x0.
        let phi = (&ss.a * dt).exp();
        let mut states = DMatrix::zeros(ss.states(), n);
        let mut x = x0.clone();
        for j in 0..n {
            states.set_column(j, &x);
            x = &phi * x;
        }
        assert_eq!(rates.len(), 1);
        let want = states.row(k).iter().fold(0.0f64, |m, r| m.max(r.abs())) * 1.0 / 20.0;
        let got = &rates[0];
        assert!(
            (got.max[2] - want).abs() <= 1e-10 * want,
            "{} vs {want}",
            got.max[2]
        );
        assert_eq!(got.max[0], 0.0, "no roll");
        assert_eq!(got.max[1], 0.0, "no pitch");
        assert_eq!(got.exceeded, [false, false, exceeded]);
        assert_eq!(got.warnings().len(), usize::from(exceeded));
    }
}
