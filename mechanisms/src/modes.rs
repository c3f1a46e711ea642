//! Linear modes about operating points, from the exact generated Jacobian
//! ([`mbd::analysis::linear`]), against closed forms: the rows of the `modes` report.
//!
//! Each mechanism's reference is derived beside its rows; a row fails when its relative
//! error (frequency, damped frequency and damping ratio, the worst of them) exceeds
//! [`GOAL`].

use crate::case10_pendulum_on_cart::{self as case10, PendulumOnCart};
use crate::case30_damped_vibration::{self as case30, DampedBlock};
use mbd::analysis::linear::{Mode, ModeKind, constrained_modes, linearize, modes, undamped_modes};
use mbd::prelude::*;
use std::f64::consts::{PI, TAU};

/// Frequencies within `1e-10` relative of the closed forms.
pub const GOAL: f64 = 1e-10;

/// Two equal point masses on massless rods of equal length, angles from the downward
/// vertical, with its exact Jacobian generated.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(a, b)]
#[particle(p1, mass = m, at = [l * sin(a), -l * cos(a)])]
#[particle(p2, mass = m, at = [l * sin(a) + l * sin(b), -l * cos(a) - l * cos(b)])]
#[output(x1 = position(p1)[0])]
#[output(y1 = position(p1)[1])]
#[output(x2 = position(p2)[0])]
#[output(y2 = position(p2)[1])]
pub struct DoublePendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

/// `m = 1 kg`, `l = 1 m`, `g = 9.81 m/s^2`.
pub const DOUBLE: DoublePendulum = DoublePendulum {
    m: 1.0,
    l: 1.0,
    g: 9.81,
};

/// The double pendulum's small-oscillation frequencies `[w_1, w_2]` in rad/s.
///
/// About `a = b = 0` the Lagrangian's quadratic part gives `M = m l^2 [[2, 1], [1, 1]]`
/// and `K = m g l [[2, 0], [0, 1]]`. With `mu = w^2 l / g`,
/// `det(K - w^2 M) / (m g l)^2 = (2 - 2 mu)(1 - mu) - mu^2 = 2 (1 - mu)^2 - mu^2 = 0`, so
/// `sqrt(2) (1 - mu) = +-mu`, `mu = sqrt(2) / (sqrt(2) +- 1) = 2 -+ sqrt(2)`:
/// `w^2 = (g / l)(2 -+ sqrt(2))`. The shapes `b / a = mu / (1 - mu)` are `+sqrt(2)` (in
/// phase, slow) and `-sqrt(2)` (against, fast).
pub fn double_pendulum_reference() -> [f64; 2] {
    let DoublePendulum { l, g, .. } = DOUBLE;
    let s = 2f64.sqrt();
    [(g / l * (2.0 - s)).sqrt(), (g / l * (2.0 + s)).sqrt()]
}

/// Case 30 about its equilibrium `x = 0`: `m x'' + c x' + k x = 0`, `lambda = -zeta w_n +-
/// i w_d` with `w_n = sqrt(k/m) = 6 rad/s`, `zeta = c / (2 sqrt(m k)) = 0.5`,
/// `w_d = w_n sqrt(1 - zeta^2) = 3 sqrt(3)`: `[w_n, zeta, w_d]`.
pub fn case30_reference() -> [f64; 3] {
    let DampedBlock { m, k, .. } = case30::MODEL;
    let [zeta, omega_d] = case30::damping();
    [(k / m).sqrt(), zeta, omega_d]
}

/// Case 10's cart (mass `M`) and bob (mass `m` on a light rod `l`), `theta` from upright.
/// Linearised about `theta = 0` at rest: `(M + m) x'' + m l theta'' = 0` and
/// `m l x'' + m l^2 theta'' - m g l theta = 0`; eliminating `x'' = -m l theta'' / (M + m)`
/// gives `theta'' = g (M + m) / (M l) theta`: `lambda = +-s`, `s = sqrt(g (M + m) / (M l))`
/// (one unstable real eigenvalue), and a double zero (the cart's free drift `x`). Hanging
/// (`theta = pi`) the sign of gravity's term flips: an oscillation at `w = s`.
pub fn cart_reference() -> f64 {
    let PendulumOnCart {
        m_cart,
        m_bob,
        g,
        l,
        ..
    } = case10::MODEL;
    (g * (m_cart + m_bob) / (m_cart * l)).sqrt()
}

/// A parallelogram four-bar hanging from pivots `(0, 0)` and `(d, 0)`: cranks of length `r`
/// at `phi`, `psi` from the downward vertical, massless, and a massless coupler of length
/// `d` with mass `m / 2` lumped at each of its pins (the loop closes by one distance
/// constraint, augmented form). A horizontal spring `k` of free length `w` holds pin A from
/// the anchor `(-w, -r)`: unstretched at the equilibrium `phi = psi = 0`.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian, augmented)]
#[gravity(0.0, -g)]
#[coords(phi, psi)]
#[constraint((d + r * sin(psi) - r * sin(phi)) * (d + r * sin(psi) - r * sin(phi))
    + (r * cos(phi) - r * cos(psi)) * (r * cos(phi) - r * cos(psi)) == d * d)]
#[point(anchor, at = [-w, -r])]
#[particle(pin_a, mass = 0.5 * m, at = [r * sin(phi), -r * cos(phi)])]
#[particle(pin_b, mass = 0.5 * m, at = [d + r * sin(psi), -r * cos(psi)])]
#[spring(spring, from = anchor, to = pin_a, k = k, length = w)]
#[output(xa = position(pin_a)[0])]
#[output(ya = position(pin_a)[1])]
#[output(xb = position(pin_b)[0])]
#[output(yb = position(pin_b)[1])]
#[generalized_force(drive, along = phi, value = tau)]
#[input(tau)]
pub struct SprungFourBar {
    pub m: f64,
    pub r: f64,
    pub d: f64,
    pub k: f64,
    pub w: f64,
    pub g: f64,
    /// A torque on the first crank (an input, 0 in the report).
    pub tau: f64,
}

/// `m = 2 kg`, `r = 0.5 m`, `d = 1.5 m`, `k = 30 N/m`, `w = 1 m`, unforced.
pub const FOUR_BAR: SprungFourBar = SprungFourBar {
    m: 2.0,
    r: 0.5,
    d: 1.5,
    k: 30.0,
    w: 1.0,
    g: 9.81,
    tau: 0.0,
};

/// The sprung four-bar's one frequency in rad/s, by hand. On the loop `psi = phi` (the
/// parallelogram branch through the equilibrium) both pins move on circles of radius `r`:
/// `T = (m/2) r^2 phi'^2 / 2 * 2 = m r^2 phi'^2 / 2`. Gravity: `V_g = m g r (1 - cos phi)`.
/// The spring's length is `sqrt((w + r sin phi)^2 + r^2 (1 - cos phi)^2) = w + r sin phi +
/// O(phi^4)`, so `V_k = k r^2 sin^2 phi / 2 + O(phi^5)` (no preload at the equilibrium, no
/// geometric stiffness). Hence `w^2 = (m g r + k r^2) / (m r^2) = g / r + k / m`.
pub fn four_bar_reference() -> f64 {
    let SprungFourBar { m, r, k, g, .. } = FOUR_BAR;
    (g / r + k / m).sqrt()
}

/// A heavy symmetric top on a fixed point: Euler angles `z-x-z` (precession `phi`,
/// nutation `theta` from the upward vertical, spin `psi`), mass `m` at distance `l` along
/// its symmetry axis, principal moments `a1, a1, c3` about its centre of mass.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(spatial, jacobian)]
#[gravity(0.0, 0.0, -g)]
#[coords(phi, theta, psi)]
#[rigid3(top, mass = m, inertia = diag(a1, a1, c3),
         at = rot_z(phi) * rot_x(theta) * [0.0, 0.0, l],
         rotation = rot_z(phi) * rot_x(theta) * rot_z(psi))]
pub struct HeavyTop {
    pub m: f64,
    pub l: f64,
    pub a1: f64,
    pub c3: f64,
    pub g: f64,
}

/// `m = 1 kg`, `l = 0.1 m`, `a1 = 0.02`, `c3 = 0.03 kg m^2`.
pub const TOP: HeavyTop = HeavyTop {
    m: 1.0,
    l: 0.1,
    a1: 0.02,
    c3: 0.03,
    g: 9.81,
};

/// The top's steady precessions at `theta0` with spin `omega3` about its axis, slow and
/// fast: `[(state, nutation frequency in rad/s); 2]`.
///
/// With `I1 = a1 + m l^2` (about the fixed point), the kinetic energy is
/// `T = I1 (theta'^2 + phi'^2 sin^2) / 2 + c3 omega3^2 / 2`, `omega3 = psi' + phi' cos`,
/// and `V = m g l cos(theta)`. `phi`, `psi` are cyclic: `p_psi = c3 omega3 =: a` and
/// `p_phi = I1 phi' sin^2 + a cos =: b` are conserved, and Routh's reduction leaves
/// `I1 theta'' = -U'(theta)` with `U = (b - a cos)^2 / (2 I1 sin^2) + m g l cos`. With
/// `Omega = phi' = (b - a cos) / (I1 sin^2)`, `U' = sin (a Omega - I1 Omega^2 cos - m g l)`:
/// steady precession where `I1 cos Omega^2 - a Omega + m g l = 0`, that is
/// `Omega = (a -+ sqrt(a^2 - 4 I1 m g l cos)) / (2 I1 cos)`. Differentiating once more,
/// with `dOmega/dtheta = (a - 2 I1 Omega cos) / (I1 sin)` and the bracket zero at the
/// steady state, `U'' = (a - 2 I1 Omega cos)^2 / I1 + I1 Omega^2 sin^2`, so the nutation
/// frequency is `w^2 = U'' / I1 = ((a - 2 I1 Omega cos) / I1)^2 + Omega^2 sin^2`
/// (fast top, `Omega -> 0`: `w -> a / I1`, the classical `I3 omega3 / I1`). The linearised
/// equations about the steady motion do not depend on `phi`, `psi` (cyclic), so `A` is
/// constant along it: a pair `+-i w` and four zeros (the cyclic angles and their momenta).
pub fn top_precessions(theta0: f64, omega3: f64) -> [(Vector<6>, f64); 2] {
    let HeavyTop { m, l, a1, c3, g } = TOP;
    let i1 = a1 + m * l * l;
    let (s, c) = theta0.sin_cos();
    let a = c3 * omega3;
    let root = (a * a - 4.0 * i1 * m * g * l * c).sqrt();
    [-1.0, 1.0].map(|sign| {
        let big_omega = (a + sign * root) / (2.0 * i1 * c);
        let psi_dot = omega3 - big_omega * c;
        let w = (((a - 2.0 * i1 * big_omega * c) / i1).powi(2) + (big_omega * s).powi(2)).sqrt();
        (
            Vector::<6>::new(0.0, theta0, 0.0, big_omega, 0.0, psi_dot),
            w,
        )
    })
}

/// `theta0 = 0.5 rad`, `omega3 = 20 rad/s`.
pub const TOP_POINT: (f64, f64) = (0.5, 20.0);

/// One row of the report (the `--json` schema).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "report", derive(serde::Serialize))]
pub struct Row {
    pub mechanism: &'static str,
    pub point: &'static str,
    /// Mode number, slowest first.
    pub mode: usize,
    /// `Oscillatory`, `Real` or `Neutral`.
    pub kind: &'static str,
    /// Natural frequency `|lambda| / 2 pi` (a neutral mode's is its computed `|lambda|`,
    /// rounding of the double zero: checked against 0 like any other).
    pub frequency_hz: f64,
    /// Damped frequency `Im lambda / 2 pi`.
    pub damped_hz: f64,
    /// `-Re lambda / |lambda|`; `None` for a neutral mode.
    pub damping_ratio: Option<f64>,
    pub unstable: bool,
    pub reference_hz: f64,
    pub reference_damping_ratio: Option<f64>,
    /// The worst of: the frequency's relative error (absolute in Hz when the reference is
    /// 0), the damped frequency's, the damping ratio's (absolute).
    pub rel_error: f64,
    /// The cost of the linearisation at this point (`modes --json` only: timing is left
    /// out of the tests).
    #[cfg_attr(feature = "report", serde(skip_serializing_if = "Option::is_none"))]
    pub cost: Option<Cost>,
}

/// Time per call at one state, in microseconds, the least over 31 interleaved batches
/// (a shared machine only ever adds time): one right-hand side, the exact `A`
/// ([`linearize`]), and `A` by forward differences (`D + 1` right-hand sides, the
/// cheapest numerical Jacobian); `ratio` is exact over forward differences.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "report", derive(serde::Serialize))]
pub struct Cost {
    pub rhs_us: f64,
    pub exact_a_us: f64,
    pub forward_difference_us: f64,
    pub ratio: f64,
}

/// [`Cost`] of a model at `y`; `None` when `timed` is false or an evaluation fails.
pub fn cost<S: OdeSystem<D>, const D: usize>(timed: bool, m: &S, y: &Vector<D>) -> Option<Cost> {
    use std::hint::black_box;
    if !timed || m.rhs(0.0, y).is_err() || linearize(m, 0.0, y).is_err() {
        return None;
    }
    let rhs = || {
        black_box(m.rhs(0.0, black_box(y)).ok());
    };
    let exact = || {
        black_box(linearize(m, 0.0, black_box(y)).ok());
    };
    let forward = || {
        black_box(mbd::jacobian::forward_difference(|y| m.rhs(0.0, y), black_box(y)).ok());
    };
    let [rhs_us, exact_a_us, forward_difference_us] = least_us([&rhs, &exact, &forward]);
    Some(Cost {
        rhs_us,
        exact_a_us,
        forward_difference_us,
        ratio: exact_a_us / forward_difference_us,
    })
}

/// The least time per call (us) of each function over 31 rounds, the functions taking
/// turns within a round; each batch long enough (about 1 ms) for the clock.
fn least_us<const K: usize>(fs: [&dyn Fn(); K]) -> [f64; K] {
    use std::time::Instant;
    let batch = fs.map(|f| {
        let mut n = 1u64;
        while {
            let s = Instant::now();
            (0..n).for_each(|_| f());
            s.elapsed().as_secs_f64() < 1e-3
        } {
            n *= 2;
        }
        n
    });
    let mut best = [f64::INFINITY; K];
    for _ in 0..31 {
        for k in 0..K {
            let s = Instant::now();
            (0..batch[k]).for_each(|_| fs[k]());
            best[k] = best[k].min(s.elapsed().as_secs_f64() * 1e6 / batch[k] as f64);
        }
    }
    best
}

/// Sets `cost` on the rows of one point.
fn stamp(rows: &mut [Row], cost: Option<Cost>) {
    for r in rows {
        r.cost = cost;
    }
}

/// A reference: natural frequency in rad/s, damping ratio (None for neutral).
type Reference = (f64, Option<f64>);

fn row(
    mechanism: &'static str,
    point: &'static str,
    index: usize,
    m: &Mode,
    (w_ref, zeta_ref): Reference,
) -> Row {
    let rel = |x: f64, r: f64| {
        if r == 0.0 {
            x.abs()
        } else {
            (x - r).abs() / r.abs()
        }
    };
    let wd_ref = match zeta_ref {
        Some(z) if z.abs() < 1.0 => w_ref * (1.0 - z * z).sqrt(),
        _ => 0.0,
    };
    let zeta_err = match (m.damping_ratio, zeta_ref) {
        (Some(z), Some(r)) => (z - r).abs(),
        (None, None) => 0.0,
        _ => f64::INFINITY,
    };
    let rel_error = rel(m.omega_n, w_ref)
        .max(rel(m.omega_d, wd_ref))
        .max(zeta_err);
    Row {
        mechanism,
        point,
        mode: index + 1,
        kind: match m.kind {
            ModeKind::Oscillatory => "oscillatory",
            ModeKind::Real => "real",
            ModeKind::Neutral => "neutral",
        },
        frequency_hz: m.frequency_hz(),
        damped_hz: m.damped_hz(),
        damping_ratio: m.damping_ratio,
        unstable: m.unstable,
        reference_hz: w_ref / TAU,
        reference_damping_ratio: zeta_ref,
        rel_error,
        cost: None,
    }
}

/// Rows for the modes of `A` at one point against references in the modes' order
/// (slowest first); a count mismatch is an error.
fn rows_of(
    mechanism: &'static str,
    point: &'static str,
    found: &[Mode],
    refs: &[Reference],
) -> mbd::Result<Vec<Row>> {
    if found.len() != refs.len() {
        return Err(mbd::Error::InvalidInput {
            what: "modes report",
            detail: format!(
                "{mechanism} at {point}: {} modes, {} references",
                found.len(),
                refs.len()
            ),
        });
    }
    Ok(found
        .iter()
        .zip(refs)
        .enumerate()
        .map(|(i, (m, r))| row(mechanism, point, i, m, *r))
        .collect())
}

/// Every row of the report.
pub fn rows() -> mbd::Result<Vec<Row>> {
    rows_timed(false)
}

/// Every row of the report, with the cost of each point's linearisation when `timed`.
pub fn rows_timed(timed: bool) -> mbd::Result<Vec<Row>> {
    let mut out = Vec::new();
    let [w1, w2] = double_pendulum_reference();
    let dp = DOUBLE;
    let a = linearize(&dp, 0.0, &Vector::<4>::zeros())?;
    out.extend(rows_of(
        "double pendulum",
        "hanging, A",
        &modes(&a)?,
        &[(w1, Some(0.0)), (w2, Some(0.0))],
    )?);
    let hanging = cost(timed, &dp, &Vector::<4>::zeros());
    stamp(&mut out, hanging);
    for (i, (nm, w)) in undamped_modes(&dp, 0.0, &Vector::<2>::zeros())?
        .iter()
        .zip([w1, w2])
        .enumerate()
    {
        let f = nm.frequency_hz().unwrap_or(f64::NAN);
        out.push(Row {
            mechanism: "double pendulum",
            point: "hanging, K v = w^2 M v",
            mode: i + 1,
            kind: "oscillatory",
            frequency_hz: f,
            damped_hz: f,
            damping_ratio: Some(0.0),
            unstable: nm.omega_squared < 0.0,
            reference_hz: w / TAU,
            reference_damping_ratio: Some(0.0),
            rel_error: if f.is_nan() {
                f64::INFINITY
            } else {
                (f * TAU - w).abs() / w
            },
            cost: hanging,
        });
    }
    let start = out.len();
    let [wn, zeta, _] = case30_reference();
    let block = case30::MODEL;
    let a = linearize(&block, 0.0, &Vector::<2>::zeros())?;
    out.extend(rows_of(
        "case 30 damped block",
        "equilibrium",
        &modes(&a)?,
        &[(wn, Some(zeta))],
    )?);
    stamp(
        &mut out[start..],
        cost(timed, &block, &Vector::<2>::zeros()),
    );
    let start = out.len();
    let s = cart_reference();
    let cart = case10::MODEL;
    let a = linearize(&cart, 0.0, &Vector::<4>::zeros())?;
    // The double zero (one neutral row for each), then -s and +s by sign: their moduli
    // agree only to rounding, so `modes`' order by modulus may put either first.
    let mut found = modes(&a)?;
    found.sort_by(|x, y| {
        (x.kind != ModeKind::Neutral)
            .cmp(&(y.kind != ModeKind::Neutral))
            .then(x.eigenvalue.re.total_cmp(&y.eigenvalue.re))
    });
    out.extend(rows_of(
        "case 10 pendulum on cart",
        "upright",
        &found,
        &[(0.0, None), (0.0, None), (s, Some(1.0)), (s, Some(-1.0))],
    )?);
    stamp(&mut out[start..], cost(timed, &cart, &Vector::<4>::zeros()));
    let start = out.len();
    let hanging = Vector::<4>::new(0.0, PI, 0.0, 0.0);
    let a = linearize(&cart, 0.0, &hanging)?;
    out.extend(rows_of(
        "case 10 pendulum on cart",
        "hanging",
        &modes(&a)?,
        &[(0.0, None), (0.0, None), (s, Some(0.0))],
    )?);
    stamp(&mut out[start..], cost(timed, &cart, &hanging));
    for ((y, w), point) in top_precessions(TOP_POINT.0, TOP_POINT.1)
        .into_iter()
        .zip(["slow precession", "fast precession"])
    {
        let start = out.len();
        // The oscillatory mode alone: the four zeros of the cyclic coordinates come out at
        // the square root of rounding (a Jordan block), checked in the tests.
        let found: Vec<Mode> = modes(&linearize(&TOP, 0.0, &y)?)?
            .into_iter()
            .filter(|m| m.kind != ModeKind::Neutral)
            .collect();
        out.extend(rows_of(
            "heavy symmetric top, nutation",
            point,
            &found,
            &[(w, Some(0.0))],
        )?);
        stamp(&mut out[start..], cost(timed, &TOP, &y));
    }
    let start = out.len();
    let found = constrained_modes(&FOUR_BAR, 0.0, &Vector::<2>::zeros())?;
    out.extend(rows_of(
        "sprung parallelogram four-bar",
        "equilibrium, tangent space",
        &found,
        &[(four_bar_reference(), Some(0.0))],
    )?);
    stamp(
        &mut out[start..],
        cost(timed, &FOUR_BAR, &Vector::<4>::zeros()),
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mbd::analysis::linear::central_difference;

    /// Every row within the goal, and the stability flags where the closed forms put them.
    #[test]
    fn modes_match_the_closed_forms() {
        let rows = rows().unwrap();
        assert_eq!(rows.len(), 2 + 2 + 1 + 4 + 3 + 2 + 1);
        for r in &rows {
            assert!(r.rel_error <= GOAL, "{r:?}");
            let diverges = r.damping_ratio.is_some_and(|z| z < 0.0);
            assert_eq!(r.unstable, diverges, "{r:?}");
        }
        assert_eq!(rows.iter().filter(|r| r.unstable).count(), 1);
    }

    /// The double pendulum's mode shapes: `b / a = +sqrt(2)` slow, `-sqrt(2)` fast, from
    /// both analyses.
    #[test]
    fn double_pendulum_shapes() {
        let a = linearize(&DOUBLE, 0.0, &Vector::<4>::zeros()).unwrap();
        let s = 2f64.sqrt();
        let found = modes(&a).unwrap();
        for (m, ratio) in found.iter().zip([s, -s]) {
            let r = m.shape[1] / m.shape[0];
            assert!((r.re - ratio).abs() < 1e-9 && r.im.abs() < 1e-9, "{r}");
        }
        let normal = undamped_modes(&DOUBLE, 0.0, &Vector::<2>::zeros()).unwrap();
        for (m, ratio) in normal.iter().zip([s, -s]) {
            assert!((m.shape[1] / m.shape[0] - ratio).abs() < 1e-12);
        }
    }

    /// `A` from the generated Jacobian against central differences at a moving state of
    /// the double pendulum: the difference falls as `h^2` (by 4 when h halves, to 10%),
    /// so it is the differences' truncation error and `A` is their limit.
    #[test]
    fn linearisation_is_the_limit_of_central_differences() {
        let y = Vector::<4>::new(0.7, -0.4, 1.3, -2.1);
        let a = linearize(&DOUBLE, 0.0, &y).unwrap();
        let err = |h: f64| {
            (central_difference(&DOUBLE, 0.0, &y, h).unwrap() - a)
                .abs()
                .max()
        };
        let (e1, e2) = (err(2e-3), err(1e-3));
        assert!(e1 < 1e-4 * a.abs().max(), "{e1}");
        let ratio = e1 / e2;
        assert!((3.6..=4.4).contains(&ratio), "ratio {ratio}, {e1} {e2}");
    }

    /// The four-bar's augmented `A` unrestricted has the loop's drift (a double zero) beside
    /// the frequency the restriction to the tangent space gives alone; the mode moves both
    /// cranks alike, velocities `i w` times the positions.
    #[test]
    fn four_bar_tangent_space() {
        let a = linearize(&FOUR_BAR, 0.0, &Vector::<4>::zeros()).unwrap();
        let full = modes(&a).unwrap();
        let kinds: Vec<_> = full.iter().map(|m| m.kind).collect();
        assert_eq!(
            kinds,
            [ModeKind::Neutral, ModeKind::Neutral, ModeKind::Oscillatory]
        );
        let w = four_bar_reference();
        assert!((full[2].omega_n - w).abs() <= GOAL * w);
        let reduced = constrained_modes(&FOUR_BAR, 0.0, &Vector::<2>::zeros()).unwrap();
        assert_eq!(reduced.len(), 1);
        let v = &reduced[0].shape;
        // Positions: phi = psi; velocities are i w times them.
        assert!((v[0] - v[1]).norm() < 1e-9 * v[0].norm(), "{v}");
        let i_w = mbd::nalgebra::Complex::new(0.0, w);
        assert!((v[2] - i_w * v[0]).norm() < 1e-8 * v[2].norm(), "{v}");
        // A point off the loop is refused.
        assert!(constrained_modes(&FOUR_BAR, 0.0, &Vector::<2>::new(0.1, 0.0)).is_err());
    }

    /// The top's steady precessions are steady (`qdd = 0` there, so `A` is the linearisation
    /// about the motion), and besides the nutation pair `A` has only the four zeros of the
    /// cyclic coordinates.
    #[test]
    fn top_steady_precession() {
        for (y, w) in top_precessions(TOP_POINT.0, TOP_POINT.1) {
            let f = TOP.rhs(0.0, &y).unwrap();
            assert!(f.fixed_rows::<3>(3).amax() < 1e-12, "{f}");
            let found = modes(&linearize(&TOP, 0.0, &y).unwrap()).unwrap();
            let kinds: Vec<_> = found.iter().map(|m| m.kind).collect();
            assert_eq!(
                kinds,
                [ModeKind::Neutral; 4]
                    .into_iter()
                    .chain([ModeKind::Oscillatory])
                    .collect::<Vec<_>>()
            );
            assert!((found[4].omega_n - w).abs() <= GOAL * w);
        }
    }

    /// Typed errors: no generated Jacobian, not an equilibrium, a damped model.
    #[test]
    fn refuses_what_it_cannot_analyse() {
        let by_hand = crate::handwritten::PendulumByHand {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        };
        assert!(linearize(&by_hand, 0.0, &Vector::<2>::zeros()).is_err());
        let off = Vector::<2>::new(0.3, 0.0);
        assert!(undamped_modes(&DOUBLE, 0.0, &off).is_err());
        assert!(undamped_modes(&case30::MODEL, 0.0, &Vector::<1>::zeros()).is_err());
        let nan = Matrix::<2, 2>::new(f64::NAN, 0.0, 0.0, 1.0);
        assert!(modes(&nan).is_err());
    }
}
