// A crank-rocker reduced to its crank angle: the rocker's rate is not in the state, so an
// `init` of it would be dropped (the run would start at rest).
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[coords(th, be, ga)]
#[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
#[rigid(crank, mass = 1.0, inertia = 0.1, at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
#[rigid(coupler, mass = 1.0, inertia = 0.1,
        at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
#[rigid(rocker, mass = 1.0, inertia = 0.1, at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
#[init(th = 0.5, der(ga) = 0.5)]
pub struct RockerRate {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
}

fn main() {}
