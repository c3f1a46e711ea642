//! Joint trees (`body`, `chain`): frames composed by the macro, accelerations by the
//! articulated-body recursion, each checked against an independent derivation:
//! the same mechanism written out body by body in explicit expressions (kinematics),
//! the mass-matrix form of Kane's equations (dynamics), and closed forms.

use approx::assert_relative_eq;
use mbd::integrate::{Dopri5, Integrator, Options};
use mbd::prelude::*;
use mbd::{Matrix, Vector};

/// Deterministic pseudo-random numbers in `[-1, 1)` (a linear congruential generator).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn vector<const N: usize>(&mut self, scale: f64) -> Vector<N> {
        Vector::<N>::from_fn(|_, _| scale * self.next())
    }
}

/// One mechanism description stamped twice: as `$name` with the given evaluation (or the
/// macro's choice) and as `$dense` forced onto the mass-matrix solve, the independent
/// derivation (Kane's equations, no recursion) the recursion is checked against.
macro_rules! with_mass_matrix_twin {
    ($(#[doc = $doc:literal])* $([$($eval:tt)*])? $name:ident, $dense:ident, { $($field:ident),* }, $(#[$attr:meta])*) => {
        $(#[doc = $doc])*
        #[derive(Debug, Mechanism)]
        $(#[mechanism($($eval)*)])?
        $(#[$attr])*
        pub struct $name { $(pub $field: f64),* }

        #[doc = concat!("[`", stringify!($name), "`] on the mass-matrix solve.")]
        #[derive(Debug, Mechanism)]
        #[mechanism(mass_matrix)]
        $(#[$attr])*
        pub struct $dense { $(pub $field: f64),* }
    };
}

with_mass_matrix_twin! {
    /// Five uniform links; `chain` chooses the recursion (five bodies).
    Chain5, Chain5Dense, { m, l, g },
    #[gravity(0.0, -g)]
    #[chain(link, n = 5, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
}

/// The same chain written out: relative angles `q1..q5`, absolute `t_k = q1 + .. + qk`,
/// link `k` along `(sin t_k, -cos t_k)` from the end of link `k - 1`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(q1, q2, q3, q4, q5)]
#[point(j2, at = [l * sin(q1), -l * cos(q1)])]
#[point(j3, at = j2 + [l * sin(q1 + q2), -l * cos(q1 + q2)])]
#[point(j4, at = j3 + [l * sin(q1 + q2 + q3), -l * cos(q1 + q2 + q3)])]
#[point(j5, at = j4 + [l * sin(q1 + q2 + q3 + q4), -l * cos(q1 + q2 + q3 + q4)])]
#[rigid(l1, mass = m, inertia = m * l * l / 12.0, angle = q1,
        at = [l / 2.0 * sin(q1), -l / 2.0 * cos(q1)])]
#[rigid(l2, mass = m, inertia = m * l * l / 12.0, angle = q1 + q2,
        at = j2 + [l / 2.0 * sin(q1 + q2), -l / 2.0 * cos(q1 + q2)])]
#[rigid(l3, mass = m, inertia = m * l * l / 12.0, angle = q1 + q2 + q3,
        at = j3 + [l / 2.0 * sin(q1 + q2 + q3), -l / 2.0 * cos(q1 + q2 + q3)])]
#[rigid(l4, mass = m, inertia = m * l * l / 12.0, angle = q1 + q2 + q3 + q4,
        at = j4 + [l / 2.0 * sin(q1 + q2 + q3 + q4), -l / 2.0 * cos(q1 + q2 + q3 + q4)])]
#[rigid(l5, mass = m, inertia = m * l * l / 12.0, angle = q1 + q2 + q3 + q4 + q5,
        at = j5 + [l / 2.0 * sin(q1 + q2 + q3 + q4 + q5), -l / 2.0 * cos(q1 + q2 + q3 + q4 + q5)])]
pub struct Chain5Explicit {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn chain_recursion_equals_mass_matrix_and_explicit_model() {
    let (m, l, g) = (1.3, 0.45, 9.81);
    let rec = Chain5 { m, l, g };
    let dense = Chain5Dense { m, l, g };
    let explicit = Chain5Explicit { m, l, g };
    assert!(Chain5::GENERATED.parts.contains(&"articulated_body"));
    assert!(!Chain5Dense::GENERATED.parts.contains(&"articulated_body"));
    assert_eq!(
        <Chain5 as MechanismModel<5>>::COORDINATES,
        ["link_q1", "link_q2", "link_q3", "link_q4", "link_q5"]
    );
    let mut rng = Lcg(7);
    for _ in 0..20 {
        let q: Vector<5> = rng.vector(3.0);
        let qd: Vector<5> = rng.vector(4.0);
        let a_rec = MechanismModel::acceleration(&rec, 0.0, &q, &qd).unwrap();
        let a_dense = MechanismModel::acceleration(&dense, 0.0, &q, &qd).unwrap();
        let a_exp = MechanismModel::acceleration(&explicit, 0.0, &q, &qd).unwrap();
        let scale = a_exp.norm();
        assert!(
            (a_rec - a_exp).norm() <= 1e-12 * scale,
            "{a_rec} vs {a_exp}"
        );
        assert!((a_dense - a_exp).norm() <= 1e-12 * scale);
        // The frames: the mass matrices of the composed and the written-out chain agree.
        let (mr, me): (Matrix<5, 5>, Matrix<5, 5>) = (
            rec.mass_matrix(0.0, &q).unwrap(),
            explicit.mass_matrix(0.0, &q).unwrap(),
        );
        assert!((mr - me).norm() <= 1e-13 * me.norm());
    }
}

/// A compound pendulum as a one-body tree, forced onto the recursion. By hand, about the
/// pivot: `(I + m d^2) theta'' = -m g d sin(theta)` with `d = l / 2`.
#[derive(Debug, Mechanism)]
#[mechanism(recursive)]
#[gravity(0.0, -g)]
#[body(bar, joint = revolute(theta), com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
pub struct CompoundPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

#[test]
fn one_body_recursion_matches_the_compound_pendulum() {
    let p = CompoundPendulum {
        m: 2.0,
        l: 0.8,
        g: 9.81,
    };
    for theta in [-2.0, -0.3, 0.0, 0.7, 2.9] {
        let qdd =
            MechanismModel::acceleration(&p, 0.0, &Vector::<1>::new(theta), &Vector::<1>::new(1.7))
                .unwrap();
        let d = 0.4;
        let exact = -2.0 * 9.81 * d * f64::sin(theta) / (2.0 * 0.64 / 12.0 + 2.0 * d * d);
        assert_relative_eq!(qdd[0], exact, max_relative = 1e-14, epsilon = 1e-15);
    }
}

with_mass_matrix_twin! {
    /// A branched tree with every joint kind, a driven joint and applied forces:
    /// a cart on a prismatic joint; an arm pinned to it; a slider running along the arm; a
    /// weight welded to the arm's end at 0.3 rad; a wheel pinned to the cart; a flap on the
    /// weight driven by `d(t)`; a spring, a damper, a viscous torque and a generalised force.
    [recursive] Tree, TreeDense, { m1, m2, g },
    #[gravity(0.0, -g)]
    #[body(cart, joint = prismatic(x, [1.0, 0.0]), mass = m1, inertia = 0.3)]
    #[body(arm, parent = cart, joint = revolute(a), at = [0.1, 0.05], com = [0.0, -0.4],
           mass = m2, inertia = 0.05)]
    #[body(slider, parent = arm, joint = prismatic(s, [0.0, -1.0]), at = [0.0, -0.2],
           com = [0.02, 0.0], mass = 0.7, inertia = 0.01)]
    #[body(weight, parent = arm, joint = fixed, at = [0.0, -0.8], angle = 0.3,
           com = [0.05, 0.0], mass = 0.4, inertia = 0.002)]
    #[body(wheel, parent = cart, joint = revolute(w), at = [-0.2, 0.0], com = [0.03, 0.0],
           mass = 0.5, inertia = 0.02)]
    #[body(flap, parent = weight, joint = revolute(d), com = [0.0, -0.1], mass = 0.2,
           inertia = 0.001)]
    #[drive(d = 0.5 * sin(2.0 * t))]
    #[spring(k1, from = [0.0, 0.0], to = slider, k = 50.0, length = 0.3)]
    #[damper(c1, from = [0.0, 1.0], to = wheel, c = 2.0)]
    #[torque(tq, on = arm, value = -0.7 * der(a) + 0.4 * cos(w))]
    #[generalized_force(gf, along = x, value = -3.0 * x)]
}

/// The same tree written out by hand, frame by frame (`R(a) v` expanded):
/// cart origin `(x, 0)`; arm origin `(x + 0.1, 0.05)`, angle `a`; slider origin
/// `arm + R(a) (0, -0.2 - s)`, angle `a`; weight origin `arm + R(a) (0, -0.8)`, angle
/// `a + 0.3`; wheel origin `(x - 0.2, 0)`, angle `w`; flap origin = weight origin, angle
/// `a + 0.3 + d`; each mass centre = origin + R(angle) com.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(x, a, s, w)]
#[drive(d = 0.5 * sin(2.0 * t))]
#[point(wo, at = [x + 0.1 + 0.8 * sin(a), 0.05 - 0.8 * cos(a)])]
#[rigid(cart, mass = m1, inertia = 0.3, at = [x, 0.0], angle = 0.0)]
#[rigid(arm, mass = m2, inertia = 0.05, angle = a,
        at = [x + 0.1 + 0.4 * sin(a), 0.05 - 0.4 * cos(a)])]
#[rigid(slider, mass = 0.7, inertia = 0.01, angle = a,
        at = [x + 0.1 + (0.2 + s) * sin(a) + 0.02 * cos(a), 0.05 - (0.2 + s) * cos(a) + 0.02 * sin(a)])]
#[rigid(weight, mass = 0.4, inertia = 0.002, angle = a + 0.3,
        at = wo + [0.05 * cos(a + 0.3), 0.05 * sin(a + 0.3)])]
#[rigid(wheel, mass = 0.5, inertia = 0.02, angle = w,
        at = [x - 0.2 + 0.03 * cos(w), 0.03 * sin(w)])]
#[rigid(flap, mass = 0.2, inertia = 0.001, angle = a + 0.3 + d,
        at = wo + [0.1 * sin(a + 0.3 + d), -0.1 * cos(a + 0.3 + d)])]
#[spring(k1, from = [0.0, 0.0], to = slider, k = 50.0, length = 0.3)]
#[damper(c1, from = [0.0, 1.0], to = wheel, c = 2.0)]
#[torque(tq, on = arm, value = -0.7 * der(a) + 0.4 * cos(w))]
#[generalized_force(gf, along = x, value = -3.0 * x)]
pub struct TreeExplicit {
    pub m1: f64,
    pub m2: f64,
    pub g: f64,
}

#[test]
fn branched_tree_with_every_joint_kind() {
    let (m1, m2, g) = (2.5, 1.1, 9.81);
    let rec = Tree { m1, m2, g };
    let dense = TreeDense { m1, m2, g };
    let explicit = TreeExplicit { m1, m2, g };
    assert!(Tree::GENERATED.parts.contains(&"articulated_body"));
    // The joints brought their coordinates, in declaration order; `d` is driven.
    assert_eq!(
        <Tree as MechanismModel<4>>::COORDINATES,
        ["x", "a", "s", "w"]
    );
    let mut rng = Lcg(11);
    for _ in 0..20 {
        let t = 2.0 * rng.next();
        let q: Vector<4> = rng.vector(1.5);
        let qd: Vector<4> = rng.vector(3.0);
        let a_rec = MechanismModel::acceleration(&rec, t, &q, &qd).unwrap();
        let a_dense = MechanismModel::acceleration(&dense, t, &q, &qd).unwrap();
        let a_exp = MechanismModel::acceleration(&explicit, t, &q, &qd).unwrap();
        let scale = a_exp.norm();
        assert!(
            (a_rec - a_exp).norm() <= 1e-12 * scale,
            "{a_rec} vs {a_exp}"
        );
        assert!((a_dense - a_exp).norm() <= 1e-12 * scale);
        let e = explicit.energy(t, &q, &qd).unwrap();
        assert_relative_eq!(rec.energy(t, &q, &qd).unwrap(), e, max_relative = 1e-13);
    }
}

/// A conservative chain keeps its energy: Kane's energy function, integrated with the
/// recursion's accelerations.
#[test]
fn recursive_chain_conserves_energy() {
    let chain = Chain5 {
        m: 0.8,
        l: 0.3,
        g: 9.81,
    };
    let mut y0 = Vector::<10>::zeros();
    y0[0] = 1.2;
    y0[2] = -0.5;
    y0[6] = 2.0;
    let opts = Options {
        rtol: 1e-11,
        atol: 1e-11,
        dense: false,
        ..Options::default()
    };
    let sol = Dopri5::new(opts).solve(&chain, 0.0, y0, 3.0, &[]).unwrap();
    let energy = |y: &Vector<10>| {
        let (q, qd) = (
            y.fixed_rows::<5>(0).into_owned(),
            y.fixed_rows::<5>(5).into_owned(),
        );
        chain.energy(0.0, &q, &qd).unwrap()
    };
    let (e0, e1) = (energy(&y0), energy(sol.y.last().unwrap()));
    // The potential's scale, m g l n^2 / 2, sets the relative measure (e0 may be near 0).
    let scale = 0.8 * 9.81 * 0.3 * 12.5;
    assert!((e1 - e0).abs() <= 1e-9 * scale, "energy {e0} -> {e1}");
}

/// A four-bar as a tree (crank, coupler on the crank, rocker on the ground) closed by a
/// revolute joint between the coupler's end and the rocker's end.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(crank, joint = revolute(a), com = [l1 / 2.0, 0.0], mass = 1.0, inertia = l1 * l1 / 12.0)]
#[body(coupler, parent = crank, joint = revolute(b), at = [l1, 0.0], com = [l2 / 2.0, 0.0],
       mass = 2.0, inertia = 2.0 * l2 * l2 / 12.0)]
#[body(rocker, joint = revolute(c), at = [d, 0.0], com = [l3 / 2.0, 0.0], mass = 1.5,
       inertia = 1.5 * l3 * l3 / 12.0)]
#[close(pin, a = coupler, at_a = [l2, 0.0], b = rocker, at_b = [l3, 0.0])]
pub struct FourBar {
    pub l1: f64,
    pub l2: f64,
    pub l3: f64,
    pub d: f64,
    pub g: f64,
}

/// The same four-bar written out: crank angle `a`, the coupler's absolute angle `a + b`,
/// the rocker's `c`; the loop `l1 e(a) + l2 e(a + b) = d x + l3 e(c)`, `e(u) = (cos u, sin u)`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(a, b, c)]
#[rigid(crank, mass = 1.0, inertia = l1 * l1 / 12.0, angle = a,
        at = [l1 / 2.0 * cos(a), l1 / 2.0 * sin(a)])]
#[rigid(coupler, mass = 2.0, inertia = 2.0 * l2 * l2 / 12.0, angle = a + b,
        at = [l1 * cos(a) + l2 / 2.0 * cos(a + b), l1 * sin(a) + l2 / 2.0 * sin(a + b)])]
#[rigid(rocker, mass = 1.5, inertia = 1.5 * l3 * l3 / 12.0, angle = c,
        at = [d + l3 / 2.0 * cos(c), l3 / 2.0 * sin(c)])]
#[constraint(l1 * cos(a) + l2 * cos(a + b) == d + l3 * cos(c))]
#[constraint(l1 * sin(a) + l2 * sin(a + b) == l3 * sin(c))]
pub struct FourBarExplicit {
    pub l1: f64,
    pub l2: f64,
    pub l3: f64,
    pub d: f64,
    pub g: f64,
}

#[test]
fn closing_joint_gives_the_loop_constraints() {
    let (l1, l2, l3, d, g) = (0.3, 0.9, 0.7, 0.8, 9.81);
    let tree = FourBar { l1, l2, l3, d, g };
    let explicit = FourBarExplicit { l1, l2, l3, d, g };
    assert!(FourBar::GENERATED.parts.contains(&"phi"));
    assert!(!FourBar::GENERATED.parts.contains(&"articulated_body"));
    let mut rng = Lcg(5);
    for _ in 0..20 {
        let q: Vector<3> = rng.vector(3.0);
        let qd: Vector<3> = rng.vector(2.0);
        assert!((tree.phi(0.0, &q) - explicit.phi(0.0, &q)).norm() <= 1e-14);
        let (a1, l1m) = tree.acceleration_and_multipliers(0.0, &q, &qd).unwrap();
        let (a2, l2m) = explicit.acceleration_and_multipliers(0.0, &q, &qd).unwrap();
        assert!(
            (a1 - a2).norm() <= 1e-11 * a2.norm().max(1.0),
            "{a1} vs {a2}"
        );
        assert!((l1m - l2m).norm() <= 1e-11 * l2m.norm().max(1.0));
    }
}

/// The pivot force of a compound pendulum, asked for with `reaction`: by Newton on the
/// bar, `R = m a_G - m g_vec`, with `a_G = d alpha t - d w^2 r`, `r = (sin u, -cos u)`,
/// `t = (cos u, sin u)`, `alpha = -m g d sin(u) / (I + m d^2)`.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(bar, joint = revolute(u), com = [0.0, -d], mass = m, inertia = i, reaction)]
#[output(rx = reaction(bar_rx), ry = reaction(bar_ry))]
pub struct PivotForce {
    pub m: f64,
    pub d: f64,
    pub i: f64,
    pub g: f64,
}

#[test]
fn tree_joint_reaction_is_the_pivot_force() {
    let (m, d, i, g) = (2.0, 0.4, 0.1, 9.81);
    let p = PivotForce { m, d, i, g };
    // One free coordinate; the relaxed joint adds none to the state.
    assert_eq!(<PivotForce as MechanismModel<1>>::COORDINATES, ["u"]);
    for (u, w) in [(0.0, 0.0), (0.6, 1.3), (-2.2, -0.4)] {
        let out = p.outputs(0.0, &Vector::<2>::new(u, w)).unwrap();
        let alpha = -m * g * d * f64::sin(u) / (i + m * d * d);
        let (r, t) = ((u.sin(), -u.cos()), (u.cos(), u.sin()));
        let a_g = (
            d * alpha * t.0 - d * w * w * r.0,
            d * alpha * t.1 - d * w * w * r.1,
        );
        assert_relative_eq!(out.rx, m * a_g.0, max_relative = 1e-12, epsilon = 1e-12);
        assert_relative_eq!(
            out.ry,
            m * a_g.1 + m * g,
            max_relative = 1e-12,
            epsilon = 1e-12
        );
    }
}

/// A double pendulum asking for its middle joint's force: the recursion (which never sees
/// the freed joint) and the mass-matrix form agree on the motion, and the reaction is the
/// lower bar's `m a_G - m g_vec`, from the accelerations of its own mass centre.
#[derive(Debug, Mechanism)]
#[mechanism(recursive)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(a), com = [0.0, -0.25], mass = 1.0, inertia = 0.02)]
#[body(lower, parent = upper, joint = revolute(b), at = [0.0, -0.5], com = [0.0, -0.3],
       mass = 0.8, inertia = 0.015, reaction)]
#[output(rx = reaction(lower_rx), ry = reaction(lower_ry), ax = acceleration(lower)[0],
         ay = acceleration(lower)[1])]
pub struct MiddleJoint {
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[mechanism(mass_matrix)]
#[gravity(0.0, -g)]
#[body(upper, joint = revolute(a), com = [0.0, -0.25], mass = 1.0, inertia = 0.02)]
#[body(lower, parent = upper, joint = revolute(b), at = [0.0, -0.5], com = [0.0, -0.3],
       mass = 0.8, inertia = 0.015)]
pub struct MiddleJointDense {
    pub g: f64,
}

#[test]
fn reaction_in_a_recursive_tree() {
    let (rec, dense) = (MiddleJoint { g: 9.81 }, MiddleJointDense { g: 9.81 });
    assert!(MiddleJoint::GENERATED.parts.contains(&"articulated_body"));
    let mut rng = Lcg(3);
    for _ in 0..10 {
        let y: Vector<4> = rng.vector(2.0);
        let (q, qd) = (
            y.fixed_rows::<2>(0).into_owned(),
            y.fixed_rows::<2>(2).into_owned(),
        );
        let a1 = MechanismModel::acceleration(&rec, 0.0, &q, &qd).unwrap();
        let a2 = MechanismModel::acceleration(&dense, 0.0, &q, &qd).unwrap();
        assert!((a1 - a2).norm() <= 1e-12 * a2.norm());
        let o = rec.outputs(0.0, &y).unwrap();
        assert_relative_eq!(o.rx, 0.8 * o.ax, max_relative = 1e-11, epsilon = 1e-11);
        assert_relative_eq!(
            o.ry,
            0.8 * o.ay + 0.8 * 9.81,
            max_relative = 1e-11,
            epsilon = 1e-11
        );
    }
}

with_mass_matrix_twin! {
    /// A spring-loaded cart with a driven arm carrying a 14-link chain: the chain's last 13
    /// links are one run of identical links, generated once as loops (`rolled_chain`), the
    /// cart, arm and first link unrolled around them. Checked against its mass-matrix twin.
    RolledTree, RolledTreeDense, { m, l, g },
    #[gravity(0.0, -g)]
    #[body(cart, joint = prismatic(x, [1.0, 0.0]), mass = 2.0, inertia = 0.3)]
    #[body(arm, parent = cart, joint = revolute(d), at = [0.2, 0.0], com = [0.0, -0.1],
           mass = 0.5, inertia = 0.01)]
    #[drive(d = 0.3 * sin(2.0 * t))]
    #[chain(link, n = 14, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0,
            parent = arm, at = [0.0, -0.2])]
    #[spring(k1, from = [0.0, 0.0], to = cart, k = 40.0, length = 0.1)]
    #[torque(tq, on = link_1, value = -0.5 * der(link_q1))]
}

#[test]
fn rolled_chain_inside_a_tree_equals_the_mass_matrix_form() {
    let (m, l, g) = (0.3, 0.15, 9.81);
    let rolled = RolledTree { m, l, g };
    let dense = RolledTreeDense { m, l, g };
    assert!(RolledTree::GENERATED.parts.contains(&"rolled_chain"));
    assert!(!RolledTreeDense::GENERATED.parts.contains(&"rolled_chain"));
    let mut rng = Lcg(23);
    for _ in 0..20 {
        let t = 2.0 * rng.next();
        let q: Vector<15> = rng.vector(1.2);
        let qd: Vector<15> = rng.vector(2.0);
        let a_rolled = MechanismModel::acceleration(&rolled, t, &q, &qd).unwrap();
        // The reference through M qdd = f: its residual, not a forward difference (M's
        // condition number would enter); 1e-13 is about n^2 eps for n = 15.
        let mass: Matrix<15, 15> = dense.mass_matrix(t, &q).unwrap();
        let f = dense.forces(t, &q, &qd).unwrap();
        let residual = (mass * a_rolled - f).amax();
        let size = mass.norm() * a_rolled.norm() + f.norm();
        assert!(
            residual <= 1e-13 * size,
            "|M qdd - f| = {residual:e}, scale {size:e}"
        );
        let a_dense = MechanismModel::acceleration(&dense, t, &q, &qd).unwrap();
        // Forward: the mass-matrix solve's own error is about cond(M) eps, cond(M) up to
        // 9e4 at these states (2e-11); measured differences are below 1e-12.
        assert!((a_rolled - a_dense).amax() <= 1e-10 * a_dense.amax());
    }
}
