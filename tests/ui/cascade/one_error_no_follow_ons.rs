//! A model with one mistake, used the way a program uses a model: only the mistake is
//! reported, not every use of the items the derive would have generated.
use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(theta)]
#[particle(bob, mass = -m, at = [l * sin(theta), -l * cos(theta)])]
#[output(x = position(bob)[0])]
#[event(bottom = theta, rising)]
#[init(theta = 0.5)]
pub struct Pendulum {
    #[default(1.0)]
    m: f64,
    l: f64,
}

fn main() {
    let p = Pendulum { m: 1.0, l: 1.0 };
    let y0 = p.initial_state();
    let events = p.events();
    let sol = Dopri5::new(Options::default()).solve(&p, 0.0, y0, 1.0, &events).unwrap();
    let (t, y) = sol.last();
    let o = p.outputs(t, y).unwrap();
    let s = PendulumState::from(y);
    println!("{} {} {} {}", o.x, s.theta, s.theta_dot, Pendulum::DOF);
    let _ = p.mass_matrix(0.0, &Vector::<1>::zeros());
}
