# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 30 - Meriam & Kraige 7th ed. P8/36: mass-spring-damper, m = 3 kg, k = 108 N/m,
# c = 18 N s/m, released from rest at x0 = 0.3 m (x from the unstretched spring, motion
# horizontal so gravity does not act along x). Wanted: x1, the position at the end of the
# first half damped period, i.e. the first minimum (x_dot = 0, from - to +).
import numpy as np
from scipy.integrate import solve_ivp
m, k, c, x0 = mp.mpf(3), mp.mpf(108), mp.mpf(18), mp.mpf("0.3")
wn = mp.sqrt(k / m)
z = c / (2 * mp.sqrt(m * k))
wd = wn * mp.sqrt(1 - z**2)
t1 = mp.pi / wd
x1 = -x0 * mp.exp(-z * wn * t1)
print("closed: omega_n =", wn, " zeta =", z, " omega_d =", wd)
print("closed: t1 = pi/omega_d =", t1)
print("closed: x1 = -x0 exp(-pi/sqrt 3) =", x1)
print("manual-rounded: -0.163 x0 =", mp.mpf("-0.163") * x0)
ev = lambda t, y: y[1]
ev.terminal, ev.direction = True, 1
s = solve_ivp(lambda t, y: [y[1], -(18 * y[1] + 108 * y[0]) / 3], [0, 5], [0.3, 0.0], method="DOP853",
              rtol=1e-13, atol=1e-16, events=ev)
print("ODE: t1 = %.13g s" % s.t_events[0][0])
print("x_1 = %.13g" % s.y_events[0][0][0])
# the same model at 30 digits (mpmath Taylor integrator), event by root finding
f = mp.odefun(lambda t, y: [y[1], -(c * y[1] + k * y[0]) / m], 0, [x0, mp.mpf(0)])
te = mp.findroot(lambda t: f(t)[1], mp.mpf(s.t_events[0][0]))
print("mp ODE: t1 [s] =", te)
print("x_1 =", f(te)[0])
