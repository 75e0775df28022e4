//! The minimal-realization section: the kept states and every removed mode with the reason
//! (uncontrollable or unobservable) and its stability.

use super::*;
use crate::error::CliError;
use crate::format::{eigenvalue, g, re_im};
use crate::shown_warning::ShownWarning;
use eom_num::StateSpace;
use eom_num::minreal::{MinrealReport, ModeStability, RankStage, RemovedKind};
use eom_num::modes::{ModeKind, Modes, Stability};
use num_complex::Complex64;

/// The minimal realization of the model as shown: the states kept, and every removed mode
/// matched to its eigenvalue with the reason and its stability.
pub(super) fn minimal_view(
    ssm: &StateSpace<f64>,
    rep: &MinrealReport,
    modes: &Modes,
    warnings: &mut Vec<ShownWarning>,
) -> Result<MinimalReport, CliError> {
    for d in rep.fragile_decisions(100.0) {
        let stage = match d.stage {
            RankStage::Controllability => "controllability",
            RankStage::Observability => "observability",
            RankStage::ControllabilityPbh => "controllability (PBH test at repeated eigenvalues)",
            RankStage::ObservabilityPbh => "observability (PBH test at repeated eigenvalues)",
            _ => "rank",
        };
        let message = format!(
            "minimal realization: the {stage} rank decision at step {} is within a factor 100 of \
             its tolerance {} (singular values {}): another choice of units could change which \
             modes count as removed",
            d.step,
            g(d.tolerance, 3),
            d.singular_values
                .iter()
                .map(|s| g(*s, 3))
                .collect::<Vec<_>>()
                .join(", ")
        );
        warnings.push(ShownWarning::new("fragile_minimal_realization", message));
    }
    // Nothing removed: the same model, the same modes.
    let mmodes = if rep.states_out == rep.states_in {
        modes.clone()
    } else {
        Modes::compute_with(ssm, &mode_options())?
    };
    let removed = rep
        .removed
        .iter()
        .map(|r| {
            // The nearest mode of the full model: its kind, and its verdict (one verdict per
            // eigenvalue, by its error estimate, wherever it is shown).
            let nearest = modes.modes.iter().min_by(|a, b| {
                (a.eigenvalue - r.eigenvalue)
                    .norm()
                    .total_cmp(&(b.eigenvalue - r.eigenvalue).norm())
            });
            let kind = nearest.map_or(ModeKind::Real, |m| m.kind);
            let reason = match r.kind {
                RemovedKind::Uncontrollable => "uncontrollable",
                RemovedKind::Unobservable => "unobservable",
            };
            let verdict = nearest.map_or(
                match r.stability {
                    ModeStability::Stable => Stability::Stable,
                    ModeStability::Marginal => Stability::Marginal,
                    ModeStability::Unstable => Stability::Unstable,
                },
                |m| m.stability,
            );
            let stability = stability_name(verdict);
            RemovedReport {
                eigenvalue: r.eigenvalue.into(),
                reason,
                stability,
                kind: kind_name(kind),
                pbh_residual: r.pbh_residual,
                note: removed_note(r.eigenvalue, r.kind, verdict, kind),
            }
        })
        .collect();
    Ok(MinimalReport {
        states: ssm.states(),
        eigenvalues: re_im(&mmodes.eigenvalues()),
        modes: mmodes.modes.iter().map(mode_report).collect(),
        removed,
    })
}

pub(super) fn removed_note(
    z: Complex64,
    why: RemovedKind,
    st: Stability,
    kind: ModeKind,
) -> String {
    let what = match kind {
        ModeKind::Zero => "zero (rigid-body/integrator) mode",
        ModeKind::Real => "real mode",
        ModeKind::Oscillatory => "oscillatory mode",
    };
    let (removed, cause) = match why {
        RemovedKind::Uncontrollable => ("uncontrollable", "the inputs cannot excite it"),
        RemovedKind::Unobservable => ("unobservable", "the outputs cannot see it"),
    };
    let lam = eigenvalue(z, SIG, false);
    match st {
        Stability::Unstable => format!(
            "UNSTABLE {what} {lam} is {removed}: {cause}, yet it grows in the physical system"
        ),
        Stability::Marginal => {
            format!("marginal {what} {lam} is {removed}: {cause}; it does not decay")
        }
        Stability::Stable => format!("stable {what} {lam} is {removed}: {cause}"),
    }
}
