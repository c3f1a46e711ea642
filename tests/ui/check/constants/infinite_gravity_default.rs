use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[coords(y)]
#[particle(ball, mass = 1.0, at = [0.0, y])]
pub struct Ball {
    #[default(1.0e308 * 10.0)]
    g: f64,
}

fn main() {}
