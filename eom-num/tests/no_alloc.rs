//! The no-allocation kernels really do not allocate: a counting global allocator (per
//! thread) observes `eigenvalues_in`, `HessenbergForm::evaluate_in`, and the time-stepping
//! loops (whose allocation count must not grow with the number of steps).

mod closed_forms;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use closed_forms::{random_matrix, rng};
use eom_num::StateSpace;
use eom_num::freq::{
    FreqOptions, FreqRange, FreqUnit, FrequencyResponse, HessenbergForm, LANES, SolveStatus,
};
use eom_num::modes::{EigenvaluesWorkspace, eigenvalues_in};
use eom_num::time::{Horizon, TimeOptions, impulse, simulate, step};
use nalgebra::DMatrix;
use num_complex::Complex64;

struct Counting;

thread_local! {
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        COUNT.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        COUNT.with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations<R>(f: impl FnOnce() -> R) -> (usize, R) {
    let before = COUNT.with(|c| c.get());
    let r = f();
    (COUNT.with(|c| c.get()) - before, r)
}

#[test]
fn kernels_do_not_allocate() {
    // The counter works (so a zero below means something).
    assert_eq!(allocations(|| Vec::<u8>::with_capacity(8)).0, 1);
    let mut r = rng(21);
    for n in [1, 6, 30] {
        let a = random_matrix(&mut r, n, n);
        let mut ws = EigenvaluesWorkspace::new(n);
        let mut out = vec![Complex64::new(0.0, 0.0); n];
        eigenvalues_in(&a, &mut ws, &mut out).unwrap(); // warm-up (lazy statics, if any)
        let (count, res) = allocations(|| eigenvalues_in(&a, &mut ws, &mut out));
        res.unwrap();
        assert_eq!(
            count, 0,
            "eigenvalues_in allocated {count} times at n = {n}"
        );

        let ss = StateSpace::new(
            a.clone(),
            random_matrix(&mut r, n, 2),
            random_matrix(&mut r, 3, n),
            random_matrix(&mut r, 3, 2),
        )
        .unwrap();
        let form = HessenbergForm::new(&ss).unwrap();
        let mut fws = form.workspace();
        let mut g = vec![Complex64::new(0.0, 0.0); 6];
        let (count, res) = allocations(|| {
            for k in 0..100 {
                form.evaluate_in(Complex64::new(0.0, 0.1 * k as f64 + 0.05), &mut fws, &mut g)?;
            }
            Ok::<_, eom_num::NumError>(())
        });
        res.unwrap();
        assert_eq!(count, 0, "evaluate_in allocated {count} times at n = {n}");
        let mut bws = form.batch_workspace();
        let mut bout = vec![Complex64::new(0.0, 0.0); 6 * LANES];
        let mut st = [SolveStatus::Regular; LANES];
        let pts = [Complex64::new(0.0, 0.3); LANES];
        let (count, res) =
            allocations(|| form.evaluate_batch_in(&pts, &mut bws, &mut bout, &mut st));
        res.unwrap();
        assert_eq!(
            count, 0,
            "evaluate_batch_in allocated {count} times at n = {n}"
        );
    }
}

#[test]
fn loops_allocate_independently_of_their_length() {
    let ss = closed_forms::smd(1.0, 0.5, 30.0);
    let count_for = |t_end: f64| {
        let opts = TimeOptions {
            horizon: Horizon::Given { t_end, dt: 0.01 },
            ..Default::default()
        };
        let (a, r1) = allocations(|| step(&ss, &opts).unwrap());
        let (b, r2) = allocations(|| impulse(&ss, &opts).unwrap());
        let u = DMatrix::from_element(1, (t_end / 0.01) as usize, 1.0);
        let (c, r3) = allocations(|| simulate(&ss, &u, 0.01, None, &opts).unwrap());
        assert!(r1.len() > 10 && r2.len() > 10 && r3.len() > 10);
        (a, b, c)
    };
    assert_eq!(count_for(1.0), count_for(100.0));
    let freq_count = |ppd: usize| {
        let opts = FreqOptions {
            range: FreqRange::Range {
                low: 0.1,
                high: 10.0,
                unit: FreqUnit::Hz,
            },
            points_per_decade: ppd,
        };
        allocations(|| FrequencyResponse::compute(&ss, &opts).unwrap()).0
    };
    assert_eq!(freq_count(10), freq_count(1000));
}
