//! A tolerance below rounding (`1e-20`) is run at what rounding allows or refused by a
//! typed error, never returned as an `Ok` off the closed form. (A tolerance of 1 or more
//! is accepted on purpose: the convergence tests take it to accept every step.)

use mbd::integrate::{Auto, Dop853, Dopri5, Integrator, Radau5, Vern9};
use mbd::prelude::*;

/// `x'' = -x` from `x = 1` at rest: `x = cos t`.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(bob, mass = 1.0, at = [x, 0.0])]
#[spring(s, from = [0.0, 0.0], to = bob, k = 1.0)]
#[init(x = 1.0)]
pub struct Oscillator {}

fn runs(o: &Options) -> [(&'static str, Result<Solution<2>, Error>); 5] {
    let (p, y0) = (Oscillator {}, Oscillator {}.initial_state());
    [
        (
            "DOPRI5",
            Dopri5::new(o.clone()).solve(&p, 0.0, y0, 10.0, &[]),
        ),
        (
            "DOP853",
            Dop853::new(o.clone()).solve(&p, 0.0, y0, 10.0, &[]),
        ),
        ("Vern9", Vern9::new(o.clone()).solve(&p, 0.0, y0, 10.0, &[])),
        ("Auto", Auto::new(o.clone()).solve(&p, 0.0, y0, 10.0, &[])),
        (
            "Radau5",
            Radau5::new(o.clone()).solve(&p, 0.0, y0, 10.0, &[]),
        ),
    ]
}

#[test]
fn a_tolerance_below_rounding_runs_to_rounding_or_says_why() {
    let o = Options {
        rtol: 1e-20,
        atol: 1e-20,
        ..Options::default()
    };
    for (method, run) in runs(&o) {
        match run {
            Ok(s) => {
                let x = s.y.last().unwrap()[0];
                assert!((x - 10f64.cos()).abs() < 1e-12, "{method}: x(10) = {x}");
            }
            Err(e) => assert!(
                matches!(
                    e,
                    Error::StepSizeUnderflow { .. }
                        | Error::TooManySteps { .. }
                        | Error::InvalidInput { .. }
                ),
                "{method}: {e}"
            ),
        }
    }
}
