"""eom: linearized equations of motion of multibody systems, from Python.

>>> import eom
>>> bike = eom.load("bicycle")
>>> lin = bike.linearize(v=5.0)
>>> lin.eigenvalues()          # doctest: +SKIP

``Model`` and ``LinearModel`` pickle (Dask, Ray, multiprocessing); ``eom.distributed`` runs
stability sweeps on a Dask cluster. See docs/python.md of the eom repository.
"""

from __future__ import annotations

from ._aero import Reference, WingDerivatives, aero
from ._errors import EomError, ModelFileError
from ._model import (
    Condition,
    LinearModel,
    Mode,
    Model,
    Polynomial,
    Preload,
    Preloads,
    Stability,
    Symbolic,
    TransferFunction,
    Warning,
    load,
    models,
)

__all__ = [
    "Condition",
    "EomError",
    "LinearModel",
    "Mode",
    "Model",
    "ModelFileError",
    "Polynomial",
    "Preload",
    "Preloads",
    "Reference",
    "Stability",
    "Symbolic",
    "TransferFunction",
    "Warning",
    "WingDerivatives",
    "aero",
    "load",
    "models",
]
__version__ = "0.1.0"
