//! Expression pools as values: a model owns its expressions, frees them when dropped, and can
//! be shared by several threads.
//!
//! Memory is measured exactly with a counting global allocator (this file is its own test
//! binary, so the allocator sees nothing but these tests; they run one at a time through a
//! lock, since the test harness runs tests in parallel).

use eom_model::{Linearizer, Method};
use eom_sym::ExprPool;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::Mutex;
use std::sync::atomic::{AtomicIsize, Ordering};

struct Counting;

static LIVE: AtomicIsize = AtomicIsize::new(0);

// SAFETY: every method forwards to `System` with the caller's arguments unchanged; the
// counter is only bookkeeping.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        LIVE.fetch_add(l.size() as isize, Ordering::Relaxed);
        // SAFETY: forwarded as is.
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size() as isize, Ordering::Relaxed);
        // SAFETY: forwarded as is.
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        LIVE.fetch_add(new as isize - l.size() as isize, Ordering::Relaxed);
        // SAFETY: forwarded as is.
        unsafe { System.realloc(p, l, new) }
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn live() -> isize {
    LIVE.load(Ordering::Relaxed)
}

/// Builds, reduces symbolically and drops a bicycle.
fn build_and_drop() {
    let m = models::build("bicycle", &[]).expect("bicycle");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    assert_eq!(sym.state_space().a.nrows(), 6);
}

#[test]
fn ten_thousand_bicycles_leave_memory_flat() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // Warm-up: the thread's default pool, the registry and the first model's pool (a thread
    // keeps the last pool made current until the next one replaces it).
    for _ in 0..20 {
        build_and_drop();
    }
    let before = live();
    let one_model = {
        let m = models::build("bicycle", &[]).expect("bicycle");
        let sym = Linearizer::new(&m).symbolic().expect("symbolic");
        let held = live() - before;
        drop((sym, m));
        held
    };
    for _ in 0..10_000 {
        build_and_drop();
    }
    let growth = live() - before;
    // Without freeing, 10 000 models would hold 10 000 × `one_model` bytes. Allowed: less than
    // two models' worth (the thread's slot holds the last pool; hash tables keep capacity).
    assert!(
        one_model > 10_000,
        "a bicycle holds {one_model} bytes: the measurement cannot see it"
    );
    assert!(
        growth < 2 * one_model,
        "memory grew by {growth} bytes over 10 000 bicycles ({one_model} bytes each)"
    );
}

#[test]
fn a_dropped_model_frees_its_pool() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let m = models::build("shimmy", &[]).expect("shimmy");
    let serial = m.pool().serial();
    assert!(ExprPool::find(serial).is_some());
    // Another model takes the thread's current-pool slot; then the first has no other owner.
    let other = models::build("smd", &[]).expect("smd");
    drop(m);
    assert!(
        ExprPool::find(serial).is_none(),
        "the pool of a dropped model is freed"
    );
    assert!(ExprPool::find(other.pool().serial()).is_some());
}

#[test]
fn one_model_is_shared_by_several_threads() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let model = models::build("bicycle", &[]).expect("bicycle");
    let speeds = [1.0, 3.0, 5.0, 7.0];
    let here: Vec<_> = speeds
        .iter()
        .map(|&v| {
            Linearizer::new(&model)
                .at(&[("v", v)])
                .method(Method::Numeric)
                .run()
                .expect("numeric")
                .state_space
                .a
        })
        .collect();
    let sym = Linearizer::new(&model).symbolic().expect("symbolic");
    std::thread::scope(|s| {
        let handles: Vec<_> = speeds
            .iter()
            .map(|&v| {
                let (model, sym) = (&model, &sym);
                s.spawn(move || {
                    // Every path, from a thread that did not build the model.
                    let mut out = Vec::new();
                    for method in [Method::Numeric, Method::Robust, Method::Symbolic] {
                        let lin = Linearizer::new(model)
                            .at(&[("v", v)])
                            .method(method)
                            .run()
                            .expect("run");
                        out.push(lin.state_space);
                    }
                    let values = model.scope.values_with(&[("v", v)]).expect("values");
                    out.push(sym.evaluate(&values).expect("evaluate"));
                    // Expressions of the model, used on this thread.
                    let mass = model.scope.get("mB").expect("mB");
                    assert_eq!((mass * 2i64).nominal(), 170.0);
                    // A constant of this thread's pool meets one of the model's.
                    let twice = mass * eom_sym::Expr::int(2);
                    assert_eq!(twice, mass * 2i64);
                    assert_eq!(twice.pool_serial(), model.pool().serial());
                    out
                })
            })
            .collect();
        for (h, want) in handles.into_iter().zip(&here) {
            let got = h.join().expect("thread");
            for ss in &got {
                let eig = |a: &nalgebra::DMatrix<f64>| {
                    let mut e = eom_num::modes::eigenvalues(a).expect("eig");
                    e.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
                    e
                };
                let (a, b) = (eig(want), eig(&ss.a));
                assert_eq!(a.len(), b.len());
                for (x, y) in a.iter().zip(&b) {
                    // The structural zero pair splits by √ε on every path (a separate issue);
                    // compare away from it.
                    if x.norm() > 1e-3 {
                        assert!((x - y).norm() <= 1e-9 * x.norm(), "{x} vs {y}");
                    }
                }
            }
        }
    });
}

#[test]
fn models_and_state_spaces_are_send_and_sync() {
    fn check<T: Send + Sync>() {}
    check::<eom_model::Model>();
    check::<eom_model::SymbolicStateSpace>();
    check::<eom_sym::Expr>();
    check::<ExprPool>();
}
