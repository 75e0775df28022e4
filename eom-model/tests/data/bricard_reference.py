# The reference of eom-model/tests/statics_scale.rs::bricard_linkage_moves_with_one_degree_of_freedom,
# run by hand (pip install mpmath): python3 bricard_reference.py
# Orthogonal Bricard 6R linkage (all link lengths a, twists alternately +90/-90 deg, offsets 0):
# configuration at theta1 = 0.9 and its one-degree-of-freedom eigenvalues, in 50 digits.
import mpmath as mp
mp.mp.dps = 50
a = mp.mpf(1)
AL = [mp.pi/2, 3*mp.pi/2]*3
def T(th, al):
    ct, st, ca, sa = mp.cos(th), mp.sin(th), mp.cos(al), mp.sin(al)
    return mp.matrix([[ct,-st*ca, st*sa, a*ct],[st, ct*ca,-ct*sa,a*st],[0,sa,ca,0],[0,0,0,1]])
th = mp.mpf('0.9')
def chain(phi):
    angs = [th, phi]*3
    F = [mp.eye(4)]
    for i in range(6): F.append(F[-1]*T(angs[i], AL[i]))
    return F
phi = mp.findroot(lambda p: chain(p)[6][0,3], mp.mpf('1.964194'))
F = chain(phi)
res = max(abs(x) for x in (F[6]-mp.eye(4)))
print("phi", phi, "closure residual", mp.nstr(res, 3))
O = [F[i][0:3,3] for i in range(6)]
Z = [F[i][0:3,2] for i in range(6)]
def cross(u,v): return mp.matrix([u[1]*v[2]-u[2]*v[1], u[2]*v[0]-u[0]*v[2], u[0]*v[1]-u[1]*v[0]])
S = mp.matrix(6,6)
for j in range(6):
    m = cross(O[j], Z[j])
    for r in range(3): S[r,j] = Z[j][r]; S[r+3,j] = m[r]
U, sv, V = mp.svd_r(S)
print("singular values", [mp.nstr(x,5) for x in sv])
w = V[5,:]  # right null vector (last row of V^T)
w = [w[j]/w[0] for j in range(6)]
print("joint rates", [mp.nstr(x,10) for x in w])
masses = [1 + mp.mpf(i)/10 for i in range(1,6)]
J = mp.mpf('0.05')
meff = mp.mpf(0)
centres = []
for i in range(1,6):  # link i, i = 1..5, between joints i and i+1 (O[i-1], O[i])
    c = (O[i-1] + O[i])/2
    centres.append(c)
    Om = sum((Z[j]*w[j] for j in range(i)), mp.matrix([0,0,0]))
    v0 = sum((cross(O[j],Z[j])*w[j] for j in range(i)), mp.matrix([0,0,0]))
    v = cross(Om, c) + v0
    meff += masses[i-1]*mp.fsum(x**2 for x in v) + J*mp.fsum(x**2 for x in Om)
k, c = mp.mpf(5), mp.mpf('0.1')
disc = mp.sqrt(c**2 - 4*meff*k + 0j)
lam = [(-c + disc)/(2*meff), (-c - disc)/(2*meff)]
print("meff", meff)
print("lambda", lam[0])
for i in range(6): print("joint", i+1, "at", [mp.nstr(x,17) for x in O[i]], "axis", [mp.nstr(x,17) for x in Z[i]])
for i in range(5): print("link", i+1, "centre", [mp.nstr(x,17) for x in centres[i]], "mass", masses[i])
