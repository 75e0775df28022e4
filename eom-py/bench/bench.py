"""Benchmarks of the Python package (see docs/python.md for the figures and the load).

    python eom-py/bench/bench.py [--points N] [--dask]

1. Model.evaluate over N random bicycle points against the Rust-only time of the same
   evaluation (no copies to or from Python): the per-point overhead of the Python layer.
2. LinearModel creation beyond the Rust linearization (symbolic method, cached tape), the
   baseline the same linearization timed in Rust alone in the same run; also with the
   matrices and names read (they are converted on first use).
3. With --dask: Model.stability points/s locally and on a LocalCluster of 1 and 2 workers.
"""

import argparse
import time

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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--dask", action="store_true")
    args = ap.parse_args()
    bike, pts = bicycle_points(args.points)
    bike.evaluate(pts[:10])  # compile once
    rust = min(bike._native._evaluate_seconds(pts) for _ in range(3))
    py = best(lambda: bike.evaluate(pts))
    print(f"evaluate: {args.points} points, Rust {rust:.3f} s, Python {py:.3f} s, "
          f"overhead {100 * (py / rust - 1):.1f} %")
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
    if args.dask:
        import distributed

        import eom.distributed as ed

        t = best(lambda: bike.stability(pts), repeat=1)
        print(f"stability local: {args.points / t:.0f} points/s")
        for workers in (1, 2):
            with distributed.LocalCluster(n_workers=workers, threads_per_worker=1,
                                          dashboard_address=None) as c, distributed.Client(c) as cl:
                ed.stability(bike, pts[:1000], client=cl)  # warm up: ship and compile
                t = best(lambda: ed.stability(bike, pts, client=cl), repeat=1)
                print(f"stability on {workers} worker(s): {args.points / t:.0f} points/s")


if __name__ == "__main__":
    main()
