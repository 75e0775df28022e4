"""Lateral modes of a motorcycle-like Whipple bicycle with a fork-mounted fairing, from the
benchmark's linear equations (Meijaard, Papadopoulos, Ruina & Schwab, Proc. R. Soc. A 463
(2007) 1955-1982, App. A: M q'' + v C1 q' + (g K0 + v^2 K2) q = f, q = (phi, delta)) plus the
fairing's quasi-steady side force written out by hand. Checks eom's
`models/motorcycle_fairing.toml` (eom-cli/tests/motorcycle_fairing.rs); docs/towing-and-fairings.md.

First the formulas are checked against the benchmark's own matrices (its Table 2 values, which
this repository's bench/pydy/gen_bicycle.py also quotes).

The fairing: a side force F = -d v_f at its centre of pressure P = (xP, 0, zP) on the front
frame (benchmark axes: x forward, y right, z down), d = (rho v S / 2) a (S the fairing's side
area, a = -CYv its side-force slope per radian of sideslip), v_f the lateral air velocity of P
in the fairing's axes (still air). To first order, with the rear contact's yaw rate
psi' = (v delta + c delta') cos(lambda)/w and lateral velocity v psi (no side slip),

    v_f = psi' xP - zP phi' + eP delta' - v (psi + delta cos(lambda)) + v psi
        = jphi phi' + jdelta delta' + b delta,
    jphi = -zP,  jdelta = eP + c xP cos(lambda)/w,  b = v cos(lambda) (xP/w - 1),
    eP = (xP - w - c) cos(lambda) - zP sin(lambda)   (P's lateral arm about the steer axis).

Its virtual work F (jphi dphi + jdelta ddelta) (virtual displacements obey the constraints
without the v terms) adds the damping d J J^T and the stiffness d b J e_delta^T, J = (jphi,
jdelta): the fairing's added steer damping is C_dd = d jdelta^2.

Run: python motorcycle_fairing.py  (writes motorcycle_fairing.json)
"""
import json
import numpy as np


def matrices(p):
    """The benchmark's M, C1, K0, K2 (Meijaard et al. 2007, App. A)."""
    w, c, lam = p["w"], p["c"], p["lambda"]
    rR, mR, IRxx, IRyy = p["rR"], p["mR"], p["IRxx"], p["IRyy"]
    xB, zB, mB = p["xB"], p["zB"], p["mB"]
    IBxx, IBzz, IBxz = p["IBxx"], p["IBzz"], p["IBxz"]
    xH, zH, mH = p["xH"], p["zH"], p["mH"]
    IHxx, IHzz, IHxz = p["IHxx"], p["IHzz"], p["IHxz"]
    rF, mF, IFxx, IFyy = p["rF"], p["mF"], p["IFxx"], p["IFyy"]
    sl, cl = np.sin(lam), np.cos(lam)
    mT = mR + mB + mH + mF
    xT = (xB * mB + xH * mH + w * mF) / mT
    zT = (-rR * mR + zB * mB + zH * mH - rF * mF) / mT
    ITxx = IRxx + IBxx + IHxx + IFxx + mR * rR**2 + mB * zB**2 + mH * zH**2 + mF * rF**2
    ITxz = IBxz + IHxz - mB * xB * zB - mH * xH * zH + mF * w * rF
    IRzz, IFzz = IRxx, IFxx
    ITzz = IRzz + IBzz + IHzz + IFzz + mB * xB**2 + mH * xH**2 + mF * w**2
    mA = mH + mF
    xA = (xH * mH + w * mF) / mA
    zA = (zH * mH - rF * mF) / mA
    IAxx = IHxx + IFxx + mH * (zH - zA)**2 + mF * (rF + zA)**2
    IAxz = IHxz - mH * (xH - xA) * (zH - zA) + mF * (w - xA) * (rF + zA)
    IAzz = IHzz + IFzz + mH * (xH - xA)**2 + mF * (w - xA)**2
    uA = (xA - w - c) * cl - zA * sl
    IAll = mA * uA**2 + IAxx * sl**2 + 2 * IAxz * sl * cl + IAzz * cl**2
    IAlx = -mA * uA * zA + IAxx * sl + IAxz * cl
    IAlz = mA * uA * xA + IAxz * sl + IAzz * cl
    mu = c / w * cl
    SR, SF = IRyy / rR, IFyy / rF
    ST = SR + SF
    SA = mA * uA + mu * mT * xT
    M = np.array([[ITxx, IAlx + mu * ITxz], [IAlx + mu * ITxz, IAll + 2 * mu * IAlz + mu**2 * ITzz]])
    K0 = np.array([[mT * zT, -SA], [-SA, -SA * sl]])
    K2 = np.array([[0, (ST - mT * zT) * cl / w], [0, (SA + SF * sl) * cl / w]])
    C1 = np.array([[0, mu * ST + SF * cl + ITxz * cl / w - mu * mT * zT],
                   [-(mu * ST + SF * cl), IAlz * cl / w + mu * (SA + ITzz * cl / w)]])
    return M, C1, K0, K2


def fairing(p, v):
    """The fairing's added damping and stiffness (2x2) at speed v."""
    w, c, lam = p["w"], p["c"], p["lambda"]
    xP, zP = p["xP"], p["zP"]
    sl, cl = np.sin(lam), np.cos(lam)
    d = 0.5 * p["rho"] * v * p["Sf"] * p["af"]
    eP = (xP - w - c) * cl - zP * sl
    J = np.array([-zP, eP + c * xP * cl / w])
    b = v * cl * (xP / w - 1)
    dC = d * np.outer(J, J)
    dK = d * b * np.outer(J, [0.0, 1.0])
    return dC, dK, {"d": d, "eP": eP, "jphi": J[0], "jdelta": J[1], "b": b}


def state_matrix(p, v, with_fairing=True):
    M, C1, K0, K2 = matrices(p)
    C, K = v * C1, p["g"] * K0 + v**2 * K2
    if with_fairing:
        dC, dK, _ = fairing(p, v)
        C, K = C + dC, K + dK
    Mi = np.linalg.inv(M)
    return np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ K, -Mi @ C]])


def eig(p, v, with_fairing=True):
    z = np.linalg.eigvals(state_matrix(p, v, with_fairing))
    return sorted(z, key=lambda x: (x.real, x.imag))


# ---- the formulas against the benchmark's printed matrices -------------------------------
bench = dict(w=1.02, c=0.08, **{"lambda": np.pi / 10}, g=9.81, rR=0.3, mR=2.0, IRxx=0.0603,
             IRyy=0.12, xB=0.3, zB=-0.9, mB=85.0, IBxx=9.2, IBzz=2.8, IBxz=2.4, xH=0.9,
             zH=-0.7, mH=4.0, IHxx=0.05892, IHzz=0.00708, IHxz=-0.00756, rF=0.35, mF=3.0,
             IFxx=0.1405, IFyy=0.28)
Mb = np.array([[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]])
C1b = np.array([[0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]])
K0b = np.array([[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]])
K2b = np.array([[0, 76.59734589573222], [0, 2.65431523794604]])
for got, want in zip(matrices(bench), (Mb, C1b, K0b, K2b)):
    assert np.abs(got - want).max() < 1e-10, (got, want)

# ---- the motorcycle: the values of models/motorcycle_fairing.toml --------------------------
moto = dict(w=1.4, c=0.1, **{"lambda": 25 * np.pi / 180}, g=9.81, rR=0.31, mR=14.0,
            IRxx=0.4, IRyy=0.8, xB=0.6, zB=-0.65, mB=250.0, IBxx=30.0, IBzz=40.0, IBxz=3.0,
            xH=1.2, zH=-0.75, mH=15.0, IHxx=0.8, IHzz=0.25, IHxz=-0.15, rF=0.3, mF=10.0,
            IFxx=0.3, IFyy=0.6, rho=1.225, Sf=0.4, af=1.5, xP=1.35, zP=-0.95)

def boundaries(p):
    """Speeds where the largest real part of an eigenvalue crosses zero (1 to 40 m/s)."""
    from scipy.optimize import brentq
    f = lambda v: max(z.real for z in eig(p, v))
    grid = np.linspace(1.0, 40.0, 391)
    vals = [f(v) for v in grid]
    return [brentq(f, a, b, xtol=1e-13, rtol=1e-14)
            for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:]) if fa * fb < 0]


def sensitivity(p, v, parts=("damping", "stiffness")):
    """d lambda / d Sf at Sf = 0 by first-order perturbation: u^T dA v / u^T v (u, v the left
    and right eigenvectors), dA the fairing's part of A per unit area (its damping and its
    stiffness, or one of them)."""
    q = dict(p, Sf=1.0)
    dC, dK, _ = fairing(q, v)
    dC, dK = (dC if "damping" in parts else 0 * dC), (dK if "stiffness" in parts else 0 * dK)
    M = matrices(p)[0]
    Mi = np.linalg.inv(M)
    dA = np.block([[np.zeros((2, 2)), np.zeros((2, 2))], [-Mi @ dK, -Mi @ dC]])
    A = state_matrix(p, v, with_fairing=False)
    lam, V = np.linalg.eig(A)
    lamT, U = np.linalg.eig(A.T)
    res = []
    for k in range(4):
        j = np.argmin(abs(lamT - lam[k]))
        u, x = U[:, j], V[:, k]
        res.append((lam[k], (u @ dA @ x) / (u @ x)))
    return sorted(res, key=lambda t: (t[0].real, t[0].imag))


out = {"parameters": {k: float(v) for k, v in moto.items()}, "speeds": {}}
for v in [5.0, 10.0, 20.0, 30.0, 40.0]:
    dC, dK, parts = fairing(moto, v)
    out["speeds"][f"{v:g}"] = {
        "with_fairing": [[float(z.real), float(z.imag)] for z in eig(moto, v)],
        "without": [[float(z.real), float(z.imag)] for z in eig(moto, v, False)],
        "added_damping": dC.tolist(),
        "added_stiffness": dK.tolist(),
        "dlambda_dSf": [[float(l.real), float(l.imag), float(s.real), float(s.imag)]
                        for l, s in sensitivity(dict(moto, Sf=0.0), v)],
        "dlambda_dSf_damping_only": [[float(l.real), float(l.imag), float(s.real), float(s.imag)]
                                     for l, s in sensitivity(dict(moto, Sf=0.0), v, ("damping",))],
        **{k: float(x) for k, x in parts.items()},
    }
out["boundaries_with_fairing"] = boundaries(moto)
out["boundaries_without"] = boundaries(dict(moto, Sf=0.0))
json.dump(out, open("motorcycle_fairing.json", "w"), indent=1)
for v, r in out["speeds"].items():
    print(v, "with", np.round(r["with_fairing"], 5).tolist())
    print(v, "w/o ", np.round(r["without"], 5).tolist(), "Cdd", r["added_damping"][1][1])
    print(v, "dlam/dSf", np.round(r["dlambda_dSf"], 6).tolist())
    print(v, "damping only", np.round(r["dlambda_dSf_damping_only"], 6).tolist())
print("boundaries with", out["boundaries_with_fairing"], "without", out["boundaries_without"])
