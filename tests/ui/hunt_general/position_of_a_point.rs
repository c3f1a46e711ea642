//! `position` of a named point: the point is already a vector, and the message says so.
use mbd::prelude::*;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
#[point(hook, on = arm, at = [0.1, -l])]
#[output(h = position(hook))]
pub struct Arm {
    m: f64,
    l: f64,
}

fn main() {}
