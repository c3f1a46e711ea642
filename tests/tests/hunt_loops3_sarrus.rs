//! Hunt: a Sarrus linkage, a spatial over-constrained (redundant) loop with one degree of
//! freedom, written as a new user writes it: a joint tree of two legs and a top plate,
//! closed by a revolute `close`. Leg A: `a1` about the ground's `x` axis at the origin
//! (`q1`), `a2` about `x` at `a1`'s tip (`q2`), the top plate about `x` at `a2`'s tip (`q3`);
//! leg B: `b1` about `y` at `(bx, by, 0)` (`p1`), `b2` about `y` at its tip (`p2`); `b2`'s
//! tip is hinged (about `y`) to the plate's point `(bx, by, 0)`. Links of length `l` along
//! their `z`. Grübler counts `6 * 5 - 5 * 6 = 0`, yet the plate moves up and down: one of
//! the closing joint's five rows is dependent (its axis row `u_a . x_top = 0` holds
//! identically, both being normal whatever the motion). Gravity along `-z`, a spring
//! `k (z - h0)^2 / 2` on the plate's height.
//!
//! Reference, by hand: leg A's tip is `(0, -l sin q1, l cos q1)`, `a2` turns to `q1 + q2`;
//! with `th = q1 = p1`, `q2 = p2 = -2 th`, `q3 = th` the plate stays level at height
//! `z = 2 l cos th` over the origin. Every link turns about a fixed axis at `+-th'`, so with
//! isotropic inertias `j`: `T = J(th) th'^2 / 2`,
//! `J = 2 [m l^2 / 4 + m (l^2 cos^2 th / 4 + 9 l^2 sin^2 th / 4) + 2 j] + 4 mt l^2 sin^2 th`
//! (`a2`'s mass centre is at `(0, -l sin th / 2, 3 l cos th / 2)`),
//! `V = g cos th (4 m l + 2 mt l) + k (2 l cos th - h0)^2 / 2`; Lagrange:
//! `J th'' + J' th'^2 / 2 + V' = 0`, `J' = 8 l^2 sin th cos th (m + mt)`.
//!
//! Defect found: the derive refused the model at compile time ("1 of this joint's 5
//! equations are identically zero: ... (a mechanism moving in a plane, written in space);
//! write it planar, or close it by a joint of fewer equations"), though the Sarrus linkage
//! is spatial and its closing joint is a hinge. An identically zero row constrains nothing;
//! it is now dropped (a `close` all of whose rows vanish is still an error).

use mbd::integrate::{Dop853, Dopri5, Integrator, Options, Radau5, Rk4};
use mbd::prelude::*;

#[derive(Debug, Clone, Mechanism)]
#[gravity(0.0, 0.0, -g)]
#[body(a1, joint = revolute(q1, x), com = [0.0, 0.0, l / 2.0], mass = m,
       inertia = diag(j, j, j))]
#[body(a2, parent = a1, joint = revolute(q2, x), at = [0.0, 0.0, l],
       com = [0.0, 0.0, l / 2.0], mass = m, inertia = diag(j, j, j))]
#[body(top, parent = a2, joint = revolute(q3, x), at = [0.0, 0.0, l],
       com = [bx / 2.0, by / 2.0, 0.0], mass = mt, inertia = diag(jt, jt, jt))]
#[body(b1, joint = revolute(p1, y), at = [bx, by, 0.0], com = [0.0, 0.0, l / 2.0], mass = m,
       inertia = diag(j, j, j))]
#[body(b2, parent = b1, joint = revolute(p2, y), at = [0.0, 0.0, l],
       com = [0.0, 0.0, l / 2.0], mass = m, inertia = diag(j, j, j))]
#[close(hinge, joint = revolute, a = b2, at_a = [0.0, 0.0, l], b = top, at_b = [bx, by, 0.0],
        axis_a = [0.0, 1.0, 0.0], axis_b = [0.0, 1.0, 0.0])]
#[potential(k / 2.0 * (position(top)[2] - h0) * (position(top)[2] - h0))]
#[output(height = position(top)[2], plate_x = position(top)[0], plate_y = position(top)[1])]
pub struct Sarrus {
    pub l: f64,
    pub m: f64,
    pub j: f64,
    pub mt: f64,
    pub jt: f64,
    pub g: f64,
    pub k: f64,
    pub h0: f64,
    pub bx: f64,
    pub by: f64,
}

const L: f64 = 0.5;
const MM: f64 = 0.8;
const JJ: f64 = 0.01;
const MT: f64 = 3.0;
const G: f64 = 9.81;
const KS: f64 = 400.0;
const H0: f64 = 0.6;

fn model() -> Sarrus {
    Sarrus {
        l: L,
        m: MM,
        j: JJ,
        mt: MT,
        jt: 0.05,
        g: G,
        k: KS,
        h0: H0,
        bx: 0.4,
        by: 0.3,
    }
}

fn inertia(th: f64) -> f64 {
    let (s, c) = th.sin_cos();
    2.0 * (MM * L * L / 4.0 + MM * (L * L * c * c / 4.0 + 9.0 * L * L * s * s / 4.0) + 2.0 * JJ)
        + 4.0 * MT * L * L * s * s
}

fn potential(th: f64) -> f64 {
    let h = 2.0 * L * th.cos();
    G * th.cos() * (4.0 * MM * L + 2.0 * MT * L) + KS * (h - H0).powi(2) / 2.0
}

fn hand_acceleration(th: f64, thd: f64) -> f64 {
    let (s, c) = th.sin_cos();
    let dj = 8.0 * L * L * s * c * (MM + MT);
    let dv = -G * s * (4.0 * MM * L + 2.0 * MT * L) + KS * (2.0 * L * c - H0) * (-2.0 * L * s);
    -(dj / 2.0 * thd * thd + dv) / inertia(th)
}

/// The state at crank angle `th` and rate `thd`, in `COORDINATES` order.
fn state(th: f64, thd: f64) -> Vector<10> {
    let value = |name: &str| match name {
        "q1" | "q3" | "p1" => (th, thd),
        "q2" | "p2" => (-2.0 * th, -2.0 * thd),
        other => panic!("{other}"),
    };
    let mut y = Vector::<10>::zeros();
    for (i, name) in Sarrus::COORDINATES.iter().enumerate() {
        (y[i], y[5 + i]) = value(name);
    }
    y
}

fn index(name: &str) -> usize {
    Sarrus::COORDINATES.iter().position(|c| *c == name).unwrap()
}

#[test]
fn the_hinge_keeps_four_rows_and_the_hand_configuration_closes_them() {
    assert_eq!(Sarrus::GENERATED.constraints, 4);
    assert!(Sarrus::GENERATED.parts.contains(&"augmented"));
    let p = model();
    for th in [0.3, 0.7, 1.1] {
        let y = state(th, 0.0);
        let q = y.fixed_rows::<5>(0).into_owned();
        assert!(p.phi(0.0, &q).amax() < 1e-15, "{th}");
        let o = p.outputs(0.0, &y).unwrap();
        assert!((o.height - 2.0 * L * th.cos()).abs() < 1e-15);
        assert!((o.plate_x - 0.2).abs() < 1e-15 && (o.plate_y - 0.15).abs() < 1e-15);
        // one degree of freedom: Phi_q has full row rank 4
        let jac = p.phi_q(0.0, &q);
        let sv = jac.svd(false, false).singular_values;
        assert!(sv.min() > 1e-3 * sv.max(), "{sv}");
    }
}

#[test]
fn accelerations_are_the_one_coordinate_reduction() {
    let p = model();
    for th in [0.3, 0.7, 1.1] {
        for thd in [0.0, 2.0, -3.0] {
            let a = p.rhs(0.0, &state(th, thd)).unwrap();
            let want = hand_acceleration(th, thd);
            let got = a[5 + index("q1")];
            assert!(
                (got - want).abs() < 1e-11 * (1.0 + want.abs()),
                "{th} {thd}: {got} vs {want}"
            );
            assert!((a[5 + index("p1")] - want).abs() < 1e-11 * (1.0 + want.abs()));
            assert!((a[5 + index("q2")] + 2.0 * want).abs() < 1e-11 * (1.0 + want.abs()));
        }
    }
}

/// The plate bounces on its spring between two heights well inside the legs' range; the
/// legs keep `p1 = q1` (no switch to the mirror `p1 = -q1`), the plate level and over the
/// same point, and the energy by hand is conserved on every method.
#[test]
fn the_plate_bounces_on_its_spring_on_every_method() {
    let p = model();
    let y0 = state(0.7, 0.0);
    let e0 = potential(0.7);
    let tight = |tol: f64| Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    let runs: Vec<(&str, mbd::Result<Solution<10>>, f64)> = vec![
        (
            "dopri5",
            Dopri5::new(tight(1e-10)).solve(&p, 0.0, y0, 3.0, &[]),
            1e-8,
        ),
        (
            "dop853",
            Dop853::new(tight(1e-10)).solve(&p, 0.0, y0, 3.0, &[]),
            1e-8,
        ),
        (
            "radau5",
            Radau5::new(tight(1e-8)).solve(&p, 0.0, y0, 3.0, &[]),
            1e-5,
        ),
        ("rk4", Rk4::new(1e-3).solve(&p, 0.0, y0, 3.0, &[]), 1e-6),
    ];
    let (iq1, iq2, iq3, ip1, ip2) = (
        index("q1"),
        index("q2"),
        index("q3"),
        index("p1"),
        index("p2"),
    );
    for (name, run, tol) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let (mut lo, mut hi) = (f64::MAX, f64::MIN);
        let mut worst = (0.0f64, 0.0f64);
        for y in &sol.y {
            let (th, thd) = (y[iq1], y[5 + iq1]);
            lo = lo.min(th);
            hi = hi.max(th);
            let e = inertia(th) * thd * thd / 2.0 + potential(th);
            worst.0 = worst.0.max((e - e0).abs() / e0);
            let legs = (y[ip1] - th)
                .abs()
                .max((y[iq2] + 2.0 * th).abs())
                .max((y[ip2] + 2.0 * th).abs())
                .max((y[iq1] + y[iq2] + y[iq3]).abs());
            worst.1 = worst.1.max(legs);
        }
        println!(
            "{name}: th in [{lo:.3}, {hi:.3}], energy {:.2e}, legs {:.2e}",
            worst.0, worst.1
        );
        assert!(
            lo > 0.6 && hi < 1.4 && hi - lo > 0.2,
            "{name}: [{lo}, {hi}]"
        );
        assert!(
            worst.0 < tol && worst.1 < tol.max(1e-9),
            "{name}: {worst:?}"
        );
    }
}

/// The planar four-bar of `tests/ui/close/planar_loop_in_space.rs` (refused before): written
/// in space about `z` and closed by a revolute `close` about `z`, three of its five rows
/// vanish; the two left are the planar pin's, and its accelerations are those of the same
/// four-bar written planar (both kept augmented, to compare every coordinate).
#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial, augmented)]
#[gravity(0.0, -9.81, 0.0)]
#[body(crank, joint = revolute(a, z), com = [0.5, 0.0, 0.0], mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
#[body(coupler, parent = crank, joint = revolute(b, z), at = [1.0, 0.0, 0.0], com = [1.0, 0.0, 0.0],
       mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
#[body(rocker, joint = revolute(c, z), at = [2.0, 0.0, 0.0], com = [0.0, 0.5, 0.0], mass = 1.0,
       inertia = diag(0.1, 0.01, 0.1))]
#[close(pin, joint = revolute, a = coupler, at_a = [2.0, 0.0, 0.0], axis_a = [0.0, 0.0, 1.0],
        b = rocker, at_b = [0.0, 1.0, 0.0], axis_b = [0.0, 0.0, 1.0])]
pub struct FourBarInSpace {}

#[derive(Debug, Clone, Mechanism)]
#[mechanism(augmented)]
#[gravity(0.0, -9.81)]
#[body(crank, joint = revolute(a), com = [0.5, 0.0], mass = 1.0, inertia = 0.1)]
#[body(coupler, parent = crank, joint = revolute(b), at = [1.0, 0.0], com = [1.0, 0.0],
       mass = 1.0, inertia = 0.1)]
#[body(rocker, joint = revolute(c), at = [2.0, 0.0], com = [0.0, 0.5], mass = 1.0, inertia = 0.1)]
#[close(pin, a = coupler, at_a = [2.0, 0.0], b = rocker, at_b = [0.0, 1.0])]
pub struct FourBarPlanar {}

#[test]
fn a_planar_loop_written_in_space_keeps_the_planar_pins_rows() {
    assert_eq!(FourBarInSpace::GENERATED.constraints, 2);
    let (s, p) = (FourBarInSpace {}, FourBarPlanar {});
    // an assembled configuration: crank at 1.2, the rest by Newton on the planar model
    let q = mbd::analysis::assemble(
        &p,
        0.0,
        &Vector::<3>::new(1.2, -1.0, 1.0),
        &[true, false, false],
        &Default::default(),
    )
    .unwrap();
    let qd = mbd::analysis::consistent_velocities(
        &p,
        0.0,
        &q,
        &Vector::<3>::new(2.0, 0.0, 0.0),
        &[true, false, false],
    )
    .unwrap();
    assert!(s.phi(0.0, &q).amax() < 1e-12);
    let y = Vector::<6>::from_fn(|i, _| if i < 3 { q[i] } else { qd[i - 3] });
    let (a, b) = (s.rhs(0.0, &y).unwrap(), p.rhs(0.0, &y).unwrap());
    assert!((a - b).amax() < 1e-12 * (1.0 + b.amax()), "{a} vs {b}");
}

#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial)]
#[gravity(0.0, -9.81, 0.0)]
#[body(crank, joint = revolute(a, z), com = [0.5, 0.0, 0.0], mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
#[body(coupler, parent = crank, joint = revolute(b, z), at = [1.0, 0.0, 0.0], com = [1.0, 0.0, 0.0],
       mass = 1.0, inertia = diag(0.01, 0.1, 0.1))]
#[body(rocker, joint = revolute(c, z), at = [2.0, 0.0, 0.0], com = [0.0, 0.5, 0.0], mass = 1.0,
       inertia = diag(0.1, 0.01, 0.1))]
#[close(pin, joint = revolute, a = coupler, at_a = [2.0, 0.0, 0.0], axis_a = [0.0, 0.0, 1.0],
        b = rocker, at_b = [0.0, 1.0, 0.0], axis_b = [0.0, 0.0, 1.0])]
#[init(a = 1.2, b = -1.1999999999999997, c = -0.3707963267948968)]
pub struct FourBarInSpaceDefault {}

/// The same four-bar in space in the derive's default form, its branch picked by `init`:
/// with the three vanishing rows dropped, the derive reduces it to the crank angle, and the
/// crank's acceleration is the planar model's on that branch. The bars (1, 2, 1, ground 2)
/// make a parallelogram, whose branches cross at the flat positions (`a = 0, pi`): the
/// chart of the init's elbow is the parallelogram for `0 < a < pi` (see
/// `hunt_loops2_parallelogram.rs`), swept here.
#[test]
fn the_planar_loop_in_space_in_its_default_form_is_the_planar_model() {
    assert_eq!(FourBarInSpaceDefault::COORDINATES, ["a"]);
    assert!(
        FourBarInSpaceDefault::GENERATED
            .parts
            .contains(&"minimal_closed_form")
    );
    let p = FourBarPlanar {};
    let s = FourBarInSpaceDefault {};
    let mut guess = Vector::<3>::new(0.1, -0.1, 0.1 - std::f64::consts::FRAC_PI_2);
    for k in 0..=40 {
        let (th, w) = (0.1 + k as f64 * 2.9 / 40.0, 2.0);
        guess[0] = th;
        let q =
            mbd::analysis::assemble(&p, 0.0, &guess, &[true, false, false], &Default::default())
                .unwrap();
        guess = q;
        let qd = mbd::analysis::consistent_velocities(
            &p,
            0.0,
            &q,
            &Vector::<3>::new(w, 0.0, 0.0),
            &[true, false, false],
        )
        .unwrap();
        let y = Vector::<6>::from_fn(|i, _| if i < 3 { q[i] } else { qd[i - 3] });
        let want = p.rhs(0.0, &y).unwrap()[3];
        let got = s.rhs(0.0, &Vector::<2>::new(th, w)).unwrap()[1];
        assert!(
            (got - want).abs() < 1e-10 * (1.0 + want.abs()),
            "{th}: {got} vs {want}"
        );
        // on the parallelogram the coupler translates: `a + b = 0`
        assert!((q[0] + q[1]).abs() < 1e-12, "{q}");
    }
}

/// The index-3 methods on the Sarrus linkage (its four rows kept): ALI3-P and
/// generalized-α's constrained form follow DOPRI5 at `1e-11` (the plate's height), and the
/// legs stay symmetric.
#[test]
fn index_three_methods_follow_the_reference() {
    let p = model();
    let y0 = state(0.7, 0.0);
    let t1 = 2.0;
    let reference = Dopri5::new(Options {
        rtol: 1e-11,
        atol: 1e-11,
        ..Options::default()
    })
    .solve(&p, 0.0, y0, t1, &[])
    .unwrap();
    let (q0, qd0) = (
        y0.fixed_rows::<5>(0).into_owned(),
        y0.fixed_rows::<5>(5).into_owned(),
    );
    let (iq1, ip1) = (index("q1"), index("p1"));
    let runs =
        [
            (
                "ali3",
                mbd::integrate::Ali3::new(1e-3).solve::<_, 5, 4, 10>(&p, 0.0, q0, qd0, t1, &[]),
            ),
            (
                "alpha",
                mbd::integrate::GeneralizedAlpha::new(0.9, 1e-3)
                    .solve_constrained::<_, 5, 4, 9, 10>(&p, 0.0, q0, qd0, t1, &[]),
            ),
        ];
    for (name, run) in runs {
        let sol = run.unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut worst = 0.0f64;
        for (&t, y) in sol.t.iter().zip(&sol.y) {
            let want = reference.at(t).unwrap()[iq1];
            worst = worst.max((y[iq1] - want).abs());
            assert!(
                (y[ip1] - y[iq1]).abs() < 1e-8,
                "{name} t = {t}: legs {} {}",
                y[ip1],
                y[iq1]
            );
        }
        println!("{name}: worst {worst:.2e}");
        assert!(worst < 2e-4, "{name}: {worst:.2e}");
    }
}
