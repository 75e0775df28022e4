//! Expression pools as values: [`ExprPool`] handles, the current pool of a thread, and
//! expressions that find their own pool.
//!
//! Every [`Expr`] is a node of one pool and carries that pool's serial number. A pool is shared
//! through [`ExprPool`] handles (cheap to clone, `Send + Sync`) and freed when the last handle is
//! dropped: a [`Model`](https://docs.rs/eom-model) holds one, so dropping a model frees its
//! expressions.
//!
//! * **Operations find the pool of their operands.** `a + b`, [`Expr::nominal`],
//!   [`Tape::compile`](crate::Tape::compile), … work on any thread, whatever pool is current.
//!   Operands of two different pools are brought into one: numbers and named constants are
//!   re-interned where they are needed, other expressions are copied (parameters are matched by
//!   their full metadata, else declared anew).
//! * **New leaves go to the current pool.** [`Expr::int`], [`Expr::param`], the parser, … create
//!   nodes in the pool current on this thread: the thread's default pool (alive as long as the
//!   thread), unless a pool was made current with [`ExprPool::enter`] (for the duration of a
//!   closure) or [`ExprPool::make_current`] (until another one is).
//!
//! # Memory
//!
//! A pool keeps every unique node built in it (about 40 bytes per node plus 4 bytes per
//! operand; [`PoolStats::bytes`] reports the total) until it is dropped. It is dropped when the
//! last of its handles goes: the models and symbolic state spaces built in it, the handles a
//! program keeps, and a thread's current-pool slot, which holds the pool most recently made
//! current on that thread. So a program that builds models in a loop holds at most one
//! finished model's pool per thread beyond those it keeps; a thread's default pool lives as long
//! as the thread.
//!
//! An `Expr` does not keep its pool alive: using an expression after every handle of its pool
//! was dropped is a programming error and panics with a message saying so. Keep the model (or
//! an [`ExprPool`] handle) while its expressions are in use.
//!
//! # Concurrency
//!
//! Each operation locks its pool for the duration of one constructor call. Threads that share a
//! pool serialise on it only while they build expressions; evaluation through a compiled
//! [`Tape`](crate::Tape) touches no pool at all.

use crate::ParamInfo;
use crate::expr::Expr;
use crate::pool::{Id, PoolData, PoolStats};
use crate::pool::{MINUS_ONE, ONE, ZERO};
use hashbrown::HashMap;
use std::cell::RefCell;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, Weak};

/// A handle to an expression pool. Clones share the pool; the pool is freed with its last
/// handle.
#[derive(Clone)]
pub struct ExprPool {
    shared: Arc<Shared>,
}

struct Shared {
    serial: u32,
    data: Mutex<PoolData>,
}

impl Drop for Shared {
    fn drop(&mut self) {
        let mut reg = registry();
        // The entry may already point to nothing (a pool being dropped is never found again).
        if reg.get(&self.serial).is_some_and(|w| w.strong_count() == 0) {
            reg.remove(&self.serial);
        }
    }
}

static NEXT_SERIAL: AtomicU32 = AtomicU32::new(1);

/// Every live pool by serial number, for operations on expressions whose pool is not the
/// current one.
fn registry() -> MutexGuard<'static, HashMap<u32, Weak<Shared>>> {
    static REGISTRY: OnceLock<Mutex<HashMap<u32, Weak<Shared>>>> = OnceLock::new();
    lock(REGISTRY.get_or_init(Default::default))
}

/// Locks a mutex; a panic in another thread while it held the lock leaves the data consistent
/// (every constructor either interns a complete node or none), so poisoning is ignored.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

thread_local! {
    /// The pool made current on this thread (`None`: the thread's default pool).
    static CURRENT: RefCell<Option<ExprPool>> = const { RefCell::new(None) };
    /// The thread's default pool, alive as long as the thread.
    static DEFAULT: ExprPool = ExprPool::new();
}

impl Default for ExprPool {
    fn default() -> Self {
        ExprPool::new()
    }
}

impl std::fmt::Debug for ExprPool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ExprPool #{} ({:?})", self.serial(), self.stats())
    }
}

impl PartialEq for ExprPool {
    fn eq(&self, o: &Self) -> bool {
        Arc::ptr_eq(&self.shared, &o.shared)
    }
}

impl ExprPool {
    /// A new, empty pool.
    pub fn new() -> Self {
        let serial = NEXT_SERIAL.fetch_add(1, Ordering::Relaxed);
        let shared = Arc::new(Shared {
            serial,
            data: Mutex::new(PoolData::new(serial)),
        });
        registry().insert(serial, Arc::downgrade(&shared));
        ExprPool { shared }
    }

    /// The pool current on this thread.
    pub fn current() -> Self {
        with_current(|p| p.clone())
    }

    /// The pool with this serial number, if it is still alive.
    pub fn find(serial: u32) -> Option<Self> {
        let shared = registry().get(&serial)?.upgrade()?;
        Some(ExprPool { shared })
    }

    /// The serial number that the pool's expressions carry.
    pub fn serial(&self) -> u32 {
        self.shared.serial
    }

    /// Runs `f` with this pool current on this thread (new leaves such as [`Expr::int`] and
    /// [`Expr::param`] go into it), then restores the previous current pool, also when `f`
    /// panics.
    pub fn enter<R>(&self, f: impl FnOnce() -> R) -> R {
        struct Restore(Option<ExprPool>);
        impl Drop for Restore {
            fn drop(&mut self) {
                let prev = self.0.take();
                CURRENT.with(|c| *c.borrow_mut() = prev);
            }
        }
        let prev = CURRENT.with(|c| c.replace(Some(self.clone())));
        let _restore = Restore(prev);
        f()
    }

    /// Makes this pool current on this thread until another pool is made current or entered
    /// (the thread's slot then keeps it alive, see the [module](self) documentation).
    pub fn make_current(&self) {
        let prev = CURRENT.with(|c| c.replace(Some(self.clone())));
        drop(prev);
    }

    /// Statistics: nodes, operands, parameters, interning calls and memory.
    pub fn stats(&self) -> PoolStats {
        self.with(|p| p.stats())
    }

    /// Metadata of parameter number `index` of this pool.
    pub fn param_info(&self, index: u32) -> Option<ParamInfo> {
        self.with(|p| p.param_info(index))
    }

    /// Parameter number `index` of this pool as an expression.
    pub fn param(&self, index: u32) -> Option<Expr> {
        self.with(|p| (index as usize) < p.params_len()).then(|| {
            let id = self.with(|p| p.param_node(index));
            Expr::new(id, self.serial())
        })
    }

    /// Runs `f` on the pool's data, locked.
    pub(crate) fn with<R>(&self, f: impl FnOnce(&mut PoolData) -> R) -> R {
        f(&mut lock(&self.shared.data))
    }
}

/// Runs `g` with the current pool of this thread.
fn with_current<R>(g: impl FnOnce(&ExprPool) -> R) -> R {
    CURRENT.with(|c| match &*c.borrow() {
        Some(p) => g(p),
        None => DEFAULT.with(g),
    })
}

/// Runs `f` on the data of the current pool (where new leaves go).
pub(crate) fn with_pool<R>(f: impl FnOnce(&mut PoolData) -> R) -> R {
    with_current(|p| p.with(f))
}

/// Runs `f` on the data of the pool with this serial number.
///
/// # Panics
///
/// When the pool was dropped (an expression outlived every handle of its pool).
pub(crate) fn with_serial<R>(serial: u32, f: impl FnOnce(&mut PoolData) -> R) -> R {
    // The common case, the current pool, runs under the thread-local borrow: no handle is
    // cloned (two atomic operations per arithmetic operation saved). `f` works on the pool's
    // data only and never makes another pool current, so the shared borrow is never contended.
    let f = match with_current(move |p| {
        if p.serial() == serial {
            Ok(p.with(f))
        } else {
            Err(f)
        }
    }) {
        Ok(r) => return r,
        Err(f) => f,
    };
    let pool = ExprPool::find(serial).unwrap_or_else(|| {
        panic!(
            "an expression of expression pool #{serial} was used after the pool was dropped: \
             keep the model (or an ExprPool handle) alive while its expressions are in use"
        )
    });
    pool.with(f)
}

/// Is node `id` one of the constants 0, 1, −1, which have the same id in every pool?
fn is_universal(id: Id) -> bool {
    id == ZERO || id == ONE || id == MINUS_ONE
}

/// The pool an operation on `items` works in, and the items' ids there: the pool of the first
/// operand that is not a plain number (or the first operand's), with operands of other pools
/// brought over.
pub(crate) fn unify(items: &[Expr]) -> (u32, Vec<Id>) {
    let Some(first) = items.iter().find(|e| !is_universal(e.id())) else {
        let serial = items
            .first()
            .map_or_else(|| ExprPool::current().serial(), |e| e.pool_serial());
        return (serial, items.iter().map(|e| e.id()).collect());
    };
    let serial = first.pool_serial();
    if items
        .iter()
        .all(|e| e.pool_serial() == serial || is_universal(e.id()))
    {
        return (serial, items.iter().map(|e| e.id()).collect());
    }
    let target = items
        .iter()
        .find(|e| !is_universal(e.id()) && !e.is_number_or_constant())
        .map_or(serial, |e| e.pool_serial());
    let ids = items
        .iter()
        .map(|&e| {
            if e.pool_serial() == target || is_universal(e.id()) {
                e.id()
            } else {
                import(e, target).id()
            }
        })
        .collect();
    (target, ids)
}

/// Two operands in one pool: the fast path of the binary operators.
pub(crate) fn unify2(a: Expr, b: Expr) -> (u32, Id, Id) {
    if a.pool_serial() == b.pool_serial() || is_universal(b.id()) {
        (a.pool_serial(), a.id(), b.id())
    } else if is_universal(a.id()) {
        (b.pool_serial(), a.id(), b.id())
    } else {
        let (s, ids) = unify(&[a, b]);
        (s, ids[0], ids[1])
    }
}

/// A copy of `e` (of another pool) in the pool with serial `target`.
fn import(e: Expr, target: u32) -> Expr {
    let pool = ExprPool::find(target).expect("the target pool is alive (an operand of it exists)");
    let mut memo = HashMap::new();
    pool.enter(|| copy(e, &mut memo))
}

/// Rebuilds `e` with the constructors of the current pool, sharing what was already copied.
fn copy(e: Expr, memo: &mut HashMap<Expr, Expr>) -> Expr {
    if let Some(&c) = memo.get(&e) {
        return c;
    }
    let c = Expr::from_view(e.view().map_children(|x| copy(x, memo)));
    memo.insert(e, c);
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operations_work_in_the_pool_of_their_operands() {
        let pool = ExprPool::new();
        let (m, k) = pool.enter(|| {
            (
                Expr::param("m", 2.0).expect("m"),
                Expr::param("k", 8.0).expect("k"),
            )
        });
        // Built outside the pool's scope: the result is still a node of `pool`.
        let e = k / m + Expr::int(1);
        assert_eq!(e.pool_serial(), pool.serial());
        assert_eq!(e.nominal(), 5.0);
        assert_eq!(pool.enter(|| k / m + Expr::int(1)), e);
        // The constants 0, 1 and −1 are the same in every pool.
        assert_eq!(pool.enter(Expr::zero), Expr::zero());
        assert_eq!(m - m, Expr::zero());
    }

    #[test]
    fn expressions_of_two_pools_meet_in_the_first_that_is_not_a_number() {
        let (a, b) = (ExprPool::new(), ExprPool::new());
        let x = a.enter(|| Expr::param("x", 3.0).expect("x"));
        let y = b.enter(|| Expr::param("y", 4.0).expect("y"));
        let s = x * y;
        assert_eq!(s.pool_serial(), a.serial());
        assert_eq!(s.nominal(), 12.0);
        // `y` was copied into `a` with its metadata; a second copy finds the first.
        let y_in_a = a.enter(|| (x * y).params());
        assert_eq!(y_in_a.len(), 2);
        assert_eq!((x * y + y).nominal(), 16.0);
        assert_eq!(Expr::params_of(&[x * y + y]).len(), 2);
    }

    #[test]
    fn a_pool_is_freed_with_its_last_handle() {
        let pool = ExprPool::new();
        let serial = pool.serial();
        let x = pool.enter(|| Expr::param("x", 1.0).expect("x"));
        assert!(ExprPool::find(serial).is_some());
        drop(pool);
        assert!(ExprPool::find(serial).is_none());
        let dead = std::panic::catch_unwind(|| x.nominal());
        let msg = dead.expect_err("using a dropped pool panics");
        let text = msg.downcast_ref::<String>().cloned().unwrap_or_default();
        assert!(text.contains("after the pool was dropped"), "{text}");
    }

    #[test]
    fn stats_count_the_nodes_and_their_memory() {
        let pool = ExprPool::new();
        let empty = pool.stats();
        pool.enter(|| {
            let x = Expr::param("x", 1.5).expect("x");
            let mut e = x;
            for k in 1..200 {
                e = e * x + Expr::int(k);
            }
            assert!(e.nominal().is_finite());
        });
        let full = pool.stats();
        assert!(full.nodes > empty.nodes + 300, "{full:?}");
        assert!(full.bytes > empty.bytes, "{full:?}");
    }
}
