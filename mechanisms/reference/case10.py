#!/usr/bin/env python3
"""Case 10 (Meriam & Kraige 7th ed. P4/31): cart of mass 2m on a smooth horizontal track
carries a pendulum (light rod l = 0.5 m, bob of mass 2m as a particle), m = 1 kg, g = 9.81.
Released from rest with the pendulum upright; measured when the bob passes the bottom.
Coordinates: x (cart), theta (rod angle from the upward vertical); bob at
(x + l sin theta, l cos theta). Momentum 2m x' + 2m (x' + l theta' cos theta) = 0 and energy give,
at the bottom (theta = pi), from a start angle theta0:
  v_x = sqrt(g l (1 + cos theta0)),  theta' = 2 v_x / l   (theta0 -> 0: sqrt(2 g l), 2 sqrt(2g/l)).
Independent check: integrate the Lagrangian model from theta0 = 1e-6 rad to the event
theta - pi = 0 (rising) and compare with the theta0 formula."""
from mpmath import mp, mpf, sqrt, cos
from scipy.integrate import solve_ivp
import math

mp.dps = 30
g, l = mpf("9.81"), mpf("0.5")
vx = sqrt(2 * g * l)
print("theta_dot =", mp.nstr(2 * vx / l, 15))
print("v_x =", mp.nstr(vx, 15))
th0 = mpf("1e-6")
vx0 = sqrt(g * l * (1 + cos(th0)))
print("theta_dot(theta0=1e-6) =", mp.nstr(2 * vx0 / l, 15))
print("v_x(theta0=1e-6) =", mp.nstr(vx0, 15))

M, mb, lf, gf = 2.0, 2.0, 0.5, 9.81
def rhs(t, z):
    x, th, xd, thd = z
    c, s = math.cos(th), math.sin(th)
    # mass matrix of T = 1/2 M x'^2 + 1/2 mb [(x' + l c th')^2 + (l s th')^2], V = mb g l c
    a11, a12, a22 = M + mb, mb * lf * c, mb * lf * lf
    b1 = mb * lf * s * thd * thd
    b2 = mb * gf * lf * s
    det = a11 * a22 - a12 * a12
    return [xd, thd, (b1 * a22 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det]
ev = lambda t, z: z[1] - math.pi
ev.direction = 1
ev.terminal = True
sol = solve_ivp(rhs, (0, 50), [0.0, 1e-6, 0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-15, events=ev)
ye = sol.y_events[0][0]
print("numerical theta_dot(theta0=1e-6) =", "%.13g" % ye[3])
print("numerical v_x(theta0=1e-6) =", "%.13g" % ye[2])
print("numerical t_bottom =", "%.13g" % sol.t_events[0][0])
