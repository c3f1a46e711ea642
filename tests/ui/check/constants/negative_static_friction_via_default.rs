use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -9.81)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[friction(along = x, mu = 0.3, mu_static = -mu_s, normal = 9.81)]
pub struct Block {
    #[default(0.5)]
    mu_s: f64,
}

fn main() {}
