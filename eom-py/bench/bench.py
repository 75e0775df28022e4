"""Benchmarks of the Python package (see docs/python.md for the figures and the load).

    python eom-py/bench/bench.py [--points N] [--dask]

1. Model.evaluate over N random bicycle points against the Rust-only time of the same
   evaluation into a fresh buffer (no Python objects): the per-point overhead of the Python
   layer; interleaved, the smallest and the median of --repeat runs.
2. LinearModel creation beyond the Rust linearization (symbolic method, cached tape), the
   baseline the same linearization timed in Rust alone in the same run; also with the
   matrices and names read (they are converted on first use).
3. With --dask (or --dask-only, without 1. and 2.): Model.stability points/s locally, and
   eom.distributed.stability on LocalClusters of 1 and 2 worker processes (one Dask thread
   each; the one worker's Rust on one thread, the two workers' on their share of the cores,
   one each on 2 cores), both up at once and timed in turn, --repeat rounds, with the points
   sent from the client and already on the cluster (a persisted dask array): the smallest
   and the median, the speed-up of 2 workers over 1, and the CPU seconds of the client's
   process (a LocalCluster's scheduler runs in it) and of the workers per sweep (what the wall times cannot show on a loaded
   machine).

The machine's load (os.getloadavg) is printed with each figure: on a shared machine the
figures are only as good as the load they were measured under.
"""

import argparse
import logging
import os
import time
import warnings

import numpy as np

import eom


def bicycle_points(n, seed=20261128):
    bike = eom.load("bicycle")
    nominal = np.array(list(bike.parameters.values()))
    rng = np.random.default_rng(seed)
    return bike, nominal * (1.0 + 0.2 * (2.0 * rng.random((n, nominal.size)) - 1.0))


def best(f, repeat=3):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def _touch(lin):
    return lin.A, lin.B, lin.C, lin.D, lin.states, lin.inputs, lin.outputs, lin.warnings


def load():
    return "load {:.2f} {:.2f} {:.2f}".format(*os.getloadavg())


def stats(times):
    return min(times), sorted(times)[len(times) // 2]


def cpu_seconds(client):
    """CPU seconds (user + system) so far of the client's process (a LocalCluster's
    scheduler runs in it, on its own thread) and of the workers together."""
    import psutil

    def own():
        return sum(psutil.Process().cpu_times()[:2])

    return own(), sum(client.run(own).values())


#: Rows per block of the array that lives on the cluster: 125 000 rows of 27 parameters are
#: 27 MB, within Dask's advice of blocks of tens to hundreds of MB (fewer, larger tasks keep
#: the scheduler's share small).
ON_CLUSTER_ROWS = 125_000


def dask_sweeps(bike, pts, clients, args):
    """eom.distributed.stability on 1 and 2 workers, interleaved round by round: the points
    sent from the client (a NumPy array) and already on the cluster (a dask array persisted
    there, ON_CLUSTER_ROWS rows a block): wall time and the CPU seconds of the client's process (with
    the scheduler) and of the workers."""
    import dask.array as da
    import distributed

    import eom.distributed as ed

    n = args.points
    on_cluster = {}
    for w, cl in clients.items():
        ed.stability(bike, pts[:1000], client=cl)  # warm up: ship and compile
        # Set-up, not timed: the array goes to the cluster through its task graph (Dask
        # warns of a large graph) and stays there.
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            on_cluster[w] = cl.persist(da.from_array(pts, chunks=(ON_CLUSTER_ROWS, -1)))
            distributed.wait(on_cluster[w])
    kinds = {"from the client": lambda w: pts, "on the cluster": lambda w: on_cluster[w]}
    runs = {(k, w): [] for k in kinds for w in clients}
    for _ in range(args.repeat):
        for k, points in kinds.items():
            for w, cl in clients.items():
                # One worker on one core (a node of one core) against two workers sharing
                # the two cores (each takes its share: one thread).
                threads = 1 if w == 1 else None
                c0 = cpu_seconds(cl)
                t = time.perf_counter()
                ed.stability(bike, points(w), client=cl, threads=threads)
                wall = time.perf_counter() - t
                c1 = cpu_seconds(cl)
                runs[k, w].append((wall,) + tuple(b - a for a, b in zip(c0, c1)))
    for k in kinds:
        s = {}
        for w in clients:
            v = runs[k, w]
            s[w] = stats([r[0] for r in v])
            med = [sorted(r[i] for r in v)[len(v) // 2] for i in range(3)]
            print(f"stability on {w} worker(s), points {k}: {n / s[w][0]:.0f} points/s "
                  f"(median {n / s[w][1]:.0f}); median CPU s: client with scheduler "
                  f"{med[1]:.2f}, workers {med[2]:.2f} (wall {med[0]:.2f})")
        print(f"  2 workers over 1, points {k}: {s[1][0] / s[2][0]:.2f}x (medians "
              f"{s[1][1] / s[2][1]:.2f}x); {load()}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--dask", action="store_true")
    ap.add_argument("--dask-only", action="store_true", help="only the Dask sweeps")
    args = ap.parse_args()
    bike, pts = bicycle_points(args.points)
    if args.dask_only:
        return dask_main(bike, pts, args)
    bike.evaluate(pts[:10])  # compile once
    rust, py = [], []
    for _ in range(args.repeat):
        rust.append(bike._native._evaluate_seconds(pts))
        t = time.perf_counter()
        bike.evaluate(pts)
        py.append(time.perf_counter() - t)
    (r0, r1), (p0, p1) = stats(rust), stats(py)
    print(f"evaluate: {args.points} points, Rust {r0:.3f} s (median {r1:.3f}), Python "
          f"{p0:.3f} s (median {p1:.3f}), overhead {100 * (p0 / r0 - 1):.1f} % "
          f"(medians {100 * (p1 / r1 - 1):.1f} %); {load()}")
    kw = dict(zip(bike.parameters, pts[0]))
    items = [(k, float(v)) for k, v in kw.items()]
    # The baseline: the same linearization in Rust alone (no conversions), interleaved with
    # the Python calls round by round, so that both see the same load; the smallest and the
    # median per-call time of 40 rounds of 200 calls.
    calls = {
        "rust": None,
        "creation": lambda: bike.linearize(method="symbolic", **kw),
        "with .A": lambda: bike.linearize(method="symbolic", **kw).A,
        "with A-D, names, warnings": lambda: _touch(bike.linearize(method="symbolic", **kw)),
    }
    times = {k: [] for k in calls}
    n = 200
    for _ in range(40):
        for k, f in calls.items():
            if f is None:
                times[k].append(bike._native._linearize_seconds("symbolic", items, n))
                continue
            t = time.perf_counter()
            for _ in range(n):
                f()
            times[k].append((time.perf_counter() - t) / n)
    stat = {k: (min(v), sorted(v)[len(v) // 2]) for k, v in times.items()}
    rs = stat.pop("rust")
    print(f"LinearModel (bicycle, symbolic): Rust linearization {1e6 * rs[0]:.1f} µs "
          f"(median {1e6 * rs[1]:.1f}); beyond it (min / median):")
    for k, (lo, med) in stat.items():
        print(f"  {k}: {1e6 * (lo - rs[0]):.1f} / {1e6 * (med - rs[1]):.1f} µs")
    print(f"  ({load()})")
    if args.dask:
        dask_main(bike, pts, args)


def dask_main(bike, pts, args):
    import distributed

    bike.evaluate(pts[:10])  # compile once
    for threads in (None, 1):
        t = stats([best(lambda: bike.stability(pts, threads=threads), repeat=1)
                   for _ in range(args.repeat)])
        print(f"stability local, {threads or 'all'} thread(s): {args.points / t[0]:.0f} "
              f"points/s (median {args.points / t[1]:.0f}); {load()}")
    clusters = {
        w: distributed.LocalCluster(n_workers=w, threads_per_worker=1,
                                    dashboard_address=None,
                                    silence_logs=logging.CRITICAL)
        for w in (1, 2)
    }
    clients = {w: distributed.Client(c) for w, c in clusters.items()}
    try:
        dask_sweeps(bike, pts, clients, args)
    finally:
        for w in clients:
            clients[w].close()
            clusters[w].close()


if __name__ == "__main__":
    main()
