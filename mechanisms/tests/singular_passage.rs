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
/// (`|sin th| < 1e-2`: within 2.5e-3 s at the 4 rad/s the cranks turn there; the index-1
/// stops are measured within 1e-5 s, a Newton failure's instant is extrapolated from the
/// rank measure, measured 7e-4 s off) with its 40 lost rows named.
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
            th.sin().abs() < 1e-2,
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

/// The assembly with its closure residual written by hand in a form without cancellation:
/// loop `i` closes where coupler `i`'s tip (crank `i` at `c_i` from the pin at `i l`, then
/// the coupler at the absolute angle `s = c_i + k_i`) meets crank `i + 1`'s tip (pin at
/// `(i + 1) l`): `l (cos c_i + cos s - 1 - cos c_{i+1})` and `l (sin c_i + sin s - sin
/// c_{i+1})`, with `cos a - cos b = -2 sin((a + b)/2) sin((a - b)/2)`, `sin a - sin b = 2
/// cos((a + b)/2) sin((a - b)/2)` and `cos s - 1 = -2 sin^2(s/2)`. The generated residual
/// sums the pins' ground positions (up to 40 m: rounding 7e-15); this one rounds relative
/// to its own size, so a state rebuilt on it lies on the exact constraints to rounding.
struct HandResidual<'a>(&'a FourBarAssembly);

impl mbd::Mechanism<{ fa::N }> for HandResidual<'_> {
    const COORDINATES: [&'static str; fa::N] =
        <FourBarAssembly as mbd::Mechanism<{ fa::N }>>::COORDINATES;
    fn mass_matrix(&self, t: f64, q: &mbd::Vector<{ fa::N }>) -> mbd::Matrix<{ fa::N }, { fa::N }> {
        self.0.mass_matrix(t, q)
    }
    fn forces(
        &self,
        t: f64,
        q: &mbd::Vector<{ fa::N }>,
        qd: &mbd::Vector<{ fa::N }>,
    ) -> mbd::Vector<{ fa::N }> {
        self.0.forces(t, q, qd)
    }
    fn acceleration(
        &self,
        t: f64,
        q: &mbd::Vector<{ fa::N }>,
        qd: &mbd::Vector<{ fa::N }>,
    ) -> mbd::Result<mbd::Vector<{ fa::N }>> {
        self.0.acceleration(t, q, qd)
    }
    fn energy(&self, t: f64, q: &mbd::Vector<{ fa::N }>, qd: &mbd::Vector<{ fa::N }>) -> f64 {
        self.0.energy(t, q, qd)
    }
}

impl mbd::Constrained<{ fa::N }, { fa::M }> for HandResidual<'_> {
    fn phi(&self, _t: f64, q: &mbd::Vector<{ fa::N }>) -> mbd::Vector<{ fa::M }> {
        let l = self.0.l;
        let mut p = mbd::Vector::<{ fa::M }>::zeros();
        for i in 0..fa::LOOPS {
            let (a, b, s) = (q[2 * i], q[2 * i + 2], q[2 * i] + q[2 * i + 1]);
            let (mean, half) = (0.5 * (a + b), 0.5 * (a - b));
            p[2 * i] = l * (-2.0 * mean.sin() * half.sin() - 2.0 * (0.5 * s).sin().powi(2));
            p[2 * i + 1] = l * (2.0 * mean.cos() * half.sin() + s.sin());
        }
        p
    }
    fn phi_q(&self, t: f64, q: &mbd::Vector<{ fa::N }>) -> mbd::Matrix<{ fa::M }, { fa::N }> {
        self.0.phi_q(t, q)
    }
    fn phi_t(&self, t: f64, q: &mbd::Vector<{ fa::N }>) -> mbd::Vector<{ fa::M }> {
        self.0.phi_t(t, q)
    }
    fn gamma(
        &self,
        t: f64,
        q: &mbd::Vector<{ fa::N }>,
        qd: &mbd::Vector<{ fa::N }>,
    ) -> mbd::Vector<{ fa::M }> {
        self.0.gamma(t, q, qd)
    }
    fn acceleration_and_multipliers(
        &self,
        t: f64,
        q: &mbd::Vector<{ fa::N }>,
        qd: &mbd::Vector<{ fa::N }>,
    ) -> mbd::Result<(mbd::Vector<{ fa::N }>, mbd::Vector<{ fa::M }>)> {
        self.0.acceleration_and_multipliers(t, q, qd)
    }
}

/// The parallelogram state with every crank at `th` turning at `w` (couplers translating).
fn parallelogram(th: f64, w: f64) -> mbd::Vector<{ fa::D }> {
    mbd::Vector::<{ fa::D }>::from_fn(|i, _| {
        let crank = (i % fa::N) % 2 == 0;
        let value = if i < fa::N { th } else { w };
        if crank { value } else { -value }
    })
}

/// The right-hand side the bridge integrates (`mbd::partition::Partitioned`) near a flat
/// position, against the reduction: on the parallelogram at `d` rad from flat, turning at
/// the energy's rate, every crank's acceleration is `th'' = -k cos d` (module docs). Its
/// rates and accelerations come from a QR of `Phi_d`, whose condition grows like `1/d`; the
/// rates' error goes into `gamma` and is divided by `d` again. Unrefined it was 8e-11 off at
/// 0.1 rad, 1.2e-9 at 0.03 and 4.8e-8 at 3e-3; refined against residuals summed in twice
/// the precision, 1e-12 .. 3e-11 (the index-1 solve's own accuracy on these states). The
/// residual is the hand-written one above, so that the positions rebuilt are the exact
/// ones: with the generated residual's 7e-15 rounding, the positions move by `7e-15 / d`
/// and the accelerations by that over `d^2` (3.6e-8 at 1e-2 rad).
#[test]
fn partitioned_accelerations_near_flat_match_the_reduction() {
    use mbd::OdeSystem;
    let a = FourBarAssembly::benchmark();
    let hand = HandResidual(&a);
    let r = fa::Reduced::of(&a);
    let k = r.moment / r.inertia;
    let start = parallelogram(0.05, -4.0)
        .fixed_rows::<{ fa::N }>(0)
        .into_owned();
    let view =
        mbd::partition::Partitioned::<_, { fa::N }, { fa::M }>::new(&hand, 0.0, &start, fa::M)
            .unwrap();
    for d in [0.1, 0.03, 0.01, 3e-3] {
        // Turned by pi/2 - d from the start's th = pi/2, th' = -1.
        let w = -(1.0 + 4.0 * k * (0.5 * (std::f64::consts::FRAC_PI_2 - d)).sin().powi(2)).sqrt();
        view.forget();
        let f = view.rhs(0.0, &parallelogram(d, w)).unwrap();
        let worst = (0..=fa::LOOPS)
            .map(|i| {
                (f[fa::N + 2 * i] + k * d.cos())
                    .abs()
                    .max((f[2 * i] - w).abs())
            })
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-10,
            "d = {d}: cranks' accelerations or rates {worst:e} off"
        );
    }
}

/// DOPRI5 through the ordinary solve over the first 3 s (three flat positions), against
/// the quadrature reference: the error converges with the tolerance, at least fourfold a
/// decade from 1e-7 to 1e-10 (measured 4.1e-8 at 1e-9, 3.8e-9 at 1e-10), and no run
/// returns `Ok` off the parallelogram. From 1e-11 on it stops falling: each step across a
/// flat position carries the generated closure residual's rounding (7e-15, the pins' ground
/// positions up to 40 m) into the rebuilt positions over the distance `d` from flat, and
/// into the accelerations over `d^3` (the test above: exact with a residual written
/// without cancellation), about `1e-10` rad/s per passage, which the slow turn over the
/// top multiplies; measured 1.2e-9 at 1e-11 and 1.6e-9 .. 5.8e-9 at 1e-12 (docs/STABILITY.md).
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
    let errors: Vec<f64> = [1e-7, 1e-8, 1e-9, 1e-10].into_iter().map(error).collect();
    for pair in errors.windows(2) {
        assert!(pair[1] < 0.25 * pair[0], "{errors:?}");
    }
    for tol in [1e-11, 1e-12] {
        let err = error(tol);
        assert!(err < 1e-8, "{tol:e}: {err:e}");
    }
}
