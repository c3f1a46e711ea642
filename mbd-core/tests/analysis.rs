//! The analyses (assembly, kinematics, inverse dynamics, statics, projection) on
//! hand-written models, each against a closed form derived next to the test.

mod models;

use mbd_core::analysis::{
    NewtonOptions, assemble, consistent_velocities, constraint_drift, inverse_dynamics,
    kinematic_sweep, kinematics, project_positions, project_state, project_velocities,
    static_equilibrium, static_equilibrium_constrained,
};
use mbd_core::integrate::Dopri5;
use mbd_core::solve::second_order_rhs;
use mbd_core::{Error, Integrator, Mechanism, OdeSystem, Options, Result, Vector};
use models::{Drive, FourBar, HangingMass, RelaxedPendulum, SliderCrank, TwoBar};

fn opts() -> NewtonOptions {
    NewtonOptions::default()
}

/// The four-bar's closed configuration for a given crank angle, by intersecting the circle
/// of radius `r2` about `A = r1 (cos th1, sin th1)` with the circle of radius `r3` about
/// `D = (g, 0)` (the "upper" intersection, `B` to the left of `A -> D`):
/// with `d = |D - A|`, `a = (r2^2 - r3^2 + d^2) / (2 d)`, `h = sqrt(r2^2 - a^2)`,
/// `B = A + a u + h u_perp`, `u = (D - A)/d`, `u_perp = (-u_y, u_x)`.
fn four_bar_closed(fb: &FourBar, th1: f64) -> Vector<3> {
    let (ax, ay) = (fb.r1 * th1.cos(), fb.r1 * th1.sin());
    let (dx, dy) = (fb.ground - ax, -ay);
    let d = dx.hypot(dy);
    let (ux, uy) = (dx / d, dy / d);
    let a = (fb.r2 * fb.r2 - fb.r3 * fb.r3 + d * d) / (2.0 * d);
    let h = (fb.r2 * fb.r2 - a * a).sqrt();
    let (bx, by) = (ax + a * ux - h * uy, ay + a * uy + h * ux);
    Vector::<3>::new(th1, (by - ay).atan2(bx - ax), by.atan2(bx - fb.ground))
}

// ---------------------------------------------------------------------------------------
// Assembly

#[test]
fn assembly_from_a_perturbed_configuration_matches_the_circle_intersection() {
    let fb = FourBar::crank_rocker();
    for th1 in [0.3, 1.7, -2.5] {
        let truth = four_bar_closed(&fb, th1);
        let guess = truth + Vector::<3>::new(0.0, 0.2, -0.15);
        let q = assemble(&fb, 0.0, &guess, &[true, false, false], &opts()).unwrap();
        assert_eq!(q[0], th1, "the held crank angle must not move");
        assert!((q - truth).amax() < 1e-12, "th1 = {th1}: {q} vs {truth}");
    }
}

/// With no coordinate held there are 3 unknowns for 2 equations: the minimum-norm
/// Gauss–Newton update still closes the loop (checked on the loop-closure equations
/// written out here again) and moves the crank only a little.
#[test]
fn underdetermined_assembly_closes_the_loop() {
    let fb = FourBar::crank_rocker();
    let guess = four_bar_closed(&fb, 0.8) + Vector::<3>::new(0.05, 0.1, -0.1);
    let q = assemble(&fb, 0.0, &guess, &[false; 3], &opts()).unwrap();
    let bx = fb.r1 * q[0].cos() + fb.r2 * q[1].cos();
    let by = fb.r1 * q[0].sin() + fb.r2 * q[1].sin();
    let gap = (bx - fb.ground - fb.r3 * q[2].cos()).hypot(by - fb.r3 * q[2].sin());
    assert!(gap < 1e-12, "loop gap {gap}");
    assert!((q - guess).amax() < 0.2);
}

/// Links 1 + 3 + 2.5 cannot span a ground of 10: no configuration closes. The residual
/// reported can be no smaller than the gap `|D - A| - r2 - r3` (Euclidean) over sqrt 2
/// (max-norm of a 2-vector).
#[test]
fn a_four_bar_that_cannot_close_fails_to_assemble() {
    let fb = FourBar {
        ground: 10.0,
        ..FourBar::crank_rocker()
    };
    let th1: f64 = 0.3;
    let gap = (fb.ground - fb.r1 * th1.cos()).hypot(fb.r1 * th1.sin()) - fb.r2 - fb.r3;
    let guess = Vector::<3>::new(th1, 0.2, 2.0);
    match assemble(&fb, 0.0, &guess, &[true, false, false], &opts()) {
        Err(Error::AssemblyFailed {
            residual,
            iterations,
            ..
        }) => {
            eprintln!(
                "cannot close: residual {residual:.3e} after {iterations} iterations, gap {gap:.3e}"
            );
            assert!(residual.is_finite() && residual >= gap / 2f64.sqrt() * (1.0 - 1e-12));
        }
        other => panic!("expected AssemblyFailed, got {other:?}"),
    }
}

/// `SingularConstraintJacobian` at `t = 0`; its detail, which names the configuration.
fn singular_at_zero<T: std::fmt::Debug>(r: mbd_core::Result<T>) -> String {
    match r {
        Err(Error::SingularConstraintJacobian { t: 0.0, detail }) => {
            assert!(detail.starts_with("at q = ["), "{detail}");
            detail
        }
        other => panic!("expected SingularConstraintJacobian at t = 0, got {other:?}"),
    }
}

/// Crank and coupler collinear (`th1 = th2 = psi`) with the rocker held: the coupler
/// point `B = (r1 + r2)(cos psi, sin psi)` lies on the rocker circle when
/// `cos psi = ((r1 + r2)^2 + g^2 - r3^2) / (2 (r1 + r2) g)` (law of cosines). There the
/// columns of `Phi_q` for `th1` and `th2` are parallel: the toggle position.
#[test]
fn a_toggle_position_is_a_singular_constraint_jacobian() {
    let fb = FourBar::crank_rocker();
    let s = fb.r1 + fb.r2;
    let psi = ((s * s + fb.ground * fb.ground - fb.r3 * fb.r3) / (2.0 * s * fb.ground)).acos();
    let th3 = (s * psi.sin()).atan2(s * psi.cos() - fb.ground);
    let q = Vector::<3>::new(psi, psi, th3);
    let held = [false, false, true];
    singular_at_zero(assemble(&fb, 0.0, &q, &held, &opts()));
    let qd = Vector::<3>::new(0.0, 0.0, 1.0);
    singular_at_zero(consistent_velocities(&fb, 0.0, &q, &qd, &held));
}

#[test]
fn non_finite_input_is_an_error_not_a_nan() {
    let fb = FourBar::crank_rocker();
    let q = Vector::<3>::new(0.3, f64::NAN, 1.0);
    assert_eq!(
        assemble(&fb, 0.0, &q, &[true, false, false], &opts()),
        Err(Error::NonFinite { t: 0.0 })
    );
}

/// Velocity loop `r1 w1 e1' + r2 w2 e2' = r3 w3 e3'` (`e' = (-sin, cos)`); dotting with
/// `e3` and `e2` (`e_i' . e_j = sin(th_j - th_i)`) gives
/// `w2 = -r1 w1 sin(th3 - th1) / (r2 sin(th3 - th2))`,
/// `w3 = r1 w1 sin(th2 - th1) / (r3 sin(th2 - th3))`.
#[test]
fn consistent_velocities_match_the_velocity_loop() {
    let fb = FourBar::crank_rocker();
    let q = four_bar_closed(&fb, 0.9);
    let w1 = 1.5;
    let qd = consistent_velocities(
        &fb,
        0.0,
        &q,
        &Vector::<3>::new(w1, 7.0, -3.0),
        &[true, false, false],
    )
    .unwrap();
    let w2 = -fb.r1 * w1 * (q[2] - q[0]).sin() / (fb.r2 * (q[2] - q[1]).sin());
    let w3 = fb.r1 * w1 * (q[1] - q[0]).sin() / (fb.r3 * (q[1] - q[2]).sin());
    assert_eq!(qd[0], w1);
    assert!(
        (qd[1] - w2).abs() < 1e-13 && (qd[2] - w3).abs() < 1e-13,
        "{qd}"
    );
}

// ---------------------------------------------------------------------------------------
// Kinematics of a slider-crank driven at constant speed

fn slider_crank(drive: Drive) -> SliderCrank {
    SliderCrank {
        r: 1.0,
        l: 3.0,
        mc: 1.0,
        mr: 2.0,
        mp: 1.5,
        k: 50.0,
        x_free: 3.2,
        grav: 9.81,
        drive,
    }
}

const TH0: f64 = 0.3;
const W: f64 = 2.0;

/// Closed-form slider-crank kinematics at crank angle `th` and constant speed `w`
/// (Meriam & Kraige, *Engineering Mechanics: Dynamics*, Sect. 5/4; written out here):
/// `S = sqrt(l^2 - r^2 sin^2 th)`, `x = r cos th + S`;
/// `S' = -a / S` with `a = r^2 sin th cos th`, `S'' = -r^2 cos 2th / S - a^2 / S^3`;
/// `xd = w (-r sin th + S')`, `xdd = w^2 (-r cos th + S'')`.
/// Rod angle `ph` (from `A` to `B`): `l sin ph = -r sin th`, `l cos ph = S`, so
/// `phd = -r w cos th / S` and `phdd = (r w^2 sin th - r sin th phd^2) / S`
/// (differentiating `l cos ph phd = -r w cos th`).
struct SliderCrankTruth {
    x: [f64; 3],
    ph: [f64; 3],
}

fn slider_crank_truth(r: f64, l: f64, th: f64, w: f64) -> SliderCrankTruth {
    let (s, c) = th.sin_cos();
    let big_s = (l * l - r * r * s * s).sqrt();
    let a = r * r * s * c;
    let s1 = -a / big_s;
    let s2 = -r * r * (2.0 * th).cos() / big_s - a * a / big_s.powi(3);
    let phd = -r * w * c / big_s;
    SliderCrankTruth {
        x: [r * c + big_s, w * (-r * s + s1), w * w * (-r * c + s2)],
        ph: [
            (-r * s).atan2(big_s),
            phd,
            (r * w * w * s - r * s * phd * phd) / big_s,
        ],
    }
}

/// 1e-12 of each quantity's scale `(r + l) w^k`: the solves are 3x3 and well conditioned
/// away from the toggle (`l = 3 r`), so only rounding remains.
#[test]
fn slider_crank_kinematics_match_the_closed_form() {
    let sc = slider_crank(Drive::Crank { th0: TH0, w: W });
    let times: Vec<f64> = (0..=100).map(|i| 0.05 * i as f64).collect();
    let guess = Vector::<3>::new(TH0, 0.0, sc.r + sc.l);
    let states = kinematic_sweep(&sc, &times, &guess, &opts()).unwrap();
    let scale = sc.r + sc.l;
    let mut worst = [0.0f64; 3];
    for s in &states {
        let truth = slider_crank_truth(sc.r, sc.l, TH0 + W * s.t, W);
        let got_x = [s.q[2], s.qd[2], s.qdd[2]];
        let got_ph = [s.q[1], s.qd[1], s.qdd[1]];
        for k in 0..3 {
            let tol = 1e-12 * scale * W.powi(k as i32);
            worst[k] = worst[k].max((got_x[k] - truth.x[k]).abs() / (tol / 1e-12));
            assert!(
                (got_x[k] - truth.x[k]).abs() < tol,
                "t = {}: x^({k}) {} vs {}",
                s.t,
                got_x[k],
                truth.x[k]
            );
            assert!(
                (got_ph[k] - truth.ph[k]).abs() < tol,
                "t = {}: ph^({k})",
                s.t
            );
        }
        assert!((s.q[0] - (TH0 + W * s.t)).abs() < 1e-12 * scale);
        assert!((s.qd[0] - W).abs() < 1e-12 * scale * W);
    }
    eprintln!(
        "slider-crank kinematics: worst piston error / scale (x, xd, xdd) = {:.2e} {:.2e} {:.2e}",
        worst[0], worst[1], worst[2]
    );
}

/// Driven by the piston, the slider-crank locks at top dead centre `x = r + l`
/// (`th = ph = 0`): the rows of `Phi_q` for the loop's `x` equation and the driver are
/// parallel, and the motion of the crank is undetermined.
#[test]
fn piston_driven_slider_crank_at_dead_centre_is_singular() {
    let sc = slider_crank(Drive::Piston { x0: 4.0, v: -1.0 });
    let guess = Vector::<3>::new(0.0, 0.0, 4.0);
    let detail = singular_at_zero(kinematics(&sc, 0.0, &guess, &opts()));
    eprintln!("{detail}");
    // Row 2 (the driver) is parallel to row 0 (the loop's `x` equation) there.
    assert!(detail.contains("rows 2 (counting from 0)"), "{detail}");
}

// ---------------------------------------------------------------------------------------
// Inverse dynamics

/// Pivot reaction of a compound pendulum. Newton for the centre of mass,
/// `m a_G = R + m g (0, -1)`, with `a_G = d (cos th thdd - sin th thd^2, sin th thdd + cos th thd^2)`
/// and `thdd = -m g d sin th / I_O`, `I_O = i_c + m d^2` (moments about the pivot):
/// `R = (m d (cos th thdd - sin th thd^2), m g + m d (sin th thdd + cos th thd^2))`.
/// Along the rod, towards the pivot `(-sin th, cos th)`: `R_n = m g cos th + m d thd^2`;
/// across it, `(cos th, sin th)`: `R_t = m g sin th i_c / I_O`.
/// The constraints pin `ux`, `uy`, and `-lambda` is the force the pivot applies along them.
#[test]
fn pendulum_multipliers_are_the_pivot_reaction() {
    let p = RelaxedPendulum {
        m: 2.0,
        d: 0.4,
        i_c: 0.05,
        grav: 9.81,
    };
    for (th, thd) in [(0.7, 1.3), (-2.0, 0.4), (3.0, -2.5)] {
        let q = Vector::<3>::new(th, 0.0, 0.0);
        let qd = Vector::<3>::new(thd, 0.0, 0.0);
        let r = inverse_dynamics(&p, 0.0, &q, &qd).unwrap();
        let (m, d, g) = (p.m, p.d, p.grav);
        let i_o = p.i_c + m * d * d;
        let thdd = -m * g * d * th.sin() / i_o;
        let rx = m * d * (th.cos() * thdd - th.sin() * thd * thd);
        let ry = m * g + m * d * (th.sin() * thdd + th.cos() * thd * thd);
        let rn = m * g * th.cos() + m * d * thd * thd;
        let rt = m * g * th.sin() * p.i_c / i_o;
        let scale = m * g + m * d * thd * thd;
        assert!((r.qdd[0] - thdd).abs() < 1e-12 * thdd.abs().max(1.0));
        assert!(r.qdd[1].abs() < 1e-12 && r.qdd[2].abs() < 1e-12);
        assert!(
            (-r.lambda[0] - rx).abs() < 1e-12 * scale,
            "{} vs {rx}",
            -r.lambda[0]
        );
        assert!(
            (-r.lambda[1] - ry).abs() < 1e-12 * scale,
            "{} vs {ry}",
            -r.lambda[1]
        );
        let (fx, fy) = (-r.lambda[0], -r.lambda[1]);
        assert!((-fx * th.sin() + fy * th.cos() - rn).abs() < 1e-12 * scale);
        assert!((fx * th.cos() + fy * th.sin() - rt).abs() < 1e-12 * scale);
        // The generalised constraint forces are the reaction on ux, uy and nothing on th.
        assert_eq!(r.constraint_forces, Vector::<3>::new(0.0, fx, fy));
    }
}

/// Driving torque of the crank-driven slider-crank by the energy rate: the loop-closure
/// forces do no work, so `tau w = dT/dt + dV/dt` with everything from the closed-form
/// kinematics above (not from the model's mass matrix):
/// `dT/dt = mr v_G . a_G + (mr l^2/12) phd phdd + mp xd xdd` (the crank turns uniformly),
/// `v_G = (vA + vB)/2`, `vA = r w (-sin th, cos th)`, `aA = -r w^2 (cos th, sin th)`, `vB = (xd, 0)`;
/// `dV/dt = (mc + mr)/2 g r w cos th + k (x - x_free) xd` (the crank's and the rod's centres
/// are both at height `r sin th / 2`). The driver's torque is `-lambda_3` (constraint `th - th0 - w t`).
/// Tolerance 1e-11 of the largest power term: the 6x6 augmented solve has a condition
/// number of order 1e2 here, so rounding is well below it.
#[test]
fn slider_crank_driving_torque_balances_the_energy_rate() {
    let sc = slider_crank(Drive::Crank { th0: TH0, w: W });
    let times: Vec<f64> = (0..=40).map(|i| 0.1 * i as f64).collect();
    let guess = Vector::<3>::new(TH0, 0.0, sc.r + sc.l);
    let (r, l, g) = (sc.r, sc.l, sc.grav);
    let mut worst = 0.0f64;
    for s in kinematic_sweep(&sc, &times, &guess, &opts()).unwrap() {
        let tau = -inverse_dynamics(&sc, s.t, &s.q, &s.qd).unwrap().lambda[2];
        let th = TH0 + W * s.t;
        let k = slider_crank_truth(r, l, th, W);
        let (sn, cs) = th.sin_cos();
        let v_g = [0.5 * (-r * W * sn + k.x[1]), 0.5 * r * W * cs];
        let a_g = [0.5 * (-r * W * W * cs + k.x[2]), 0.5 * (-r * W * W * sn)];
        let terms = [
            sc.mr * (v_g[0] * a_g[0] + v_g[1] * a_g[1]),
            sc.mr * l * l / 12.0 * k.ph[1] * k.ph[2],
            sc.mp * k.x[1] * k.x[2],
            0.5 * (sc.mc + sc.mr) * g * r * W * cs,
            sc.k * (k.x[0] - sc.x_free) * k.x[1],
        ];
        let power: f64 = terms.iter().sum();
        let scale = terms.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        worst = worst.max((tau * W - power).abs() / scale);
        assert!(
            (tau * W - power).abs() < 1e-11 * scale,
            "t = {}: tau w = {} vs dE/dt = {power}",
            s.t,
            tau * W
        );
    }
    eprintln!("slider-crank driving torque: worst |tau w - dE/dt| / max term = {worst:.2e}");
}

// ---------------------------------------------------------------------------------------
// Statics

/// `m g = k (x - l0)`: `x = l0 + m g / k`.
#[test]
fn hanging_mass_rests_where_the_spring_carries_its_weight() {
    let hm = HangingMass {
        m: 2.0,
        k: 100.0,
        l0: 0.5,
        grav: 9.81,
    };
    let x = static_equilibrium(&hm, 0.0, &Vector::<1>::new(0.0), &opts()).unwrap();
    let truth = hm.l0 + hm.m * hm.grav / hm.k;
    assert!((x[0] - truth).abs() < 1e-12 * truth);
}

/// Symmetric equilibrium `th1 = th, th2 = -th` by virtual work with one DOF `th`:
/// `V = m g L sin th + k/2 (2 L cos th)^2`, `dV/dth = m g L cos th - 4 k L^2 sin th cos th = 0`,
/// so `sin th = m g / (4 k L)`. The guide's normal force at `C` from moments about `A`
/// (the spring acts along `C A`): `N_C 2 L cos th = m g (L/2) cos th + m g (3L/2) cos th`,
/// `N_C = m g`; the constraint `y_C = 0` has `-Phi_q^T lambda = N_C dy_C/dq`, so `lambda = -m g`.
#[test]
fn two_bar_linkage_with_a_spring_matches_virtual_work() {
    let tb = TwoBar {
        len: 0.5,
        m: 1.0,
        k: 10.0,
        grav: 9.81,
    };
    let guess = Vector::<2>::new(0.4, -0.6);
    let (q, lambda) =
        static_equilibrium_constrained::<_, 2, 1, 3>(&tb, 0.0, &guess, &opts()).unwrap();
    let th = (tb.m * tb.grav / (4.0 * tb.k * tb.len)).asin();
    assert!(
        (q[0] - th).abs() < 1e-12 && (q[1] + th).abs() < 1e-12,
        "{q}"
    );
    assert!(
        (lambda[0] + tb.m * tb.grav).abs() < 1e-12 * tb.m * tb.grav,
        "{lambda}"
    );
}

/// A spring-less pendulum has no isolated equilibrium in `ux` once relaxed without
/// constraints: the stiffness in a coordinate nothing holds is zero.
#[test]
fn a_neutral_direction_is_reported_not_divided_by() {
    let free = models::CircleParticle { m: 1.0, l: 1.0 };
    let got = static_equilibrium(&free, 0.0, &Vector::<2>::new(0.3, 0.2), &opts());
    assert!(matches!(got, Err(Error::StaticsFailed { .. })), "{got:?}");
}

// ---------------------------------------------------------------------------------------
// Projection

/// The velocity projection is `M`-orthogonal to the tangent space: for the tangent
/// `v` (the closed-form consistent velocity with `w1 = 1`) `v^T M (qd_new - qd_old) = 0`,
/// and the projected velocity satisfies the constraint.
#[test]
fn velocity_projection_is_mass_orthogonal() {
    let fb = FourBar::crank_rocker();
    let q = four_bar_closed(&fb, 1.1);
    let mut qd = Vector::<3>::new(0.7, -0.4, 0.9);
    let old = qd;
    project_velocities(&fb, 0.0, &q, &mut qd).unwrap();
    let v = Vector::<3>::new(
        1.0,
        -fb.r1 * (q[2] - q[0]).sin() / (fb.r2 * (q[2] - q[1]).sin()),
        fb.r1 * (q[1] - q[0]).sin() / (fb.r3 * (q[1] - q[2]).sin()),
    );
    let m = fb.mass_matrix(0.0, &q).unwrap();
    assert!((v.transpose() * m * (qd - old))[0].abs() < 1e-13);
    assert!(constraint_drift(&fb, 0.0, &q, &qd).1 < 1e-14);
}

/// Converged by the documented rule `max |Phi_i| <= tol`, from an offset
/// a thousand times larger.
#[test]
fn position_projection_returns_to_the_manifold() {
    let fb = FourBar::crank_rocker();
    let mut q = four_bar_closed(&fb, -0.6) + Vector::<3>::new(1e-3, -2e-3, 1.5e-3);
    let before = constraint_drift(&fb, 0.0, &q, &Vector::<3>::zeros()).0;
    project_positions(&fb, 0.0, &mut q, &opts()).unwrap();
    let after = constraint_drift(&fb, 0.0, &q, &Vector::<3>::zeros()).0;
    assert!(
        before > 1e-3 && after <= opts().tol,
        "{before:e} -> {after:e}"
    );
}

/// The four-bar as a first-order system in index-1 form (`[M Phi_q^T; Phi_q 0]` solved at
/// every right-hand side), projected after every step with `project_state`.
struct IndexOne(FourBar);

impl OdeSystem<6> for IndexOne {
    fn rhs(&self, t: f64, y: &Vector<6>) -> Result<Vector<6>> {
        second_order_rhs::<3, 6>(y, |q, qd| self.0.acceleration(t, q, qd))
    }
    fn project(&self, t: f64, y: &mut Vector<6>) -> Result<()> {
        project_state::<_, 3, 2, 6>(&self.0, t, y)
    }
}

/// Ten seconds of the four-bar swinging under gravity with DOPRI5 (rtol 1e-8) and
/// projection after every accepted step: the state stays on both manifolds to 1e-10.
#[test]
fn projected_index_one_four_bar_does_not_drift() {
    let fb = FourBar::crank_rocker();
    let q0 = four_bar_closed(&fb, 0.3);
    let qd0 = consistent_velocities(
        &fb,
        0.0,
        &q0,
        &Vector::<3>::new(2.0, 0.0, 0.0),
        &[true, false, false],
    )
    .unwrap();
    let mut y0 = Vector::<6>::zeros();
    y0.fixed_rows_mut::<3>(0).copy_from(&q0);
    y0.fixed_rows_mut::<3>(3).copy_from(&qd0);
    let dopri = Dopri5::new(Options {
        rtol: 1e-8,
        atol: 1e-10,
        ..Options::default()
    });
    let sol = dopri.solve(&IndexOne(fb), 0.0, y0, 10.0, &[]).unwrap();
    assert_eq!(*sol.t.last().unwrap(), 10.0);
    let (mut worst_p, mut worst_v) = (0.0f64, 0.0f64);
    for (t, y) in sol.t.iter().zip(&sol.y) {
        let q = y.fixed_rows::<3>(0).into_owned();
        let qd = y.fixed_rows::<3>(3).into_owned();
        let (p, v) = constraint_drift(&fb, *t, &q, &qd);
        worst_p = worst_p.max(p);
        worst_v = worst_v.max(v);
    }
    eprintln!(
        "four-bar, DOPRI5 + projection: {} steps, drift {worst_p:.2e} (position), {worst_v:.2e} (velocity)",
        sol.t.len() - 1
    );
    assert!(
        worst_p < 1e-10 && worst_v < 1e-10,
        "drift {worst_p:e}, {worst_v:e}"
    );
    // Without projection the same run drifts by far more (shows the test has teeth).
    let loose = Dopri5::new(Options {
        rtol: 1e-8,
        atol: 1e-10,
        project: false,
        ..Options::default()
    });
    let sol = loose.solve(&IndexOne(fb), 0.0, y0, 10.0, &[]).unwrap();
    let (_, y) = sol.last();
    let q = y.fixed_rows::<3>(0).into_owned();
    let free_drift = constraint_drift(&fb, 10.0, &q, &Vector::<3>::zeros()).0;
    eprintln!("four-bar, DOPRI5 without projection: position drift {free_drift:.2e} at t = 10");
    assert!(free_drift > 1e-9);
}
