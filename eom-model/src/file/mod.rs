//! Model files: a model described in TOML, with parameters and expressions, loaded strictly.
//!
//! The format is documented in `docs/model-files.md` of the repository. In short: a
//! `[model]` table (name, description, gravity), a `[parameters]` table (a number, an
//! expression string for a derived parameter, or a table with `value`, `unit`, `description`
//! and `range`), and one array of tables per item kind (`[[body]]`, `[[spring]]`,
//! `[[flex_point]]`, `[[wing]]`, …) whose fields are those of the Rust builders, every number a number or
//! an expression string. An item with `mirror = "y"` also gets its mirror image, with `left`
//! and `right` exchanged in its name and in the names of the bodies it connects.
//!
//! Loading is strict: an unknown key, a value of the wrong type, an expression that does not
//! parse or names an unknown parameter, a duplicated name, a body that does not exist, a cycle
//! among derived parameters — each is a [`FileError`] with the file, line and column, the item
//! and field, and the valid alternatives where there is a short list; an error of the model's
//! checks ([`ModelError`]) is positioned at the table of the body or item at fault.
//!
//! ```
//! let text = r#"
//! [model]
//! name = "mass on a spring"
//! [parameters]
//! m = { value = 2, unit = "kg", range = "> 0" }
//! k = { value = 8, unit = "N/m", range = "> 0" }
//! [[body]]
//! name = "block"
//! mass = "m"
//! [[rigid_point]]
//! name = "slider"
//! between = ["block", "ground"]
//! forces = 2
//! moments = 3
//! axis = [0, 0, 1]
//! [[flex_point]]
//! name = "spring"
//! between = ["block", "ground"]
//! forces = 1
//! axis = [0, 0, 1]
//! stiffness = ["k", 0]
//! "#;
//! let model = eom_model::file::from_str(text, "spring.toml", &[]).unwrap();
//! let lin = eom_model::Linearizer::new(&model).run().unwrap();
//! assert_eq!(lin.state_space.a[(1, 0)], -4.0); // −k/m
//! ```

mod error;
mod export;
mod items;
mod mirror;
mod params;
mod source;
mod wing;

pub use error::FileError;
pub use export::{to_toml, toml_string};
pub use params::{ParamRange, ParamSpec};
pub use source::FilePosition;

#[cfg(doc)]
use crate::error::ModelError;
use crate::items::{BODY, KINDS, Load};
use crate::model::Model;
use crate::warning::Warning;
use eom_sym::Expr;
use source::{Ctx, Table};
use std::path::Path;

/// A loaded model file: the model and the parameters' declared ranges (for checking values
/// given later, e.g. on the command line).
#[derive(Clone, Debug)]
pub struct LoadedModel {
    /// The model, with the nominal values of the file (or the overrides).
    pub model: Model,
    /// The model's description (`[model] description`).
    pub description: String,
    /// The independent parameters in declaration order, with units, descriptions and ranges.
    pub params: Vec<ParamSpec>,
    /// The derived parameters: name and defining expression text.
    pub derived: Vec<(String, String)>,
    /// Warnings of the loading (e.g. the entries an AVL stability-axis file cannot give,
    /// taken as zero).
    pub warnings: Vec<Warning>,
}

/// Reads and loads the model file at `path`; `overrides` replace nominal values by name.
pub fn load(path: &Path, overrides: &[(&str, f64)]) -> Result<LoadedModel, FileError> {
    let text =
        eom_text::read_limited(path, eom_text::MAX_FILE_BYTES).map_err(|e| FileError::Invalid {
            position: FilePosition::whole(&path.display().to_string()),
            context: String::new(),
            problem: format!("cannot be read: {e}"),
        })?;
    load_in(&text, &path.display().to_string(), overrides, path.parent())
}

/// Loads a model file given as text (`origin` names it in messages).
pub fn from_str(text: &str, origin: &str, overrides: &[(&str, f64)]) -> Result<Model, FileError> {
    Ok(load_str(text, origin, overrides)?.model)
}

/// Loads a model file given as text, with its parameter declarations (AVL files it names are
/// relative to the current directory).
pub fn load_str(
    text: &str,
    origin: &str,
    overrides: &[(&str, f64)],
) -> Result<LoadedModel, FileError> {
    load_in(text, origin, overrides, None)
}

/// Loads a model file given as text, its relative paths taken from `base`.
fn load_in(
    text: &str,
    origin: &str,
    overrides: &[(&str, f64)],
    base: Option<&Path>,
) -> Result<LoadedModel, FileError> {
    let ctx = Ctx::new(text, origin, base);
    let doc = ctx.parse()?;
    let root = Table::new(&ctx, &doc, "the file");
    let mut keys = vec!["model", "parameters", BODY.key];
    keys.extend(KINDS.iter().map(|k| k.key));
    root.only(&keys)?;
    let (name, description, gravity, unsteady) = model_section(&root)?;
    let mut model = Model::new(&name);
    let decl = params::declare(&root, &mut model, overrides)?;
    let scope = decl.scope(&mut model)?;
    let mut cx = items::Builder::new(&ctx, &scope, &decl, &mut model);
    cx.unsteady = unsteady;
    cx.all(&root)?;
    let mut spans = std::mem::take(&mut cx.spans);
    let warnings = std::mem::take(&mut cx.warnings);
    if let Some(g) = gravity {
        let g = params::vector(&ctx, &scope, &decl, g, "[model] gravity")?;
        add_weights(&mut model, g, &mut spans);
    }
    model.validate_at().map_err(|located| {
        let (place, error) = *located;
        FileError::Model {
            position: match spans.of(place) {
                Some(span) => ctx.position(span.start),
                None => FilePosition::whole(ctx.origin),
            },
            error: Box::new(error),
        }
    })?;
    Ok(LoadedModel {
        model,
        description,
        params: decl.specs,
        derived: decl.derived_text,
        warnings,
    })
}

/// `[model]`: name, description, gravity, and the default `unsteady` of wings and strips.
type ModelSection<'a> = (
    String,
    String,
    Option<&'a source::Value<'a>>,
    Option<crate::items::Unsteady>,
);

fn model_section<'a>(root: &Table<'a>) -> Result<ModelSection<'a>, FileError> {
    let Some(m) = root.table("model")? else {
        return Ok(("model".into(), String::new(), None, None));
    };
    m.only(&["name", "description", "gravity", "unsteady"])?;
    let name = m.string("name")?.unwrap_or_else(|| "model".into());
    let description = m.string("description")?.unwrap_or_default();
    let unsteady = items::unsteady(&m)?;
    Ok((name, description, m.get("gravity"), unsteady))
}

/// A weight (dead load `m·g` at the mass centre) on every body with mass (defined by no table
/// of the file).
fn add_weights(model: &mut Model, g: [Expr; 3], spans: &mut items::Spans) {
    let bodies: Vec<_> = model.bodies.clone();
    for b in bodies {
        if b.mass.is_zero() {
            continue;
        }
        let f = [b.mass * g[0], b.mass * g[1], b.mass * g[2]];
        let place = model.add_placed(
            Load::new(&format!("{} weight", b.name), &b.name)
                .at(b.location)
                .force(f),
        );
        spans.record(place, None);
    }
}
