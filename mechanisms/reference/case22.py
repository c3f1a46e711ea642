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
# Case 22 - Meriam & Kraige 7th ed. P6/29: platform (mass m, inferred 200 kg) carried in
# curvilinear translation by two parallel 1.2 m links: EF (driven, theta(t)) and CD
# (massless two-force link, pinned at both ends). Fixed pivots C = (0, 0), E = (-0.6, 0);
# links point up, D = C + 1.2 (sin th, cos th), F = E + 1.2 (sin th, cos th); G of the
# platform is 0.6 right of F (above D's x) and 0.48 above the FD line. g = 9.81.
# theta(t) = (pi/6)(1 - cos(pi t / 2)).
g, l = mp.mpf("9.81"), mp.mpf("1.2")
th = lambda t: mp.pi / 6 * (1 - mp.cos(mp.pi * t / 2))
thd = lambda t: mp.pi**2 / 12 * mp.sin(mp.pi * t / 2)
thdd = lambda t: mp.pi**3 / 24 * mp.cos(mp.pi * t / 2)
# mass inferred from the manual's t = 0 result: (m g - F_D) 0.6 = m a_t 0.48
at0 = l * thdd(0)
m_inferred = 1714 / (g - at0 * mp.mpf("0.8"))
print("inferred m from 1714 N [kg] =", m_inferred)
m = mp.mpf(200)
FD0 = m * (g - mp.mpf("0.8") * at0)
an1 = l * thd(1) ** 2
c30, s30 = mp.cos(mp.pi / 6), mp.sin(mp.pi / 6)
FD1 = (m * g * mp.mpf("0.6") - m * an1 * (mp.mpf("0.6") * c30 - mp.mpf("0.48") * s30)) / (mp.mpf("0.6") * c30)
print("closed: a_t(0) = 1.2 pi^3/24 =", at0)
print("closed: F_D(t=0) = m (g - 0.04 pi^3) =", FD0)
print("closed: a_n(1) = 1.2 (pi^2/12)^2 =", an1)
print("closed: F_D(t=1) =", FD1)
# model: bodies 0 = EF (driven, massless), 1 = CD (massless), 2 = platform (frame at G)
sys = Planar(3)
h = l / 2
# link frames: body x-axis along the link, phi = pi/2 - theta
sys.pin(0, (-h, 0), None, g=(-mp.mpf("0.6"), 0))   # E
sys.pin(1, (-h, 0), None, g=(0, 0))                # C
sys.pin(0, (h, 0), 2, (-mp.mpf("0.6"), -mp.mpf("0.48")))   # F
sys.pin(1, (h, 0), 2, (0, -mp.mpf("0.48")))                 # D (rows 6, 7)
sys.drive(2, lambda t: mp.pi / 2 - th(t), lambda t: -thd(t), lambda t: -thdd(t))
masses = [(0, 0), (0, 0), (m, mp.mpf(10))]   # platform I irrelevant (translation)
def state(t):
    a = th(t)
    u = (mp.sin(a), mp.cos(a))
    q0 = [-mp.mpf("0.6") + h * u[0], h * u[1], mp.pi / 2 - a, h * u[0], h * u[1], mp.pi / 2 - a,
          l * u[0], l * u[1] + mp.mpf("0.48"), 0]
    # velocities: full kinematic system = this one plus a driver of CD (dependent, so use
    # the position solve of the determined subsystem through finite differences)
    return q0
for t in (0, 1):
    q = state(t)
    qd = [mp.diff(lambda s: state(s)[k], t) for k in range(9)]
    qdd, lam = sys.dynamics(q, qd, t, masses, gravity(masses, g))
    print("model t=%d: platform accel =" % t, (qdd[6], qdd[7]), " alpha_plat =", qdd[8])
    print("F_D_t%d =" % t, mp.sqrt(lam[6] ** 2 + lam[7] ** 2))
