//! Singular positions passed by the bridge of `mbd::passage`: the IFToMM A02 assembly of 40
//! four-bar loops (all links horizontal at t = 0.72, 1.24 and 2.69 s in the first 3 s, where
//! `Phi_q` loses 40 of its 80 ranks) with the integrators whose index-1 accelerations stop
//! there, against the one-coordinate reduction derived in `mechanisms::fourbar_assembly`
//! (started as a parallelogram it stays one: every crank at the angle `th` with
//! `(41/3 + 40) m l^2 th'' = -(41/2 + 40) m g l cos th`). The reduction also gives the
//! singular instants: the links are horizontal where `sin th = 0`.

use mbd::integrate::{GeneralizedAlpha, Radau5};
use mbd::passage::{self, Passed, Settings};
use mbd::{Dopri5, Options};
use mechanisms::fourbar_assembly::{self as fa, FourBarAssembly};

const T1: f64 = 3.0;

fn options(tol: f64) -> Options {
    Options {
        rtol: tol,
        atol: tol,
        ..Default::default()
    }
}

/// Tip error against the reduction, crank spread, and every passage bridging a flat
/// instant of the reduction (`sin th` changes sign over the bridge) and reported at it
/// (`|sin th| < 1e-3`: within 2e-4 s at the 4.8 rad/s the cranks turn there; the instants
/// located on the smooth singular-value measure are measured within about 1e-5 s, where
/// the pivoted remainder's were up to 2.2e-2 s off, and 7e-4 s extrapolated after a Newton
/// failure) with its 40 lost rows named.
fn check(a: &FourBarAssembly, run: &Passed<{ fa::D }>, t1: f64, what: &str) -> f64 {
    let reference = fa::reference(a, 1.0, t1).unwrap();
    let sol = &run.solution;
    assert_eq!(sol.t_end, t1, "{what}");
    let spread = sol.y.iter().map(|y| a.spread(y).0).fold(0.0, f64::max);
    let err = fa::tip_error(a, sol, &reference, t1, 60);
    eprintln!(
        "{what}: tip error {err:e}, crank spread {spread:e}, passages at {:?}",
        run.passages.iter().map(|p| p.t).collect::<Vec<_>>()
    );
    assert!(spread < 1e-6, "{what}: cranks {spread} apart");
    for p in &run.passages {
        let sin = |t: f64| reference.at(t).unwrap()[0].sin();
        assert!(
            sin(p.from) * sin(p.to) < 0.0,
            "{what}: no flat instant in the bridge [{}, {}]",
            p.from,
            p.to
        );
        let th = reference.at(p.t).unwrap()[0];
        assert!(
            th.sin().abs() < 1e-3,
            "{what}: passage at t = {} where th = {th}",
            p.t
        );
        assert_eq!(p.rows.len(), fa::LOOPS, "{what}: rows {:?}", p.rows);
    }
    err
}

/// DOPRI5 at 1e-9 and 1e-10: where its index-1 accelerations stop at a flat position (the
/// banded LU's pivots and the augmented Lagrangian's residual both out of bounds: at 1e-10
/// the stage nearest the instant of t = 2.69 comes close enough), the bridge carries the
/// run on the parallelogram branch; at 1e-9 the steps land far enough from the instants for
/// the index-1 accelerations to hold. Either way the error falls with the tolerance.
#[test]
fn dopri5_is_bridged_on_the_parallelogram_branch() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let (mut errors, mut bridged) = (vec![], 0);
    for tol in [1e-9, 1e-10] {
        let run = passage::solve(
            &Dopri5::new(options(tol)),
            &a,
            0.0,
            y0,
            T1,
            &[],
            &Settings::new(tol),
        )
        .unwrap();
        bridged += run.passages.len();
        errors.push(check(&a, &run, T1, &format!("DOPRI5 {tol:e}")));
    }
    assert!(
        bridged > 0,
        "no passage bridged: the bridge is not exercised"
    );
    assert!(
        errors[0] < 1e-5 && errors[1] < 0.5 * errors[0],
        "{errors:?}"
    );
}

/// The whole 20 s of the benchmark by DOPRI5 at the tight tolerances where the bridge
/// once crawled (main before this test: 1e-10 and 1e-12 ended in `TooManySteps` after
/// 100 000 steps at t = 11.07 and 9.11, the instant misplaced by the pivoted rank measure
/// and crossed inside a leg). Every run ends at 20 s on the parallelogram branch, each
/// passage at a flat instant of the reduction, the tip within 1e-6 / 1e-7 of it (measured
/// here: 3.3e-7 at 1e-10, 2.1e-8 at 1e-12; 8.9e-8 before the constants-first rows).
#[test]
fn dopri5_runs_the_whole_20_s_at_tight_tolerances() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    for (tol, bound) in [(1e-10, 1e-6), (1e-12, 1e-7)] {
        let run = passage::solve(
            &Dopri5::new(options(tol)),
            &a,
            0.0,
            y0,
            20.0,
            &[],
            &Settings::new(tol),
        )
        .unwrap();
        assert!(!run.passages.is_empty(), "{tol:e}: nothing bridged");
        let err = check(&a, &run, 20.0, &format!("DOPRI5 {tol:e}, 20 s"));
        assert!(err < bound, "{tol:e}: {err:e}");
    }
}

/// Radau5 at 1e-9 (unbridged it stops at the first flat position, t = 0.72).
#[test]
fn radau5_is_bridged_on_the_parallelogram_branch() {
    big_stack(radau5);
}

/// The 162-state matrices of the implicit methods are larger than a test thread's stack.
fn big_stack(f: fn()) {
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(f)
        .unwrap()
        .join()
        .unwrap();
}

fn radau5() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let run = passage::solve(
        &Radau5::new(options(1e-9)),
        &a,
        0.0,
        y0,
        T1,
        &[],
        &Settings::new(1e-9),
    )
    .unwrap();
    assert!(!run.passages.is_empty());
    let err = check(&a, &run, T1, "Radau5 1e-9");
    assert!(err < 1e-4, "{err:e}");
}

/// Generalized-α (index 3) at h = 1e-3 through the bridge: its Newton iteration (the
/// banded matrix from `M` and `Phi_q`, increments that stall at the rounding accepted)
/// passes the flat positions by itself, so nothing is bridged; still on the parallelogram
/// branch (its own test: `fourbar_assembly_generalized_alpha.rs`).
#[test]
fn generalized_alpha_is_bridged_on_the_parallelogram_branch() {
    big_stack(generalized_alpha);
}

fn generalized_alpha() {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let h = 1e-3;
    let run =
        passage::solve_generalized_alpha::<_, { fa::N }, { fa::M }, { fa::N + fa::M }, { fa::D }>(
            &GeneralizedAlpha::new(0.9, h),
            &a,
            0.0,
            y0,
            1.0,
            &[],
            &Settings::new(h * h),
        )
        .unwrap();
    assert!(run.passages.is_empty(), "{:?}", run.passages);
    let err = check(&a, &run, 1.0, "generalized-alpha 1e-3");
    assert!(err < 1e-3, "{err:e}");
}

/// The ordinary `Dopri5::solve` of the assembly (no `passage` call written) bridges its
/// flat positions and reports them in `Solution::passages`, with the same truth as above;
/// with `Options::passages` off it is one raw run, which stops with the typed error at
/// the first flat position its index-1 accelerations refuse.
#[test]
fn the_ordinary_solve_bridges_and_the_opt_out_stops() {
    use mbd::integrate::Integrator;
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let tol = 1e-10;
    let solution = Dopri5::new(options(tol))
        .solve(&a, 0.0, y0, T1, &[])
        .unwrap();
    let run = Passed {
        passages: solution.passages.clone(),
        solution,
    };
    assert!(!run.passages.is_empty(), "no passage bridged");
    let err = check(&a, &run, T1, "DOPRI5 1e-10, ordinary solve");
    assert!(err < 1e-7, "{err:e}");
    let raw = Options {
        passages: false,
        ..options(tol)
    };
    match Dopri5::new(raw).solve(&a, 0.0, y0, T1, &[]) {
        Err(mbd::Error::SingularPosition { t, .. }) => {
            let th = fa::reference(&a, 1.0, T1).unwrap().at(t).unwrap()[0];
            assert!(th.sin().abs() < 1e-2, "stopped at t = {t}, th = {th}");
        }
        other => panic!(
            "expected SingularPosition, got {:?}",
            other.map(|s| s.t_end)
        ),
    }
}

/// The quadrature reference (`Reduced::exact`, for tolerances where the integrated one's own
/// error shows): at t = 0 the start; its rate is the energy's, `th'^2 / 2 + k sin th`
/// constant, to rounding; its angle's difference quotient is its rate; and it agrees with
/// the reduction integrated by DOPRI5 at 1e-13 over the 3 s of these tests.
#[test]
fn quadrature_reference_is_the_reduction() {
    let a = FourBarAssembly::benchmark();
    let r = fa::Reduced::of(&a);
    let k = r.moment / r.inertia;
    let integrated = fa::reference(&a, 1.0, T1).unwrap();
    let (th0, w0) = r.exact(-1.0, 0.0);
    assert!((th0 - std::f64::consts::FRAC_PI_2).abs() < 1e-15 && (w0 + 1.0).abs() < 1e-15);
    let energy = 0.5 + k;
    let mut worst: f64 = 0.0;
    for i in 0..=300 {
        let t = T1 * i as f64 / 300.0;
        let (th, w) = r.exact(-1.0, t);
        let e = 0.5 * w * w + k * th.sin();
        assert!(
            (e - energy).abs() < 1e-13 * energy,
            "t = {t}: energy {e} vs {energy}"
        );
        let d = 1e-5;
        let quotient = (r.exact(-1.0, t + d).0 - r.exact(-1.0, t - d).0) / (2.0 * d);
        assert!(
            (quotient - w).abs() < 1e-8 * w.abs().max(1.0),
            "t = {t}: {quotient} vs {w}"
        );
        worst = worst.max((integrated.at(t).unwrap()[0] - th).abs());
    }
    assert!(worst < 1e-9, "{worst:e}");
}

/// DOPRI5 through the ordinary solve over the first 3 s (three flat positions), against
/// the quadrature reference: the error converges with the tolerance, at least eightfold a
/// decade from 1e-7 to 1e-11 (measured 4.7e-6, 4.4e-7, 4.0e-8, 3.7e-9, 2.4e-10: 10.8,
/// 10.9, 10.8, 15.7), and no run returns `Ok` off the parallelogram. At 1e-12, the one
/// setting that also bridges the passage at 0.72 s, it reaches the floor (measured
/// 6.4e-11; docs/STABILITY.md). The closure rows cancel the pins' ground offsets before
/// the cosines (rounding 4e-16, was 7e-15), the bridge's solves are refined and the
/// instant is placed on a smooth measure; before, 1e-11 gave 4.0e-9 and 1e-12 1.9e-9.
#[test]
fn dopri5_error_converges_with_the_tolerance_to_the_floor() {
    use mbd::integrate::Integrator;
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let error = |tol: f64| {
        let sol = Dopri5::new(options(tol))
            .solve(&a, 0.0, y0, T1, &[])
            .unwrap();
        let spread = sol.y.iter().map(|y| a.spread(y).0).fold(0.0, f64::max);
        assert!(spread < 1e-6, "{tol:e}: cranks {spread:e} apart");
        let err = fa::tip_error_exact(&a, &sol, 1.0, T1, 60);
        eprintln!(
            "DOPRI5 {tol:e}: tip error {err:e}, {} passages",
            sol.passages.len()
        );
        err
    };
    let errors: Vec<f64> = [1e-7, 1e-8, 1e-9, 1e-10, 1e-11]
        .into_iter()
        .map(error)
        .collect();
    for pair in errors.windows(2) {
        assert!(pair[1] < 0.125 * pair[0], "{errors:?}");
    }
    let err = error(1e-12);
    assert!(err < 1e-10, "1e-12: {err:e}");
}
