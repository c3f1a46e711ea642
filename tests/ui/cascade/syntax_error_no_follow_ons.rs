//! A mistake found while reading the attributes (an unknown key): the items still exist.
use mbd::prelude::*;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(theta)]
#[particle(bob, mass = 1.0, at = [sin(theta), -cos(theta)], colour = 2.0)]
#[output(x = position(bob)[0])]
pub struct Pendulum {}

fn main() {
    let p = Pendulum {};
    let y0 = p.initial_state();
    println!("{}", p.outputs(0.0, &y0).unwrap().x);
}
