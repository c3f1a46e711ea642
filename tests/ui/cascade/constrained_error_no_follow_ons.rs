//! A closed-loop model with one mistake, and a friction model with one: the constraint and
//! friction items still exist.
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x, y)]
#[particle(bob, mass = 1.0, at = [x, y])]
#[constraint(x * x + y * y == l * l)]
#[friction(along = x, mu = -0.2, normal = 9.81)]
pub struct Bead {
    l: f64,
}

fn main() {
    let b = Bead { l: 1.0 };
    let q = Vector::<2>::zeros();
    let _ = b.phi(0.0, &q);
    let _ = b.acceleration_sliding(0.0, &q, &q, &[1.0]);
    let _ = b.x_sticks(0.0, &b.initial_state());
    let _ = mbd::hybrid::solve(
        &mbd::integrate::Dopri5::new(Options::default()),
        &b,
        0.0,
        b.initial_state(),
        1.0,
        &[],
    );
}
