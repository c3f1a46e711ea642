//! Hunting big models: the implicit methods keep their `D x D` Jacobians, iteration
//! matrices and LU factors on the stack (const generics). A 100-link chain (`D = 200`)
//! needed about 5 MiB there: Radau5 and Gauss aborted the process with a stack overflow
//! (`SIGABRT`, no error, no result) in a thread of the default 2 MiB (a test's, a rayon
//! worker's), and a 128-link chain would in a main thread's 8 MiB. Now a run whose
//! matrices may not fit what is left of the stack gets a stack of its own.
//!
//! The truth: the chain is conservative, so its energy (the generated `energy`, evaluated
//! on the result) stays the initial one, and the state at the end is DOP853's at a tight
//! tolerance (an explicit method, which never needed the matrices).

use mbd::Vector;
use mbd::integrate::{Dop853, Gauss, Integrator, Options, Radau5};
use mbd::prelude::*;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, -g)]
#[chain(link, n = 100, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
pub struct Chain100 {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

const P: Chain100 = Chain100 {
    m: 1.0,
    l: 0.1,
    g: 9.81,
};
const T1: f64 = 0.05;

fn y0() -> Vector<200> {
    let mut y = P.initial_state();
    y[0] = 0.3;
    y[1] = -0.2;
    y
}

fn energy(y: &Vector<200>) -> f64 {
    let q = y.fixed_rows::<100>(0).into_owned();
    let qd = y.fixed_rows::<100>(100).into_owned();
    P.energy(0.0, &q, &qd).unwrap()
}

/// Runs `solve` on a thread with the default 2 MiB stack a test or a rayon worker has.
fn on_small_stack(solve: fn() -> Vector<200>) -> Vector<200> {
    std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(solve)
        .unwrap()
        .join()
        .unwrap()
}

fn reference() -> Vector<200> {
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let sol = Dop853::new(opts).solve(&P, 0.0, y0(), T1, &[]).unwrap();
    *sol.y.last().unwrap()
}

fn check(name: &str, y: &Vector<200>, tol: f64) {
    let (e0, e1) = (energy(&y0()), energy(y));
    let reference = reference();
    let off = (y - reference).amax();
    eprintln!("{name}: energy {e0} -> {e1}, off DOP853 {off:.2e}");
    assert!(
        (e1 - e0).abs() <= 1e-6 * e0.abs(),
        "{name}: energy {e0} -> {e1}"
    );
    assert!(off <= tol, "{name}: {off}");
}

#[test]
fn radau5_on_a_100_link_chain_in_a_2_mib_thread() {
    let y = on_small_stack(|| {
        let opts = Options {
            rtol: 1e-8,
            atol: 1e-8,
            ..Options::default()
        };
        let sol = Radau5::new(opts).solve(&P, 0.0, y0(), T1, &[]).unwrap();
        *sol.y.last().unwrap()
    });
    check("Radau5", &y, 1e-5);
}

#[test]
fn gauss_on_a_100_link_chain_in_a_2_mib_thread() {
    let y = on_small_stack(|| {
        let sol = Gauss::new(2.5e-4).solve(&P, 0.0, y0(), T1, &[]).unwrap();
        *sol.y.last().unwrap()
    });
    check("Gauss", &y, 1e-5);
}
