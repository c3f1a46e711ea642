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
# Case 18 - Meriam & Kraige 7th ed. P5/204: crank OB (0.25 m) turns clockwise at a
# constant 5 rad/s; rod BD slides through a collar pivoted at the fixed point C.
# Geometry at t = 0 (ground axes): O = (0, 0), B = (0, 0.25) (crank vertical),
# C = (-0.6, 0); |BC| = 0.65, beta = atan(250/600) = 22.62 deg. The manual works in
# axes rotated by beta (x along DB); angular rates do not depend on that choice.
w0, r, c = mp.mpf(5), mp.mpf("0.25"), mp.mpf("0.6")
# closed form: rod angle phi = atan2(B - C), B = r (sin psi, cos psi), psi = w0 t
def rod_angle(t):
    p = w0 * t
    return mp.atan2(r * mp.cos(p), c + r * mp.sin(p))
# analytic: with d = B - C, omega = (d x d') / |d|^2, alpha = (d x d'')/|d|^2 - 2 (d.d') omega/|d|^2
dx, dy = c, r
vx, vy = r * w0, 0
ax, ay = 0, -r * w0**2
L2 = dx**2 + dy**2
om = (dx * vy - dy * vx) / L2
al = (dx * ay - dy * ax) / L2 - 2 * (dx * vx + dy * vy) * om / L2
print("closed: omega_BD =", om)
print("closed: alpha_BD = -(15/8)/0.4225 + ... =", al)
print("closed: alpha_BD exact fraction = -1.115625/0.17850625 =", mp.mpf("-1.115625") / mp.mpf("0.17850625"))
# model: bodies 0 = crank OB, 1 = rod BD (frame along the rod, B at its origin);
# constraints: crank pinned at O, rod pinned to crank at B, C lies on the rod's line
# (relative coordinate of the collar along the rod is free): written with Planar rows plus
# one line-through-point row handled below.
sys = Planar(2)
sys.pin(0, (0, -r / 2), None, g=(0, 0))                  # O (crank frame: B at +r/2 along body y)
sys.pin(0, (0, r / 2), 1, (0, 0))                         # B
sys.drive(2, lambda t: -w0 * t, lambda t: -w0, lambda t: 0)
def line_row(q, t):   # (C - r_rod) x e_rod = 0
    ex, ey = mp.cos(q[5]), mp.sin(q[5])
    return (-c - q[3]) * ey - (0 - q[4]) * ex
base = sys.phi
sys.phi = lambda q, t: mp.matrix(list(base(q, t)) + [line_row(q, t)])
basej = sys.jac
def jac(q):
    J0 = basej(q); J = mp.zeros(J0.rows + 1, 6)
    for i in range(J0.rows):
        for k in range(6): J[i, k] = J0[i, k]
    for k in range(6):
        J[J0.rows, k] = mp.diff(lambda x: line_row([q[j] if j != k else x for j in range(6)], 0), q[k])
    return J
sys.jac = jac
basep = sys.phit
sys.phit = lambda t: mp.matrix(list(basep(t)) + [0])
def solve(t):
    return sys.position([0, r / 2, 0, 0, r, mp.atan2(r, c)], t)
print("omega_BD =", mp.diff(lambda t: solve(t)[5], 0))
print("alpha_BD =", mp.diff(lambda t: solve(t)[5], 0, 2))
