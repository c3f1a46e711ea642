# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 26 - Meriam & Kraige 7th ed. P6/139: crank OA (8 kg, |OA| = 0.4 m, G at 0.18 m
# from O, k_O = 0.22 m) pinned to a uniform slender bar AB (12 kg) whose end B slides on
# a smooth horizontal guide. Released from rest with OA horizontal; find v_B when OA
# swings through the vertical (A straight below O). g = 9.81.
# The manual fixes only the drops (G_OA 0.18 m, G_AB 0.2 m = half of A's 0.4 m drop);
# |AB| and the guide height are not in it. Reconstructed: O = (0, 0), A0 = (0.4, 0),
# |AB| = 0.8 m, guide y = 0 (B0 = (1.2, 0), O-A-B collinear at release), OA swinging
# clockwise (down). The result does not depend on these two choices (checked below).
import numpy as np
from scipy.integrate import solve_ivp
m1, m2, kO, rb, a, g = mp.mpf(8), mp.mpf(12), mp.mpf("0.22"), mp.mpf("0.18"), mp.mpf("0.4"), mp.mpf("9.81")
v = mp.sqrt((m1 * g * rb + m2 * g * a / 2) / (m1 * kO**2 / (2 * a**2) + m2 / 2))
print("closed: v_B = sqrt((8 g 0.18 + 12 g 0.2)/(1.21 + 6)) =", v)
print("closed: omega_OA =", v / a)
# model: theta (angle of OA from +x, ccw), B = (x_A + sqrt(L^2 - (yg - y_A)^2), yg);
# Lagrange: M(theta) thdd + 1/2 M'(theta) thd^2 = -V'(theta)  (double precision DOP853)
def run(L, yg):
    a = 0.4

    def kin(th):
        xa, ya = a * np.cos(th), a * np.sin(th)
        dxa, dya = -a * np.sin(th), a * np.cos(th)
        s = yg - ya
        wv = np.sqrt(L * L - s * s)
        dw = s * dya / wv                     # d/dth sqrt(L^2 - s^2), ds = -dya
        xb, dxb = xa + wv, dxa + dw
        gx, gy = (xa + xb) / 2, (ya + yg) / 2
        dgx, dgy = (dxa + dxb) / 2, dya / 2
        dphi = (wv * (-dya) - s * dw) / (L * L)
        return gx, gy, dgx, dgy, dphi, dxb
    I1, I2 = 8 * 0.22**2, 12 * L * L / 12
    def Mof(th):
        _, _, dgx, dgy, dphi, _ = kin(th)
        return I1 + 12 * (dgx**2 + dgy**2) + I2 * dphi**2
    def Vof(th):
        _, gy, _, _, _, _ = kin(th)
        return 8 * 9.81 * 0.18 * np.sin(th) + 12 * 9.81 * gy
    def d(f, x):   # complex-step derivative: exact to rounding for analytic f
        return (f(x + 1e-30j)).imag / 1e-30
    def rhs(t, y):
        th, w = y
        return [w, (-d(Vof, th) - 0.5 * d(Mof, th) * w * w) / Mof(th).real]
    ev = lambda t, y: y[0] + np.pi / 2
    ev.terminal, ev.direction = True, -1
    s = solve_ivp(rhs, [0, 5], [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, events=ev)
    th, w = s.y_events[0][0]
    return s.t_events[0][0], abs(kin(th)[5] * w), w
for L, yg in ((0.8, 0.0), (0.8, -0.1), (1.0, -0.3)):
    te, vb, w = run(L, yg)
    print("ODE (|AB| = %g, guide y = %g): t = %.12g s, omega_OA = %.13g, v_B = %.13g" % (L, yg, te, w, vb))
te, vb, w = run(0.8, 0.0)
print("v_B = %.13g" % vb)
