#!/usr/bin/env python3
"""Case 12 (Meriam & Kraige 7th ed. P5/54): crank of radius r = 0.1 m turns about its fixed
pivot P1 at theta' = 3 rad/s; its pin X slides in a slotted link pivoted at P2, l = 0.2 m from
P1 on the theta = 0 line; instant theta = 45 deg. beta = angle at P2 between P2->P1 and
P2->X; omega = beta' (the slotted link's angular speed). The worked solution uses
theta' = 3, l = 0.2, r = 0.1; the manual's data table (0.5 rad/s, r = 0.2, l = 0.1) is wrong.
Closed form: tan(beta) = r sin(theta)/(l - r cos(theta)),
  beta' = r theta' cos(theta+beta)/(l cos(beta) - r cos(theta+beta)).
Independent check: Newton on q = (s, phi) (phi = absolute angle of P2->X, s = |P2 X|)
  l + s cos(phi) - r cos(theta(t)) = 0,  s sin(phi) - r sin(theta(t)) = 0,  theta(t) = pi/4 + 3t
beta = pi - phi, so beta' = -phi' (the link turns clockwise while the crank turns ccw)."""
from mpmath import mp, mpf, pi, sin, cos, atan, diff, findroot

mp.dps = 30
r, l, w = mpf("0.1"), mpf("0.2"), mpf(3)
th = pi / 4
be = atan(r * sin(th) / (l - r * cos(th)))
om = r * w * cos(th + be) / (l * cos(be) - r * cos(th + be))
print("beta_deg =", mp.nstr(be * 180 / pi, 15))
print("omega_link =", mp.nstr(om, 15))

def q(t):
    tt = pi / 4 + w * t
    f = lambda s, ph: [l + s * cos(ph) - r * cos(tt), s * sin(ph) - r * sin(tt)]
    return findroot(f, (mpf("0.147"), pi - be), tol=mpf(10) ** (-2 * mp.dps + 4))
print("numerical omega_link (-phi') =", mp.nstr(-diff(lambda t: q(t)[1], 0), 15))
