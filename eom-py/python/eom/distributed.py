"""Stability sweeps on Dask: the points go to the workers in chunks, each worker evaluates
its chunk in Rust (all its cores, the GIL released), the results come back in order.

Every point's result depends on that point alone, so the sweep equals ``Model.stability``
bit for bit whatever the chunking and the number of workers.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Optional, Sequence

import numpy as np

from ._model import Model, Points, Stability

#: Points per task by default: at ~1 ms of scheduler overhead per task and a few µs per
#: point, 10⁴ points keep the overhead to a few percent.
DEFAULT_CHUNK = 20_000


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _chunk_stability(
    model: Model, points: np.ndarray, threads: Optional[int], slots: Dict[str, int]
) -> Stability:
    if threads is None:
        from distributed import get_worker

        threads = _worker_threads(slots, get_worker().address)
    return model.stability(points, threads=threads)


def _worker_threads(slots: Dict[str, int], address: str) -> Optional[int]:
    """A task's threads on the worker at ``address``: its share of its machine's cores, as
    many as one task slot has among all the task slots of the workers on the machine (one
    thread each for two one-thread workers on two cores, not two each competing for them);
    None (all cores) for a worker the scheduler did not list."""
    shared = slots.get(address)
    return max(1, _cores() // shared) if shared else None


def _slots_per_host(client: Any) -> Dict[str, int]:
    """Worker address → the task slots (threads) of all the workers on its host."""
    try:
        info = client.scheduler_info(n_workers=-1)
    except TypeError:  # an older distributed: every worker listed anyway
        info = client.scheduler_info()
    workers = info.get("workers", {})
    per_host: Dict[str, int] = {}
    for w in workers.values():
        per_host[w["host"]] = per_host.get(w["host"], 0) + int(w.get("nthreads", 1))
    return {addr: per_host[w["host"]] for addr, w in workers.items()}


def stability(
    model: Model,
    points: Points,
    client: Optional[Any] = None,
    chunk: int = DEFAULT_CHUNK,
    names: Optional[Sequence[str]] = None,
    threads: Optional[int] = None,
) -> Stability:
    """``model.stability(points)`` on the workers of ``client`` (a
    ``dask.distributed.Client``) in chunks of ``chunk`` points; without a client, locally.

    ``threads``: Rust threads per task. By default each task takes its worker's share of its
    machine's cores (cores ÷ the task slots of all workers on that machine), so that workers
    sharing a machine do not oversubscribe it; locally, all cores."""
    p = model.points(points, names)
    if client is None:
        return model.stability(p, threads=threads)
    if chunk < 1:
        raise ValueError(f"chunk: at least 1 point, got {chunk}")
    slots = _slots_per_host(client) if threads is None else {}
    # The model once to every worker (it compiles on first use; the compiled reduction stays
    # in the worker's process for every later model of the same source).
    # A fresh key per call (hash=False): a content-hashed key would be shared with an
    # earlier call whose release can race with this one ("lost dependencies").
    remote_model = client.scatter(model, broadcast=True, hash=False)
    # The chunks go to the workers as data (scatter), not inside the task graph: arrays
    # embedded in the graph pass through the scheduler (Dask warns of a "large graph").
    parts = client.scatter([p[i : i + chunk] for i in range(0, p.shape[0], chunk)], hash=False)
    futures = client.map(
        _chunk_stability, [remote_model] * len(parts), parts, threads=threads, slots=slots,
        pure=False,
    )
    results = client.gather(futures)
    if not results:
        return model.stability(p, threads=threads)
    return Stability(
        np.concatenate([r.max_real for r in results]),
        np.concatenate([r.verdict for r in results]),
        np.concatenate([r.fallback for r in results]),
    )
