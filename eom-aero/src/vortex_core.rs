//! AVL's finite vortex core: the velocity that a vortex line induces on a *different*
//! component of the configuration is smoothed within a core radius of the line.
//!
//! Near a vortex line the Biot–Savart velocity grows as Γ/(2πr). Where one surface's
//! trailing legs run close to another surface's control points — a wing's root legs along
//! the root of a fin on the centre line, a tail in the wing's wake — that singular velocity
//! makes the interference depend on where the lattice happens to put its points. AVL
//! (M. Drela and H. Youngren, versions 3.5x, routine VORVELC) smooths it, between
//! components only, with the n = 2 member of Vatistas' family of core models (G. H.
//! Vatistas, V. Kozel and W. C. Mih, *Exp. Fluids* 11, 1991), which AVL's source calls
//! Leishman's R⁴ variant of the Scully (Burnham–Hallock) core:
//!
//! ```text
//!   infinite line:   v_θ = Γ/(2π) · r / √(r⁴ + r_c⁴)
//!   segment a → b:   v = Γ/(4π) · (r₁×r₂) [r₀·r₁/(|r₁|⁴+r_c⁴)^¼ − r₀·r₂/(|r₂|⁴+r_c⁴)^¼]
//!                              / √(|r₁×r₂|⁴ + |r₀|⁴ r_c⁴)
//!   trailing leg:    v = Γ/(4π) · (x̂×r)(1 + r_x/|r|) / √(h⁴ + r_c⁴),   h² = r_y² + r_z²
//! ```
//!
//! with r₁ = p − a, r₂ = p − b, r₀ = b − a; with r_c = 0 these are the classic kernels.
//! The core radius of a horseshoe is
//!
//! ```text
//!   r_c = max(VRCOREC · c, VRCOREW · w)
//! ```
//!
//! with c the chord of its strip and w the length of its bound segment projected on the y–z
//! plane (the strip's width). It applies to the whole horseshoe (bound segment and both
//! legs, and their ground images) seen from control and force points of *other*
//! components; within a component the kernels stay singular (AVL's token core of 10⁻⁴ w
//! there changes nothing that a lattice point can see). AVL's defaults are VRCOREC = 0,
//! VRCOREW = 2: a core twice the strip width. Components are AVL's: each surface is its own,
//! a `YDUPLICATE` image belongs to its original's, and `COMPONENT`/`INDEX` puts surfaces
//! together ([`Surface::component`](crate::Surface::component)).
//!
//! AVL reads the fractions from the `CORE` keyword of the `.avl` file (a line
//! `VRCOREC VRCOREW SRCORE` after it; SRCORE is the source core of slender bodies, which
//! this crate does not model) and lets the user change them in its OPER options menu. Here
//! the file's value is [`Configuration::vortex_core`](crate::Configuration::vortex_core),
//! and [`SolverOptions::vortex_core`](crate::SolverOptions::vortex_core) overrides it.

use serde::Serialize;

/// The core radius fractions of AVL's finite vortex core (see the [module](self) docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct VortexCore {
    /// Core radius per strip chord (AVL's VRCOREC).
    pub chord_fraction: f64,
    /// Core radius per strip width, the bound segment's length in the y–z plane (AVL's
    /// VRCOREW).
    pub width_fraction: f64,
}

impl VortexCore {
    /// AVL's defaults: VRCOREC = 0, VRCOREW = 2.
    pub const AVL_DEFAULT: VortexCore = VortexCore {
        chord_fraction: 0.0,
        width_fraction: 2.0,
    };

    /// No core (VRCOREC = VRCOREW = 0): singular Biot–Savart kernels everywhere.
    pub const OFF: VortexCore = VortexCore {
        chord_fraction: 0.0,
        width_fraction: 0.0,
    };

    /// A core of `chord_fraction` strip chords or `width_fraction` strip widths, the larger.
    pub fn new(chord_fraction: f64, width_fraction: f64) -> Self {
        VortexCore {
            chord_fraction,
            width_fraction,
        }
    }

    /// The core radius of a horseshoe on a strip of `chord` and y–z `width`.
    pub fn radius(&self, chord: f64, width: f64) -> f64 {
        (self.chord_fraction * chord).max(self.width_fraction * width)
    }

    /// Why these fractions cannot be used (negative or not finite), if so.
    pub fn problem(&self) -> Option<String> {
        let ok = |v: f64| v.is_finite() && v >= 0.0;
        (!(ok(self.chord_fraction) && ok(self.width_fraction))).then(|| {
            format!(
                "the core fractions VRCOREC, VRCOREW must be finite and not negative, are {} and {}",
                self.chord_fraction, self.width_fraction
            )
        })
    }
}

impl Default for VortexCore {
    fn default() -> Self {
        VortexCore::AVL_DEFAULT
    }
}
