//! A symmetric top on a fixed pivot: precession `psi` about the vertical, then nutation
//! `theta`; its mass centre lies a distance `h` up the symmetry axis.
use mbd::prelude::*;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -g)]
#[coords(psi, theta)]
#[rigid3(
    top,
    mass = m,
    inertia = diag(a, a, c),
    at = rot_z(psi) * rot_y(theta) * [0.0, 0.0, h],
    rotation = rot_z(psi) * rot_y(theta)
)]
#[init(theta = 0.3)]
pub struct Top {
    pub m: f64,
    pub a: f64,
    pub c: f64,
    pub h: f64,
    pub g: f64,
}

fn main() {
    let top = Top {
        m: 1.0,
        a: 0.01,
        c: 0.02,
        h: 0.1,
        g: 9.81,
    };
    let _ = top.initial_state();
}
