//! The `build.rs` helper: generate a model's module into `OUT_DIR`.
//!
//! ```no_run
//! // build.rs of a controller crate, in `fn main()`:
//! println!("cargo:rerun-if-changed=build.rs");
//! let model = models::build("bicycle", &[]).expect("model");
//! eom_codegen::build::Generate::new(model)
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
//! change of the package (the build-dependencies on this crate and on the model's crate rerun it
//! when the generator or the model changes).

use crate::{CodegenError, EmitOptions, Emitted, Functions, emit_model};
use eom_model::Model;
use eom_sym::Expr;
use std::path::{Path, PathBuf};

/// Builder for one generated file.
pub struct Generate {
    model: Box<Model<Expr>>,
    opts: EmitOptions,
}

impl Generate {
    /// Generate code for `model` (built by the caller, e.g. with `models::build`).
    pub fn new(model: Model<Expr>) -> Self {
        Generate {
            model: Box::new(model),
            opts: EmitOptions::default(),
        }
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
    /// Also emit the stability verdict without eigenvalues (`EmitOptions::stability`).
    pub fn stability(mut self, on: bool) -> Self {
        self.opts = self.opts.stability(on);
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
        emit_model(&self.model, &self.opts)
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
