//! Kinematic analysis needs as many constraint rows as coordinates: a slider-crank whose
//! crank is not driven keeps one free coordinate (three coordinates, two closure rows), so
//! `kinematics` is refused by `cargo check`, with a note saying what to use instead.
use mbd::analysis::{NewtonOptions, kinematics};
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[mechanism(augmented)]
#[coords(theta, beta, x)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[particle(piston, mass = m, at = [x, 0.0])]
#[rigid(crank, mass = m, inertia = m * r * r / 12.0, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
pub struct FreeCrank {
    pub r: f64,
    pub l: f64,
    pub m: f64,
}

fn main() {
    let sc = FreeCrank { r: 0.1, l: 0.3, m: 1.0 };
    let guess = mbd::Vector::<3>::new(0.0, 0.0, 0.4);
    let _ = kinematics(&sc, 0.0, &guess, &NewtonOptions::default());
}
