use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, -g)]
#[repeat(i in 3..3, particle(bob[i], mass = m, at = [i, 0.0]))]
#[repeat(i in 0..2, particle(bob[i - 1], mass = m, at = [i, 0.0]))]
#[repeat(i in 0..2, particle(bob[i * m], mass = m, at = [i, 0.0]))]
#[repeat(i in 0..2, repeat(j in 0..2))]
#[repeat(i in 0..2)]
#[coords(x)]
#[particle(ball, mass = m, at = [x, 0.0])]
pub struct Bad {
    pub m: f64,
    pub g: f64,
}

fn main() {
    // The model's items exist despite the errors: no follow-on error here.
    let _ = Bad::COORDINATES;
}
