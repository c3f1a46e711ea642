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
# Case 21 - Meriam & Kraige 7th ed. P6/25: parallelogram linkage. Fixed pivots A = (0, 0)
# and C = (0, -0.8); massless cranks AB and CD (0.6 m), horizontal at the instant;
# bar BD (25 kg) translates, B = (0.6, 0), D = (0.6, -0.8), its mass centre G is on BD,
# 0.5 m below B. Torque M = 200 N m on AB (counter-clockwise), omega = 5 rad/s, g = 9.81.
m, g, M, w, r = mp.mpf(25), mp.mpf("9.81"), mp.mpf(200), mp.mpf(5), mp.mpf("0.6")
alpha = (M / r - m * g) / (m * r)
Dn = m * r * w**2 * mp.mpf("0.5") / mp.mpf("0.8")
print("closed: alpha = (M/0.6 - m g)/(m 0.6) =", alpha)
print("closed: D_n = m a_n 0.5/0.8 =", Dn)
print("closed: B_n = m a_n - D_n =", m * r * w**2 - Dn, " B_t = M/0.6 =", M / r)
# model: bodies 0 = AB (massless, G at mid), 1 = CD (massless), 2 = BD (frame at G)
sys = Planar(3)
h = r / 2
sys.pin(0, (-h, 0), None, g=(0, 0))                      # A
sys.pin(1, (-h, 0), None, g=(0, -mp.mpf("0.8")))         # C
sys.pin(0, (h, 0), 2, (0, mp.mpf("0.5")))                # B: 0.5 above G
sys.pin(1, (h, 0), 2, (0, -mp.mpf("0.3")))               # D: 0.3 below G (rows 6, 7)
q = [h, 0, 0, h, -mp.mpf("0.8"), 0, r, -mp.mpf("0.5"), 0]
qd = [0, h * w, w, 0, h * w, w, 0, r * w, 0]
masses = [(0, 0), (0, 0), (m, mp.mpf("1.0"))]   # I of BD irrelevant: BD translates
Q = gravity(masses, g)
Q[2] = M
qdd, lam = sys.dynamics(q, qd, 0, masses, Q)
print("alpha_AB =", qdd[2], " alpha_BD =", qdd[8])
print("alpha =", qdd[5])
print("D force on BD (= +lam, BD is the second body of the pin) =", (lam[6], lam[7]))
print("R_D =", mp.sqrt(lam[6] ** 2 + lam[7] ** 2))
print("R_B =", mp.sqrt(lam[4] ** 2 + lam[5] ** 2))
# same with I_BD = 3 kg m^2 (must not change anything: BD translates)
masses[2] = (m, mp.mpf(3))
qdd, lam = sys.dynamics(q, qd, 0, masses, Q)
print("check I_BD=3: alpha =", qdd[5], " R_D =", mp.sqrt(lam[6] ** 2 + lam[7] ** 2))
