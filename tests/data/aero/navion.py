"""Rigid-body flight modes of the Navion (R. C. Nelson, *Flight Stability and Automatic
Control*, 2nd ed., McGraw-Hill 1998, App. B and the Navion examples of ch. 4 and 5), from the
linearised flight equations written out by hand.

Data (consistent US units, sea level, level flight): V = 176 ft/s, rho = 0.002378 slug/ft^3,
g = 32.2 ft/s^2, W = 2750 lbf, S = 184 ft^2, b = 33.4 ft, cbar = 5.7 ft, Ix = 1048,
Iy = 3000, Iz = 3530, Ixz = 0 slug ft^2, moments about the mass centre. Body axes x forward,
y right, z down, x along the flight path at trim (so body = stability axes, theta_0 = 0).
Derivatives in AVL's body-axis normalisation (forces per q S, moments per q S cbar (pitch)
and q S b (roll, yaw); u, v, w per V; p, r per b/2V; q per cbar/2V), the u column carrying
the dynamic-pressure terms: CXu = -(CDu + 2 CD0) = -0.10, CZu = -(CLu + 2 CL0) = -0.82,
CXw = -(CDa - CL0) = 0.08, CZw = -(CLa + CD0) = -4.49, CZq = -CLq = -3.8, Cmw = Cma = -0.683,
Cmq = -9.96, CYv = CYb = -0.564, Clv = Clb = -0.074, Cnv = Cnb = 0.0701, Clp = -0.410,
Cnp = -0.0575, Clr = 0.107, Cnr = -0.125, the rest 0; Cm_alphadot = -4.36 per alphadot
cbar/2V, CL_alphadot = 0; trim CL0 = 0.41, CD0 = 0.05, thrust constant (equal to drag).

Dimensional derivatives (F = q S C):  X_u = (qS/V) CXu, X_w = (qS/V) CXw, Z_q = (qS/V)(cbar/2)
CZq, M_w = (qS cbar/V) Cmw, M_q = (qS cbar/V)(cbar/2) Cmq, M_wdot = (qS cbar)(cbar/2V) Cmad / V,
Y_v = (qS/V) CYv, L_p = (qS b/V)(b/2) Clp, and so on.

Full equations (m = W/g):
  m u'  = X_u u + X_w w - m g theta
  m w'  = Z_u u + Z_w w + (Z_q + m V) q
  Iy q' = M_u u + M_w w + M_wdot w' + M_q q          (the aerodynamic mass term M_wdot)
  theta' = q
  m v'  = Y_v v + Y_p p + (Y_r - m V) r + m g phi
  Ix p' - Ixz r' = L_v v + L_p p + L_r r
  Iz r' - Ixz p' = N_v v + N_p p + N_r r
  phi' = p,  psi' = r
Nelson's forms: the same longitudinal 4x4 with Z_q neglected (his matrix has u0 alone in the
w row), his short-period approximation [[Z_w, u0], [M_w + M_wdot Z_w, M_q + M_wdot u0]]
(per unit mass / inertia), and his lateral 4x4 in (beta, p, r, phi) (equal to the full
lateral equations here, since Y_p = Y_r = Ixz = 0).
Writes navion.json. Run: python navion.py   (numpy)
"""
import json

import numpy as np

V, RHO, G, W, S, B, C = 176.0, 0.002378, 32.2, 2750.0, 184.0, 33.4, 5.7
IX, IY, IZ, IXZ = 1048.0, 3000.0, 3530.0, 0.0
D = dict(CXu=-0.10, CXw=0.08, CZu=-0.82, CZw=-4.49, CZq=-3.8, Cmw=-0.683, Cmq=-9.96,
         CYv=-0.564, Clv=-0.074, Cnv=0.0701, Clp=-0.410, Cnp=-0.0575, Clr=0.107, Cnr=-0.125,
         Cmad=-4.36)
NELSON = {"short_period": (-2.5, 2.59), "phugoid": (-0.0171, 0.213),
          "dutch_roll": (-0.487, 2.335), "roll": -8.435, "spiral": -0.00877}

M = W / G
QS = 0.5 * RHO * V**2 * S


def dimensional():
    f = QS / V
    return dict(
        Xu=f * D["CXu"], Xw=f * D["CXw"], Zu=f * D["CZu"], Zw=f * D["CZw"],
        Zq=f * C / 2 * D["CZq"], Mu=0.0, Mw=f * C * D["Cmw"], Mq=f * C * C / 2 * D["Cmq"],
        Mwd=QS * C * (C / (2 * V)) * D["Cmad"] / V,
        Yv=f * D["CYv"], Yp=0.0, Yr=0.0,
        Lv=f * B * D["Clv"], Lp=f * B * B / 2 * D["Clp"], Lr=f * B * B / 2 * D["Clr"],
        Nv=f * B * D["Cnv"], Np=f * B * B / 2 * D["Cnp"], Nr=f * B * B / 2 * D["Cnr"])


def longitudinal(d, with_zq=True):
    """States (u, w, q, theta): E x' = A x, with the aerodynamic mass M_wdot in E."""
    zq = d["Zq"] if with_zq else 0.0
    e = np.array([[M, 0, 0, 0], [0, M, 0, 0], [0, -d["Mwd"], IY, 0], [0, 0, 0, 1.0]])
    a = np.array([[d["Xu"], d["Xw"], 0, -M * G],
                  [d["Zu"], d["Zw"], zq + M * V, 0],
                  [d["Mu"], d["Mw"], d["Mq"], 0],
                  [0, 0, 1.0, 0]])
    return np.linalg.solve(e, a)


def lateral(d):
    """States (v, p, r, phi, psi)."""
    e = np.array([[M, 0, 0, 0, 0], [0, IX, -IXZ, 0, 0], [0, -IXZ, IZ, 0, 0],
                  [0, 0, 0, 1.0, 0], [0, 0, 0, 0, 1.0]])
    a = np.array([[d["Yv"], d["Yp"], d["Yr"] - M * V, M * G, 0],
                  [d["Lv"], d["Lp"], d["Lr"], 0, 0],
                  [d["Nv"], d["Np"], d["Nr"], 0, 0],
                  [0, 1.0, 0, 0, 0],
                  [0, 0, 1.0, 0, 0]])
    return np.linalg.solve(e, a)


def short_period_approximation(d):
    zw, mw, mq, mwd = d["Zw"] / M, d["Mw"] / IY, d["Mq"] / IY, d["Mwd"] / IY
    return np.linalg.eigvals(np.array([[zw, V], [mw + mwd * zw, mq + mwd * V]]))


def upper(ev):
    """The eigenvalues with nonnegative imaginary part, sorted by real part."""
    ev = ev[ev.imag >= -1e-12]
    return sorted(ev, key=lambda z: z.real)


def pair(z):
    return {"re": z.real, "im": abs(z.imag), "omega_n": abs(z), "zeta": -z.real / abs(z)}


def main():
    d = dimensional()
    lon = upper(np.linalg.eigvals(longitudinal(d)))
    lon_nelson = upper(np.linalg.eigvals(longitudinal(d, with_zq=False)))
    sp_nelson = upper(short_period_approximation(d))
    lat = upper(np.linalg.eigvals(lateral(d)))
    # lat sorted by real part: roll, Dutch roll, spiral, heading (0)
    roll, dutch, spiral, heading = lat[0], lat[1], lat[2], lat[3]
    table = {
        "short_period": pair(lon[0]), "phugoid": pair(lon[1]),
        "roll": roll.real, "dutch_roll": pair(dutch), "spiral": spiral.real,
        "heading": heading.real,
    }
    nelson_form = {
        "short_period_approximation": pair(sp_nelson[0]),
        "longitudinal_without_Zq": {"short_period": pair(lon_nelson[0]),
                                    "phugoid": pair(lon_nelson[1])},
        "lateral": {"roll": roll.real, "dutch_roll": pair(dutch), "spiral": spiral.real},
    }
    out = {"source": "navion.py (numpy); docs/aero-references.md", "nelson_printed": NELSON,
           "dimensional_derivatives_slug_ft_s": d, "mass_slug": M,
           "full_equations": table, "nelson_form": nelson_form,
           "zero_eigenvalues": "heading psi (lateral); eom's model adds the position states "
                               "x, y, z (zero eigenvalues: no force depends on them)"}
    with open("navion.json", "w") as f:
        json.dump(out, f, indent=1)
    print("dimensional derivatives:", {k: round(v, 4) for k, v in d.items()})
    print("full equations (with CZq):")
    print(f"  short period {lon[0]:.5f}   phugoid {lon[1]:.6f}")
    print(f"  roll {roll.real:.5f}   Dutch roll {dutch:.5f}   spiral {spiral.real:.6f}"
          f"   heading {heading.real:.1e}")
    print("Nelson's forms:")
    print(f"  short-period approximation {sp_nelson[0]:.4f}  (Nelson -2.5 +- 2.59i)")
    print(f"  4x4 without Zq: short period {lon_nelson[0]:.4f}, phugoid {lon_nelson[1]:.5f}"
          "  (Nelson phugoid -0.0171 +- 0.213i)")
    print(f"  lateral: roll {roll.real:.4f} (-8.435), Dutch roll {dutch:.4f} (-0.487 +- 2.335i),"
          f" spiral {spiral.real:.6f} (-0.00877)")


if __name__ == "__main__":
    main()
