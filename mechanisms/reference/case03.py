#!/usr/bin/env python3
"""Case 03 (Meriam & Kraige 7th ed. P2/161): crank CA (90 mm) turns at beta' = 60 rad/s
(constant) about C, 300 mm from O; the pin A slides in the slotted arm pivoted at O.
O = (0, 0), C = (0.3, 0), A = C + 0.09(-cos beta, sin beta), beta = 30 deg at t = 0.
Quantities: r = |OA| rates r', r'', and the arm angle rates theta', theta''.
Closed form from the polar components of A's velocity/acceleration (as in the manual,
unrounded), and independently Newton on the loop closure
    r cos(theta) - (0.3 - 0.09 cos beta(t)) = 0,  r sin(theta) - 0.09 sin beta(t) = 0
with numerical time derivatives of the solved (r, theta)."""
from mpmath import mp, mpf, pi, sqrt, cos, sin, atan2, diff, findroot, matrix

mp.dps = 30
L, b, w = mpf("0.3"), mpf("0.09"), mpf(60)
beta0 = pi / 6

# closed form (manual's route, exact numbers)
xA, yA = L - b * cos(beta0), b * sin(beta0)
r = sqrt(xA**2 + yA**2)
th = atan2(yA, xA)
gam = beta0 + th
v, a = b * w, b * w**2                      # speed and (centripetal) acceleration of A
thd = v * cos(gam) / r
rd = v * sin(gam)
rdd = r * thd**2 + a * cos(gam)
thdd = (-a * sin(gam) - 2 * rd * thd) / r
print("r =", mp.nstr(r, 15))
print("theta_deg =", mp.nstr(th * 180 / pi, 15))
print("r_dot =", mp.nstr(rd, 15))
print("r_ddot =", mp.nstr(rdd, 15))
print("theta_dot =", mp.nstr(thd, 15))
print("theta_ddot =", mp.nstr(thdd, 15))

# independent: Newton on the loop closure for q = (r, theta) at time t
def q(t):
    be = beta0 + w * t
    f = lambda rr, tt: [rr * cos(tt) - (L - b * cos(be)), rr * sin(tt) - b * sin(be)]
    return findroot(f, (mpf("0.2266"), mpf("0.2")), tol=mpf(10) ** (-2 * mp.dps + 4))
rn = lambda t: q(t)[0]
tn = lambda t: q(t)[1]
print("numerical r_dot =", mp.nstr(diff(rn, 0), 15))
print("numerical r_ddot =", mp.nstr(diff(rn, 0, 2), 15))
print("numerical theta_dot =", mp.nstr(diff(tn, 0), 15))
print("numerical theta_ddot =", mp.nstr(diff(tn, 0, 2), 15))
