use mbd::Mechanism;

/// A four-bar whose default lengths cannot close (ground 5, the others 1): no configuration
/// satisfies the loop for these constants.
#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(th, be, ga)]
#[constraint(a * cos(th) + b * cos(be) == d + c * cos(ga))]
#[constraint(a * sin(th) + b * sin(be) == c * sin(ga))]
#[rigid(crank, mass = 1.0, inertia = 0.1, at = [a / 2.0 * cos(th), a / 2.0 * sin(th)], angle = th)]
#[rigid(coupler, mass = 1.0, inertia = 0.1,
        at = [a * cos(th) + b / 2.0 * cos(be), a * sin(th) + b / 2.0 * sin(be)], angle = be)]
#[rigid(rocker, mass = 1.0, inertia = 0.1, at = [d + c / 2.0 * cos(ga), c / 2.0 * sin(ga)], angle = ga)]
#[init(th = 0.5)]
pub struct Apart {
    #[default(1.0)]
    pub a: f64,
    #[default(1.0)]
    pub b: f64,
    #[default(1.0)]
    pub c: f64,
    #[default(5.0)]
    pub d: f64,
}

fn main() {}
