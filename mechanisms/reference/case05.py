#!/usr/bin/env python3
"""Case 05 (Meriam & Kraige 7th ed. P3/2): 50 kg crate launched down a 15 deg incline at
7 m/s, kinetic friction mu = 0.40, g = 9.81 (the manual's value). Constant deceleration
a = g (sin 15 - mu cos 15) < 0, so it stops after s = v0^2/(2|a|), t = v0/|a|.
(For 30 deg, a = g (sin 30 - mu cos 30) > 0: it never stops.)
Independent check: the model s'' = g sin(th) - mu N/m sign(s'), N = m g cos(th) (the normal
reaction, i.e. the multiplier of the relaxed normal coordinate), integrated to the event
s' = 0 (falling)."""
from mpmath import mp, mpf, pi, sin, cos
from scipy.integrate import solve_ivp
import math

mp.dps = 30
g, mu, v0, m = mpf("9.81"), mpf("0.40"), mpf(7), mpf(50)
for deg in (15, 30):
    th = mpf(deg) * pi / 180
    a = g * (sin(th) - mu * cos(th))
    print("a_%d =" % deg, mp.nstr(a, 15))
th = pi / 12
a = g * (sin(th) - mu * cos(th))
print("t_stop_15 =", mp.nstr(-v0 / a, 15))
print("x_stop_15 =", mp.nstr(v0**2 / (-2 * a), 15))
print("N_15 =", mp.nstr(m * g * cos(th), 15))

gf, muf, thf = 9.81, 0.40, math.pi / 12
def rhs(t, s):
    N = 50 * gf * math.cos(thf)                 # normal reaction (relaxed coordinate)
    # sliding phase (s' > 0 until the stop event): kinetic friction opposes s'
    return [s[1], gf * math.sin(thf) - muf * N / 50]
stop = lambda t, s: s[1]
stop.direction = -1
stop.terminal = True
sol = solve_ivp(rhs, (0, 20), [0.0, 7.0], method="DOP853", rtol=1e-13, atol=1e-13, events=stop)
print("numerical t_stop_15 =", "%.13g" % sol.t_events[0][0])
print("numerical x_stop_15 =", "%.13g" % sol.y_events[0][0][0])
