#!/usr/bin/env python3
"""Reference eigenvalues of the half car of models/half_car.toml with its front damper at 0,
computed independently of eom: the equations of motion derived by hand and solved in 40-digit
arithmetic (mpmath). Writes half_car_mpmath.json beside this script.

The body (mass m, pitch inertia I about the mass centre) bounces (z, up) and pitches (θ) on a
front spring kf and damper cf at a ahead of the mass centre and a rear spring kr and damper cr
at b behind it. With the suspension points' vertical displacements z + aθ and z − bθ,

    V = kf (z + aθ)²/2 + kr (z − bθ)²/2,   D = cf (ż + aθ̇)²/2 + cr (ż − bθ̇)²/2,

so M = diag(m, I), K = [[kf + kr, a kf − b kr], [a kf − b kr, a² kf + b² kr]] and C likewise
with cf, cr; the eigenvalues are the roots of det(s² M + s C + K). Gravity adds no stiffness
(the springs are vertical, their body ends at the mass centre's height, the weight acts at
the mass centre). With cf = 0 the quartic has the factor of an undamped mode exactly when
I = m a b (the front and rear halves decouple, and the front half has no damper), so near
I = m a b = 2016 kg m² one mode's real part is of the order of (I − m a b)²: a stable model
whose largest real part is tiny, where a verdict depends on the tolerance it is judged by.

Run: python3 half_car_mpmath.py   (mpmath 1.3)
"""

import json
import os

import mpmath as mp

mp.mp.dps = 40


def roots(m, I, a, b, kf, kr, cf, cr):
    """The four eigenvalues, sorted by (re, im)."""
    M = [[m, 0], [0, I]]
    K = [[kf + kr, a * kf - b * kr], [a * kf - b * kr, a * a * kf + b * b * kr]]
    C = [[cf + cr, a * cf - b * cr], [a * cf - b * cr, a * a * cf + b * b * cr]]
    # det of the 2×2 polynomial matrix P(s) = M s² + C s + K, coefficients from s⁴ down.
    def entry(i, j):
        return [M[i][j], C[i][j], K[i][j]]  # s², s¹, s⁰

    def mul(p, q):
        r = [mp.mpf(0)] * (len(p) + len(q) - 1)
        for i, x in enumerate(p):
            for j, y in enumerate(q):
                r[i + j] += x * y
        return r

    p11_p22 = mul(entry(0, 0), entry(1, 1))
    p12_p21 = mul(entry(0, 1), entry(1, 0))
    coeffs = [x - y for x, y in zip(p11_p22, p12_p21)]
    r = mp.polyroots(coeffs, maxsteps=200, extraprec=200)
    return sorted(r, key=lambda z: (mp.re(z), mp.im(z)))


def main():
    base = dict(
        m=mp.mpf(1200),
        a=mp.mpf("1.2"),
        b=mp.mpf("1.4"),
        kf=mp.mpf(35000),
        kr=mp.mpf(38000),
        cf=mp.mpf(0),
        cr=mp.mpf(3000),
    )
    cases = []
    for I in ["2016.0033", "2016", "2016.1"]:
        r = roots(I=mp.mpf(I), **base)
        cases.append(
            {
                "set": {"cf": 0, "I": float(I)},
                "I": I,
                "eigenvalues": [[mp.nstr(mp.re(z), 20), mp.nstr(mp.im(z), 20)] for z in r],
                "max_real": mp.nstr(max(mp.re(z) for z in r), 20),
            }
        )
    out = {
        "source": "half_car_mpmath.py: det(s^2 M + s C + K) of the hand-derived half car, mpmath polyroots at 40 digits",
        "model": "models/half_car.toml",
        "cases": cases,
    }
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "half_car_mpmath.json"), "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
