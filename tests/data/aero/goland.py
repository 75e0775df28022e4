"""Flutter of the Goland wing by strip theory: Theodorsen (exact C(k)), Jones' two lag states,
and quasi-steady (C = 1), on two discretisations of the same uniform cantilever:

* "modal": Galerkin with nb cantilever bending modes and nt torsion modes (the continuum
  reference, converged in the number of modes);
* "lumped": the discretisation eom's model file will use, N equal beam segments: nodes at
  y_i = i L/N (i = 1..N; y_0 = 0 clamped); at each node a rigid body carrying the mass,
  static moment and pitch inertia of its tributary span (L/N, L/(2N) at the tip) and a strip
  of that width; Euler-Bernoulli beam elements (Hermite cubics, stiffness only) between
  nodes for bending; torsion springs GJ/(L/N) between nodes; the bending slope has no
  inertia (condensed); converged in N.

M. Goland, "The flutter of a uniform cantilever wing", J. Appl. Mech. 12(4) A197-A208 (1945);
M. J. Patil, D. H. Hodges, C. E. S. Cesnik, "Nonlinear aeroelasticity and flight dynamics of
high-altitude long-endurance aircraft", J. Aircraft 38(1) 88-94 (2001) (Goland wing: 137 m/s,
70.7 rad/s). Equations: docs/aero-references.md ("Goland wing").

Section as typical_section.py: plunge h positive down, pitch theta nose up about the elastic
axis, strip loads per unit span -L, M with Theodorsen's circulatory and apparent-mass terms.
Writes goland.json. Run: python goland.py   (numpy, scipy, mpmath)
"""
import json

import numpy as np
from scipy.optimize import brentq, fsolve

from theodorsen import JONES, theodorsen, theodorsen_scipy

L_SPAN, CHORD = 6.096, 1.8288
B = CHORD / 2
A = (0.33 * CHORD - B) / B                 # elastic axis at 33 % chord: a = -0.34
XCG = (0.43 - 0.33) * CHORD                # mass centre 0.18288 m aft of the elastic axis
MASS, I_THETA = 35.71, 8.64                # kg/m, kg m^2/m about the elastic axis
EI, GJ, RHO = 9.77e6, 0.987e6, 1.2256
S_THETA = MASS * XCG


def section_aero(a=A, b=B, rho=RHO):
    """Per unit span, on (h, theta): apparent mass, apparent damping per unit U, circulatory
    force per unit U (times C[w]), downwash w = d.q' + U s.q."""
    pr = np.pi * rho * b**2
    ma = pr * np.array([[1.0, -b * a], [-b * a, b**2 * (1 / 8 + a**2)]])
    da = pr * np.array([[0.0, 1.0], [0.0, b * (0.5 - a)]])
    e = 2 * np.pi * rho * b * np.array([-1.0, b * (a + 0.5)])
    d = np.array([1.0, b * (0.5 - a)])
    s = np.array([0.0, 1.0])
    return ma, da, e, d, s


class Aeroelastic:
    """M q'' + U Da q' + K q = U E C[w],  w = R q' + U S q  (plus apparent mass in M)."""

    def __init__(self, ms, ks, ma, da, e, r, s):
        self.ms, self.ks, self.ma, self.da, self.e, self.r, self.s = ms, ks, ma, da, e, r, s
        self.n = ms.shape[0]

    def harmonic(self, k, c):
        """A(k): K q = omega^2 (Ms + A) q for harmonic motion with C(k) = c."""
        ub = B / k
        return self.ma - 1j * ub * self.da + ub * c * self.e @ (1j * self.r + ub * self.s)

    def k_method_branches(self, k):
        c = complex(theodorsen(k))
        lam = np.linalg.eigvals(np.linalg.solve(self.ks, self.ms + self.harmonic(k, c)))
        return lam

    def k_method(self, k_hi=2.0, k_lo=0.01, steps=1500):
        """Lowest-speed g = 0 crossing, branches followed by nearest eigenvalue."""
        ks = np.geomspace(k_hi, k_lo, steps)
        prev = self.k_method_branches(ks[0])
        best = None
        for k0, k1 in zip(ks[:-1], ks[1:]):
            cur = self.k_method_branches(k1)
            order = [int(np.argmin(np.abs(cur - p))) for p in prev]
            if len(set(order)) < len(order):
                order = list(np.argsort(-cur.real))
                prev = prev[np.argsort(-prev.real)]
            cur = cur[order]
            g0, g1 = prev.imag / prev.real, cur.imag / cur.real
            for j in range(self.n):
                if g0[j] < 0 <= g1[j]:
                    def nearest(k, lo=prev[j], hi=cur[j], k0=k0, k1=k1):
                        # the branch nearest to the straight line between its two ends
                        t = np.log(k0 / k) / np.log(k0 / k1)
                        lam = self.k_method_branches(k)
                        return lam[np.argmin(np.abs(lam - (lo + t * (hi - lo))))]

                    kf = brentq(lambda k: nearest(k).imag / nearest(k).real, k1, k0, xtol=1e-14)
                    lj = nearest(kf)
                    om = 1 / np.sqrt(lj.real)
                    u = om * B / kf
                    if best is None or u < best[0]:
                        best = (u, om, kf)
            prev = cur
        return best

    def determinant_root(self, u0, om0):
        """Second method: det(K - omega^2 (Ms + A(k))) / det(K) = 0 in (k, omega)."""
        kinv = np.linalg.inv(self.ks)

        def f(x):
            k, om = x
            c = theodorsen_scipy(abs(k))
            d = np.linalg.det(np.eye(self.n) - om**2 * kinv @ (self.ms + self.harmonic(abs(k), c)))
            return [d.real, d.imag]

        k, om = fsolve(f, [om0 * B / u0, om0], xtol=1e-14)
        return om * B / k, om, k

    def state_matrix(self, u, model):
        n, nw = self.n, self.r.shape[0]
        m = self.ms + self.ma
        minv = np.linalg.inv(m)
        e = u * self.e
        half = 1.0 if model == "quasi-steady" else 0.5
        k_eff = self.ks - half * e @ (u * self.s)
        d_eff = u * self.da - half * e @ self.r
        if model == "quasi-steady":
            return np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ k_eff, -minv @ d_eff]])
        size = 2 * n + 2 * nw
        a = np.zeros((size, size))
        a[:n, n:2 * n] = np.eye(n)
        a[n:2 * n, :n] = -minv @ k_eff
        a[n:2 * n, n:2 * n] = -minv @ d_eff
        for j, (cj, bj) in enumerate(JONES):
            beta = bj * u / B
            sl = slice(2 * n + j * nw, 2 * n + (j + 1) * nw)
            a[n:2 * n, sl] = minv @ e * cj * beta
            a[sl, :n] = u * self.s
            a[sl, n:2 * n] = self.r
            a[sl, sl] = -beta * np.eye(nw)
        return a

    def max_real(self, u, model, band):
        ev = np.linalg.eigvals(self.state_matrix(u, model))
        osc = ev[(np.abs(ev.imag) > band[0]) & (np.abs(ev.imag) < band[1])]
        i = int(np.argmax(osc.real))
        return osc[i].real, abs(osc[i].imag)

    def state_space_flutter(self, model, u_hi=400.0, band=(1.0, 1e9)):
        us = np.linspace(5.0, u_hi, 400)
        prev = self.max_real(us[0], model, band)[0]
        for u0, u1 in zip(us[:-1], us[1:]):
            cur = self.max_real(u1, model, band)[0]
            if prev < 0 <= cur:
                uf = brentq(lambda u: self.max_real(u, model, band)[0], u0, u1, xtol=1e-10)
                return uf, self.max_real(uf, model, band)[1]
            prev = cur
        return None


def cantilever_mode(i, y):
    """Cantilever bending mode i (1-based), value and second derivative, in a form stable for
    high modes; normalised to 1 ... 2 at the tip."""
    roots = [1.8751040687119611, 4.6940911329741745, 7.8547574382376126, 10.995540734875467,
             14.137168391046471, 17.278759532088237, 20.420352251041251, 23.561944901806445,
             26.703537555518299, 29.845130209101253, 32.986722862692829, 36.128315516282622]
    bl = roots[i - 1]
    be = bl / L_SPAN
    x = be * y
    den = np.sinh(bl) + np.sin(bl)
    one_minus_sigma = (-np.exp(-bl) + np.sin(bl) - np.cos(bl)) / den
    sigma = 1 - one_minus_sigma
    # cosh x - sigma sinh x = (1 + sigma)/2 e^-x + (1 - sigma)/2 e^x
    hyp = 0.5 * (1 + sigma) * np.exp(-x) + 0.5 * one_minus_sigma * np.exp(x)
    hyp2 = hyp  # (cosh - sigma sinh)'' = be^2 (cosh - sigma sinh)
    phi = hyp - np.cos(x) + sigma * np.sin(x)
    phi2 = be**2 * (hyp2 + np.cos(x) - sigma * np.sin(x))
    return phi, phi2


def modal(nb, nt, nq=400):
    y, w = np.polynomial.legendre.leggauss(nq)
    y = 0.5 * L_SPAN * (y + 1)
    w = 0.5 * L_SPAN * w
    phi = np.array([cantilever_mode(i, y)[0] for i in range(1, nb + 1)])
    phi2 = np.array([cantilever_mode(i, y)[1] for i in range(1, nb + 1)])
    psi = np.array([np.sin((2 * j - 1) * np.pi * y / (2 * L_SPAN)) for j in range(1, nt + 1)])
    dpsi = np.array([(2 * j - 1) * np.pi / (2 * L_SPAN) * np.cos((2 * j - 1) * np.pi * y / (2 * L_SPAN))
                     for j in range(1, nt + 1)])
    g = lambda f1, f2: (f1 * w) @ f2.T  # noqa: E731
    ghh, ght, gtt = g(phi, phi), g(phi, psi), g(psi, psi)
    ms = np.block([[MASS * ghh, S_THETA * ght], [S_THETA * ght.T, I_THETA * gtt]])
    ks = np.block([[EI * g(phi2, phi2), np.zeros((nb, nt))], [np.zeros((nt, nb)), GJ * g(dpsi, dpsi)]])
    ma, da, e, d, s = section_aero()
    gb = [[ghh, ght], [ght.T, gtt]]
    blk = lambda mat: np.block([[mat[r, c] * gb[r][c] for c in range(2)] for r in range(2)])  # noqa: E731
    # w(y) = phi.eta' + U psi.xi + b(1/2 - a) psi.xi' = Phi(y) . w_vec
    r = np.block([[np.eye(nb), np.zeros((nb, nt))], [np.zeros((nt, nb)), d[1] * np.eye(nt)]])
    sm = np.block([[np.zeros((nb, nb)), np.zeros((nb, nt))], [np.zeros((nt, nb)), np.eye(nt)]])
    ec = np.block([[e[0] * ghh, e[0] * ght], [e[1] * ght.T, e[1] * gtt]])
    return Aeroelastic(ms, ks, blk(ma), blk(da), ec, r, sm)


def lumped(n, roll_inertia=False):
    """N segments; generalized coordinates (h_i, theta_i), i = 1..N, slopes condensed."""
    le = L_SPAN / n
    width = np.full(n, le)
    width[-1] = le / 2
    # bending: Hermite elements on (h_0, s_0, ..., h_N, s_N), node 0 clamped
    kb = np.zeros((2 * n + 2, 2 * n + 2))
    ke = EI / le**3 * np.array([[12, 6 * le, -12, 6 * le], [6 * le, 4 * le**2, -6 * le, 2 * le**2],
                                [-12, -6 * le, 12, -6 * le], [6 * le, 2 * le**2, -6 * le, 4 * le**2]])
    for i in range(n):
        idx = [2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3]
        kb[np.ix_(idx, idx)] += ke
    kb = kb[2:, 2:]
    hi = np.arange(0, 2 * n, 2)
    si = np.arange(1, 2 * n, 2)
    if roll_inertia:
        # keep the slopes as coordinates with the segment's rotary inertia m w^3/12 about the
        # chordwise axis (a rigid segment about its centre), evaluated below
        pass
    khh = kb[np.ix_(hi, hi)] - kb[np.ix_(hi, si)] @ np.linalg.solve(kb[np.ix_(si, si)], kb[np.ix_(si, hi)])
    kt = np.zeros((n + 1, n + 1))
    for i in range(n):
        kt[np.ix_([i, i + 1], [i, i + 1])] += GJ / le * np.array([[1, -1], [-1, 1]])
    kt = kt[1:, 1:]
    z = np.zeros((n, n))
    ms = np.block([[np.diag(MASS * width), np.diag(S_THETA * width)],
                   [np.diag(S_THETA * width), np.diag(I_THETA * width)]])
    ks = np.block([[khh, z], [z, kt]])
    ma, da, e, d, s = section_aero()
    dw = np.diag(width)
    blk = lambda mat: np.block([[mat[r, c] * dw for c in range(2)] for r in range(2)])  # noqa: E731
    eye = np.eye(n)
    r = np.hstack([eye, d[1] * eye])        # w_i = h_i' + U th_i + b(1/2 - a) th_i'
    sm = np.hstack([z, eye])
    ec = np.vstack([e[0] * dw, e[1] * dw])
    model = Aeroelastic(ms, ks, blk(ma), blk(da), ec, r, sm)
    if roll_inertia:
        model = with_slope_inertia(n, le, width, kb, hi, si, model)
    return model


def with_slope_inertia(n, le, width, kb, hi, si, base):
    """The lumped model with the slopes kept as coordinates, each with the rotary inertia
    m w^3/12 of its tributary segment: coordinates (h, theta, slope)."""
    kbb = np.block([[kb[np.ix_(hi, hi)], kb[np.ix_(hi, si)]], [kb[np.ix_(si, hi)], kb[np.ix_(si, si)]]])
    nt = 3 * n
    ms = np.zeros((nt, nt))
    ms[:2 * n, :2 * n] = base.ms
    ms[2 * n:, 2 * n:] = np.diag(MASS * width**3 / 12)
    ks = np.zeros((nt, nt))
    ks[:2 * n, :2 * n] = base.ks
    # replace the condensed bending block by the full one on (h, slope)
    ks[:n, :n] = kbb[:n, :n]
    ks[:n, 2 * n:] = kbb[:n, n:]
    ks[2 * n:, :n] = kbb[n:, :n]
    ks[2 * n:, 2 * n:] = kbb[n:, n:]
    pad = lambda mat: np.pad(mat, ((0, n), (0, n)))  # noqa: E731
    r = np.hstack([base.r, np.zeros((n, n))])
    sm = np.hstack([base.s, np.zeros((n, n))])
    ec = np.vstack([base.e, np.zeros((n, n))])
    return Aeroelastic(ms, ks, pad(base.ma), pad(base.da), ec, r, sm)


def solve(model):
    u, om, k = model.k_method()
    ud, omd, kd = model.determinant_root(u, om)
    assert abs(ud / u - 1) < 1e-6 and abs(omd / om - 1) < 1e-6, (u, ud, om, omd)
    band = (0.5 * om, 2.0 * om)  # the flutter mode's neighbourhood
    j = model.state_space_flutter("jones", band=(1.0, 1e9))
    q = model.state_space_flutter("quasi-steady", band=(1.0, 1e9))
    return {"theodorsen": {"U_F_m_s": ud, "omega_F_rad_s": omd, "k_F": kd},
            "jones": j and {"U_F_m_s": j[0], "omega_F_rad_s": j[1]},
            "quasi_steady": q and {"U_F_m_s": q[0], "omega_F_rad_s": q[1]}}


def fmt(r):
    t, j, q = r["theodorsen"], r["jones"], r["quasi_steady"]
    qs = f"{q['U_F_m_s']:9.4f} {q['omega_F_rad_s']:8.4f}" if q else "   none"
    return (f"{t['U_F_m_s']:10.5f} {t['omega_F_rad_s']:9.5f} {t['k_F']:8.5f} | "
            f"{j['U_F_m_s']:10.5f} {j['omega_F_rad_s']:9.5f} | {qs}")


def main():
    out = {"source": "goland.py (numpy, scipy, mpmath); docs/aero-references.md",
           "case": {"semispan_m": L_SPAN, "chord_m": CHORD, "b_m": B, "a": A, "x_cg_m": XCG,
                    "mass_kg_per_m": MASS, "I_theta_kg_m": I_THETA, "EI_N_m2": EI,
                    "GJ_N_m2": GJ, "rho_kg_m3": RHO},
           "modal": [], "lumped": [], "lumped_with_slope_inertia": []}
    print("modal (nb bending, nt torsion modes): Theodorsen U, omega, k | Jones U, omega | quasi-steady")
    for nb, nt in [(1, 1), (2, 2), (3, 3), (4, 4), (6, 6), (8, 8), (10, 10)]:
        r = solve(modal(nb, nt))
        r.update({"bending_modes": nb, "torsion_modes": nt})
        out["modal"].append(r)
        print(f"  {nb:2d} {nt:2d}  {fmt(r)}")
    print("lumped, N segments")
    for n in [2, 4, 8, 16, 32, 64]:
        r = solve(lumped(n))
        r["segments"] = n
        out["lumped"].append(r)
        print(f"  {n:3d}    {fmt(r)}")
    print("lumped with the segments' rotary inertia about the chordwise axis")
    for n in [4, 8, 16]:
        r = solve(lumped(n, roll_inertia=True))
        r["segments"] = n
        out["lumped_with_slope_inertia"].append(r)
        print(f"  {n:3d}    {fmt(r)}")
    with open("goland.json", "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
