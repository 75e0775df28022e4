//! The strip's aerodynamic transfer functions, plunge → lift, pitch → lift and pitch → moment,
//! taken from the assembled model (added mass, damping and stiffness, and the Jones lag
//! states' equations and force), against Theodorsen's exact frequency response with C(k)
//! from the repository's table (`tests/data/aero/theodorsen_ck.csv`, mpmath Hankel functions;
//! docs/aero-references.md §1): within R. T. Jones' known error |ΔC| ≤ 0.015 at every
//! tabulated reduced frequency, and equal to Jones' C(ik) of the same table to 1e-9.

use eom_model::{Body, Model, RigidPoint, Strip, Unsteady, Wing, assemble, vec3, y_axis, z_axis};
use nalgebra::{Complex, DMatrix, DVector};
use std::f64::consts::PI;

type C64 = Complex<f64>;

/// (k, C(k), C_J(ik)) from the table.
fn table() -> Vec<(f64, C64, C64)> {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data/aero/theodorsen_ck.csv");
    let text = std::fs::read_to_string(p).expect("the table");
    text.lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().expect("a number")).collect();
            (v[0], C64::new(v[1], v[2]), C64::new(v[3], v[4]))
        })
        .collect()
}

const B: f64 = 0.5;
const A: f64 = -0.2;
const U: f64 = 10.0;
const RHO: f64 = 1.225;

/// A free plunging and pitching body at the origin with a strip there.
fn model(unsteady: Unsteady) -> Model<f64> {
    let mut m = Model::<f64>::new("section");
    m.add(Body::new("s").mass(1.0).moments([1.0; 3]));
    m.add(
        RigidPoint::new("in plane")
            .between("s", "ground")
            .forces(2)
            .axis(z_axis()),
    );
    m.add(
        RigidPoint::new("pitch only")
            .between("s", "ground")
            .moments(2)
            .axis(y_axis()),
    );
    m.add(
        Strip::new("airfoil")
            .on("s")
            .at(vec3(0.0, 0.0, 0.0))
            .semichord(B)
            .elastic_axis(A)
            .width(1.0)
            .density(RHO)
            .airspeed(U)
            .unsteady(unsteady),
    );
    m
}

/// The aerodynamic generalized force on the body's six coordinates for the harmonic motion
/// `q e^{iωt}`: `−(−ω² M_item + iω C + K) q + F_a (iω − A_a)⁻¹ (P_a + iω W_a) q`.
fn force(m: &Model<f64>, omega: f64, q: &DVector<C64>) -> DVector<C64> {
    let a = assemble(m).expect("assembled");
    let c = |x: &eom_sym::matrix::SparseMatrix<f64>| x.to_dense().map(|v| C64::new(v, 0.0));
    let iw = C64::new(0.0, omega);
    // The body's own mass is the identity (unit mass and moments at its mass centre).
    let m_item = c(&a.mass) - DMatrix::<C64>::identity(6, 6);
    let direct = m_item * C64::new(-omega * omega, 0.0) + c(&a.damping) * iw + c(&a.stiffness);
    let mut f = -(direct * q);
    let na = a.lags.len();
    if na > 0 {
        let lhs = DMatrix::<C64>::identity(na, na) * iw - c(&a.lags.rate);
        let rhs = (c(&a.lags.position) + c(&a.lags.velocity) * iw) * q;
        let x = lhs.lu().solve(&rhs).expect("regular");
        f += c(&a.lags.force) * x;
    }
    f
}

/// Theodorsen's lift and moment (per unit span) for plunge h and pitch θ at ω with `ck`.
fn theodorsen(h: f64, theta: f64, omega: f64, ck: C64) -> (C64, C64) {
    let iw = C64::new(0.0, omega);
    let (hd, hdd) = (iw * h, iw * iw * h);
    let (td, tdd) = (iw * theta, iw * iw * theta);
    let w = hd + U * theta + B * (0.5 - A) * td;
    let q = PI * RHO * B * B;
    let lift = q * (hdd + U * td - B * A * tdd) + 2.0 * PI * RHO * U * B * ck * w;
    let moment = q * (B * A * hdd - U * B * (0.5 - A) * td - B * B * (0.125 + A * A) * tdd)
        + 2.0 * PI * RHO * U * B * B * (A + 0.5) * ck * w;
    (lift, moment)
}

#[test]
fn jones_states_follow_theodorsen_within_the_known_error() {
    let jones = model(Unsteady::Jones);
    let mut worst = 0.0f64;
    for (k, exact, cj) in table().into_iter().filter(|r| r.0 > 0.0) {
        let omega = k * U / B;
        // Plunge h = 1 (z = −1), then pitch θ = 1 (rotation −1 about y: nose up).
        for (h, theta) in [(1.0, 0.0), (0.0, 1.0)] {
            let mut q = DVector::<C64>::zeros(6);
            q[2] = C64::new(-h, 0.0);
            q[4] = C64::new(-theta, 0.0);
            let f = force(&jones, omega, &q);
            let (lift, moment) = (f[2], -f[4]);
            let iw = C64::new(0.0, omega);
            let w = iw * h + U * theta + B * (0.5 - A) * iw * theta;
            let unit_lift = 2.0 * PI * RHO * U * B * w;
            // The model's C: its lift less the apparent-mass part, per quasi-steady lift.
            let (apparent, _) = theodorsen(h, theta, omega, C64::new(0.0, 0.0));
            let c_model = (lift - apparent) / unit_lift;
            assert!(
                (c_model - cj).norm() < 1e-9,
                "k = {k}: the model's C {c_model} is not Jones' {cj}"
            );
            let dc = (c_model - exact).norm();
            worst = worst.max(dc);
            assert!(dc <= 0.015, "k = {k}: |ΔC| = {dc}");
            let (want_l, want_m) = theodorsen(h, theta, omega, exact);
            let scale = unit_lift.norm();
            assert!((lift - want_l).norm() <= 0.015 * scale, "k = {k}: lift");
            assert!(
                (moment - want_m).norm()
                    <= 0.015 * scale * B * (A + 0.5).abs() + 1e-9 * want_m.norm(),
                "k = {k}: moment {moment} vs {want_m}"
            );
        }
    }
    assert!(
        worst > 0.01,
        "the table reaches Jones' largest error: {worst}"
    );
}

/// Quasi-steady (C = 1): the same transfer functions with C = 1 exactly, off by |1 − C(k)|.
#[test]
fn quasi_steady_strip_is_theodorsen_with_c_one() {
    let qs = model(Unsteady::QuasiSteady);
    for (k, _, _) in table().into_iter().filter(|r| r.0 > 0.0) {
        let omega = k * U / B;
        let mut q = DVector::<C64>::zeros(6);
        q[4] = C64::new(-1.0, 0.0);
        let f = force(&qs, omega, &q);
        let (want_l, want_m) = theodorsen(0.0, 1.0, omega, C64::new(1.0, 0.0));
        assert!((f[2] - want_l).norm() <= 1e-10 * want_l.norm(), "k = {k}");
        assert!(
            (-f[4] - want_m).norm() <= 1e-10 * want_m.norm().max(1.0),
            "k = {k}"
        );
    }
}

/// A plunging and pitching body with a wing of thin-airfoil lift slope (CZw = −2π, chord 2b) in
/// an air stream.
fn wing_model(unsteady: Unsteady) -> Model<f64> {
    let mut m = Model::<f64>::new("wing");
    m.add(Body::new("s").mass(1.0).moments([1.0; 3]));
    m.add(
        RigidPoint::new("in plane")
            .between("s", "ground")
            .forces(2)
            .axis(z_axis()),
    );
    m.add(
        RigidPoint::new("pitch only")
            .between("s", "ground")
            .moments(2)
            .axis(y_axis()),
    );
    m.add(
        Wing::new("w")
            .on("s")
            .area(2.0 * B)
            .chord(2.0 * B)
            .span(1.0)
            .density(RHO)
            .airspeed(U)
            .derivative("CZw", -2.0 * PI)
            .unsteady(unsteady),
    );
    m
}

/// The wing item with Jones' states: its lift per plunge and per pitch, divided by the
/// quasi-steady wing's, is Jones' C(ik) with k = ωc/2V (to 1e-9), within 0.015 of Theodorsen's.
#[test]
fn the_wings_lag_states_follow_theodorsen_within_the_known_error() {
    let (qs, jones) = (
        wing_model(Unsteady::QuasiSteady),
        wing_model(Unsteady::Jones),
    );
    for (k, exact, cj) in table().into_iter().filter(|r| r.0 > 0.0) {
        let omega = k * U / B;
        for dof in [2, 4] {
            let mut q = DVector::<C64>::zeros(6);
            q[dof] = C64::new(1.0, 0.0);
            let (fq, fj) = (force(&qs, omega, &q), force(&jones, omega, &q));
            let c = fj[2] / fq[2];
            assert!(
                (c - cj).norm() < 1e-9,
                "k = {k}, dof {dof}: {c} vs Jones {cj}"
            );
            assert!(
                (c - exact).norm() <= 0.015,
                "k = {k}, dof {dof}: {c} vs {exact}"
            );
        }
    }
}
