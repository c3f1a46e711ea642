//! Work-precision sweeps: the error of the measured quantities against their exact
//! references, against the work (wall time, steps, right-hand-side and Jacobian evaluations)
//! each integrator spends, for every model that integrates in time.
//!
//! A [`Problem`] runs one model with one [`Setting`] (a method and its step size or
//! tolerance) and returns the [`Measured`] quantities with their references, which are the
//! exact or corrected values the cases' own tests use (`caseNN::references()`), or, for the
//! three zero-overhead models of [`crate::handwritten`], closed forms derived here
//! ([`OneDof`], and the reversibility and energy of the double pendulum). The error of a run
//! is the largest relative error of its quantities ([`Measured::error`]).
//!
//! [`sweep`] runs a problem over a method's settings and times each run ([`time_runs`]:
//! median over repeats of batches long enough for the clock). [`time_to_reach`] reads the
//! time to reach an error off a curve, interpolating in log-log on its Pareto front.
//!
//! Every run takes its model's parameters through [`std::hint::black_box`]: they are runtime
//! data, as in an application, and the compiler cannot fold them into the code (which it does
//! unevenly: a hand-written `-(g/l) sin θ` with constant `g/l` loses its division, the
//! generated mass-matrix solve does not).
//!
//! The binary `work-precision` drives it all and writes the report.

use crate::handwritten::{
    self, DoublePendulum, DoublePendulumByHand, Pendulum, PendulumByHand, SliderCrank,
    SliderCrankByHand,
};
use crate::{
    case01_vertical_throw as c01, case05_crate_on_incline as c05, case07_collar_spring as c07,
    case08_slider_bumper as c08, case09_rotating_tube as c09, case10_pendulum_on_cart as c10,
    case19_slider_crank_max_speed as c19, case20_pendulum_bearing as c20,
    case23_block_reversing_torque as c23, case26_crank_bar_released as c26,
    case27_bar_spring_released as c27, case28_falling_bar_spring as c28,
    case30_damped_vibration as c30,
};
use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use mbd::analysis::{NewtonOptions, kinematics};
use mbd::integrate::{
    Dop853, Dopri5, Event, EventHit, GeneralizedAlpha, Integrator, Radau5, Rk4, Solution, Vern9,
};
use mbd::{Constrained, OdeSystem, Options, Stats, Vector};
use std::cell::Cell;
use std::fmt;
use std::hint::black_box;
use std::sync::OnceLock;
use std::time::Instant;

/// An integration method of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// mbd's classic RK4, swept over the step size.
    Rk4,
    /// mbd's Dormand–Prince 5(4), swept over `rtol = atol`.
    Dopri5,
    /// mbd's Dormand–Prince 8(5,3), swept over `rtol = atol`.
    Dop853,
    /// mbd's Verner 9(8), swept over `rtol = atol`.
    Vern9,
    /// mbd's Dormand–Prince 5(4) without the projection onto the constraint manifolds
    /// (the same algorithm as the peer's, for the comparison on the slider-crank).
    Dopri5NoProjection,
    /// mbd's Radau IIA 5, swept over `rtol = atol`.
    Radau5,
    /// mbd's generalized-α (`ρ∞ = `[`RHO_INF`]), swept over the step size.
    GeneralizedAlpha,
    /// The peer: `differential-equations`' DOPRI5 on the same generated right-hand side.
    PeerDopri5,
}

/// Spectral radius at infinity of the generalized-α runs.
pub const RHO_INF: f64 = 0.9;

impl Method {
    /// The mbd methods every case is swept with.
    pub const MBD: [Method; 6] = [
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
        Method::Vern9,
        Method::Radau5,
        Method::GeneralizedAlpha,
    ];

    /// Name for reports.
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "RK4",
            Method::Dopri5 => "DOPRI5",
            Method::Dop853 => "DOP853",
            Method::Vern9 => "VERN9",
            Method::Dopri5NoProjection => "DOPRI5 (no projection)",
            Method::Radau5 => "Radau5",
            Method::GeneralizedAlpha => "generalized-alpha",
            Method::PeerDopri5 => "differential-equations DOPRI5",
        }
    }

    /// Whether the method takes fixed steps (swept over `h`) rather than a tolerance.
    pub fn fixed_step(self) -> bool {
        matches!(self, Method::Rk4 | Method::GeneralizedAlpha)
    }

    /// The sweep's settings. Adaptive methods: `rtol = atol = 1e-3 .. 1e-12`. Fixed-step
    /// methods: `h = span / n`, `n = 4 .. 4096` (RK4) or `8 .. 131072` (generalized-α, of
    /// order 2), doubling, where `span` is the problem's integrated time.
    pub fn settings(self, span: f64) -> Vec<Setting> {
        let make = |value| Setting {
            method: self,
            value,
        };
        match self {
            Method::Rk4 => (2..=12)
                .map(|k| make(span / f64::from(1u32 << k)))
                .collect(),
            Method::GeneralizedAlpha => (3..=17)
                .map(|k| make(span / f64::from(1u32 << k)))
                .collect(),
            _ => (3..=12).map(|k| make(10f64.powi(-k))).collect(),
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One point of a sweep: a method and its step size (fixed-step methods) or `rtol = atol`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting {
    pub method: Method,
    /// `h`, or `rtol = atol`.
    pub value: f64,
}

impl Setting {
    /// `h=1.953e-3` or `tol=1e-6`.
    pub fn label(&self) -> String {
        if self.method.fixed_step() {
            format!("h={:.4e}", self.value)
        } else {
            format!("tol={:.0e}", self.value)
        }
    }

    fn adaptive_options(&self, project: bool) -> Options {
        Options {
            rtol: self.value,
            atol: self.value,
            dense: false,
            project,
            ..Options::default()
        }
    }
}

/// Why a run produced no error figure.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// The method cannot run this model (the reason).
    Unsupported(String),
    /// The run failed (an integrator error, or an event that was not found).
    Failed(String),
}

impl From<mbd::Error> for Failure {
    fn from(e: mbd::Error) -> Self {
        Failure::Failed(e.to_string())
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Unsupported(why) => write!(f, "skipped: {why}"),
            Failure::Failed(why) => write!(f, "failed: {why}"),
        }
    }
}

/// A measured quantity and its exact reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quantity {
    pub name: &'static str,
    pub value: f64,
    pub reference: f64,
}

impl Quantity {
    /// `|value − reference| / |reference|` (the absolute error for a zero reference).
    pub fn relative_error(&self) -> f64 {
        let e = (self.value - self.reference).abs();
        if self.reference == 0.0 {
            e
        } else {
            e / self.reference.abs()
        }
    }
}

/// What one run measured, and the work it took.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub quantities: Vec<Quantity>,
    /// Work counters summed over the run's integrations. `n_rhs` counts every call of the
    /// right-hand side, those of finite-difference Jacobians included (generalized-α: its
    /// residual evaluations).
    pub stats: Stats,
    /// The time integrated, summed over the run's integrations.
    pub span: f64,
}

impl Measured {
    /// The largest relative error of the quantities (NaN counts as infinite).
    pub fn error(&self) -> f64 {
        self.quantities
            .iter()
            .map(|q| {
                let e = q.relative_error();
                if e.is_nan() { f64::INFINITY } else { e }
            })
            .fold(0.0, f64::max)
    }
}

fn q(name: &'static str, value: f64, reference: f64) -> Quantity {
    Quantity {
        name,
        value,
        reference,
    }
}

fn add(a: Stats, b: Stats) -> Stats {
    Stats {
        n_rhs: a.n_rhs + b.n_rhs,
        n_jac: a.n_jac + b.n_jac,
        n_lu: a.n_lu + b.n_lu,
        n_steps: a.n_steps + b.n_steps,
        n_accepted: a.n_accepted + b.n_accepted,
        n_rejected: a.n_rejected + b.n_rejected,
    }
}

const GA_NEEDS_MECHANISM: &str =
    "generalized-alpha needs the second-order form M(q) q'' = f of a Mechanism";
const PEER_ONLY: &str = "the peer runs only on the pendulum and the slider-crank";

/// Integrate a first-order system with the setting's method (not generalized-α, which
/// needs a [`mbd::Mechanism`]).
pub fn solve_ode<S: OdeSystem<D>, const D: usize>(
    s: &Setting,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
) -> Result<Solution<D>, Failure> {
    let mut sol = match s.method {
        Method::Rk4 => Rk4::new(s.value).solve(sys, t0, y0, t1, events),
        Method::Dopri5 => Dopri5::new(s.adaptive_options(true)).solve(sys, t0, y0, t1, events),
        Method::Dop853 => Dop853::new(s.adaptive_options(true)).solve(sys, t0, y0, t1, events),
        Method::Vern9 => Vern9::new(s.adaptive_options(true)).solve(sys, t0, y0, t1, events),
        Method::Dopri5NoProjection => {
            Dopri5::new(s.adaptive_options(false)).solve(sys, t0, y0, t1, events)
        }
        Method::Radau5 => Radau5::new(s.adaptive_options(true)).solve(sys, t0, y0, t1, events),
        Method::GeneralizedAlpha => return Err(Failure::Unsupported(GA_NEEDS_MECHANISM.into())),
        Method::PeerDopri5 => return Err(Failure::Unsupported(PEER_ONLY.into())),
    }?;
    if s.method == Method::Radau5 && !S::EXACT_JACOBIAN {
        // Radau5 counts its own calls only (as radau5.f); each forward-difference
        // Jacobian makes D + 1 more.
        sol.stats.n_rhs += sol.stats.n_jac * (D + 1);
    }
    Ok(sol)
}

fn split<const N: usize, const D: usize>(y: &Vector<D>) -> (Vector<N>, Vector<N>) {
    (
        y.fixed_rows::<N>(0).into_owned(),
        y.fixed_rows::<N>(N).into_owned(),
    )
}

/// Integrate an unconstrained mechanism; generalized-α runs its second-order form.
pub fn solve_mechanism<S: OdeSystem<D> + mbd::Mechanism<N>, const N: usize, const D: usize>(
    s: &Setting,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
) -> Result<Solution<D>, Failure> {
    if s.method == Method::GeneralizedAlpha {
        let (q0, qd0) = split::<N, D>(&y0);
        Ok(GeneralizedAlpha::new(RHO_INF, s.value).solve(sys, t0, q0, qd0, t1, events)?)
    } else {
        solve_ode(s, sys, t0, y0, t1, events)
    }
}

/// Integrate a closed loop (`A = N + M`); generalized-α runs its index-3 form.
pub fn solve_loop<
    S: OdeSystem<D> + Constrained<N, M>,
    const N: usize,
    const M: usize,
    const A: usize,
    const D: usize,
>(
    s: &Setting,
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'_, D>],
) -> Result<Solution<D>, Failure> {
    if s.method == Method::GeneralizedAlpha {
        let (q0, qd0) = split::<N, D>(&y0);
        Ok(GeneralizedAlpha::new(RHO_INF, s.value)
            .solve_constrained::<S, N, M, A, D>(sys, t0, q0, qd0, t1, events)?)
    } else {
        solve_ode(s, sys, t0, y0, t1, events)
    }
}

fn event<const D: usize>(
    sol: &Solution<D>,
    index: usize,
    what: &str,
) -> Result<EventHit<D>, Failure> {
    sol.events
        .iter()
        .find(|e| e.event == index)
        .cloned()
        .ok_or_else(|| Failure::Failed(format!("{what} was not found")))
}

fn measured<const D: usize>(quantities: Vec<Quantity>, sols: &[&Solution<D>]) -> Measured {
    Measured {
        quantities,
        stats: sols.iter().fold(Stats::default(), |a, s| add(a, s.stats)),
        span: sols.iter().map(|s| s.last().0 - s.t[0]).sum(),
    }
}

/// A model swept by the report.
#[derive(Debug, Clone, Copy)]
pub struct Problem {
    /// Name in the report (`case01`, `pendulum`, `pendulum (hand-written)`, ...).
    pub name: &'static str,
    /// What is measured.
    pub title: &'static str,
    /// The methods to sweep.
    pub methods: &'static [Method],
    /// One run.
    pub run: fn(&Setting) -> Result<Measured, Failure>,
}

const PEER_METHODS: [Method; 7] = [
    Method::Rk4,
    Method::Dopri5,
    Method::Dop853,
    Method::Vern9,
    Method::Radau5,
    Method::GeneralizedAlpha,
    Method::PeerDopri5,
];
const PEER_METHODS_LOOP: [Method; 8] = [
    Method::Rk4,
    Method::Dopri5,
    Method::Dop853,
    Method::Vern9,
    Method::Dopri5NoProjection,
    Method::Radau5,
    Method::GeneralizedAlpha,
    Method::PeerDopri5,
];

/// The cases of the validation manual whose measured quantities come from a forward-
/// dynamics integration.
pub fn cases() -> Vec<Problem> {
    let p = |name, title, run| Problem {
        name,
        title,
        methods: &Method::MBD,
        run,
    };
    vec![
        p("case01", "vertical throw: h, t_AB, v_B (events)", case01),
        p(
            "case05",
            "crate on an incline with friction: stop time and distance (event)",
            case05,
        ),
        p("case07", "collar pulled by a spring: v_B (event)", case07),
        p(
            "case08",
            "slider into a bumper: v_B, largest deflection (two phases, events)",
            case08,
        ),
        p(
            "case09",
            "particle leaving a rotating tube: exit time and angle (event)",
            case09,
        ),
        p(
            "case10",
            "pendulum on a free cart: θ', v_x at the bottom (event)",
            case10,
        ),
        p(
            "case19",
            "driven slider-crank: v_A,max and its crank angle (event, 2 constraints)",
            case19,
        ),
        p(
            "case20",
            "pendulum bearing force at 60° (event, reactions)",
            case20,
        ),
        p(
            "case23",
            "block turned by a reversing torque: t_90 (two phases, events)",
            case23,
        ),
        p(
            "case26",
            "crank and bar released: v_B at the vertical (event, 1 constraint)",
            case26,
        ),
        p(
            "case27",
            "bar with a spring: ω_max and its angle (event on θ'')",
            case27,
        ),
        p(
            "case28",
            "falling bar with a spring: ω_min, its angle, ω(90°) (events)",
            case28,
        ),
        p(
            "case30",
            "damped vibration: x after half a damped cycle (event)",
            case30,
        ),
    ]
    .into_iter()
    .chain(crate::stick_slip::problems())
    .chain(crate::loop_rows::problems())
    .collect()
}

/// The cases left out, and why.
pub fn excluded_cases() -> Vec<(&'static str, &'static str)> {
    let kinematic = "kinematic or instantaneous analysis: no time integration";
    vec![
        ("case02", kinematic),
        ("case03", kinematic),
        (
            "case04",
            "no state: the events lie on a prescribed motion (the integrator is only a clock)",
        ),
        (
            "case06",
            "measured from the generated outputs at t = 0; the integration only draws the plot",
        ),
        ("case11", kinematic),
        ("case12", kinematic),
        ("case13", kinematic),
        ("case14", kinematic),
        ("case15", kinematic),
        ("case16", kinematic),
        ("case17", kinematic),
        ("case18", kinematic),
        (
            "case21",
            "measured from the generated outputs at t = 0; the integration only draws the plot",
        ),
        ("case22", kinematic),
        ("case24", kinematic),
        ("case25", kinematic),
        ("case29", kinematic),
    ]
}

/// The zero-overhead models, generated and hand-written, in pairs `(generated, hand-written)`.
pub fn zero_overhead() -> Vec<(Problem, Problem)> {
    vec![
        (
            Problem {
                name: "pendulum",
                title: PENDULUM_TITLE,
                methods: &PEER_METHODS,
                run: pendulum_generated,
            },
            Problem {
                name: "pendulum (hand-written)",
                title: PENDULUM_TITLE,
                methods: &Method::MBD,
                run: pendulum_by_hand,
            },
        ),
        (
            Problem {
                name: "double pendulum",
                title: DOUBLE_TITLE,
                methods: &Method::MBD,
                run: double_generated,
            },
            Problem {
                name: "double pendulum (hand-written)",
                title: DOUBLE_TITLE,
                methods: &Method::MBD,
                run: double_by_hand,
            },
        ),
        (
            Problem {
                name: "slider-crank",
                title: SLIDER_TITLE,
                methods: &PEER_METHODS_LOOP,
                run: slider_generated,
            },
            Problem {
                name: "slider-crank (hand-written)",
                title: SLIDER_TITLE,
                methods: &Method::MBD,
                run: slider_by_hand,
            },
        ),
    ]
}

// ---------------------------------------------------------------------------------------
// The cases: each reruns its case's measurement with the setting's method, against the
// case's own references.

fn case01(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c01::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 10.0, &events)?;
    let apex = event(&sol, 0, "the apex")?;
    let at_b = event(&sol, 1, "the passage at B")?;
    let [h, t_ab, v_b] = c01::references();
    let speed = model.outputs(at_b.t, &at_b.y)?.speed;
    Ok(measured(
        vec![
            q("h", apex.y[0] - model.b, h),
            q("t_AB", at_b.t, t_ab),
            q("v_B", speed, v_b),
        ],
        &[&sol],
    ))
}

fn case05(s: &Setting) -> Result<Measured, Failure> {
    if s.method == Method::GeneralizedAlpha {
        return Err(Failure::Unsupported(
            "Coulomb friction: the smooth sliding view is a first-order system only (the plain \
             model runs mode by mode with generalized-alpha: the stick-slip rows)"
                .into(),
        ));
    }
    let model = black_box(c05::MODEL);
    let events = model.events();
    let sliding = model.sliding([1.0]);
    let sol = solve_ode(s, &sliding, 0.0, model.initial_state(), 20.0, &events)?;
    let stop = event(&sol, 0, "the stop")?;
    let [t_stop, x_stop] = c05::references();
    Ok(measured(
        vec![
            q("t_stop_15", stop.t, t_stop),
            q("x_stop_15", stop.y[0], x_stop),
        ],
        &[&sol],
    ))
}

fn case07(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c07::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 5.0, &events)?;
    let at_b = event(&sol, 0, "the arrival at B")?;
    let [v_b] = c07::references();
    Ok(measured(
        vec![q("v_B", model.outputs(at_b.t, &at_b.y)?.speed, v_b)],
        &[&sol],
    ))
}

fn case08(s: &Setting) -> Result<Measured, Failure> {
    let (guide_model, bumper) = black_box((c08::MODEL, c08::BUMPER));
    let guide_events = guide_model.events();
    let guide = solve_mechanism::<_, 1, 2>(
        s,
        &guide_model,
        0.0,
        guide_model.initial_state(),
        10.0,
        &guide_events,
    )?;
    let lowest = event(&guide, 0, "the lowest point")?;
    let contact = event(&guide, 1, "the contact with the bumper")?;
    let bump_events = bumper.events();
    let bump = solve_mechanism::<_, 1, 2>(s, &bumper, 0.0, contact.y, 1.0, &bump_events)?;
    let stop = event(&bump, 0, "the largest deflection")?;
    // As the case does: the deflection from a run that ends at the located event time.
    let to_stop = solve_mechanism::<_, 1, 2>(s, &bumper, 0.0, contact.y, stop.t, &[])?;
    let delta = bumper.outputs(stop.t, to_stop.last().1)?.deflection_mm;
    let v_b = guide_model.outputs(lowest.t, &lowest.y)?.speed;
    let [v_b_exact, delta_exact] = c08::references();
    Ok(measured(
        vec![q("v_B", v_b, v_b_exact), q("delta", delta, delta_exact)],
        &[&guide, &bump, &to_stop],
    ))
}

fn case09(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c09::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 10.0, &events)?;
    let exit = event(&sol, 0, "the exit")?;
    let [t_exit, theta_exit] = c09::references();
    Ok(measured(
        vec![
            q("t_exit", exit.t, t_exit),
            q(
                "theta_exit",
                model.outputs(exit.t, &exit.y)?.theta_deg,
                theta_exit,
            ),
        ],
        &[&sol],
    ))
}

fn case10(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c10::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 2, 4>(s, &model, 0.0, model.initial_state(), 10.0, &events)?;
    let bottom = event(&sol, 0, "the lowest position")?;
    let o = model.outputs(bottom.t, &bottom.y)?;
    let [theta_dot, v_x] = c10::references();
    Ok(measured(
        vec![q("theta_dot", o.theta_dot, theta_dot), q("v_x", o.v_x, v_x)],
        &[&sol],
    ))
}

fn case19(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c19::MODEL);
    // The case's start: the state at t = 0 by kinematic analysis from the init guess.
    let guess = model.initial_state().fixed_rows::<2>(0).into_owned();
    let k = kinematics(&model, 0.0, &guess, &NewtonOptions::default())?;
    let y0 = Vector::<4>::new(k.q[0], k.q[1], k.qd[0], k.qd[1]);
    let turn = 2.0 * std::f64::consts::PI / model.omega;
    let events = model.events();
    let sol = solve_loop::<_, 2, 2, 4, 4>(s, &model, 0.0, y0, turn, &events)?;
    let at_max = event(&sol, 0, "the maximum piston speed")?;
    let found = model.outputs(at_max.t, &at_max.y)?;
    let [v_max, theta_max] = c19::references();
    Ok(measured(
        vec![
            q("v_A_max", found.v_a, v_max),
            q("theta_at_v_A_max", found.crank_angle, theta_max),
        ],
        &[&sol],
    ))
}

fn case20(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c20::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 2.0, &events)?;
    let at_60 = event(&sol, 0, "the 60° position")?;
    let [r_o] = c20::references();
    Ok(measured(
        vec![q("R_O", model.outputs(at_60.t, &at_60.y)?.r_o, r_o)],
        &[&sol],
    ))
}

fn case23(s: &Setting) -> Result<Measured, Failure> {
    let (model, reversed) = black_box((c23::MODEL, c23::REVERSED));
    let events = model.events();
    let first =
        solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 200.0, &events[..1])?;
    let switch = event(&first, 0, "the 45° switch")?;
    let events = reversed.events();
    // Phase 2 watches only the stop (its event index 1 is 0 in the slice).
    let second = solve_mechanism::<_, 1, 2>(s, &reversed, 0.0, switch.y, 200.0, &events[1..])?;
    let stop = event(&second, 0, "the stop")?;
    let [t_90] = c23::references();
    Ok(measured(
        vec![q("t_90deg", switch.t + stop.t, t_90)],
        &[&first, &second],
    ))
}

fn case26(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c26::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 2.0, &events)?;
    let hit = event(&sol, 0, "OA vertical")?;
    let [v_b] = c26::references();
    Ok(measured(
        vec![q("v_B", model.outputs(hit.t, &hit.y)?.v_b, v_b)],
        &[&sol],
    ))
}

fn case27(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c27::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 5.0, &events)?;
    let fastest = event(&sol, 0, "the maximum angular speed")?;
    let [omega, theta] = c27::references();
    Ok(measured(
        vec![
            q(
                "omega_max",
                model.outputs(fastest.t, &fastest.y)?.omega,
                omega,
            ),
            q("theta_at_omega_max", fastest.y[0].to_degrees(), theta),
        ],
        &[&sol],
    ))
}

fn case28(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c28::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 5.0, &events)?;
    let slowest = event(&sol, 0, "the minimum angular speed")?;
    let horizontal = event(&sol, 1, "the horizontal")?;
    let [omega_min, theta, omega_90] = c28::references();
    Ok(measured(
        vec![
            q(
                "omega_min",
                model.outputs(slowest.t, &slowest.y)?.omega,
                omega_min,
            ),
            q("theta_at_omega_min", slowest.y[0].to_degrees(), theta),
            q(
                "omega_at_90deg",
                model.outputs(horizontal.t, &horizontal.y)?.omega,
                omega_90,
            ),
        ],
        &[&sol],
    ))
}

fn case30(s: &Setting) -> Result<Measured, Failure> {
    let model = black_box(c30::MODEL);
    let events = model.events();
    let sol = solve_mechanism::<_, 1, 2>(s, &model, 0.0, model.initial_state(), 5.0, &events)?;
    let extreme = event(&sol, 0, "the turning point")?;
    let [x_1] = c30::references();
    Ok(measured(vec![q("x_1", extreme.y[0], x_1)], &[&sol]))
}

// ---------------------------------------------------------------------------------------
// References of the zero-overhead models.

/// Composite Gauss–Legendre quadrature of `f` over `[a, b]`, five points on each of
/// `panels` equal panels (exact for polynomials of degree 9 on each panel). Nodes and
/// weights in closed form: `0`, `±(1/3) sqrt(5 ∓ 2 sqrt(10/7))`;
/// `128/225`, `(322 ± 13 sqrt 70)/900`.
pub fn gauss_legendre(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let s = (10.0f64 / 7.0).sqrt();
    let (x1, x2) = ((5.0 - 2.0 * s).sqrt() / 3.0, (5.0 + 2.0 * s).sqrt() / 3.0);
    let r70 = 70f64.sqrt();
    let (w0, w1, w2) = (
        128.0 / 225.0,
        (322.0 + 13.0 * r70) / 900.0,
        (322.0 - 13.0 * r70) / 900.0,
    );
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|i| {
            let c = a + (i as f64 + 0.5) * h;
            let r = 0.5 * h;
            let sum = w0 * f(c)
                + w1 * (f(c - r * x1) + f(c + r * x1))
                + w2 * (f(c - r * x2) + f(c + r * x2));
            sum * r
        })
        .sum()
}

/// A conservative system of one degree of freedom released from rest at `theta_0`, with
/// generalised inertia `J(θ)`, swinging between the turning points `theta_0` and
/// `theta_other < theta_0`. `gap(θ, d0, d1)` is the energy gap `V(θ_0) − V(θ)`, given also
/// `d0 = θ_0 − θ` and `d1 = θ − θ_other` to full relative precision, so that it can be
/// written without cancellation near the turning points.
///
/// By energy, `θ'² = 2 (V(θ_0) − V(θ)) / J(θ)`, and the time from `θ_0` to `θ` is
/// `∫ dθ / |θ'|`. With `θ = θ_c + A cos u` (`θ_c`, `A` the centre and half-width of the
/// swing, `u` from 0 at `θ_0` to π at `θ_other`), `d0 = 2 A sin²(u/2)`,
/// `d1 = 2 A cos²(u/2)` and `dθ = −A sin u du`: the inverse-square-root singularities at the
/// turning points cancel, and [`gauss_legendre`] integrates smooth functions, on `[0, π/2]`
/// in `u` and, for the other half, in `v = π − u`, each end computed where it is accurate.
#[derive(Debug, Clone, Copy)]
pub struct OneDof<J, G> {
    pub inertia: J,
    pub gap: G,
    pub theta_0: f64,
    pub theta_other: f64,
}

/// Panels of the reference quadratures on each half swing (a test checks that doubling them
/// changes nothing).
pub const PANELS: usize = 200;

impl<J: Fn(f64) -> f64, G: Fn(f64, f64, f64) -> f64> OneDof<J, G> {
    fn half_width(&self) -> f64 {
        0.5 * (self.theta_0 - self.theta_other)
    }

    /// `|θ'|` at θ.
    pub fn speed(&self, theta: f64) -> f64 {
        self.speed_at(theta, self.theta_0 - theta, theta - self.theta_other)
    }

    fn speed_at(&self, theta: f64, d0: f64, d1: f64) -> f64 {
        (2.0 * (self.gap)(theta, d0, d1) / (self.inertia)(theta)).sqrt()
    }

    /// `dt/du` on the half next to `theta_0` (`u` in `[0, π/2]`).
    fn near_start(&self, u: f64) -> f64 {
        let a = self.half_width();
        let (d0, d1) = (
            2.0 * a * (0.5 * u).sin().powi(2),
            2.0 * a * (0.5 * u).cos().powi(2),
        );
        a * u.sin() / self.speed_at(self.theta_0 - d0, d0, d1)
    }

    /// `dt/dv` on the half next to `theta_other` (`v = π − u` in `[0, π/2]`).
    fn near_other(&self, v: f64) -> f64 {
        let a = self.half_width();
        let (d0, d1) = (
            2.0 * a * (0.5 * v).cos().powi(2),
            2.0 * a * (0.5 * v).sin().powi(2),
        );
        a * v.sin() / self.speed_at(self.theta_other + d1, d0, d1)
    }

    /// The time from `theta_0` to `theta` (between the turning points), `panels` panels
    /// per half swing.
    pub fn time_to(&self, theta: f64, panels: usize) -> f64 {
        let a = self.half_width();
        let half = std::f64::consts::FRAC_PI_2;
        let (d0, d1) = (self.theta_0 - theta, theta - self.theta_other);
        if d0 <= a {
            let u = 2.0 * (d0 / (2.0 * a)).sqrt().asin();
            gauss_legendre(|u| self.near_start(u), 0.0, u, panels)
        } else {
            let v = 2.0 * (d1 / (2.0 * a)).sqrt().asin();
            gauss_legendre(|u| self.near_start(u), 0.0, half, panels)
                + gauss_legendre(|v| self.near_other(v), v, half, panels)
        }
    }

    /// The period: twice the time from one turning point to the other.
    pub fn period(&self, panels: usize) -> f64 {
        let half = std::f64::consts::FRAC_PI_2;
        2.0 * (gauss_legendre(|u| self.near_start(u), 0.0, half, panels)
            + gauss_legendre(|v| self.near_other(v), 0.0, half, panels))
    }

    /// `(t, θ, θ')` after `periods` full swings and then the way from `theta_0` to `theta`:
    /// the end of a run and its exact state.
    pub fn state_after(&self, periods: u32, theta: f64, panels: usize) -> (f64, f64, f64) {
        let t = f64::from(periods) * self.period(panels) + self.time_to(theta, panels);
        (t, theta, -self.speed(theta))
    }
}

/// Complete elliptic integral of the first kind `K(k) = π / (2 AGM(1, sqrt(1 − k²)))`.
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..64 {
        if (a - b).abs() <= 1e-16 * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Release angle, end angle and full swings of the pendulum runs.
pub const PENDULUM_RUN: (f64, f64, u32) = (2.0, 1.0, 2);

const PENDULUM_TITLE: &str = "released at 2 rad: θ, θ' after two periods and the swing down to 1 rad \
     (exact by energy and quadrature)";

/// The pendulum's exact motion: `J = m l²`, `V(θ_0) − V(θ) = m g l (cos θ − cos θ_0) =
/// 2 m g l sin((θ_0 − θ)/2) sin((θ_0 + θ)/2)`, turning points `±θ_0` (so `θ_0 + θ = d1`); its
/// period is `4 K(sin(θ_0/2)) / sqrt(g/l)`.
pub fn pendulum_motion(
    p: &Pendulum,
    theta_0: f64,
) -> OneDof<impl Fn(f64) -> f64, impl Fn(f64, f64, f64) -> f64> {
    let (m, l, g) = (p.m, p.l, p.g);
    OneDof {
        inertia: move |_| m * l * l,
        gap: move |_, d0: f64, d1: f64| 2.0 * m * g * l * (0.5 * d0).sin() * (0.5 * d1).sin(),
        theta_0,
        theta_other: -theta_0,
    }
}

/// `(t1, θ(t1), θ'(t1))` of the pendulum runs, computed once (not part of a timed run).
pub fn pendulum_reference() -> (f64, f64, f64) {
    static REFERENCE: OnceLock<(f64, f64, f64)> = OnceLock::new();
    *REFERENCE.get_or_init(|| {
        let (theta_0, theta_1, periods) = PENDULUM_RUN;
        pendulum_motion(&handwritten::PENDULUM, theta_0).state_after(periods, theta_1, PANELS)
    })
}

fn pendulum_run<S: OdeSystem<2> + mbd::Mechanism<1>>(
    s: &Setting,
    sys: &S,
) -> Result<Measured, Failure> {
    let (t1, theta, theta_dot) = pendulum_reference();
    let y0 = Vector::<2>::new(PENDULUM_RUN.0, 0.0);
    let sol = solve_mechanism::<_, 1, 2>(s, sys, 0.0, y0, t1, &[])?;
    let y = sol.last().1;
    Ok(measured(
        vec![q("theta", y[0], theta), q("theta_dot", y[1], theta_dot)],
        &[&sol],
    ))
}

fn pendulum_generated(s: &Setting) -> Result<Measured, Failure> {
    let p = black_box(handwritten::PENDULUM);
    if s.method == Method::PeerDopri5 {
        let (t1, theta, theta_dot) = pendulum_reference();
        let y0 = Vector::<2>::new(PENDULUM_RUN.0, 0.0);
        let (y, stats) = peer_dopri5(&p, 0.0, y0, t1, s.value)?;
        return Ok(Measured {
            quantities: vec![q("theta", y[0], theta), q("theta_dot", y[1], theta_dot)],
            stats,
            span: t1,
        });
    }
    pendulum_run(s, &p)
}

fn pendulum_by_hand(s: &Setting) -> Result<Measured, Failure> {
    pendulum_run(s, &PendulumByHand::from(&black_box(handwritten::PENDULUM)))
}

/// Initial state `[a, b, a', b']` and length of one leg of the double-pendulum round trip.
pub const DOUBLE_RUN: ([f64; 4], f64) = ([0.9, -0.5, 0.4, 1.2], 2.0);

const DOUBLE_TITLE: &str = "round trip: 2 s forward, velocities reversed, 2 s again, reversed: back at the \
     start (time reversibility), and the energy conserved";

/// The double pendulum's energy in closed form:
/// `T = ½ (m1+m2) l1² a'² + m2 l1 l2 cos(a − b) a' b' + ½ m2 l2² b'²`,
/// `V = −(m1+m2) g l1 cos a − m2 g l2 cos b`.
pub fn double_pendulum_energy(p: &DoublePendulum, y: &Vector<4>) -> f64 {
    let (m1, m2, l1, l2, g) = (p.m1, p.m2, p.l1, p.l2, p.g);
    let (a, b, ad, bd) = (y[0], y[1], y[2], y[3]);
    0.5 * (m1 + m2) * l1 * l1 * ad * ad
        + m2 * l1 * l2 * (a - b).cos() * ad * bd
        + 0.5 * m2 * l2 * l2 * bd * bd
        - (m1 + m2) * g * l1 * a.cos()
        - m2 * g * l2 * b.cos()
}

fn double_run<S: OdeSystem<4> + mbd::Mechanism<2>>(
    s: &Setting,
    p: &DoublePendulum,
    sys: &S,
) -> Result<Measured, Failure> {
    let (start, leg) = DOUBLE_RUN;
    let y0 = Vector::<4>::from(start);
    let reverse = |y: &Vector<4>| Vector::<4>::new(y[0], y[1], -y[2], -y[3]);
    let out = solve_mechanism::<_, 2, 4>(s, sys, 0.0, y0, leg, &[])?;
    let back = solve_mechanism::<_, 2, 4>(s, sys, 0.0, reverse(out.last().1), leg, &[])?;
    let end = reverse(back.last().1);
    let e0 = double_pendulum_energy(p, &y0);
    let mut quantities: Vec<Quantity> = ["a", "b", "a_dot", "b_dot"]
        .iter()
        .zip(0..4)
        .map(|(name, i)| q(name, end[i], y0[i]))
        .collect();
    quantities.push(q("energy", double_pendulum_energy(p, out.last().1), e0));
    Ok(measured(quantities, &[&out, &back]))
}

fn double_generated(s: &Setting) -> Result<Measured, Failure> {
    let p = black_box(handwritten::DOUBLE_PENDULUM);
    double_run(s, &p, &p)
}

fn double_by_hand(s: &Setting) -> Result<Measured, Failure> {
    let p = black_box(handwritten::DOUBLE_PENDULUM);
    double_run(s, &p, &DoublePendulumByHand::from(&p))
}

/// Release angle, end angle and full swings of the slider-crank runs.
pub const SLIDER_RUN: (f64, f64, u32) = (0.3, -2.5, 2);

const SLIDER_TITLE: &str = "released at θ = 0.3 rad: θ, θ' after two periods and the swing down to -2.5 rad \
     (exact by energy and quadrature)";

/// The free slider-crank swinging under gravity, in closed form. The rod's centre is at
/// height `r sin θ / 2` (its end B stays on the axis), so `V = g r (m_c + m_r) sin θ / 2` and
/// `V(θ_0) − V(θ) = g r (m_c + m_r) cos((θ_0 + θ)/2) sin((θ_0 − θ)/2)`: the turning points
/// are `θ_0` and `−π − θ_0`, and `cos((θ_0 + θ)/2) = sin(d1/2)`. The generalised inertia is `2 T / θ'²` with
/// `β = asin(r sin θ / l)`, `β_θ = r cos θ / (l cos β)`, `x_θ = −r sin θ − l sin β β_θ`:
/// `J = m_c r²/3 + m_r |v_G|² + m_r l²/12 β_θ² + m_p x_θ²`,
/// `v_G = (−r sin θ − (l/2) sin β β_θ, r cos θ − (l/2) cos β β_θ)`.
pub fn slider_crank_motion(
    p: &SliderCrank,
    theta_0: f64,
) -> OneDof<impl Fn(f64) -> f64, impl Fn(f64, f64, f64) -> f64> {
    let (r, l, m_c, m_r, m_p, g) = (p.r, p.l, p.m_c, p.m_r, p.m_p, p.g);
    OneDof {
        inertia: move |th: f64| {
            let (st, ct) = th.sin_cos();
            let beta = (r * st / l).asin();
            let (sb, cb) = beta.sin_cos();
            let b_th = r * ct / (l * cb);
            let x_th = -r * st - l * sb * b_th;
            let vg = (-r * st - 0.5 * l * sb * b_th, r * ct - 0.5 * l * cb * b_th);
            m_c * r * r / 3.0
                + m_r * (vg.0 * vg.0 + vg.1 * vg.1)
                + m_r * l * l / 12.0 * b_th * b_th
                + m_p * x_th * x_th
        },
        gap: move |_, d0: f64, d1: f64| g * r * (m_c + m_r) * (0.5 * d1).sin() * (0.5 * d0).sin(),
        theta_0,
        theta_other: -std::f64::consts::PI - theta_0,
    }
}

/// `(t1, θ(t1), θ'(t1))` of the slider-crank runs, computed once (not part of a timed run).
pub fn slider_reference() -> (f64, f64, f64) {
    static REFERENCE: OnceLock<(f64, f64, f64)> = OnceLock::new();
    *REFERENCE.get_or_init(|| {
        let (theta_0, theta_1, periods) = SLIDER_RUN;
        slider_crank_motion(&handwritten::SLIDER_CRANK, theta_0)
            .state_after(periods, theta_1, PANELS)
    })
}

fn slider_run<S: OdeSystem<6> + Constrained<3, 2>>(
    s: &Setting,
    sys: &S,
) -> Result<Measured, Failure> {
    let (t1, theta, theta_dot) = slider_reference();
    let y0 = handwritten::slider_crank_state(&handwritten::SLIDER_CRANK, SLIDER_RUN.0, 0.0);
    let sol = solve_loop::<_, 3, 2, 5, 6>(s, sys, 0.0, y0, t1, &[])?;
    let y = sol.last().1;
    Ok(measured(
        vec![q("theta", y[0], theta), q("theta_dot", y[3], theta_dot)],
        &[&sol],
    ))
}

fn slider_generated(s: &Setting) -> Result<Measured, Failure> {
    let p = black_box(handwritten::SLIDER_CRANK);
    if s.method == Method::PeerDopri5 {
        let (t1, theta, theta_dot) = slider_reference();
        let y0 = handwritten::slider_crank_state(&p, SLIDER_RUN.0, 0.0);
        let (y, stats) = peer_dopri5(&p, 0.0, y0, t1, s.value)?;
        return Ok(Measured {
            quantities: vec![q("theta", y[0], theta), q("theta_dot", y[3], theta_dot)],
            stats,
            span: t1,
        });
    }
    slider_run(s, &p)
}

fn slider_by_hand(s: &Setting) -> Result<Measured, Failure> {
    slider_run(
        s,
        &SliderCrankByHand::from(&black_box(handwritten::SLIDER_CRANK)),
    )
}

// ---------------------------------------------------------------------------------------
// The peer.

/// A generated model seen through `differential-equations`' `ODE` trait, on plain arrays
/// (that crate's own state type: no second linear-algebra crate). An error of the model is
/// kept and the derivative set to NaN, which makes the peer reject the step.
struct PeerSystem<'a, S> {
    sys: &'a S,
    error: &'a Cell<Option<mbd::Error>>,
}

impl<S: OdeSystem<D>, const D: usize> ODE<f64, [f64; D]> for PeerSystem<'_, S> {
    fn diff(&self, t: f64, y: &[f64; D], dy: &mut [f64; D]) {
        match self.sys.rhs(t, &Vector::<D>::from_column_slice(y)) {
            Ok(f) => dy.copy_from_slice(f.as_slice()),
            Err(e) => {
                dy.fill(f64::NAN);
                self.error.set(Some(e));
            }
        }
    }
}

/// Integrate `sys` from `(t0, y0)` to `t1` with `differential-equations`' DOPRI5 at
/// `rtol = atol = tol` (its default controller, Hairer's), recording the end state only,
/// returning it and its work counters.
pub fn peer_dopri5<S: OdeSystem<D>, const D: usize>(
    sys: &S,
    t0: f64,
    y0: Vector<D>,
    t1: f64,
    tol: f64,
) -> Result<(Vector<D>, Stats), Failure> {
    let error = Cell::new(None);
    let system = PeerSystem { sys, error: &error };
    let mut start = [0.0; D];
    start.copy_from_slice(y0.as_slice());
    let method = ExplicitRungeKutta::dopri5()
        .rtol(tol)
        .atol(tol)
        .max_steps(PEER_MAX_STEPS);
    let result = IVP::ode(&system, t0, t1, start)
        .method(method)
        .t_eval([t1])
        .solve();
    if let Some(e) = error.take() {
        return Err(e.into());
    }
    let sol = result.map_err(|e| Failure::Failed(format!("differential-equations: {e:?}")))?;
    let end = match (sol.t.last(), sol.y.last()) {
        (Some(&t), Some(y)) if (t - t1).abs() <= 1e-12 * t1.abs().max(1.0) => {
            Vector::<D>::from_column_slice(y)
        }
        _ => Vector::<D>::from_element(f64::NAN),
    };
    if !end.iter().all(|v| v.is_finite()) {
        return Err(Failure::Failed(
            "differential-equations: the run did not reach t1 with a finite state".into(),
        ));
    }
    let (accepted, rejected) = (sol.steps.accepted, sol.steps.rejected);
    Ok((
        end,
        Stats {
            n_rhs: sol.evals.function,
            n_steps: accepted + rejected,
            n_accepted: accepted,
            n_rejected: rejected,
            ..Stats::default()
        },
    ))
}

/// The peer's step budget: ample for every sweep (a run that needs more fails).
const PEER_MAX_STEPS: usize = 100_000;

// ---------------------------------------------------------------------------------------
// Timing and sweeps.

/// One timed run of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    pub setting: Setting,
    pub outcome: Result<(Measured, f64), Failure>,
}

impl Run {
    /// `(runtime_s, error)` of a successful run.
    pub fn point(&self) -> Option<(f64, f64)> {
        self.outcome.as_ref().ok().map(|(m, t)| (*t, m.error()))
    }
}

/// How runs are timed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Timed repeats; the run time is their median.
    pub repeats: usize,
    /// Each repeat runs the measurement back to back until at least this long, and counts
    /// the mean: a run of microseconds is timed over many.
    pub min_batch_s: f64,
}

impl Default for Timing {
    fn default() -> Self {
        Timing {
            repeats: 7,
            min_batch_s: 1e-3,
        }
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Run each of `runs` once (their results), then time them: `timing.repeats` rounds, each
/// timing every run over a batch in turn, in alternating order (interleaved, so that a slow
/// spell of the machine falls on all of them alike); each run's time is the median of its
/// rounds. Runs that fail are not timed.
pub fn time_runs(
    runs: &[&dyn Fn() -> Result<Measured, Failure>],
    timing: Timing,
) -> Vec<Result<(Measured, f64), Failure>> {
    let mut first: Vec<Result<(Measured, f64), Failure>> = runs
        .iter()
        .map(|run| {
            let start = Instant::now();
            let m = run()?;
            Ok((m, start.elapsed().as_secs_f64()))
        })
        .collect();
    let batches: Vec<usize> = first
        .iter()
        .map(|r| match r {
            Ok((_, t)) => ((timing.min_batch_s / t.max(1e-9)).ceil() as usize).clamp(1, 1_000_000),
            Err(_) => 0,
        })
        .collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); runs.len()];
    for round in 0..timing.repeats {
        let order: Vec<usize> = if round % 2 == 0 {
            (0..runs.len()).collect()
        } else {
            (0..runs.len()).rev().collect()
        };
        for i in order {
            let run = runs[i];
            if batches[i] == 0 {
                continue;
            }
            let start = Instant::now();
            for _ in 0..batches[i] {
                // Deterministic: the same result as the first call.
                let _ = std::hint::black_box(run());
            }
            times[i].push(start.elapsed().as_secs_f64() / batches[i] as f64);
        }
    }
    for (r, t) in first.iter_mut().zip(times) {
        if let Ok((_, time)) = r
            && !t.is_empty()
        {
            *time = median(t);
        }
    }
    first
}

/// Errors below this are rounding: a sweep stops after two runs in a row reach it.
pub const ERROR_FLOOR: f64 = 1e-13;

/// A sweep stops after a run that took longer than this (the next would take twice as long).
pub const MAX_RUN_S: f64 = 0.25;

/// The problem's integrated time, from a pilot run (DOPRI5, tol 1e-8, or Radau5): it sets
/// the fixed-step methods' steps `h = span / n`.
pub fn pilot_span(problem: &Problem) -> Result<f64, Failure> {
    let pilot = |method| {
        (problem.run)(&Setting {
            method,
            value: 1e-8,
        })
    };
    pilot(Method::Dopri5)
        .or_else(|_| pilot(Method::Radau5))
        .map(|m| m.span)
}

/// Sweep `problems` (which share their settings: a generated model and its hand-written
/// twin) with `method` over its settings, timing them side by side ([`time_runs`]).
/// Stops early once the error has been at rounding level ([`ERROR_FLOOR`]) twice in a row
/// for every problem, after a run longer than [`MAX_RUN_S`], or at the first setting that
/// the method cannot run.
pub fn sweep(problems: &[&Problem], method: Method, span: f64, timing: Timing) -> Vec<Vec<Run>> {
    let mut out: Vec<Vec<Run>> = vec![Vec::new(); problems.len()];
    let mut floor_hits = vec![0usize; problems.len()];
    for setting in method.settings(span) {
        let closures: Vec<Box<dyn Fn() -> Result<Measured, Failure> + '_>> = problems
            .iter()
            .map(|p| {
                let run = p.run;
                Box::new(move || run(&setting)) as Box<dyn Fn() -> Result<Measured, Failure>>
            })
            .collect();
        let refs: Vec<&dyn Fn() -> Result<Measured, Failure>> =
            closures.iter().map(|c| c.as_ref()).collect();
        let results = time_runs(&refs, timing);
        let mut unsupported = false;
        let mut too_long = false;
        for (i, outcome) in results.into_iter().enumerate() {
            match &outcome {
                Ok((_, t)) if *t > MAX_RUN_S => too_long = true,
                _ => {}
            }
            match &outcome {
                Ok((m, _)) if m.error() <= ERROR_FLOOR => floor_hits[i] += 1,
                Ok(_) => floor_hits[i] = 0,
                Err(Failure::Unsupported(_)) => unsupported = true,
                Err(_) => {}
            }
            out[i].push(Run { setting, outcome });
        }
        if unsupported || too_long || floor_hits.iter().all(|&n| n >= 2) {
            break;
        }
    }
    out
}

/// The Pareto front of `(time, error)` points: sorted by time, each more accurate than
/// every faster one. Non-finite points are dropped.
pub fn pareto(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(t, e)| t.is_finite() && *t > 0.0 && e.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for pt in p {
        if front.last().is_none_or(|last| pt.1 < last.1) {
            front.push(pt);
        }
    }
    front
}

/// The time a curve of `(time, error)` points needs to reach `target`: on its Pareto front,
/// the first point at or below the target, interpolated linearly in `(log error, log time)`
/// with the point before it. `None` when no point reaches the target.
pub fn time_to_reach(points: &[(f64, f64)], target: f64) -> Option<f64> {
    let front = pareto(points);
    let k = front.iter().position(|&(_, e)| e <= target)?;
    let (t1, e1) = front[k];
    if k == 0 || e1 <= 0.0 {
        return Some(t1);
    }
    let (t0, e0) = front[k - 1];
    let s = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
    Some((t0.ln() + s * (t1.ln() - t0.ln())).exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_to_reach_interpolates_on_the_front() {
        // Error 1e-4 at 1 ms, 1e-8 at 10 ms: 1e-6 lies halfway in log-log, at sqrt(10) ms.
        let pts = [(1e-3, 1e-4), (1e-2, 1e-8), (5e-3, 1e-3)];
        let t = time_to_reach(&pts, 1e-6).unwrap();
        assert!((t - 1e-3 * 10f64.sqrt()).abs() < 1e-15);
        assert_eq!(time_to_reach(&pts, 1e-9), None);
        assert_eq!(time_to_reach(&pts, 1e-3), Some(1e-3));
        // The slower, less accurate point is off the front.
        assert_eq!(pareto(&pts).len(), 2);
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_nine() {
        let i = gauss_legendre(|x| x.powi(9) + 3.0 * x.powi(4), 0.0, 2.0, 1);
        let exact = 2f64.powi(10) / 10.0 + 3.0 * 2f64.powi(5) / 5.0;
        assert!((i - exact).abs() < 1e-12 * exact);
    }
}
