#!/usr/bin/env python3
"""Case 04 (Meriam & Kraige 7th ed. P2/253): pendulum OA (l = 0.8 m) driven by the
prescribed small-oscillation law theta(t) = theta0 sin(omega_n t), theta0 = pi/3,
omega_n = sqrt(g/l), g = 9.81 (the manual's value: a_max = g theta0^2 = 10.76 needs 9.81).
Acceleration magnitude of A: |a| = g theta0 sqrt(sin^2 + theta0^2 cos^4) (of omega_n t).
Extremes over the first quarter period: max at t = 0 (g theta0^2), min where
cos^2(omega_n t) = 1/(2 theta0^2): |a|min = g theta0 sqrt(1 - 1/(4 theta0^2)).
Independent check: Cartesian position of A differentiated twice numerically, and the
minimum located as the zero crossing (upward) of d|a|^2/dt by Newton."""
from mpmath import mp, mpf, pi, sqrt, sin, cos, acos, diff, findroot

mp.dps = 30
g, l, th0 = mpf("9.81"), mpf("0.8"), pi / 3
wn = sqrt(g / l)

a_max = g * th0**2
t_min = acos(1 / (sqrt(2) * th0)) / wn
a_min = g * th0 * sqrt(1 - 1 / (4 * th0**2))
th_min = th0 * sin(wn * t_min)
print("a_min =", mp.nstr(a_min, 15))
print("t_at_a_min =", mp.nstr(t_min, 15))
print("theta_at_a_min_deg =", mp.nstr(th_min * 180 / pi, 15))
print("a_max =", mp.nstr(a_max, 15))
print("t_at_a_max =", 0)
print("quarter_period =", mp.nstr(pi / (2 * wn), 15))
print("a_at_quarter_period =", mp.nstr(g * th0, 15))

# independent: A = l (sin theta, -cos theta) with the driven theta(t)
th = lambda t: th0 * sin(wn * t)
x = lambda t: l * sin(th(t))
y = lambda t: -l * cos(th(t))
a2 = lambda t: diff(x, t, 2) ** 2 + diff(y, t, 2) ** 2
da2 = lambda t: diff(a2, t)
tn = findroot(da2, (mpf("0.1"), mpf("0.4")), solver="anderson")
print("numerical t_at_a_min =", mp.nstr(tn, 15))
print("numerical a_min =", mp.nstr(sqrt(a2(tn)), 15))
print("numerical theta_at_a_min_deg =", mp.nstr(th(tn) * 180 / pi, 15))
print("numerical a_max =", mp.nstr(sqrt(a2(mpf(0))), 15))
