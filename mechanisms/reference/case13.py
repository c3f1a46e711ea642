#!/usr/bin/env python3
"""Case 13 (Meriam & Kraige 7th ed. P5/57): slider-crank, crank OB r = 0.1 m at constant
omega0 = theta' = 3 rad/s, rod AB l = 0.2 m, slider A on the line through O; instant
theta = 60 deg. beta = rod angle with the slider line, l sin(beta) = r sin(theta);
the manual's omega_AB = beta', alpha_AB = beta'' (the rod's absolute angle is pi - beta).
Closed form: beta' = (r/l) w cos(theta)/sqrt(1 - (r/l sin theta)^2),
  beta'' = (r/l) w^2 sin(theta) ((r/l)^2 - 1)/(1 - (r/l sin theta)^2)^(3/2).
Independent check: Newton on q = (x_A, psi)
  x_A + l cos(psi) - r cos(theta(t)) = 0,  l sin(psi) - r sin(theta(t)) = 0, theta = pi/3 + 3t
with beta = pi - psi, derivatives numerically."""
from mpmath import mp, mpf, pi, sin, cos, sqrt, asin, diff, findroot

mp.dps = 30
r, l, w = mpf("0.1"), mpf("0.2"), mpf(3)
th = pi / 3
k = r / l
c = 1 - (k * sin(th)) ** 2
om = k * w * cos(th) / sqrt(c)
al = k * w**2 * sin(th) * (k**2 - 1) / c ** mpf(1.5)
print("omega_AB =", mp.nstr(om, 15))
print("alpha_AB =", mp.nstr(al, 15))

be0 = asin(k * sin(th))
def q(t):
    tt = th + w * t
    f = lambda x, ps: [x + l * cos(ps) - r * cos(tt), l * sin(ps) - r * sin(tt)]
    return findroot(f, (r * cos(th) + l * cos(be0), pi - be0), tol=mpf(10) ** (-2 * mp.dps + 4))
beta = lambda t: pi - q(t)[1]
print("numerical omega_AB =", mp.nstr(diff(beta, 0), 15))
print("numerical alpha_AB =", mp.nstr(diff(beta, 0, 2), 15))
