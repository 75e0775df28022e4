//! `NativeModel`: a model by name or file, linearized at a point or evaluated from its
//! compiled tape at many points; and `modes` of a state matrix.

use crate::errors::{eom_error, model_error};
use crate::points::{self, Compiled};
use crate::source::Source;
use eom_model::file::ParamRange;
use eom_model::{Linearizer, Method};
use eom_num::StateSpace;
use eom_num::modes::{ModeKind, ModeOptions, Modes, Stability};
use nalgebra::DMatrix;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyReadonlyArray2, PyReadwriteArray1};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::sync::{Arc, Mutex, OnceLock};

/// A model: where it comes from, its parameters, and (built on first use) its compiled
/// symbolic state space.
#[pyclass(module = "eom._eom", frozen)]
pub struct NativeModel {
    source: Source,
    name: String,
    param_names: Vec<String>,
    defaults: Vec<f64>,
    /// The parameters' allowed values (model order), for the symbolic method's quick check.
    ranges: Option<Vec<ParamRange>>,
    compiled: OnceLock<Result<Arc<Compiled>, String>>,
}

impl NativeModel {
    fn new(source: Source) -> PyResult<Self> {
        let model = source.build(&[])?;
        let param_names = model.scope.names();
        Ok(NativeModel {
            name: model.name.clone(),
            ranges: source.ranges(&param_names),
            param_names,
            defaults: model.scope.nominal_values(),
            source,
            compiled: OnceLock::new(),
        })
    }

    /// The compiled symbolic state space, reduced once (pivots chosen at the defaults).
    pub fn compiled(&self) -> PyResult<Arc<Compiled>> {
        self.compiled
            .get_or_init(|| compiled_of(&self.source))
            .clone()
            .map_err(eom_error)
    }

    /// The linearization at the point: the cached reduction for the symbolic method (pivots
    /// chosen at the defaults, as `eom analyze --method symbolic` reduces at the defaults and
    /// evaluates at the point), else the method at the point.
    fn linearization(
        &self,
        method: Method,
        values: &[(String, f64)],
    ) -> PyResult<eom_model::Linearization> {
        if method == Method::Symbolic
            && let Some(v) = self.point_values(values)
        {
            return self.compiled()?.linearize(&v).map_err(model_error);
        }
        let ov = self.overrides(values);
        let at_point = self.source.build(&ov)?;
        if method == Method::Symbolic {
            let c = self.compiled()?;
            let v = at_point
                .scope
                .values_with(&ov)
                .map_err(|e| model_error(e.into()))?;
            return c.linearize(&v).map_err(model_error);
        }
        Linearizer::new(&at_point)
            .method(method)
            .run()
            .map_err(model_error)
    }

    /// All parameter values (model order) of the point: the defaults with `values` by name,
    /// when every name is a parameter and every value in its declared range; `None` otherwise
    /// (building the model at the point then says what is wrong, as it always did). What the
    /// symbolic method needs without building the model at the point: the compiled reduction
    /// is evaluated there, as `evaluate` does for many points.
    fn point_values(&self, values: &[(String, f64)]) -> Option<Vec<f64>> {
        let ranges = self.ranges.as_ref()?;
        let mut v = self.defaults.clone();
        for (name, x) in values {
            let k = self.param_names.iter().position(|n| n == name)?;
            if !ranges[k].contains(*x) {
                return None;
            }
            v[k] = *x;
        }
        Some(v)
    }

    /// Overrides by name, each checked against the parameter list.
    fn overrides<'a>(&self, values: &'a [(String, f64)]) -> Vec<(&'a str, f64)> {
        values.iter().map(|(k, v)| (k.as_str(), *v)).collect()
    }
}

/// The compiled reduction of `source`, shared by every model of this process that is the
/// same model (its model file, as `to_toml` writes it, is the key: the text of a file and the
/// files it reads, such as AVL geometries, are in it): a model unpickled afresh on a Dask
/// worker for every sweep reuses the reduction the worker compiled for the first (a handful
/// kept, the oldest dropped).
fn compiled_of(source: &Source) -> Result<Arc<Compiled>, String> {
    type Cache = Vec<(String, Arc<Compiled>)>;
    static CACHE: Mutex<Cache> = Mutex::new(Vec::new());
    const KEPT: usize = 8;
    let model = source.build(&[]).map_err(|e| e.to_string())?;
    let key = eom_model::file::to_toml(&model);
    let cached = |cache: &Cache| cache.iter().find(|(k, _)| *k == key).map(|e| e.1.clone());
    if let Some(c) = cached(&CACHE.lock().unwrap_or_else(|e| e.into_inner())) {
        return Ok(c);
    }
    // Compiled without the lock held (other models compile meanwhile); the same reduction
    // whoever finishes first.
    let c = Arc::new(Compiled::of(&model)?);
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(c) = cached(&cache) {
        return Ok(c);
    }
    if cache.len() == KEPT {
        cache.remove(0);
    }
    cache.push((key, c.clone()));
    Ok(c)
}

/// The parameter values of a dict name → number (the keyword arguments of `linearize`).
fn values_of(d: &Bound<'_, PyDict>) -> PyResult<Vec<(String, f64)>> {
    d.iter()
        .map(|(k, v)| Ok((k.extract::<String>()?, v.extract::<f64>()?)))
        .collect()
}

/// Appends the bytes of a matrix in row-major order (NumPy's default).
fn row_major_into(m: &DMatrix<f64>, out: &mut Vec<u8>) {
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            out.extend_from_slice(&m[(i, j)].to_ne_bytes());
        }
    }
}

fn method_of(name: &str) -> PyResult<Method> {
    match name {
        "numeric" => Ok(Method::Numeric),
        "robust" => Ok(Method::Robust),
        "symbolic" => Ok(Method::Symbolic),
        m => Err(eom_error(format!(
            "unknown method `{m}`; methods are: numeric, robust, symbolic"
        ))),
    }
}

#[pymethods]
impl NativeModel {
    /// A built-in model by name or a model file by path.
    #[staticmethod]
    fn load(name_or_path: &str) -> PyResult<Self> {
        NativeModel::new(Source::resolve(name_or_path)?)
    }

    /// The model back from the state of `__reduce__`.
    #[staticmethod]
    fn _from_state(kind: &str, name: String, text: String) -> PyResult<Self> {
        NativeModel::new(Source::from_state(kind, name, text)?)
    }

    fn __reduce__(slf: &Bound<'_, Self>) -> PyResult<(Py<PyAny>, (String, String, String))> {
        let ctor = slf.get_type().getattr("_from_state")?.unbind();
        Ok((ctor, slf.get().source.state()))
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// Parameter names in the model's order.
    #[getter]
    fn parameter_names(&self) -> Vec<String> {
        self.param_names.clone()
    }

    /// Default values in the order of `parameter_names`.
    #[getter]
    fn defaults(&self) -> Vec<f64> {
        self.defaults.clone()
    }

    /// Where the model comes from: `("builtin", name, "")` or `("file", path, text)`.
    #[getter]
    fn source(&self) -> (String, String, String) {
        self.source.state()
    }

    /// Warnings of loading the model file (none for a built-in).
    #[getter]
    fn load_warnings(&self) -> Vec<crate::source::WarningRow> {
        self.source.load_warnings()
    }

    /// The model as a model file (with the values given).
    fn to_toml(&self, py: Python<'_>, values: Vec<(String, f64)>) -> PyResult<String> {
        let ov = self.overrides(&values);
        py.detach(|| {
            let m = self.source.build(&ov)?;
            Ok(eom_model::file::to_toml(&m))
        })
    }

    /// Linearizes at the point (see [`NativeModel::linearization`]): the result stays in
    /// Rust until Python asks for a part of it.
    fn linearize(
        &self,
        py: Python<'_>,
        method: &str,
        values: &Bound<'_, PyDict>,
    ) -> PyResult<NativeLinear> {
        let m = method_of(method)?;
        let values = values_of(values)?;
        let lin = py.detach(|| self.linearization(m, &values))?;
        Ok(NativeLinear { lin })
    }

    /// The Rust-only time of `linearize` (no conversions to or from Python), in seconds per
    /// call over `repeat` calls: the baseline of the Python benchmark.
    fn _linearize_seconds(
        &self,
        py: Python<'_>,
        method: &str,
        values: Vec<(String, f64)>,
        repeat: usize,
    ) -> PyResult<f64> {
        let m = method_of(method)?;
        py.detach(|| {
            let t = std::time::Instant::now();
            for _ in 0..repeat.max(1) {
                std::hint::black_box(self.linearization(m, &values)?);
            }
            Ok(t.elapsed().as_secs_f64() / repeat.max(1) as f64)
        })
    }

    /// The static preloads at the point (as `eom analyze` reports them): `(statics, items)`
    /// with per item `(item, body, force, moment, tension, unique, computed)`.
    fn preloads(&self, py: Python<'_>, values: Vec<(String, f64)>) -> PyResult<PreloadsOut> {
        let ov = self.overrides(&values);
        py.detach(|| {
            let at_point = self.source.build(&ov)?;
            let numeric = at_point.nominal().map_err(model_error)?;
            let a = eom_model::assemble(&numeric)
                .map_err(|e| eom_error(format!("static preloads not computed: {e}")))?;
            let p = eom_model::preloads::Preloads::of(&numeric, &a);
            Ok((
                p.statics,
                p.items
                    .into_iter()
                    .map(|r| {
                        (
                            r.item, r.body, r.force, r.moment, r.tension, r.unique, r.computed,
                        )
                    })
                    .collect(),
            ))
        })
    }

    /// Shapes of A, B, C, D of the compiled model (compiling it on first use).
    fn shapes(&self, py: Python<'_>) -> PyResult<Vec<(usize, usize)>> {
        let c = py.detach(|| self.compiled())?;
        Ok(c.shapes().to_vec())
    }

    /// State, input and output names of the compiled model.
    fn signal_names(&self, py: Python<'_>) -> PyResult<(Vec<String>, Vec<String>, Vec<String>)> {
        let c = py.detach(|| self.compiled())?;
        let n = c.names();
        Ok((n.states.clone(), n.inputs.clone(), n.outputs.clone()))
    }

    /// Warnings of the symbolic reduction.
    fn compiled_warnings(&self, py: Python<'_>) -> PyResult<Vec<crate::source::WarningRow>> {
        let c = py.detach(|| self.compiled())?;
        Ok(crate::source::warning_rows(c.warnings()))
    }

    /// A, B, C, D (row-major, one after the other per point: one row per point) at the points
    /// (rows of `points`, all parameters in model order), on `threads` threads (all cores
    /// when None) without the GIL, written straight into a Rust buffer that becomes the NumPy
    /// array without a copy. A buffer NumPy allocates itself is asked to be backed by huge
    /// pages, and faulting those in (zeroing 2 MiB each, compacting memory) cost a third to a
    /// half more than the whole evaluation on the development machine (docs/python.md).
    #[pyo3(signature = (points, threads=None))]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let pts = points.as_slice()?;
        let n = self.param_names.len();
        let (out, len) = py.detach(|| -> PyResult<(Vec<f64>, usize)> {
            let c = self.compiled()?;
            let mut out = vec![0.0; pts.len() / n.max(1) * c.abcd_len()];
            points::with_threads(threads, || points::evaluate_into(&c, pts, n, &mut out))?;
            Ok((out, c.abcd_len()))
        })?;
        let count = out.len() / len.max(1);
        out.into_pyarray(py).reshape([count, len])
    }

    /// The largest real part (structural zeros excluded), the verdict (1 stable, -1
    /// unstable, 0 neither) and whether the robust path was used, per point, written straight
    /// into the arrays given, on `threads` threads (all cores when None) without the GIL.
    #[pyo3(signature = (points, max_real, verdict, fallback, threads=None))]
    fn stability_into(
        &self,
        py: Python<'_>,
        points: PyReadonlyArray2<'_, f64>,
        mut max_real: PyReadwriteArray1<'_, f64>,
        mut verdict: PyReadwriteArray1<'_, i8>,
        mut fallback: PyReadwriteArray1<'_, bool>,
        threads: Option<usize>,
    ) -> PyResult<()> {
        let pts = points.as_slice()?;
        let out = points::StabilityOut {
            max_real: max_real.as_slice_mut()?,
            verdict: verdict.as_slice_mut()?,
            fallback: fallback.as_slice_mut()?,
        };
        py.detach(|| {
            let c = self.compiled()?;
            points::with_threads(threads, || {
                points::stability_into(&c, &self.source, &self.param_names, pts, out)
            })
        })
    }

    /// The Rust-only time of `evaluate` (into a fresh buffer, no Python objects), in
    /// seconds: the baseline of the Python benchmark.
    #[pyo3(signature = (points, threads=None))]
    fn _evaluate_seconds(
        &self,
        py: Python<'_>,
        points: PyReadonlyArray2<'_, f64>,
        threads: Option<usize>,
    ) -> PyResult<f64> {
        let pts = points.as_slice()?;
        let n = self.param_names.len();
        py.detach(|| -> PyResult<f64> {
            let c = self.compiled()?;
            let t = std::time::Instant::now();
            let mut out = vec![0.0; pts.len() / n.max(1) * c.abcd_len()];
            points::with_threads(threads, || points::evaluate_into(&c, pts, n, &mut out))?;
            std::hint::black_box(&out);
            Ok(t.elapsed().as_secs_f64())
        })
    }

    /// The generated Rust module (`eom codegen`).
    #[pyo3(signature = (values, f32=false, no_std=false, simplify=false, stability=false, module=None))]
    #[allow(clippy::too_many_arguments)]
    fn codegen(
        &self,
        py: Python<'_>,
        values: Vec<(String, f64)>,
        f32: bool,
        no_std: bool,
        simplify: bool,
        stability: bool,
        module: Option<String>,
    ) -> PyResult<String> {
        let ov = self.overrides(&values);
        py.detach(|| {
            let m = self.source.build(&ov)?;
            let mut opts = eom_codegen::EmitOptions::default()
                .simplify(simplify)
                .stability(stability);
            if f32 {
                opts = opts.f32();
            }
            if !no_std {
                opts = opts.std_math();
            }
            if let Some(name) = &module {
                opts = opts.module(name);
            }
            eom_codegen::emit_model(&m, &opts)
                .map(|e| e.source)
                .map_err(eom_error)
        })
    }

    /// The closed forms (`eom symbolic`): see `crate::symbolic`.
    #[pyo3(signature = (keep=None, stability=true, transfer=true, solve_for=None, max_states=8))]
    fn symbolic<'py>(
        &self,
        py: Python<'py>,
        keep: Option<Vec<String>>,
        stability: bool,
        transfer: bool,
        solve_for: Option<String>,
        max_states: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let keep = keep.unwrap_or_else(|| self.param_names.clone());
        for k in keep.iter().chain(&solve_for) {
            if !self.param_names.contains(k) {
                return Err(eom_error(format!(
                    "model `{}` has no parameter `{k}`; its parameters are: {}",
                    self.name,
                    self.param_names.join(", ")
                )));
            }
        }
        if let Some(x) = solve_for.as_ref().filter(|x| !keep.contains(x)) {
            return Err(eom_error(format!(
                "solve_for: `{x}` is substituted by its default; keep it symbolic (keep=[…, \"{x}\"])"
            )));
        }
        let req = crate::symbolic::Request {
            keep,
            stability,
            transfer,
            solve_for,
            max_states,
        };
        let out =
            py.detach(|| crate::symbolic::closed_forms(&self.source, &self.param_names, &req))?;
        out.into_dict(py)
    }

    fn __repr__(&self) -> String {
        format!("<eom model `{}`>", self.name)
    }
}

/// The preloads as returned to Python: the statics and per item (item, body, force, moment,
/// tension, unique, computed).
type PreloadsOut = (
    &'static str,
    Vec<(String, String, [f64; 3], [f64; 3], Option<f64>, bool, bool)>,
);

/// A linearization held in Rust: Python converts the parts it reads (`LinearModel` asks
/// lazily), so that creating one costs little beyond the linearization itself.
#[pyclass(module = "eom._eom", frozen)]
pub struct NativeLinear {
    lin: eom_model::Linearization,
}

#[pymethods]
impl NativeLinear {
    /// A, B, C, D one after the other, each row-major, as one `bytes`, and their shapes.
    fn matrices<'py>(&self, py: Python<'py>) -> (Bound<'py, PyBytes>, [(usize, usize); 4]) {
        let ss = &self.lin.state_space;
        let mats = [&ss.a, &ss.b, &ss.c, &ss.d];
        let size: usize = mats.iter().map(|m| m.len()).sum();
        let mut out = Vec::with_capacity(size * 8);
        for m in mats {
            row_major_into(m, &mut out);
        }
        (PyBytes::new(py, &out), mats.map(|m| (m.nrows(), m.ncols())))
    }

    /// State, input and output names; input and output units.
    fn names(&self) -> NamesOut {
        let n = &self.lin.state_space.names;
        (
            n.states.clone(),
            n.inputs.clone(),
            n.outputs.clone(),
            n.input_units.clone(),
            n.output_units.clone(),
        )
    }

    /// The warnings of the reduction (or the robust path).
    #[getter]
    fn warnings(&self) -> Vec<crate::source::WarningRow> {
        crate::source::warning_rows(&self.lin.warnings)
    }

    /// The zero eigenvalues the model's structure proves, one description each.
    #[getter]
    fn structural_zeros(&self) -> Vec<String> {
        self.lin.structural_zeros.clone()
    }

    /// `numeric`, `robust` or `symbolic`.
    #[getter]
    fn method(&self) -> &'static str {
        match self.lin.method {
            Method::Numeric => "numeric",
            Method::Robust => "robust",
            Method::Symbolic => "symbolic",
        }
    }

    /// The modes of A (see [`modes`]), without a round trip of A through Python.
    fn modes(&self, py: Python<'_>) -> PyResult<Vec<ModeRow>> {
        let a = &self.lin.state_space.a;
        py.detach(|| modes_of(a.clone(), self.lin.structural_zeros.len()))
    }
}

/// State, input and output names; input and output units.
type NamesOut = (
    Vec<String>,
    Vec<String>,
    Vec<String>,
    Vec<String>,
    Vec<String>,
);

/// One mode as returned to Python: Re λ, Im λ, frequency (Hz), damping ratio, time
/// constant, kind, stability.
type ModeRow = (f64, f64, f64, Option<f64>, f64, &'static str, &'static str);

/// The modes of a state matrix (row-major, n × n): per mode (eigenvalue real part,
/// imaginary part, natural frequency in Hz, damping ratio or None, time constant, kind,
/// stability). `structural_zeros`: the zero eigenvalues the model's structure proves.
#[pyfunction]
pub fn modes(
    py: Python<'_>,
    a: Vec<f64>,
    n: usize,
    structural_zeros: usize,
) -> PyResult<Vec<ModeRow>> {
    if a.len() != n * n {
        return Err(eom_error(format!(
            "modes: {} entries for a {n} × {n} matrix",
            a.len()
        )));
    }
    py.detach(|| modes_of(DMatrix::from_row_slice(n, n, &a), structural_zeros))
}

/// The modes of the state matrix `a` (see [`modes`]).
fn modes_of(a: DMatrix<f64>, structural_zeros: usize) -> PyResult<Vec<ModeRow>> {
    let n = a.nrows();
    let ss = StateSpace {
        a,
        b: DMatrix::zeros(n, 0),
        c: DMatrix::zeros(0, n),
        d: DMatrix::zeros(0, 0),
        phys: DMatrix::zeros(0, n),
        names: eom_num::SignalNames {
            states: (1..=n).map(|k| format!("x{k}")).collect(),
            ..Default::default()
        },
    };
    let opts = ModeOptions {
        shapes: false,
        structural_zeros,
        ..ModeOptions::default()
    };
    let m = Modes::compute_with(&ss, &opts).map_err(eom_error)?;
    Ok(m.modes
        .iter()
        .map(|m| {
            (
                m.eigenvalue.re,
                m.eigenvalue.im,
                m.natural_frequency_hz,
                m.damping_ratio,
                m.time_constant,
                match m.kind {
                    ModeKind::Zero => "zero",
                    ModeKind::Real => "real",
                    ModeKind::Oscillatory => "oscillatory",
                },
                match m.stability {
                    Stability::Stable => "stable",
                    Stability::Marginal => "marginal",
                    Stability::Unstable => "unstable",
                },
            )
        })
        .collect())
}
