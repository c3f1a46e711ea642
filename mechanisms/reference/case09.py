#!/usr/bin/env python3
"""Case 09 (Meriam & Kraige 7th ed. P3/350): smooth tube of length 1 m pivoted at O rotates
in the vertical plane at constant omega0 = 0.5 rad/s, starting horizontal and turning
downward (theta measured below the horizontal); a particle starts at rest at O (r = 0).
Radial equation r'' - omega0^2 r = g sin(omega0 t), g = 9.81 (the manual's 0.10194 =
4 omega0^2 / g). Solution r = g/(2 omega0^2) (sinh(theta) - sin(theta)), theta = omega0 t.
Exit when r = 1: solve sinh(theta) - sin(theta) = 2 omega0^2 / g.
Independent check: integrate the 1-dof model (free r, driven theta) to the event r - 1 = 0
(rising)."""
from mpmath import mp, mpf, sinh, sin, findroot, pi
from scipy.integrate import solve_ivp
import math

mp.dps = 30
g, w = mpf("9.81"), mpf("0.5")
th = findroot(lambda x: sinh(x) - sin(x) - 2 * w**2 / g, mpf("0.53"))
print("theta_exit_rad =", mp.nstr(th, 15))
print("theta_exit_deg =", mp.nstr(th * 180 / pi, 15))
print("t_exit =", mp.nstr(th / w, 15))
print("theta_deg_of_manual_0.5347rad =", mp.nstr(mpf("0.5347") * 180 / pi, 15))

def rhs(t, z):
    return [z[1], 0.25 * z[0] + 9.81 * math.sin(0.5 * t)]
ev = lambda t, z: z[0] - 1.0
ev.direction = 1
ev.terminal = True
sol = solve_ivp(rhs, (0, 5), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-15, events=ev)
te = sol.t_events[0][0]
print("numerical t_exit =", "%.13g" % te)
print("numerical theta_exit_deg =", "%.13g" % math.degrees(0.5 * te))
