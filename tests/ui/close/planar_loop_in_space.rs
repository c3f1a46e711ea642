use mbd::Mechanism;

/// A four-bar on revolute joints about `z`, written in space and closed by a revolute `close`
/// about `z`: the points' `z` and the axes' tilt never change, so three of the five rows are
/// identically zero. Written planar, the same loop is a planar `close`.
#[derive(Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, -9.81, 0.0)]
#[body(crank, joint = revolute(a, z), com = [0.5, 0.0, 0.0], mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
#[body(coupler, parent = crank, joint = revolute(b, z), at = [1.0, 0.0, 0.0], com = [1.0, 0.0, 0.0],
       mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
#[body(rocker, joint = revolute(c, z), at = [2.0, 0.0, 0.0], com = [0.0, 0.5, 0.0], mass = 1.0,
       inertia = diag(0.1, 0.01, 0.1))]
#[close(pin, joint = revolute, a = coupler, at_a = [2.0, 0.0, 0.0], axis_a = [0.0, 0.0, 1.0],
        b = rocker, at_b = [0.0, 1.0, 0.0], axis_b = [0.0, 0.0, 1.0])]
pub struct FourBar {}

fn main() {}
