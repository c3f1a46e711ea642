//! The language's conveniences, each checked against a closed form written beside it:
//! vector outputs (components `p_x`, `p_y`, `p_z`).

use mbd::Vector;
use mbd::prelude::*;

/// A planar pendulum as a tree body, its bob's position and velocity as vector outputs.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
#[output(p = position(arm), v = velocity(arm), tip = position(arm, [0.0, -l / 2.0]))]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// A spatial particle: `position` has three components.
#[derive(Debug, Mechanism)]
#[gravity(0.0, 0.0, -g)]
#[coords(x, y, z)]
#[particle(ball, mass = m, at = [x, y, z])]
#[output(r = position(ball), speed = norm(velocity(ball)))]
pub struct Ball {
    pub m: f64,
    pub g: f64,
}

#[test]
fn vector_outputs_are_their_components() -> Result<(), mbd::Error> {
    assert_eq!(
        Pendulum::OUTPUTS,
        ["p_x", "p_y", "v_x", "v_y", "tip_x", "tip_y"]
    );
    let p = Pendulum {
        m: 1.5,
        l: 0.8,
        g: 9.81,
    };
    for (q, w) in [(0.3, -1.2), (-2.0, 0.7), (1.0, 0.0)] {
        let o = p.outputs(0.0, &Vector::<2>::new(q, w))?;
        // Closed form: the bob at l (sin q, -cos q), its velocity l w (cos q, sin q).
        let (s, c) = f64::sin_cos(q);
        let tol = 1e-15;
        assert!((o.p_x - p.l * s).abs() < tol && (o.p_y + p.l * c).abs() < tol);
        assert!((o.v_x - p.l * w * c).abs() < tol && (o.v_y - p.l * w * s).abs() < tol);
        assert!((o.tip_x - p.l / 2.0 * s).abs() < tol && (o.tip_y + p.l / 2.0 * c).abs() < tol);
        assert_eq!(p.output_values(0.0, &Vector::<2>::new(q, w))?[0], o.p_x);
    }
    let b = Ball { m: 2.0, g: 9.81 };
    assert_eq!(Ball::OUTPUTS, ["r_x", "r_y", "r_z", "speed"]);
    let y = Vector::<6>::from_column_slice(&[1.0, -2.0, 3.0, 3.0, 4.0, 12.0]);
    let o = b.outputs(0.0, &y)?;
    assert_eq!([o.r_x, o.r_y, o.r_z, o.speed], [1.0, -2.0, 3.0, 13.0]);
    Ok(())
}
