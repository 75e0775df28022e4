"""Rounding error of PyDy's generated C for the bicycle (bicycle6: A 6x6, B 6x2) against a
30-digit evaluation of the same sympy expressions, at 1024 points within +-20 % of nominal
(all 27 parameters, independently uniform). Needs bicycle_lin.pkl (derive_bicycle.py) and
pydy_bicycle6.c (gen_bicycle.py); compiles the C alone with gcc -O2 into a shared library.

Measures over every nonzero entry of A and B and every point:
  * entrywise, of B and of A separately:  |C - ref| / |ref|
  * row-scaled: |C - ref| / max |ref| over the entry's row of [A B]
Entries that are zero in exact arithmetic although sympy's expression is not (A[0, 4]: the
yaw rate does not depend on the roll rate) have a reference below 1e-20 of their row and
are left out of the entrywise measures (PyDy computes rounding noise there). The entrywise
error of A is dominated by entries whose value passes near zero inside the box.
"""
import ctypes
import pickle
import subprocess
import sys

import mpmath
import numpy as np
import sympy as sm

N = int(sys.argv[1]) if len(sys.argv) > 1 else 1024
mpmath.mp.dps = 30

d = pickle.load(open('./bicycle_lin.pkl', 'rb'))
P = d['params']
A4, B4, A_full = d['A4'], d['B4'], d['A_full']
names = [str(p) for p in P]
v = P[names.index('v')]
# The same matrices as gen_bicycle.py's bicycle6.
A6 = sm.zeros(6, 6)
A6[0, 2:6] = A_full.extract([0], [1, 2, 3, 4])
A6[1, 0] = v
A6[2:6, 2:6] = A4
B6 = sm.zeros(6, 2)
B6[2:6, :] = B4  # [T_phi, T_delta], as gen_bicycle.py
nominal = [1.02, 0.08, np.pi / 10, 9.81, 5.0, 0.3, 2.0, 0.0603, 0.12, 0.3, -0.9, 85.0,
           9.2, 11.0, 2.8, 2.4, 0.9, -0.7, 4.0, 0.05892, 0.06, 0.00708, -0.00756,
           0.35, 3.0, 0.1405, 0.28]

subprocess.run(['gcc', '-O2', '-shared', '-fPIC', '-o', 'libpydy_bicycle6.so',
                'pydy_bicycle6.c'], check=True)
lib = ctypes.CDLL('./libpydy_bicycle6.so')
dbl = ctypes.POINTER(ctypes.c_double)
lib.bicycle6_pydy.argtypes = [dbl] * 5

entries = [(i, j) for i in range(6) for j in range(6) if A6[i, j] != 0]
bentries = [(i, j) for i in range(6) for j in range(2) if B6[i, j] != 0]
exprs = [A6[i, j] for i, j in entries] + [B6[i, j] for i, j in bentries]
rows = [i for i, _ in entries] + [i for i, _ in bentries]
ref_fn = sm.lambdify([P], exprs, modules='mpmath', cse=True)

rng = np.random.default_rng(20261126)
nA = len(entries)
worst = {'A': (0.0, None), 'B': (0.0, None), 'row': (0.0, None)}


def raise_(key, e, n, x):
    if e > worst[key][0]:
        worst[key] = (e, (n, float(x)))



for k in range(N):
    p = [x * rng.uniform(0.8, 1.2) for x in nominal]
    pin = (ctypes.c_double * 27)(*p)
    a, b = (ctypes.c_double * 36)(), (ctypes.c_double * 12)()
    c, dd = (ctypes.c_double * 12)(), (ctypes.c_double * 4)()
    lib.bicycle6_pydy(pin, a, b, c, dd)
    got = [a[6 * i + j] for i, j in entries] + [b[2 * i + j] for i, j in bentries]
    ref = ref_fn([mpmath.mpf(x) for x in p])
    rowmax = {}
    for r, x in zip(rows, ref):
        rowmax[r] = max(rowmax.get(r, 0), abs(x))
    for n, (g, x) in enumerate(zip(got, ref)):
        err = abs(mpmath.mpf(g) - x)
        raise_('row', float(err / rowmax[rows[n]]), n, x)
        if abs(x) > 1e-20 * rowmax[rows[n]]:
            raise_('A' if n < nA else 'B', float(err / abs(x)), n, x)


def label(key):
    e, (n, x) = worst[key]
    at = ('A[%d,%d]' % entries[n]) if n < nA else ('B[%d,%d]' % bentries[n - nA])
    return '%.3e (%s = %.4g)' % (e, at, x)


print('PyDy bicycle6, %d points: max entrywise relative error of B %s, of A %s; '
      'max row-scaled error %s' % (N, label('B'), label('A'), label('row')))
