//! Wing geometry: a [`Configuration`] of lifting [`Surface`]s, each a ruled surface through
//! two or more [`Section`]s.
//!
//! Coordinates are AVL's *geometry axes*: x downstream (aft), y out of the right wing, z up.
//! Section chords lie along +x; a section's incidence tilts only the flow-tangency normal
//! (linear theory), not the panels.

use crate::derivatives::Reference;
use crate::error::{AeroError, Result};
use crate::spacing::Spacing;
use serde::Serialize;

/// A whole configuration: reference quantities, Mach number and surfaces.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Configuration {
    /// Title (the first line of an `.avl` file).
    pub title: String,
    /// Free-stream Mach number (Prandtl–Glauert compressibility correction); 0 … < 1.
    pub mach: f64,
    /// Reference area, chord, span and the moment reference point (geometry axes).
    pub reference: Reference,
    /// Image planes of the flow (AVL's iYsym, iZsym, Zsym): the z plane (ground effect, a
    /// free surface) is supported, the y plane is not (use [`Surface::y_duplicate`]).
    pub symmetry: Symmetry,
    /// Profile drag coefficient CDp of the `.avl` header (read, not used by the lattice).
    pub cdp: f64,
    /// The lifting surfaces.
    pub surfaces: Vec<Surface>,
}

/// AVL's flow-symmetry flags: image planes y = 0 (`iysym`) and z = `zsym` (`izsym`),
/// +1 a solid wall (e.g. the ground), −1 a constant-pressure plane, 0 none.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Symmetry {
    /// Image about y = 0.
    pub iysym: i32,
    /// Image about z = `zsym`.
    pub izsym: i32,
    /// Height of the z image plane.
    pub zsym: f64,
}

/// One lifting surface (a wing, a tail, a fin).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Surface {
    /// Name, used in error messages.
    pub name: String,
    /// AVL component index (informational: all surfaces share one lattice here).
    pub component: Option<i64>,
    /// Chordwise panels and their spacing (AVL `Nchord Cspace`).
    pub chordwise: Spacing,
    /// Spanwise strips over the whole surface (AVL `Nspan Sspace` on the surface line);
    /// when absent, every section but the last must give its own.
    pub spanwise: Option<Spacing>,
    /// Mirror the surface about the plane y = this value (AVL `YDUPLICATE`).
    pub y_duplicate: Option<f64>,
    /// Scale factors applied to the section data before the translation (AVL `SCALE`);
    /// chords are scaled by the x factor.
    pub scale: [f64; 3],
    /// Translation applied after scaling (AVL `TRANSLATE`).
    pub translate: [f64; 3],
    /// Incidence added to every section, degrees (AVL `ANGLE`).
    pub angle_deg: f64,
    /// The surface's control points ignore α, β and the rotation rates (AVL `NOALBE`):
    /// they see only the axial free stream, e.g. for a ground plane.
    pub no_alpha_beta: bool,
    /// The surface's loads are left out of the totals and derivatives (AVL `NOLOAD`).
    pub no_load: bool,
    /// The sections, in spanwise order.
    pub sections: Vec<Section>,
}

/// A section: the chord line at one spanwise station.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Section {
    /// Leading-edge point (geometry axes).
    pub leading_edge: [f64; 3],
    /// Chord length (along +x).
    pub chord: f64,
    /// Incidence, degrees, positive nose up.
    pub incidence_deg: f64,
    /// Strips from this section to the next (AVL `Nspan Sspace` on the section line), used
    /// when the surface gives none.
    pub spanwise: Option<Spacing>,
}

impl Section {
    /// A flat section at `leading_edge` with `chord`, no incidence.
    pub fn new(leading_edge: [f64; 3], chord: f64) -> Self {
        Section {
            leading_edge,
            chord,
            incidence_deg: 0.0,
            spanwise: None,
        }
    }

    /// The same section with an incidence (degrees, nose up).
    pub fn incidence_deg(mut self, deg: f64) -> Self {
        self.incidence_deg = deg;
        self
    }

    /// The same section with its own strip count and spacing to the next section.
    pub fn strips(mut self, count: usize, parameter: f64) -> Self {
        self.spanwise = Some(Spacing::new(count, parameter));
        self
    }
}

impl Surface {
    /// An empty surface named `name` with the recommended lattice: 8 cosine-spaced
    /// chordwise panels and 16 cosine-spaced strips. Add at least two sections.
    pub fn new(name: impl Into<String>) -> Self {
        Surface {
            name: name.into(),
            component: None,
            chordwise: Spacing::cosine(8),
            spanwise: Some(Spacing::cosine(16)),
            y_duplicate: None,
            scale: [1.0; 3],
            translate: [0.0; 3],
            angle_deg: 0.0,
            no_alpha_beta: false,
            no_load: false,
            sections: Vec::new(),
        }
    }

    /// A straight-tapered half wing from the root section at the origin out to +y, mirrored
    /// about y = 0 (so `semi_span` is half the span). `sweep_le_deg` sweeps the leading edge
    /// back, `dihedral_deg` raises the tip.
    pub fn wing(
        name: impl Into<String>,
        semi_span: f64,
        root_chord: f64,
        tip_chord: f64,
        sweep_le_deg: f64,
        dihedral_deg: f64,
    ) -> Self {
        let tip = [
            semi_span * sweep_le_deg.to_radians().tan(),
            semi_span,
            semi_span * dihedral_deg.to_radians().tan(),
        ];
        Surface::new(name)
            .section(Section::new([0.0; 3], root_chord))
            .section(Section::new(tip, tip_chord))
            .mirrored_about_y(0.0)
    }

    /// A vertical fin from its root at the origin up to z = `height`, not mirrored.
    pub fn fin(
        name: impl Into<String>,
        height: f64,
        root_chord: f64,
        tip_chord: f64,
        sweep_le_deg: f64,
    ) -> Self {
        let tip = [height * sweep_le_deg.to_radians().tan(), 0.0, height];
        Surface::new(name)
            .section(Section::new([0.0; 3], root_chord))
            .section(Section::new(tip, tip_chord))
    }

    /// Adds a section (in spanwise order).
    pub fn section(mut self, section: Section) -> Self {
        self.sections.push(section);
        self
    }

    /// Sets the lattice: `nchord` panels with spacing `cspace`, `nspan` strips with spacing
    /// `sspace` over the whole surface (AVL's `Nchord Cspace Nspan Sspace`).
    pub fn lattice(mut self, nchord: usize, cspace: f64, nspan: usize, sspace: f64) -> Self {
        self.chordwise = Spacing::new(nchord, cspace);
        self.spanwise = Some(Spacing::new(nspan, sspace));
        self
    }

    /// Takes the strip counts from the sections instead of the surface.
    pub fn strips_per_section(mut self) -> Self {
        self.spanwise = None;
        self
    }

    /// Mirrors the surface about the plane y = `y` (AVL `YDUPLICATE`).
    pub fn mirrored_about_y(mut self, y: f64) -> Self {
        self.y_duplicate = Some(y);
        self
    }

    /// Moves the surface by `offset` (AVL `TRANSLATE`).
    pub fn translated(mut self, offset: [f64; 3]) -> Self {
        self.translate = offset;
        self
    }

    /// Scales the section data (AVL `SCALE`).
    pub fn scaled(mut self, factors: [f64; 3]) -> Self {
        self.scale = factors;
        self
    }

    /// Adds `deg` to every section's incidence (AVL `ANGLE`).
    pub fn angle_deg(mut self, deg: f64) -> Self {
        self.angle_deg = deg;
        self
    }

    fn err(&self, section: Option<usize>, field: &'static str, reason: String) -> AeroError {
        AeroError::Geometry {
            surface: self.name.clone(),
            section,
            field,
            reason,
        }
    }

    /// Checks the surface; the error names the surface, section and field at fault.
    pub fn validate(&self) -> Result<()> {
        if self.sections.len() < 2 {
            return Err(self.err(
                None,
                "sections",
                format!("needs at least 2 sections, has {}", self.sections.len()),
            ));
        }
        if let Some(r) = self.chordwise.problem() {
            return Err(self.err(None, "Nchord/Cspace", r));
        }
        if let Some(r) = self.spanwise.and_then(|s| s.problem()) {
            return Err(self.err(None, "Nspan/Sspace", r));
        }
        check_finite(self, None, "scale", &self.scale)?;
        if self.scale.contains(&0.0) {
            return Err(self.err(None, "scale", "factors must be nonzero".into()));
        }
        check_finite(self, None, "translate", &self.translate)?;
        check_finite(self, None, "angle", &[self.angle_deg])?;
        if let Some(y) = self.y_duplicate {
            check_finite(self, None, "YDUPLICATE", &[y])?;
        }
        self.validate_sections()
    }

    fn validate_sections(&self) -> Result<()> {
        let last = self.sections.len() - 1;
        for (k, s) in self.sections.iter().enumerate() {
            check_finite(self, Some(k), "leading edge", &s.leading_edge)?;
            check_finite(self, Some(k), "incidence", &[s.incidence_deg])?;
            if !(s.chord.is_finite() && s.chord > 0.0) {
                return Err(self.err(
                    Some(k),
                    "chord",
                    format!("must be positive, is {}", s.chord),
                ));
            }
            if k < last {
                match (self.spanwise, s.spanwise) {
                    (None, None) => {
                        return Err(self.err(
                            Some(k),
                            "Nspan/Sspace",
                            "missing: give strips on the surface or on every section but the last"
                                .into(),
                        ));
                    }
                    (None, Some(sp)) => {
                        if let Some(r) = sp.problem() {
                            return Err(self.err(Some(k), "Nspan/Sspace", r));
                        }
                    }
                    _ => {}
                }
                let next = &self.sections[k + 1];
                let dy = next.leading_edge[1] - s.leading_edge[1];
                let dz = next.leading_edge[2] - s.leading_edge[2];
                if (dy * self.scale[1]).hypot(dz * self.scale[2]) <= 0.0 {
                    return Err(self.err(
                        Some(k + 1),
                        "leading edge",
                        "coincides with the previous section in the y-z plane (zero span)".into(),
                    ));
                }
            }
        }
        Ok(())
    }
}

fn check_finite(s: &Surface, section: Option<usize>, field: &'static str, v: &[f64]) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(s.err(section, field, format!("must be finite, is {v:?}")))
    }
}

impl Configuration {
    /// A configuration with `reference` quantities, Mach 0, no surfaces yet.
    pub fn new(title: impl Into<String>, reference: Reference) -> Self {
        Configuration {
            title: title.into(),
            mach: 0.0,
            reference,
            symmetry: Symmetry::default(),
            cdp: 0.0,
            surfaces: Vec::new(),
        }
    }

    /// Adds a surface.
    pub fn surface(mut self, surface: Surface) -> Self {
        self.surfaces.push(surface);
        self
    }

    /// Puts a solid wall (the ground) at z = `z`: the lattice gains a mirror image that
    /// cancels the normal velocity there (AVL's iZsym = 1).
    pub fn ground_at(mut self, z: f64) -> Self {
        self.symmetry.izsym = 1;
        self.symmetry.zsym = z;
        self
    }

    /// Sets the Mach number.
    pub fn mach(mut self, mach: f64) -> Self {
        self.mach = mach;
        self
    }

    fn err(&self, field: &'static str, reason: String) -> AeroError {
        AeroError::Configuration {
            config: self.title.clone(),
            field,
            reason,
        }
    }

    /// Checks the configuration and every surface.
    pub fn validate(&self) -> Result<()> {
        if let Err((field, reason)) = self.reference.check() {
            return Err(self.err(field, reason));
        }
        if !(self.mach.is_finite() && (0.0..1.0).contains(&self.mach)) {
            return Err(self.err(
                "Mach",
                format!(
                    "must be in 0 ... < 1 (subsonic Prandtl-Glauert), is {}",
                    self.mach
                ),
            ));
        }
        if self.symmetry.iysym != 0 {
            return Err(self.err(
                "iYsym",
                "the y image is not supported: model both halves (YDUPLICATE) instead".into(),
            ));
        }
        if !(-1..=1).contains(&self.symmetry.izsym) || !self.symmetry.zsym.is_finite() {
            return Err(self.err(
                "iZsym/Zsym",
                format!(
                    "iZsym must be -1, 0 or 1 and Zsym finite, are {} and {}",
                    self.symmetry.izsym, self.symmetry.zsym
                ),
            ));
        }
        if self.surfaces.is_empty() {
            return Err(self.err("surfaces", "none given".into()));
        }
        self.surfaces.iter().try_for_each(Surface::validate)
    }
}
