# Self-contained reference script (refs-b); mpmath at 30 digits, scipy only for cross-checks.
# --- planar multibody in redundant (x, y, phi) coordinates, 30-digit mpmath ---
# Independent of mbd: bodies are (x, y, phi) triples, joints are constraint rows
# Phi(q, t) = 0; kinematics by Newton, velocities from Phi_q qd = -Phi_t,
# accelerations and multipliers from the augmented system
#   [M  Phi_q^T] [qdd]   [Q    ]
#   [Phi_q    0] [lam] = [gamma],   gamma = -(Phi_q qd)_q qd - 2 Phi_qt qd - Phi_tt.
# The constraint force on the bodies is -Phi_q^T lam: for a pin between bodies i and j
# the force on i is -lam and on j is +lam (on a body pinned to ground: -lam).
import mpmath as mp

mp.mp.dps = 30


def rot(phi, s):
    c, n = mp.cos(phi), mp.sin(phi)
    return (c * s[0] - n * s[1], n * s[0] + c * s[1])


def drot(phi, s):
    c, n = mp.cos(phi), mp.sin(phi)
    return (-n * s[0] - c * s[1], c * s[0] - n * s[1])


class Planar:
    def __init__(self, nbodies):
        self.nb = nbodies
        self.rows = []  # each: (kind, data)

    # r_i + R_i s_i - (r_j + R_j s_j) = 0, j = None means a ground point g
    def pin(self, i, si, j=None, sj=(0, 0), g=(0, 0), comps=(0, 1)):
        for c in comps:
            self.rows.append(("pin", (i, si, j, sj, g, c)))

    # q[k] - f(t) = 0 with f, f', f'' given
    def drive(self, k, f, fd, fdd):
        self.rows.append(("drive", (k, f, fd, fdd)))

    def n(self):
        return 3 * self.nb

    def phi(self, q, t):
        out = []
        for kind, d in self.rows:
            if kind == "pin":
                i, si, j, sj, g, c = d
                pi = rot(q[3 * i + 2], si)[c] + q[3 * i + c]
                pj = g[c] if j is None else rot(q[3 * j + 2], sj)[c] + q[3 * j + c]
                out.append(pi - pj)
            else:
                k, f, _, _ = d
                out.append(q[k] - f(t))
        return mp.matrix(out)

    def jac(self, q):
        J = mp.zeros(len(self.rows), self.n())
        for r, (kind, d) in enumerate(self.rows):
            if kind == "pin":
                i, si, j, sj, g, c = d
                J[r, 3 * i + c] = 1
                J[r, 3 * i + 2] = drot(q[3 * i + 2], si)[c]
                if j is not None:
                    J[r, 3 * j + c] = -1
                    J[r, 3 * j + 2] = -drot(q[3 * j + 2], sj)[c]
            else:
                J[r, d[0]] = 1
        return J

    def phit(self, t):
        return mp.matrix([0 if k == "pin" else -d[2](t) for k, d in self.rows])

    def gamma(self, q, qd, t):
        out = []
        for kind, d in self.rows:
            if kind == "pin":
                i, si, j, sj, g, c = d
                v = rot(q[3 * i + 2], si)[c] * qd[3 * i + 2] ** 2
                if j is not None:
                    v -= rot(q[3 * j + 2], sj)[c] * qd[3 * j + 2] ** 2
                out.append(v)
            else:
                out.append(d[3](t))
        return mp.matrix(out)

    def position(self, q0, t):
        q = mp.matrix(q0)
        for _ in range(100):
            dq = mp.lu_solve(self.jac(q), -self.phi(q, t))
            q += dq
            if mp.norm(dq) < mp.mpf(10) ** (-mp.mp.dps + 3):
                break
        return q

    def velocity(self, q, t):
        return mp.lu_solve(self.jac(q), -self.phit(t))

    def dynamics(self, q, qd, t, masses, forces):
        """masses: list of (m, I) per body; forces: generalised force vector Q."""
        n, m = self.n(), len(self.rows)
        A = mp.zeros(n + m, n + m)
        J = self.jac(q)
        for b, (mass, inertia) in enumerate(masses):
            A[3 * b, 3 * b] = mass
            A[3 * b + 1, 3 * b + 1] = mass
            A[3 * b + 2, 3 * b + 2] = inertia
        for r in range(m):
            for c in range(n):
                A[n + r, c] = J[r, c]
                A[c, n + r] = J[r, c]
        rhs = mp.matrix(list(forces) + list(self.gamma(q, qd, t)))
        x = mp.lu_solve(A, rhs)
        return [x[i] for i in range(n)], [x[n + i] for i in range(m)]


def gravity(masses, g):
    Q = []
    for mass, _ in masses:
        Q += [0, -mass * g, 0]
    return Q
# Case 25 - Meriam & Kraige 7th ed. P6/105: vertical single-cylinder engine at constant
# crank speed omega = 100 pi rad/s (3000 rev/min), crank OB r = 0.0425 m, connecting rod
# AB l = 0.1075 m (mass 0.6 kg, G at 0.0325 m from the crank pin B, radius of gyration
# about G 0.028 m), piston A 0.82 kg on the vertical line through O, above O. Instant:
# crank horizontal (theta = 90 deg from the cylinder axis): B = (r, 0), A = (0, sqrt(l^2 - r^2)).
# Wanted: magnitude of the pin force at A. g = 9.81 (the manual shows variants without g).
mr, mp_, r, l, rho, kG = (mp.mpf("0.6"), mp.mpf("0.82"), mp.mpf("0.0425"), mp.mpf("0.1075"),
                          mp.mpf("0.0325"), mp.mpf("0.028"))
w = 100 * mp.pi
def closed(g, g_rod):
    yA = mp.sqrt(l**2 - r**2)
    aA = r**2 * w**2 / yA                       # piston accel, upward (away from O)
    # rod angle phi (from +x), unit e = (A - B)/l; omega_AB = 0; alpha from x_A = 0:
    ex, ey = -r / l, yA / l
    # a_A = a_B + alpha k x (l e) ; a_B = (-r w^2, 0); x: -r w^2 - alpha l ey = 0
    al = -r * w**2 / (l * ey)
    aGx = -r * w**2 - al * rho * ey
    aGy = al * rho * ex
    # piston: F_Ay (force of rod on piston) - mp g = mp aA ; rod gets -F_A at A
    FAy = mp_ * (aA + g)
    # rod: moments about B:  (A-B) x (-F_A) + (G-B) x (-m g j) = IG al + (G-B) x m a_G
    IG = mr * kG**2
    Gx, Gy = rho * ex, rho * ey
    Ax_, Ay_ = l * ex, l * ey
    rhs = IG * al + mr * (Gx * aGy - Gy * aGx) - (Gx * (-mr * g_rod))
    # (A-B) x (-F) = -(Ax_ FAy - Ay_ FAx) = rhs  ->  FAx
    FAx = (rhs + Ax_ * FAy) / Ay_
    return al, aA, FAx, FAy, mp.sqrt(FAx**2 + FAy**2)
g = mp.mpf("9.81")
for label, gp, gr in (("with gravity", g, g), ("no gravity", 0, 0), ("piston g only", g, 0)):
    al, aA, FAx, FAy, R = closed(gp, gr)
    print("closed (%s): alpha_AB = %s, a_A = %s, A_x = %s, A_y = %s, R_A = %s" %
          (label, mp.nstr(al, 15), mp.nstr(aA, 15), mp.nstr(FAx, 15), mp.nstr(FAy, 15), mp.nstr(R, 15)))
# model: bodies 0 = crank (massless, driven), 1 = rod (frame at G, x from B to A),
# 2 = piston (frame at A); piston x = 0 and phi = 0 (prismatic), pin A rows 4,5
sys = Planar(3)
sys.pin(0, (-r / 2, 0), None, g=(0, 0))                    # O
sys.pin(0, (r / 2, 0), 1, (-rho, 0))                       # B
sys.pin(1, (l - rho, 0), 2, (0, 0))                        # A (rows 4, 5)
sys.drive(2, lambda t: w * t, lambda t: w, lambda t: 0)    # crank angle from +x, ccw
sys.drive(6, lambda t: 0, lambda t: 0, lambda t: 0)        # piston x
sys.drive(8, lambda t: 0, lambda t: 0, lambda t: 0)        # piston rotation
yA = mp.sqrt(l**2 - r**2)
phi = mp.atan2(yA, -r)
q = [r / 2, 0, 0, r + rho * mp.cos(phi), rho * mp.sin(phi), phi, 0, yA, 0]
q = sys.position(q, 0)
qd = sys.velocity(q, 0)
print("model: omega_AB =", qd[5])
for label, gv in (("with gravity", g), ("no gravity", 0)):
    masses = [(0, 0), (mr, mr * kG**2), (mp_, mp.mpf("1e-3"))]
    qdd, lam = sys.dynamics(q, qd, 0, masses, gravity(masses, gv))
    print("model (%s): alpha_AB = %s, a_A = %s, F_A on piston = (%s, %s)" %
          (label, mp.nstr(qdd[5], 15), mp.nstr(qdd[7], 15), mp.nstr(lam[4], 15), mp.nstr(lam[5], 15)))
    print("R_A (%s) =" % label, mp.sqrt(lam[4] ** 2 + lam[5] ** 2))
    if gv:
        print("R_A =", mp.sqrt(lam[4] ** 2 + lam[5] ** 2))
