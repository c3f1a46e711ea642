//! Coulomb friction whose normal force is a reaction, and a terminal event at rest.

use approx::assert_relative_eq;
use mbd::integrate::{Dopri5, Integrator, Radau5};
use mbd::nalgebra;
use mbd::prelude::*;

/// A block sliding down a slope of angle `slope`; `s` along the slope (downhill positive),
/// `n` normal to it, relaxed so that `reaction(n)` is the normal force.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(s)]
#[relaxed(n)]
#[particle(block, mass = m, at = [s * cos(slope) + n * sin(slope), -s * sin(slope) + n * cos(slope)])]
#[friction(along = s, mu = mu, normal = reaction(n))]
#[init(s = 0.0, der(s) = v0)]
#[output(normal = reaction(n))]
#[event(stops = der(s), falling, terminal)]
pub struct Slope {
    pub m: f64,
    pub g: f64,
    pub slope: f64,
    pub mu: f64,
    pub v0: f64,
}

#[test]
fn block_stops_where_constant_deceleration_says() {
    let b = Slope {
        m: 50.0,
        g: 9.81,
        slope: 15f64.to_radians(),
        mu: 0.4,
        v0: 7.0,
    };
    // Sliding: a = g (sin th - mu cos th) < 0; stops at t = v0/|a|, s = v0^2 / (2 |a|).
    let a = 9.81 * (b.slope.sin() - 0.4 * b.slope.cos());
    let (t_stop, s_stop) = (-7.0 / a, 49.0 / (-2.0 * a));
    let y0 = b.initial_state();
    let normal = b.outputs(0.0, &y0).unwrap().normal;
    assert_relative_eq!(normal, 50.0 * 9.81 * b.slope.cos(), max_relative = 1e-14);
    let events = b.events();
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    // The sliding view keeps the friction against downhill motion through the stop, so the
    // stop is an event on a smooth solution, for the implicit and the explicit method alike.
    let sliding = b.sliding([1.0]);
    let radau = Radau5::new(opts.clone())
        .solve(&sliding, 0.0, y0, 20.0, &events)
        .unwrap();
    let dopri = Dopri5::new(opts)
        .solve(&sliding, 0.0, y0, 20.0, &events)
        .unwrap();
    for sol in [&radau, &dopri] {
        assert_eq!(sol.stopped_by, Some(0));
        assert_relative_eq!(sol.events[0].t, t_stop, max_relative = 1e-11);
        assert_relative_eq!(sol.events[0].y[0], s_stop, max_relative = 1e-11);
    }
    let hit = &radau.events[0];
    // At rest the static friction holds it: tan(15 deg) < 0.4.
    assert!(b.s_sticks(hit.t, &hit.y).unwrap());
    // On a 30 degree slope it would not: tan(30 deg) > 0.4.
    let steep = Slope {
        slope: 30f64.to_radians(),
        ..b
    };
    assert!(
        !steep
            .s_sticks(0.0, &nalgebra::Vector2::new(0.0, 0.0))
            .unwrap()
    );
}
