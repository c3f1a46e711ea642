//! Hunt: a toggle of equal links driven through its fold, a true bifurcation. The upper
//! link `l` turns about the origin, driven at `th = th0 + w t`; the lower link `l` joins the
//! knee `K = l (cos th, sin th)` to a ram `B = (x, 0)` on the `x` axis
//! (`B = K + l (cos be, -sin be)`). The loop `l sin th = l sin be` has two solution branches,
//! `be = th` (the ram at `x = 2 l cos th`, passing through the pivot) and `be = pi - th`
//! (the ram held at `x = 0`, the lower link folded back), which cross at `th = pi / 2`.
//! Driven through it, the motion may continue on either: no method may return `Ok` on a
//! silently chosen branch; each ends with a typed error naming the singular position, or
//! reports the passage (`Solution::passages`).

use mbd::analysis::{NewtonOptions, kinematic_sweep};
use mbd::integrate::{Dop853, Dopri5, Gauss, Integrator, Options, Radau5, Rk4};
use mbd::prelude::*;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[drive(th = th0 + w * t)]
#[coords(be, x)]
#[constraint(l * cos(th) + l * cos(be) == x)]
#[constraint(l * sin(th) == l * sin(be))]
#[rigid(upper, mass = 1.0, inertia = l * l / 12.0,
        at = [l / 2.0 * cos(th), l / 2.0 * sin(th)], angle = th)]
#[rigid(lower, mass = 1.0, inertia = l * l / 12.0,
        at = [l * cos(th) + l / 2.0 * cos(be), l * sin(th) - l / 2.0 * sin(be)], angle = -be)]
#[particle(ram, mass = 2.0, at = [x, 0.0])]
#[output(motor = reaction(th))]
pub struct Fold {
    pub l: f64,
    pub g: f64,
    pub th0: f64,
    pub w: f64,
}

const P: Fold = Fold {
    l: 0.6,
    g: 9.81,
    th0: 1.2,
    w: 1.0,
};

fn start() -> Vector<4> {
    // on the branch be = th: x = 2 l cos th, rates be' = w, x' = -2 l sin th w
    let th = P.th0;
    Vector::<4>::new(th, 2.0 * P.l * th.cos(), P.w, -2.0 * P.l * th.sin() * P.w)
}

/// The run's outcome: a typed singular-position error, or `Ok` with the passage reported.
fn judge(name: &str, run: mbd::Result<Solution<4>>) {
    let fold = (std::f64::consts::FRAC_PI_2 - P.th0) / P.w;
    match run {
        Err(
            e @ (mbd::Error::SingularPosition { t, .. }
            | mbd::Error::SingularConstraintJacobian { t, .. }),
        ) => {
            println!("{name}: {e}");
            // the error names the fold's time, or the step that crossed it: `between t = a
            // and t = b` (DOP853 crosses it in one long step, 0.30 -> 0.8: its `t` is the
            // step's end)
            let text = e.to_string();
            let number = |key: &str| -> Option<f64> {
                let rest = &text[text.find(key)? + key.len()..];
                let end = rest.find([' ', ')']).unwrap_or(rest.len());
                rest[..end].parse().ok()
            };
            match (number("between t = "), number(" and t = ")) {
                (Some(a), Some(b)) => assert!(
                    a <= fold && fold <= b && b == t,
                    "{name}: [{a}, {b}] at t = {t}, the fold at {fold}"
                ),
                _ => assert!(
                    (t - fold).abs() < 1e-3,
                    "{name}: t = {t}, the fold at {fold}"
                ),
            }
        }
        Ok(sol) if !sol.passages.is_empty() => {
            println!("{name}: passage at t = {}", sol.passages[0].t);
            let t = sol.passages[0].t;
            assert!(
                (P.th0 + P.w * t - std::f64::consts::FRAC_PI_2).abs() < 1e-3,
                "{name}: {t}"
            );
        }
        Ok(sol) => {
            let y = sol.y.last().unwrap();
            panic!(
                "{name}: Ok through the fold, nothing reported: be = {}, x = {}",
                y[0], y[1]
            );
        }
        Err(e) => panic!("{name}: an untyped failure: {e}"),
    }
}

#[test]
fn driven_through_the_fold_no_method_chooses_a_branch_silently() {
    let y0 = start();
    let t1 = 0.8; // th from 1.2 to 2.0, through pi / 2 at t = 0.3708
    let o = Options {
        rtol: 1e-9,
        atol: 1e-9,
        ..Options::default()
    };
    judge("dopri5", Dopri5::new(o.clone()).solve(&P, 0.0, y0, t1, &[]));
    judge("dop853", Dop853::new(o.clone()).solve(&P, 0.0, y0, t1, &[]));
    judge("radau5", Radau5::new(o.clone()).solve(&P, 0.0, y0, t1, &[]));
    judge("rk4", Rk4::new(1e-3).solve(&P, 0.0, y0, t1, &[]));
    judge("gauss", Gauss::new(1e-3).solve(&P, 0.0, y0, t1, &[]));
}

/// Defect found: sampled every 0.05 s (0.05 rad), the sweep went on through the fold on
/// the branch `be = th` and returned `Ok` (`x = 2 l cos 2 = -0.499` at the end), while every
/// integrator stopped there with a typed error. The sweep now watches the sign of
/// `det Phi_q` between its (sub-)steps: a sign change is a singular position passed.
#[test]
fn the_kinematic_sweep_through_the_fold_is_a_typed_error() {
    let times: Vec<f64> = (0..=16).map(|i| i as f64 * 0.05).collect();
    let q0 = start().fixed_rows::<2>(0).into_owned();
    let fold = (std::f64::consts::FRAC_PI_2 - P.th0) / P.w;
    match kinematic_sweep(&P, &times, &q0, &NewtonOptions::default()) {
        Err(e @ mbd::Error::SingularConstraintJacobian { t, .. }) => {
            println!("{e}");
            // named at the end of the sub-step that crossed the fold
            assert!(
                t > fold && t < fold + 0.05,
                "t = {t}, the fold is at {fold}"
            );
        }
        Ok(ks) => {
            let k = ks.last().unwrap();
            panic!("Ok through the fold: be = {}, x = {}", k.q[0], k.q[1]);
        }
        Err(e) => panic!("an untyped failure: {e}"),
    }
}
