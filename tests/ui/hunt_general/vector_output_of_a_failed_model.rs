//! A model with one mistake whose vector outputs are read by component: only the mistake
//! is reported, not each `out.p_x` of the outputs the derive would have generated.
use mbd::prelude::*;

#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, 0.0, -9.81)]
#[body(bar, joint = revolute(q, x), com = [0.0, 0.0, -l], mass = -m)]
#[point(hook, on = bar, at = [0.0, 0.1, -l])]
#[output(p = position(bar), v = velocity(bar, [0.0, 0.0, -l]), w = angular_velocity(bar))]
#[output(h = hook, r = [q, 2.0 * q], depth = position(bar)[2])]
pub struct Hinged {
    #[default(1.0)]
    m: f64,
    l: f64,
}

fn main() {
    let p = Hinged { m: 1.0, l: 1.0 };
    let o = p.outputs(0.0, &Vector::<2>::zeros()).unwrap();
    println!("{} {} {} {}", o.p_x, o.v_y, o.w_z, o.h_z);
    println!("{} {} {}", o.r_x, o.r_y, o.depth);
}
