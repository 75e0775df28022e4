"""Stability sweeps on Dask: the points go to the workers in chunks, each worker evaluates
its chunk in Rust (all its cores, the GIL released), the results come back in order.

Every point's result depends on that point alone, so the sweep equals ``Model.stability``
bit for bit whatever the chunking and the number of workers.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

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


def _is_dask_array(points: Any) -> bool:
    """Whether ``points`` is a ``dask.array.Array`` (checked without importing Dask)."""
    return type(points).__module__.startswith("dask.array") and hasattr(points, "to_delayed")


def _chunk_stability(
    model: Model,
    points: np.ndarray,
    threads: Optional[int],
    slots: Dict[str, int],
    names: Optional[Sequence[str]] = None,
) -> Stability:
    if threads is None:
        from distributed import get_worker

        threads = _worker_threads(slots, get_worker().address)
    return model.stability(points, names, threads=threads)


def _worker_threads(slots: Dict[str, int], address: str) -> Optional[int]:
    """A task's threads on the worker at ``address``: its share of its machine's cores, as
    many as one task slot has among all the task slots of the workers on the machine (one
    thread each for two one-thread workers on two cores, not two each competing for them);
    None (all cores) for a worker the scheduler did not list."""
    shared = slots.get(address)
    return max(1, _cores() // shared) if shared else None


def _slots_per_host(client: Any) -> Dict[str, int]:
    """Worker address → the task slots (threads) of all the workers on its host."""
    workers = _workers(client)
    per_host: Dict[str, int] = {}
    for w in workers.values():
        per_host[w["host"]] = per_host.get(w["host"], 0) + int(w.get("nthreads", 1))
    return {addr: per_host[w["host"]] for addr, w in workers.items()}


def stability(
    model: Model,
    points: Union[Points, Any],
    client: Optional[Any] = None,
    chunk: int = DEFAULT_CHUNK,
    names: Optional[Sequence[str]] = None,
    threads: Optional[int] = None,
    direct: bool = True,
) -> Stability:
    """``model.stability(points)`` on the workers of ``client`` (a
    ``dask.distributed.Client``) in chunks of ``chunk`` points; without a client, locally.

    ``points``: as ``Model.stability`` (a dict name → array, or an (N, k) array with
    ``names``), or a ``dask.array.Array`` of shape (N, k) (all parameters in model order, or
    ``names`` for its columns) whose blocks already live on the cluster or are computed
    there: each block of rows is evaluated where it is, without passing through the client,
    and ``chunk`` is not used (the array's row chunks are the tasks).

    ``threads``: Rust threads per task. By default each task takes its worker's share of its
    machine's cores (cores ÷ the task slots of all workers on that machine), so that workers
    sharing a machine do not oversubscribe it; locally, all cores.

    ``direct``: the chunks and results travel straight between the client and the workers;
    False where the client reaches the scheduler only (they are relayed by it)."""
    if _is_dask_array(points):
        return _stability_of_dask_array(model, points, client, names, threads, direct)
    if client is None:
        return model.stability(points, names, threads=threads)
    if chunk < 1:
        raise ValueError(f"chunk: at least 1 point, got {chunk}")
    p, names = _given_columns(model, points, names)
    slots = _slots_per_host(client) if threads is None else {}
    remote_model = _broadcast(client, model)
    bounds = list(range(0, p.shape[0], chunk))
    # Pipelined: the chunks go out one round at a time (one chunk to each worker, sent
    # concurrently), and each round's tasks are submitted as soon as its chunks are there, so
    # that the workers evaluate the first chunks while the client sends the next ones (sent
    # all at once, the workers idled until the last chunk had arrived). ``direct``: straight
    # to the workers, not through the scheduler (one hop and one copy fewer); numpy chunks
    # travel as buffers, without pickling copies. As data, not inside the task graph: arrays
    # embedded in the graph pass through the scheduler (Dask warns of a "large graph").
    per_round = max(1, len(_workers(client)))
    futures = []
    for r in range(0, len(bounds), per_round):
        parts = client.scatter(
            [p[i : i + chunk] for i in bounds[r : r + per_round]], hash=False, direct=direct
        )
        futures += [
            client.submit(
                _chunk_stability, remote_model, part, threads, slots, names, pure=False
            )
            for part in parts
        ]
    if not futures:
        return model.stability(p, names, threads=threads)
    return _joined(client.gather(futures, direct=direct))


def _given_columns(
    model: Model, points: Points, names: Optional[Sequence[str]]
) -> Tuple[np.ndarray, Optional[Sequence[str]]]:
    """The points as an (N, k) array of the parameters given, and their names (None for all
    parameters in model order): only what varies travels to the workers, which fill in the
    defaults (``Model.points``, the same values as locally). Checked here first, so that bad
    points raise on the client, as locally."""
    if isinstance(points, Mapping):
        cols = {k: np.asarray(v, dtype=np.float64) for k, v in points.items()}
        if not cols or len({c.shape for c in cols.values()}) > 1 or next(
            iter(cols.values())
        ).ndim != 1:
            return model.points(points), None  # raises, or the defaults (no column given)
        model.points({k: c[:1] for k, c in cols.items()})  # the names checked
        return np.column_stack(list(cols.values())), list(cols)
    if names is None:
        return model.points(points), None
    arr = np.asarray(points, dtype=np.float64)
    model.points(arr[:1], names)  # the shape and names checked
    return np.ascontiguousarray(arr), list(names)


def _stability_of_dask_array(
    model: Model,
    points: Any,
    client: Optional[Any],
    names: Optional[Sequence[str]],
    threads: Optional[int],
    direct: bool,
) -> Stability:
    if points.ndim != 2:
        raise ValueError(f"points: an (N, k) dask array, got shape {points.shape}")
    if client is None:
        # Locally: the array computed with Dask's default scheduler, then all cores.
        return model.stability(np.asarray(points.compute()), names, threads=threads)
    if points.numblocks[1] > 1:
        points = points.rechunk({1: -1})  # a task needs whole rows
    slots = _slots_per_host(client) if threads is None else {}
    remote_model = _broadcast(client, model)
    # One graph for the whole sweep, each block's task beside its block (computed on the
    # cluster, or already there if persisted): no point passes through the client, and the
    # client and scheduler handle one submission, not one per block.
    import dask

    task = dask.delayed(_chunk_stability, pure=False)
    parts = [task(remote_model, b, threads, slots, names) for b in points.to_delayed().ravel()]
    if not parts:
        return model.stability(np.empty((0, len(model.parameters))), threads=threads)
    return _joined(client.gather(client.compute(parts), direct=direct))


def _broadcast(client: Any, model: Model) -> Any:
    """The model once to every worker (it compiles on first use; the compiled reduction stays
    in the worker's process for every later model of the same source). A fresh key per call
    (hash=False): a content-hashed key would be shared with an earlier call whose release can
    race with this one ("lost dependencies")."""
    return client.scatter(model, broadcast=True, hash=False)


def _workers(client: Any) -> Dict[str, Any]:
    try:
        return client.scheduler_info(n_workers=-1).get("workers", {})
    except TypeError:  # an older distributed: every worker listed anyway
        return client.scheduler_info().get("workers", {})


def _joined(results: Sequence[Stability]) -> Stability:
    """The chunks' results in order, as one."""
    return Stability(
        np.concatenate([r.max_real for r in results]),
        np.concatenate([r.verdict for r in results]),
        np.concatenate([r.fallback for r in results]),
    )
