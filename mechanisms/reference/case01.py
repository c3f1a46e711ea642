#!/usr/bin/env python3
"""Case 01 (Meriam & Kraige 7th ed. P2/13): ball thrown up at 25 m/s from A at the foot of a
15 m cliff, lands at B on top of the cliff. g = 9.807 (the manual's value).
Closed form (uniform acceleration) and, independently, integration of the model y'' = -g
with events (apex: y' = 0 falling; landing: y - 15 = 0 falling)."""
from mpmath import mp, mpf, sqrt
from scipy.integrate import solve_ivp

mp.dps = 30
g, v0, H = mpf("9.807"), mpf(25), mpf(15)

# closed form
t_up = v0 / g
s_max = v0**2 / (2 * g)
h = s_max - H
t_AB = t_up + sqrt(2 * h / g)
v_B = sqrt(v0**2 - 2 * g * H)
print("h =", mp.nstr(h, 15))
print("t_AB =", mp.nstr(t_AB, 15))
print("v_B =", mp.nstr(v_B, 15))

# independent numerical model: q = y, ydd = -g, y(0)=0, yd(0)=25
gf = float(g)
def rhs(t, s):
    return [s[1], -gf]
apex = lambda t, s: s[1]
apex.direction = -1
land = lambda t, s: s[0] - 15.0
land.direction = -1
land.terminal = True
sol = solve_ivp(rhs, (0, 10), [0.0, 25.0], method="DOP853", rtol=1e-13, atol=1e-13,
                events=[apex, land], dense_output=True)
ta = sol.t_events[0][0]
tb = sol.t_events[1][0]
print("numerical h =", "%.13g" % (sol.y_events[0][0][0] - 15.0))
print("numerical t_AB =", "%.13g" % tb)
print("numerical v_B =", "%.13g" % abs(sol.y_events[1][0][1]))
