use mbd::Mechanism;

#[derive(Mechanism)]
#[coords(x, y)]
#[particle(bob, mass = m, at = [x, y])]
#[output(p = position(bob), p_x = x)]
#[event(low = position(bob), falling)]
pub struct Bob {
    pub m: f64,
}

fn main() {}
