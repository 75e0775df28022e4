"""Model and LinearModel: the Python face of the native module ``eom._eom``."""

from __future__ import annotations

from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _eom

Points = Union[Mapping[str, Any], np.ndarray]


def models() -> List[str]:
    """The names of the built-in models (``chainN`` stands for chain1, chain2, …)."""
    return _eom.models()


def load(name_or_path: str) -> "Model":
    """A built-in model by name (``"bicycle"``) or a model file by path (``"car.toml"``).

    A name ending in ``.toml`` or holding a ``/`` is a file. Errors: ``EomError`` (unknown
    model, listing the models), ``ModelFileError`` (an invalid file: ``file``, ``line``)."""
    return Model(_eom.NativeModel.load(str(name_or_path)))


class Warning(NamedTuple):  # noqa: A001 - the name users look for
    """A warning of eom. ``kind`` says where it comes from: ``"load"`` (reading a model
    file), ``"reduction"`` (the elimination of the numeric or symbolic method) or
    ``"robust"`` (the SVD path); ``message`` is eom's text."""

    kind: str
    message: str


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
    """int8 per point: 1 stable, −1 unstable, 0 neither (largest real part exactly 0)."""
    fallback: np.ndarray
    """bool per point: A came from the robust path (the symbolic reduction broke down)."""

    @property
    def stable(self) -> np.ndarray:
        """bool per point: asymptotically stable."""
        return self.verdict == 1


def _readonly(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a


def _matrix(buf: bytes, shape: Tuple[int, int]) -> np.ndarray:
    return np.frombuffer(buf, dtype=np.float64).reshape(shape)


class Model:
    """A multibody model with symbolic parameters (built-in or from a model file)."""

    def __init__(self, native: "_eom.NativeModel"):
        self._native = native

    @property
    def name(self) -> str:
        """The model's name."""
        return self._native.name

    @property
    def parameters(self) -> Dict[str, float]:
        """{name: default} in the model's order."""
        return dict(zip(self._native.parameter_names, self._native.defaults))

    def __repr__(self) -> str:
        return f"<eom.Model {self.name!r}: {len(self._native.parameter_names)} parameters>"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Model) and self._native.source == other._native.source

    def __hash__(self) -> int:
        return hash(self._native.source)

    def to_toml(self, **values: float) -> str:
        """The model as a model file (at the values given, else the defaults)."""
        return self._native.to_toml(_values(values))

    def linearize(self, method: str = "numeric", **values: float) -> "LinearModel":
        """The state-space model at the point (parameters by name, the rest at their defaults).

        ``method``: ``"numeric"`` (elimination at the point, the default), ``"robust"`` (SVD
        complements) or ``"symbolic"`` (the reduction at the defaults, compiled once and
        evaluated at the point)."""
        d = self._native.linearize(method, _values(values))
        kind = "robust" if d["method"] == "robust" else "reduction"
        warnings = [Warning("load", w) for w in self._native.load_warnings]
        warnings += [Warning(kind, w) for w in d["warnings"]]
        return LinearModel(
            A=_matrix(d["A"], d["A_shape"]),
            B=_matrix(d["B"], d["B_shape"]),
            C=_matrix(d["C"], d["C_shape"]),
            D=_matrix(d["D"], d["D_shape"]),
            states=d["states"],
            inputs=d["inputs"],
            outputs=d["outputs"],
            warnings=warnings,
            structural_zeros=d["structural_zeros"],
            method=d["method"],
            model=self.name,
            parameters={**self.parameters, **{k: float(v) for k, v in values.items()}},
        )

    def points(self, points: Points, names: Optional[Sequence[str]] = None) -> np.ndarray:
        """The (N, P) matrix of all parameters (model order) of ``points``: a dict name →
        array of shape (N,), or an (N, k) array with ``names`` for its columns; parameters
        not given take their defaults."""
        pnames = self._native.parameter_names
        defaults = self._native.defaults
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
        for j, (name, default) in enumerate(zip(pnames, defaults)):
            out[:, j] = cols.get(name, default)
        return out

    def signals(self) -> Dict[str, List[str]]:
        """The state, input and output names of the matrices ``evaluate`` returns (those of
        the symbolic reduction, pivots chosen at the defaults)."""
        states, inputs, outputs = self._native.signal_names()
        return {"states": states, "inputs": inputs, "outputs": outputs}

    def evaluate(self, points: Points, names: Optional[Sequence[str]] = None) -> Evaluation:
        """A, B, C, D at every point, from the compiled symbolic reduction, on all cores
        with the GIL released. A point outside the validity region of the reduction (pivots
        chosen at the defaults) raises ``EomError`` naming it."""
        p = self.points(points, names)
        shapes = self._native.shapes()
        sizes = [r * c for r, c in shapes]
        out = np.empty((p.shape[0], sum(sizes)))
        self._native.evaluate_into(p, out)
        mats = []
        start = 0
        for (r, c), size in zip(shapes, sizes):
            mats.append(_readonly(out[:, start : start + size].reshape(p.shape[0], r, c)))
            start += size
        return Evaluation(*mats)

    def stability(self, points: Points, names: Optional[Sequence[str]] = None) -> Stability:
        """The largest real part of the eigenvalues (structural zeros excluded) and the
        verdict at every point, on all cores with the GIL released (the robust path where
        the symbolic reduction breaks down, as ``eom sweep``)."""
        p = self.points(points, names)
        n = p.shape[0]
        max_real = np.empty(n)
        verdict = np.empty(n, dtype=np.int8)
        fallback = np.empty(n, dtype=np.uint8)
        self._native.stability_into(p, max_real, verdict, fallback)
        return Stability(max_real, verdict, fallback.astype(bool))

    def symbolic(self, keep: Optional[Sequence[str]] = None) -> "Symbolic":
        """A, B, C, D in closed form, with the parameters of ``keep`` symbolic (all by
        default) and the others at their defaults as exact decimals."""
        return Symbolic(self._native.symbolic(None if keep is None else list(keep)))

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
            _values(values), f32=f32, no_std=no_std, simplify=simplify,
            stability=stability, module=module,
        )


class Symbolic:
    """Closed forms of a model: ``matrices`` {"A": [[str]]…} in the parser's syntax
    (``"0"`` for structural zeros), ``latex`` {"A": str…}, ``symbolic_parameters`` and
    ``substituted`` [(name, exact value)]."""

    def __init__(self, d: Dict[str, Any]):
        self.symbolic_parameters: List[str] = d["symbolic_parameters"]
        self.substituted: List[Tuple[str, str]] = d["substituted"]
        self.matrices: Dict[str, List[List[str]]] = {}
        self.latex: Dict[str, str] = {}
        for name, m in d["matrices"].items():
            rows, cols = m["shape"]
            grid = [["0"] * cols for _ in range(rows)]
            for i, j, e in m["entries"]:
                grid[i][j] = e
            self.matrices[name] = grid
            self.latex[name] = m["latex"]

    def to_sympy(self) -> Dict[str, Any]:
        """The matrices as ``sympy.Matrix`` (needs sympy)."""
        import sympy

        syms = {n: sympy.Symbol(n) for n in self.symbolic_parameters}
        return {
            name: sympy.Matrix(
                [[sympy.sympify(e.replace("^", "**"), locals=syms) for e in row] for row in m]
            )
            for name, m in self.matrices.items()
        }


class LinearModel:
    """ẋ = A x + B u, y = C x + D u at one point. A, B, C, D are read-only float64 arrays."""

    def __init__(
        self,
        A: np.ndarray,
        B: np.ndarray,
        C: np.ndarray,
        D: np.ndarray,
        states: List[str],
        inputs: List[str],
        outputs: List[str],
        warnings: List[Warning],
        structural_zeros: List[str],
        method: str,
        model: str,
        parameters: Dict[str, float],
    ):
        self.A = _readonly(A)
        self.B = _readonly(B)
        self.C = _readonly(C)
        self.D = _readonly(D)
        self.states = states
        self.inputs = inputs
        self.outputs = outputs
        self.warnings = warnings
        self.structural_zeros = structural_zeros
        """The zero eigenvalues the model's structure proves (one description each)."""
        self.method = method
        self.model = model
        self.parameters = parameters

    def __repr__(self) -> str:
        return (
            f"<eom.LinearModel {self.model!r} ({self.method}): {len(self.states)} states, "
            f"{len(self.inputs)} inputs, {len(self.outputs)} outputs>"
        )

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__dict__.update(state)
        for k in "ABCD":
            _readonly(self.__dict__[k])

    def modes(self) -> List[Mode]:
        """Every eigenvalue with frequency, damping, kind and stability (as ``eom analyze``)."""
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


def _values(values: Mapping[str, float]) -> List[Tuple[str, float]]:
    return [(k, float(v)) for k, v in values.items()]


def _eom_error(message: str) -> Exception:
    from ._errors import EomError

    return EomError(message)
