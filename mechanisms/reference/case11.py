#!/usr/bin/env python3
"""Case 11 (Meriam & Kraige 7th ed. Sample Problem 5/9): slider-crank, crank OB r = 0.125 m
turning clockwise at 1500 rev/min (50 pi rad/s), connecting rod AB l = 0.35 m with G at
l1 = 0.25 m from A (0.1 m from B), piston A on the line through O; instant theta = AOB = 60 deg.
Frame: O = (0,0), A = (x_A, 0) with x_A > 0, B = r (cos phi, sin phi), phi(t) = pi/3 - 50 pi t.
Closed form: sin(beta) = r sin(theta)/l, beta' = r theta' cos(theta)/(l cos(beta)),
x_A = r cos(theta) + l cos(beta), G = (x_A - l1 cos(beta), l1 sin(beta)).
Independent check: Newton on the loop closure in q = (x_A, psi) (psi = absolute angle of A->B)
  x_A + l cos(psi) - r cos(phi(t)) = 0,  l sin(psi) - r sin(phi(t)) = 0
and numerical time derivatives of G = (x_A + l1 cos psi, l1 sin psi) and psi."""
from mpmath import mp, mpf, pi, sqrt, sin, cos, asin, diff, findroot

mp.dps = 30
r, l, l1, w = mpf("0.125"), mpf("0.35"), mpf("0.25"), 50 * pi
th, thd = pi / 3, -w
be = asin(r * sin(th) / l)
bed = r * thd * cos(th) / (l * cos(be))
xAd = -r * sin(th) * thd - l * sin(be) * bed
vG = sqrt((xAd + l1 * sin(be) * bed) ** 2 + (l1 * cos(be) * bed) ** 2)
print("beta_deg =", mp.nstr(be * 180 / pi, 15))
print("v_A =", mp.nstr(abs(xAd), 15))
print("v_G =", mp.nstr(vG, 15))
print("omega_AB =", mp.nstr(abs(bed), 15))

def q(t):
    ph = pi / 3 - w * t
    f = lambda x, ps: [x + l * cos(ps) - r * cos(ph), l * sin(ps) - r * sin(ph)]
    return findroot(f, (mpf("0.395"), pi - be), tol=mpf(10) ** (-2 * mp.dps + 4))
Gx = lambda t: q(t)[0] + l1 * cos(q(t)[1])
Gy = lambda t: l1 * sin(q(t)[1])
print("numerical v_A =", mp.nstr(abs(diff(lambda t: q(t)[0], 0)), 15))
print("numerical v_G =", mp.nstr(sqrt(diff(Gx, 0) ** 2 + diff(Gy, 0) ** 2), 15))
print("numerical omega_AB (psi') =", mp.nstr(diff(lambda t: q(t)[1], 0), 15))
