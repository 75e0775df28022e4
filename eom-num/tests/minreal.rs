//! Minimal realization: constructed systems with known minimal order and known removed modes,
//! transfer-function preservation against an independent evaluation, and cases where
//! the EoM software's absolute-tolerance Mayne elimination (re-implemented below from
//! its specification as a foil) goes wrong.

mod analysis_support;

use analysis_support::{
    eig_nalgebra, mat, points, rand_mat, rand_orth, rng, set_distance, subset_of, tf, tf_parts,
    tf_rel_error,
};
use eom_num::minreal::{
    MinrealOptions, ModeStability, RankStage, RemovedKind, controllability_staircase,
    minimal_realization, observability_staircase,
};
use eom_num::{NumError, SignalNames, StateSpace};
use nalgebra::DMatrix;
use num_complex::Complex64;

fn ss(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>, d: DMatrix<f64>) -> StateSpace<f64> {
    StateSpace::new(a, b, c, d).unwrap()
}

/// Kalman-form system `[co, c-not-o, not-c-o, not-c-not-o]` with the allowed couplings and a
/// block-diagonal choice of eigenvalues, hidden by an orthogonal similarity. Returns the
/// system and the eigenvalues of the four blocks.
fn kalman_system(
    seed: u64,
    sizes: [usize; 4],
    m: usize,
    p: usize,
) -> (StateSpace<f64>, [Vec<Complex64>; 4]) {
    let mut r = rng(seed);
    let n: usize = sizes.iter().sum();
    let off: Vec<usize> = (0..=4).map(|i| sizes[..i].iter().sum()).collect();
    let mut a = DMatrix::zeros(n, n);
    let mut eigs: [Vec<Complex64>; 4] = Default::default();
    for (k, eig) in eigs.iter_mut().enumerate() {
        let blk = rand_mat(&mut r, sizes[k], sizes[k]) * 2.0;
        *eig = eig_nalgebra(&blk);
        a.view_mut((off[k], off[k]), (sizes[k], sizes[k]))
            .copy_from(&blk);
    }
    for (i, j) in [(0, 2), (1, 0), (1, 2), (1, 3), (3, 2)] {
        let blk = rand_mat(&mut r, sizes[i], sizes[j]);
        a.view_mut((off[i], off[j]), (sizes[i], sizes[j]))
            .copy_from(&blk);
    }
    let mut b = DMatrix::zeros(n, m);
    b.rows_mut(off[0], sizes[0] + sizes[1])
        .copy_from(&rand_mat(&mut r, sizes[0] + sizes[1], m));
    let mut c = DMatrix::zeros(p, n);
    c.columns_mut(off[0], sizes[0])
        .copy_from(&rand_mat(&mut r, p, sizes[0]));
    c.columns_mut(off[2], sizes[2])
        .copy_from(&rand_mat(&mut r, p, sizes[2]));
    let d = rand_mat(&mut r, p, m);
    let q = rand_orth(&mut r, n);
    let sys = ss(q.transpose() * a * &q, q.transpose() * b, c * &q, d);
    (sys, eigs)
}

#[test]
fn kalman_systems_reduce_to_the_controllable_observable_block() {
    for (seed, sizes) in [
        (1, [3, 2, 2, 1]),
        (2, [1, 1, 1, 1]),
        (3, [4, 0, 2, 0]),
        (4, [2, 3, 0, 0]),
        (5, [5, 1, 1, 2]),
        (6, [0, 2, 1, 1]),
    ] {
        let (sys, eigs) = kalman_system(seed, sizes, 2, 2);
        let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), sizes[0], "seed {seed}");
        assert_eq!(rep.uncontrollable, sizes[2] + sizes[3], "seed {seed}");
        assert_eq!(rep.unobservable, sizes[1], "seed {seed}");
        // Poles of the minimal system = eigenvalues of the co block (built independently).
        let poles = eig_nalgebra(&min.a);
        let dist = set_distance(&poles, &eigs[0]).unwrap();
        assert!(dist < 1e-12, "seed {seed}: poles off by {dist:e}");
        // Removed modes, marked by kind.
        let unc: Vec<Complex64> = rep
            .removed
            .iter()
            .filter(|r| r.kind == RemovedKind::Uncontrollable)
            .map(|r| r.eigenvalue)
            .collect();
        let uno: Vec<Complex64> = rep
            .removed
            .iter()
            .filter(|r| r.kind == RemovedKind::Unobservable)
            .map(|r| r.eigenvalue)
            .collect();
        let mut want_unc = eigs[2].clone();
        want_unc.extend(eigs[3].iter().copied());
        assert!(
            set_distance(&unc, &want_unc).unwrap() < 1e-12,
            "seed {seed}"
        );
        assert!(set_distance(&uno, &eigs[1]).unwrap() < 1e-12, "seed {seed}");
        // Transfer function kept (rank decisions on exact zeros only).
        let err = tf_rel_error(&min, &sys, &points());
        assert!(err < 1e-12, "seed {seed}: transfer function error {err:e}");
        // Every decision is clear-cut on these systems, and the PBH test confirms each
        // removal.
        assert!(rep.fragile_decisions(1e3).is_empty(), "seed {seed}");
        assert!(
            rep.removed
                .iter()
                .all(|r| r.pbh_residual.is_some_and(|v| v < 1e-14)),
            "{rep:?}"
        );
    }
}

#[test]
fn a_minimal_system_is_returned_unchanged() {
    let mut r = rng(11);
    let sys = ss(
        rand_mat(&mut r, 6, 6),
        rand_mat(&mut r, 6, 2),
        rand_mat(&mut r, 3, 6),
        DMatrix::zeros(3, 2),
    );
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min, sys);
    assert!(rep.removed.is_empty());
    assert_eq!((rep.states_in, rep.states_out), (6, 6));
    assert!(
        rep.decisions
            .iter()
            .any(|d| d.stage == RankStage::Controllability)
    );
    assert!(
        rep.decisions
            .iter()
            .any(|d| d.stage == RankStage::Observability)
    );
}

#[test]
fn an_unstable_mode_the_sensors_cannot_see_is_reported() {
    // Two decoupled oscillators driven by one force; the sensor sees only the first. The
    // second is unstable (negative damping): minreal removes it, the report must say so.
    let a = mat(&[
        &[0.0, 1.0, 0.0, 0.0],
        &[-4.0, -0.4, 0.0, 0.0],
        &[0.0, 0.0, 0.0, 1.0],
        &[0.0, 0.0, -9.0, 0.6],
    ]);
    let b = mat(&[&[0.0], &[1.0], &[0.0], &[1.0]]);
    let c = mat(&[&[1.0, 0.0, 0.0, 0.0]]);
    let q = rand_orth(&mut rng(5), 4);
    let sys = ss(
        q.transpose() * a * &q,
        q.transpose() * b,
        c * &q,
        DMatrix::zeros(1, 1),
    );
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 2);
    assert_eq!(rep.unobservable, 2);
    assert!(rep.removed_unstable());
    let hidden: Vec<_> = rep.removed_not_stable().collect();
    assert_eq!(hidden.len(), 2);
    for h in &hidden {
        assert_eq!(h.kind, RemovedKind::Unobservable);
        assert_eq!(h.stability, ModeStability::Unstable);
        // λ = 0.3 ± i √(9 − 0.09)
        assert!((h.eigenvalue.re - 0.3).abs() < 1e-12);
        assert!((h.eigenvalue.im.abs() - (9.0f64 - 0.09).sqrt()).abs() < 1e-12);
    }
    // The PBH confirmation can be switched off (then it is absent, not a made-up number).
    let quick = MinrealOptions {
        pbh_check: false,
        ..Default::default()
    };
    let (_, rep2) = minimal_realization(&sys, &quick).unwrap();
    assert!(rep2.removed.iter().all(|r| r.pbh_residual.is_none()));
    assert!(rep.removed.iter().all(|r| r.pbh_residual.unwrap() < 1e-14));
    // The JSON form names the kind and the stability.
    let json = serde_json::to_value(&rep).unwrap();
    assert_eq!(json["removed"][0]["kind"], "Unobservable");
    assert_eq!(json["removed"][0]["stability"], "Unstable");
    assert!(json["removed"][0]["eigenvalue"]["re"].is_number());
}

#[test]
fn rigid_body_modes_removed_are_marginal() {
    // A free mass (double integrator) that the input does not push, observed by the sensor,
    // next to a driven damped oscillator.
    let a = mat(&[
        &[0.0, 1.0, 0.0, 0.0],
        &[-4.0, -0.4, 0.0, 0.0],
        &[0.0, 0.0, 0.0, 1.0],
        &[0.0, 0.0, 0.0, 0.0],
    ]);
    let b = mat(&[&[0.0], &[1.0], &[0.0], &[0.0]]);
    let c = mat(&[&[1.0, 0.0, 1.0, 0.0]]);
    let q = rand_orth(&mut rng(8), 4);
    let sys = ss(
        q.transpose() * a * &q,
        q.transpose() * b,
        c * &q,
        DMatrix::zeros(1, 1),
    );
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 2);
    assert_eq!(rep.uncontrollable, 2);
    assert!(!rep.removed_unstable());
    assert_eq!(rep.removed_not_stable().count(), 2);
    assert!(
        rep.removed
            .iter()
            .all(|r| r.stability == ModeStability::Marginal)
    );
}

#[test]
fn phys_and_names_follow_the_reduction() {
    // Only an uncontrollable part is removed: the forced state lies in the kept subspace, so
    // phys (sI − A)⁻¹ B must equal phys_min (sI − A_min)⁻¹ B_min exactly.
    let (sys, _) = kalman_system(21, [3, 0, 2, 1], 2, 2);
    let mut r = rng(22);
    let phys = rand_mat(&mut r, 6, 6);
    let names = SignalNames {
        states: (0..6).map(|i| format!("q{i}")).collect(),
        inputs: vec!["f1".into(), "f2".into()],
        input_units: vec!["N".into(), "N".into()],
        outputs: vec!["y1".into(), "y2".into()],
        output_units: vec!["m".into(), "m".into()],
        bodies: vec!["body".into()],
    };
    let sys = sys
        .with_phys(phys.clone())
        .unwrap()
        .with_names(names)
        .unwrap();
    let (min, _) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 3);
    min.validate().unwrap();
    assert_eq!(min.names.states, vec!["z1", "z2", "z3"]);
    assert_eq!(min.names.inputs, sys.names.inputs);
    assert_eq!(min.names.output_units, sys.names.output_units);
    assert_eq!(min.names.bodies, sys.names.bodies);
    for s in points() {
        let full = tf_parts(&sys.a, &sys.b, &sys.phys, &DMatrix::zeros(6, 2), s);
        let red = tf_parts(&min.a, &min.b, &min.phys, &DMatrix::zeros(6, 2), s);
        let err = (&red - &full).norm() / full.norm();
        assert!(err < 1e-12, "phys response error {err:e}");
    }
}

#[test]
fn decisions_do_not_depend_on_the_units_of_time() {
    // Two oscillators (k 1e3 and 2e3 per unit mass) joined by a weak spring kc = 1e-6; the
    // force acts on the first, the sensor (gain 1e3) reads the second, so the whole transfer
    // function passes through the weak spring. Expressing the same system with time in ms
    // divides A and B by 1000: an absolute tolerance then sees kc/1000 = 1e-9 as zero.
    let osc = |kc: f64| {
        let a = mat(&[
            &[0.0, 1.0, 0.0, 0.0],
            &[-(1e3 + kc), -1.0, kc, 0.0],
            &[0.0, 0.0, 0.0, 1.0],
            &[kc, 0.0, -(2e3 + kc), -2.0],
        ]);
        let b = mat(&[&[0.0], &[1.0], &[0.0], &[0.0]]);
        let c = mat(&[&[0.0, 0.0, 1e3, 0.0]]);
        (a, b, c)
    };
    let (a, b, c) = osc(1e-6);
    let seconds = ss(a.clone(), b.clone(), c.clone(), DMatrix::zeros(1, 1));
    let millis = ss(a / 1e3, b / 1e3, c, DMatrix::zeros(1, 1));
    let pts_s = [Complex64::new(0.5, 31.0), Complex64::new(-2.0, 45.0)];
    let pts_ms: Vec<Complex64> = pts_s.iter().map(|s| s / 1e3).collect();
    for (sys, pts) in [(&seconds, &pts_s[..]), (&millis, &pts_ms[..])] {
        let (min, rep) = minimal_realization(sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), 4, "{rep:?}");
        let err = tf_rel_error(&min, sys, pts);
        assert!(err < 1e-10, "transfer function error {err:e}");
        // The absolute-1e-7 elimination of the reference: fine in seconds, drops the
        // weakly coupled oscillator (100 % transfer-function error) in milliseconds.
        let (am, bm, cm) = mayne_minreal(&sys.a, &sys.b, &sys.c);
        let mayne_err = pts
            .iter()
            .map(|&s| {
                let g = tf(sys, s);
                (tf_parts(&am, &bm, &cm, &sys.d, s) - &g).norm() / g.norm()
            })
            .fold(0.0, f64::max);
        if std::ptr::eq(sys, &seconds) {
            assert!(mayne_err < 1e-6, "{mayne_err:e}");
        } else {
            assert!(mayne_err > 0.5, "{mayne_err:e}");
        }
    }
}

#[test]
fn mixed_scales_where_the_absolute_elimination_invents_an_unstable_pole() {
    // Entries of 1e3 next to an input coupling of 1e-6, and a stable uncontrollable mode
    // −1500. The states are ordered so that the 1e-6 entry is the reference's first pivot
    // (accepted since 1e-6 > 1e-7): its elimination multiplies by 1e9 and the absolute test
    // then removes the wrong states, leaving a pole at ≈ +666.7 that the system does not
    // have.
    let a = mat(&[
        &[-2.0e3, -0.7e3, 0.9e3],
        &[0.0, -1.5e3, 0.0],
        &[0.8e3, 0.5e3, -1.2e3],
    ]);
    let b = mat(&[&[1e3], &[0.0], &[1e-6]]);
    let c = mat(&[&[0.3, 0.6, 1.0]]);
    let sys = ss(a, b, c, DMatrix::zeros(1, 1));
    let eig = eig_nalgebra(&sys.a);
    let pts = [
        Complex64::new(0.0, 300.0),
        Complex64::new(-100.0, 1000.0),
        Complex64::new(50.0, -2000.0),
    ];

    let (am, bm, cm) = mayne_minreal(&sys.a, &sys.b, &sys.c);
    let mayne_poles = eig_nalgebra(&am);
    assert!(
        mayne_poles.iter().any(|p| p.re > 600.0),
        "the foil no longer fails: {mayne_poles:?}"
    );
    assert!(!subset_of(&mayne_poles, &eig, 1e-6));
    let g0 = tf(&sys, pts[0]);
    assert!((tf_parts(&am, &bm, &cm, &sys.d, pts[0]) - &g0).norm() / g0.norm() > 0.5);

    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 2);
    let poles = eig_nalgebra(&min.a);
    assert!(
        subset_of(&poles, &eig, 1e-12),
        "invented poles: {poles:?} vs {eig:?}"
    );
    assert!(poles.iter().all(|p| p.re < 0.0));
    assert_eq!(rep.removed.len(), 1);
    assert!((rep.removed[0].eigenvalue - Complex64::new(-1500.0, 0.0)).norm() < 1e-9);
    assert_eq!(rep.removed[0].kind, RemovedKind::Uncontrollable);
    let err = tf_rel_error(&min, &sys, &pts);
    assert!(err < 1e-10, "transfer function error {err:e}");
}

/// Rotor on a bushing (translation x, y and tilts θx, θy; mass 1300 kg, transverse inertia
/// 500 kg m², polar 1000 kg m², k 1e3 N/m, kθ 1e4 N m/rad, CG 0.75 m above the bushing),
/// spin Ω; force input along x; sensors x and y with gain 1000. At Ω = 0 the y–θx plane is
/// decoupled from the force: 4 uncontrollable states. Any Ω > 0 couples the planes through
/// the gyroscopic term.
fn rotor(omega: f64) -> StateSpace<f64> {
    let (m, it, jp, k, kt, c, ct, h) = (1300.0, 500.0, 1000.0, 1e3, 1e4, 1.0, 10.0, 0.75);
    let mm = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![m, m, it, it]));
    let kk = mat(&[
        &[k, 0.0, 0.0, k * h],
        &[0.0, k, -k * h, 0.0],
        &[0.0, -k * h, kt + k * h * h, 0.0],
        &[k * h, 0.0, 0.0, kt + k * h * h],
    ]);
    let mut dd = mat(&[
        &[c, 0.0, 0.0, c * h],
        &[0.0, c, -c * h, 0.0],
        &[0.0, -c * h, ct + c * h * h, 0.0],
        &[c * h, 0.0, 0.0, ct + c * h * h],
    ]);
    dd[(2, 3)] += omega * jp;
    dd[(3, 2)] -= omega * jp;
    let mi = mm.try_inverse().unwrap();
    let mut a = DMatrix::zeros(8, 8);
    a.view_mut((0, 4), (4, 4)).fill_with_identity();
    a.view_mut((4, 0), (4, 4)).copy_from(&(-&mi * kk));
    a.view_mut((4, 4), (4, 4)).copy_from(&(-&mi * dd));
    let mut b = DMatrix::zeros(8, 1);
    b.view_mut((4, 0), (4, 1))
        .copy_from(&(&mi * mat(&[&[1.0], &[0.0], &[0.0], &[0.0]])));
    let mut cc = DMatrix::zeros(2, 8);
    cc[(0, 0)] = 1000.0;
    cc[(1, 1)] = 1000.0;
    // An arbitrary orthonormal basis, as the descriptor reduction produces.
    let q = rand_orth(&mut rng(77), 8);
    ss(
        q.transpose() * a * &q,
        q.transpose() * b,
        cc * &q,
        DMatrix::zeros(2, 1),
    )
}

#[test]
fn rotor_at_zero_spin_loses_exactly_the_decoupled_plane() {
    let pts = [
        Complex64::new(0.1, 1.0),
        Complex64::new(-0.5, 3.0),
        Complex64::new(0.0, 0.7),
    ];
    let sys = rotor(0.0);
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 4);
    assert_eq!(rep.uncontrollable, 4);
    let eig = eig_nalgebra(&sys.a);
    let poles = eig_nalgebra(&min.a);
    assert!(subset_of(&poles, &eig, 1e-10), "{poles:?} vs {eig:?}");
    let removed: Vec<Complex64> = rep.removed.iter().map(|r| r.eigenvalue).collect();
    let mut all = poles.clone();
    all.extend(removed);
    assert!(set_distance(&all, &eig).unwrap() < 1e-10);
    let err = tf_rel_error(&min, &sys, &pts);
    assert!(err < 1e-10, "transfer function error {err:e}");
    // y (output 2) does not respond to the x force at zero spin.
    for s in pts {
        let g = tf(&min, s);
        assert!(g[(1, 0)].norm() <= 1e-10 * g[(0, 0)].norm());
    }
    for omega in [1e-3, 1.0] {
        let sys = rotor(omega);
        let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), 8, "Ω = {omega}: {rep:?}");
    }
}

#[test]
fn relative_tolerance_makes_decisions_scale_invariant() {
    let (sys, _) = kalman_system(31, [3, 1, 1, 1], 1, 2);
    for scale in [1e-9, 1.0, 1e9] {
        let scaled = ss(&sys.a * scale, &sys.b * scale, sys.c.clone(), sys.d.clone());
        let (min, _) = minimal_realization(&scaled, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), 3, "scale {scale}");
    }
}

#[test]
fn staircases_are_orthogonal_and_structured() {
    let (sys, _) = kalman_system(41, [2, 1, 2, 1], 2, 1);
    let n = sys.states();
    let st = controllability_staircase(&sys.a, &sys.b, &sys.c, 1e-10).unwrap();
    assert_eq!(st.kept, 3);
    assert_eq!(st.blocks.iter().sum::<usize>(), 3);
    let qtq = st.q.transpose() * &st.q;
    assert!((qtq - DMatrix::<f64>::identity(n, n)).norm() < 1e-13);
    assert!((st.q.transpose() * &sys.a * &st.q - &st.a).norm() < 1e-12);
    assert_eq!(st.a.view((3, 0), (3, 3)).norm(), 0.0);
    assert_eq!(st.b.rows(3, 3).norm(), 0.0);
    let so = observability_staircase(&sys.a, &sys.b, &sys.c, 1e-10).unwrap();
    // Observable: the co and the uncontrollable-but-observable blocks.
    assert_eq!(so.kept, 4);
    assert_eq!(so.a.view((0, 4), (4, 2)).norm(), 0.0);
    assert_eq!(so.c.columns(4, 2).norm(), 0.0);
    assert!((so.c.clone() - &sys.c * &so.q).norm() < 1e-12);
}

/// A Kalman-form system whose reachable part is a chain: the input drives the first co
/// state, each reachable state the next (unit links plus a small upper triangle; the co
/// states first, then the controllable-unobservable ones), the output sees the last co state
/// and the observable uncontrollable block. Returns the system and the eigenvalues of the
/// four blocks.
///
/// Why a chain: a single-input staircase is a Krylov process, and perturbations of the order
/// of rounding grow along it by about ‖A‖/h per step (h the staircase block, here the
/// link). On a random dense reachable block of size 25, or a symmetric tridiagonal one of
/// size 34, the blocks that are zero in exact arithmetic already come out near 1e-8 · ‖A‖ by
/// any orthogonal staircase (this one or a step-by-step SVD). The chain's links dominate its
/// norm, which keeps every decision clear-cut for reachable parts of a few dozen states.
/// Hidden by a random orthogonal similarity.
fn chain_kalman_system(
    seed: u64,
    sizes: [usize; 4],
    m: usize,
) -> (StateSpace<f64>, [Vec<Complex64>; 4]) {
    let mut r = rng(seed);
    let n: usize = sizes.iter().sum();
    let off: Vec<usize> = (0..=4).map(|i| sizes[..i].iter().sum()).collect();
    let mut a = DMatrix::zeros(n, n);
    let mut eigs: [Vec<Complex64>; 4] = Default::default();
    for (k, eig) in eigs.iter_mut().enumerate() {
        let sz = sizes[k];
        let rnd = rand_mat(&mut r, sz, sz);
        let blk = if k < 2 {
            DMatrix::from_fn(sz, sz, |i, j| match i {
                _ if i == j + 1 => 1.0,
                _ if i <= j => 0.05 * rnd[(i, j)],
                _ => 0.0,
            })
        } else {
            // Spectral radius about 0.5: perturbations do not outgrow the chain.
            rnd * (0.5 / (sz as f64).sqrt())
        };
        *eig = eig_nalgebra(&blk);
        a.view_mut((off[k], off[k]), (sz, sz)).copy_from(&blk);
    }
    if sizes[0] > 0 && sizes[1] > 0 {
        a[(off[1], off[1] - 1)] = 1.0; // the last co state drives the first cno state
    }
    for (i, j) in [(0, 2), (1, 2), (1, 3), (3, 2)] {
        let blk = rand_mat(&mut r, sizes[i], sizes[j]) * (0.1 / (sizes[j].max(1) as f64).sqrt());
        a.view_mut((off[i], off[j]), (sizes[i], sizes[j]))
            .copy_from(&blk);
    }
    let mut b = DMatrix::zeros(n, m);
    for j in 0..m {
        b[(0, j)] = 1.0 / (j + 1) as f64; // rank one when m > 1
    }
    let mut c = DMatrix::zeros(1, n);
    c[(0, off[1] - 1)] = 1.0;
    c.columns_mut(off[2], sizes[2])
        .copy_from(&rand_mat(&mut r, 1, sizes[2]));
    let q = rand_orth(&mut r, n);
    let d = DMatrix::zeros(1, m);
    let sys = ss(q.transpose() * a * &q, q.transpose() * b, c * &q, d);
    (sys, eigs)
}

/// Systems large enough for the staircase's blocked Hessenberg tail (one-column blocks from
/// some step on, in both staircases): single input, and two inputs through a rank-one B. The
/// minimal order, the removed eigenvalues (blocks built independently) and the transfer
/// function must come out as for the small systems. (The co chain is kept short: the transfer
/// function of a long chain, ~1/sᵏ, cannot be evaluated accurately by any method.)
#[test]
fn large_systems_reduce_through_the_blocked_tail() {
    // The last two are large enough for faer's blocked Hessenberg reduction (≥ 256).
    for (seed, sizes, m) in [
        (61, [8, 12, 9, 3], 1),
        (62, [6, 0, 30, 0], 1),
        (63, [10, 20, 2, 1], 2),
        (64, [10, 20, 200, 40], 1),
        (65, [8, 30, 150, 80], 2),
    ] {
        let (sys, eigs) = chain_kalman_system(seed, sizes, m);
        let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), sizes[0], "seed {seed}");
        assert_eq!(rep.uncontrollable, sizes[2] + sizes[3], "seed {seed}");
        assert_eq!(rep.unobservable, sizes[1], "seed {seed}");
        assert!(rep.fragile_decisions(1e3).is_empty(), "seed {seed}");
        let removed = |kind: RemovedKind| -> Vec<Complex64> {
            (rep.removed.iter())
                .filter(|r| r.kind == kind)
                .map(|r| r.eigenvalue)
                .collect()
        };
        let mut want_unc = eigs[2].clone();
        want_unc.extend(eigs[3].iter().copied());
        for (got, want, what) in [
            (
                removed(RemovedKind::Uncontrollable),
                &want_unc,
                "uncontrollable",
            ),
            (removed(RemovedKind::Unobservable), &eigs[1], "unobservable"),
        ] {
            let dist = set_distance(&got, want).unwrap();
            assert!(dist < 1e-9, "seed {seed}: {what} off by {dist:e}");
        }
        let err = tf_rel_error(&min, &sys, &points());
        assert!(err < 1e-10, "seed {seed}: transfer function error {err:e}");
        assert!(
            rep.removed
                .iter()
                .all(|r| r.pbh_residual.is_some_and(|v| v < 1e-13)),
            "seed {seed}"
        );
    }
}

#[test]
fn large_staircases_are_orthogonal_and_structured() {
    let (sys, _) = chain_kalman_system(71, [30, 4, 6, 2], 1);
    let n = sys.states();
    let st = controllability_staircase(&sys.a, &sys.b, &sys.c, 1e-10).unwrap();
    assert_eq!(st.kept, 34);
    assert_eq!(st.blocks, vec![1; 34]);
    let qtq = st.q.transpose() * &st.q;
    assert!((qtq - DMatrix::<f64>::identity(n, n)).norm() < 1e-13);
    assert!((st.q.transpose() * &sys.a * &st.q - &st.a).norm() < 1e-12 * sys.a.norm());
    assert!((st.q.transpose() * &sys.b - &st.b).norm() < 1e-12 * sys.b.norm());
    assert!((&sys.c * &st.q - &st.c).norm() < 1e-12 * sys.c.norm());
    // Controller Hessenberg form: zero below the subdiagonal, and the uncontrollable block
    // decoupled exactly.
    for j in 0..n {
        for i in j + 2..n {
            assert_eq!(st.a[(i, j)], 0.0, "({i}, {j})");
        }
    }
    assert_eq!(st.a.view((34, 0), (8, 34)).norm(), 0.0);
    assert_eq!(st.b.rows(1, n - 1).norm(), 0.0);
}

#[test]
fn bad_input_gets_typed_errors() {
    let mut sys = ss(
        DMatrix::identity(2, 2),
        DMatrix::zeros(2, 1),
        DMatrix::zeros(1, 2),
        DMatrix::zeros(1, 1),
    );
    let opts = MinrealOptions {
        rtol: Some(-1.0),
        ..Default::default()
    };
    assert!(matches!(
        minimal_realization(&sys, &opts),
        Err(NumError::InvalidOption(_))
    ));
    sys.a[(0, 1)] = f64::NAN;
    assert!(matches!(
        minimal_realization(&sys, &MinrealOptions::default()),
        Err(NumError::NonFinite(_))
    ));
    let a = DMatrix::zeros(2, 3);
    assert!(matches!(
        controllability_staircase(&a, &DMatrix::zeros(2, 1), &DMatrix::zeros(1, 2), 0.0),
        Err(NumError::Dimension(_))
    ));
    assert!(matches!(
        observability_staircase(
            &DMatrix::zeros(2, 2),
            &DMatrix::zeros(2, 1),
            &DMatrix::zeros(1, 2),
            f64::NAN
        ),
        Err(NumError::InvalidOption(_))
    ));
}

#[test]
fn no_inputs_or_no_outputs_leave_nothing() {
    let mut r = rng(3);
    let a = rand_mat(&mut r, 3, 3);
    let sys = ss(
        a.clone(),
        DMatrix::zeros(3, 0),
        rand_mat(&mut r, 1, 3),
        DMatrix::zeros(1, 0),
    );
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 0);
    assert_eq!(rep.uncontrollable, 3);
    let sys = ss(
        a,
        rand_mat(&mut r, 3, 1),
        DMatrix::zeros(0, 3),
        DMatrix::zeros(0, 1),
    );
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 0);
    assert_eq!(rep.unobservable, 3);
    let empty = ss(
        DMatrix::zeros(0, 0),
        DMatrix::zeros(0, 1),
        DMatrix::zeros(1, 0),
        DMatrix::from_element(1, 1, 2.0),
    );
    let (min, _) = minimal_realization(&empty, &MinrealOptions::default()).unwrap();
    assert_eq!(min, empty);
}

// --- The foil: the EoM software's minreal, Mayne (1973), as it works (absolute tolerance 1e-7,
// --- Mayne's elementary similarity eliminations, no scaling).

fn mayne_cont_part(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    const EPS: f64 = 1e-7;
    let (n, m, p) = (a.nrows(), b.ncols(), c.nrows());
    let mut h = DMatrix::zeros(n + p, n + m);
    h.view_mut((0, 0), (n, n)).copy_from(a);
    h.view_mut((0, n), (n, m)).copy_from(b);
    h.view_mut((n, 0), (p, n)).copy_from(c);
    // 1-based i, j as in the specification.
    let (mut i, mut j) = (n, n + m);
    while i != j && i > 1 {
        if (0..i).any(|r| h[(r, j - 1)].abs() > EPS) {
            if h[(i - 1, j - 1)].abs() < EPS {
                let r = (0..i - 1)
                    .max_by(|&x, &y| h[(x, j - 1)].abs().total_cmp(&h[(y, j - 1)].abs()))
                    .unwrap();
                h.swap_rows(i - 1, r);
                h.swap_columns(i - 1, r);
            }
            for r in 0..i - 1 {
                let f = -h[(r, j - 1)] / h[(i - 1, j - 1)];
                for k in 0..n + m {
                    let v = h[(i - 1, k)];
                    h[(r, k)] += f * v;
                }
                for k in 0..n + p {
                    let v = h[(k, r)];
                    h[(k, i - 1)] -= f * v;
                }
            }
            i -= 1;
        }
        j -= 1;
    }
    let mut jj = 0;
    for k in 1..n {
        if h.view((0, k), (k, n + m - k))
            .iter()
            .all(|v| v.abs() <= EPS)
        {
            jj = k;
        }
    }
    if jj == 0 {
        return (a.clone(), b.clone(), c.clone());
    }
    let r = n - jj;
    (
        h.view((jj, jj), (r, r)).clone_owned(),
        h.view((jj, n), (r, m)).clone_owned(),
        h.view((n, jj), (p, r)).clone_owned(),
    )
}

fn mayne_minreal(
    a: &DMatrix<f64>,
    b: &DMatrix<f64>,
    c: &DMatrix<f64>,
) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let (a1, b1, c1) = mayne_cont_part(a, b, c);
    let (a2, b2, c2) = mayne_cont_part(&a1.transpose(), &c1.transpose(), &b1.transpose());
    (a2.transpose(), c2.transpose(), b2.transpose())
}

/// The bicycle's unobservable heading and lateral position, in miniature: two headings whose
/// columns are negatives of each other to 1–3 ulps, a rate, and a position that integrates the
/// first heading with rounding residues of the elimination (9e-16, −7e-15) in its column. The
/// outputs see only the relative heading: minimal order 2 (the relative heading and the
/// rate), the transfer function `y/u = ½ / ((s − 2)(s + 1) + 3/2)` and the physical
/// response (phys = identity) preserved. Balancing the residues up made them couplings and
/// the order 4 (the bicycle's 6 of 6).
#[test]
fn residues_in_a_column_nothing_depends_on_do_not_count_as_couplings() {
    let ulp = |x: f64, k: i64| f64::from_bits((x.to_bits() as i64 + k) as u64);
    let a = mat(&[
        &[0.0, 0.0, 1.0, 0.0],
        &[-2.0, ulp(2.0, 1), 0.5, 9e-16],
        &[-3.0, ulp(3.0, 3), -1.0, -7e-15],
        &[2.0, 0.0, 0.0, 0.0],
    ]);
    let b = mat(&[&[0.0], &[0.0], &[1.0], &[0.0]]);
    let c = mat(&[&[1.0, -1.0, 0.0, 0.0]]);
    let sys = ss(a, b, c, DMatrix::zeros(1, 1))
        .with_phys(DMatrix::identity(4, 4))
        .unwrap();
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!(min.states(), 2, "{rep:?}");
    assert_eq!(rep.unobservable + rep.uncontrollable, 2);
    for s in points() {
        let want = 0.5 / ((s - 2.0) * (s + 1.0) + 1.5);
        let got = tf(&min, s)[(0, 0)];
        assert!(
            (got - want).norm() <= 1e-12 * want.norm(),
            "{got} vs {want}"
        );
        // The relative heading x1 − x2 of the physical response is the output.
        let phys = tf_parts(&min.a, &min.b, &min.phys, &DMatrix::zeros(4, 1), s);
        let rel = phys[(0, 0)] - phys[(1, 0)];
        assert!(
            (rel - want).norm() <= 1e-12 * want.norm(),
            "{rel} vs {want}"
        );
    }
}
