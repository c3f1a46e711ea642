# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 17 - Meriam & Kraige 7th ed. P5/198: crank OA (0.1 m, 3 rad/s ccw) drives a pin A
# that slides in the slot of rocker CB (pivot C, |CB| = 0.5 m).
# Geometry at t = 0: O = (0, 0), C = (0, -0.3) (C directly below O, |OC| = 0.3),
# OA at theta = 30 deg above the horizontal, so angle AOC = 120 deg (law of cosines in
# the manual). Rocker angle psi measured from +x; A stays on the rocker's centre line.
W = mp.mpf(3)
r, d, L = mp.mpf("0.1"), mp.mpf("0.3"), mp.mpf("0.5")
th = mp.pi / 6
# closed form: psi = atan2(r sin th + d, r cos th); psi_dot = r thdot (r + d sin th) / CA^2
ca2 = r**2 + d**2 - 2 * r * d * mp.cos(2 * mp.pi / 3)
w_closed = W * r * (r + d * mp.sin(th)) / ca2
print("closed: CA^2 =", ca2, " CA =", mp.sqrt(ca2))
print("closed: omega_BC = 0.075/0.13 =", w_closed)
print("closed: v_B = 0.5 omega_BC =", L * w_closed)
# manual's route: beta, gamma, v_A cos(gamma)/CA
beta = mp.asin(r / mp.sqrt(ca2) * mp.sin(2 * mp.pi / 3))
gam = mp.pi - 2 * mp.pi / 3 - beta
print("closed: beta [deg] =", mp.degrees(beta), " gamma [deg] =", mp.degrees(gam))
print("closed: v_A cos(gamma)/CA =", W * r * mp.cos(gam) / mp.sqrt(ca2))
# model: coordinates q = (theta(t) driven, psi); constraint: A on the rocker line
#   Phi = (A - C) x e(psi) = (r cos th) sin psi - (r sin th + d) cos psi = 0
def phi(psi, t):
    a = th + W * t
    return r * mp.cos(a) * mp.sin(psi) - (r * mp.sin(a) + d) * mp.cos(psi)
def psi_of(t):
    return mp.findroot(lambda p: phi(p, t), mp.atan2(r * mp.sin(th) + d, r * mp.cos(th)))
w_model = mp.diff(psi_of, 0)
print("omega_BC =", w_model)
print("v_B =", L * w_model)
print("alpha_BC =", mp.diff(psi_of, 0, 2))
