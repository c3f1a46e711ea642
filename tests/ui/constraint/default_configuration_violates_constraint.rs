use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[constraint(x * x + y * y == l * l)]
#[init(x = 0.0, y = -1.0)]
pub struct Pendulum {
    #[default(1.0)]
    pub m: f64,
    #[default(2.0)]
    pub l: f64,
    #[default(9.81)]
    pub g: f64,
}

fn main() {}
