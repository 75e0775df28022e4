//! The options of the minimal realization.

use super::tolerance_error;
use crate::error::NumError;

/// Options of [`minimal_realization`].
#[derive(Clone, Debug, PartialEq)]
pub struct MinrealOptions {
    /// Relative rank tolerance (see the module documentation). `None` uses
    /// `1000 · max(n, m, p) · ε`.
    pub rtol: Option<f64>,
    /// Absolute floor of the rank tolerance (default 0). Only useful when the caller knows the
    /// absolute accuracy of the model data.
    pub atol: f64,
    /// Balance the states before the reduction (default `true`).
    pub balance: bool,
    /// A removed mode is classified as marginal when `|Re λ| ≤ stability_rtol · ‖A‖_F`
    /// (balanced A), unstable when `Re λ` is above that and stable when below its negative.
    /// The default `1e-8 ≈ √ε` also covers the √ε spread of a computed double zero
    /// eigenvalue (a rigid-body mode: position and velocity).
    pub stability_rtol: f64,
    /// Confirm every removal by the PBH test ([`RemovedMode::pbh_residual`]; default
    /// `true`). It costs one Hessenberg reduction of `A` per kind of removed mode and O(n²)
    /// per distinct removed eigenvalue (conjugates and repeated eigenvalues share one).
    pub pbh_check: bool,
    /// Run the cluster PBH pass after each staircase (default `true`; see the module
    /// documentation). It costs one eigenvalue computation of the controllable part (and of
    /// the observable part when the previous stages removed something) and one SVD per
    /// cluster of eigenvalues.
    pub cluster_pbh: bool,
    /// Eigenvalues within `cluster_rtol · ‖A‖_F` (balanced A) of each other, transitively,
    /// form a cluster examined by the PBH pass. Rounding splits a semisimple multiple
    /// eigenvalue by about `ε ‖A‖` times its condition number, and a defective double one by
    /// about `√(ε ‖A‖ · |coupling|)`, i.e. `√ε ≈ 1.5e-8` relative (the truck–trailer's
    /// heading and lateral position, split to about `±1e-6 i` by the robust reduction,
    /// lie about `2e-8 ‖A‖_F` apart). The default `1e-6` covers both with a margin of about 60 for the
    /// conditioning. A larger value costs PBH tests but removes nothing that the test at the
    /// cluster's mean does not confirm.
    pub cluster_rtol: f64,
}

impl Default for MinrealOptions {
    fn default() -> Self {
        MinrealOptions {
            rtol: None,
            atol: 0.0,
            balance: true,
            stability_rtol: 1e-8,
            pbh_check: true,
            cluster_pbh: true,
            cluster_rtol: 1e-6,
        }
    }
}

impl MinrealOptions {
    /// The default relative rank tolerance `1000 · max(n, m, p, 1) · ε` for a system with `n`
    /// states, `m` inputs and `p` outputs.
    pub fn default_rtol(n: usize, m: usize, p: usize) -> f64 {
        1000.0 * (n.max(m).max(p).max(1) as f64) * f64::EPSILON
    }

    pub(super) fn validate(&self) -> Result<(), NumError> {
        if let Some(r) = self.rtol
            && !(r.is_finite() && r >= 0.0)
        {
            return Err(tolerance_error("MinrealOptions.rtol", r));
        }
        if !(self.atol.is_finite() && self.atol >= 0.0) {
            return Err(tolerance_error("MinrealOptions.atol", self.atol));
        }
        if !(self.stability_rtol.is_finite() && self.stability_rtol >= 0.0) {
            return Err(tolerance_error(
                "MinrealOptions.stability_rtol",
                self.stability_rtol,
            ));
        }
        if !(self.cluster_rtol.is_finite() && self.cluster_rtol >= 0.0) {
            return Err(tolerance_error(
                "MinrealOptions.cluster_rtol",
                self.cluster_rtol,
            ));
        }
        Ok(())
    }
}
