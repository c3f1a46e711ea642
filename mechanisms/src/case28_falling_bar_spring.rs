//! Case 28: a falling bar with a spring at its middle: the minimum angular speed, and the
//! angular speed at the horizontal (Meriam & Kraige 7th ed., P6/229, p. 511).
//!
//! **Problem.** A uniform slender bar, `m = 30 kg`, `l = 2.4 m`, is pivoted at its lower end
//! O in a vertical plane; a spring `k = 3 kN/m` joins a fixed point C to the bar's midpoint.
//! In the vertical position the spring is unstretched and the bar turns at `ω_0 = 4 rad/s`,
//! falling over. Find the minimum angular speed `ω_min` and its angle θ, and ω when the bar
//! reaches the horizontal (θ = 90°). The manual uses `g = 9.81 m/s^2`.
//!
//! **Geometry, reconstructed from the worked solution** (the figure was lost).
//! `I_O = (1/3) 30 × 2.4^2 = 57.6` (its unit "m^2" is a typo for kg m^2): a uniform bar
//! pivoted at an end. `30 × 9.81 × 1.2 (1 − cos θ)` is gained as θ grows: G, 1.2 m from O,
//! starts straight *above* O, and θ is the bar's angle from the upward vertical.
//! `l^2 = 1.2^2 + 1.2^2 − 2 × 1.2 × 1.2 cos(90° + θ)`: the spring joins G to a fixed point C
//! 1.2 m from O, 90° from the vertical on the side *away from* the fall (the spring
//! lengthens as θ grows); its free length is `1.2 √2`. Chosen frame: O = (0, 0),
//! C = (−1.2, 0), G = 1.2 (sin θ, cos θ), the bar falling clockwise with `θ'(0) = +4`. The
//! manual's "l_2 = 0.2 m" is not used by its solution (the spring acts at 1.2 m) and plays
//! no part here.
//!
//! **Model.** One body, one free coordinate θ: the bar (30 kg, `I_G = 30 × 2.4^2/12`, G at
//! mid-length, angle `π/2 − θ`), gravity `(0, −g)`, the spring from C to G with free length
//! `1.2 √2`. Initial state θ = 0, `θ' = 4 rad/s`. The minimum of `θ'` is the first upward
//! crossing of `θ''` (recorded); the horizontal the first upward crossing of `θ − π/2`
//! (terminal).
//!
//! **Reference (exact).** Energy: `½ I_O ω^2 = ½ I_O ω_0^2 + m g 1.2 (1 − cos θ) − ½ k δ^2`,
//! `δ = 1.2 √2 (sqrt(1 + sin θ) − 1)`. `d(ω^2)/dθ = 0` is
//! `m g h sin θ = k h^2 cos θ (1 − 1/sqrt(1 + sin θ))`, a transcendental equation solved by
//! bisection in [`references`]: **θ = 1.29236769462631380537431168011 rad =
//! 74.0472144811397795624418045996°**, **`ω_min = 0.910158253959415037777940144597 rad/s`**;
//! **`ω(90°) = sqrt((460.8 + 353.16 − 4320 (3 − 2√2))/28.8) =
//! 1.58951838993089810697372371744 rad/s`** (`mechanisms/reference/case28.py`: closed form
//! and the equation of motion integrated at 30 digits; event times 0.6061069262547 s and
//! 0.8533986068592 s).
//!
//! **Discrepancies in the manual.** Its ω formula rounds `7826.04/28.8 = 271.7375` to 271.74
//! and `353.16/28.8 = 12.2625` to 12.263; that formula's minimum is 0.90871 at 74.0466°,
//! hence its 0.909 (exact 0.910158). Its printed angle 73.79° (1.2879 rad) is not the
//! minimum even of its own formula (a misread plot): corrected θ = 74.047°. Its
//! `ω(90°) = 1.589` is its rounded formula's 1.58873; the exact 1.5895184 rounds to 1.590.
//! RecurDyn is about 1 % off in both ω's, in opposite directions.

use crate::drawing::{At, Sketch};
use crate::sim;
use crate::validation::{Curve, Outcome, Row};
use mbd::prelude::*;

/// A bar pivoted at its lower end O (θ from the upward vertical, clockwise), with a spring
/// from C, `c` to the left of O, to its mass centre.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[point(anchor_c, at = [-c, 0.0])]
#[rigid(bar, mass = m, inertia = m * l * l / 12.0,
        at = [l / 2.0 * sin(theta), l / 2.0 * cos(theta)], angle = PI / 2.0 - theta)]
#[spring(spring, from = anchor_c, to = bar, k = k, length = hypot(c, l / 2.0))]
#[init(theta = 0.0, der(theta) = omega_0)]
#[output(omega = der(theta))]
#[event(slowest = der(der(theta)), rising)]
#[event(horizontal = theta - PI / 2.0, rising, terminal)]
pub struct FallingBar {
    pub m: f64,
    pub g: f64,
    pub l: f64,
    /// C's distance from O, horizontally.
    pub c: f64,
    pub k: f64,
    /// Angular speed in the vertical position.
    pub omega_0: f64,
}

/// The manual's data.
pub const MODEL: FallingBar = FallingBar {
    m: 30.0,
    g: 9.81,
    l: 2.4,
    c: 1.2,
    k: 3000.0,
    omega_0: 4.0,
};

/// The drawing beyond the model's shapes. The bar's upper end is free.
pub const SKETCH: Sketch = Sketch {
    free: &[At("bar", 1)],
    ..Sketch::NONE
};

/// `ω^2` at θ from the energy balance (the module docs), for `c = l/2`.
pub fn omega_sq(theta: f64) -> f64 {
    let FallingBar {
        m,
        g,
        l,
        k,
        omega_0,
        ..
    } = MODEL;
    let (h, i_o) = (l / 2.0, m * l * l / 3.0);
    let stretch = h * 2f64.sqrt() * ((1.0 + theta.sin()).sqrt() - 1.0);
    omega_0 * omega_0
        + (m * g * h * (1.0 - theta.cos()) - k / 2.0 * stretch * stretch) / (i_o / 2.0)
}

/// Exact references `[ω_min, θ at ω_min in degrees, ω(90°)]`. The stationary point solves
/// `m g h sin θ − k h^2 cos θ (1 − 1/sqrt(1 + sin θ)) = 0`, negative before the minimum and
/// positive after; it is bracketed by [60°, 85°] and found by bisection to rounding.
pub fn references() -> [f64; 3] {
    let FallingBar { m, g, l, k, .. } = MODEL;
    let h = l / 2.0;
    let slope = |th: f64| {
        m * g * h * th.sin() - k * h * h * th.cos() * (1.0 - 1.0 / (1.0 + th.sin()).sqrt())
    };
    let (mut lo, mut hi) = (60f64.to_radians(), 85f64.to_radians());
    while hi - lo > f64::EPSILON * hi {
        let mid = 0.5 * (lo + hi);
        if slope(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let theta = 0.5 * (lo + hi);
    [
        omega_sq(theta).sqrt(),
        theta.to_degrees(),
        omega_sq(std::f64::consts::FRAC_PI_2).sqrt(),
    ]
}

pub fn run() -> mbd::Result<Outcome> {
    let model = MODEL;
    let events = model.events();
    let sol = sim::integrate(&model, model.initial_state(), 5.0, &events)?;
    let find = |event: usize, detail: &str| {
        sol.events
            .iter()
            .find(|e| e.event == event)
            .ok_or(mbd::Error::InvalidInput {
                what: "case 28",
                detail: detail.into(),
            })
    };
    let slowest = find(0, "no minimum of the angular speed")?;
    let horizontal = find(1, "the bar did not reach the horizontal")?;
    let omega_min = model.outputs(slowest.t, &slowest.y)?.omega;
    let [omega_min_ref, theta_ref, omega_90_ref] = references();
    let speed = || sim::sample(&sol, 200, |t, y| (t, y[1]));
    const SPEED: &str = "angular speed θ' [rad/s]";
    Ok(Outcome {
        rows: vec![
            Row {
                quantity: "omega_min",
                value: omega_min,
                reference: omega_min_ref,
                method: sim::METHOD,
                curve: Curve::at_instant(SPEED, speed(), slowest.t),
            },
            Row {
                quantity: "theta_at_omega_min",
                value: slowest.y[0].to_degrees(),
                reference: theta_ref,
                method: sim::METHOD,
                curve: Curve::at_instant(
                    "bar angle θ [deg]",
                    sim::sample(&sol, 200, |t, y| (t, y[0].to_degrees())),
                    slowest.t,
                ),
            },
            Row {
                quantity: "omega_at_90deg",
                value: model.outputs(horizontal.t, &horizontal.y)?.omega,
                reference: omega_90_ref,
                method: sim::METHOD,
                curve: Curve::at_instant(SPEED, speed(), horizontal.t),
            },
        ],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn case28_matches_the_exact_values() {
        let out = run().unwrap();
        for row in &out.rows {
            assert_relative_eq!(row.value, row.reference, max_relative = 1e-9);
        }
    }

    #[test]
    fn case28_references_are_the_30_digit_values() {
        // mechanisms/reference/case28.py.
        let [omega_min, theta, omega_90] = references();
        assert_relative_eq!(omega_min, 0.910_158_253_959_415, max_relative = 1e-14);
        assert_relative_eq!(theta, 74.047_214_481_139_78, max_relative = 1e-14);
        assert_relative_eq!(omega_90, 1.589_518_389_930_898, max_relative = 1e-14);
        let closed = ((460.8 + 353.16 - 4320.0 * (3.0 - 2.0 * 2f64.sqrt())) / 28.8).sqrt();
        assert_relative_eq!(omega_90, closed, max_relative = 1e-13);
    }

    #[test]
    fn case28_event_times_and_energy() {
        let model = MODEL;
        let events = model.events();
        let sol = sim::integrate(&model, model.initial_state(), 5.0, &events).unwrap();
        let (slowest, horizontal) = (&sol.events[0], &sol.events[1]);
        assert_eq!((slowest.event, horizontal.event), (0, 1));
        // mechanisms/reference/case28.py, 30-digit integration.
        assert_relative_eq!(slowest.t, 0.606_106_926_254_739_4, max_relative = 1e-9);
        assert_relative_eq!(horizontal.t, 0.853_398_606_859_183_6, max_relative = 1e-9);
        let e = |y: &Vector<2>| {
            MechanismModel::energy(
                &model,
                0.0,
                &Vector::<1>::new(y[0]),
                &Vector::<1>::new(y[1]),
            )
            .unwrap()
        };
        // Conservative; the initial kinetic energy ½ I_O ω_0^2 = 460.8 J sets the scale.
        assert_relative_eq!(
            e(&horizontal.y),
            e(&model.initial_state()),
            epsilon = 1e-9 * 460.8
        );
    }

    #[test]
    fn case28_pins_the_corrected_values() {
        let [omega_min, theta, omega_90] = references();
        assert_eq!(format!("{omega_min:.3}"), "0.910");
        assert_eq!(format!("{theta:.2}"), "74.05");
        assert_eq!(format!("{omega_90:.3}"), "1.590");
        // The manual's rounded formula ω^2 = −271.74 − 12.263 cos θ − 150 sin θ
        // + 300 sqrt(1 + sin θ) gives its 1.589 at 90° and a minimum of 0.909 at 74.05°,
        // not at its printed 73.79°.
        let rounded = |th: f64| {
            (-271.74 - 12.263 * th.cos() - 150.0 * th.sin() + 300.0 * (1.0 + th.sin()).sqrt())
                .sqrt()
        };
        assert_eq!(
            format!("{:.3}", rounded(std::f64::consts::FRAC_PI_2)),
            "1.589"
        );
        let (at, min) = (0..=4000)
            .map(|i| 70.0 + 6.0 * f64::from(i) / 4000.0)
            .map(|deg| (deg, rounded(deg.to_radians())))
            .fold((0.0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        assert_eq!(format!("{min:.3}"), "0.909");
        assert_eq!(format!("{at:.2}"), "74.05");
        assert!(rounded(73.79f64.to_radians()) > min);
    }
}
