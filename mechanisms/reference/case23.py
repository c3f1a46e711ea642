# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 23 - Meriam & Kraige 7th ed. P6/57: 6000-kg rectangular block 1.5 m x 2.5 m
# rotating about a fixed axis O (perpendicular to the 1.5 x 2.5 face) at d = 2.05 m from
# G; torque T = +30 N m until theta = 45 deg, then -30 N m, so it stops at 90 deg.
# No gravity moment about the axis (vertical axis / gravity along the rotation axis).
import numpy as np
from scipy.integrate import solve_ivp
m, a, b, d, T = mp.mpf(6000), mp.mpf("1.5"), mp.mpf("2.5"), mp.mpf("2.05"), mp.mpf(30)
IG = m * (a**2 + b**2) / 12
IO = IG + m * d**2
alpha = T / IO
t1 = mp.sqrt(2 * (mp.pi / 4) / alpha)
print("closed: I_G =", IG, " I_O =", IO)
print("closed: alpha =", alpha)
print("closed: t(45 deg) =", t1)
print("closed: t_90deg = 2 sqrt(pi I_O/(2T)) =", 2 * t1)
print("manual-rounded: alpha 1.018e-3 -> t =", 2 * mp.sqrt(mp.pi / 2 / mp.mpf("1.018e-3")))
# model: one coordinate theta, torque T sign(pi/4 - theta); event theta_dot = 0 decreasing
IOf = float(IO)
ev1 = lambda t, y: y[0] - np.pi / 4
ev1.terminal, ev1.direction = True, 1
s1 = solve_ivp(lambda t, y: [y[1], 30 / IOf], [0, 200], [0, 0], method="DOP853", rtol=1e-13, atol=1e-16, events=ev1)
ts, ys = s1.t_events[0][0], s1.y_events[0][0]
ev2 = lambda t, y: y[1]
ev2.terminal, ev2.direction = True, -1
s2 = solve_ivp(lambda t, y: [y[1], -30 / IOf], [ts, 400], ys, method="DOP853", rtol=1e-13, atol=1e-16, events=ev2)
print("ODE: switch t = %.15g" % ts)
print("t_90deg = %.15g" % s2.t_events[0][0])
print("ODE: theta at stop [deg] = %.15g" % np.degrees(s2.y_events[0][0][0]))
# the same two-phase model at 30 digits (mpmath.odefun), switch and stop by root finding
f1 = mp.odefun(lambda t, y: [y[1], T / IO], 0, [mp.mpf(0), mp.mpf(0)])
ts = mp.findroot(lambda t: f1(t)[0] - mp.pi / 4, mp.mpf(40))
f2 = mp.odefun(lambda t, y: [y[1], -T / IO], ts, list(f1(ts)))
tstop = mp.findroot(lambda t: f2(t)[1], mp.mpf(78))
print("mp ODE: switch t [s] =", ts)
print("t_90deg =", tstop)
print("mp ODE: theta at stop [deg] =", mp.degrees(f2(tstop)[0]))
