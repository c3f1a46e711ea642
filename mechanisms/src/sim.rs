//! The integration settings the cases share, in one place.

use crate::validation::{Animation, Frame};
use mbd::integrate::{Event, Integrator, Radau5, Solution};
use mbd::{Drawable, OdeSystem, Options, Vector};

/// Tolerance of the reference runs: tight enough that the integration error is far below
/// the 1e-6 relative the cases are judged at.
pub const TOL: f64 = 1e-12;

/// The method name reported for [`integrate`].
pub const METHOD: &str = "Radau IIA 5, rtol = atol = 1e-12";

/// Integrate `sys` from `(0, y0)` to `t1` with the cases' reference settings.
pub fn integrate<'e, S: OdeSystem<D>, const D: usize>(
    sys: &S,
    y0: Vector<D>,
    t1: f64,
    events: &[Event<'e, D>],
) -> mbd::Result<Solution<D>> {
    let opts = Options {
        rtol: TOL,
        atol: TOL,
        ..Options::default()
    };
    Radau5::new(opts).solve(sys, 0.0, y0, t1, events)
}

/// Sample a solution's dense output at `n + 1` equally spaced times, mapped by `f`.
pub fn sample<const D: usize>(
    sol: &Solution<D>,
    n: usize,
    f: impl Fn(f64, &Vector<D>) -> (f64, f64),
) -> Vec<(f64, f64)> {
    let (t0, (t1, _)) = (sol.t[0], sol.last());
    (0..=n)
        .filter_map(|i| {
            // The last sample at the run's end itself (an event's instant), not an ulp off.
            let t = if i == n {
                t1
            } else {
                t0 + (t1 - t0) * i as f64 / n as f64
            };
            sol.at(t).map(|y| f(t, &y))
        })
        .collect()
}

/// `f` at `n + 1` equally spaced times of a solution's dense output: a quantity's curve
/// over the run (or the model's outputs there, for [`crate::validation::series`]).
pub fn curve<const D: usize, O>(
    sol: &Solution<D>,
    n: usize,
    f: impl Fn(f64, &Vector<D>) -> mbd::Result<O>,
) -> mbd::Result<Vec<(f64, O)>> {
    let (t0, (t1, _)) = (sol.t[0], sol.last());
    (0..=n)
        .filter_map(|i| {
            // The last sample at the run's end itself (an event's instant), not an ulp off.
            let t = if i == n {
                t1
            } else {
                t0 + (t1 - t0) * i as f64 / n as f64
            };
            sol.at(t).map(|y| Ok((t, f(t, &y)?)))
        })
        .collect()
}

/// How many frames an animation has (plus one per compared instant).
pub const FRAMES: usize = 120;

/// The model's outputs by name at a state (empty for a model without outputs).
pub type Outputs<'a, const D: usize> =
    &'a dyn Fn(f64, &Vector<D>) -> mbd::Result<Vec<(&'static str, f64)>>;

/// The mechanism drawn at `FRAMES + 1` uniform times over `[0, span]` and at each instant
/// of `at` inside it (`stills`), with its `outputs`, from the run of [`integrate`] from
/// `y0`.
pub fn animate<S: OdeSystem<D> + Drawable<D>, const D: usize>(
    sys: &S,
    y0: Vector<D>,
    span: f64,
    at: &[f64],
    outputs: Outputs<'_, D>,
) -> mbd::Result<Animation> {
    // A closed loop's `init` need not give consistent velocities (the cases complete them
    // by a kinematic analysis): project onto the loop's manifolds first.
    let mut y0 = y0;
    sys.project(0.0, &mut y0)?;
    let sol = integrate(sys, y0, span, &[])?;
    let (t1, _) = sol.last();
    let draw = |t: f64| -> mbd::Result<Option<Frame>> {
        match sol.at(t) {
            Some(y) => Ok(Some(Frame {
                t,
                shapes: sys.geometry(t, &y)?,
                outputs: outputs(t, &y)?,
                added: Vec::new(),
            })),
            None => Ok(None),
        }
    };
    let mut frames = Vec::with_capacity(FRAMES + 1);
    for i in 0..=FRAMES {
        frames.extend(draw(t1 * i as f64 / FRAMES as f64)?);
    }
    let mut stills = Vec::new();
    for &t in at.iter().filter(|t| (0.0..=t1).contains(*t)) {
        stills.extend(draw(t)?);
    }
    Ok(Animation {
        frames,
        stills,
        ..Animation::default()
    })
}
