#!/usr/bin/env python3
"""Case 02 (Meriam & Kraige 7th ed. P2/136): point B in polar coordinates with r = 0.5 m,
r' = -0.15 m/s, theta' = 60 deg/s, r'' = 0, theta'' = 0 (the worked a_r = -548.31 mm/s^2 and
a_theta = -314.16 mm/s^2 are exactly -r theta'^2 and 2 r' theta', so both rates are constant).
Closed form in polar components, and independently the Cartesian position
x = r(t) cos(theta(t)), y = r(t) sin(theta(t)) differentiated numerically at t = 0."""
from mpmath import mp, mpf, pi, sqrt, cos, sin, diff

mp.dps = 30
r0, rd, thd = mpf("0.5"), mpf("-0.15"), pi / 3

v = sqrt(rd**2 + (r0 * thd) ** 2)
a = sqrt((-r0 * thd**2) ** 2 + (2 * rd * thd) ** 2)
print("v =", mp.nstr(v, 15))
print("a =", mp.nstr(a, 15))

# driven coordinates r(t) = 0.5 - 0.15 t, theta(t) = (pi/3) t; Cartesian point B
x = lambda t: (r0 + rd * t) * cos(thd * t)
y = lambda t: (r0 + rd * t) * sin(thd * t)
vn = sqrt(diff(x, 0) ** 2 + diff(y, 0) ** 2)
an = sqrt(diff(x, 0, 2) ** 2 + diff(y, 0, 2) ** 2)
print("numerical v =", mp.nstr(vn, 15))
print("numerical a =", mp.nstr(an, 15))
