# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
import mpmath as mp

mp.mp.dps = 30

# Case 29 - Meriam & Kraige 7th ed. P7/46: a frame turns about the fixed vertical z axis at
# Omega = 4 pi rad/s; a disk of radius 0.1 m, centre O' at R = (0.3, 0, 0.1) m from the
# origin on the axis, spins relative to the frame at p = 10 pi rad/s about the frame's
# y axis. A is the top point of the disk at t = 0 (r_A/O' = 0.1 k). Both rates constant.
# Wanted at t = 0: angular acceleration of the disk and acceleration of A.
Om, p = 4 * mp.pi, 10 * mp.pi
print("closed: alpha_x = -p Omega = -40 pi^2 =", -p * Om)
print("closed: a_A = 2 pi^2 (-2.4, 4, -5) =", [2 * mp.pi**2 * c for c in (-mp.mpf("2.4"), 4, -5)])
print("closed: |a_A| =", 2 * mp.pi**2 * mp.sqrt(mp.mpf("2.4") ** 2 + 16 + 25))
# model: 3D, driven angles psi = Omega t (frame about z) and phi = p t (disk about the
# frame's y axis); A(t) = Rz(psi) [R + Ry(phi) (0, 0, 0.1)]
def Rz(a):
    return mp.matrix([[mp.cos(a), -mp.sin(a), 0], [mp.sin(a), mp.cos(a), 0], [0, 0, 1]])
def Ry(a):
    return mp.matrix([[mp.cos(a), 0, mp.sin(a)], [0, 1, 0], [-mp.sin(a), 0, mp.cos(a)]])
R = mp.matrix([mp.mpf("0.3"), 0, mp.mpf("0.1")])
def A(t):
    return Rz(Om * t) * (R + Ry(p * t) * mp.matrix([0, 0, mp.mpf("0.1")]))
def omega(t):   # absolute angular velocity: Omega k + p Rz(psi) j
    return mp.matrix([0, 0, Om]) + p * (Rz(Om * t) * mp.matrix([0, 1, 0]))
names = ("a_Ax", "a_Ay", "a_Az")
for i in range(3):
    print(names[i], "=", mp.diff(lambda t: A(t)[i], 0, 2))
print("alpha_x =", mp.diff(lambda t: omega(t)[0], 0))
print("alpha_y =", mp.diff(lambda t: omega(t)[1], 0), " alpha_z =", mp.diff(lambda t: omega(t)[2], 0))
