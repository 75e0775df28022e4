//! `[[wing]]`: a wing's fields through the builder, its derivatives from a table of AVL names
//! or from an AVL file (`.sb`, `.st` read; `.avl` solved by eom-aero's vortex lattice),
//! relative to the model file.

use super::error::FileError;
use super::items::Builder;
use super::mirror::Mirror;
use super::params::value_expr;
use super::source::Table;
use crate::items::{WING_ACCELERATION_DERIVATIVES, WING_DERIVATIVES, Wing, wing_derivative_index};
use crate::warning::{ItemRef, Warning};
use eom_aero::{AvlOutput, Derivatives, SolverOptions};
use eom_sym::Expr;
use std::path::Path;

/// Signs of the rows and columns of a wing's derivatives under a mirror image: the wing's own
/// y changes sign (its mirrored axes are forward', down', and right' = down' × forward').
const MIRROR_SIGNS: [f64; 6] = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];

/// A hint for a stability-axis name of AVL's ST file: its β derivatives are the body-axis v
/// derivatives (β = v/V), its lift derivatives the negated z-force ones at α = 0.
fn stability_axis_hint(key: &str) -> Option<String> {
    let as_v = key.strip_suffix('b').map(|k| format!("{k}v"));
    if let Some(v) = as_v.filter(|v| wing_derivative_index(v).is_some()) {
        return Some(format!(
            " (did you mean `{v}`? AVL's β derivatives are the v derivatives, per unit v/V)"
        ));
    }
    let lift = key.strip_prefix("CL").map(|c| c.replace('a', "w"));
    if let Some(z) = lift
        .map(|c| format!("CZ{c}"))
        .filter(|z| wing_derivative_index(z).is_some())
    {
        return Some(format!(
            " (lift derivatives are body-axis z-force ones: at α = 0, {z} = −{key})"
        ));
    }
    None
}

impl Builder<'_> {
    /// Before a wing's declared fields: the reference quantities and derivatives of its AVL
    /// file (`avl`, which `area`, `chord` and `span` may not repeat), and the model's default
    /// `unsteady`.
    pub(super) fn wing_before(
        &mut self,
        t: &Table<'_>,
        name: &str,
        w: &mut Wing<Expr>,
    ) -> Result<(), FileError> {
        if let Some(d) = self.avl_file(t, name)? {
            for key in ["area", "chord", "span"] {
                if let Some(v) = t.get(key) {
                    return Err(t.field_error(
                        key,
                        &v.span(),
                        "comes from the AVL file (`avl`); give one or the other",
                    ));
                }
            }
            *w = Wing::from_derivatives(name, &d);
        }
        if let Some(u) = self.unsteady {
            w.unsteady = u;
        }
        Ok(())
    }

    /// After a wing's declared fields: its `derivatives` table, and in a mirrored copy the
    /// signs of the derivatives that change with the wing's y.
    pub(super) fn wing_after(
        &self,
        t: &Table<'_>,
        m: Option<Mirror>,
        w: &mut Wing<Expr>,
    ) -> Result<(), FileError> {
        self.derivative_table(t, w)?;
        if m.is_some() {
            for (i, d) in w.acceleration.iter_mut().enumerate() {
                if MIRROR_SIGNS[i] * MIRROR_SIGNS[2] < 0.0 && !d.is_zero() {
                    *d = -*d;
                }
            }
            for (i, row) in w.derivatives.iter_mut().enumerate() {
                for (j, d) in row.iter_mut().enumerate() {
                    if MIRROR_SIGNS[i] * MIRROR_SIGNS[j] < 0.0 && !d.is_zero() {
                        *d = -*d;
                    }
                }
            }
        }
        Ok(())
    }

    /// `derivatives = { CYv = …, … }`: each by its AVL name (replacing the AVL file's).
    fn derivative_table(&self, t: &Table<'_>, w: &mut Wing<Expr>) -> Result<(), FileError> {
        let Some(v) = t.get("derivatives") else {
            return Ok(());
        };
        let d = Table::sub(self.ctx, v, t.field_context("derivatives"))?;
        for (key, span, value) in d.entries() {
            if let Some(i) = WING_ACCELERATION_DERIVATIVES.iter().position(|n| *n == key) {
                let x = value_expr(self.ctx, self.decl, value, &t.field_context("derivatives"))?;
                w.acceleration[i] = x;
                continue;
            }
            let Some((i, j)) = wing_derivative_index(key) else {
                let names: Vec<&str> = WING_DERIVATIVES.iter().flatten().copied().collect();
                let hint =
                    stability_axis_hint(key).unwrap_or_else(|| eom_text::did_you_mean(key, &names));
                return Err(t.field_error(
                    "derivatives",
                    &span,
                    format!(
                        "unknown derivative `{key}`{hint}; the derivatives are (AVL's body-axis \
                         names, case matters): {}",
                        names.join(" ")
                    ),
                ));
            };
            let x = value_expr(self.ctx, self.decl, value, &t.field_context("derivatives"))?;
            w.derivatives[i][j] = x;
        }
        Ok(())
    }

    /// `avl = "file"`: the derivatives (and S, c, b) of an AVL `.sb` or `.st` file, or of a
    /// `.avl` geometry by the vortex lattice at α = 0; the path is relative to the model file.
    fn avl_file(&mut self, t: &Table<'_>, name: &str) -> Result<Option<Derivatives>, FileError> {
        let Some(path) = t.string("avl")? else {
            return Ok(None);
        };
        let span = t.get("avl").map(|v| v.span()).unwrap_or(t.span.clone());
        let full = match self.ctx.base {
            Some(base) if Path::new(&path).is_relative() => base.join(&path),
            _ => Path::new(&path).to_path_buf(),
        };
        let ext = full
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_lowercase);
        let fail = |e: eom_aero::AeroError| t.field_error("avl", &span, e.to_string());
        match ext.as_deref() {
            Some("sb") | Some("st") => {
                let out = AvlOutput::read(&full).map_err(fail)?;
                let body = out.derivatives().map_err(fail)?;
                self.warnings
                    .extend(body.warnings.iter().map(|w| Warning::AvlFile {
                        item: ItemRef::new("wing", name),
                        path: full.display().to_string(),
                        warning: w.clone(),
                    }));
                Ok(Some(body.derivatives))
            }
            Some("avl") => {
                let config = eom_aero::read_avl(&full).map_err(fail)?;
                let sol = eom_aero::solve(&config, &SolverOptions::default()).map_err(fail)?;
                Ok(Some(sol.derivatives))
            }
            _ => Err(t.field_error(
                "avl",
                &span,
                format!(
                    "`{path}`: expected an AVL output file (.sb body axes, .st stability axes) \
                     or an AVL geometry file (.avl)"
                ),
            )),
        }
    }
}
