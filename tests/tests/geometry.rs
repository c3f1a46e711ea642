//! The generated `geometry` part (`#[mechanism(geometry)]`): every point it draws is
//! checked against the mechanism's closed-form positions.

use approx::assert_relative_eq;
use mbd::prelude::*;
use mbd::{ShapeKind, Vector};

/// A double pendulum as a joint tree hanging from a pin at `(0, h)`, with a spring from a
/// fixed point to the lower link's mass centre, a point fixed on the lower link (its tip) and
/// a damper to a point given by position.
#[derive(Debug, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -9.81)]
#[body(upper, joint = revolute(a), at = [0.0, h], com = [l / 2.0, 0.0], mass = m, inertia = m * l * l / 12.0)]
#[body(lower, parent = upper, joint = revolute(b), at = [l, 0.0], com = [l / 2.0, 0.0], mass = m, inertia = m * l * l / 12.0)]
#[point(anchor, at = [2.0 * l, h])]
#[point(tip, on = lower, at = [l, 0.0])]
#[spring(pull, from = anchor, to = lower, k = 10.0)]
#[damper(drag, from = [0.0, 0.0], to = upper, c = 1.0)]
pub struct Hanging {
    pub m: f64,
    pub l: f64,
    pub h: f64,
}

/// A slider with a bar pinned to it: explicit expressions, a particle and a rigid body.
#[derive(Debug, Mechanism)]
#[mechanism(geometry)]
#[gravity(0.0, -9.81)]
#[coords(x, th)]
#[particle(slider, mass = m, at = [x, 0.0])]
#[rigid(bar, mass = m, inertia = m * l * l / 12.0, at = [x + l / 2.0 * cos(th), l / 2.0 * sin(th)], angle = th)]
pub struct SliderBar {
    pub m: f64,
    pub l: f64,
}

/// Without the option there is no `Drawable`.
#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(p, mass = 1.0, at = [x, 0.0])]
pub struct Plain {}

fn close(a: [f64; 3], b: [f64; 3]) {
    for i in 0..3 {
        assert_relative_eq!(a[i], b[i], epsilon = 1e-14);
    }
}

#[test]
fn a_tree_is_drawn_joint_to_joint_with_its_spring_and_damper() {
    let (m, l, h) = (1.0, 0.7, 2.0);
    let model = Hanging { m, l, h };
    let (a, b) = (0.4_f64, -1.1_f64);
    let y = Vector::<4>::new(a, b, 0.3, -0.2);
    let shapes = model.geometry(0.0, &y).unwrap();
    let kinds: Vec<_> = shapes.iter().map(|s| (s.kind, s.name)).collect();
    assert_eq!(
        kinds,
        [
            (ShapeKind::Link, "upper"),
            (ShapeKind::Link, "lower"),
            (ShapeKind::Point, "anchor"),
            (ShapeKind::Point, "tip"),
            (ShapeKind::Spring, "pull"),
            (ShapeKind::Damper, "drag"),
        ]
    );
    let pin = [0.0, h, 0.0];
    let elbow = [l * a.cos(), h + l * a.sin(), 0.0];
    let lower_com = [
        elbow[0] + l / 2.0 * (a + b).cos(),
        elbow[1] + l / 2.0 * (a + b).sin(),
        0.0,
    ];
    let tip = [
        elbow[0] + l * (a + b).cos(),
        elbow[1] + l * (a + b).sin(),
        0.0,
    ];
    // Upper: parent joint (its own, on the ground), joint, mass centre, far end.
    let upper = &shapes[0].points;
    close(upper[0], pin);
    close(upper[1], pin);
    close(upper[2], [l / 2.0 * a.cos(), h + l / 2.0 * a.sin(), 0.0]);
    close(upper[3], elbow);
    // Lower: from the upper's joint to its own, its mass centre, the tip.
    let lower = &shapes[1].points;
    close(lower[0], pin);
    close(lower[1], elbow);
    close(lower[2], lower_com);
    close(lower[3], tip);
    close(shapes[2].points[0], [2.0 * l, h, 0.0]);
    // A body-fixed point moves with its body.
    close(shapes[3].points[0], tip);
    close(shapes[4].points[0], [2.0 * l, h, 0.0]);
    close(shapes[4].points[1], lower_com);
    close(shapes[5].points[0], [0.0, 0.0, 0.0]);
    close(shapes[5].points[1], upper[2]);
    assert!(Hanging::GENERATED.parts.contains(&"geometry"));
    assert!(!Plain::GENERATED.parts.contains(&"geometry"));
}

#[test]
fn a_rigid_body_is_the_bar_of_its_mass_and_inertia() {
    // I = m l^2 / 12 about the centre: the slender bar of length l, so its ends are the
    // pin on the slider and the free end.
    let model = SliderBar { m: 2.0, l: 0.9 };
    let (x, th) = (0.25_f64, 0.6_f64);
    let y = Vector::<4>::new(x, th, 1.0, 2.0);
    let shapes = model.geometry(0.0, &y).unwrap();
    assert_eq!(shapes[0].kind, ShapeKind::Particle);
    close(shapes[0].points[0], [x, 0.0, 0.0]);
    assert_eq!(shapes[1].kind, ShapeKind::Rigid);
    let bar = &shapes[1].points;
    close(bar[0], [x + 0.45 * th.cos(), 0.45 * th.sin(), 0.0]);
    close(bar[1], [x + 0.9 * th.cos(), 0.9 * th.sin(), 0.0]);
    close(bar[2], [x, 0.0, 0.0]);
}
