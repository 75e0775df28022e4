"""Load the symbolic linearization (bicycle_lin.pkl from derive_bicycle.py),
check it numerically against the Meijaard et al. (2007) benchmark, and run
PyDy's C code generator (cse=True) on

  * bicycle4: A (4x4, [phi, delta, phid, deltad]) and B (4x2, [T_phi, T_delta])
  * bicycle6: A (6x6, [psi, y, phi, delta, phid, deltad]), B (6x2, [T_phi, T_delta]),
              C (2x6, outputs [delta, phi]), D (2x2)  -- the same shapes as our
              generated `bicycle` module (different but equivalent state choice).

The psi row is the sympy-linearized yaw kinematics (row q1' of the full
linearization); the lateral-position row y' = v*psi (rear contact) is added by
hand.
"""
import pickle
import sys

import numpy as np
import sympy as sm

from pydy_common import write_pydy

d = pickle.load(open('./bicycle_lin.pkl', 'rb'))
P = d['params']
A4, B4, A_full, B_full = d['A4'], d['B4'], d['A_full'], d['B_full']
names = [str(p) for p in P]
nominal = [1.02, 0.08, np.pi / 10, 9.81, 5.0, 0.3, 2.0, 0.0603, 0.12, 0.3, -0.9, 85.0,
           9.2, 11.0, 2.8, 2.4, 0.9, -0.7, 4.0, 0.05892, 0.06, 0.00708, -0.00756,
           0.35, 3.0, 0.1405, 0.28]
iv = names.index('v')

# ---- numerical sanity check against the benchmark ------------------------
fA = sm.lambdify([P], A4, 'numpy')
fB = sm.lambdify([P], B4, 'numpy')
Mb = np.array([[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]])
C1 = np.array([[0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]])
K0 = np.array([[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]])
K2 = np.array([[0, 76.59734589573222], [0, 2.65431523794604]])


def A_bench(v, g=9.81):
    Mi = np.linalg.inv(Mb)
    return np.block([[np.zeros((2, 2)), np.eye(2)],
                     [-Mi @ (g * K0 + v**2 * K2), -Mi @ (v * C1)]])


out = []
maxerr = 0
for v in [0.0, 1.0, 2.5, 4.0, 5.0, 6.0, 8.0, 10.0]:
    p = list(nominal)
    p[iv] = v
    A = np.array(fA(p), dtype=float)
    maxerr = max(maxerr, np.abs(A - A_bench(v)).max())
ev = {}
for v in [4.29, 4.30, 5.0, 6.02, 6.03]:
    p = list(nominal)
    p[iv] = v
    ev[v] = np.sort_complex(np.linalg.eigvals(np.array(fA(p), dtype=float)))
p = list(nominal)
Bn = np.array(fB(p), dtype=float)
Mi = np.linalg.inv(Mb)
out.append('max |A_sympy - A_benchmark(M,C1,K0,K2)| over v in 0..10: %.3e' % maxerr)
out.append('B (nominal) =\n%s\nbenchmark [0; M^-1] =\n%s' % (Bn, np.vstack([np.zeros((2, 2)), Mi])))
for v, e in ev.items():
    out.append('v=%.2f eig: %s  max Re = %+.5f' % (v, np.array2string(e, precision=5), e.real.max()))


# weave and capsize speeds by bisection on max real part
def maxre(v):
    p = list(nominal)
    p[iv] = v
    return np.linalg.eigvals(np.array(fA(p), dtype=float)).real.max()


def bisect(lo, hi):
    slo = maxre(lo) > 0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if (maxre(mid) > 0) == slo:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


out.append('weave speed %.6f m/s (benchmark 4.29238), capsize speed %.6f m/s (benchmark 6.02426)'
           % (bisect(4.0, 5.0), bisect(5.5, 6.5)))
txt = '\n'.join(out)
print(txt)
open('./eigcheck.txt', 'w').write(txt + '\n')
if maxerr > 1e-9:
    sys.exit('linearization does not match the benchmark')

# ---- PyDy code generation -------------------------------------------------
open('./opcounts.txt', 'a').write('--- bicycle ---\n')
write_pydy('bicycle4', list(P), [A4, B4])

v = P[iv]
# full independent state of the linearization: [q1 q2 q4 u2 u4 u5]; rows/cols
# 1..4 are [phi, delta, phid, deltad]; row 0 is psi' (yaw kinematics)
yaw_row = A_full.extract([0], [1, 2, 3, 4])
assert A_full[0, 0] == 0 and A_full[0, 5] == 0
A6 = sm.zeros(6, 6)
A6[0, 2:6] = yaw_row
A6[1, 0] = v                       # y' = v psi
A6[2:6, 2:6] = A4
B6 = sm.zeros(6, 2)
B6[2:6, :] = B4                    # [T_phi, T_delta], as eom's bicycle
C6 = sm.zeros(2, 6)
C6[0, 3] = 1                       # delta
C6[1, 2] = 1                       # phi
D6 = sm.zeros(2, 2)
print('yaw row:', sm.simplify(yaw_row))
write_pydy('bicycle6', list(P), [A6, B6, C6, D6])
