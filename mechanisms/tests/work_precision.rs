//! The sweep machinery of the `work-precision` report: its references, its error measure
//! and its models. No timing is asserted.

use mbd::integrate::{Dopri5, Integrator};
use mbd::{Options, Vector};
use mechanisms::handwritten::{
    DOUBLE_PENDULUM, DoublePendulumByHand, PENDULUM, PendulumByHand, SLIDER_CRANK,
    SliderCrankByHand, slider_crank_state,
};
use mechanisms::workprecision::{
    Method, PANELS, Setting, cases, elliptic_k, pendulum_motion, pendulum_reference,
    slider_crank_motion, slider_reference, zero_overhead,
};

fn run(name: &str, method: Method, value: f64) -> f64 {
    let all = zero_overhead();
    let problem = all
        .iter()
        .flat_map(|(g, h)| [g, h])
        .find(|p| p.name == name)
        .expect("a zero-overhead model");
    (problem.run)(&Setting { method, value })
        .expect("the run succeeds")
        .error()
}

#[test]
fn pendulum_period_by_quadrature_is_the_elliptic_integral() {
    // T = 4 K(sin(θ0/2)) / sqrt(g/l), K by the arithmetic-geometric mean.
    let p = PENDULUM;
    let theta_0 = 2.0f64;
    let exact = 4.0 * elliptic_k((theta_0 / 2.0).sin()) / (p.g / p.l).sqrt();
    let motion = pendulum_motion(&p, theta_0);
    let period = motion.period(PANELS);
    assert!(
        (period - exact).abs() < 1e-14 * exact,
        "{period} vs {exact}"
    );
    // Quarter period: from the release to the bottom.
    let quarter = motion.time_to(0.0, PANELS);
    assert!((quarter - exact / 4.0).abs() < 1e-14 * exact);
    // Small amplitude: 2π sqrt(l/g).
    let small = pendulum_motion(&p, 1e-4).period(PANELS);
    let linear = 2.0 * std::f64::consts::PI * (p.l / p.g).sqrt();
    assert!((small - linear).abs() < 1e-8 * linear);
}

#[test]
fn slider_crank_reference_is_converged_and_consistent() {
    // Doubling the panels changes nothing at the 1e-14 level.
    let motion = slider_crank_motion(&SLIDER_CRANK, 0.3);
    let (a, b) = (motion.period(PANELS), motion.period(2 * PANELS));
    assert!((a - b).abs() < 1e-14 * a, "{a} vs {b}");
    // The reference end state conserves the energy of the generated model.
    let (_, theta, theta_dot) = slider_reference();
    let energy = |y: Vector<6>| {
        mbd::Mechanism::<3>::energy(
            &SLIDER_CRANK,
            0.0,
            &y.fixed_rows::<3>(0).into_owned(),
            &y.fixed_rows::<3>(3).into_owned(),
        )
        .unwrap()
    };
    let e0 = energy(slider_crank_state(&SLIDER_CRANK, 0.3, 0.0));
    let e1 = energy(slider_crank_state(&SLIDER_CRANK, theta, theta_dot));
    assert!((e1 - e0).abs() < 1e-13 * e0.abs().max(1.0), "{e0} vs {e1}");
}

#[test]
fn rk4_error_on_the_pendulum_falls_at_order_four() {
    let (t1, _, _) = pendulum_reference();
    let h = t1 / 1024.0;
    let (e1, e2) = (
        run("pendulum", Method::Rk4, h),
        run("pendulum", Method::Rk4, h / 2.0),
    );
    let order = (e1 / e2).log2();
    assert!(
        (3.7..4.3).contains(&order),
        "observed order {order} ({e1}, {e2})"
    );
}

#[test]
fn generalized_alpha_error_falls_at_order_two() {
    let (t1, _, _) = pendulum_reference();
    let h = t1 / 2048.0;
    let (e1, e2) = (
        run("pendulum", Method::GeneralizedAlpha, h),
        run("pendulum", Method::GeneralizedAlpha, h / 2.0),
    );
    let order = (e1 / e2).log2();
    assert!(
        (1.8..2.2).contains(&order),
        "observed order {order} ({e1}, {e2})"
    );
}

#[test]
fn adaptive_errors_follow_the_tolerance() {
    for name in ["pendulum", "double pendulum", "slider-crank"] {
        for method in [Method::Dopri5, Method::Radau5] {
            let loose = run(name, method, 1e-4);
            let tight = run(name, method, 1e-10);
            assert!(
                tight < 1e-6 && tight < loose * 1e-3,
                "{name} {method}: {loose} -> {tight}"
            );
        }
    }
}

#[test]
fn peer_reaches_the_same_accuracy() {
    for name in ["pendulum", "slider-crank"] {
        let peer = run(name, Method::PeerDopri5, 1e-10);
        let ours = run(name, Method::Dopri5NoProjection, 1e-10);
        assert!(
            peer < 1e-6 && ours < 1e-6,
            "{name}: peer {peer}, mbd {ours}"
        );
    }
}

fn end_state<S: mbd::OdeSystem<D>, const D: usize>(sys: &S, y0: Vector<D>, t1: f64) -> Vector<D> {
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    };
    *Dopri5::new(opts)
        .solve(sys, 0.0, y0, t1, &[])
        .expect("the run succeeds")
        .last()
        .1
}

#[test]
fn hand_written_and_generated_models_give_the_same_trajectory() {
    let p = PENDULUM;
    let y0 = Vector::<2>::new(2.0, 0.0);
    let (a, b) = (
        end_state(&p, y0, 3.0),
        end_state(&PendulumByHand::from(&p), y0, 3.0),
    );
    assert!((a - b).amax() < 1e-12, "pendulum: {a} vs {b}");

    let d = DOUBLE_PENDULUM;
    let y0 = Vector::<4>::new(0.9, -0.5, 0.4, 1.2);
    let (a, b) = (
        end_state(&d, y0, 2.0),
        end_state(&DoublePendulumByHand::from(&d), y0, 2.0),
    );
    assert!((a - b).amax() < 1e-12, "double pendulum: {a} vs {b}");

    let s = SLIDER_CRANK;
    let y0 = slider_crank_state(&s, 0.3, 0.0);
    let (a, b) = (
        end_state(&s, y0, 1.0),
        end_state(&SliderCrankByHand::from(&s), y0, 1.0),
    );
    assert!((a - b).amax() < 1e-12, "slider-crank: {a} vs {b}");
}

#[test]
fn every_case_reaches_its_references_with_dopri5() {
    for case in cases() {
        let m = (case.run)(&Setting {
            method: Method::Dopri5,
            value: 1e-12,
        })
        .unwrap_or_else(|e| panic!("{}: {e}", case.name));
        assert!(m.error() < 1e-8, "{}: error {}", case.name, m.error());
    }
}

#[test]
fn friction_case_is_skipped_by_generalized_alpha_with_a_reason() {
    let case05 = cases().into_iter().find(|c| c.name == "case05").unwrap();
    let out = (case05.run)(&Setting {
        method: Method::GeneralizedAlpha,
        value: 1e-3,
    });
    assert!(matches!(
        out,
        Err(mechanisms::workprecision::Failure::Unsupported(_))
    ));
}

/// The time-to-accuracy table's pieces: the pendulum's Jacobi-elliptic reference starts at
/// the release angle and crosses zero at the quarter period found by quadrature; a DOP853
/// run at 1e-12 gives the 101 grid states (t0 and 100 more, the last at t1) within 1e-10 of
/// it; and DOP853 is swept with every model.
#[test]
fn time_to_accuracy_reference_and_grid() {
    use mechanisms::accuracy::{GRID, pendulum_angle, states};
    let p = PENDULUM;
    let (theta0, w) = (std::f64::consts::FRAC_PI_3, (p.g / p.l).sqrt());
    assert!((pendulum_angle(w, theta0, 0.0) - theta0).abs() < 1e-15);
    let quarter = pendulum_motion(&p, theta0).time_to(0.0, PANELS);
    assert!(pendulum_angle(w, theta0, quarter).abs() < 1e-12);
    let y0 = Vector::<2>::new(theta0, 0.0);
    let (ys, n_rhs) = states("DOP853", &p, y0, 10.0, 1e-12).unwrap();
    assert_eq!(ys.len(), GRID);
    assert!(n_rhs > 0);
    let worst = ys
        .iter()
        .enumerate()
        .map(|(i, y)| (y[0] - pendulum_angle(w, theta0, 0.1 * i as f64)).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-10, "{worst:e}");
    // Vern9 on the same grid at 1e-11, its states from its interpolant: below 1e-10 (1.5 tol
    // measured over its dense output, `mbd-core/tests/vern9.rs`).
    let (ys, _) = states("VERN9", &p, y0, 10.0, 1e-11).unwrap();
    let worst9 = ys
        .iter()
        .enumerate()
        .map(|(i, y)| (y[0] - pendulum_angle(w, theta0, 0.1 * i as f64)).abs())
        .fold(0.0, f64::max);
    assert!(worst9 < 1e-10, "{worst9:e}");
    for m in [Method::Dop853, Method::Vern9] {
        assert!(Method::MBD.contains(&m));
        assert!(cases().iter().all(|c| c.methods.contains(&m)));
    }
}
