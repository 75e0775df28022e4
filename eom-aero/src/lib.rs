//! # eom-aero — quasi-steady wing aerodynamics
//!
//! A wing on a vehicle model enters the equations of motion as a 6×6 damping-like matrix:
//! the aerodynamic force and moment at a point, linearised in the six velocities of that
//! point (u, v, w, p, q, r). This crate computes that matrix, in the non-dimensional form
//! of AVL's body-axis ("SB") derivatives, [`Derivatives`], in two ways:
//!
//! * [`solve`]: a vortex-lattice method for flat lifting surfaces described by a
//!   [`Configuration`] (built in Rust, or read from an AVL `.avl` file with [`read_avl`]);
//! * [`AvlOutput`]: a reader for the `.sb` and `.st` files that AVL itself writes, for users
//!   who have AVL results already.
//!
//! It knows nothing about multibody models: it turns geometry into derivatives. The model
//! layer rotates them into its own axes and attaches them to a point.
//!
//! ## A first wing
//!
//! The vertical fin of the EoM seed paper: a flat plate 1 m high with a 0.5 m chord, in the
//! x–z plane, with the moment reference at its quarter chord.
//!
//! ```
//! use eom_aero::{Configuration, Reference, Section, SolverOptions, Surface, solve};
//!
//! # fn main() -> Result<(), eom_aero::AeroError> {
//! // AVL geometry axes: x aft, y right, z up. Sref, Cref, Bref and the reference point.
//! let fin = Configuration::new("fin", Reference::new(0.5, 0.5, 1.0, [0.125, 0.0, 0.0]))
//!     .surface(
//!         Surface::new("Fin")
//!             .lattice(8, 1.0, 16, 1.0) // 8 chordwise × 16 spanwise panels, cosine/cosine
//!             .section(Section::new([0.0, 0.0, -0.5], 0.5))
//!             .section(Section::new([0.0, 0.0, 0.5], 0.5)),
//!     );
//! let solution = solve(&fin, &SolverOptions::default())?;
//! let d = &solution.derivatives;
//!
//! // side force per sideslip and yaw damping, as AVL 3.32 prints them: −2.474202, −0.146157
//! assert!((d.get("CYv").unwrap() / -2.474202 - 1.0).abs() < 1e-3);
//! assert!((d.get("Cnr").unwrap() / -0.146157 - 1.0).abs() < 1e-3);
//!
//! // dimensional ∂F/∂x at ρ = 1.225 kg/m³, V = 10 m/s: ∂Y/∂v [N·s/m]
//! let dfdx = d.dimensional(1.225, 10.0)?;
//! assert!((dfdx[1][1] / -7.57725 - 1.0).abs() < 1e-3);
//! # Ok(())
//! # }
//! ```
//!
//! ## The method
//!
//! The horseshoe vortex-lattice method of Katz & Plotkin (*Low-Speed Aerodynamics*, 2nd
//! ed., Cambridge 2001, ch. 12), in linear theory: the wake is a set of straight trailing
//! vortices along the x axis, the lifting surfaces are flat, and incidence only tilts the
//! direction in which flow tangency is imposed.
//!
//! 1. **Lattice.** Each surface is a ruled surface through its sections (leading-edge
//!    point, chord along +x, incidence), cut into strips along the span and panels along
//!    the chord. Each panel carries a horseshoe vortex: a bound segment across the panel and
//!    two trailing legs to x = +∞. Chordwise, cosine spacing uses Lan's quasi-vortex-lattice
//!    stations (C. E. Lan, *J. Aircraft* 11(9), 1974): vortex at ½(1 − cos((2j − 1)π/2N)),
//!    control point at ½(1 − cos(jπ/N)) of the chord; equal spacing uses the ¼–¾ rule.
//!    Spanwise, the control point of a strip sits at the image of the strip's middle
//!    parameter under the spacing function (the cosine of the mid-angle), not at the
//!    midpoint of its edges, which keeps the lattice accurate from coarse meshes on.
//!    `YDUPLICATE` adds the mirror image as a real surface, so asymmetric flight is exact.
//! 2. **Normals.** Section chord lines are tilted by their incidence and interpolated
//!    linearly; a panel's normal is perpendicular to that chord line and to its bound
//!    vortex.
//! 3. **Flow tangency.** At each control point, the velocity induced by all horseshoes
//!    (Biot–Savart law for straight segments and semi-infinite lines) cancels the normal
//!    component of the air's velocity relative to the body, V_rel = −(U + ω × r). The
//!    circulations are linear in the state x = (u, v, w, p, q, r), so one dense LU of the
//!    influence matrix solves for the trim circulation and for the six ∂Γ/∂x_j together.
//! 4. **Loads.** The Kutta–Joukowski force ρΓ(W × l) acts on each bound segment at the
//!    point of the segment at its control point's spanwise station, with W the local
//!    velocity (free stream, rotation and induced velocity of all other vortices). The
//!    on-surface parts of the trailing legs can carry load too
//!    ([`SolverOptions::trailing_leg_forces`]). The forces are bilinear in (Γ, W), so their
//!    derivatives ρΣ[∂Γ (W × l) + Γ (∂W × l)] are exact, lift-dependent couplings included.
//! 5. **Normalisation.** Forces and moments about the reference point are converted to
//!    AVL's standard axes (x forward, y right, z down) and divided by q·S (forces), q·S·b
//!    (roll, yaw) and q·S·c (pitch); the state by V (velocities), 2V/b and 2V/c (rates).
//!
//! Compressibility follows the Prandtl–Glauert rule in Göthert's form: the induced
//! velocities are those of the geometry stretched by 1/√(1 − M²) along x. Ground effect
//! ([`Configuration::ground_at`], AVL's iZsym = 1) adds the mirror image of every horseshoe
//! below the ground plane with reversed circulation, so that no air flows through the
//! ground; iZsym = −1 (a constant-pressure plane) keeps the image's circulation.
//!
//! ## Conventions
//!
//! | what | convention |
//! |---|---|
//! | geometry input | AVL geometry axes: x aft, y right, z up |
//! | derivatives | AVL standard body axes: x forward, y right, z down |
//! | rows | CX, CY, CZ (per q·S), Cl, Cn (per q·S·b), Cm (per q·S·c) |
//! | columns | u/V, v/V, w/V, p·b/2V, q·c/2V, r·b/2V |
//! | sideslip | β > 0 ⇔ v > 0 (wind from the right) |
//! | dimensional | [`Derivatives::dimensional`] = (qS/V)·build_mtx; the EoM wing damping is its negative |
//!
//! ## AVL files
//!
//! [`read_avl`] reads the lifting-surface part of AVL's geometry format ([`avl_input`]
//! lists what is refused). [`AvlOutput`] reads ST and SB files by name; SB is the one to
//! prefer, since ST files give stability-axis derivatives from which the u column (and,
//! away from α = 0, the w column) cannot be recovered. [`validity`] has the limits within
//! which quasi-steady derivatives can be trusted.
//!
//! ## Not covered
//!
//! Camber lines, slender bodies, control surfaces, viscous drag, the y image plane
//! (iYsym; model both halves instead), and surfaces without a wake (NOWAKE).
//!
//! ## Vortex core
//!
//! Like AVL, the lattice smooths the velocity that one component's vortices induce on
//! another component's points within a finite core, by default twice the strip width
//! ([`vortex_core`]: AVL's VRCOREC = 0, VRCOREW = 2). It matters where one surface's
//! trailing legs pass close to another's points, e.g. a wing's root legs along the root
//! of a fin on the centre line (a few percent in CYv, Cnv, CYp). It is read from the `CORE`
//! line of an `.avl` file and can be set or switched off ([`VortexCore::OFF`]) in
//! [`SolverOptions::vortex_core`]; without it the interference of such surfaces converges
//! faster with the lattice, with it the results match AVL's at equal lattices.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod avl_input;
pub mod avl_output;
pub mod derivatives;
pub mod error;
pub mod geometry;
mod kernel;
mod lattice;
pub mod solver;
pub mod spacing;
pub mod stability;
pub mod validity;
pub mod vortex_core;
pub mod warning;
pub mod wing_file;

pub use avl_input::{parse_avl, read_avl};

/// The most horseshoe vortices of one lattice (mirror images included). The influence matrix
/// is dense: 10 000 panels take 1.6 GB with its factors and about 7·10¹¹ operations (AVL's own
/// default limit is 6 000 vortices). A larger lattice is refused before it is built, and the
/// influence matrix's memory is checked against `eom_num::budget` (`EOM_MEMORY_LIMIT`).
pub const MAX_PANELS: usize = 10_000;
pub use avl_output::{AvlOutput, AvlOutputKind};
pub use derivatives::{Derivatives, Reference, StabilityDerivatives};
pub use error::{AeroError, Result};
pub use geometry::{Configuration, Section, Surface, Symmetry};
pub use solver::{LatticeSize, Solution, SolverOptions, Totals, solve};
pub use spacing::Spacing;
pub use stability::BodyDerivatives;
pub use validity::{REDUCED_FREQUENCY_LIMIT, RateCheck, check_rates, reduced_frequency};
pub use vortex_core::VortexCore;
pub use warning::AeroWarning;
pub use wing_file::{WingFileDerivatives, WingFileKind, read_wing_file};
