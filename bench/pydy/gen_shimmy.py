"""Shimmy (trailing wheel with lateral spring) A,B,C,D as sympy expressions
(states y, psi, psi_dot; input applied force; outputs spring force, mass
motion), written from the model's closed form, then fed to PyDy's
CMatrixGenerator (cse=True).  Writes pydy_shimmy.c / .h with function
`shimmy_pydy` (PyDy names it `evaluate`; only the name is changed)."""
import sympy as sm
from pydy.codegen.c_code import CMatrixGenerator

from pydy_common import write_pydy

m, I, k, l, x, u = sm.symbols('m I k l x u', real=True)
params = [m, I, k, l, x, u]            # order of our module's PARAM_NAMES

a = x * l                               # t4 (mass centre behind the spring)
den = I + m * l**2 * x**2               # 1/t9
s = k * (a - l)                         # t7
A = sm.Matrix([
    [0, u, a],
    [0, 0, 1],
    [-(k * a - s) / den, (a * s - k * (a - l)**2) / den, -m * u * a / den],
])
B = sm.Matrix([0, 0, -a / den])
C = sm.Matrix([[-k, s, 0], [-1, 0, 0]])
D = sm.Matrix([0, 0])

if __name__ == '__main__':
    write_pydy('shimmy', params, [A, B, C, D])
