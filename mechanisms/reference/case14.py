#!/usr/bin/env python3
"""Case 14 (Meriam & Kraige 7th ed. P5/80): crank OB (r = 0.25 m) turns clockwise at
0.8 rad/s about O; link AB (l = 0.5 m); end A slides on a straight guide inclined 20 deg to
the horizontal; C is the midpoint of AB. Instant: OB horizontal (B = (0.25, 0)), A directly
below O at (0, -h), h = sqrt(l^2 - r^2) = 0.4330; guide through A with direction
(cos 20, sin 20) (the worked IC distances 0.158 = h tan 20 and 0.461 = h / cos 20 pin this).
Closed form (instant centre I on the line OB at x = -h tan 20):
  omega_AB = v_B/|IB|, v_A = omega_AB |IA|, v_C = omega_AB |IC|.
Independent check: Newton on q = (s, psi), s = slider travel along the guide, psi = angle of B->A
  r cos(phi) + l cos(psi) - s cos20 = 0,  r sin(phi) + l sin(psi) + h - s sin20 = 0,
  phi(t) = -0.8 t; v_A = |s'|, v_C = |d/dt (B + l/2 (cos psi, sin psi))|."""
from mpmath import mp, mpf, pi, sin, cos, tan, sqrt, atan2, diff, findroot

mp.dps = 30
r, l, w = mpf("0.25"), mpf("0.5"), mpf("0.8")
be = pi / 9
h = sqrt(l**2 - r**2)
xi = -h * tan(be)
om = r * w / (r - xi)
vA = om * h / cos(be)
vC = om * sqrt((r / 2 - xi) ** 2 + (h / 2) ** 2)
print("omega_AB =", mp.nstr(om, 15))
print("v_A =", mp.nstr(vA, 15))
print("v_C =", mp.nstr(vC, 15))

def q(t):
    ph = -w * t
    f = lambda s, ps: [r * cos(ph) + l * cos(ps) - s * cos(be),
                       r * sin(ph) + l * sin(ps) + h - s * sin(be)]
    return findroot(f, (mpf(0), atan2(-h, -r)), tol=mpf(10) ** (-2 * mp.dps + 4))
Cx = lambda t: r * cos(-w * t) + l / 2 * cos(q(t)[1])
Cy = lambda t: r * sin(-w * t) + l / 2 * sin(q(t)[1])
print("numerical omega_AB (-psi') =", mp.nstr(-diff(lambda t: q(t)[1], 0), 15))
print("numerical v_A =", mp.nstr(abs(diff(lambda t: q(t)[0], 0)), 15))
print("numerical v_C =", mp.nstr(sqrt(diff(Cx, 0) ** 2 + diff(Cy, 0) ** 2), 15))
