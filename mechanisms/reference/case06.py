#!/usr/bin/env python3
"""Case 06 (Meriam & Kraige 7th ed., sliders A and B joined by a light rigid link of length
0.5 m; the manual misprints the reference as P3/2). Horizontal plane: A (2 kg) slides along
the x axis pushed by P = 40 N (+x), B (3 kg) slides along the y axis; weight plays no part
(the worked equation for B has no mg term). Instant: x_A = 0.4, y_B = 0.3, x_A' = 0.9,
y_B' = -1.2 (m, m/s). T = link tension (pulls A towards B).
Closed form: a_A = 15/11, a_B = -205/22, T = 1025/22 (exact solution of the manual's two
equations). Independent check: Lagrange multiplier form
  M q'' + Phi_q^T lam = Q,  Phi_q q'' = gamma
with Phi = sqrt(x_A^2 + y_B^2) - L, solved as one linear system (lam = T)."""
from mpmath import mp, mpf, matrix, lu_solve, sqrt

mp.dps = 30
print("a_A =", mp.nstr(mpf(15) / 11, 15))
print("a_B =", mp.nstr(mpf(-205) / 22, 15))
print("T =", mp.nstr(mpf(1025) / 22, 15))

mA, mB, P = mpf(2), mpf(3), mpf(40)
x, y, xd, yd = mpf("0.4"), mpf("0.3"), mpf("0.9"), mpf("-1.2")
d = sqrt(x**2 + y**2)
J = [x / d, y / d]                                      # Phi_q
# gamma = -(d/dt Phi_q) q' = -(second derivative of d with q'' = 0)
gam = -((xd**2 + yd**2) / d - (x * xd + y * yd) ** 2 / d**3)
A = matrix([[mA, 0, J[0]], [0, mB, J[1]], [J[0], J[1], 0]])
s = lu_solve(A, matrix([P, 0, gam]))
print("numerical a_A =", mp.nstr(s[0], 15))
print("numerical a_B =", mp.nstr(s[1], 15))
print("numerical T =", mp.nstr(s[2], 15))
