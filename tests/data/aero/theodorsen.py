"""Theodorsen's function C(k) from Hankel functions, and R. T. Jones' two-pole approximation.

    C(k) = H1(k) / (H1(k) + i H0(k)),   Hn = Hn^(2) = Jn - i Yn   (Hankel functions of the
                                                                   second kind)
    C_J(s) = 1 - 0.165 s/(s + 0.0455) - 0.335 s/(s + 0.3),  s = p b / V  (Laplace variable
                                                                   made non-dimensional),
    evaluated at s = i k, k = omega b / V (reduced frequency on the semichord b).

T. Theodorsen, "General theory of aerodynamic instability and the mechanism of flutter",
NACA Report 496 (1935); R. T. Jones, "Operational treatment of the nonuniform-lift theory in
airplane dynamics", NACA Report 667 (1938) (the indicial form 1 - 0.165 e^{-0.0455 s}
- 0.335 e^{-0.3 s} of Wagner's function, whose Laplace transform is C_J).

Writes theodorsen_ck.csv: k, F, G (C = F + iG) exact (mpmath, 30 digits, checked against
scipy), F, G of Jones, |C_J - C|, and prints the largest |dC| over the table.
Run: python theodorsen.py   (numpy, scipy, mpmath)
"""
import csv

import mpmath as mp
import numpy as np
from scipy.special import hankel2

mp.mp.dps = 30

JONES = ((0.165, 0.0455), (0.335, 0.3))


def theodorsen(k):
    """C(k) at 30 digits (mpmath), k > 0; C(0) = 1."""
    k = mp.mpf(k)
    if k == 0:
        return mp.mpc(1)
    h1 = mp.hankel2(1, k)
    h0 = mp.hankel2(0, k)
    return h1 / (h1 + 1j * h0)


def theodorsen_scipy(k):
    h1, h0 = hankel2(1, k), hankel2(0, k)
    return h1 / (h1 + 1j * h0)


def jones(s):
    """Jones' approximation at the complex non-dimensional Laplace variable s = p b / V."""
    return 1 - sum(a * s / (s + b) for a, b in JONES)


def table():
    ks = [0.0, 0.005, 0.01, 0.02, 0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6,
          0.8, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0]
    rows = []
    for k in ks:
        c = complex(theodorsen(k))
        if k > 0:
            assert abs(c - theodorsen_scipy(k)) < 1e-12, k
        cj = jones(1j * k)
        rows.append((k, c.real, c.imag, cj.real, cj.imag, abs(cj - c)))
    return rows


def largest_error():
    """max |C_J(ik) - C(k)| over a fine grid of k, and where."""
    ks = np.concatenate([np.linspace(1e-4, 0.5, 5001), np.linspace(0.5, 10, 951)])
    err = [abs(jones(1j * k) - theodorsen_scipy(k)) for k in ks]
    i = int(np.argmax(err))
    return ks[i], err[i]


def main():
    rows = table()
    with open("theodorsen_ck.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["k", "F", "G", "F_jones", "G_jones", "abs_dC"])
        for r in rows:
            w.writerow([f"{r[0]:g}"] + [f"{x:.12f}" for x in r[1:]])
    for r in rows:
        print("k = %6g  C = %.6f %+.6fi  Jones %.6f %+.6fi  |dC| = %.5f" % r)
    k, e = largest_error()
    print(f"largest |C_J - C| = {e:.5f} at k = {k:.4f}")


if __name__ == "__main__":
    main()
