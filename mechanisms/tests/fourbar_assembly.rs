//! The IFToMM A02 assembly of 40 four-bar loops against its one-coordinate reduction
//! (derived in `mechanisms::fourbar_assembly`: started as a parallelogram it stays one, all
//! cranks at one angle `th` with `(41/3 + 40) m l^2 th'' = -(41/2 + 40) m g l cos th`).
//! The first 3 s pass the singular (all-horizontal) positions at t = 0.72, 1.24 and 2.69 s,
//! where `Phi_q` loses 40 of its 80 ranks; the full 20 s sweep of every method is the
//! `loops` report binary.

use mbd::analysis::rank_and_redundant;
use mbd::integrate::Integrator;
use mbd::{Constrained, Dopri5, Options};
use mechanisms::fourbar_assembly::{self as fa, FourBarAssembly};

const T1: f64 = 3.0;

fn dopri(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Default::default()
    }
}

/// Passing the singular positions, the assembly stays a parallelogram (every crank at
/// crank 0's angle), and the tip error converges with the tolerance.
#[test]
fn passes_the_singular_positions_on_the_parallelogram_branch() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let reference = fa::reference(&a, 1.0, T1).unwrap();
    let mut errors = vec![];
    for tol in [1e-6, 1e-8] {
        let sol = Dopri5::new(dopri(tol)).solve(&a, 0.0, y0, T1, &[]).unwrap();
        let spread = sol.y.iter().map(|y| a.spread(y).0).fold(0.0, f64::max);
        let err = fa::tip_error(&a, &sol, &reference, T1, 60);
        eprintln!("DOPRI5 {tol:e}: tip error {err:e}, crank spread {spread:e}");
        assert!(spread < 1e-6, "cranks {spread} apart at tol {tol}");
        errors.push(err);
    }
    assert!(
        errors[0] < 1e-3 && errors[1] < 0.1 * errors[0],
        "{errors:?}"
    );
}

/// At the start the 80 closure equations are independent; with every link horizontal
/// (cranks at 0, couplers along them) 40 of them are redundant, and the acceleration solve
/// still answers, with finite, minimum-norm multipliers.
#[test]
fn finds_the_rank_loss_at_the_horizontal_position() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let q0 = y0.fixed_rows::<{ fa::N }>(0).into_owned();
    assert_eq!(rank_and_redundant(&a.phi_q(0.0, &q0)), (fa::M, vec![]));
    let flat = mbd::Vector::<{ fa::N }>::zeros();
    assert!(a.phi(0.0, &flat).norm() < 1e-14);
    let (rank, redundant) = rank_and_redundant(&a.phi_q(0.0, &flat));
    assert_eq!((rank, redundant.len()), (fa::LOOPS, fa::LOOPS));
    // Passing flat at the rate th' = w (couplers translating) the 40 vanished rows ask
    // nothing (their gamma is -w^2 + w^2 = 0): a consistent system, solved, finite.
    let w = 4.0;
    let qd = mbd::Vector::<{ fa::N }>::from_fn(|i, _| if i % 2 == 0 { w } else { -w });
    let (qdd, lambda) = a.acceleration_and_multipliers(0.0, &flat, &qd).unwrap();
    let residual = (a.phi_q(0.0, &flat) * qdd - a.gamma(0.0, &flat, &qd)).amax();
    assert!(residual < 1e-10, "{residual}");
    assert!(qdd.iter().chain(lambda.iter()).all(|v| v.is_finite()));
}

/// The index-3 augmented Lagrangian integrator (trapezoidal rule) passes the same three
/// singular positions on the parallelogram branch, its tip error converging at least at
/// second order in `h` (halving `h` divides it by 4 or more; measured 9.5 over these 3 s). The cranks stay parallel to 1e-5 rad (measured
/// 1.1e-6 at h = 2e-3: what the Newton tolerance `1e-9` leaves in the directions `Phi_q`
/// loses at the singular positions; a branch switch puts them 0.5 rad apart).
#[test]
fn ali3_passes_the_singular_positions_with_second_order_error() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let q0 = y0.fixed_rows::<{ fa::N }>(0).into_owned();
    let qd0 = y0.fixed_rows::<{ fa::N }>(fa::N).into_owned();
    let reference = fa::reference(&a, 1.0, T1).unwrap();
    let mut errors = vec![];
    for h in [2e-3, 1e-3] {
        let sol = mbd::integrate::Ali3::new(h)
            .solve::<_, { fa::N }, { fa::M }, { fa::D }>(&a, 0.0, q0, qd0, T1, &[])
            .unwrap();
        let spread = sol.y.iter().map(|y| a.spread(y).0).fold(0.0, f64::max);
        let err = fa::tip_error(&a, &sol, &reference, T1, 60);
        eprintln!("ALI3-P h = {h:e}: tip error {err:e}, crank spread {spread:e}");
        assert!(spread < 1e-5, "cranks {spread} apart at h {h}");
        errors.push(err);
    }
    let ratio = errors[0] / errors[1];
    assert!(errors[1] < 1e-3 && ratio > 3.5, "{errors:?}");
}

/// The generated closure residual rounds at its own size, not at the pins' ground
/// positions. On an exact parallelogram (every crank at `th`, every coupler at `-th` from
/// its crank, so horizontal) loop `i`'s rows are exactly
/// `i l + l cos th + l - ((i + 1) l + l cos th) = 0` and `l sin th + 0 - l sin th = 0`;
/// the derive sums the offsets `i l - (i + 1) l = -l` first (exact), so what is left is
/// the rounding of terms of size `l`: a few `eps l`. Summed in the written order, the x
/// rows rounded at the size of `(i + 2) l` (`ulp(41) = 7e-15`; this check failed with
/// 1.8e-15 at `th = 0.03`); Gauss–Newton near a flat position divides that by the distance
/// to it (docs/STABILITY.md).
#[test]
fn closure_residual_rounds_at_its_own_size() {
    let a = FourBarAssembly::benchmark();
    for th in [1.0, 0.3, 0.1, 0.03, 1e-2, 3e-3, 1e-3, -0.02, 2.5] {
        let q = mbd::Vector::<{ fa::N }>::from_fn(|i, _| if i % 2 == 0 { th } else { -th });
        let worst = a.phi(0.0, &q).amax();
        assert!(worst <= 4.0 * f64::EPSILON * a.l, "th = {th}: {worst:e}");
    }
}
