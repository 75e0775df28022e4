//! [`EmitOptions`]: what to generate and how.

/// The floating-point type of the generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Precision {
    /// `f64` throughout (the default): agrees with [`SymbolicStateSpace::evaluate`](eom_model::SymbolicStateSpace::evaluate)
    /// to rounding.
    #[default]
    F64,
    /// `f32` throughout, for targets without double-precision hardware. Constants are rounded
    /// to `f32`; the validity checks use the same tolerances (so they can only be stricter).
    F32,
}

impl Precision {
    /// The Rust type name.
    pub fn type_name(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }
}

/// Where elementary functions (`sqrt`, `sin`, `pow`, …) come from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum MathLib {
    /// The `libm` crate (the default): works under `#![no_std]`, where `f64::sqrt`, `sin`,
    /// `powi` do not exist. The consumer needs `libm` as a dependency when the model has such
    /// functions.
    #[default]
    Libm,
    /// The inherent methods of `std` (`x.sin()`): needs `std`, and uses the platform's math
    /// library, which is often faster.
    Std,
}

/// Which functions to emit (each evaluates its matrices, checks the validity region, and
/// checks that every computed entry is finite).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Functions {
    /// `eval_abcd`: A, B, C, D.
    pub abcd: bool,
    /// `eval_ab`: A and B only (what a controller needs every tick).
    pub ab: bool,
    /// `eval_cd`: C and D only.
    pub cd: bool,
    /// `eval_phys`: the map from the state to the physical coordinates of the bodies.
    pub phys: bool,
}

impl Default for Functions {
    fn default() -> Self {
        Functions {
            abcd: true,
            ab: true,
            cd: true,
            phys: true,
        }
    }
}

/// Default bound on the temporaries of one generated function (rustc/LLVM crash or crawl on
/// straight-line functions of several thousand `let`s with debug info).
pub const DEFAULT_CHUNK: usize = 1500;

/// Options of [`emit`](crate::emit), builder style:
/// `EmitOptions::default().f32().module("bike").simplify(true)`.
#[derive(Clone, Debug, PartialEq)]
pub struct EmitOptions {
    /// Floating-point type.
    pub precision: Precision,
    /// Source of elementary functions.
    pub math: MathLib,
    /// Name of the generated module (`None`: from the model name).
    pub module: Option<String>,
    /// Model name used in the documentation (`None`: from the model, or `model`).
    pub model_name: Option<String>,
    /// Run the bounded egg simplification ([`eom_sym::simplify::Simplifier`]) over all
    /// entries and checks before lowering; its result is used only when it has fewer
    /// operations and is estimated faster (see [`emit_with_stats`](crate::emit_with_stats)).
    pub simplify: bool,
    /// With `simplify`: use the simplified expressions whenever they have fewer operations,
    /// even when estimated slower. Factoring can also remove a cancellation (the
    /// shimmy's `k·lx − k·(lx − l)` becomes `k·l`), so this trades speed for accuracy.
    pub simplify_always: bool,
    /// Most temporaries per generated function; larger evaluations are split into chunks that
    /// pass values through the caller's work buffer.
    pub max_temporaries: usize,
    /// Which functions to emit.
    pub functions: Functions,
    /// Parameters to fix at a value before lowering (partial evaluation): they disappear from
    /// the generated interface, and everything that depends only on them is folded.
    pub fixed: Vec<(String, f64)>,
    /// Also emit the characteristic polynomial, the Liénard–Chipart conditions with their
    /// rounding-error bounds and the verdict `stability` (`f64` only; models of up to
    /// [`MAX_STABILITY_STATES`](crate::MAX_STABILITY_STATES) states).
    pub stability: bool,
    /// Also emit `eval_discrete` (needs `eval_ab`): the zero-order-hold `Ad = e^{A h}`,
    /// `Bd = ∫₀ʰ e^{A t} dt B` at a sample time h, by scaling and squaring with a Padé
    /// approximant, without allocation.
    pub discrete: bool,
    /// Lines added to the module's documentation (what was done to the model before).
    pub notes: Vec<String>,
    /// Rust items added to the module as they are (constants describing the model).
    pub extra_items: Vec<String>,
}

impl Default for EmitOptions {
    fn default() -> Self {
        EmitOptions {
            precision: Precision::F64,
            math: MathLib::Libm,
            module: None,
            model_name: None,
            simplify: false,
            simplify_always: false,
            max_temporaries: DEFAULT_CHUNK,
            functions: Functions::default(),
            fixed: Vec::new(),
            stability: false,
            discrete: false,
            notes: Vec::new(),
            extra_items: Vec::new(),
        }
    }
}

impl EmitOptions {
    /// `f32` code.
    pub fn f32(mut self) -> Self {
        self.precision = Precision::F32;
        self
    }
    /// `f64` code (the default).
    pub fn f64(mut self) -> Self {
        self.precision = Precision::F64;
        self
    }
    /// Elementary functions from `std` instead of `libm` (the output then needs `std`).
    pub fn std_math(mut self) -> Self {
        self.math = MathLib::Std;
        self
    }
    /// Name of the generated module.
    pub fn module(mut self, name: &str) -> Self {
        self.module = Some(name.to_string());
        self
    }
    /// Model name for the documentation.
    pub fn model_name(mut self, name: &str) -> Self {
        self.model_name = Some(name.to_string());
        self
    }
    /// Run the bounded egg simplification first (used when fewer operations and estimated
    /// faster).
    pub fn simplify(mut self, on: bool) -> Self {
        self.simplify = on;
        self
    }
    /// Simplify, and use the result whenever it has fewer operations (see
    /// [`EmitOptions::simplify_always`]).
    pub fn simplify_always(mut self, on: bool) -> Self {
        self.simplify_always = on;
        if on {
            self.simplify = true;
        }
        self
    }
    /// Most temporaries per generated function (at least 1).
    pub fn max_temporaries(mut self, n: usize) -> Self {
        self.max_temporaries = n;
        self
    }
    /// Which functions to emit.
    pub fn functions(mut self, f: Functions) -> Self {
        self.functions = f;
        self
    }
    /// Emit the stability verdict without eigenvalues (see [`EmitOptions::stability`]).
    pub fn stability(mut self, on: bool) -> Self {
        self.stability = on;
        self
    }
    /// Also emit `eval_discrete`, the zero-order-hold discretisation at a sample time.
    pub fn discrete(mut self, on: bool) -> Self {
        self.discrete = on;
        self
    }
    /// Fix a parameter at a value (partial evaluation); may be called repeatedly.
    pub fn fix(mut self, name: &str, value: f64) -> Self {
        self.fixed.push((name.to_string(), value));
        self
    }
}
