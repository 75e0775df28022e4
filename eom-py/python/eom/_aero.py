"""``eom.aero``: the body-axis stability derivatives of a wing file, as ``eom aero`` gives
them."""

from __future__ import annotations

from typing import Dict, Iterator, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _eom


class Reference(NamedTuple):
    """The reference quantities of the normalisation (AVL's Sref, Cref, Bref) and the moment
    reference point (AVL geometry axes: x aft, y right, z up)."""

    sref: float
    cref: float
    bref: float
    point: Tuple[float, float, float]


class WingDerivatives:
    """The 36 body-axis derivatives of a wing (AVL's standard axes: x forward, y right,
    z down), by AVL name (``d["CYv"]``), and their dimensional 6×6.

    * ``coefficients``: read-only (6, 6) array, rows CX, CY, CZ, Cl, Cm, Cn; columns per
      u/V, v/V, w/V, pb/2V, qc/2V, rb/2V; ``names`` the AVL names in the same layout;
    * ``dimensional``: ∂F/∂x in SI at ``density`` and ``speed`` (rows X, Y, Z, L, M, N;
      columns u, v, w, p, q, r; the wing item's damping is its negative);
    * ``file``, ``source`` (what the file holds), ``reference``, ``alpha_deg``,
      ``unknown`` (the names an ``.st`` file cannot give, reported as 0), ``warnings``."""

    def __init__(self, d: Dict[str, object]):
        self.file: str = d["file"]  # type: ignore[assignment]
        self.source: str = d["source"]  # type: ignore[assignment]
        sref, cref, bref, point = d["reference"]  # type: ignore[misc]
        self.reference = Reference(sref, cref, bref, tuple(point))
        self.alpha_deg: float = d["alpha_deg"]  # type: ignore[assignment]
        self.names: List[List[str]] = [list(r) for r in d["names"]]  # type: ignore[union-attr]
        self.coefficients = _readonly(np.array(d["coefficients"], dtype=np.float64))
        self.unknown: List[str] = list(d["unknown"])  # type: ignore[call-overload]
        self.warnings: List[str] = list(d["warnings"])  # type: ignore[call-overload]
        self.density: float = d["density"]  # type: ignore[assignment]
        self.speed: float = d["speed"]  # type: ignore[assignment]
        self.dimensional = _readonly(np.array(d["dimensional"], dtype=np.float64))

    def __getitem__(self, name: str) -> float:
        for i, row in enumerate(self.names):
            if name in row:
                return float(self.coefficients[i, row.index(name)])
        raise KeyError(f"no derivative `{name}`; AVL's names are CXu … Cnr")

    def __iter__(self) -> Iterator[str]:
        return (n for row in self.names for n in row)

    def __len__(self) -> int:
        return 36

    def to_dict(self) -> Dict[str, float]:
        """{AVL name: value} in the order CXu … Cnr (as the JSON of ``eom aero``)."""
        return {n: self[n] for n in self}

    def __repr__(self) -> str:
        return f"<eom.WingDerivatives {self.file!r}: {self.source}, alpha = {self.alpha_deg} deg>"


def aero(
    path: str,
    *,
    alpha: Optional[float] = None,
    reference: Optional[Sequence[float]] = None,
    density: float = 1.225,
    speed: float = 10.0,
) -> WingDerivatives:
    """The derivatives of a wing file (``eom aero FILE``): an AVL geometry (``.avl``, solved by
    eom's vortex lattice at angle of attack ``alpha`` in degrees, default 0, about
    ``reference`` — the moment reference point in AVL geometry axes, default the file's) or
    AVL's own output (``.sb`` body axes, ``.st`` stability axes; ``alpha`` and ``reference``
    do not apply). ``density`` [kg/m³] and ``speed`` [m/s] scale the dimensional matrix.

    Errors: ``EomError`` naming the file (and line, for a syntax error)."""
    ref = None if reference is None else tuple(float(x) for x in reference)
    if ref is not None and len(ref) != 3:
        from ._errors import EomError

        raise EomError(f"reference: three numbers (x, y, z), got {len(ref)}")
    return WingDerivatives(
        _eom.aero(str(path), None if alpha is None else float(alpha), ref, float(density),
                  float(speed))
    )


def _readonly(a: np.ndarray) -> np.ndarray:
    a.flags.writeable = False
    return a
