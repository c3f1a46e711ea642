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
# Case 16 - Meriam & Kraige 7th ed. P5/195: two-input five-bar O-C-B-A with slider A.
# Reference: closed form from the velocity triangle, and Newton/linear solves on the
# reconstructed loop-closure model (planar helper above).
# Geometry at t = 0 (O at the origin, x right, y up, metres):
#   C = (0, 0.3)   crank OC vertical, driven clockwise at 2 rad/s
#   B = (0.4, 0.3) link CB horizontal, |CB| = 0.4
#   A = (0.8, 0.6) slider on the horizontal line y = 0.6, driven at +1.2 m/s
#   |AB| = 0.5, AB at atan(3/4) to the horizontal.
W_OC, V_A = mp.mpf(2), mp.mpf("1.2")
# closed form (manual's velocity triangle, tan(theta) = 3/4, sin(theta) = 3/5)
v_c = W_OC * mp.mpf("0.3")
w_bc_closed = (V_A - v_c) / (mp.mpf(3) / 4) / mp.mpf("0.4")
w_ab_closed = (V_A - v_c) / (mp.mpf(3) / 5) / mp.mpf("0.5")
print("closed: |omega_BC| =", w_bc_closed)
print("closed: |omega_AB| =", w_ab_closed)
# model: bodies 0 = OC (G at its middle), 1 = CB, 2 = BA (body frames along the links)
sys = Planar(3)
sys.pin(0, (-mp.mpf("0.15"), 0), None, g=(0, 0))            # O
sys.pin(0, (mp.mpf("0.15"), 0), 1, (-mp.mpf("0.2"), 0))     # C
sys.pin(1, (mp.mpf("0.2"), 0), 2, (-mp.mpf("0.25"), 0))     # B
sys.pin(2, (mp.mpf("0.25"), 0), None, g=(0, mp.mpf("0.6")), comps=(1,))  # A on y = 0.6
sys.drive(2, lambda t: mp.pi / 2 - W_OC * t, lambda t: -W_OC, lambda t: 0)   # OC angle
# A's x coordinate: x_BA + 0.25 cos(phi_BA) = 0.8 + 1.2 t  -> drive through a pin row on x
sys.rows.append(("pin", (2, (mp.mpf("0.25"), 0), None, (0, 0), (0, 0), 0)))
# replace the fixed x of A by a moving one: subclass phit for that row
base_phi, base_phit = sys.phi, sys.phit
def phi(q, t):
    p = base_phi(q, t); p[len(sys.rows) - 1] -= mp.mpf("0.8") + V_A * t; return p
def phit(t):
    p = base_phit(t); p[len(sys.rows) - 1] = -V_A; return p
sys.phi, sys.phit = phi, phit
ab = mp.atan2(mp.mpf("0.3"), mp.mpf("0.4"))
q0 = [0, mp.mpf("0.15"), mp.pi / 2,
      mp.mpf("0.2"), mp.mpf("0.3"), 0,
      mp.mpf("0.6"), mp.mpf("0.45"), ab]
q = sys.position(q0, 0)
qd = sys.velocity(q, 0)
print("model: A =", (q[6] + mp.mpf("0.25") * mp.cos(q[8]), q[7] + mp.mpf("0.25") * mp.sin(q[8])))
print("omega_BC =", qd[5])
print("omega_AB =", qd[8])
print("omega_OC =", qd[2])
