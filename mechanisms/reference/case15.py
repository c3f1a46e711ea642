#!/usr/bin/env python3
"""Case 15 (Meriam & Kraige 7th ed. P5/89): four-bar O-B-A-C. Crank OB (0.12 m) turns
clockwise at 0.5 rad/s about O; coupler BA; rocker CA (0.2 m, tan = 4/3) about C.
Instant (from the worked vectors r_OB = 0.12 j, r_CA = (-0.12, 0.16), r_BA = (-0.24, 0.04)):
O = (0, 0), B = (0, 0.12), A = (-0.24, 0.16), C = (-0.12, 0); |BA| = sqrt(0.0592).
Closed form: the manual's two velocity equations, 0.16 w_AC = 0.06 + 0.04 w_AB and
0.12 w_AC = 0.24 w_AB, give w_AB = 3/14, w_AC = 3/7 (both clockwise).
Independent check: Newton on q = (psi, chi), psi = angle of B->A, chi = angle of C->A,
  0.12 cos(phi) + d cos(psi) - (-0.12 + 0.2 cos(chi)) = 0,
  0.12 sin(phi) + d sin(psi) - 0.2 sin(chi) = 0,  phi(t) = pi/2 - 0.5 t,
clockwise rates = -psi', -chi'."""
from mpmath import mp, mpf, pi, sin, cos, sqrt, atan2, diff, findroot

mp.dps = 30
print("omega_AB =", mp.nstr(mpf(3) / 14, 15))
print("omega_AC =", mp.nstr(mpf(3) / 7, 15))

a, c, w = mpf("0.12"), mpf("0.2"), mpf("0.5")
d = sqrt(mpf("0.24") ** 2 + mpf("0.04") ** 2)
def q(t):
    ph = pi / 2 - w * t
    f = lambda ps, ch: [a * cos(ph) + d * cos(ps) + a - c * cos(ch),
                        a * sin(ph) + d * sin(ps) - c * sin(ch)]
    return findroot(f, (atan2(mpf("0.04"), mpf("-0.24")), atan2(mpf("0.16"), mpf("-0.12"))),
                    tol=mpf(10) ** (-2 * mp.dps + 4))
print("numerical omega_AB =", mp.nstr(-diff(lambda t: q(t)[0], 0), 15))
print("numerical omega_AC =", mp.nstr(-diff(lambda t: q(t)[1], 0), 15))
