# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 28 - Meriam & Kraige 7th ed. P6/229: uniform slender bar OA, m = 30 kg, l = 2.4 m,
# pivoted at its lower end O, moving in the vertical plane; spring k = 3 kN/m from the
# fixed point C = (-1.2, 0) (1.2 m from O, horizontal) to the bar's midpoint G. At
# theta = 0 the bar is vertical (up), the spring is at its free length 1.2 sqrt 2 and the
# bar has omega_0 = 4 rad/s clockwise (theta increasing, the bar falls to the right).
# Wanted: the minimum angular speed and where it occurs, and omega at theta = 90 deg.
# g = 9.81.
import numpy as np
from scipy.integrate import solve_ivp
m, k, g, l, w0 = mp.mpf(30), mp.mpf(3000), mp.mpf("9.81"), mp.mpf("2.4"), mp.mpf(4)
IO = m * l**2 / 3
h = l / 2
def w2(th):
    ln = h * mp.sqrt(2 * (1 + mp.sin(th)))
    return (IO / 2 * w0**2 + m * g * h * (1 - mp.cos(th)) - k / 2 * (ln - h * mp.sqrt(2)) ** 2) / (IO / 2)
th_star = mp.findroot(lambda t: mp.diff(w2, t), mp.mpf("1.29"))
print("closed: theta at omega_min [rad] =", th_star, " [deg] =", mp.degrees(th_star))
print("closed: omega_min =", mp.sqrt(w2(th_star)))
print("closed: omega(90 deg) =", mp.sqrt(w2(mp.pi / 2)))
print("closed: omega(90 deg) = sqrt((460.8 + 353.16 - 4320 (3 - 2 sqrt 2))/28.8) =",
      mp.sqrt((mp.mpf("460.8") + mp.mpf("353.16") - 4320 * (3 - 2 * mp.sqrt(2))) / mp.mpf("28.8")))
# model: theta from the upward vertical, clockwise; G = h (sin th, cos th); C = (-h, 0)
def dV(th):
    gx, gy = 1.2 * np.sin(th), 1.2 * np.cos(th)
    dx, dy = gx + 1.2, gy
    ln = np.hypot(dx, dy)
    dgx, dgy = 1.2 * np.cos(th), -1.2 * np.sin(th)
    return 30 * 9.81 * dgy + 3000 * (ln - 1.2 * np.sqrt(2)) * (dx * dgx + dy * dgy) / ln
IOf = float(IO)
rhs = lambda t, y: [y[1], -dV(y[0]) / IOf]
ev1 = lambda t, y: -dV(y[0])            # theta_ddot crosses - -> + at the minimum of omega
ev1.terminal, ev1.direction = True, 1
s = solve_ivp(rhs, [0, 5], [0.0, 4.0], method="DOP853", rtol=1e-13, atol=1e-15, events=ev1)
te, (th, w) = s.t_events[0][0], s.y_events[0][0]
print("ODE: event t = %.13g s" % te)
print("omega_min = %.13g" % w)
print("theta_at_omega_min [deg] = %.13g" % np.degrees(th))
ev2 = lambda t, y: y[0] - np.pi / 2
ev2.terminal, ev2.direction = True, 1
s = solve_ivp(rhs, [0, 5], [0.0, 4.0], method="DOP853", rtol=1e-13, atol=1e-15, events=ev2)
print("ODE: t(90 deg) = %.13g s" % s.t_events[0][0])
print("omega_at_90deg = %.13g" % s.y_events[0][0][1])
# the same model at 30 digits (mpmath Taylor integrator), events by root finding
def dVm(th):
    gx, gy = h * mp.sin(th), h * mp.cos(th)
    dx, dy = gx + h, gy
    ln = mp.sqrt(dx * dx + dy * dy)
    dgx, dgy = h * mp.cos(th), -h * mp.sin(th)
    return m * g * dgy + k * (ln - h * mp.sqrt(2)) * (dx * dgx + dy * dgy) / ln
f = mp.odefun(lambda t, y: [y[1], -dVm(y[0]) / IO], 0, [mp.mpf(0), w0])
t1 = mp.findroot(lambda t: dVm(f(t)[0]), mp.mpf(te))
print("mp ODE: event t (omega_min) [s] =", t1)
print("omega_min =", f(t1)[1])
print("theta_at_omega_min [deg] =", mp.degrees(f(t1)[0]))
t2 = mp.findroot(lambda t: f(t)[0] - mp.pi / 2, mp.mpf(s.t_events[0][0]))
print("mp ODE: t(90 deg) [s] =", t2)
print("omega_at_90deg =", f(t2)[1])
