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
# Case 24 - Meriam & Kraige 7th ed. P6/92: crank OA (0.4 m) turns at a constant
# omega_0 = 4.5 rad/s (ccw); uniform 10-kg bar AB (1.0 m) with a massless roller B on a
# horizontal floor (y = 0). Instant: O = (0.4, 0.8), A = (0, 0.8) (OA horizontal, A left
# of O), B = (0.6, 0); AB has slope 4/3, G = (0.3, 0.4). g = 9.81.
m, L, g, w0, r = mp.mpf(10), mp.mpf(1), mp.mpf("9.81"), mp.mpf("4.5"), mp.mpf("0.4")
# closed form (ccw positive, moments about A)
rx, ry = mp.mpf("0.6"), -mp.mpf("0.8")            # B - A
vAy = -r * w0                                      # A moves down
wAB = -vAy / rx
aAx = r * w0**2                                    # toward O (+x)
aAB = wAB**2 * ry / rx                             # from a_By = 0
aG = aAx - aAB * ry / 2 - wAB**2 * rx / 2            # a_A + alpha k x r_G - w^2 r_G
aGy = aAB * rx / 2 - wAB**2 * ry / 2
IG = m * L**2 / 12
# sum M_A: 0.6 N - 0.3 m g = IG alpha + r_G/A x m a_G
rGx, rGy = rx / 2, ry / 2
N = (IG * aAB + m * (rGx * aGy - rGy * aG) + mp.mpf("0.3") * m * g) / mp.mpf("0.6")
print("closed: omega_AB =", wAB, " alpha_AB =", aAB)
print("closed: a_G =", (aG, aGy))
print("closed: N_B =", N, " (= (0.3*98.1 - 7.6)/0.6)")
# model: bodies 0 = OA (massless, driven), 1 = AB (frame at G, x-axis from A to B)
sys = Planar(2)
h = r / 2
sys.pin(0, (h, 0), None, g=(mp.mpf("0.4"), mp.mpf("0.8")))       # O: body 0 x-axis from A to O
sys.pin(0, (-h, 0), 1, (-L / 2, 0))                                # A
sys.pin(1, (L / 2, 0), None, g=(0, 0), comps=(1,))                 # B on y = 0 (row 4)
sys.drive(2, lambda t: w0 * t, lambda t: w0, lambda t: 0)          # OA angle (A - O direction + pi)
phiAB = mp.atan2(ry, rx)
q = [mp.mpf("0.2"), mp.mpf("0.8"), 0, mp.mpf("0.3"), mp.mpf("0.4"), phiAB]
qd = sys.velocity(sys.position(q, 0), 0)
masses = [(0, 0), (m, IG)]
qdd, lam = sys.dynamics(q, qd, 0, masses, gravity(masses, g))
print("model: omega_AB =", qd[5], " alpha_AB =", qdd[5])
print("N_B =", -lam[4])
