//! Recognising expressions that are identically zero although not structurally zero.
//!
//! The smart constructors never expand, so a cancellation such as
//! `k·l·(1 − x) + k·l·x − k·l` stays a sum even though it is zero for every parameter value.
//! Left in a matrix, such an entry is evaluated as a rounding residue (1e-16 instead of 0): it
//! costs operations, hides structure (a zero column of A becomes a column of noise), and can
//! spoil eigenvalue accuracy (a Jordan block at zero perturbed by ε splits by √ε).
//!
//! [`is_identically_zero`] decides it by randomized identity testing: a sum whose nominal value
//! is tiny compared with its terms is evaluated in double-double at two random parameter
//! points; if it vanishes at both, relative to the size of its terms, to within 1e-24, it is
//! zero. A nonzero analytic function vanishes on a set of measure zero, so an accidental
//! agreement at two independent random points to 24 digits does not happen in practice
//! (the Schwartz–Zippel argument for rational functions). The double-double values of every
//! node are memoised in its pool, so testing many entries of one DAG costs one evaluation of
//! the DAG per probe point.

use crate::dd::Dd;
use crate::expr::Expr;
use crate::pool::{PoolData, Shape};
use hashbrown::HashMap;

const PROBES: usize = 2;

/// Prefilter: a sum is a candidate when `|value| ≤ CANDIDATE · Σ|terms|` at the nominal point.
const CANDIDATE: f64 = 1e-9;
/// Decision: zero when `|value| ≤ DECIDE · Σ|terms|` at every probe point (double-double).
const DECIDE: f64 = 1e-24;

/// The memo of the probe evaluations of one pool.
pub(crate) struct Probe {
    /// Random relative perturbation per parameter index and probe.
    factors: HashMap<u32, [f64; PROBES]>,
    /// (value, Σ|terms| for sums) per node and probe.
    values: HashMap<u32, [(Dd, f64); PROBES]>,
    state: u64,
}

impl Default for Probe {
    fn default() -> Self {
        Probe {
            factors: HashMap::new(),
            values: HashMap::new(),
            state: 0x5eed_1234_abcd_9876,
        }
    }
}

impl Probe {
    fn rand(&mut self) -> f64 {
        self.state = self.state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn param_value(&mut self, index: u32, nominal: f64, positive: bool, k: usize) -> Dd {
        if !self.factors.contains_key(&index) {
            let f = [0.5 + self.rand(), 0.5 + self.rand()];
            self.factors.insert(index, f);
        }
        let f = self.factors[&index][k];
        // Multiplicative perturbation keeps the sign (positivity assumptions hold); a zero
        // nominal value gets an additive one.
        if nominal != 0.0 {
            Dd::from_f64(nominal) * Dd::from_f64(f)
        } else if positive {
            Dd::from_f64(f)
        } else {
            Dd::from_f64(f - 1.0)
        }
    }
}

/// Evaluate node `id` at probe `k` in double-double (memoised), returning (value, Σ|terms|).
fn value(pool: &PoolData, p: &mut Probe, id: u32, k: usize) -> (Dd, f64) {
    if let Some(v) = p.values.get(&id)
        && !v[k].0.hi.is_nan()
    {
        return v[k];
    }
    // Iterative post-order over the children (deep DAGs must not overflow the stack).
    let mut stack = vec![(id, false)];
    while let Some((n, ready)) = stack.pop() {
        if p.values.get(&n).is_some_and(|v| !v[k].0.hi.is_nan()) {
            continue;
        }
        let shape = pool.shape(n);
        if !ready {
            stack.push((n, true));
            for &c in shape.children() {
                if p.values.get(&c).is_none_or(|v| v[k].0.hi.is_nan()) {
                    stack.push((c, false));
                }
            }
            continue;
        }
        let get = |c: u32| p.values[&c][k].0;
        let res: (Dd, f64) = match shape {
            Shape::Param(i) => {
                let info = pool.param(i);
                let positive = matches!(info.assume, crate::pool::Assumption::Positive);
                let v = p.param_value(i, info.nominal, positive, k);
                (v, v.abs().to_f64())
            }
            Shape::Invalid(_) => (Dd::from_f64(f64::NAN), f64::NAN),
            _ => {
                let v = shape
                    .eval(get, |e| pool.exponent(e))
                    .expect("a node with a value");
                // A sum's magnitude: the sum of its terms' (the scale of its rounding).
                let mag = match shape {
                    Shape::Add(a) => a[1..]
                        .chunks_exact(2)
                        .fold(get(a[0]).abs().to_f64(), |m, t| {
                            m + (get(t[1]) * get(t[0])).abs().to_f64()
                        }),
                    _ => v.abs().to_f64(),
                };
                (v, mag)
            }
        };
        let entry = p
            .values
            .entry(n)
            .or_insert([(Dd::from_f64(f64::NAN), f64::NAN); PROBES]);
        entry[k] = res;
    }
    p.values[&id][k]
}

/// Is `e` identically zero (see the module docs)? Only sums can hide a cancellation; anything
/// else is zero only when it is the constant 0.
pub fn is_identically_zero(e: Expr) -> bool {
    if e.is_zero() {
        return true;
    }
    let id = e.id();
    e.with_pool(|pool| {
        let Some((c0, pairs)) = pool.add_parts(id) else {
            return false;
        };
        let v = pool.nominal(id);
        let mag = pool.nominal(c0).abs()
            + pairs
                .chunks_exact(2)
                .map(|t| (pool.nominal(t[0]) * pool.nominal(t[1])).abs())
                .sum::<f64>();
        if !(v.is_finite() && mag.is_finite() && v.abs() <= CANDIDATE * mag) {
            return false;
        }
        let mut probe = pool.take_probe();
        let zero = (0..PROBES).all(|k| {
            let (v, mag) = value(pool, &mut probe, id, k);
            v.is_finite() && mag.is_finite() && v.abs().to_f64() <= DECIDE * mag
        });
        pool.put_probe(probe);
        zero
    })
}

/// `e`, or the constant 0 when `e` is identically zero.
pub fn zero_if_identically_zero(e: Expr) -> Expr {
    if is_identically_zero(e) {
        Expr::zero()
    } else {
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hidden_cancellations_are_found_and_real_values_kept() {
        let k = Expr::param("k", 1.5).unwrap();
        let l = Expr::param("l", 1.0).unwrap();
        let x = Expr::param("x", 0.5).unwrap();
        let hidden = k * l * (Expr::one() - x) + k * l * x - k * l;
        assert!(!hidden.is_zero(), "not structurally zero");
        assert!(is_identically_zero(hidden));
        // Nominally zero but not identically zero: x − 1/2 at x = 1/2.
        let nominal_zero = x - Expr::rational(1, 2).unwrap();
        assert_eq!(nominal_zero.nominal(), 0.0);
        assert!(!is_identically_zero(nominal_zero));
        // Trigonometric identity hidden in a sum.
        let t = (Expr::int(2) * x).sin() - Expr::int(2) * x.sin() * x.cos();
        assert!(is_identically_zero(t));
        assert!(!is_identically_zero(x.sin() - x));
    }
}
