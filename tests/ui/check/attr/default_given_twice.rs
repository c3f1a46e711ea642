use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x)]
#[particle(ball, mass = m, at = [x, 0.0])]
pub struct Ball {
    #[default(1.0)]
    #[default(2.0)]
    m: f64,
}

fn main() {}
