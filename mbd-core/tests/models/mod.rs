//! Hand-written models for the analysis tests (the derive does not exist yet). Every
//! expression is derived in the comments next to it; the tests compare against closed forms
//! that do not reuse these expressions.
#![allow(dead_code, reason = "each test file uses a subset of the models")]

use mbd_core::solve::{solve_augmented, solve_mass};
use mbd_core::{Constrained, Matrix, Mechanism, Result, Vector};

// ---------------------------------------------------------------------------------------
// Four-bar linkage

/// A planar four-bar under gravity (`-y`). Crank `O A` (length `r1`, angle `th1` from `+x`),
/// coupler `A B` (`r2`, `th2`), rocker `D B` (`r3`, `th3`) pivoted at `D = (g, 0)`; each
/// link a uniform rod of mass `m_i`. `q = (th1, th2, th3)`, two loop-closure constraints.
#[derive(Debug, Clone, Copy)]
pub struct FourBar {
    pub r1: f64,
    pub r2: f64,
    pub r3: f64,
    pub ground: f64,
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub grav: f64,
}

impl FourBar {
    /// Grashof crank-rocker (1 + 3.5 < 3 + 2.5): the crank turns fully, no toggle.
    pub fn crank_rocker() -> Self {
        FourBar {
            r1: 1.0,
            r2: 3.0,
            r3: 2.5,
            ground: 3.5,
            m1: 1.0,
            m2: 2.0,
            m3: 1.5,
            grav: 9.81,
        }
    }
}

impl Mechanism<3> for FourBar {
    const COORDINATES: [&'static str; 3] = ["th1", "th2", "th3"];

    // T = 1/2 (m1 r1^2/3) w1^2                                  (crank about O)
    //   + 1/2 m2 |r1 w1 e1' + (r2/2) w2 e2'|^2 + 1/2 (m2 r2^2/12) w2^2   (coupler, e' = (-s, c))
    //   + 1/2 (m3 r3^2/3) w3^2                                  (rocker about D)
    // e1'.e2' = cos(th1 - th2), so M12 = m2 r1 r2/2 cos(th1 - th2), M22 = m2 r2^2/3.
    fn mass_matrix(&self, _t: f64, q: &Vector<3>) -> Result<Matrix<3, 3>> {
        let c12 = 0.5 * self.m2 * self.r1 * self.r2 * (q[0] - q[1]).cos();
        Ok(Matrix::<3, 3>::new(
            self.m1 * self.r1.powi(2) / 3.0 + self.m2 * self.r1.powi(2),
            c12,
            0.0,
            c12,
            self.m2 * self.r2.powi(2) / 3.0,
            0.0,
            0.0,
            0.0,
            self.m3 * self.r3.powi(2) / 3.0,
        ))
    }

    // Lagrange with M12 = c cos(th1 - th2), c = m2 r1 r2 / 2: the velocity terms are
    // row 1: c sin(th1 - th2) w2^2, row 2: -c sin(th1 - th2) w1^2 (as for a double pendulum),
    // moved to the right-hand side. Gravity: V = (m1/2 + m2) g r1 s1 + m2 g (r2/2) s2 + m3 g (r3/2) s3.
    fn forces(&self, _t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<Vector<3>> {
        let c = 0.5 * self.m2 * self.r1 * self.r2;
        let s12 = (q[0] - q[1]).sin();
        let g = self.grav;
        Ok(Vector::<3>::new(
            -(0.5 * self.m1 + self.m2) * g * self.r1 * q[0].cos() - c * s12 * qd[1].powi(2),
            -self.m2 * g * 0.5 * self.r2 * q[1].cos() + c * s12 * qd[0].powi(2),
            -self.m3 * g * 0.5 * self.r3 * q[2].cos(),
        ))
    }

    fn acceleration(&self, t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<Vector<3>> {
        Ok(self.acceleration_and_multipliers(t, q, qd)?.0)
    }

    fn energy(&self, t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<f64> {
        let g = self.grav;
        Ok(0.5 * qd.dot(&(self.mass_matrix(t, q)? * qd))
            + (0.5 * self.m1 + self.m2) * g * self.r1 * q[0].sin()
            + self.m2 * g * 0.5 * self.r2 * q[1].sin()
            + self.m3 * g * 0.5 * self.r3 * q[2].sin())
    }
}

impl Constrained<3, 2> for FourBar {
    // Loop closure O -> A -> B = D -> B: r1 e1 + r2 e2 - r3 e3 - (g, 0) = 0.
    fn phi(&self, _t: f64, q: &Vector<3>) -> Vector<2> {
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let (s3, c3) = q[2].sin_cos();
        Vector::<2>::new(
            self.r1 * c1 + self.r2 * c2 - self.r3 * c3 - self.ground,
            self.r1 * s1 + self.r2 * s2 - self.r3 * s3,
        )
    }

    fn phi_q(&self, _t: f64, q: &Vector<3>) -> Matrix<2, 3> {
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let (s3, c3) = q[2].sin_cos();
        Matrix::<2, 3>::new(
            -self.r1 * s1,
            -self.r2 * s2,
            self.r3 * s3,
            self.r1 * c1,
            self.r2 * c2,
            -self.r3 * c3,
        )
    }

    fn phi_t(&self, _t: f64, _q: &Vector<3>) -> Vector<2> {
        Vector::<2>::zeros()
    }

    // (Phi_q qd)_q qd = (-r1 c1 w1^2 - r2 c2 w2^2 + r3 c3 w3^2, -r1 s1 w1^2 - r2 s2 w2^2 + r3 s3 w3^2);
    // gamma is its negative (Phi is scleronomic: no Phi_qt, Phi_tt).
    fn gamma(&self, _t: f64, q: &Vector<3>, qd: &Vector<3>) -> Vector<2> {
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let (s3, c3) = q[2].sin_cos();
        let (w1, w2, w3) = (qd[0].powi(2), qd[1].powi(2), qd[2].powi(2));
        Vector::<2>::new(
            self.r1 * c1 * w1 + self.r2 * c2 * w2 - self.r3 * c3 * w3,
            self.r1 * s1 * w1 + self.r2 * s2 * w2 - self.r3 * s3 * w3,
        )
    }

    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &Vector<3>,
        qd: &Vector<3>,
    ) -> Result<(Vector<3>, Vector<2>)> {
        solve_augmented::<3, 2, 5>(
            t,
            &self.mass_matrix(t, q)?,
            &self.forces(t, q, qd)?,
            &self.phi_q(t, q),
            &self.gamma(t, q, qd),
        )
    }
}

// ---------------------------------------------------------------------------------------
// Slider-crank

/// What drives a [`SliderCrank`].
#[derive(Debug, Clone, Copy)]
pub enum Drive {
    /// `th - th0 - w t = 0`.
    Crank { th0: f64, w: f64 },
    /// `x - x0 - v t = 0`.
    Piston { x0: f64, v: f64 },
}

/// An in-line slider-crank: crank `O A` (length `r`, angle `th`, uniform rod of mass `mc`),
/// connecting rod `A B` (length `l`, angle `ph`, uniform rod of mass `mr`), piston `B = (x, 0)`
/// (mass `mp`) on a spring `k (x - x_free)`; gravity `-y`. `q = (th, ph, x)`; two
/// loop-closure constraints and one driver: zero degrees of freedom.
#[derive(Debug, Clone, Copy)]
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub mc: f64,
    pub mr: f64,
    pub mp: f64,
    pub k: f64,
    pub x_free: f64,
    pub grav: f64,
    pub drive: Drive,
}

impl Mechanism<3> for SliderCrank {
    const COORDINATES: [&'static str; 3] = ["th", "ph", "x"];

    // T = 1/2 (mc r^2/3) w^2 + 1/2 mr |v_G|^2 + 1/2 (mr l^2/12) wp^2 + 1/2 mp xd^2,
    // v_G = r w e_th' + (l/2) wp e_ph'  =>  M12 = mr r l/2 cos(th - ph), M22 = mr l^2/3.
    fn mass_matrix(&self, _t: f64, q: &Vector<3>) -> Result<Matrix<3, 3>> {
        let c = 0.5 * self.mr * self.r * self.l * (q[0] - q[1]).cos();
        Ok(Matrix::<3, 3>::new(
            self.mc * self.r.powi(2) / 3.0 + self.mr * self.r.powi(2),
            c,
            0.0,
            c,
            self.mr * self.l.powi(2) / 3.0,
            0.0,
            0.0,
            0.0,
            self.mp,
        ))
    }

    // Velocity terms as for the four-bar's crank and coupler; potential
    // V = (mc/2 + mr) g r sin th + mr g (l/2) sin ph + k/2 (x - x_free)^2.
    fn forces(&self, _t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<Vector<3>> {
        let c = 0.5 * self.mr * self.r * self.l;
        let s = (q[0] - q[1]).sin();
        let g = self.grav;
        Ok(Vector::<3>::new(
            -(0.5 * self.mc + self.mr) * g * self.r * q[0].cos() - c * s * qd[1].powi(2),
            -self.mr * g * 0.5 * self.l * q[1].cos() + c * s * qd[0].powi(2),
            -self.k * (q[2] - self.x_free),
        ))
    }

    fn acceleration(&self, t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<Vector<3>> {
        Ok(self.acceleration_and_multipliers(t, q, qd)?.0)
    }

    fn energy(&self, t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<f64> {
        let g = self.grav;
        Ok(0.5 * qd.dot(&(self.mass_matrix(t, q)? * qd))
            + (0.5 * self.mc + self.mr) * g * self.r * q[0].sin()
            + self.mr * g * 0.5 * self.l * q[1].sin()
            + 0.5 * self.k * (q[2] - self.x_free).powi(2))
    }
}

impl Constrained<3, 3> for SliderCrank {
    // B = A + l e_ph = (x, 0):  r cos th + l cos ph - x = 0,  r sin th + l sin ph = 0; driver.
    fn phi(&self, t: f64, q: &Vector<3>) -> Vector<3> {
        let drive = match self.drive {
            Drive::Crank { th0, w } => q[0] - th0 - w * t,
            Drive::Piston { x0, v } => q[2] - x0 - v * t,
        };
        Vector::<3>::new(
            self.r * q[0].cos() + self.l * q[1].cos() - q[2],
            self.r * q[0].sin() + self.l * q[1].sin(),
            drive,
        )
    }

    fn phi_q(&self, _t: f64, q: &Vector<3>) -> Matrix<3, 3> {
        let (s, c) = q[0].sin_cos();
        let (sp, cp) = q[1].sin_cos();
        let drive_row = match self.drive {
            Drive::Crank { .. } => [1.0, 0.0, 0.0],
            Drive::Piston { .. } => [0.0, 0.0, 1.0],
        };
        Matrix::<3, 3>::new(
            -self.r * s,
            -self.l * sp,
            -1.0,
            self.r * c,
            self.l * cp,
            0.0,
            drive_row[0],
            drive_row[1],
            drive_row[2],
        )
    }

    fn phi_t(&self, _t: f64, _q: &Vector<3>) -> Vector<3> {
        let rate = match self.drive {
            Drive::Crank { w, .. } => w,
            Drive::Piston { v, .. } => v,
        };
        Vector::<3>::new(0.0, 0.0, -rate)
    }

    // (Phi_q qd)_q qd = (-r c w^2 - l cp wp^2, -r s w^2 - l sp wp^2, 0); the drivers are
    // linear in t, so Phi_qt = 0 and Phi_tt = 0.
    fn gamma(&self, _t: f64, q: &Vector<3>, qd: &Vector<3>) -> Vector<3> {
        let (s, c) = q[0].sin_cos();
        let (sp, cp) = q[1].sin_cos();
        let (w2, wp2) = (qd[0].powi(2), qd[1].powi(2));
        Vector::<3>::new(
            self.r * c * w2 + self.l * cp * wp2,
            self.r * s * w2 + self.l * sp * wp2,
            0.0,
        )
    }

    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &Vector<3>,
        qd: &Vector<3>,
    ) -> Result<(Vector<3>, Vector<3>)> {
        solve_augmented::<3, 3, 6>(
            t,
            &self.mass_matrix(t, q)?,
            &self.forces(t, q, qd)?,
            &self.phi_q(t, q),
            &self.gamma(t, q, qd),
        )
    }
}

// ---------------------------------------------------------------------------------------
// Compound pendulum relaxed at its pivot

/// A compound pendulum (mass `m`, centre of mass at distance `d` from the pivot, inertia
/// `i_c` about the centre of mass) whose pivot is relaxed by two displacements `(ux, uy)`
/// pinned by `ux = 0`, `uy = 0`. `q = (th, ux, uy)`, `th` from the downward vertical;
/// the centre of mass is at `(ux + d sin th, uy - d cos th)`; gravity `-y`.
#[derive(Debug, Clone, Copy)]
pub struct RelaxedPendulum {
    pub m: f64,
    pub d: f64,
    pub i_c: f64,
    pub grav: f64,
}

impl Mechanism<3> for RelaxedPendulum {
    const COORDINATES: [&'static str; 3] = ["th", "ux", "uy"];

    // v_G = (uxd + d cos th thd, uyd + d sin th thd):
    // T = 1/2 (m d^2 + i_c) thd^2 + m d cos th thd uxd + m d sin th thd uyd + 1/2 m (uxd^2 + uyd^2).
    fn mass_matrix(&self, _t: f64, q: &Vector<3>) -> Result<Matrix<3, 3>> {
        let (s, c) = q[0].sin_cos();
        let (m, d) = (self.m, self.d);
        Ok(Matrix::<3, 3>::new(
            m * d * d + self.i_c,
            m * d * c,
            m * d * s,
            m * d * c,
            m,
            0.0,
            m * d * s,
            0.0,
            m,
        ))
    }

    // d/dt dT/duxd = m uxdd + m d c thdd - m d s thd^2 (no dT/dux), so f_ux = + m d s thd^2;
    // likewise f_uy = -m g - m d c thd^2; in the th row the velocity terms cancel, leaving
    // the gravity moment -m g d sin th. V = m g (uy - d cos th).
    fn forces(&self, _t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<Vector<3>> {
        let (s, c) = q[0].sin_cos();
        let (m, d, g) = (self.m, self.d, self.grav);
        let w2 = qd[0].powi(2);
        Ok(Vector::<3>::new(
            -m * g * d * s,
            m * d * s * w2,
            -m * g - m * d * c * w2,
        ))
    }

    fn acceleration(&self, t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<Vector<3>> {
        Ok(self.acceleration_and_multipliers(t, q, qd)?.0)
    }

    fn energy(&self, t: f64, q: &Vector<3>, qd: &Vector<3>) -> Result<f64> {
        Ok(0.5 * qd.dot(&(self.mass_matrix(t, q)? * qd))
            + self.m * self.grav * (q[2] - self.d * q[0].cos()))
    }
}

impl Constrained<3, 2> for RelaxedPendulum {
    fn phi(&self, _t: f64, q: &Vector<3>) -> Vector<2> {
        Vector::<2>::new(q[1], q[2])
    }
    fn phi_q(&self, _t: f64, _q: &Vector<3>) -> Matrix<2, 3> {
        Matrix::<2, 3>::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    }
    fn phi_t(&self, _t: f64, _q: &Vector<3>) -> Vector<2> {
        Vector::<2>::zeros()
    }
    fn gamma(&self, _t: f64, _q: &Vector<3>, _qd: &Vector<3>) -> Vector<2> {
        Vector::<2>::zeros()
    }
    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &Vector<3>,
        qd: &Vector<3>,
    ) -> Result<(Vector<3>, Vector<2>)> {
        solve_augmented::<3, 2, 5>(
            t,
            &self.mass_matrix(t, q)?,
            &self.forces(t, q, qd)?,
            &self.phi_q(t, q),
            &self.gamma(t, q, qd),
        )
    }
}

// ---------------------------------------------------------------------------------------
// Mass on a spring

/// A mass `m` hanging from a spring (stiffness `k`, free length `l0`); `x` is the spring's
/// length, measured downwards, so gravity pulls towards larger `x`: `m xdd = m g - k (x - l0)`.
#[derive(Debug, Clone, Copy)]
pub struct HangingMass {
    pub m: f64,
    pub k: f64,
    pub l0: f64,
    pub grav: f64,
}

impl Mechanism<1> for HangingMass {
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _t: f64, _q: &Vector<1>) -> Result<Matrix<1, 1>> {
        Ok(Matrix::<1, 1>::new(self.m))
    }
    fn forces(&self, _t: f64, q: &Vector<1>, _qd: &Vector<1>) -> Result<Vector<1>> {
        Ok(Vector::<1>::new(
            self.m * self.grav - self.k * (q[0] - self.l0),
        ))
    }
    fn acceleration(&self, t: f64, q: &Vector<1>, qd: &Vector<1>) -> Result<Vector<1>> {
        solve_mass(t, &self.mass_matrix(t, q)?, &self.forces(t, q, qd)?)
    }
    fn energy(&self, _t: f64, q: &Vector<1>, qd: &Vector<1>) -> Result<f64> {
        Ok(0.5 * self.m * qd[0].powi(2) - self.m * self.grav * q[0]
            + 0.5 * self.k * (q[0] - self.l0).powi(2))
    }
}

// ---------------------------------------------------------------------------------------
// Two-bar linkage with a spring

/// Two equal uniform bars (length `L`, mass `m`): `A B` pinned at the origin `A`, `B C`
/// pinned at `B`; the end `C` slides on the horizontal line through `A` (`y_C = 0`), and a
/// zero-free-length spring `k` joins `A` and `C`; gravity `-y`. `q = (th1, th2)`, bar angles
/// from `+x`.
#[derive(Debug, Clone, Copy)]
pub struct TwoBar {
    pub len: f64,
    pub m: f64,
    pub k: f64,
    pub grav: f64,
}

impl Mechanism<2> for TwoBar {
    const COORDINATES: [&'static str; 2] = ["th1", "th2"];

    // As the four-bar's crank and coupler: M11 = m L^2/3 + m L^2, M12 = m L^2/2 cos(th1 - th2),
    // M22 = m L^2/3.
    fn mass_matrix(&self, _t: f64, q: &Vector<2>) -> Result<Matrix<2, 2>> {
        let (m, l) = (self.m, self.len);
        let c = 0.5 * m * l * l * (q[0] - q[1]).cos();
        Ok(Matrix::<2, 2>::new(
            4.0 / 3.0 * m * l * l,
            c,
            c,
            m * l * l / 3.0,
        ))
    }

    // V = m g (L/2) s1 + m g (L s1 + (L/2) s2) + k/2 |C|^2, C = L (c1 + c2, s1 + s2):
    // -dV/dth1 = -3/2 m g L c1 - k (C . dC/dth1), dC/dth1 = L (-s1, c1); same for th2.
    fn forces(&self, _t: f64, q: &Vector<2>, qd: &Vector<2>) -> Result<Vector<2>> {
        let (m, l, g, k) = (self.m, self.len, self.grav, self.k);
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        let (cx, cy) = (l * (c1 + c2), l * (s1 + s2));
        let c = 0.5 * m * l * l;
        let s12 = (q[0] - q[1]).sin();
        Ok(Vector::<2>::new(
            -1.5 * m * g * l * c1 - k * (cx * -l * s1 + cy * l * c1) - c * s12 * qd[1].powi(2),
            -0.5 * m * g * l * c2 - k * (cx * -l * s2 + cy * l * c2) + c * s12 * qd[0].powi(2),
        ))
    }

    fn acceleration(&self, t: f64, q: &Vector<2>, qd: &Vector<2>) -> Result<Vector<2>> {
        Ok(self.acceleration_and_multipliers(t, q, qd)?.0)
    }

    fn energy(&self, t: f64, q: &Vector<2>, qd: &Vector<2>) -> Result<f64> {
        let (m, l, g, k) = (self.m, self.len, self.grav, self.k);
        let (s1, c1) = q[0].sin_cos();
        let (s2, c2) = q[1].sin_cos();
        Ok(0.5 * qd.dot(&(self.mass_matrix(t, q)? * qd))
            + m * g * (0.5 * l * s1 + l * s1 + 0.5 * l * s2)
            + 0.5 * k * l * l * ((c1 + c2).powi(2) + (s1 + s2).powi(2)))
    }
}

impl Constrained<2, 1> for TwoBar {
    fn phi(&self, _t: f64, q: &Vector<2>) -> Vector<1> {
        Vector::<1>::new(self.len * (q[0].sin() + q[1].sin()))
    }
    fn phi_q(&self, _t: f64, q: &Vector<2>) -> Matrix<1, 2> {
        Matrix::<1, 2>::new(self.len * q[0].cos(), self.len * q[1].cos())
    }
    fn phi_t(&self, _t: f64, _q: &Vector<2>) -> Vector<1> {
        Vector::<1>::zeros()
    }
    fn gamma(&self, _t: f64, q: &Vector<2>, qd: &Vector<2>) -> Vector<1> {
        Vector::<1>::new(self.len * (q[0].sin() * qd[0].powi(2) + q[1].sin() * qd[1].powi(2)))
    }
    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &Vector<2>,
        qd: &Vector<2>,
    ) -> Result<(Vector<2>, Vector<1>)> {
        solve_augmented::<2, 1, 3>(
            t,
            &self.mass_matrix(t, q)?,
            &self.forces(t, q, qd)?,
            &self.phi_q(t, q),
            &self.gamma(t, q, qd),
        )
    }
}

// ---------------------------------------------------------------------------------------
// Oscillator and a particle on a circle (generalized-α convergence)

/// `m xdd = -k x`: `x = x0 cos(w t)`, `w = sqrt(k / m)` from rest.
#[derive(Debug, Clone, Copy)]
pub struct Oscillator {
    pub m: f64,
    pub k: f64,
}

impl Mechanism<1> for Oscillator {
    const COORDINATES: [&'static str; 1] = ["x"];
    fn mass_matrix(&self, _t: f64, _q: &Vector<1>) -> Result<Matrix<1, 1>> {
        Ok(Matrix::<1, 1>::new(self.m))
    }
    fn forces(&self, _t: f64, q: &Vector<1>, _qd: &Vector<1>) -> Result<Vector<1>> {
        Ok(Vector::<1>::new(-self.k * q[0]))
    }
    fn acceleration(&self, t: f64, q: &Vector<1>, qd: &Vector<1>) -> Result<Vector<1>> {
        solve_mass(t, &self.mass_matrix(t, q)?, &self.forces(t, q, qd)?)
    }
    fn energy(&self, _t: f64, q: &Vector<1>, qd: &Vector<1>) -> Result<f64> {
        Ok(0.5 * self.m * qd[0].powi(2) + 0.5 * self.k * q[0].powi(2))
    }
}

/// A free particle of mass `m` in the plane held on the circle `x^2 + y^2 = l^2`
/// (no gravity): from `(l, 0)` with velocity `(0, l w)` it turns uniformly,
/// `(x, y) = l (cos w t, sin w t)`, with `m (-w^2 q) + 2 q lambda = 0`: `lambda = m w^2 / 2`.
#[derive(Debug, Clone, Copy)]
pub struct CircleParticle {
    pub m: f64,
    pub l: f64,
}

impl Mechanism<2> for CircleParticle {
    const COORDINATES: [&'static str; 2] = ["x", "y"];
    fn mass_matrix(&self, _t: f64, _q: &Vector<2>) -> Result<Matrix<2, 2>> {
        Ok(Matrix::<2, 2>::identity() * self.m)
    }
    fn forces(&self, _t: f64, _q: &Vector<2>, _qd: &Vector<2>) -> Result<Vector<2>> {
        Ok(Vector::<2>::zeros())
    }
    fn acceleration(&self, t: f64, q: &Vector<2>, qd: &Vector<2>) -> Result<Vector<2>> {
        Ok(self.acceleration_and_multipliers(t, q, qd)?.0)
    }
    fn energy(&self, _t: f64, _q: &Vector<2>, qd: &Vector<2>) -> Result<f64> {
        Ok(0.5 * self.m * qd.norm_squared())
    }
}

impl Constrained<2, 1> for CircleParticle {
    fn phi(&self, _t: f64, q: &Vector<2>) -> Vector<1> {
        Vector::<1>::new(q.norm_squared() - self.l * self.l)
    }
    fn phi_q(&self, _t: f64, q: &Vector<2>) -> Matrix<1, 2> {
        Matrix::<1, 2>::new(2.0 * q[0], 2.0 * q[1])
    }
    fn phi_t(&self, _t: f64, _q: &Vector<2>) -> Vector<1> {
        Vector::<1>::zeros()
    }
    // (Phi_q qd)_q qd = 2 |qd|^2.
    fn gamma(&self, _t: f64, _q: &Vector<2>, qd: &Vector<2>) -> Vector<1> {
        Vector::<1>::new(-2.0 * qd.norm_squared())
    }
    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &Vector<2>,
        qd: &Vector<2>,
    ) -> Result<(Vector<2>, Vector<1>)> {
        solve_augmented::<2, 1, 3>(
            t,
            &self.mass_matrix(t, q)?,
            &self.forces(t, q, qd)?,
            &self.phi_q(t, q),
            &self.gamma(t, q, qd),
        )
    }
}
