#!/usr/bin/env python3
"""Case 07 (Meriam & Kraige 7th ed. P3/139): 0.9 kg collar released from rest at A slides up
a smooth straight rod (vertical plane) to the stop at B, pulled by a spring k = 24 N/m,
free length 0.375 m, anchored at O. Reconstructed geometry (from x_A = 0.4996, x_B = 0.125,
h_B = 0.25 and "measure v when the slider's x is zero"): O = (0, 0), B = (0, -0.5),
A = (0.45, -0.75); |OA| = sqrt(0.765) = 0.87464, |OB| = 0.5. Mass 0.9 kg is the mass that
reproduces v_B = 1.1558; the manual's figure uses g = 9.807 and x_A rounded to 0.4996.
Closed form by energy; independent check by integrating the 1-dof model along the rod to
the event x = 0 (x decreasing)."""
from mpmath import mp, mpf, sqrt
from scipy.integrate import solve_ivp
import math

mp.dps = 30
k, l0, m = mpf(24), mpf("0.375"), mpf("0.9")
xA = sqrt(mpf("0.45") ** 2 + mpf("0.75") ** 2) - l0
xB = mpf("0.5") - l0
hB = mpf("0.25")
vB = lambda g, xa: sqrt(k / m * (xa**2 - xB**2) - 2 * g * hB)
print("x_A =", mp.nstr(xA, 15))
print("v_B =", mp.nstr(vB(mpf("9.807"), xA), 15), " (g = 9.807, exact x_A)")
print("v_B_g981 =", mp.nstr(vB(mpf("9.81"), xA), 15), " (g = 9.81, exact x_A)")
print("v_B_manual_rounding =", mp.nstr(vB(mpf("9.807"), mpf("0.4996")), 15), " (g = 9.807, x_A = 0.4996)")

# numerical model: s = distance travelled from A along the unit vector u towards B
A = (0.45, -0.75)
Lr = math.hypot(0.45, 0.25)
u = (-0.45 / Lr, 0.25 / Lr)
for gf in (9.807, 9.81):
    def rhs(t, z):
        p = (A[0] + z[0] * u[0], A[1] + z[0] * u[1])
        d = math.hypot(*p)
        f = -24.0 * (d - 0.375) / d                      # spring force = f * p
        F = (f * p[0], f * p[1] - 0.9 * gf)
        return [z[1], (F[0] * u[0] + F[1] * u[1]) / 0.9]
    ev = lambda t, z: A[0] + z[0] * u[0]
    ev.direction = -1
    ev.terminal = True
    sol = solve_ivp(rhs, (0, 5), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-14, events=ev)
    print("numerical v_B (g = %s) =" % gf, "%.13g" % sol.y_events[0][0][1])
