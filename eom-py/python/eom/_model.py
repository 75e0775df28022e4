"""Model and LinearModel: the Python face of the native module ``eom._eom``."""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import re

import numpy as np

from . import _eom

Points = Union[Mapping[str, Any], np.ndarray]

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def models() -> List[str]:
    """The names of the built-in models (``chainN`` stands for chain1, chain2, …)."""
    return _eom.models()


def load(name_or_path: str) -> "Model":
    """A built-in model by name (``"bicycle"``) or a model file by path (``"car.toml"``).

    A name ending in ``.toml`` or holding a ``/`` is a file. Errors: ``EomError`` (unknown
    model, listing the models), ``ModelFileError`` (an invalid file: ``file``, ``line``)."""
    return Model(_eom.NativeModel.load(str(name_or_path)))


class Warning(NamedTuple):  # noqa: A001 - the name users look for
    """A warning of eom, as data. ``kind`` says what it is, as a short name
    (``"statics_redundant"``, ``"reduction_redundant"``, ``"robust_redundant"``,
    ``"near_equilibrium"``, ``"inertia_triangle"``, ``"auto_lagged"``, … — the variants of
    ``eom_model::Warning``, see docs/diagnostics.md); ``item`` is the name of the item it is
    about (``None`` when it is about no single item); ``message`` is eom's text (also
    ``str(w)``); ``source`` says where it comes from: ``"load"`` (reading a model file),
    ``"reduction"`` (the elimination of the numeric or symbolic method) or ``"robust"`` (the
    SVD path)."""

    kind: str
    item: Optional[str]
    message: str
    source: str

    def __str__(self) -> str:
        return self.message


class Mode(NamedTuple):
    """One eigenvalue of A as ``eom analyze`` reports it."""

    eigenvalue: complex
    frequency: float
    """Natural frequency |λ|/2π in Hz."""
    damping: Optional[float]
    """Damping ratio −Re λ/|λ| (None for a zero eigenvalue)."""
    time_constant: float
    kind: str
    """``"zero"``, ``"real"`` or ``"oscillatory"``."""
    stability: str
    """``"stable"``, ``"marginal"`` (|Re λ| within its error estimate) or ``"unstable"``."""


class Evaluation(NamedTuple):
    """A, B, C, D at N points, stacked: shapes (N, n, n), (N, n, m), (N, p, n), (N, p, m)."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray


class Stability(NamedTuple):
    """The stability of N points."""

    max_real: np.ndarray
    """Largest real part of the eigenvalues per point, the structural zeros excluded."""
    verdict: np.ndarray
    """int8 per point: 1 stable, −1 unstable, 0 marginal: a real part within its
    eigenvalue's error estimate, where its sign is not known (the verdict of ``eom analyze``
    and ``eom sweep``)."""
    fallback: np.ndarray
    """bool per point: A came from the robust path (the symbolic reduction broke down)."""

    @property
    def stable(self) -> np.ndarray:
        """bool per point: asymptotically stable."""
        return self.verdict == 1


def _threads(threads: Optional[int]) -> Optional[int]:
    if threads is not None and (
        not isinstance(threads, int) or isinstance(threads, bool) or threads < 1
    ):
        raise _eom_error(f"threads: a positive number of threads, got {threads!r}")
    return None if threads is None else int(threads)


def _readonly(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


def _matrix(buf: bytes, shape: Tuple[int, int]) -> np.ndarray:
    return np.frombuffer(buf, dtype=np.float64).reshape(shape)


class Model:
    """A multibody model with symbolic parameters (built-in or from a model file)."""

    def __init__(self, native: "_eom.NativeModel"):
        self._native = native
        # Asked once: every linearize and points() call needs them.
        self._names: Tuple[str, ...] = tuple(native.parameter_names)
        self._defaults: Tuple[float, ...] = tuple(native.defaults)
        self._load_warnings: Optional[List["Warning"]] = None

    def __getstate__(self) -> Dict[str, Any]:
        return {"_native": self._native}

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__init__(state["_native"])  # type: ignore[misc]

    @property
    def name(self) -> str:
        """The model's name."""
        return self._native.name

    @property
    def parameters(self) -> Dict[str, float]:
        """{name: default} in the model's order."""
        return dict(zip(self._names, self._defaults))

    def __repr__(self) -> str:
        return f"<eom.Model {self.name!r}: {len(self._names)} parameters>"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Model) and self._native.source == other._native.source

    def __hash__(self) -> int:
        return hash(self._native.source)

    def to_toml(self, **values: float) -> str:
        """The model as a model file (at the values given, else the defaults)."""
        return self._native.to_toml(_pairs(values))

    def linearize(self, method: str = "numeric", **values: float) -> "LinearModel":
        """The state-space model at the point (parameters by name, the rest at their defaults).

        ``method``: ``"numeric"`` (elimination at the point, the default), ``"robust"`` (SVD
        complements) or ``"symbolic"`` (the reduction at the defaults, compiled once and
        evaluated at the point, as ``evaluate`` does: the values are checked against the
        parameters' declared ranges, the model is not rebuilt at the point)."""
        return LinearModel(self, self._native.linearize(method, values), values)

    def load_warnings(self) -> List["Warning"]:
        """The warnings of reading the model file (none for a built-in), with
        ``source == "load"``."""
        if self._load_warnings is None:
            self._load_warnings = [Warning(*w, "load") for w in self._native.load_warnings]
        return list(self._load_warnings)

    def points(self, points: Points, names: Optional[Sequence[str]] = None) -> np.ndarray:
        """The (N, P) matrix of all parameters (model order) of ``points``: a dict name →
        array of shape (N,), or an (N, k) array with ``names`` for its columns; parameters
        not given take their defaults."""
        pnames = self._names
        if isinstance(points, Mapping):
            cols = {k: np.asarray(v, dtype=np.float64) for k, v in points.items()}
        else:
            arr = np.asarray(points, dtype=np.float64)
            if arr.ndim != 2:
                raise _eom_error(f"points: an (N, k) array, got shape {arr.shape}")
            if names is None:
                if arr.shape[1] != len(pnames):
                    raise _eom_error(
                        f"points: {arr.shape[1]} columns without names; the model has "
                        f"{len(pnames)} parameters: {', '.join(pnames)}"
                    )
                return np.require(arr, np.float64, ["C_CONTIGUOUS", "ALIGNED"])
            if len(names) != arr.shape[1]:
                raise _eom_error(f"points: {arr.shape[1]} columns, {len(names)} names")
            cols = {n: arr[:, j] for j, n in enumerate(names)}
        unknown = [k for k in cols if k not in pnames]
        if unknown:
            raise _eom_error(
                f"model `{self.name}` has no parameter `{unknown[0]}`; its parameters are: "
                + ", ".join(pnames)
            )
        sizes = {c.shape for c in cols.values()}
        if len(sizes) > 1 or any(len(s) != 1 for s in sizes):
            raise _eom_error(f"points: every array of shape (N,), got {sorted(sizes)}")
        n = next(iter(sizes))[0] if sizes else 1
        out = np.empty((n, len(pnames)))
        for j, (name, default) in enumerate(zip(pnames, self._defaults)):
            out[:, j] = cols.get(name, default)
        return out

    def signals(self) -> Dict[str, List[str]]:
        """The state, input and output names of the matrices ``evaluate`` returns (those of
        the symbolic reduction, pivots chosen at the defaults)."""
        states, inputs, outputs = self._native.signal_names()
        return {"states": states, "inputs": inputs, "outputs": outputs}

    def evaluate(
        self,
        points: Points,
        names: Optional[Sequence[str]] = None,
        *,
        threads: Optional[int] = None,
    ) -> Evaluation:
        """A, B, C, D at every point, from the compiled symbolic reduction, on ``threads``
        threads (all cores by default) with the GIL released, written straight into the
        buffer of the arrays returned (read-only views of one (N, entries) array). A point outside the validity region of the reduction (pivots
        chosen at the defaults) raises ``EomError`` naming it."""
        p = self.points(points, names)
        shapes = self._native.shapes()
        sizes = [r * c for r, c in shapes]
        # (N, entries of A..D): the Rust buffer the evaluation wrote, not copied.
        out = self._native.evaluate(p, _threads(threads))
        mats = []
        start = 0
        for (r, c), size in zip(shapes, sizes):
            mats.append(_readonly(out[:, start : start + size].reshape(p.shape[0], r, c)))
            start += size
        return Evaluation(*mats)

    def stability(
        self,
        points: Points,
        names: Optional[Sequence[str]] = None,
        *,
        threads: Optional[int] = None,
    ) -> Stability:
        """The largest real part of the eigenvalues (structural zeros excluded) and the
        verdict at every point, on ``threads`` threads (all cores by default) with the GIL
        released (the robust path where the symbolic reduction breaks down, as ``eom
        sweep``)."""
        p = self.points(points, names)
        n = p.shape[0]
        max_real = np.empty(n)
        verdict = np.empty(n, dtype=np.int8)
        fallback = np.empty(n, dtype=np.bool_)
        self._native.stability_into(p, max_real, verdict, fallback, _threads(threads))
        return Stability(max_real, verdict, fallback)

    def symbolic(
        self,
        keep: Optional[Sequence[str]] = None,
        *,
        stability: bool = True,
        transfer: bool = True,
        solve_for: Optional[str] = None,
        max_states: int = 8,
    ) -> "Symbolic":
        """The model in closed form (as ``eom symbolic``): A, B, C, D with the parameters of
        ``keep`` symbolic (all by default) and the others at their defaults as exact
        decimals; for models of up to ``max_states`` states also the characteristic
        polynomial, ωₙ and ζ of a second-order model, the stability conditions
        (``stability``; each boundary solved for ``solve_for`` where it is of degree ≤ 2 in
        it) and the transfer functions of every output/input pair (``transfer``)."""
        return Symbolic(
            self._native.symbolic(
                None if keep is None else list(keep), stability, transfer, solve_for, max_states
            )
        )

    def codegen(
        self,
        *,
        f32: bool = False,
        no_std: bool = False,
        simplify: bool = False,
        stability: bool = False,
        module: Optional[str] = None,
        **values: float,
    ) -> str:
        """The Rust module ``eom codegen`` writes (one ``pub mod``)."""
        return self._native.codegen(
            _pairs(values), f32=f32, no_std=no_std, simplify=simplify,
            stability=stability, module=module,
        )


class Polynomial(NamedTuple):
    """``det(sI − A) = s^zero_roots · p(s) / scale``; ``coefficients`` are those of p,
    ``s⁰`` first, in the parser's syntax (factored where they factor)."""

    coefficients: List[str]
    zero_roots: int
    scale: str
    normalized: bool
    """False when a bound of the exact algebra was reached: exact but not in normal form."""
    latex: str
    """p(s) in LaTeX, highest power first."""


class Condition(NamedTuple):
    """One condition ``expression > 0`` of asymptotic stability (Liénard–Chipart)."""

    expression: str
    satisfiable: bool
    """False when it holds for no parameter values (``never`` says why)."""
    never: Optional[str]
    source: str
    """``"coefficient k"`` or ``"hurwitz k"``."""
    divided_out: List[str]
    """Factors of known sign divided out."""
    boundary: Optional[Tuple[str, List[str]]]
    """(parameter, roots): where the condition changes sign, solved for ``solve_for``."""
    latex: str


class TransferFunction(NamedTuple):
    """``G(s) = numerator(s) / denominator(s)`` from ``input`` to ``output``; coefficients
    ``s⁰`` first in the parser's syntax."""

    output: str
    input: str
    numerator: List[str]
    denominator: List[str]
    normalized: bool
    latex: str


class Symbolic:
    """Closed forms of a model (``eom symbolic``), every expression as text in the parser's
    syntax, with LaTeX beside it:

    * ``matrices`` {"A": [[str]]…} (``"0"`` for structural zeros), ``latex`` {"A": str…};
    * ``characteristic_polynomial`` (a ``Polynomial``), ``second_order`` (ωₙ, ζ) of a
      two-state model;
    * ``stability`` [``Condition``], all of which must hold, and ``stability_verdict``
      (``"always"``, ``"never: …"``, ``"undecided: …"`` (a condition that is a constant
      too close to zero to decide its sign) or ``"when all conditions hold"``; conditions
      that are constants, as with ``keep=[]``, are decided by their exact value);
    * ``transfer_functions`` [``TransferFunction``];
    * ``symbolic_parameters``, ``substituted`` [(name, exact value)], ``notes`` (what was
      skipped and why).

    The closed forms other than the matrices are None (or empty) when the model has more
    states than ``max_states`` or when not requested. ``to_sympy()`` gives them as sympy
    expressions."""

    def __init__(self, d: Dict[str, Any]):
        self.symbolic_parameters: List[str] = d["symbolic_parameters"]
        self.substituted: List[Tuple[str, str]] = d["substituted"]
        self.notes: List[str] = d["notes"]
        self.matrices: Dict[str, List[List[str]]] = {}
        self.latex: Dict[str, str] = {}
        for name, m in d["matrices"].items():
            rows, cols = m["shape"]
            grid = [["0"] * cols for _ in range(rows)]
            for i, j, e in m["entries"]:
                grid[i][j] = e
            self.matrices[name] = grid
            self.latex[name] = m["latex"]
        p = d.get("characteristic_polynomial")
        self.characteristic_polynomial: Optional[Polynomial] = (
            None
            if p is None
            else Polynomial(
                p["coefficients"], p["zero_roots"], p["scale"], p["normalized"], p["latex"]
            )
        )
        so = d.get("second_order")
        self.second_order: Optional[Tuple[str, str]] = (
            None if so is None else (so["natural_frequency"], so["damping_ratio"])
        )
        conds = d.get("stability")
        self.stability: Optional[List[Condition]] = (
            None
            if conds is None
            else [
                Condition(
                    c["expression"], c["satisfiable"], c["never"], c["source"],
                    c["divided_out"],
                    None if c["boundary"] is None else (c["boundary"][0], c["boundary"][1]),
                    c["latex"],
                )
                for c in conds
            ]
        )
        self.stability_verdict: Optional[str] = d.get("stability_verdict")
        self.transfer_functions: List[TransferFunction] = [
            TransferFunction(
                t["output"], t["input"], t["numerator"], t["denominator"], t["normalized"],
                t["latex"],
            )
            for t in d.get("transfer_functions", [])
        ]
        self._latex_parts = {
            "polynomial": None if p is None else (p["latex"], p["zero_roots"]),
            "second_order": None if so is None else so["latex"],
            "boundaries": [c["boundary"][2] for c in conds or [] if c["boundary"] is not None],
        }

    def transfer_function(self, output: str, input: str) -> TransferFunction:
        """The transfer function from ``input`` to ``output`` (by name)."""
        for t in self.transfer_functions:
            if t.output == output and t.input == input:
                return t
        raise KeyError(
            f"no transfer function {output} / {input}; pairs: "
            + ", ".join(f"{t.output} / {t.input}" for t in self.transfer_functions)
        )

    def to_latex(self) -> str:
        """Everything as one LaTeX ``align*`` block (as ``eom symbolic --format latex``)."""
        lines = [f"{name} &= {tex}" for name, tex in self.latex.items()]
        poly = self._latex_parts["polynomial"]
        if poly is not None:
            tex, zeros = poly
            z = f"s^{{{zeros}}}\\," if zeros > 0 else ""
            lines.append(f"\\det(sI - A) &= {z}\\left({tex}\\right)")
        so = self._latex_parts["second_order"]
        if so is not None:
            lines.append(f"\\omega_n &= {so[0]}")
            lines.append(f"\\zeta &= {so[1]}")
        lines += [f"& {c.latex}" for c in self.stability or []]
        lines += [f"& {b}" for b in self._latex_parts["boundaries"]]
        lines += [f"G_{{{t.output},{t.input}}}(s) &= {t.latex}" for t in self.transfer_functions]
        return "\\begin{align*}\n" + " \\\\\n".join(lines) + "\n\\end{align*}\n"

    def to_sympy(self) -> Dict[str, Any]:
        """Everything as sympy objects (needs sympy): ``"A"`` … ``"D"`` as ``sympy.Matrix``;
        ``"s"`` the Laplace variable; ``"characteristic_polynomial"`` p(s) (as an
        expression in s); ``"second_order"`` (ωₙ, ζ); ``"stability"`` [``expr > 0``];
        ``"transfer_functions"`` {(output, input): numerator/denominator}."""
        import sympy

        # Every parameter through a placeholder: names such as `lambda` (a Python keyword)
        # or `E`, `I`, `S` (sympy's own) then parse as the parameter's symbol.
        placeholder = {n: f"_eom_p{k}" for k, n in enumerate(self.symbolic_parameters)}
        syms = {placeholder[n]: sympy.Symbol(n) for n in self.symbolic_parameters}
        s = sympy.Symbol("s")

        def expr(text: str) -> Any:
            text = _IDENTIFIER.sub(lambda m: placeholder.get(m.group(0), m.group(0)), text)
            return sympy.sympify(text.replace("^", "**"), locals=syms)

        def poly(coefficients: List[str]) -> Any:
            return sympy.Add(*[expr(c) * s**k for k, c in enumerate(coefficients)])

        out: Dict[str, Any] = {
            name: sympy.Matrix([[expr(e) for e in row] for row in m])
            for name, m in self.matrices.items()
        }
        out["s"] = s
        p = self.characteristic_polynomial
        if p is not None:
            out["characteristic_polynomial"] = poly(p.coefficients)
        if self.second_order is not None:
            out["second_order"] = tuple(expr(x) for x in self.second_order)
        if self.stability is not None:
            out["stability"] = [
                sympy.StrictGreaterThan(expr(c.expression), 0) if c.satisfiable else sympy.false
                for c in self.stability
            ]
        out["transfer_functions"] = {
            (t.output, t.input): poly(t.numerator) / poly(t.denominator)
            for t in self.transfer_functions
        }
        return out


class Preload(NamedTuple):
    """The static preload of one constraint or elastic item (as ``eom analyze`` reports it):
    the force and moment it exerts on its first body at the equilibrium the model's geometry
    describes, in model axes."""

    item: str
    """The item, e.g. ``"rigid point `pin1`"``."""
    body: str
    """The item's first body: the one the force and moment act on."""
    force: Tuple[float, float, float]
    """Force on ``body`` in N (model axes)."""
    moment: Tuple[float, float, float]
    """Moment on ``body`` in N m about the item's point (a line item: its end on ``body``)."""
    tension: Optional[float]
    """A line item's tension in N (positive pulls its ends together; a twist item: the
    torque in N m); None for other items."""
    unique: bool
    """False when the statics does not determine it (redundant rigid constraints: the
    minimum-norm preload is given)."""
    computed: bool
    """False for an item whose preload is not computed (a beam's end loads: reported as 0)."""


class Preloads(NamedTuple):
    """The static preloads at a point: ``statics`` says how they were found
    (``"unloaded"``, ``"determinate"`` or ``"indeterminate"``), ``items`` has one
    ``Preload`` per constraint or elastic item, constraints first. Values smaller than 1e-12
    of the largest of their kind are 0 (the statics' rounding)."""

    statics: str
    items: List[Preload]

    def __getitem__(self, key: Any) -> Any:  # type: ignore[override]
        """``preloads["rigid point `pin1`"]`` or ``preloads["pin1"]``: one item by its label
        or name; an int or slice indexes the tuple (``statics``, ``items``)."""
        if not isinstance(key, str):
            return tuple.__getitem__(self, key)
        for p in self.items:
            if p.item == key or p.item.endswith(f"`{key}`"):
                return p
        raise KeyError(f"no preload of `{key}`; items: " + ", ".join(p.item for p in self.items))


_MATRICES = ("A", "B", "C", "D")
_NAMES = ("states", "inputs", "outputs", "input_units", "output_units")


class LinearModel:
    """ẋ = A x + B u, y = C x + D u at one point. A, B, C, D are read-only float64 arrays.

    Created cheaply: the linearization stays in Rust and each part (the matrices, the
    names, the warnings, the preloads) is converted when first read, then kept."""

    def __init__(self, model: Model, native: "_eom.NativeLinear", values: Dict[str, float]):
        self._model = model
        self._native = native
        self._values = values

    def _get(self, name: str) -> Any:
        d = self.__dict__
        if name in d:
            return d[name]
        native = self._native
        if name in _MATRICES:
            buf, shapes = native.matrices()
            # Views of one immutable buffer: read-only, no copies.
            offset = 0
            for key, (r, c) in zip(_MATRICES, shapes):
                d[key] = np.ndarray((r, c), np.float64, buf, offset)
                offset += 8 * r * c
        elif name in _NAMES:
            d.update(zip(_NAMES, native.names()))
        elif name == "warnings":
            source = "robust" if native.method == "robust" else "reduction"
            d[name] = self._model.load_warnings() + [Warning(*w, source) for w in native.warnings]
        elif name == "structural_zeros":
            d[name] = native.structural_zeros
        elif name == "method":
            d[name] = native.method
        else:
            raise AttributeError(name)
        return d[name]

    A = property(lambda self: self._get("A"), doc="The state matrix (n × n).")
    B = property(lambda self: self._get("B"), doc="The input matrix (n × m).")
    C = property(lambda self: self._get("C"), doc="The output matrix (p × n).")
    D = property(lambda self: self._get("D"), doc="The feedthrough matrix (p × m).")
    states = property(lambda self: self._get("states"), doc="State names.")
    inputs = property(lambda self: self._get("inputs"), doc="Input names.")
    outputs = property(lambda self: self._get("outputs"), doc="Output names.")
    input_units = property(lambda self: self._get("input_units"), doc="Input units.")
    output_units = property(lambda self: self._get("output_units"), doc="Output units.")
    warnings = property(
        lambda self: self._get("warnings"),
        doc="[Warning(kind, item, message, source)]: of loading the file, then of the reduction.",
    )
    structural_zeros = property(
        lambda self: self._get("structural_zeros"),
        doc="The zero eigenvalues the model's structure proves (one description each).",
    )
    method = property(
        lambda self: self._get("method"), doc='``"numeric"``, ``"robust"`` or ``"symbolic"``.'
    )

    @property
    def model(self) -> str:
        """The model's name."""
        return self._model.name

    @property
    def parameters(self) -> Dict[str, float]:
        """Every parameter's value at this point."""
        return {**self._model.parameters, **_values(self._values)}

    @property
    def preloads(self) -> Preloads:
        """The static preloads at this point (as ``eom analyze``): the force and moment each
        constraint and elastic item exerts on its first body. Computed on first use;
        ``EomError`` when the statics cannot be solved."""
        d = self.__dict__
        if "preloads" not in d:
            statics, items = self._model._native.preloads(_pairs(self._values))
            d["preloads"] = Preloads(
                statics,
                [
                    Preload(item, body, tuple(f), tuple(m), t, u, c)
                    for item, body, f, m, t, u, c in items
                ],
            )
        return d["preloads"]

    def __repr__(self) -> str:
        return (
            f"<eom.LinearModel {self.model!r} ({self.method}): {len(self.states)} states, "
            f"{len(self.inputs)} inputs, {len(self.outputs)} outputs>"
        )

    def __getstate__(self) -> Dict[str, Any]:
        # Every part converted (the native linearization does not pickle); the preloads are
        # recomputed from the model and the values if asked for again.
        for name in _MATRICES + _NAMES + ("warnings", "structural_zeros", "method"):
            self._get(name)
        state = {k: v for k, v in self.__dict__.items() if k != "_native"}
        for k in _MATRICES:
            state[k] = np.array(state[k])
        return state

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__dict__.update(state)
        self._native = None
        for k in _MATRICES:
            _readonly(self.__dict__[k])

    def modes(self) -> List[Mode]:
        """Every eigenvalue with frequency, damping, kind and stability (as ``eom analyze``)."""
        if self._native is not None:
            rows = self._native.modes()
        else:
            n = self.A.shape[0]
            rows = _eom.modes(self.A.ravel().tolist(), n, len(self.structural_zeros))
        return [Mode(complex(re, im), f, z, tc, k, s) for re, im, f, z, tc, k, s in rows]

    def eigenvalues(self) -> np.ndarray:
        """The eigenvalues of A (complex, sorted as ``eom analyze`` lists them)."""
        return np.array([m.eigenvalue for m in self.modes()], dtype=np.complex128)

    def to_control(self) -> Any:
        """A ``control.StateSpace`` with the state, input and output names (no states
        removed)."""
        import control

        return control.ss(
            np.array(self.A), np.array(self.B), np.array(self.C), np.array(self.D),
            states=list(self.states), inputs=list(self.inputs), outputs=list(self.outputs),
            name=self.model, remove_useless_states=False,
        )

    def to_scipy(self) -> Any:
        """A ``scipy.signal.StateSpace``."""
        from scipy import signal

        return signal.StateSpace(
            np.array(self.A), np.array(self.B), np.array(self.C), np.array(self.D)
        )


def _values(values: Mapping[str, float]) -> Dict[str, float]:
    return {k: float(v) for k, v in values.items()}


def _pairs(values: Mapping[str, float]) -> List[Tuple[str, float]]:
    return [(k, float(v)) for k, v in values.items()]


def _eom_error(message: str) -> Exception:
    from ._errors import EomError

    return EomError(message)
