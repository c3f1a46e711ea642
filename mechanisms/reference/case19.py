# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 19 - Meriam & Kraige 7th ed. P5/212: slider-crank, crank OB r = 0.125 m at a
# constant 1500 rev/min (theta = omega t, theta = 0 with B on the cylinder axis on the
# piston side), connecting rod BA l = 0.35 m, piston A on the horizontal line through O.
# x = OA = r cos(theta) + l cos(beta), l sin(beta) = r sin(theta); v_A = -x_dot (toward O).
r, l = mp.mpf("0.125"), mp.mpf("0.35")
w = 1500 * 2 * mp.pi / 60
def vA(th):
    return r * w * mp.sin(th) * (1 + mp.cos(th) / mp.sqrt((l / r) ** 2 - mp.sin(th) ** 2))
def aA(th):
    return mp.diff(vA, th) * w
th_star = mp.findroot(lambda th: mp.diff(vA, th), mp.mpf("1.26"))
print("omega [rad/s] =", w)
print("closed: theta at v_A max [rad] =", th_star)
print("closed: theta at v_A max [deg] =", mp.degrees(th_star))
print("closed: v_A max [m/s] =", vA(th_star))
print("closed: v_A at theta = 0.4 pi (72 deg) =", vA(2 * mp.pi / 5))
print("closed: a_A(0) =", r * w**2 * (1 + r / l), " a_A(pi) =", r * w**2 * (-1 + r / l))
# model: coordinates theta(t) = w t driven, beta and x free; loop closure
#   Phi1 = r cos th + l cos beta - x = 0,  Phi2 = r sin th - l sin beta = 0
def x_of(t):
    th = w * t
    sol = mp.findroot(lambda b, x: [r * mp.cos(th) + l * mp.cos(b) - x, r * mp.sin(th) - l * mp.sin(b)],
                      [mp.asin(r / l * mp.sin(th)), r * mp.cos(th) + l])
    return sol[1]
vmodel = lambda t: -mp.diff(x_of, t)
amodel = lambda t: -mp.diff(x_of, t, 2)
# event: a_A = 0 crossing from + to - (extremum of v_A) in the first half turn
t_ev = mp.findroot(amodel, th_star / w)
print("model: event t [s] =", t_ev)
print("theta_at_v_A_max [rad] =", w * t_ev)
print("v_A_max [m/s] =", vmodel(t_ev))
print("model: a_A just before/after =", amodel(t_ev * mp.mpf("0.999")), amodel(t_ev * mp.mpf("1.001")))
