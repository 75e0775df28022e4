#!/usr/bin/env python3
"""Reference data for eom-num's minimal-realization and transmission-zero tests, computed by
python-control (SLICOT TB01PD for minreal, AB08ND for zeros, through slycot).

Regenerate (from the repository root; CI does not run Python):

    python3 -m venv /tmp/pyc
    /tmp/pyc/bin/pip install control slycot numpy
    /tmp/pyc/bin/python eom-num/tests/data/gen_pycontrol.py > eom-num/tests/data/pycontrol.json

Versions used for the committed pycontrol.json (also written into the file):
python-control 0.10.2, slycot 0.7.1, numpy 2.4.6, scipy 1.17.1, Python 3.11.7.

What is stored per system: A, B, C, D (row-major lists); the order the system has by
construction ("expected_order": the size of the controllable and observable block we built);
python-control's minreal result as invariants only (state count, poles of the minimal system,
its transfer function at the fixed complex points below); python-control's zeros; and, as an
independent check of python-control, the transfer function of the *original* system at the same
points computed here by a plain complex solve C (sI - A)^-1 B + D. Bases of minimal realizations
are not unique, so no matrices of the reduced systems are stored.

Systems (fixed seed): random dense ones (n 1-10, m, p 1-3, D zero or not); ones with an
uncontrollable part, an unobservable part, or all four Kalman parts, each built block-structured
and hidden by a random similarity transform that is orthogonal times a diagonal with entries in
[0.5, 2] (condition number at most 4, so the hidden zero blocks stay at rounding level); square
systems with invertible D (their zeros are also eig(A - B D^-1 C)); and non-square ones.

Where python-control is wrong on this data (checked in eom-num/tests/pycontrol.rs):
* unobservable_9: minreal keeps 5 states instead of 4 (TB01PD's default tolerance is below the
  rounding of the hidden block; with tol=1e-12 it keeps 4). Its transfer function is right.
* kalman_4: zeros() misses the two input-decoupling zeros of this 3-input, 2-output system
  (AB08ND's default tolerance; with tol=1e-12 it finds them).
* random_4, square_d_2 (n = 1, m = p = 3): zeros() raises SlycotParameterError ('ldwork', the
  slycot wrapper's default workspace is below AB08ND's minimum); see pc_zeros below.
"""

import json
import sys

import numpy as np
import scipy
import scipy.linalg
import control
import slycot
import slycot.exceptions

SEED = 20261121
POINTS = [0.3 + 1.1j, -0.7 + 2.3j, 1.9 - 0.4j, 0.05 + 0.5j]
rng = np.random.default_rng(SEED)


def orth(n):
    q, r = np.linalg.qr(rng.standard_normal((n, n)))
    return q * np.sign(np.diag(r))


def similarity(n):
    """A random similarity T = Q diag(d), d in [0.5, 2]: cond(T) <= 4."""
    return orth(n) @ np.diag(2.0 ** rng.uniform(-1, 1, n))


def rand(r, c):
    return rng.standard_normal((r, c))


def tf(a, b, c, d, s):
    n = a.shape[0]
    if n == 0:
        return d.astype(complex)
    return c @ np.linalg.solve(s * np.eye(n) - a, b) + d


def far_from_points(a):
    ev = np.linalg.eigvals(a) if a.shape[0] else np.array([])
    return all(np.min(np.abs(ev - s)) > 0.05 for s in POINTS) if len(ev) else True


def cplx_list(v):
    return [[float(z.real), float(z.imag)] for z in v]


def sort_c(v):
    return sorted(v, key=lambda z: (z.real, z.imag))


def pc_zeros(sys_):
    """python-control's zeros(). slycot 0.7.1's ab08nd wrapper passes a default workspace
    n + 3 max(m, p) that is below AB08ND's documented minimum for some shapes (n = 1,
    m = p = 3 raises SlycotParameterError 'ldwork'); then call ab08nd with a sufficient
    workspace and post-process exactly as python-control's StateSpace.zeros does."""
    try:
        return sort_c(np.asarray(sys_.zeros(), dtype=complex)), None
    except slycot.exceptions.SlycotParameterError:
        a, b, c, d = (np.asarray(x) for x in (sys_.A, sys_.B, sys_.C, sys_.D))
        n, m, p = a.shape[0], b.shape[1], c.shape[0]
        ldwork = max(1, min(p, m) + max(3 * m - 1, n), min(p, n) + max(3 * p - 1, n + p, n + m))
        out = slycot.ab08nd(n, m, p, a, b, c, d, ldwork=4 * ldwork)
        nu = out[0]
        z = scipy.linalg.eigvals(out[8][:nu, :nu], out[9][:nu, :nu]) if nu else []
        return (sort_c(np.asarray(z, dtype=complex)),
                "python-control zeros() raised SlycotParameterError (ldwork); "
                "AB08ND called directly with a sufficient workspace")


def kalman(n_co, n_cu, n_uo, n_uu, m, p, with_d):
    """Kalman form x = [co, c-not-o, not-c-o, not-c-not-o] with the allowed couplings."""
    sizes = [n_co, n_cu, n_uo, n_uu]
    n = sum(sizes)
    o = np.cumsum([0] + sizes)
    blk = lambda i: slice(o[i], o[i + 1])
    a = np.zeros((n, n))
    for i in range(4):
        a[blk(i), blk(i)] = rand(sizes[i], sizes[i])
    # Allowed couplings of the Kalman canonical form.
    for i, j in [(0, 2), (1, 0), (1, 2), (1, 3), (3, 2)]:
        a[blk(i), blk(j)] = 0.5 * rand(sizes[i], sizes[j])
    b = np.zeros((n, m))
    b[blk(0), :] = rand(n_co, m)
    b[blk(1), :] = rand(n_cu, m)
    c = np.zeros((p, n))
    c[:, blk(0)] = rand(p, n_co)
    c[:, blk(2)] = rand(p, n_uo)
    d = rand(p, m) if with_d else np.zeros((p, m))
    t = similarity(n)
    ti = np.linalg.inv(t)
    return ti @ a @ t, ti @ b, c @ t, d, n_co


def make(kind, i):
    while True:
        if kind == "random":
            n = int(rng.integers(1, 11))
            m = int(rng.integers(1, 4))
            p = int(rng.integers(1, 4))
            a, b, c = rand(n, n), rand(n, m), rand(p, n)
            d = rand(p, m) if i % 2 else np.zeros((p, m))
            order = n
        elif kind == "uncontrollable":
            n_co = int(rng.integers(1, 7))
            n_uo = int(rng.integers(1, 4))
            m, p = int(rng.integers(1, 4)), int(rng.integers(1, 4))
            a, b, c, d, order = kalman(n_co, 0, n_uo, 0, m, p, i % 2 == 1)
        elif kind == "unobservable":
            n_co = int(rng.integers(1, 7))
            n_cu = int(rng.integers(1, 4))
            m, p = int(rng.integers(1, 4)), int(rng.integers(1, 4))
            a, b, c, d, order = kalman(n_co, n_cu, 0, 0, m, p, i % 2 == 1)
        elif kind == "kalman":
            sizes = [int(rng.integers(1, 5)), int(rng.integers(1, 3)),
                     int(rng.integers(1, 3)), int(rng.integers(0, 3))]
            m, p = int(rng.integers(1, 4)), int(rng.integers(1, 4))
            a, b, c, d, order = kalman(*sizes, m, p, i % 2 == 0)
        elif kind == "square_d":
            n = int(rng.integers(1, 9))
            m = p = int(rng.integers(1, 4))
            a, b, c = rand(n, n), rand(n, m), rand(p, n)
            d = orth(m) @ np.diag(rng.uniform(0.5, 2.0, m)) @ orth(m)
            order = n
        elif kind == "nonsquare":
            n = int(rng.integers(2, 11))
            m = int(rng.integers(1, 4))
            p = int(rng.integers(1, 4))
            while p == m:
                p = int(rng.integers(1, 4))
            a, b, c = rand(n, n), rand(n, m), rand(p, n)
            d = rand(p, m) if i % 2 else np.zeros((p, m))
            order = n
        else:
            raise ValueError(kind)
        if far_from_points(a):
            return a, b, c, d, order


def main():
    plan = [("random", 16), ("uncontrollable", 10), ("unobservable", 10), ("kalman", 10),
            ("square_d", 6), ("nonsquare", 8)]
    systems = []
    for kind, count in plan:
        for i in range(count):
            a, b, c, d, order = make(kind, i)
            sys_ = control.ss(a, b, c, d)
            mr = control.minreal(sys_, verbose=False)
            am, bm, cm, dm = (np.asarray(x) for x in (mr.A, mr.B, mr.C, mr.D))
            poles = sort_c(np.linalg.eigvals(am)) if am.shape[0] else []
            tf_min = [tf(am, bm, cm, dm, s) for s in POINTS]
            tf_orig = [tf(a, b, c, d, s) for s in POINTS]
            err = max(np.linalg.norm(x - y) / max(np.linalg.norm(y), 1e-300)
                      for x, y in zip(tf_min, tf_orig))
            zeros, zeros_note = pc_zeros(sys_)
            entry = {
                "name": f"{kind}_{i}",
                "kind": kind,
                "A": a.tolist(), "B": b.tolist(), "C": c.tolist(), "D": d.tolist(),
                "expected_order": int(order),
                "pc_minreal_order": int(am.shape[0]),
                "pc_minreal_poles": cplx_list(poles),
                "pc_minreal_tf": [[cplx_list(row) for row in g] for g in tf_min],
                "tf_original": [[cplx_list(row) for row in g] for g in tf_orig],
                "pc_tf_rel_error_vs_original": float(err),
                "pc_zeros": cplx_list(zeros),
            }
            if zeros_note:
                entry["pc_zeros_note"] = zeros_note
            if kind == "square_d":
                entry["zeros_via_inverse_d"] = cplx_list(
                    sort_c(np.linalg.eigvals(a - b @ np.linalg.solve(d, c))))
            systems.append(entry)
    out = {
        "source": "python-control minreal (SLICOT TB01PD) and zeros (SLICOT AB08ND), "
                  "generated by eom-num/tests/data/gen_pycontrol.py",
        "versions": {
            "python-control": control.__version__,
            "slycot": slycot.__version__,
            "numpy": np.__version__,
            "scipy": scipy.__version__,
            "python": sys.version.split()[0],
        },
        "seed": SEED,
        "points": cplx_list(POINTS),
        "systems": systems,
    }
    json.dump(out, sys.stdout, indent=None, separators=(",", ":"))
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
