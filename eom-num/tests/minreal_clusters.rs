//! Minimal realization of systems whose uncontrollable or unobservable modes share their
//! eigenvalue with a controllable and observable one: the case the Krylov staircase alone
//! cannot decide and the cluster PBH pass does. The correct orders are counted by hand.

mod analysis_support;

use analysis_support::{
    eig_nalgebra, points, rand_orth, rng, set_distance, tf_parts, tf_rel_error,
};
use eom_num::minreal::{MinrealOptions, RankStage, RemovedKind, minimal_realization};
use eom_num::{NumError, OptionError, StateSpace};
use nalgebra::DMatrix;

/// A damped oscillator `ẍ + 2ζω ẋ + ω² x` as a 2 × 2 block (position, velocity).
fn oscillator(w: f64, zeta: f64) -> DMatrix<f64> {
    DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * zeta * w])
}

/// `k` blocks on the diagonal.
fn block_diag(blocks: &[DMatrix<f64>]) -> DMatrix<f64> {
    let n: usize = blocks.iter().map(|b| b.nrows()).sum();
    let mut a = DMatrix::zeros(n, n);
    let mut off = 0;
    for b in blocks {
        a.view_mut((off, off), b.shape()).copy_from(b);
        off += b.nrows();
    }
    a
}

/// `(Qᵀ A Q, Qᵀ B, C Q)` for a random orthogonal `Q`: no structure left to see.
fn hide(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>, seed: u64) -> StateSpace<f64> {
    let q = rand_orth(&mut rng(seed), a.nrows());
    let d = DMatrix::zeros(c.nrows(), b.ncols());
    StateSpace::new(q.transpose() * a * &q, q.transpose() * b, c * &q, d).unwrap()
}

/// Oscillators 1 and 2 are identical; the force drives 1 and the sensor sees 1; a chain of
/// distinct oscillators 3.. is driven through 1 and seen through it. Oscillator 2 is
/// decoupled: the minimal order is the size of everything else.
fn twin_system(extra: usize, seed: u64) -> (StateSpace<f64>, usize) {
    let mut blocks = vec![oscillator(2.0, 0.05), oscillator(2.0, 0.05)];
    for i in 0..extra {
        blocks.push(oscillator(3.0 + 1.7 * i as f64, 0.02));
    }
    let mut a = block_diag(&blocks);
    let n = a.nrows();
    // Oscillators 3.. are driven by the velocity of the one before (1 for 3), one way, so
    // that 1 keeps its eigenvalues, those of 2.
    for i in 0..extra {
        let (from, to) = (if i == 0 { 1 } else { 4 + 2 * (i - 1) + 1 }, 4 + 2 * i + 1);
        let w = 3.0 + 1.7 * i as f64;
        a[(to, from)] = 0.5 * w * w;
    }
    let mut b = DMatrix::zeros(n, 1);
    b[(1, 0)] = 1.0;
    // The sensor sees the last oscillator of the chain (1 when there is none).
    let mut c = DMatrix::zeros(1, n);
    c[(0, if extra == 0 { 0 } else { n - 2 })] = 1.0;
    (hide(a, b, c, seed), n - 2)
}

/// Two identical fixed–free chains of `k` unit masses and unit springs with stiffness-
/// proportional damping, one along y and one along x (4k states). The force and the sensor
/// act on the last mass along y: the y chain (a Jacobi system, every mode of which moves the
/// last mass) is controllable and observable, the x chain is not touched, and its eigenvalues
/// are exactly those of the y chain. Minimal order 2k.
fn two_axis_chain(k: usize, seed: u64) -> StateSpace<f64> {
    let one = two_axis_chain_block(k);
    let a = block_diag(&[one.clone(), one]);
    let mut b = DMatrix::zeros(4 * k, 1);
    b[(2 * k - 1, 0)] = 1.0;
    let mut c = DMatrix::zeros(1, 4 * k);
    c[(0, k - 1)] = 1.0;
    hide(a, b, c, seed)
}

/// The state matrix of one axis of [`two_axis_chain`]. Spring i (from mass i − 1, or the
/// wall, to mass i) is as stiff as the tension in a hanging chain: proportional to the number
/// of masses below it.
fn two_axis_chain_block(k: usize) -> DMatrix<f64> {
    let spring = |i: usize| (k - i) as f64;
    let mut stiff = DMatrix::<f64>::zeros(k, k);
    for i in 0..k {
        stiff[(i, i)] = spring(i) + if i + 1 < k { spring(i + 1) } else { 0.0 };
        if i + 1 < k {
            stiff[(i, i + 1)] = -spring(i + 1);
            stiff[(i + 1, i)] = -spring(i + 1);
        }
    }
    two_axis_chain_block_from(&stiff)
}

/// `[0 I; −K −0.01 K]` for unit masses.
fn two_axis_chain_block_from(stiff: &DMatrix<f64>) -> DMatrix<f64> {
    let k = stiff.nrows();
    let mut one = DMatrix::<f64>::zeros(2 * k, 2 * k);
    one.view_mut((0, k), (k, k)).fill_with_identity();
    one.view_mut((k, 0), (k, k)).copy_from(&(-stiff));
    one.view_mut((k, k), (k, k)).copy_from(&(-0.01 * stiff));
    one
}

fn pbh_directions_removed(rep: &eom_num::minreal::MinrealReport) -> usize {
    rep.decisions
        .iter()
        .filter(|d| {
            matches!(
                d.stage,
                RankStage::ControllabilityPbh | RankStage::ObservabilityPbh
            )
        })
        .map(|d| d.singular_values.len() - d.rank)
        .sum()
}

#[test]
fn twin_oscillators_reduce_to_the_driven_one() {
    for (extra, seed) in [(0, 1), (2, 2), (5, 3)] {
        let (sys, order) = twin_system(extra, seed);
        let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), order, "extra {extra}");
        assert_eq!(rep.uncontrollable, 2, "extra {extra}");
        // The removed pair is oscillator 2's: −ζω ± iω√(1 − ζ²).
        let wd = 2.0 * (1.0f64 - 0.05 * 0.05).sqrt();
        for r in &rep.removed {
            assert_eq!(r.kind, RemovedKind::Uncontrollable);
            assert!(
                (r.eigenvalue.re + 0.1).abs() < 1e-6 && (r.eigenvalue.im.abs() - wd).abs() < 1e-6
            );
        }
        assert!(tf_rel_error(&min, &sys, &points()) < 1e-8, "extra {extra}");
    }
}

#[test]
fn twin_chains_keep_one_chain() {
    // 30 masses per axis: the staircase alone keeps (nearly) every state here, since the
    // rounding of the rotation couples the coincident modes by O(1) in the Krylov sense.
    let k = 30;
    for seed in [1, 2] {
        let mut sys = two_axis_chain(k, seed);
        // Every original state as a "physical coordinate" (4k = 6 · 20 rows).
        sys.phys = DMatrix::identity(4 * k, 4 * k);
        let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), 2 * k, "seed {seed}");
        assert_eq!(rep.uncontrollable, 2 * k, "seed {seed}");
        assert_eq!(rep.unobservable, 0, "seed {seed}");
        // One direction per coincident pair (a complex λ removes it and its conjugate).
        assert_eq!(pbh_directions_removed(&rep), k, "seed {seed}");
        assert!(tf_rel_error(&min, &sys, &points()) < 1e-8, "seed {seed}");
        // The motion of the original states from rest, `phys (sI − A)⁻¹ B`, is the minimal
        // system's through its `phys`: the map includes the PBH pass's rotation.
        for &s in &points() {
            let zero = DMatrix::zeros(sys.phys.nrows(), 1);
            let full = tf_parts(&sys.a, &sys.b, &sys.phys, &zero, s);
            let reduced = tf_parts(&min.a, &min.b, &min.phys, &zero, s);
            let err = (&reduced - &full).norm() / full.norm();
            assert!(
                err < 1e-8,
                "seed {seed}, s = {s}: phys response error {err:.1e}"
            );
        }
        // The removed modes are the x chain's, i.e. those of one chain alone, and every one
        // is confirmed by the PBH test on the full system.
        let one = two_axis_chain_block(k);
        let mut expected = eig_nalgebra(&one);
        expected.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        let got: Vec<_> = rep.removed.iter().map(|r| r.eigenvalue).collect();
        assert!(set_distance(&got, &expected).unwrap() < 1e-8, "seed {seed}");
        for r in &rep.removed {
            assert!(r.pbh_residual.unwrap() <= rep.rtol, "{r:?}");
        }
    }
}

/// A Jordan pair at 0 (heading ψ and lateral position y of a vehicle, `ψ̇ = x`, `ẏ = U ψ`)
/// driven by an oscillator that the force drives and the sensor sees; ψ and y act on
/// nothing else. Unobservable, defective: minimal order 2. The dual has an uncontrollable
/// Jordan pair.
fn jordan_system(seed: u64) -> StateSpace<f64> {
    let mut a = block_diag(&[oscillator(3.0, 0.1), DMatrix::zeros(2, 2)]);
    a[(2, 0)] = 1.0; // ψ̇ = x
    a[(3, 2)] = 30.0; // ẏ = U ψ
    let b = DMatrix::from_column_slice(4, 1, &[0.0, 1.0, 0.0, 0.0]);
    let c = DMatrix::from_row_slice(1, 4, &[1.0, 0.0, 0.0, 0.0]);
    hide(a, b, c, seed)
}

#[test]
fn defective_unobservable_and_uncontrollable_pairs_are_removed() {
    for seed in [1, 2, 3] {
        let sys = jordan_system(seed);
        let dual = StateSpace::new(
            sys.a.transpose(),
            sys.c.transpose(),
            sys.b.transpose(),
            sys.d.transpose(),
        )
        .unwrap();
        for (which, s, kind) in [
            ("primal", &sys, RemovedKind::Unobservable),
            ("dual", &dual, RemovedKind::Uncontrollable),
        ] {
            let (min, rep) = minimal_realization(s, &MinrealOptions::default()).unwrap();
            assert_eq!(min.states(), 2, "{which} seed {seed}");
            assert_eq!(rep.removed.len(), 2, "{which} seed {seed}");
            for r in &rep.removed {
                assert_eq!(r.kind, kind, "{which} seed {seed}");
                // A computed defective double zero splits by about √(ε ‖A‖ U): near 0, not 0.
                assert!(r.eigenvalue.norm() < 1e-5, "{which} seed {seed}: {r:?}");
            }
            assert!(
                tf_rel_error(&min, s, &points()) < 1e-8,
                "{which} seed {seed}"
            );
        }
    }
}

#[test]
fn invalid_cluster_rtol_is_named() {
    let (sys, _) = twin_system(0, 1);
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        let opts = MinrealOptions {
            cluster_rtol: bad,
            ..MinrealOptions::default()
        };
        match minimal_realization(&sys, &opts) {
            Err(NumError::InvalidOption(OptionError::Tolerance {
                option: "MinrealOptions.cluster_rtol",
                ..
            })) => {}
            other => panic!("cluster_rtol = {bad}: {other:?}"),
        }
    }
}

/// `N` identical decoupled damped oscillators `A = I_N ⊗ A₀` driven through `B = B_N ⊗ b₀`
/// (force per unit of each input on each oscillator) and seen through `C = C_N ⊗ c₀`
/// (position). The Markov parameters are `C Aʲ B = (C_N B_N) ⊗ (c₀ A₀ʲ b₀)`, and the
/// scalar oscillator is minimal (order 2), so the Hankel rank, the minimal order, is
/// `2 · rank(C_N B_N)` (issue 27, item 7).
fn identical_oscillators(bn: &DMatrix<f64>, cn: &DMatrix<f64>) -> StateSpace<f64> {
    let n = bn.nrows();
    let a0 = oscillator(2.0, 0.05);
    let a = block_diag(&vec![a0; n]);
    let b = DMatrix::from_fn(2 * n, bn.ncols(), |i, j| {
        if i % 2 == 1 { bn[(i / 2, j)] } else { 0.0 }
    });
    let c = DMatrix::from_fn(cn.nrows(), 2 * n, |i, j| {
        if j % 2 == 0 { cn[(i, j / 2)] } else { 0.0 }
    });
    let d = DMatrix::zeros(cn.nrows(), bn.ncols());
    StateSpace::new(a, b, c, d).unwrap()
}

/// Every removed mode of `rep` is the oscillator's `−ζω ± iω√(1 − ζ²)`, confirmed by PBH.
fn removed_are_the_oscillator(rep: &eom_num::minreal::MinrealReport) {
    let wd = 2.0 * (1.0f64 - 0.05 * 0.05).sqrt();
    for r in &rep.removed {
        assert!(
            (r.eigenvalue.re + 0.1).abs() < 1e-12 && (r.eigenvalue.im.abs() - wd).abs() < 1e-12,
            "{r:?}"
        );
        assert!(r.pbh_residual.unwrap() <= rep.rtol, "{r:?}");
    }
}

#[test]
fn identical_oscillators_keep_two_states_per_independent_input_output_pair() {
    let n = 200;
    let unit = |rows: usize, cols: usize, ones: &[(usize, usize)]| {
        let mut m = DMatrix::zeros(rows, cols);
        for &(i, j) in ones {
            m[(i, j)] = 1.0;
        }
        m
    };
    // (B_N, C_N, rank(C_N B_N), what)
    let cases = [
        (
            unit(n, 1, &[(0, 0)]),
            unit(1, n, &[(0, 0)]),
            1,
            "one input, one sensor, one body",
        ),
        (
            unit(n, 5, &[(0, 0), (1, 1), (2, 2), (3, 3), (4, 4)]),
            unit(5, n, &[(0, 0), (1, 1), (2, 2), (3, 3), (4, 4)]),
            5,
            "five inputs and sensors on five bodies",
        ),
        (
            unit(n, 1, &[(0, 0), (1, 0), (2, 0), (3, 0), (4, 0), (5, 0)]),
            unit(1, n, &[(0, 0)]),
            1,
            "one input shared by six bodies",
        ),
        (
            unit(n, 2, &[(0, 0), (1, 1)]),
            unit(1, n, &[(0, 0), (0, 1)]),
            1,
            "two inputs, one sensor of their sum",
        ),
    ];
    for (bn, cn, rank, what) in cases {
        let sys = identical_oscillators(&bn, &cn);
        let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), 2 * rank, "{what}");
        assert_eq!(rep.removed.len(), 2 * n - 2 * rank, "{what}");
        removed_are_the_oscillator(&rep);
        assert!(tf_rel_error(&min, &sys, &points()) < 1e-12, "{what}");
    }
    // Without inputs every state is removed by the structure alone.
    let sys = identical_oscillators(&DMatrix::zeros(n, 0), &DMatrix::zeros(0, n));
    let (min, rep) = minimal_realization(&sys, &MinrealOptions::default()).unwrap();
    assert_eq!((min.states(), rep.structurally_uncontrollable), (0, 2 * n));
    removed_are_the_oscillator(&rep);
}

/// The same oscillators in coordinates that hide the structure (a random orthogonal
/// change): no exact zero is left, and the cluster of identical eigenvalues is decided by
/// the staircase and the PBH pass, with the same orders.
#[test]
fn hidden_identical_oscillators_keep_two_states_per_input() {
    let n = 20;
    for (inputs, seed) in [(1, 1), (3, 2)] {
        let bn = DMatrix::from_fn(n, inputs, |i, j| if i == j { 1.0 } else { 0.0 });
        let cn = bn.transpose();
        let sys = identical_oscillators(&bn, &cn);
        let hidden = hide(sys.a.clone(), sys.b.clone(), sys.c.clone(), seed);
        let (min, rep) = minimal_realization(&hidden, &MinrealOptions::default()).unwrap();
        assert_eq!(min.states(), 2 * inputs, "{inputs} inputs");
        assert_eq!(rep.structurally_uncontrollable, 0);
        for r in &rep.removed {
            assert!(r.pbh_residual.unwrap() <= rep.rtol, "{r:?}");
        }
        assert!(
            tf_rel_error(&min, &hidden, &points()) < 1e-8,
            "{inputs} inputs"
        );
    }
}

/// [`twin_chains_keep_one_chain`] at 50 masses per axis (200 states, from which the PBH
/// tests of the clusters run on the pool's threads, and the dense steps use faer's parallel
/// kernels), on pools of one and of three threads: the same order and the same removed
/// modes, those of one chain.
#[test]
fn twin_chains_keep_one_chain_on_any_number_of_threads() {
    let k = 50;
    let sys = two_axis_chain(k, 3);
    let mut expected = eig_nalgebra(&two_axis_chain_block(k));
    expected.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (min, rep) = pool
            .install(|| minimal_realization(&sys, &MinrealOptions::default()))
            .unwrap();
        assert_eq!(min.states(), 2 * k, "{threads} thread(s)");
        assert_eq!(pbh_directions_removed(&rep), k, "{threads} thread(s)");
        let got: Vec<_> = rep.removed.iter().map(|r| r.eigenvalue).collect();
        let dist = set_distance(&got, &expected).unwrap();
        assert!(dist < 1e-8, "{threads} thread(s): {dist:e}");
        assert!(
            tf_rel_error(&min, &sys, &points()) < 1e-8,
            "{threads} thread(s)"
        );
    }
}
