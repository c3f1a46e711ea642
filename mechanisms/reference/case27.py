# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 27 - Meriam & Kraige 7th ed. P6/221: uniform slender bar OB, m = 1.2 kg, length
# l1 + l2 = 0.8 m, pivoted at its end O; spring k = 100 N/m from the fixed point C,
# 0.6 m directly above O, to the point A of the bar 0.6 m from O. Released from rest with
# the bar horizontal (theta = 0, spring at its free length 0.6 sqrt 2); theta measured
# downward from the horizontal. Wanted: the maximum angular speed and the angle where it
# occurs. g = 9.81.
import numpy as np
from scipy.integrate import solve_ivp
m, k, g, L, a = mp.mpf("1.2"), mp.mpf(100), mp.mpf("9.81"), mp.mpf("0.8"), mp.mpf("0.6")
IO = m * L**2 / 3
l0 = a * mp.sqrt(2)
def w2(th):   # energy: 1/2 IO w^2 = m g (L/2) sin th - 1/2 k (len - l0)^2
    ln = a * mp.sqrt(2 * (1 + mp.sin(th)))
    return (m * g * L / 2 * mp.sin(th) - k / 2 * (ln - l0) ** 2) / (IO / 2)
# d(w^2)/dth = 0: cos th [m g L/2 - k a^2 (1 - 1/sqrt(1 + sin th))] = 0
root = k * a**2 / (k * a**2 - m * g * L / 2)   # sqrt(1 + sin th)
th_star = mp.asin(root**2 - 1)
print("closed: sqrt(1 + sin th*) = 36/31.2912 =", root)
print("closed: theta at omega_max [rad] =", th_star, " [deg] =", mp.degrees(th_star))
print("closed: omega_max =", mp.sqrt(w2(th_star)))
print("closed: theta_max (rest) [deg] =", mp.degrees(mp.asin(mp.findroot(lambda X: (m * g * L / 2) * X - k / 2 * (a * mp.sqrt(2 * (1 + X)) - l0) ** 2, 0.7))))
# model: coordinate theta; bar B = L (cos th, -sin th); spring from C = (0, a) to
# A = a (cos th, -sin th); V = m g y_G + k/2 (|A - C| - l0)^2; IO thdd = -V'(th).
def dV(th):
    ax_, ay_ = 0.6 * np.cos(th), -0.6 * np.sin(th)
    dx, dy = ax_, ay_ - 0.6
    ln = np.hypot(dx, dy)
    dax, day = -0.6 * np.sin(th), -0.6 * np.cos(th)
    dln = (dx * dax + dy * day) / ln
    return 1.2 * 9.81 * (-0.4 * np.cos(th)) + 100 * (ln - 0.6 * np.sqrt(2)) * dln
IOf = float(IO)
ev = lambda t, y: -dV(y[0])             # theta_ddot, crosses + -> - at omega max
ev.terminal, ev.direction = True, -1
s = solve_ivp(lambda t, y: [y[1], -dV(y[0]) / IOf], [0, 5], [0.0, 0.0], method="DOP853",
              rtol=1e-13, atol=1e-15, events=ev)
te, (th, w) = s.t_events[0][0], s.y_events[0][0]
print("ODE: event t = %.13g s" % te)
print("omega_max = %.13g" % w)
print("theta_at_omega_max [deg] = %.13g" % np.degrees(th))
# the same model at 30 digits (mpmath Taylor integrator), event by root finding
def dVm(th):
    ax_, ay_ = a * mp.cos(th), -a * mp.sin(th)
    dx, dy = ax_, ay_ - a
    ln = mp.sqrt(dx * dx + dy * dy)
    dax, day = -a * mp.sin(th), -a * mp.cos(th)
    return m * g * (-L / 2 * mp.cos(th)) + k * (ln - l0) * (dx * dax + dy * day) / ln
f = mp.odefun(lambda t, y: [y[1], -dVm(y[0]) / IO], 0, [mp.mpf(0), mp.mpf(0)])
te = mp.findroot(lambda t: dVm(f(t)[0]), mp.mpf(te))
print("mp ODE: event t [s] =", te)
print("omega_max =", f(te)[1])
print("theta_at_omega_max [deg] =", mp.degrees(f(te)[0]))
