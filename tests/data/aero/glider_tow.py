"""Aerotow: a tow plane and a glider in level free flight joined by an elastic rope
(models/glider_tow.toml, docs/towing-and-fairings.md), the linearised equations of the two
rigid aircraft and the rope written out by hand, as a reference for eom-cli/tests/glider_tow.rs.

Inputs: the data of the model file and each aircraft's body-axis stability derivatives, which
eom-aero's vortex lattice computes from models/avl/towplane.avl and models/avl/glider.avl
(`eom aero FILE`; eom-aero is checked against AVL in its own fixture tests). They are pasted
below (the entries below 1e-10, round-off of the symmetric geometry, are zero); CXu is -2 C_D.

Axes: model axes x forward, y left, z up; each aircraft's mass centre on the x axis (tow plane
at 0, glider at xg = -(ht + L + hg)), flying at V along x. Small perturbations: positions r_i,
small rotations th_i (about x, y, z), no rotation at trim, so M r'' = F and I th'' = M_cg.

Forces, per aircraft (to first order):
  * weight (dead) and trim lift m g z (a follower: rotates with the body): d(F) = th x (m g z);
  * tow plane: thrust less drag T x (follower): th_t x (T x); glider: drag -T x (follower);
  * the rope from the glider's nose A = (xg + hg, 0, 0) to the tow hook B = (-ht, 0, 0), length
    L, tension T + k (|d| - L), k = EA/L, d = p_B - p_A: on the glider at A
        F_A = T e + k (e.dd) e + (T/L)(dd - e (e.dd)),  e = x,
    dd = (r_t + th_t x b) - (r_g + th_g x a), a = (hg, 0, 0), b = (-ht, 0, 0); on the tow plane
    -F_A at B; moments about each mass centre from the lever (rotated) and the force (changed):
        dM_g = (th_g x a) x (T e) + a x dF_A,   dM_t = (th_t x b) x (-T e) + b x (-dF_A);
  * aerodynamics at the mass centre: the body-axis air velocity of the reference point
    u_b = r' - V (th x x) = (x', y' - V th_z, z' + V th_y), rates w = th', turned into AVL's
    axes (x forward, y right, z down: y, z change sign), then forces q S C (per u/V, v/V, w/V,
    p b/2V, q c/2V, r b/2V) and moments q S (b Cl, c Cm, b Cn), turned back.

Run: python glider_tow.py  (writes glider_tow.json)
"""
import json
import numpy as np

CASES = {
    "defaults": {},
    "EA=5000": {"EA": 5000.0},
    "ht=2": {"ht": 2.0},
    "T=0": {"T": 0.0},
}
NOMINAL = dict(EA=50000.0, L=50.0, T=194.0, V=35.0, rho=1.225, g=9.81,
               mt=1000.0, Ixt=1300.0, Iyt=1800.0, Izt=2800.0, CDt=0.055, ht=5.2,
               mg=500.0, Ixg=3000.0, Iyg=1100.0, Izg=3900.0, CDg=0.0145, hg=3.4)
# Reference geometry of the .avl files: S, c, b.
REF = {"tow": (17.12, 1.6, 10.7), "glider": (17.85, 1.05, 17.0)}
DERIV = {
    "tow": dict(CXw=0.4321912529246009, CXq=-0.606032773667894,
                CYv=-0.13405688978458177, CYp=0.13408432621412253, CYr=0.13140174856999962,
                CZu=-1.5269162956570712, CZw=-4.702080100494211, CZq=-7.681640798693271,
                Clv=-0.11376117374899591, Clp=-0.4718876391067873, Clr=0.20069407124764355,
                Cmu=0.0001357616308439246, Cmw=-0.6594854607071274, Cmq=-9.62541768867688,
                Cnv=0.051107796907442014, Cnp=-0.05289267060289614, Cnr=-0.05698243680918262),
    "glider": dict(CXw=0.28096552936909247, CXq=-0.14657109895588005,
                   CYv=-0.15863943047549933, CYp=-0.07873557153409992, CYr=0.11295731693634836,
                   CZu=-0.7321571488411495, CZw=-5.726364696835284, CZq=-9.44602649586262,
                   Clv=-0.07344674174703684, Clp=-0.634340754093201, Clr=0.09776223995766176,
                   Cmu=6.682965802356871e-06, Cmw=-1.4002088346787562, Cmq=-21.17988375085219,
                   Cnv=0.03984976423705242, Cnp=-0.03358049172361187, Cnr=-0.029331371043380475),
}


def skew(a):
    return np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])


def aero(p, which):
    """(D_pos, D_vel): the aerodynamic force and moment (model axes, 6) per (r, th) and per
    (r', th') of one aircraft."""
    S, c, b = REF[which]
    V, rho = p["V"], p["rho"]
    q = 0.5 * rho * V * V
    C = np.zeros((6, 6))
    rows, cols = "XYZlmn", "uvwpqr"
    for k, x in DERIV[which].items():
        C[rows.index(k[1]), cols.index(k[2])] = x
    C[0, 0] = -2 * (p["CDt"] if which == "tow" else p["CDg"])
    # AVL variables per model-axis body velocities: u/V, v/V, w/V, p b/2V, q c/2V, r b/2V.
    flip = np.diag([1, -1, -1])
    scale_in = np.diag([1 / V] * 3 + [b / (2 * V), c / (2 * V), b / (2 * V)])
    to_avl = np.block([[flip, np.zeros((3, 3))], [np.zeros((3, 3)), flip]])
    scale_out = np.diag([q * S] * 3 + [q * S * b, q * S * c, q * S * b])
    G = to_avl @ scale_out @ C @ scale_in @ to_avl  # force/moment per (u_b, w) in model axes
    # u_b = r' + V (0, -th_z, th_y): the position part through th.
    P = np.zeros((6, 6))
    P[1, 5], P[2, 4] = -V, V
    return G[:, :3] @ P[:3, :] + 0 * P, G


def state_matrix(p):
    """24 states: r_t, th_t, r_g, th_g, then their rates."""
    g, T, L, k = p["g"], p["T"], p["L"], p["EA"] / p["L"]
    e = np.array([1.0, 0, 0])
    a, b = np.array([p["hg"], 0, 0]), np.array([-p["ht"], 0, 0])
    Kf = np.zeros((12, 12))  # generalised force per position: [F_t, M_t, F_g, M_g]
    Cf = np.zeros((12, 12))
    # Follower loads at the mass centres: dF = th x f0 = -skew(f0) th.
    for i, f0 in ((0, np.array([T, 0, p["mt"] * g])), (6, np.array([-T, 0, p["mg"] * g]))):
        Kf[i:i + 3, i + 3:i + 6] += -skew(f0)
    # The rope: dd = (r_t - skew(b) th_t) - (r_g - skew(a) th_g).
    Jd = np.zeros((3, 12))
    Jd[:, 0:3], Jd[:, 3:6] = np.eye(3), -skew(b)
    Jd[:, 6:9], Jd[:, 9:12] = -np.eye(3), skew(a)
    Kr = k * np.outer(e, e) + T / L * (np.eye(3) - np.outer(e, e))  # dF_A per dd
    dFA = Kr @ Jd
    Kf[6:9] += dFA
    Kf[9:12] += skew(a) @ dFA
    Kf[9:12, 9:12] += -skew(T * e) @ (-skew(a))    # (th x a) x T e = -skew(Te)(th x a)
    Kf[0:3] -= dFA
    Kf[3:6] -= skew(b) @ dFA
    Kf[3:6, 3:6] += -skew(-T * e) @ (-skew(b))     # (th x b) x (-T e)
    for i, which in ((0, "tow"), (6, "glider")):
        Dp, Dv = aero(p, which)
        Kf[i:i + 6, i:i + 6] += Dp
        Cf[i:i + 6, i:i + 6] += Dv
    Mm = np.diag([p["mt"]] * 3 + [p["Ixt"], p["Iyt"], p["Izt"]] + [p["mg"]] * 3
                 + [p["Ixg"], p["Iyg"], p["Izg"]])
    Mi = np.linalg.inv(Mm)
    return np.block([[np.zeros((12, 12)), np.eye(12)], [Mi @ Kf, Mi @ Cf]])


out = {}
for name, change in CASES.items():
    p = dict(NOMINAL, **change)
    z = np.linalg.eigvals(state_matrix(p))
    z = sorted(z, key=lambda x: (x.real, x.imag))
    out[name] = {"set": change, "eigenvalues": [[float(x.real), float(x.imag)] for x in z]}
    print(name, np.round(z, 6).tolist())
json.dump(out, open("glider_tow.json", "w"), indent=1)
