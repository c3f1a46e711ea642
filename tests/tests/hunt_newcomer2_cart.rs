//! A cart on a spring and a damper, pushed by a force input `u`: the model a control
//! engineer starts with, written from the language reference (`input`, `jacobian`,
//! `analysis::linear::state_space`).
//!
//! Hand derivation. The cart at `x` (ground frame), a spring of rest length `l0` and a
//! damper from the wall point `(0, 0)`, both along the cart's distance `x > 0`, and a force
//! `[u, 0]` at the cart: `m x'' = -k (x - l0) - c x' + u`. In the state `y = [x, x']` and
//! the output `stretch = x - l0`: `A = [[0, 1], [-k/m, -c/m]]`, `B = [0, 1/m]^T`,
//! `C = [1, 0]`, `D = 0`, and the frequency response `stretch / u = 1 / (k - m w^2 + i c w)`.
//! From rest at `x = l0` under a constant `u`, with `w^2 = k / m`, `z = c / (2 m w)`,
//! `wd = w sqrt(1 - z^2)`: `x - l0 = u / k (1 - e^(-z w t) (cos(wd t) + z w / wd sin(wd t)))`.

use mbd::analysis::linear::state_space;
use mbd::prelude::*;

/// A cart between a wall spring and damper, pushed by `u`.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[coords(x)]
#[particle(cart, mass = m, at = [x, 0.0])]
#[point(wall, at = [0.0, 0.0])]
#[spring(s, from = wall, to = cart, k = k, length = l0)]
#[damper(d, from = wall, to = cart, c = c)]
#[force(push, at = position(cart), value = [u, 0.0])]
#[input(u)]
#[init(x = l0)]
#[output(stretch = x - l0)]
pub struct Cart {
    pub m: f64,
    pub k: f64,
    pub c: f64,
    pub l0: f64,
    pub u: f64,
}

const P: Cart = Cart {
    m: 2.0,
    k: 80.0,
    c: 3.0,
    l0: 0.5,
    u: 4.0,
};

#[test]
fn state_space_is_the_textbook_one() {
    let y = P.initial_state();
    let ss = state_space(&P, 0.0, &y).unwrap();
    let exact_a = [[0.0, 1.0], [-P.k / P.m, -P.c / P.m]];
    for (r, row) in exact_a.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            assert!((ss.a[(r, c)] - v).abs() < 1e-14, "A[{r},{c}]");
        }
    }
    assert_eq!(ss.inputs, ["u"]);
    assert_eq!(ss.outputs, ["stretch"]);
    assert!(ss.b[(0, 0)].abs() < 1e-15 && (ss.b[(1, 0)] - 1.0 / P.m).abs() < 1e-15);
    assert!((ss.c[(0, 0)] - 1.0).abs() < 1e-15 && ss.c[(0, 1)].abs() < 1e-15);
    assert!(ss.d[(0, 0)].abs() < 1e-15);
    for w in [0.5, 6.0, 20.0] {
        let g = ss.frequency_response(w).unwrap()[(0, 0)];
        let den = (P.k - P.m * w * w, P.c * w);
        let mag2 = den.0 * den.0 + den.1 * den.1;
        let (re, im) = (den.0 / mag2, -den.1 / mag2);
        assert!(
            (g.re - re).abs() < 1e-14 && (g.im - im).abs() < 1e-14,
            "w = {w}"
        );
    }
}

#[test]
fn a_step_push_gives_the_damped_step_response() {
    let w = (P.k / P.m).sqrt();
    let z = P.c / (2.0 * P.m * w);
    let wd = w * (1.0 - z * z).sqrt();
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let sol = Dopri5::new(opts)
        .solve(&P, 0.0, P.initial_state(), 3.0, &[])
        .unwrap();
    for k in 1..=30 {
        let t = 0.1 * k as f64;
        let y = sol.at(t).unwrap();
        let env = (-z * w * t).exp();
        let want = P.u / P.k * (1.0 - env * ((wd * t).cos() + z * w / wd * (wd * t).sin()));
        let got = P.outputs(t, &y).unwrap().stretch;
        assert!((got - want).abs() < 1e-10, "t = {t}: {got} vs {want}");
    }
}
