//! A free joint's rotation coordinates are modified Rodrigues parameters (switched to their
//! shadow set once a turn): friction along one of them has no meaning.
use mbd::Mechanism;

#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -g)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [0.0, 0.0, -1.0], mass = m, inertia = diag(0.1, 0.1, 0.1))]
#[friction(along = s2, mu = 0.3, normal = m * g)]
pub struct Sat {
    m: f64,
    g: f64,
}

fn main() {}
