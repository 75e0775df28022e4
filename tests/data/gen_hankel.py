#!/usr/bin/env python3
"""Reference Hankel singular values of the chain of 50 masses (`chain50`) and the quarter car
(`quarter_car`) at their default parameters, for tests/tests/reduction.rs.

Both models are built here from their physics, independently of eom (the Hankel singular values
do not depend on the choice of state coordinates):

* chain50: N = 50 equal masses m = 1 kg on sliders, link i (spring k = 1 N/m and damper
  c = 0.1 N s/m) between mass i and mass i-1, link 1 to the ground; input the force on mass 50,
  output the position of mass 50.  x = [positions; velocities], M x'' + C x' + K x = B f.
* quarter_car: sprung mass ms = 500 kg, unsprung mu = 50 kg, suspension ks = 18000 N/m,
  cs = 1500 N s/m, tyre kt = 180000 N/m, ct = 500 N s/m; input the road displacement z_g
  (the tyre force is kt (z_g - z_u) + ct (z_g' - z_u')); outputs z_s, z_s - z_u, z_u - z_g.
  The rate input is removed by the state w_u = v_u - (ct/mu) z_g.

Two computations of each Hankel singular value sigma_i = sqrt(lambda_i(P Q)), with
A P + P A^T + B B^T = 0 and A^T Q + Q A + C^T C = 0:

1. "scipy": P and Q by SciPy's solve_continuous_lyapunov (Bartels-Stewart, LAPACK trsyl),
   sigma_i from the symmetric eigendecompositions P = Vp diag(p) Vp^T, Q = Vq diag(q) Vq^T
   (negative rounding residues set to 0): the singular values of diag(sqrt q) Vq^T Vp diag(sqrt p).
   In double precision: P and Q carry absolute errors of about eps*||P||, eps*||Q||, so a
   sigma_i far below sigma_1 is not resolved (the "scipy_resolved" flag: sigma_i^2 above
   1e6 eps ||P|| ||Q||, where the relative error is below about 1e-9).
2. "mpmath": the same equations at 40 significant digits (mpmath), solved in the modal
   coordinates of A (A = V diag(lambda) V^-1 by mp.eig; the gramians there are
   P^_ij = -(b^ b^H)_ij / (lambda_i + conj(lambda_j)), b^ = V^-1 B, and likewise Q^ with
   c^ = C V), sigma_i^2 the eigenvalues of P^ Q^ (similar to P Q) by mp.eig. Every value is
   printed to 17 significant digits.

Regenerate (from the repository root; CI does not run Python; about 10 minutes, mpmath):

    pip install numpy scipy mpmath
    python3 tests/data/gen_hankel.py > tests/data/hankel.json

Versions used for the committed hankel.json are written into it.
"""

import json
import sys

import mpmath as mp
import numpy as np
import scipy
import scipy.linalg as sl


def chain(N, m, k, c, num=float):
    """M, K, C of the chain (link i between mass i and mass i-1, link 0 to ground)."""
    K = [[num(0)] * N for _ in range(N)]
    D = [[num(0)] * N for _ in range(N)]
    for i in range(N):
        K[i][i] += k
        D[i][i] += c
        if i > 0:
            K[i - 1][i - 1] += k
            D[i - 1][i - 1] += c
            K[i][i - 1] -= k
            K[i - 1][i] -= k
            D[i][i - 1] -= c
            D[i - 1][i] -= c
    n = 2 * N
    A = [[num(0)] * n for _ in range(n)]
    for i in range(N):
        A[i][N + i] = num(1)
        for j in range(N):
            A[N + i][j] = -K[i][j] / m
            A[N + i][N + j] = -D[i][j] / m
    B = [[num(0)] for _ in range(n)]
    B[n - 1][0] = num(1) / m
    C = [[num(0)] * n]
    C[0][N - 1] = num(1)
    return A, B, C


def quarter_car(ms, mu, ks, kt, cs, ct, num=float):
    """x = [z_u, z_s, w_u, v_s], w_u = v_u - (ct/mu) z_g, input z_g."""
    g = ct / mu
    # v_u = w_u + g z_g
    # mu v_u' = -kt z_u - ct v_u + kt z_g + ct z_g' - ks (z_u - z_s) - cs (v_u - v_s)
    # w_u' = v_u' - g z_g'  (the z_g' terms cancel)
    A = [
        [num(0), num(0), num(1), num(0)],
        [num(0), num(0), num(0), num(1)],
        [-(kt + ks) / mu, ks / mu, -(ct + cs) / mu, cs / mu],
        [ks / ms, -ks / ms, cs / ms, -cs / ms],
    ]
    B = [
        [g],
        [num(0)],
        [kt / mu - (ct + cs) / mu * g],
        [cs / ms * g],
    ]
    C = [
        [num(0), num(1), num(0), num(0)],
        [-num(1), num(1), num(0), num(0)],
        [num(1), num(0), num(0), num(0)],
    ]
    return A, B, C


def hsv_scipy(A, B, C):
    A, B, C = (np.array(x, dtype=float) for x in (A, B, C))
    P = sl.solve_continuous_lyapunov(A, -B @ B.T)
    Q = sl.solve_continuous_lyapunov(A.T, -C.T @ C)
    P, Q = (P + P.T) / 2, (Q + Q.T) / 2
    p, Vp = np.linalg.eigh(P)
    q, Vq = np.linalg.eigh(Q)
    Lp = Vp * np.sqrt(np.maximum(p, 0))
    Lq = Vq * np.sqrt(np.maximum(q, 0))
    s = np.linalg.svd(Lq.T @ Lp, compute_uv=False)
    floor = 1e6 * np.finfo(float).eps * np.linalg.norm(P, 2) * np.linalg.norm(Q, 2)
    return [float(x) for x in s], [bool(x * x > floor) for x in s]


def hsv_mpmath(A, B, C):
    A, B, C = mp.matrix(A), mp.matrix(B), mp.matrix(C)
    n = A.rows
    lam, V = mp.eig(A)
    Vi = mp.inverse(V)
    b = Vi * B
    c = C * V
    P = mp.matrix(n, n)
    Q = mp.matrix(n, n)
    for i in range(n):
        for j in range(n):
            bb = sum(b[i, k] * mp.conj(b[j, k]) for k in range(b.cols))
            cc = sum(mp.conj(c[k, i]) * c[k, j] for k in range(c.rows))
            P[i, j] = -bb / (lam[i] + mp.conj(lam[j]))
            Q[i, j] = -cc / (mp.conj(lam[i]) + lam[j])
    ev = mp.eig(P * Q, left=False, right=False)
    s = sorted((mp.sqrt(abs(mp.re(x))) for x in ev), reverse=True)
    return [mp.nstr(x, 17, min_fixed=-1, max_fixed=-1) for x in s]


def main():
    mp.mp.dps = 40
    cases = []
    for name, build, args in [
        ("quarter_car", quarter_car, (500, 50, 18000, 180000, 1500, 500)),
        ("chain50", chain, (50, 1, 1, "0.1")),
    ]:
        fargs = [float(a) if isinstance(a, str) else a for a in args]
        s, resolved = hsv_scipy(*build(*fargs))
        margs = [mp.mpf(a) if isinstance(a, str) else a for a in args]
        if name == "chain50":
            margs = [args[0]] + [mp.mpf(a) for a in args[1:]]
        else:
            margs = [mp.mpf(a) for a in args]
        m = hsv_mpmath(*build(*margs, num=mp.mpf))
        print(f"{name}: done", file=sys.stderr)
        cases.append(
            {
                "model": name,
                "scipy": s,
                "scipy_resolved": resolved,
                "mpmath": [float(x) for x in m],
                "mpmath_text": m,
            }
        )
    out = {
        "source": "tests/data/gen_hankel.py: SciPy solve_continuous_lyapunov (Bartels-Stewart) "
        "and mpmath (40 digits, modal coordinates) on the models built from their physics",
        "versions": {
            "numpy": np.__version__,
            "scipy": scipy.__version__,
            "mpmath": mp.__version__,
            "python": sys.version.split()[0],
        },
        "cases": cases,
    }
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
