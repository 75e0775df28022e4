//! The `truck_trailer` model against the linear single-track truck–trailer equations written
//! by hand (Newton–Euler for each body, the hitch force as the one unknown of the joint, linear
//! tyres `F = −c·α`): eigenvalues from those equations, the steady-state yaw-rate gain from
//! their closed-form solution. On every reduction path the gains are right to 1e-9 or the
//! analysis reports a failure (issue 19, case 4: the robust path's A hides the defective zero
//! pair of heading and lateral position in rounding, and `C A⁻¹ B` amplified it).

use eom_model::{Linearizer, Method};
use eom_num::NumError;
use eom_num::gain::{Gain, GainOptions, steady_state_gain_with};
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

/// The parameters, in the order of the catalogue.
#[derive(Clone, Copy, Debug)]
struct Truck {
    u: f64,
    m: f64,
    iz: f64,
    a: f64,
    b: f64,
    d: f64,
    cf: f64,
    cr: f64,
    mt: f64,
    it: f64,
    e: f64,
    h: f64,
    ct: f64,
}

const DEFAULTS: Truck = Truck {
    u: 10.0,
    m: 1730.3,
    iz: 3508.0,
    a: 1.289,
    b: 1.596,
    d: 2.7,
    cf: 80000.0,
    cr: 80000.0,
    mt: 2000.0,
    it: 3000.0,
    e: 2.7,
    h: 0.3,
    ct: 80000.0,
};

/// A point past the trailer's sway stability limit where the robust path's A split the
/// zero pair into ±4.6e-8 and the gain of r came out as 1.71 instead of −255.8.
const SPLIT_PAIR: Truck = Truck {
    u: 32.62854178786839,
    m: 1392.5172098071382,
    a: 1.1415764187627846,
    b: 1.4047348807768743,
    d: 1.9685550596593275,
    mt: 2467.2229086545653,
    e: 3.158418171064846,
    h: 0.3387717504569377,
    ..DEFAULTS
};

impl Truck {
    fn overrides(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("u", self.u),
            ("m", self.m),
            ("Iz", self.iz),
            ("a", self.a),
            ("b", self.b),
            ("d", self.d),
            ("cf", self.cf),
            ("cr", self.cr),
            ("mt", self.mt),
            ("It", self.it),
            ("et", self.e),
            ("h", self.h),
            ("ct", self.ct),
        ]
    }

    /// Steady-state yaw rate per unit steer angle, solved by hand: with r₁ = r₂ = r, the
    /// trailer's moment balance about its mass centre gives the hitch force
    /// Y = m_t·u·r·h/(e + h); the truck's force and moment balances then give the front and
    /// rear tyre forces F_f = K_f·r, F_r = K_r·r, and the front axle's slip condition
    /// δ = F_f/c_f + L·r/u − F_r/c_r.
    fn yaw_rate_gain(&self) -> f64 {
        let l = self.a + self.b;
        let w = self.mt * self.h / (self.e + self.h);
        let kf = self.u * (self.b * (self.m + w) - self.d * w) / l;
        let kr = self.u * (self.a * (self.m + w) + self.d * w) / l;
        1.0 / (l / self.u + kf / self.cf - kr / self.cr)
    }

    /// Eigenvalues of the hand-written equations in (v₁, r₁, r₂, γ): the trailer's lateral
    /// velocity follows from the hitch, v₂ = v₁ − d·r₁ − e·r₂ − u·γ; the unknowns of each
    /// instant are v̇₁, ṙ₁, ṙ₂ and the hitch force Y (on the trailer; −Y on the truck).
    /// The heading and lateral position add two zeros.
    fn eigenvalues(&self) -> Vec<Complex64> {
        let Truck {
            u,
            m,
            iz,
            a,
            b,
            d,
            cf,
            cr,
            mt,
            it,
            e,
            h,
            ct,
        } = *self;
        // Rows: truck force, truck moment, trailer force, trailer moment; unknowns
        // (v̇₁, ṙ₁, ṙ₂, Y).
        let lhs = DMatrix::from_row_slice(
            4,
            4,
            &[
                m,
                0.0,
                0.0,
                1.0, //
                0.0,
                iz,
                0.0,
                -d, //
                mt,
                -mt * d,
                -mt * e,
                -1.0, //
                0.0,
                0.0,
                it,
                -e,
            ],
        );
        let mut a_mat = DMatrix::<f64>::zeros(4, 4);
        for k in 0..4 {
            let mut x = DVector::<f64>::zeros(4);
            x[k] = 1.0;
            let (v1, r1, r2, g) = (x[0], x[1], x[2], x[3]);
            let v2 = v1 - d * r1 - e * r2 - u * g;
            let ff = -cf * (v1 + a * r1) / u;
            let fr = -cr * (v1 - b * r1) / u;
            let ft = -ct * (v2 - h * r2) / u;
            let rhs = DVector::from_vec(vec![
                ff + fr - m * u * r1,
                a * ff - b * fr,
                ft - mt * u * r1,
                -h * ft,
            ]);
            let z = lhs.clone().lu().solve(&rhs).expect("regular");
            a_mat[(0, k)] = z[0];
            a_mat[(1, k)] = z[1];
            a_mat[(2, k)] = z[2];
            a_mat[(3, k)] = r2 - r1;
        }
        let mut ev: Vec<Complex64> = a_mat.complex_eigenvalues().iter().copied().collect();
        ev.extend([Complex64::new(0.0, 0.0); 2]);
        ev
    }
}

const METHODS: [Method; 3] = [Method::Numeric, Method::Robust, Method::Symbolic];

#[test]
fn eigenvalues_match_the_single_track_equations_on_every_path() {
    for t in [
        DEFAULTS,
        Truck {
            u: 25.0,
            ..DEFAULTS
        },
        SPLIT_PAIR,
    ] {
        let model = models::build("truck_trailer", &t.overrides()).unwrap();
        let expected = t.eigenvalues();
        for method in METHODS {
            let lin = Linearizer::new(&model).method(method).run().unwrap();
            let got = eom_num::modes::eigenvalues(&lin.state_space.a).unwrap();
            let scale = expected.iter().fold(0.0f64, |m, z| m.max(z.norm()));
            for (g, e) in tests::match_eigenvalues(&got, &expected) {
                // The zero pair is split by rounding (√ε·‖A‖) on every path alike.
                let tol = if e.norm() == 0.0 {
                    1e-6 * scale
                } else {
                    1e-9 * e.norm()
                };
                assert!((g - e).norm() <= tol, "{method:?} at {t:?}: {g} vs {e}");
            }
        }
    }
}

/// The gains of one path, with the structural zeros the linearization found.
fn gains(t: &Truck, method: Method) -> Result<Vec<Gain>, NumError> {
    let model = models::build("truck_trailer", &t.overrides()).unwrap();
    let lin = Linearizer::new(&model).method(method).run().unwrap();
    let opts = GainOptions {
        structural_zeros: lin.structural_zeros.len(),
        ..GainOptions::default()
    };
    steady_state_gain_with(&lin.state_space, &opts).map(|g| g.gains.iter().copied().collect())
}

#[test]
fn yaw_rate_gain_matches_the_closed_form_on_every_path() {
    let points = [
        DEFAULTS,
        Truck { u: 2.0, ..DEFAULTS },
        Truck {
            u: 20.0,
            ..DEFAULTS
        },
        Truck {
            u: 30.0,
            ..DEFAULTS
        },
        SPLIT_PAIR,
    ];
    for t in points {
        let expected = t.yaw_rate_gain();
        for method in METHODS {
            let g = gains(&t, method).unwrap_or_else(|e| panic!("{method:?} at {t:?}: {e}"));
            // Outputs r, a_y (= u·r in the steady turn), γ.
            let r = g[0].finite().expect("finite yaw-rate gain");
            let ay = g[1].finite().expect("finite lateral acceleration gain");
            assert!(
                (r - expected).abs() <= 1e-9 * expected.abs(),
                "{method:?} at {t:?}: r/δ = {r}, closed form {expected}"
            );
            assert!(
                (ay - t.u * expected).abs() <= 1e-9 * (t.u * expected).abs(),
                "{method:?} at {t:?}: a_y/δ = {ay}, closed form {}",
                t.u * expected
            );
        }
    }
}

#[test]
fn without_the_structure_the_split_pair_is_a_reported_failure_not_a_wrong_gain() {
    let model = models::build("truck_trailer", &SPLIT_PAIR.overrides()).unwrap();
    let expected = SPLIT_PAIR.yaw_rate_gain();
    for method in METHODS {
        let lin = Linearizer::new(&model).method(method).run().unwrap();
        match steady_state_gain_with(&lin.state_space, &GainOptions::default()) {
            Ok(g) => {
                let r = g.get(0, 0).finite().expect("finite");
                assert!(
                    (r - expected).abs() <= 1e-9 * expected.abs(),
                    "{method:?}: r/δ = {r}, closed form {expected}"
                );
            }
            Err(e) => assert!(matches!(e, NumError::AmbiguousRank(_)), "{method:?}: {e}"),
        }
    }
}
