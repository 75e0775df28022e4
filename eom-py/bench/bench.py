"""Benchmarks of the Python package (see docs/python.md for the figures and the load).

    python eom-py/bench/bench.py [--points N] [--dask]

1. Model.evaluate over N random bicycle points against the Rust-only time of the same
   evaluation (no copies to or from Python): the per-point overhead of the Python layer.
2. LinearModel creation beyond the Rust linearization (symbolic method, cached tape).
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
    n = 2000
    t_py = best(lambda: [bike.linearize(method="symbolic", **kw) for _ in range(n)]) / n
    t_rs = best(lambda: [bike._native.linearize("symbolic", list(kw.items())) for _ in range(n)]) / n
    print(f"LinearModel: {1e6 * t_py:.1f} µs per linearize, {1e6 * (t_py - t_rs):.1f} µs "
          f"beyond the native call")
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
