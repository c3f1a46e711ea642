//! Hunting extreme mass ratios: a double pendulum of two point masses whose ratio is 1e-12
//! or 1e12 (a near-massless bob on a heavy one, and the reverse), in the articulated-body
//! recursion and in the mass-matrix form, against the closed-form accelerations (Cramer's
//! rule written out in absolute angles, exact at any ratio): each within 1e-12 of the
//! largest acceleration, no NaN, no singular mass matrix.

use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[mechanism(recursive)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(a), com = [0.0, -l1], mass = m1)]
#[body(lower, parent = upper, joint = revolute(b), at = [0.0, -l1], com = [0.0, -l2], mass = m2)]
pub struct Recursive {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[mechanism(mass_matrix)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(a), com = [0.0, -l1], mass = m1)]
#[body(lower, parent = upper, joint = revolute(b), at = [0.0, -l1], com = [0.0, -l2], mass = m2)]
pub struct ByMatrix {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

/// The double pendulum of point masses in absolute angles `t1`, `t2` from the downward
/// vertical (`d = t1 - t2`, `den = 2 m1 + m2 - m2 cos 2d`):
/// `t1'' = (-g (2 m1 + m2) sin t1 - m2 g sin(t1 - 2 t2) - 2 sin d m2 (w2^2 l2 + w1^2 l1 cos d)) / (l1 den)`,
/// `t2'' = 2 sin d (w1^2 l1 (m1 + m2) + g (m1 + m2) cos t1 + w2^2 l2 m2 cos d) / (l2 den)`.
/// Returned in the model's relative coordinates `a = t1`, `b = t2 - t1`.
fn closed_form(m1: f64, m2: f64, l1: f64, l2: f64, g: f64, q: [f64; 2], qd: [f64; 2]) -> [f64; 2] {
    let (t1, t2, w1, w2) = (q[0], q[0] + q[1], qd[0], qd[0] + qd[1]);
    let d = t1 - t2;
    let den = 2.0 * m1 + m2 - m2 * (2.0 * d).cos();
    let a1 = (-g * (2.0 * m1 + m2) * t1.sin()
        - m2 * g * (t1 - 2.0 * t2).sin()
        - 2.0 * d.sin() * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * d.cos()))
        / (l1 * den);
    let a2 = 2.0
        * d.sin()
        * (w1 * w1 * l1 * (m1 + m2) + g * (m1 + m2) * t1.cos() + w2 * w2 * l2 * m2 * d.cos())
        / (l2 * den);
    [a1, a2 - a1]
}

#[test]
fn mass_ratios_of_a_trillion_either_way_give_the_closed_form() {
    let (l1, l2, g) = (0.8, 0.5, 9.81);
    for (m1, m2) in [(1e6, 1e-6), (1e-6, 1e6), (1.0, 1e-12), (1e-12, 1.0)] {
        let rec = Recursive { m1, m2, l1, l2, g };
        let mm = ByMatrix { m1, m2, l1, l2, g };
        for (q, qd) in [
            ([0.7, -1.1], [1.3, 0.4]),
            ([2.5, 0.3], [-0.6, 2.2]),
            ([0.0, 0.0], [0.0, 0.0]),
        ] {
            let want = closed_form(m1, m2, l1, l2, g, q, qd);
            let scale = want[0].abs().max(want[1].abs()).max(1.0);
            let (qv, qdv) = (Vector::<2>::from(q), Vector::<2>::from(qd));
            for (name, got) in [
                ("recursive", rec.acceleration(0.0, &qv, &qdv)),
                ("mass matrix", mm.acceleration(0.0, &qv, &qdv)),
            ] {
                let got = got.unwrap_or_else(|e| panic!("{name} m1 {m1:e} m2 {m2:e}: {e}"));
                for k in 0..2 {
                    assert!(
                        (got[k] - want[k]).abs() < 1e-12 * scale,
                        "{name} m1 {m1:e} m2 {m2:e} q {q:?}: {} against {}",
                        got[k],
                        want[k]
                    );
                }
            }
        }
    }
}
