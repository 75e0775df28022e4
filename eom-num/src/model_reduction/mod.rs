//! Model reduction with error bounds: a small model of the dynamics that matter, for a
//! controller or a fast simulation, and how far it is from the full one.
//!
//! [`Reducer`] keeps the modes a reduction must not touch whole — structural zeros (a
//! vehicle's position and heading), other rigid-body and integrator modes, undamped and
//! unstable modes, as [`crate::modes::Modes`] classes them — and reduces the stable rest
//! (`G = G_kept + G_stable`, split by an ordered real Schur form and a Sylvester equation):
//!
//! * [`ReductionMethod::Balanced`]: square-root balanced truncation. The Hankel singular values
//!   σᵢ of the stable part come from Cholesky factors of its Gramians computed directly
//!   (Hammarling's method on the Schur form), and the error of the reduced model is bounded by
//!   `‖G − G_r‖_∞ ≤ 2 Σ_{i>r} σᵢ` (Glover 1984; Enns 1984).
//! * [`ReductionMethod::MatchDc`]: the singular perturbation approximation of the balanced
//!   realization — the same bound, and the steady-state gain kept exactly.
//! * [`ReductionMethod::Modal`]: the modes in a frequency band (or the slowest ones) kept with
//!   their eigenvalues unchanged; no a-priori bound.
//!
//! Every result carries the error measured on a frequency grid ([`MeasuredError`]): the
//! largest singular value of `G(jω) − G_r(jω)` and its value at ω = 0.
//!
//! ```
//! use eom_num::StateSpace;
//! use eom_num::model_reduction::{Reducer, ReductionMethod};
//! use nalgebra::DMatrix;
//!
//! // Four masses in a chain (force on the last, its position measured).
//! let n = 4;
//! let k = DMatrix::from_fn(n, n, |i, j| match (i as i64 - j as i64).abs() {
//!     0 => if i + 1 == n { 1.0 } else { 2.0 },
//!     1 => -1.0,
//!     _ => 0.0,
//! });
//! let mut a = DMatrix::zeros(2 * n, 2 * n);
//! a.view_mut((0, n), (n, n)).fill_with_identity();
//! a.view_mut((n, 0), (n, n)).copy_from(&(-&k));
//! a.view_mut((n, n), (n, n)).copy_from(&(-0.1 * &k));
//! let mut b = DMatrix::zeros(2 * n, 1);
//! b[(2 * n - 1, 0)] = 1.0;
//! let mut c = DMatrix::zeros(1, 2 * n);
//! c[(0, n - 1)] = 1.0;
//! let ss = StateSpace::new(a, b, c, DMatrix::zeros(1, 1)).unwrap();
//!
//! let r = Reducer::new(&ss).method(ReductionMethod::Balanced).order(4).run().unwrap();
//! assert_eq!(r.state_space.states(), 4);
//! let bound = r.bound.unwrap();
//! assert!(r.error.hinf <= bound);
//! assert!((bound - 2.0 * r.hankel[4..].iter().sum::<f64>()).abs() < 1e-15 * bound.max(1.0));
//! ```

mod balanced;
mod lyapunov;
mod measure;
mod modal;
mod schur;
mod small;
mod split;
mod sylvester;

pub use measure::MeasuredError;

use nalgebra::DMatrix;
use num_complex::Complex64;
use serde::Serialize;

use crate::statespace::{SignalNames, StateSpace};
use crate::{NumError, NumWarning, OptionError};

/// The reduction of the stable part.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ReductionMethod {
    /// Square-root balanced truncation (error bound `2 Σ σ` beyond the order).
    Balanced,
    /// Singular perturbation approximation of the balanced realization: the same bound, the
    /// steady-state gain matched exactly.
    MatchDc,
    /// Modal truncation: the chosen modes kept with their eigenvalues (no a-priori bound).
    Modal,
}

impl ReductionMethod {
    /// The name on the command line (`balanced`, `matchdc`, `modal`).
    pub fn name(self) -> &'static str {
        match self {
            ReductionMethod::Balanced => "balanced",
            ReductionMethod::MatchDc => "matchdc",
            ReductionMethod::Modal => "modal",
        }
    }
}

/// How the order is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OrderChoice {
    /// The smallest order whose bound is at most [`DEFAULT_RELATIVE_TOLERANCE`] times σ₁
    /// (balanced and matchdc); modal truncation needs an order or a band.
    Default,
    /// This many states in all (the kept ones included).
    States(usize),
    /// The smallest order whose bound `2 Σ σ` is at most this (in the units of G; balanced
    /// and matchdc only).
    Tolerance(f64),
}

/// The default order keeps the bound below this fraction of the largest Hankel singular value.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-3;

/// A reduction to run: `Reducer::new(&ss).method(…).order(r).run()`.
#[derive(Clone, Debug)]
pub struct Reducer<'a> {
    ss: &'a StateSpace<f64>,
    method: ReductionMethod,
    order: OrderChoice,
    band_hz: Option<(f64, f64)>,
}

/// A reduced model and how good it is.
#[derive(Clone, Debug)]
pub struct ReducedModel {
    /// The reduced model: the kept states first (structural zeros, then the other kept
    /// modes), then the reduced stable part; `phys` is the full model's times [`Self::v`].
    pub state_space: StateSpace<f64>,
    /// How the stable part was reduced.
    pub method: ReductionMethod,
    /// States of the full model.
    pub full_states: usize,
    /// States kept whole (zero, marginal and unstable modes).
    pub kept: usize,
    /// Of those, the structural zeros (exactly zero eigenvalues in the reduced model too).
    pub structural_zeros: usize,
    /// The Hankel singular values of the stable part, non-increasing.
    pub hankel: Vec<f64>,
    /// Stable states whose Hankel singular value is above rounding (`n·ε·σ₁`); the others
    /// are uncontrollable or unobservable to working precision and never kept by the
    /// balanced methods.
    pub numerical_order: usize,
    /// The a-priori bound `2 Σ_{i>r} σᵢ` on `‖G − G_r‖_∞` (balanced and matchdc).
    pub bound: Option<f64>,
    /// The error measured on a frequency grid.
    pub error: MeasuredError,
    /// `x ≈ V z` (n × r): the full state from the reduced one (for matchdc, the balanced
    /// truncation's basis, which leaves out the residualised states' static part).
    pub v: DMatrix<f64>,
    /// `z = Wᵀ x` (n × r), `WᵀV = I`: the reduced state of a full one. For balanced and modal
    /// truncation the reduced model is the Petrov–Galerkin projection `(WᵀAV, WᵀB, CV, D)`.
    pub w: DMatrix<f64>,
    /// ‖X‖_F of the Sylvester equation that splits the kept part off (large: a stable mode
    /// nearly touches a kept one).
    pub coupling: f64,
    /// Numerical concerns, in words.
    pub warnings: Vec<NumWarning>,
}

impl ReducedModel {
    /// The number of states of the reduced model.
    pub fn order(&self) -> usize {
        self.state_space.states()
    }

    /// The bound `2 Σ σ` for every order the balanced methods can reach: `(states in all,
    /// bound)` from the kept part alone up to the numerical order.
    pub fn bounds(&self) -> Vec<(usize, f64)> {
        (0..=self.numerical_order)
            .map(|r| (self.kept + r, balanced::bound(&self.hankel, r)))
            .collect()
    }
}

fn invalid(problem: OptionError) -> NumError {
    NumError::InvalidOption(problem)
}

impl<'a> Reducer<'a> {
    /// A balanced truncation of `ss` to the default order.
    pub fn new(ss: &'a StateSpace<f64>) -> Self {
        Reducer {
            ss,
            method: ReductionMethod::Balanced,
            order: OrderChoice::Default,
            band_hz: None,
        }
    }

    /// The method for the stable part.
    pub fn method(mut self, method: ReductionMethod) -> Self {
        self.method = method;
        self
    }

    /// Reduce to `r` states in all (the kept ones included).
    pub fn order(mut self, r: usize) -> Self {
        self.order = OrderChoice::States(r);
        self
    }

    /// Reduce to the smallest order whose bound is at most `tol` (balanced, matchdc).
    pub fn tolerance(mut self, tol: f64) -> Self {
        self.order = OrderChoice::Tolerance(tol);
        self
    }

    /// Modal truncation: keep the stable modes whose natural frequency `|λ|/2π` lies in
    /// `[low, high]` Hz.
    pub fn band_hz(mut self, low: f64, high: f64) -> Self {
        self.band_hz = Some((low, high));
        self
    }

    /// Runs the reduction.
    ///
    /// Errors: those of [`StateSpace::validate`]; [`NumError::InvalidOption`] for an order
    /// below the kept states or above what the method can reach, a bad tolerance or band, a
    /// band without modal truncation, an order that would split a complex pair (modal);
    /// [`NumError::NoConvergence`] from the Schur form or its reordering.
    pub fn run(&self) -> Result<ReducedModel, NumError> {
        let ss = self.ss;
        ss.validate()?;
        self.check_options()?;
        let n = ss.states();
        let sp = split::split(ss)?;
        let nu = sp.kept();
        let ns = n - nu;
        let hankel = if ns > 0 {
            Some(balanced::Hankel::new(&sp.a_s, &sp.b_s, &sp.c_s)?)
        } else {
            None
        };
        let sigma = hankel.as_ref().map(|h| h.sigma.clone()).unwrap_or_default();
        let numerical = hankel.as_ref().map_or(0, |h| h.numerical_order());
        let mut warnings = Vec::new();
        if numerical < ns && self.method != ReductionMethod::Modal {
            warnings.push(NumWarning::HankelNegligible {
                count: ns - numerical,
                stable: ns,
            });
        }
        if sp.coupling_singular || sp.coupling > 1e8 {
            warnings.push(NumWarning::StableKeptCoupling { norm: sp.coupling });
        }
        let d = &ss.d;
        let (a_r, b_r, c_r, d_r, v_s, w_s, bound) = match self.method {
            ReductionMethod::Modal => {
                let (v, w, t11, singular) = self.modal(&sp)?;
                if singular {
                    warnings.push(NumWarning::ModalTruncationIllConditioned);
                }
                let b = w.transpose() * &sp.b_s;
                let c = &sp.c_s * &v;
                (t11, b, c, DMatrix::zeros(d.nrows(), d.ncols()), v, w, None)
            }
            method => {
                let rs = self.balanced_order(nu, ns, &sigma, numerical)?;
                let (v, w) = match &hankel {
                    Some(h) => h.bases(rs),
                    None => (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0)),
                };
                let zero_d = DMatrix::zeros(d.nrows(), d.ncols());
                let (a, b, c, dd) = if method == ReductionMethod::MatchDc && rs < numerical {
                    let (vm, wm) = hankel.as_ref().expect("stable part").bases(numerical);
                    let ab = wm.transpose() * &sp.a_s * &vm;
                    let bb = wm.transpose() * &sp.b_s;
                    let cb = &sp.c_s * &vm;
                    let [a, b, c, dd] =
                        balanced::singular_perturbation(&ab, &bb, &cb, &zero_d, rs)?;
                    (a, b, c, dd)
                } else if ns > 0 {
                    (
                        w.transpose() * &sp.a_s * &v,
                        w.transpose() * &sp.b_s,
                        &sp.c_s * &v,
                        zero_d,
                    )
                } else {
                    (
                        DMatrix::zeros(0, 0),
                        DMatrix::zeros(0, ss.inputs()),
                        DMatrix::zeros(ss.outputs(), 0),
                        zero_d,
                    )
                };
                (a, b, c, dd, v, w, Some(balanced::bound(&sigma, rs)))
            }
        };
        let zero_d = DMatrix::zeros(d.nrows(), d.ncols());
        let error = if ns > 0 {
            measure::measure(
                [&sp.a_s, &sp.b_s, &sp.c_s, &zero_d],
                [&a_r, &b_r, &c_r, &d_r],
            )?
        } else {
            MeasuredError {
                hinf: 0.0,
                at_hz: 0.0,
                dc: 0.0,
                points: 0,
            }
        };
        let rs = a_r.nrows();
        let state_space = assemble(ss, &sp, [&a_r, &b_r, &c_r, &d_r], &v_s, &w_s, self.method)?;
        let (v, w) = full_bases(&sp, &v_s, &w_s, ns, rs);
        let phys = &ss.phys * &v;
        let state_space = state_space.with_phys(phys)?;
        Ok(ReducedModel {
            state_space,
            method: self.method,
            full_states: n,
            kept: nu,
            structural_zeros: sp.structural,
            hankel: sigma,
            numerical_order: numerical,
            bound,
            error,
            v,
            w,
            coupling: sp.coupling,
            warnings,
        })
    }

    fn check_options(&self) -> Result<(), NumError> {
        if let Some((lo, hi)) = self.band_hz {
            if self.method != ReductionMethod::Modal {
                return Err(invalid(OptionError::BandNeedsModal));
            }
            if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && lo <= hi) {
                return Err(invalid(OptionError::Band { low: lo, high: hi }));
            }
            if self.order != OrderChoice::Default {
                return Err(invalid(OptionError::BandAndOrder));
            }
        }
        match self.order {
            OrderChoice::Tolerance(t) if !(t.is_finite() && t > 0.0) => {
                Err(invalid(OptionError::ReductionTolerance { tolerance: t }))
            }
            OrderChoice::Tolerance(_) if self.method == ReductionMethod::Modal => {
                Err(invalid(OptionError::ModalTolerance))
            }
            OrderChoice::Default
                if self.method == ReductionMethod::Modal && self.band_hz.is_none() =>
            {
                Err(invalid(OptionError::ModalWithoutOrder))
            }
            _ => Ok(()),
        }
    }

    /// The order of the stable part for the balanced methods.
    fn balanced_order(
        &self,
        nu: usize,
        ns: usize,
        sigma: &[f64],
        numerical: usize,
    ) -> Result<usize, NumError> {
        let smallest = |tol: f64| {
            (0..=numerical)
                .find(|&r| balanced::bound(sigma, r) <= tol)
                .unwrap_or(numerical)
        };
        match self.order {
            OrderChoice::States(r) => {
                if r < nu {
                    return Err(invalid(OptionError::OrderBelowKept { order: r, kept: nu }));
                }
                if r - nu > numerical {
                    return Err(invalid(OptionError::OrderAboveReducible {
                        order: r,
                        kept: nu,
                        reducible: numerical,
                        hidden: ns.saturating_sub(numerical),
                    }));
                }
                Ok(r - nu)
            }
            OrderChoice::Tolerance(t) => Ok(smallest(t)),
            OrderChoice::Default => Ok(smallest(
                DEFAULT_RELATIVE_TOLERANCE * sigma.first().copied().unwrap_or(0.0),
            )),
        }
    }

    /// The bases and reduced A of modal truncation.
    fn modal(&self, sp: &split::Split) -> Result<modal::ModalBases, NumError> {
        let nu = sp.kept();
        let ns = sp.a_s.nrows();
        let hz = |z: Complex64| z.norm() / (2.0 * std::f64::consts::PI);
        if let Some((lo, hi)) = self.band_hz {
            return modal::modal_bases(&sp.a_s, |z| (lo..=hi).contains(&hz(z)));
        }
        let OrderChoice::States(r) = self.order else {
            unreachable!("checked: modal has an order or a band")
        };
        if r < nu || r - nu > ns {
            return Err(invalid(OptionError::ModalOrder {
                order: r,
                kept: nu,
                all: nu + ns,
            }));
        }
        let k = r - nu;
        let mut mags: Vec<f64> = schur::eigenvalues(&sp.a_s)
            .iter()
            .map(|z| z.norm())
            .collect();
        mags.sort_by(f64::total_cmp);
        if k == 0 {
            return modal::modal_bases(&sp.a_s, |_| false);
        }
        let limit = mags[k - 1];
        if k < ns && mags[k] <= limit {
            return Err(invalid(OptionError::OrderSplitsModes {
                order: r,
                hz: limit / (2.0 * std::f64::consts::PI),
            }));
        }
        modal::modal_bases(&sp.a_s, |z| z.norm() <= limit)
    }
}

/// The reduced model: `blkdiag(A_kept, A_r)`, `[B_kept; B_r]`, `[C_kept, C_r]`, `D + D_r`, with
/// the full model's input and output names.
fn assemble(
    ss: &StateSpace<f64>,
    sp: &split::Split,
    reduced: [&DMatrix<f64>; 4],
    _v: &DMatrix<f64>,
    _w: &DMatrix<f64>,
    method: ReductionMethod,
) -> Result<StateSpace<f64>, NumError> {
    let [ar, br, cr, dr] = reduced;
    let (nu, rs) = (sp.kept(), ar.nrows());
    let r = nu + rs;
    let (m, p) = (ss.inputs(), ss.outputs());
    let mut a = DMatrix::zeros(r, r);
    a.view_mut((0, 0), (nu, nu)).copy_from(&sp.a_u);
    a.view_mut((nu, nu), (rs, rs)).copy_from(ar);
    let mut b = DMatrix::zeros(r, m);
    b.view_mut((0, 0), (nu, m)).copy_from(&sp.b_u);
    b.view_mut((nu, 0), (rs, m)).copy_from(br);
    let mut c = DMatrix::zeros(p, r);
    c.view_mut((0, 0), (p, nu)).copy_from(&sp.c_u);
    c.view_mut((0, nu), (p, rs)).copy_from(cr);
    let d = &ss.d + dr;
    let prefix = match method {
        ReductionMethod::Modal => "modal",
        _ => "balanced",
    };
    let mut states = sp.kept_names.clone();
    states.extend((1..=rs).map(|k| format!("{prefix} {k}")));
    let names = SignalNames {
        states,
        bodies: Vec::new(),
        ..ss.names.clone()
    };
    StateSpace::new(a, b, c, d)?.with_names(names)
}

/// `V` and `W` of the whole reduction: the kept coordinates of the split, then the stable
/// part's bases mapped through it.
fn full_bases(
    sp: &split::Split,
    v_s: &DMatrix<f64>,
    w_s: &DMatrix<f64>,
    ns: usize,
    rs: usize,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = sp.to_x.nrows();
    let nu = sp.kept();
    let mut v = DMatrix::zeros(n, nu + rs);
    v.view_mut((0, 0), (n, nu))
        .copy_from(&sp.to_x.columns(0, nu));
    let mut w = DMatrix::zeros(n, nu + rs);
    w.view_mut((0, 0), (n, nu))
        .copy_from(&sp.from_x.rows(0, nu).transpose());
    if ns > 0 && rs > 0 {
        let vs = sp.to_x.columns(nu, ns) * v_s;
        v.view_mut((0, nu), (n, rs)).copy_from(&vs);
        let ws = sp.from_x.rows(nu, ns).transpose() * w_s;
        w.view_mut((0, nu), (n, rs)).copy_from(&ws);
    }
    (v, w)
}
