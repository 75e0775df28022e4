"""Flutter of the typical section (pitch-plunge airfoil), Hodges & Pierce's case:
a = -1/5, x_theta = 1/10, mu = 20, r^2 = 6/25, sigma = omega_h/omega_theta = 2/5.

D. H. Hodges and G. A. Pierce, *Introduction to Structural Dynamics and Aeroelasticity*,
2nd ed., Cambridge 2011, ch. 5 (the case of their flutter examples: a = -1/5, e = -1/10, so
x_theta = e - a = 1/10); T. Theodorsen, NACA Report 496 (1935); R. T. Jones, NACA Report 667
(1938). Equations and conventions: docs/aero-references.md (section "Typical section").

Per unit span, plunge h positive DOWN, pitch theta positive NOSE UP about the elastic axis
(at a semichords aft of mid-chord), mass centre x_theta semichords aft of the elastic axis:

    m h'' + S th'' + k_h h = -L,         S = m b x_theta,  k_h = m omega_h^2
    S h'' + I th'' + k_th th = M,        I = m b^2 r^2,    k_th = I omega_theta^2
    L = pi rho b^2 (h'' + U th' - b a th'') + 2 pi rho U b C[w]
    M = pi rho b^2 (b a h'' - U b (1/2 - a) th' - b^2 (1/8 + a^2) th'')
        + 2 pi rho U b^2 (a + 1/2) C[w]
    w = h' + U th + b (1/2 - a) th'        (downwash at the three-quarter chord)

C[w]: Theodorsen's C(k) for harmonic motion (k-method, and a direct Newton solve of the
flutter determinant in (k, omega) as the second method); C = 1 (quasi-steady, apparent-mass
terms kept); or Jones' two lag states
    C[w] = w/2 + 0.165 beta1 x1 + 0.335 beta2 x2,  x_i' = -beta_i x_i + w,
    beta1 = 0.0455 U/b, beta2 = 0.3 U/b
(quasi-steady and Jones: eigenvalues of the linear state-space model, flutter where the real
part of the flutter mode crosses zero).

Dimensional as the model file: b = 0.5 m, omega_theta = 10 rad/s, rho = 1.225 kg/m^3, span
width 1 m, so m = mu pi rho b^2. The flutter speed ratio does not depend on these choices.
Writes typical_section.json. Run: python typical_section.py   (numpy, scipy, mpmath)
"""
import json

import mpmath as mp
import numpy as np
from scipy.linalg import eig
from scipy.optimize import brentq

from theodorsen import JONES, theodorsen

A, X_THETA, MU, R2, SIGMA = -0.2, 0.1, 20.0, 0.24, 0.4
B, W_THETA, RHO = 0.5, 10.0, 1.225


def section():
    m = MU * np.pi * RHO * B**2
    s = m * B * X_THETA
    i = m * B**2 * R2
    ms = np.array([[m, s], [s, i]])
    ks = np.diag([m * (SIGMA * W_THETA) ** 2, i * W_THETA**2])
    return ms, ks


def aero_matrices(a=A, b=B, rho=RHO):
    """Apparent mass, the apparent-mass damping per unit U, and the circulatory vectors:
    force e*C[w] with w = d.q' + U s.q."""
    pr = np.pi * rho * b**2
    ma = pr * np.array([[1.0, -b * a], [-b * a, b**2 * (1 / 8 + a**2)]])
    ca_per_u = pr * np.array([[0.0, 1.0], [0.0, b * (0.5 - a)]])
    e_per_u = 2 * np.pi * rho * b * np.array([-1.0, b * (a + 0.5)])
    d = np.array([1.0, b * (0.5 - a)])
    s = np.array([0.0, 1.0])
    return ma, ca_per_u, e_per_u, d, s


def harmonic_aero(k, c):
    """F = omega^2 A(k) q for harmonic motion at reduced frequency k with C(k) = c."""
    ma, ca_u, e_u, d, s = aero_matrices()
    # U = omega b / k: U q' -> i omega (omega b/k) = omega^2 i b/k ; U^2 q -> omega^2 (b/k)^2
    u_over_w = B / k
    circ = np.outer(e_u * u_over_w, c * (1j * d + u_over_w * s))
    return ma - 1j * u_over_w * ca_u + circ


def k_method(ks_grid=None):
    """Structural damping g required for harmonic motion, per branch, over k; returns the
    flutter point (g = 0 crossing from below with decreasing k)."""
    ms, kst = section()
    if ks_grid is None:
        ks_grid = np.geomspace(2.0, 0.02, 2000)
    kinv = np.linalg.inv(kst)

    def branches(k):
        c = complex(theodorsen(k))
        # K (1 + i g) q = omega^2 (Ms + A) q  ->  lambda = (1 + i g)/omega^2
        lam = np.linalg.eigvals(kinv @ (ms + harmonic_aero(k, c)))
        lam = lam[np.argsort(-lam.real)]
        omega = 1 / np.sqrt(lam.real)
        g = lam.imag / lam.real
        return omega, g

    prev, k_prev = branches(ks_grid[0]), ks_grid[0]
    for k in ks_grid[1:]:
        cur = branches(k)
        for j in range(2):
            if prev[1][j] < 0 <= cur[1][j]:
                k0 = brentq(lambda kk: branches(kk)[1][j], k, k_prev)
                om = branches(k0)[0][j]
                return k0, om / W_THETA, om * B / k0 / (B * W_THETA)
        prev, k_prev = cur, k
    raise RuntimeError("no flutter in the k range")


def determinant_root(k0, w0):
    """Second method: det(K - omega^2 (Ms + A(k))) = 0 solved for (k, omega/omega_theta)
    by Newton's method at 30 digits (mpmath), from the k-method's point."""
    ms, kst = section()
    mp.mp.dps = 30
    ma, ca_u, e_u, d, s = aero_matrices()

    def det(k, w):
        om = w * W_THETA
        c = theodorsen(k)
        u_w = mp.mpf(B) / k
        m = mp.matrix(2, 2)
        for i in range(2):
            for j in range(2):
                a_ij = (ma[i, j] - 1j * u_w * ca_u[i, j]
                        + e_u[i] * u_w * c * (1j * d[j] + u_w * s[j]))
                m[i, j] = kst[i, j] - om**2 * (ms[i, j] + a_ij)
        return mp.det(m)

    k, w = mp.findroot(lambda k, w: [mp.re(det(k, w)), mp.im(det(k, w))], (k0, w0))
    return float(k), float(w), float(w / k)


def state_space(u, model):
    """The linear state matrix at airspeed u: model 'quasi-steady' (C = 1) or 'jones'."""
    ms, kst = section()
    ma, ca_u, e_u, d, s = aero_matrices()
    m = ms + ma
    e = e_u * u
    w_rate, w_disp = d, u * s     # w = d.q' + u s.q
    if model == "quasi-steady":
        c_tot = ca_u * u - np.outer(e, w_rate)
        k_tot = kst - np.outer(e, w_disp)
        minv = np.linalg.inv(m)
        return np.block([[np.zeros((2, 2)), np.eye(2)], [-minv @ k_tot, -minv @ c_tot]])
    betas = [bb * u / B for _, bb in JONES]
    coeff = [aa for aa, _ in JONES]
    c_tot = ca_u * u - 0.5 * np.outer(e, w_rate)
    k_tot = kst - 0.5 * np.outer(e, w_disp)
    minv = np.linalg.inv(m)
    a = np.zeros((6, 6))
    a[0:2, 2:4] = np.eye(2)
    a[2:4, 0:2] = -minv @ k_tot
    a[2:4, 2:4] = -minv @ c_tot
    for j, (cj, bj) in enumerate(zip(coeff, betas)):
        a[2:4, 4 + j] = minv @ e * cj * bj
        a[4 + j, 0:2] = w_disp
        a[4 + j, 2:4] = w_rate
        a[4 + j, 4 + j] = -bj
    return a


def oscillatory_max_real(u, model):
    ev = np.linalg.eigvals(state_space(u, model))
    osc = ev[np.abs(ev.imag) > 1e-6]
    i = int(np.argmax(osc.real))
    return osc[i].real, abs(osc[i].imag)


def state_space_flutter(model, u_lo=0.5, u_hi=60.0):
    us = np.linspace(u_lo, u_hi, 600)
    prev = oscillatory_max_real(us[0], model)[0]
    for a, b in zip(us[:-1], us[1:]):
        cur = oscillatory_max_real(b, model)[0]
        if prev < 0 <= cur:
            uf = brentq(lambda u: oscillatory_max_real(u, model)[0], a, b, xtol=1e-13)
            wf = oscillatory_max_real(uf, model)[1]
            return uf / (B * W_THETA), wf / W_THETA, uf, wf
        prev = cur
    raise RuntimeError(f"no flutter for {model} below {u_hi} m/s")


def main():
    k0, w_k, u_k = k_method()
    k1, w_d, u_d = determinant_root(k0, w_k)
    assert abs(u_d / u_k - 1) < 1e-6 and abs(w_d / w_k - 1) < 1e-6, (u_k, u_d, w_k, w_d)
    uj, wj, uj_dim, wj_dim = state_space_flutter("jones")
    uq, wq, uq_dim, wq_dim = state_space_flutter("quasi-steady")
    ms, kst = section()
    out = {
        "source": "typical_section.py (numpy, scipy, mpmath); docs/aero-references.md",
        "case": {"a": A, "x_theta": X_THETA, "mu": MU, "r2": R2, "sigma": SIGMA,
                 "b_m": B, "omega_theta_rad_s": W_THETA, "rho_kg_m3": RHO,
                 "mass_kg_per_m": ms[0, 0], "static_moment_kg": ms[0, 1],
                 "inertia_kg_m": ms[1, 1], "k_h_N_per_m2": kst[0, 0],
                 "k_theta_N": kst[1, 1]},
        "theodorsen_exact": {"U_F_over_b_omega_theta": u_d, "omega_F_over_omega_theta": w_d,
                             "k_F": k1, "U_F_m_s": u_d * B * W_THETA,
                             "omega_F_rad_s": w_d * W_THETA,
                             "k_method": {"U_F_over_b_omega_theta": u_k,
                                          "omega_F_over_omega_theta": w_k, "k_F": k0}},
        "jones_states": {"U_F_over_b_omega_theta": uj, "omega_F_over_omega_theta": wj,
                         "U_F_m_s": uj_dim, "omega_F_rad_s": wj_dim},
        "quasi_steady": {"U_F_over_b_omega_theta": uq, "omega_F_over_omega_theta": wq,
                         "U_F_m_s": uq_dim, "omega_F_rad_s": wq_dim},
    }
    with open("typical_section.json", "w") as f:
        json.dump(out, f, indent=1)
    print(f"Theodorsen (k-method)     U_F/(b w_th) = {u_k:.6f}  w_F/w_th = {w_k:.6f}  k = {k0:.6f}")
    print(f"Theodorsen (determinant)  U_F/(b w_th) = {u_d:.8f}  w_F/w_th = {w_d:.8f}  k = {k1:.8f}")
    print(f"Jones states              U_F/(b w_th) = {uj:.8f}  w_F/w_th = {wj:.8f}"
          f"  ({100 * (uj / u_d - 1):+.3f} %, {100 * (wj / w_d - 1):+.3f} %)")
    print(f"quasi-steady (C = 1)      U_F/(b w_th) = {uq:.8f}  w_F/w_th = {wq:.8f}"
          f"  ({100 * (uq / u_d - 1):+.3f} %, {100 * (wq / w_d - 1):+.3f} %)")


if __name__ == "__main__":
    main()
