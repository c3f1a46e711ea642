//! Stress suite, part 4: extreme scales (docs/STABILITY.md, row "scales").
//!
//! - Mass and inertia ratios of 1e6 / 1e-6 inside one mechanism: a chain of three bodies
//!   whose masses are 1e6, 1, 1e-6 kg and whose inertias run the other way, on linear and
//!   torsional springs. The truth is the modal solution of the linear system
//!   `M x'' + K x = 0`, `x = M^-1/2 V (cos(w t)) V^T M^1/2 x0` with `V`, `w^2` the
//!   eigenvectors and eigenvalues of the symmetric `M^-1/2 K M^-1/2` (nalgebra's symmetric
//!   eigensolver, independent of everything integrated here).
//! - The same pendulum (Cartesian coordinates, a closed loop `x^2 + y^2 = l^2`) in
//!   millimetres, metres and kilometres, against the Jacobi-elliptic solution: with `atol`
//!   scaled with the unit the runs are the same run (same steps, same relative error);
//!   with a fixed `atol` they are not.

use mbd::integrate::{Dopri5, Integrator, Radau5};
use mbd::nalgebra::{Matrix3, SymmetricEigen, Vector3};
use mbd::prelude::*;

#[path = "../../mbd-core/tests/exact/mod.rs"]
mod exact;

/// Three rigid bodies in a row, each moving along x (`x1..x3`) and turning (`p1..p3`).
/// Linear springs wall - 1 - 2 - 3 (`k1..k3`), torsional springs ground - 3 - 2 - 1
/// (`c3, c2, c1`): each spring sits next to the heavier body it acts on, so that every
/// natural frequency is of order 1 rad/s and the ratios are pure scale, not stiffness.
#[derive(Debug, Mechanism)]
#[mechanism(planar, jacobian)]
#[coords(x1, x2, x3, p1, p2, p3)]
#[rigid(b1, mass = m1, inertia = j1, at = [x1, 0.0], angle = p1)]
#[rigid(b2, mass = m2, inertia = j2, at = [x2 + 1.0, 0.0], angle = p2)]
#[rigid(b3, mass = m3, inertia = j3, at = [x3 + 2.0, 0.0], angle = p3)]
#[potential(0.5 * k1 * x1 * x1 + 0.5 * k2 * (x2 - x1) * (x2 - x1)
            + 0.5 * k3 * (x3 - x2) * (x3 - x2)
            + 0.5 * c3 * p3 * p3 + 0.5 * c2 * (p2 - p3) * (p2 - p3)
            + 0.5 * c1 * (p1 - p2) * (p1 - p2))]
pub struct ScaleChain {
    pub m1: f64,
    pub m2: f64,
    pub m3: f64,
    pub j1: f64,
    pub j2: f64,
    pub j3: f64,
    pub k1: f64,
    pub k2: f64,
    pub k3: f64,
    pub c1: f64,
    pub c2: f64,
    pub c3: f64,
}

impl ScaleChain {
    /// Masses `(big, 1, 1/big)`, inertias `(1/big, 1, big)`; springs `mass * w^2` of the body
    /// they hold, `w = 1, 2, 3`.
    fn new(big: f64) -> Self {
        let (m1, m2, m3) = (big, 1.0, 1.0 / big);
        let (j1, j2, j3) = (1.0 / big, 1.0, big);
        ScaleChain {
            m1,
            m2,
            m3,
            j1,
            j2,
            j3,
            k1: m1,
            k2: 4.0 * m2,
            k3: 9.0 * m3,
            c3: j3,
            c2: 4.0 * j2,
            c1: 9.0 * j1,
        }
    }

    /// The modal solution of one three-body chain `diag(m) x'' + K x = 0` from rest at `x0`:
    /// `(x(t), x'(t))`.
    fn modal(
        m: [f64; 3],
        k: Matrix3<f64>,
        x0: Vector3<f64>,
        t: f64,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let s = Vector3::new(m[0].sqrt(), m[1].sqrt(), m[2].sqrt());
        let kt = Matrix3::from_fn(|i, j| k[(i, j)] / (s[i] * s[j]));
        let eig = SymmetricEigen::new(kt);
        let v = eig.eigenvectors;
        let modes = v.transpose() * x0.component_mul(&s);
        let w = eig.eigenvalues.map(f64::sqrt);
        let xi = v * Vector3::from_fn(|i, _| modes[i] * (w[i] * t).cos());
        let xid = v * Vector3::from_fn(|i, _| -modes[i] * w[i] * (w[i] * t).sin());
        (xi.component_div(&s), xid.component_div(&s))
    }

    /// `(x1..x3, p1..p3)` and their rates at `t` from rest at `0.1` everywhere.
    fn exact(&self, t: f64) -> Vector<12> {
        let x0 = Vector3::new(0.1, 0.1, 0.1);
        // Translation: wall - 1 - 2 - 3.
        let kx = Matrix3::new(
            self.k1 + self.k2,
            -self.k2,
            0.0,
            -self.k2,
            self.k2 + self.k3,
            -self.k3,
            0.0,
            -self.k3,
            self.k3,
        );
        let (x, xd) = Self::modal([self.m1, self.m2, self.m3], kx, x0, t);
        // Rotation: ground - 3 - 2 - 1.
        let kp = Matrix3::new(
            self.c1,
            -self.c1,
            0.0,
            -self.c1,
            self.c1 + self.c2,
            -self.c2,
            0.0,
            -self.c2,
            self.c2 + self.c3,
        );
        let (p, pd) = Self::modal([self.j1, self.j2, self.j3], kp, x0, t);
        let mut y = Vector::<12>::zeros();
        for i in 0..3 {
            y[i] = x[i];
            y[3 + i] = p[i];
            y[6 + i] = xd[i];
            y[9 + i] = pd[i];
        }
        y
    }
}

/// Masses 1e6, 1, 1e-6 kg and inertias 1e-6, 1, 1e6 kg m^2 in one mechanism (ratios 1e12
/// end to end), 10 s: Radau IIA and DOPRI5 at rtol = 1e-8, atol = 1e-10 follow the modal
/// solution within 10 tol of the amplitude (0.1 for coordinates, 0.3 for rates) in every
/// coordinate and rate, the lightest body included (measured at most 2.9 tol for Radau IIA,
/// 6.1 tol for DOPRI5, both on the lightest body and the smallest inertia). Past what `f64` can hold in one mass matrix the solve refuses: with
/// masses 1e8 and 1e-8 (ratio 1e16, below `N eps`) `L D L^T` and LU both see a zero pivot and
/// the run stops with `SingularMassMatrix` at once: a typed error, not a NaN.
#[test]
fn mass_and_inertia_ratios_of_a_million() {
    let chain = ScaleChain::new(1e6);
    let y0 = chain.exact(0.0);
    let tol = 1e-8;
    let o = Options {
        rtol: tol,
        atol: 1e-10,
        ..Options::default()
    };
    for (name, sol) in [
        (
            "Radau5",
            Radau5::new(o.clone())
                .solve(&chain, 0.0, y0, 10.0, &[])
                .unwrap(),
        ),
        (
            "DOPRI5",
            Dopri5::new(o.clone())
                .solve(&chain, 0.0, y0, 10.0, &[])
                .unwrap(),
        ),
    ] {
        // Errors in units of the amplitudes: 0.1 for coordinates, 0.1 w_max = 0.3 for rates.
        let mut worst = Vector::<12>::zeros();
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let e = chain.exact(t);
            for i in 0..12 {
                let amplitude = if i < 6 { 0.1 } else { 0.3 };
                worst[i] = worst[i].max((y[i] - e[i]).abs() / amplitude);
            }
        }
        eprintln!(
            "mass ratios 1e6..1e-6, {name}: {} steps; error/(amplitude tol) x1..x3 {:.2} {:.2} {:.2}, p1..p3 {:.2} {:.2} {:.2}, rates max {:.2}",
            sol.stats.n_steps,
            worst[0] / tol,
            worst[1] / tol,
            worst[2] / tol,
            worst[3] / tol,
            worst[4] / tol,
            worst[5] / tol,
            worst.fixed_rows::<6>(6).max() / tol
        );
        assert!(worst.max() < 10.0 * tol, "{name}: {worst:?}");
    }
    let too_far = ScaleChain::new(1e8);
    let r = Dopri5::new(o).solve(&too_far, 0.0, too_far.exact(0.0), 10.0, &[]);
    eprintln!("mass ratio 1e16: {:?}", r.as_ref().map(|s| s.stats));
    assert!(matches!(r, Err(Error::SingularMassMatrix { .. })), "{r:?}");
}

// ---------------------------------------------------------------------------------------
// The same mechanism in millimetres, metres and kilometres

/// A pendulum in Cartesian coordinates: a point mass held at distance `l` from the origin
/// by the constraint `x^2 + y^2 = l^2`.
#[derive(Debug, Mechanism)]
#[mechanism(planar, jacobian)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[constraint(x * x + y * y == l * l)]
#[particle(bob, mass = m, at = [x, y])]
pub struct CartesianPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// The same pendulum with its constraint written without units, `(x/l)^2 + (y/l)^2 = 1`.
#[derive(Debug, Mechanism)]
#[mechanism(planar, jacobian)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[constraint((x / l) * (x / l) + (y / l) * (y / l) == 1.0)]
#[particle(bob, mass = m, at = [x, y])]
pub struct UnitFreePendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

const THETA0: f64 = 1.0;

/// The angle from the downward vertical, from rest at `THETA0` ([`exact::pendulum_angle`],
/// `w = sqrt(g/l)`, unit-free).
fn theta(t: f64) -> f64 {
    exact::pendulum_angle(9.81f64.sqrt(), THETA0, t)
}

/// One run in length unit `unit` (1e3 for mm, 1 for m, 1e-3 for km) with the constraint
/// written with units (`unit_free = false`) or without: `(steps, largest position error / l,
/// largest |x^2 + y^2 - l^2| / l^2)`.
fn run_in_units<I: Integrator>(solver: &I, unit: f64, unit_free: bool) -> (usize, f64, f64) {
    let (m, l, g) = (1.0, unit, 9.81 * unit);
    let y0 = Vector::<4>::new(l * THETA0.sin(), -l * THETA0.cos(), 0.0, 0.0);
    let sol = if unit_free {
        solver.solve(&UnitFreePendulum { m, l, g }, 0.0, y0, 10.0, &[])
    } else {
        solver.solve(&CartesianPendulum { m, l, g }, 0.0, y0, 10.0, &[])
    }
    .unwrap();
    let (mut err, mut drift) = (0.0f64, 0.0f64);
    for (&t, y) in sol.t.iter().zip(&sol.y) {
        let th = theta(t);
        err = err
            .max((y[0] - l * th.sin()).abs() / l)
            .max((y[1] + l * th.cos()).abs() / l);
        drift = drift.max((y[0] * y[0] + y[1] * y[1] - l * l).abs() / (l * l));
    }
    (sol.stats.n_steps, err, drift)
}

/// mm / m / km, 10 s (4.7 periods), rtol = 1e-10.
///
/// What the user must do: scale `atol` with the unit (`atol + rtol |y|` is scale-free only
/// then) and write constraints whose residual has no unit, because the projection onto
/// `Phi = 0` after each step stops at `max |Phi| <= 1e-12` in the units of `Phi`
/// ([`NewtonOptions`](mbd::analysis::NewtonOptions)'s default, absolute).
///
/// - Unit-free constraint, `atol = 1e-10 * unit`: the three runs are the same run: the same
///   steps (within 5%) and the same relative error (within 5%). Against the elliptic
///   solution that error is 9 tol for Radau IIA and 22 tol for DOPRI5 (measured; the global
///   error of 900..1200 steps each within the local tolerance), asserted below 50 tol.
/// - Constraint `x^2 + y^2 = l^2` (in m^2, mm^2, km^2), `atol` scaled: the same steps, but
///   the projection's 1e-12 is 1e-18 of `l^2` in millimetres (it iterates to rounding), 1e-12
///   in metres and 1e-6 in kilometres, where it never acts: there the drift grows to
///   2.5e-10 of `l^2` and Radau IIA's error to 17 tol (measured), against 9 tol in mm and m.
///   Asserted: mm and m within 50 tol; the drift stays under the projection's bound (or
///   rounding, in mm).
/// - `atol = 1e-10` in every unit: in millimetres 26% more steps for an error 5 times
///   smaller than asked; in kilometres 4.4 times fewer steps and an error of 3e-6 of `l`,
///   30000 tol (measured): the tolerance the user gave is not the one they meant.
#[test]
fn millimetres_and_kilometres_give_the_same_run_when_atol_is_scaled() {
    let tol = 1e-10;
    let units = [("mm", 1e3), ("m", 1.0), ("km", 1e-3)];
    let o = |atol: f64| Options {
        rtol: tol,
        atol,
        max_steps: 1_000_000,
        ..Options::default()
    };
    for name in ["Radau5", "DOPRI5"] {
        let run = |atol: f64, unit: f64, unit_free: bool| {
            if name == "Radau5" {
                run_in_units(&Radau5::new(o(atol)), unit, unit_free)
            } else {
                run_in_units(&Dopri5::new(o(atol)), unit, unit_free)
            }
        };
        let (mut steps, mut errors) = (Vec::new(), Vec::new());
        for (unit_name, unit) in units {
            let free = run(tol * unit, unit, true);
            let dim = run(tol * unit, unit, false);
            let fixed = run(tol, unit, false);
            eprintln!(
                "{name} pendulum in {unit_name}: unit-free constraint, atol scaled: {} steps, error/l {:.2e}, drift {:.1e}; constraint in {unit_name}^2, atol scaled: {} steps, error/l {:.2e}, drift {:.1e}; atol = 1e-10 fixed: {} steps, error/l {:.2e}",
                free.0, free.1, free.2, dim.0, dim.1, dim.2, fixed.0, fixed.1
            );
            assert!(free.1 < 50.0 * tol, "{name} {unit_name}: {free:?}");
            if unit >= 1.0 {
                assert!(dim.1 < 50.0 * tol, "{name} {unit_name}: {dim:?}");
            }
            errors.push(free.1);
            // The projection's bound, 1e-12 in m^2-like units, or rounding of l^2.
            let bound = (1e-12 / (unit * unit)).max(8.0 * f64::EPSILON);
            assert!(dim.2 <= bound, "{name} {unit_name}: {dim:?}");
            steps.push(free.0);
            steps.push(dim.0);
        }
        let (lo, hi) = (
            *steps.iter().min().unwrap() as f64,
            *steps.iter().max().unwrap() as f64,
        );
        assert!(hi <= 1.05 * lo, "{name}: steps {steps:?}");
        let (lo, hi) = (
            errors.iter().copied().fold(f64::INFINITY, f64::min),
            errors.iter().copied().fold(0.0, f64::max),
        );
        assert!(hi <= 1.05 * lo, "{name}: errors {errors:?}");
    }
}
