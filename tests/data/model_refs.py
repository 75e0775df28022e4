"""Closed-form reference answers of the built-in models, at 30 digits (mpmath).

Prints the numbers that the sidecars `models/NAME.ref.toml` quote as "tests/data/model_refs.py"
(docs/model-files.md, "Reference answers"); each block names its formula. Nothing here reads
eom: the formulas are those of docs/references.md and of the derivations noted per block.

Run: python3 tests/data/model_refs.py
"""

import mpmath as mp

mp.mp.dps = 30


def show(title, values):
    print(f"# {title}")
    for v in values:
        v = mp.mpc(v)
        print(f"  [{mp.nstr(v.real, 17)}, {mp.nstr(v.imag, 17)}],")


def roots(coeffs):
    """Roots of a polynomial, highest power first, sorted by (re, im)."""
    r = mp.polyroots(coeffs, maxsteps=200, extraprec=200)
    return sorted((mp.mpc(x) for x in r), key=lambda z: (float(z.real), float(z.imag)))


# Spring-mass-damper, m z'' + c z' + k z = f: s = -c/2m +- i sqrt(k/m - c^2/4m^2).
for m, k, c in [(1, 10, mp.mpf("0.1")), (mp.mpf("2.5"), 40, 3)]:
    show(f"smd m={m} k={k} c={c}", roots([m, c, k]))
    show(f"smd gain z/f = 1/k", [mp.mpf(1) / k])

# Pendulum on a pin: (Ix + m r^2) phi'' + m g r phi = ...: s = +- i sqrt(m g r/(Ix + m r^2));
# gains y/Y = y/L = 1/(m g) (y = r phi).
for m, r, ix, g in [(10, 1, 1, mp.mpf("9.807")), (2, mp.mpf("0.4"), mp.mpf("0.05"), mp.mpf("9.81"))]:
    show(f"pendulum m={m} r={r} Ix={ix} g={g}", roots([ix + m * r * r, 0, m * g * r]))
    show("pendulum gain y/Y", [mp.mpf(1) / (m * g)])

# Shimmy (Schwab & Meijaard 2003; docs/references.md B):
# (I + m a^2) s^3 + m a u s^2 + k l^2 s + k l u = 0, a = x l; stable for
# (l - sqrt(l^2 - 4I/m))/2 < a < (l + sqrt(...))/2. Static gains with the force at the mass
# centre: the wheel's side force N and the spring's k y balance F and their moments about the
# mass centre, so y = a F/(k l) and the spring force k y = (a/l) F.
def shimmy(m, I, k, l, x, u, D=0):
    a = x * l
    return roots([I + m * a * a, m * a * u + D, k * l * l, k * l * u])


m, I, k, l = 5, mp.mpf("1.05"), mp.mpf("1.5"), 1
show("shimmy x=0.5 u=10", shimmy(m, I, k, l, mp.mpf("0.5"), 10))
show("shimmy x=0.4 u=1", shimmy(m, I, k, l, mp.mpf("0.4"), 1))
root = mp.sqrt(l * l - 4 * I / m)
show("shimmy stable x interval", [(l - root) / 2 / l, (l + root) / 2 / l])
x = mp.mpf("0.4")
show("shimmy gains at x=0.4: spring force/F, y/F", [x, x * l / (k * l)])

# Shimmy with the seed paper's fin (entries L22, L26, L62, L66 at rho = 1.225, V = 10):
# D = L22 l^2 + (L26 + L62) l + L66 adds to the s^2 coefficient; stable when
# m a (l - a) > I - D l/u, and L proportional to u makes the interval speed-independent.
L22, L26, L62, L66 = mp.mpf("7.59895"), mp.mpf("-2.05293"), mp.mpf("0.153319"), mp.mpf("0.224167")
D = L22 * l * l + (L26 + L62) * l + L66
show("shimmy_wing x=0.5 u=10", shimmy(m, I, k, l, mp.mpf("0.5"), 10, D))
rw = mp.sqrt(1 - 4 * (I - D * l / 10) / (m * l * l))
show("shimmy_wing stable x interval", [(1 - rw) / 2, (1 + rw) / 2])
# The vortex lattice's entries are within 0.3 % of the paper's (models/tests/wings.rs): the
# interval ends move by |dx/dD| * 0.003 |D| at most.
dxdD = mp.diff(lambda d: (1 - mp.sqrt(1 - 4 * (I - d * l / 10) / (m * l * l))) / 2, D)
show("shimmy_fin: |dx/dD| * 0.003 |D|", [abs(dxdD) * mp.mpf("0.003") * abs(D)])

# Heavy symmetric top on a fixed point: (Ip s^2 - m g h)^2 + (Ia r s)^2 = 0, Ip = It + m h^2,
# plus two zeros; stable above r = 2 sqrt(Ip m g h)/Ia.
mt, h, It, Ia, g = mp.mpf("0.01"), mp.mpf("0.04"), mp.mpf("3e-4"), mp.mpf("4e-4"), mp.mpf("9.81")
Ip = It + mt * h * h
for r in [1, 8]:
    # (Ip s^2 - mgh)^2 + Ia^2 r^2 s^2
    mgh = mt * g * h
    show(f"top r={r}", roots([Ip * Ip, 0, Ia * Ia * r * r - 2 * Ip * mgh, 0, mgh * mgh]))
show("top critical spin (above it the roots are purely imaginary)", [2 * mp.sqrt(Ip * mt * g * h) / Ia])

# Rolling disk (Schwab & Meijaard 2003): s^2 = 4 (g r - 3 u^2)/(5 r^2), four zeros; stable
# above u = sqrt(g r/3).
r, g = mp.mpf("0.5"), mp.mpf("9.81")
for u in [mp.mpf("0.1"), mp.mpf("0.5"), mp.mpf("1.5")]:
    s = mp.sqrt(4 * (g * r - 3 * u * u) / (5 * r * r))
    show(f"disk u={u}", [-s, s])
show("disk critical speed", [mp.sqrt(g * r / 3)])

# Chain of n equal masses, fixed-free: mu_j = 4 sin^2((2j - 1) pi/(2(2n + 1))),
# m s^2 + c mu s + k mu = 0 for each j.
n, m, k, c = 10, 1, 1, mp.mpf("0.1")
vals = []
for j in range(1, n + 1):
    mu = 4 * mp.sin((2 * j - 1) * mp.pi / (2 * (2 * n + 1))) ** 2
    vals += roots([m, c * mu, k * mu])
show("chain10 defaults", sorted(vals, key=lambda z: (float(z.real), float(z.imag))))

# Quarter car: (ms s^2 + cs s + ks)(mu s^2 + (cs + ct) s + ks + kt) - (cs s + ks)^2 = 0.
ms, mu_, ks, kt, cs, ct = 500, 50, 18000, 180000, 1500, 500
p1 = [ms, cs, ks]
p2 = [mu_, cs + ct, ks + kt]
poly = [0] * 5
for i in range(3):
    for j in range(3):
        poly[i + j] += p1[i] * p2[j]
poly[2] -= cs * cs
poly[3] -= 2 * cs * ks
poly[4] -= ks * ks
show("quarter_car defaults", roots(poly))
# Static gains of the road input: the sprung and unsprung masses follow the road, 1 m/m.

# Spring-mass-damper under a wing (seed paper eq. 13; docs/references.md D):
# m s^2 + (c + rho V S (CLa + CD)/2) s + k = 0.
m, k, c, rho, V, S = 1, 50, mp.mpf("0.2"), mp.mpf("1.225"), 10, mp.mpf("0.5")
CLa = mp.mpf("2.4812897959183675")
show("smd_wing defaults", roots([m, c + rho * V * S * CLa / 2, k]))
show("smd_wing V=20", roots([m, c + rho * 20 * S * CLa / 2, k]))

# Double pendulum of two uniform rods (mass centres at mid-length, centroidal inertia
# m l^2/12), pinned end to end: M = [[(m1/3 + m2) l1^2, m2 l1 l2/2], [m2 l1 l2/2, m2 l2^2/3]],
# K = g [[(m1/2 + m2) l1, 0], [0, m2 l2/2]]; det(M s^2 + K) = 0.
def double_pendulum(m1, m2, l1, l2, g):
    M = mp.matrix([[(m1 / 3 + m2) * l1**2, m2 * l1 * l2 / 2], [m2 * l1 * l2 / 2, m2 * l2**2 / 3]])
    K = mp.matrix([[g * (m1 / 2 + m2) * l1, 0], [0, g * m2 * l2 / 2]])
    # det(M s^2 + K) as a polynomial in s^2
    a = M[0, 0] * M[1, 1] - M[0, 1] ** 2
    b = M[0, 0] * K[1, 1] + K[0, 0] * M[1, 1]
    cc = K[0, 0] * K[1, 1]
    out = []
    for s2 in roots([a, b, cc]):
        out += [mp.sqrt(s2), -mp.sqrt(s2)]
    return sorted(out, key=lambda z: (float(z.real), float(z.imag)))


show("double_pendulum defaults", double_pendulum(1, 1, 1, 1, mp.mpf("9.81")))
show("double_pendulum m2=2 l2=0.5", double_pendulum(1, 2, 1, mp.mpf("0.5"), mp.mpf("9.81")))
# Static: the pin forces carry the weights; pin1 carries (m1 + m2) g, pin2 m2 g (vertical).

# Truck and trailer, yaw-rate gain of the steer angle from the steady turn (the derivation
# in tests/tests/truck_trailer.rs): the trailer's moment balance gives the hitch force, the
# truck's balances the axle forces, the front axle's slip the steer angle.
def yaw_rate_gain(u=10, m=mp.mpf("1730.3"), a=mp.mpf("1.289"), b=mp.mpf("1.596"), d=mp.mpf("2.7"),
                  cf=80000, cr=80000, mt=2000, e=mp.mpf("2.7"), h=mp.mpf("0.3")):
    l = a + b
    w = mt * h / (e + h)
    kf = u * (b * (m + w) - d * w) / l
    kr = u * (a * (m + w) + d * w) / l
    return 1 / (l / u + kf / cf - kr / cr)


show("truck_trailer r/delta_f defaults", [yaw_rate_gain()])
show("truck_trailer r/delta_f u=25", [yaw_rate_gain(u=25)])

# Car with wings, bounce and pitch (models/ride_wings.toml), derived by hand in the frame
# moving with the car: heave z up, pitch θ about y, nose down positive; the suspensions act on
# z - x θ and its rate. A wing at x_i, in the stream u from ahead, sees in its own axes
# (x forward, z down) w = -(z' + u θ - x_i θ') (the pitch attitude tilts the stream) and
# q = -θ', and pushes F_z = -Z, M_y = -M - x_i F_z, with (q̄ = ρ u S/2, per unit velocity)
# Z = q̄ (CZw w + CZq (c/2) q) and M = q̄ c (Cmw w + Cmq (c/2) q). The wings' derivatives are
# the file's (from a vortex lattice): the reference is the assembly, independent of eom's.
def ride_wings(u=40, rho=mp.mpf("1.225")):
    m, Iy, a, b = 1200, 1800, mp.mpf("1.2"), mp.mpf("1.4")
    kf, kr, cf, cr = 35000, 38000, 3000, 3000
    wings = [  # x, area, chord, CZw, CZq, Cmw, Cmq
        (a + mp.mpf("0.7"), mp.mpf("0.5599999999999999"), mp.mpf("0.35"), -mp.mpf("3.819025933690348"),
         -mp.mpf("3.936684282881915"), mp.mpf("0.058815165062207055"), -mp.mpf("0.683137734076857")),
        (-b - mp.mpf("0.4"), mp.mpf("0.52"), mp.mpf("0.4"), -mp.mpf("3.276807813097697"),
         -mp.mpf("3.4281261300766004"), mp.mpf("0.07564936740602789"), -mp.mpf("0.6484567116328459")),
    ]
    K = mp.zeros(2, 2)
    C = mp.zeros(2, 2)
    for x, ks, cs in [(a, kf, cf), (-b, kr, cr)]:
        g = [1, -x]
        for i in range(2):
            for j in range(2):
                K[i, j] += ks * g[i] * g[j]
                C[i, j] += cs * g[i] * g[j]
    for x, S, ch, CZw, CZq, Cmw, Cmq in wings:
        q = rho * u * S / 2
        zw, zq = q * CZw, q * CZq * ch / 2
        mw, mq = q * ch * Cmw, q * ch * Cmq * ch / 2
        fz = [zw, -zw * x + zq, zw * u]  # coefficients of z', θ', θ
        my = [mw - x * fz[0], (-mw * x + mq) - x * fz[1], mw * u - x * fz[2]]
        C[0, 0] -= fz[0]
        C[0, 1] -= fz[1]
        K[0, 1] -= fz[2]
        C[1, 0] -= my[0]
        C[1, 1] -= my[1]
        K[1, 1] -= my[2]
    A = mp.zeros(4, 4)
    A[0, 2] = A[1, 3] = 1
    Minv = [1 / mp.mpf(m), 1 / mp.mpf(Iy)]
    for i in range(2):
        for j in range(2):
            A[2 + i, j] = -Minv[i] * K[i, j]
            A[2 + i, 2 + j] = -Minv[i] * C[i, j]
    ev = mp.eig(A, left=False, right=False)
    return sorted((mp.mpc(z) for z in ev), key=lambda z: (float(z.real), float(z.imag)))


show("ride_wings defaults (u = 40)", ride_wings())
show("ride_wings u = 20", ride_wings(u=20))


# Static preloads (force on the body, ground axes, z up) from the equilibrium of forces and
# moments. Pendulum: the pin carries the weight m g. Double pendulum: pin1 carries both rods,
# pin2 the lower one. Half car: the axles share the weight by the lever rule, m g b/(a + b)
# front and m g a/(a + b) rear. Taildragger on its gear: the tail wheel at 4.6 m behind the
# mass centre and the two main wheels xm ahead share the weight W = m g by the lever rule,
# W xm/(xm + 4.6) on the tail wheel and W 4.6/(2 (xm + 4.6)) on each main wheel (no lift at
# the trim: the wing and tail sit at zero incidence).
show("pendulum pin", [10 * mp.mpf("9.807")])
show("double_pendulum pin1, pin2", [2 * mp.mpf("9.81"), mp.mpf("9.81")])
m, g, a, b = 1200, mp.mpf("9.81"), mp.mpf("1.2"), mp.mpf("1.4")
show("half_car front, rear", [m * g * b / (a + b), m * g * a / (a + b)])
W, xm = 550 * mp.mpf("9.81"), mp.mpf("0.45")
show("aircraft_ground tail, each main", [W * xm / (xm + mp.mpf("4.6")), W * mp.mpf("4.6") / (2 * (xm + mp.mpf("4.6")))])
