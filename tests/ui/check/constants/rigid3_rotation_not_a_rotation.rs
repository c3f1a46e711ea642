use mbd::Mechanism;

#[derive(Mechanism)]
#[gravity(0.0, 0.0, -9.81)]
#[coords(a)]
#[rigid3(top, mass = 1.0, inertia = diag(1.0, 1.0, 2.0), at = [0.0, 0.0, 0.0],
         rotation = [[cos(a), -sin(a), 0.0], [sin(a), cos(a), 0.0], [0.0, 0.0, s]])]
pub struct Top {
    #[default(2.0)]
    s: f64,
}

fn main() {}
