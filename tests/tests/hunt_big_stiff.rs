//! Hunting stiff big models: a 16-link chain whose joints carry stiff torsional springs
//! (`k = 1e8 N m/rad`), released at rest straight at `theta0`: it swings as one rigid bar
//! of length `L = 16 l` (`theta'' = -(3 g / 2 L) sin theta`, the closed form of
//! `exact::pendulum_angle`), up to the bending its joints take under the load, about
//! `m g L / k` (1e-6 rad). Its fast modes (about 1e5 rad/s) make it stiff for every explicit
//! method: each must say so (`Stiff`, or `NonFinite` for fixed-step RK4) or be right, never
//! a wrong `Ok`; Radau5 and Gauss must be right, Radau5 with bounded steps. Found: DOP853,
//! Vern9 and `Auto` stopped with `NonFinite` on their first trial step (the stages of a step
//! far beyond the stability limit overflow); a non-finite trial step is now rejected with
//! the controller's largest cut, and they report `Stiff`.

use mbd::integrate::{Auto, Dop853, Dopri5, Gauss, Integrator, Radau5, Rk4, Vern9};
use mbd::prelude::*;

#[path = "../../mbd-core/tests/exact/mod.rs"]
mod exact;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 16, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
#[repeat(i in 2..=16, generalized_force(spring[i], along = link_q[i], value = -k * link_q[i] - c * der(link_q[i])))]
#[init(link_q1 = theta0)]
pub struct StiffChain {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub k: f64,
    pub c: f64,
    pub theta0: f64,
}

const T1: f64 = 1.0;

fn chain() -> StiffChain {
    StiffChain {
        m: 1.0,
        l: 0.5,
        g: 9.81,
        k: 1e8,
        c: 3e3,
        theta0: 0.5,
    }
}

/// The rigid bar's angle at `t`.
fn rigid(p: &StiffChain, t: f64) -> f64 {
    let w = (1.5 * p.g / (16.0 * p.l)).sqrt();
    exact::pendulum_angle(w, p.theta0, t)
}

/// Largest distance of the run from the rigid bar: the first joint's angle from the closed
/// form, and the largest bend of the other joints.
fn off_rigid(p: &StiffChain, sol: &Solution<32>) -> (f64, f64) {
    sol.t
        .iter()
        .zip(&sol.y)
        .fold((0.0f64, 0.0f64), |(e, b), (&t, y)| {
            let bend = y.fixed_rows::<15>(1).amax();
            (e.max((y[0] - rigid(p, t)).abs()), b.max(bend))
        })
}

fn opts(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    }
}

#[test]
fn radau5_swings_the_stiff_chain_as_a_rigid_bar() {
    let p = chain();
    let sol = Radau5::new(opts(1e-8))
        .solve(&p, 0.0, p.initial_state(), T1, &[])
        .unwrap();
    let (err, bend) = off_rigid(&p, &sol);
    eprintln!(
        "Radau5: {} steps, off the rigid bar {err:.2e} rad, bend {bend:.2e}",
        sol.stats.n_accepted
    );
    assert!(err < 1e-5 && bend < 1e-5, "{err} {bend}");
    assert!(sol.stats.n_accepted < 2000, "{}", sol.stats.n_accepted);
}

#[test]
fn explicit_methods_on_the_stiff_chain_say_stiff_or_are_right() {
    let p = chain();
    let y0 = p.initial_state();
    type Run<'a> = (&'a str, Box<dyn Fn() -> Result<Solution<32>, Error> + 'a>);
    let runs: [Run; 5] = [
        (
            "DOPRI5",
            Box::new(|| Dopri5::new(opts(1e-8)).solve(&p, 0.0, y0, T1, &[])),
        ),
        (
            "DOP853",
            Box::new(|| Dop853::new(opts(1e-8)).solve(&p, 0.0, y0, T1, &[])),
        ),
        (
            "Vern9",
            Box::new(|| Vern9::new(opts(1e-8)).solve(&p, 0.0, y0, T1, &[])),
        ),
        (
            "Auto",
            Box::new(|| Auto::new(opts(1e-8)).solve(&p, 0.0, y0, T1, &[])),
        ),
        (
            "RK4 h = 1e-3",
            Box::new(|| Rk4::new(1e-3).solve(&p, 0.0, y0, T1, &[])),
        ),
    ];
    for (name, run) in runs {
        match run() {
            Ok(sol) => {
                let (err, bend) = off_rigid(&p, &sol);
                eprintln!(
                    "{name}: Ok, {} steps, off {err:.2e}, bend {bend:.2e}",
                    sol.stats.n_accepted
                );
                assert!(
                    err < 1e-5 && bend < 1e-5,
                    "{name}: a wrong Ok: {err} {bend}"
                );
            }
            Err(e) => {
                eprintln!("{name}: {e}");
                // The adaptive methods must name the cause; RK4 has no error estimate.
                if name.starts_with("RK4") {
                    assert!(matches!(e, Error::NonFinite { .. }), "{name}: {e:?}");
                } else {
                    assert!(matches!(e, Error::Stiff { .. }), "{name}: {e:?}");
                }
            }
        }
    }
}

/// Gauss (A-stable, h = 1e-3, far above the fast modes' period) keeps the slow motion.
#[test]
fn gauss_swings_the_stiff_chain_as_a_rigid_bar() {
    let p = chain();
    let sol = Gauss::new(1e-3)
        .solve(&p, 0.0, p.initial_state(), T1, &[])
        .unwrap();
    let (err, bend) = off_rigid(&p, &sol);
    assert!(err < 1e-5 && bend < 1e-5, "{err} {bend}");
}
