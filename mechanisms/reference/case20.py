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
# Case 20 - Meriam & Kraige 7th ed. Sample Problem 6/4: pendulum, m = 7.5 kg, mass
# centre G at rbar = 0.25 m from the pivot O, radius of gyration about O k_O = 0.295 m,
# released from rest with OG horizontal (theta = 0), theta measured downward; find the
# total bearing force at O when theta = 60 deg. g = 9.81.
import numpy as np
from scipy.integrate import solve_ivp
m, rb, kO, g = mp.mpf("7.5"), mp.mpf("0.25"), mp.mpf("0.295"), mp.mpf("9.81")
IO = m * kO**2
th = mp.pi / 3
alpha = m * g * rb * mp.cos(th) / IO
omega2 = 2 * m * g * rb * mp.sin(th) / IO
On = m * g * mp.sin(th) + m * rb * omega2
Ot = m * g * mp.cos(th) - m * rb * alpha
print("closed: alpha [rad/s^2] =", alpha)
print("closed: omega [rad/s] =", mp.sqrt(omega2))
print("closed: O_n [N] =", On, " O_t [N] =", Ot)
print("closed: R_O [N] =", mp.sqrt(On**2 + Ot**2))
# manual's propagated roundings: omega = 6.99, alpha = 14.091
On_m = m * g * mp.sin(th) + m * rb * mp.mpf("6.99") ** 2
Ot_m = m * g * mp.cos(th) - m * rb * mp.mpf("14.091")
print("manual-rounded: O_n =", On_m, " O_t =", Ot_m, " R_O =", mp.sqrt(On_m**2 + Ot_m**2))
# model 1: ODE IO thdd = m g rb cos(th), event th - pi/3 = 0 increasing (double precision)
IOf, mf, gf, rbf = float(IO), 7.5, 9.81, 0.25
ev = lambda t, y: y[0] - np.pi / 3
ev.terminal, ev.direction = True, 1
sol = solve_ivp(lambda t, y: [y[1], mf * gf * rbf * np.cos(y[0]) / IOf], [0, 5], [0, 0],
                method="DOP853", rtol=1e-13, atol=1e-15, events=ev)
te, (the, wde) = sol.t_events[0][0], sol.y_events[0][0]
ade = mf * gf * rbf * np.cos(the) / IOf
# Newton for the mass centre G = rb (cos th, -sin th): reaction O = m a_G - m g
aG = np.array([-rbf * (np.sin(the) * ade + np.cos(the) * wde**2),
               -rbf * (np.cos(the) * ade - np.sin(the) * wde**2)])
Ovec = mf * aG - np.array([0, -mf * gf])
print("ODE: event t [s] = %.15g, omega = %.15g" % (te, wde))
print("ODE: R_O [N] = %.15g" % np.hypot(*Ovec))
# model 2: Planar multibody, relaxed pin at O: body (x, y, phi), G at the origin of the
# body frame, O at s = (-rb, 0); multiplier of the pin rows = -(pin force on the body)
sys = Planar(1)
sys.pin(0, (-rb, 0), None, g=(0, 0))
phi = -th
q = [rb * mp.cos(th), -rb * mp.sin(th), phi]
w = -mp.sqrt(omega2)
qd = [-rb * mp.sin(phi) * w, rb * mp.cos(phi) * w, w]
masses = [(m, IO - m * rb**2)]
qdd, lam = sys.dynamics(q, qd, 0, masses, gravity(masses, g))
print("model: theta_ddot =", -qdd[2])
print("R_O =", mp.sqrt(lam[0] ** 2 + lam[1] ** 2))
# model 3: the same ODE at 30 digits (mpmath Taylor integrator), event by root finding
f = mp.odefun(lambda t, y: [y[1], m * g * rb * mp.cos(y[0]) / IO], 0, [mp.mpf(0), mp.mpf(0)])
te = mp.findroot(lambda t: f(t)[0] - mp.pi / 3, mp.mpf(te))
th_e, w_e = f(te)
a_e = m * g * rb * mp.cos(th_e) / IO
aGx = -rb * (mp.sin(th_e) * a_e + mp.cos(th_e) * w_e**2)
aGy = -rb * (mp.cos(th_e) * a_e - mp.sin(th_e) * w_e**2)
print("mp ODE: event t [s] =", te)
print("R_O =", mp.sqrt((m * aGx) ** 2 + (m * aGy + m * g) ** 2))
