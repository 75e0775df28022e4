//! The `build.rs` helper: generate a model's module into `OUT_DIR`.
//!
//! ```no_run
//! // build.rs of a controller crate, in `fn main()`:
//! println!("cargo:rerun-if-changed=build.rs");
//! eom_codegen::build::Generate::model("bicycle")
//!     .f32()
//!     .write_to_out_dir("bicycle.rs")
//!     .expect("code generation");
//! // src/lib.rs:
//! // include!(concat!(env!("OUT_DIR"), "/bicycle.rs"));   // `pub mod bicycle { … }`
//! ```
//!
//! The file is rewritten only when its content changes, so an unchanged model does not make
//! cargo recompile the crate that includes it. Built-in models read no file; a build script
//! should print `cargo:rerun-if-changed=build.rs` so that cargo does not rerun it on every
//! change of the package (the build-dependency on this crate reruns it when the generator or
//! the model library changes).

use crate::{CodegenError, EmitOptions, Emitted, Functions, emit_model};
use eom_sym::Expr;
use eom_sym::model::Model;
use std::path::{Path, PathBuf};

enum Source {
    Named(String, Vec<(String, f64)>),
    Model(Box<Model<Expr>>),
}

/// Builder for one generated file.
pub struct Generate {
    source: Source,
    opts: EmitOptions,
}

impl Generate {
    /// A built-in model by name (`"bicycle"`, `"chain50"`, …; see `models::catalogue`).
    pub fn model(name: &str) -> Self {
        Generate {
            source: Source::Named(name.to_string(), Vec::new()),
            opts: EmitOptions::default(),
        }
    }
    /// A model built by the caller.
    pub fn from_model(model: Model<Expr>) -> Self {
        Generate {
            source: Source::Model(Box::new(model)),
            opts: EmitOptions::default(),
        }
    }
    /// Nominal value of a parameter of a built-in model (where the pivots are chosen and the
    /// default of `Params::NOMINAL`); ignored for [`Generate::from_model`].
    pub fn nominal(mut self, name: &str, value: f64) -> Self {
        if let Source::Named(_, o) = &mut self.source {
            o.push((name.to_string(), value));
        }
        self
    }
    /// `f32` code.
    pub fn f32(mut self) -> Self {
        self.opts = self.opts.f32();
        self
    }
    /// `f64` code (the default).
    pub fn f64(mut self) -> Self {
        self.opts = self.opts.f64();
        self
    }
    /// Elementary functions from `std` (the consumer then needs `std`).
    pub fn std_math(mut self) -> Self {
        self.opts = self.opts.std_math();
        self
    }
    /// Name of the generated module.
    pub fn module(mut self, name: &str) -> Self {
        self.opts = self.opts.module(name);
        self
    }
    /// Run the bounded egg simplification first (used when fewer operations and estimated
    /// faster).
    pub fn simplify(mut self, on: bool) -> Self {
        self.opts = self.opts.simplify(on);
        self
    }
    /// Simplify, and use the result whenever it has fewer operations.
    pub fn simplify_always(mut self, on: bool) -> Self {
        self.opts = self.opts.simplify_always(on);
        self
    }
    /// Most temporaries per generated function.
    pub fn max_temporaries(mut self, n: usize) -> Self {
        self.opts = self.opts.max_temporaries(n);
        self
    }
    /// Which functions to emit.
    pub fn functions(mut self, f: Functions) -> Self {
        self.opts = self.opts.functions(f);
        self
    }
    /// Fix a parameter at a value (partial evaluation).
    pub fn fix(mut self, name: &str, value: f64) -> Self {
        self.opts = self.opts.fix(name, value);
        self
    }
    /// All options at once.
    pub fn options(mut self, opts: EmitOptions) -> Self {
        self.opts = opts;
        self
    }

    /// Generate the source.
    pub fn emit(&self) -> Result<Emitted, CodegenError> {
        match &self.source {
            Source::Named(name, nominal) => {
                let o: Vec<(&str, f64)> = nominal.iter().map(|(k, v)| (k.as_str(), *v)).collect();
                let m = models::build(name, &o)?;
                emit_model(&m, &self.opts)
            }
            Source::Model(m) => emit_model(m, &self.opts),
        }
    }

    /// Generate and write to `path` (only if the content changed). Returns what was generated.
    pub fn write_to(&self, path: impl AsRef<Path>) -> Result<Emitted, CodegenError> {
        let e = self.emit()?;
        write_if_changed(path.as_ref(), &e.source)?;
        Ok(e)
    }

    /// Generate and write to `$OUT_DIR/file` (inside a build script). Returns the path.
    pub fn write_to_out_dir(&self, file: &str) -> Result<PathBuf, CodegenError> {
        let dir = std::env::var_os("OUT_DIR").ok_or(CodegenError::MissingEnv("OUT_DIR"))?;
        let path = PathBuf::from(dir).join(file);
        self.write_to(&path)?;
        Ok(path)
    }
}

/// Write `text` to `path` unless it already holds exactly that.
pub fn write_if_changed(path: &Path, text: &str) -> Result<(), CodegenError> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| CodegenError::Io {
            path: dir.display().to_string(),
            source: e,
        })?;
    }
    std::fs::write(path, text).map_err(|e| CodegenError::Io {
        path: path.display().to_string(),
        source: e,
    })
}
