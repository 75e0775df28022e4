"""Derive the Whipple/Meijaard benchmark bicycle with sympy.physics.mechanics
(KanesMethod) using the 27 benchmark parameters directly (all symbolic), and
linearize about upright straight running at speed v.

Conventions (benchmark): x forward, y right, z down; rear contact at origin in
the reference configuration; roll phi about the yaw-frame x axis; steer delta
about the steer axis (pointing down); rear-frame pitch theta is the dependent
coordinate.  Output: bicycle_lin.pkl with A (4x4, states [phi, delta, phid,
deltad]), B (4x2, inputs [T_phi, T_delta]) as sympy expressions.
"""
import pickle
import time

import sympy as sm
import sympy.physics.mechanics as me

t0 = time.time()
# 27 benchmark parameters, in the order of our module's PARAM_NAMES
names = ("w c lambda g v rR mR IRxx IRyy xB zB mB IBxx IByy IBzz IBxz "
         "xH zH mH IHxx IHyy IHzz IHxz rF mF IFxx IFyy")
P = sm.symbols(names, real=True)
(w, c, lam, g, v, rR, mR, IRxx, IRyy, xB, zB, mB, IBxx, IByy, IBzz, IBxz,
 xH, zH, mH, IHxx, IHyy, IHzz, IHxz, rF, mF, IFxx, IFyy) = P

# coordinates: yaw, roll, pitch (dependent), steer
q1, q2, q3, q4 = me.dynamicsymbols('q1 q2 q3 q4')
# speeds: yaw rate, roll rate, pitch rate, steer rate, rear wheel, front wheel
u1, u2, u3, u4, u5, u6 = me.dynamicsymbols('u1 u2 u3 u4 u5 u6')
T_phi, T_delta = me.dynamicsymbols('T_phi T_delta')

N = me.ReferenceFrame('N')
Yf = N.orientnew('Y', 'Axis', [q1, N.z])      # yaw
Rf = Yf.orientnew('R', 'Axis', [q2, Yf.x])    # roll
C = Rf.orientnew('C', 'Axis', [q3, Rf.y])     # rear frame (pitch)
D = C.orientnew('D', 'Axis', [lam, C.y])      # D.z = steer axis (down)
E = D.orientnew('E', 'Axis', [q4, D.z])       # front frame (steer)
Ep = E.orientnew('Ep', 'Axis', [-lam, E.y])   # front frame, aligned with C at delta=0
WR = me.ReferenceFrame('WR')
WF = me.ReferenceFrame('WF')

Yf.set_ang_vel(N, u1 * N.z)
Rf.set_ang_vel(Yf, u2 * Yf.x)
C.set_ang_vel(Rf, u3 * Rf.y)
E.set_ang_vel(C, u4 * D.z)
WR.set_ang_vel(C, u5 * C.y)
WF.set_ang_vel(E, u6 * E.y)


def in_E(ax, az):
    """Vector fixed in the front frame whose C-components at delta=0 are (ax, 0, az)."""
    vec = ax * C.x + az * C.z
    return sm.trigsimp(vec.dot(D.x)) * E.x + sm.trigsimp(vec.dot(D.z)) * E.z


# points
cR = me.Point('cR')                            # rear contact (fixed in WR, at rest)
oR = cR.locatenew('oR', -rR * Rf.z)            # rear wheel centre
S = oR.locatenew('S', (w + c) * C.x + rR * C.z)  # steer axis / ground point at ref
Bo = oR.locatenew('Bo', xB * C.x + (zB + rR) * C.z)
oF = S.locatenew('oF', in_E(-c, -rF))          # front wheel centre
Ho = S.locatenew('Ho', in_E(xH - w - c, zH))   # front frame mass centre
dn = (N.z - E.y.dot(N.z) * E.y)
cF = oF.locatenew('cF', rF * dn.normalize())   # front contact

cR.set_vel(N, 0)
oR.v2pt_theory(cR, N, WR)
S.v2pt_theory(oR, N, C)
Bo.v2pt_theory(oR, N, C)
oF.v2pt_theory(S, N, E)
Ho.v2pt_theory(S, N, E)
cF.v2pt_theory(oF, N, WF)

kd = [q1.diff() - u1, q2.diff() - u2, q3.diff() - u3, q4.diff() - u4]
con_vel = [cF.vel(N).dot(Yf.x), cF.vel(N).dot(Yf.y), cF.vel(N).dot(Yf.z)]
con_pos = [cF.pos_from(cR).dot(N.z)]

bodies = [
    me.RigidBody('B', Bo, C, mB, (me.inertia(C, IBxx, IByy, IBzz, 0, 0, IBxz), Bo)),
    me.RigidBody('H', Ho, E, mH, (me.inertia(Ep, IHxx, IHyy, IHzz, 0, 0, IHxz), Ho)),
    me.RigidBody('R', oR, WR, mR, (me.inertia(C, IRxx, IRyy, IRxx), oR)),
    me.RigidBody('F', oF, WF, mF, (me.inertia(E, IFxx, IFyy, IFxx), oF)),
]
loads = [(Bo, mB * g * N.z), (Ho, mH * g * N.z), (oR, mR * g * N.z), (oF, mF * g * N.z),
         (Rf, T_phi * Yf.x), (E, T_delta * D.z), (C, -T_delta * D.z)]

KM = me.KanesMethod(N, q_ind=[q1, q2, q4], q_dependent=[q3],
                    configuration_constraints=con_pos,
                    u_ind=[u2, u4, u5], u_dependent=[u1, u3, u6],
                    velocity_constraints=con_vel, kd_eqs=kd,
                    constraint_solver='CRAMER')
fr, frstar = KM.kanes_equations(bodies, loads)
print('kanes_equations done %.1f s' % (time.time() - t0), flush=True)

op = {q1: 0, q2: 0, q3: 0, q4: 0, u1: 0, u2: 0, u3: 0, u4: 0,
      u5: -v / rR, u6: -v / rF}
op.update({ui.diff(): 0 for ui in (u1, u2, u3, u4, u5, u6)})
A, B, rvec = KM.linearize(A_and_B=True, op_point=op, linear_solver='CRAMER')
print('linearize done %.1f s' % (time.time() - t0), flush=True)
print('A shape', A.shape, 'B shape', B.shape, 'r', rvec)
print('states', KM.q[:, 0].T, KM.u[:, 0].T)

# with A_and_B=True the state is the independent one: [q1 q2 q4 u2 u4 u5]
# -> pick roll q2 (1), steer q4 (2), roll rate u2 (3), steer rate u4 (4)
assert A.shape == (6, 6), A.shape
idx = [1, 2, 3, 4]
A4 = A.extract(idx, idx)
B4 = B.extract(idx, [list(rvec).index(T_phi), list(rvec).index(T_delta)])
with open('./bicycle_lin.pkl', 'wb') as f:
    pickle.dump({'params': P, 'A_full': A, 'B_full': B, 'A4': A4, 'B4': B4,
                 'r': list(rvec)}, f)
print('saved %.1f s' % (time.time() - t0))
