"""Stability sweeps on Dask: the points go to the workers in chunks, each worker evaluates
its chunk in Rust (all its cores, the GIL released), the results come back in order.

Every point's result depends on that point alone, so the sweep equals ``Model.stability``
bit for bit whatever the chunking and the number of workers.
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from ._model import Model, Points, Stability

#: Points per task by default: at ~1 ms of scheduler overhead per task and a few µs per
#: point, 10⁴ points keep the overhead to a few percent.
DEFAULT_CHUNK = 20_000


def _chunk_stability(model: Model, points: np.ndarray) -> Stability:
    return model.stability(points)


def stability(
    model: Model,
    points: Points,
    client: Optional[Any] = None,
    chunk: int = DEFAULT_CHUNK,
    names: Optional[Sequence[str]] = None,
) -> Stability:
    """``model.stability(points)`` on the workers of ``client`` (a
    ``dask.distributed.Client``) in chunks of ``chunk`` points; without a client, locally."""
    p = model.points(points, names)
    if client is None:
        return model.stability(p)
    if chunk < 1:
        raise ValueError(f"chunk: at least 1 point, got {chunk}")
    # The model once to every worker (it compiles on first use and stays there).
    # A fresh key per call (hash=False): a content-hashed key would be shared with an
    # earlier call whose release can race with this one ("lost dependencies").
    remote_model = client.scatter(model, broadcast=True, hash=False)
    # The chunks go to the workers as data (scatter), not inside the task graph: arrays
    # embedded in the graph pass through the scheduler (Dask warns of a "large graph").
    parts = client.scatter([p[i : i + chunk] for i in range(0, p.shape[0], chunk)], hash=False)
    futures = client.map(_chunk_stability, [remote_model] * len(parts), parts, pure=False)
    results = client.gather(futures)
    if not results:
        return model.stability(p)
    return Stability(
        np.concatenate([r.max_real for r in results]),
        np.concatenate([r.verdict for r in results]),
        np.concatenate([r.fallback for r in results]),
    )
