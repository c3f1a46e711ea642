//! Coulomb friction as discrete modes: the accelerations in given modes, the modes
//! consistent with a state, and the switching functions (see [`crate::model::Hybrid`]).
//!
//! Per contact `k` along free coordinate `s_k`: sliding, the friction force is
//! `-mu_k |N_k| sign(qd_s)`; stuck, `qdd_s = 0` is one more row of the linear solve,
//! `[M Phi_q^T E^T; Phi_q 0 0; E 0 0] [qdd; lambda; h] = [f; gamma; 0]`, and `h_k`, the
//! generalised load that friction must cancel (the friction force is `-h_k`), is solved with
//! the other unknowns. A stuck contact breaks away when `|h_k| > mu_s |N_k|`, in the
//! direction of `h_k`; a sliding one stops when `qd_s` reaches zero, and then sticks or
//! reverses as the load decides. At `qd_s = 0` (either signed zero) the mode comes from the
//! loads, never from the sign bit of the velocity: of the combinations of stick and slip for
//! the contacts at rest, the first consistent one is taken, most contacts stuck first (a
//! stuck contact strictly within its bound, a sliding one accelerating the way it slides;
//! only if none is, the same with the boundaries included).

use crate::error::{Error, Result};
use crate::linalg::Lu;
use crate::model::{Contacts, Frictional, Matrix, Normals, Slip, Vector};
use crate::solve::{finite, solve_mass};

/// Contacts at rest whose modes are enumerated at most (`3^12` solves would be too many).
pub const MAX_RESTING: usize = 12;

/// Accelerations, multipliers and friction loads in given modes.
#[derive(Debug, Clone, PartialEq)]
pub struct InModes<const N: usize, const M: usize, const F: usize> {
    /// `qdd`; exactly zero along stuck contacts.
    pub qdd: Vector<N>,
    /// Constraint multipliers.
    pub lambda: Vector<M>,
    /// The load friction must cancel at each stuck contact (the friction force is its
    /// negative); zero at sliding ones.
    pub load: [f64; F],
}

/// The direction of a sliding velocity, `0.0` at rest (`+0.0` and `-0.0` alike).
#[inline]
pub fn direction(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Refuse coefficients outside `0 <= mu_k <= mu_s` (finite) and a non-finite normal force.
fn check<const N: usize, const M: usize, const F: usize>(
    t: f64,
    c: &Contacts<N, M, F>,
) -> Result<()> {
    for k in 0..F {
        let (mk, ms) = (c.mu_k[k], c.mu_s[k]);
        if !(mk >= 0.0 && ms >= mk && ms.is_finite()) {
            return Err(Error::InvalidInput {
                what: "friction coefficients",
                detail: format!(
                    "contact {k}: need 0 <= mu_k <= mu_s, got mu_k = {mk}, mu_s = {ms}"
                ),
            });
        }
        if !c.normal[k].is_finite() {
            return Err(Error::NonFinite { t });
        }
    }
    Ok(())
}

/// Solve the equations of motion with the contacts in `modes`.
pub fn solve_in<const N: usize, const M: usize, const F: usize, const A: usize>(
    t: f64,
    c: &Contacts<N, M, F>,
    along: &[usize; F],
    modes: &[Slip; F],
) -> Result<InModes<N, M, F>> {
    const { assert!(A == N + M + F, "friction solve size must be N + M + F") };
    check(t, c)?;
    let mut f = c.forces;
    for k in 0..F {
        let d = match modes[k] {
            Slip::Forward => 1.0,
            Slip::Backward => -1.0,
            Slip::Stick => continue,
        };
        f[along[k]] -= c.mu_k[k] * c.normal[k].abs() * d;
    }
    if M == 0 && modes.iter().all(|m| *m != Slip::Stick) {
        let qdd = solve_mass(t, &c.mass, &f)?;
        return Ok(InModes {
            qdd,
            lambda: Vector::<M>::zeros(),
            load: [0.0; F],
        });
    }
    if M == 0 {
        return held(t, c, along, modes, &f);
    }
    let mut k = Matrix::<A, A>::zeros();
    k.fixed_view_mut::<N, N>(0, 0).copy_from(&c.mass);
    k.fixed_view_mut::<M, N>(N, 0).copy_from(&c.phi_q);
    k.fixed_view_mut::<N, M>(0, N)
        .copy_from(&c.phi_q.transpose());
    for (j, mode) in modes.iter().enumerate() {
        let r = N + M + j;
        if *mode == Slip::Stick {
            k[(r, along[j])] = 1.0;
            k[(along[j], r)] = 1.0;
        } else {
            k[(r, r)] = 1.0;
        }
    }
    let mut rhs = Vector::<A>::zeros();
    rhs.fixed_rows_mut::<N>(0).copy_from(&f);
    rhs.fixed_rows_mut::<M>(N).copy_from(&c.gamma);
    let x = match Lu::factor(k) {
        Some(lu) => lu.solve(&rhs),
        None => redundant(t, c, modes, &k, &rhs)?,
    };
    let x = finite(t, x)?;
    let mut qdd = x.fixed_rows::<N>(0).into_owned();
    let lambda = x.fixed_rows::<M>(N).into_owned();
    for j in 0..F {
        if modes[j] == Slip::Stick {
            // Held exactly: a stuck coordinate must not creep by the solve's rounding.
            qdd[along[j]] = 0.0;
        }
    }
    // The holding loads as the residuals of their rows, so that `M qdd + Phi_q^T lambda`
    // equals the forces with friction to the last bit (a body at rest stays at rest under
    // methods that iterate on that residual).
    let residual = f - c.mass * qdd - c.phi_q.transpose() * lambda;
    let load = std::array::from_fn(|j| {
        if modes[j] == Slip::Stick {
            residual[along[j]]
        } else {
            0.0
        }
    });
    Ok(InModes { qdd, lambda, load })
}

/// The solve of [`solve_in`] when its matrix is singular. With contacts stuck that is
/// either an impossible stick (a stuck row contradicting the constraints: a piston at a
/// dead centre, which the loop moves at second order; [`Error::SingularConstraintJacobian`],
/// so the modes without it decide) or stuck contacts tied to each other by the constraints
/// (blocks joined by bars): the accelerations are still unique, but the holding loads are
/// not, only the combinations the ties transmit. Then the loads are taken in that family to
/// spread the load as evenly as the bounds allow (least `max |h_k| / (mu_s |N_k|)`), so the
/// stick holds exactly when some split of the load holds.
fn redundant<const N: usize, const M: usize, const F: usize, const A: usize>(
    t: f64,
    c: &Contacts<N, M, F>,
    modes: &[Slip; F],
    k: &Matrix<A, A>,
    rhs: &Vector<A>,
) -> Result<Vector<A>> {
    use nalgebra::{DMatrix, DVector};
    let singular = Error::SingularConstraintJacobian {
        t,
        detail: String::new(),
    };
    let stuck: Vec<usize> = (0..F).filter(|&j| modes[j] == Slip::Stick).collect();
    // Only the stuck rows may be at fault: a singular loop (constraints dependent by
    // themselves) keeps its typed error.
    let mut loose = *k;
    for &j in &stuck {
        let r = N + M + j;
        loose.row_mut(r).fill(0.0);
        loose.column_mut(r).fill(0.0);
        loose[(r, r)] = 1.0;
    }
    if stuck.is_empty() || Lu::factor(loose).is_none() {
        return Err(singular);
    }
    let kd = DMatrix::from_iterator(A, A, k.iter().copied());
    let b = DVector::from_iterator(A, rhs.iter().copied());
    let svd = kd.clone().svd(true, true);
    let top = svd.singular_values.max();
    let tol = 1e-9 * top;
    let x = svd.solve(&b, tol).map_err(|_| singular.clone())?;
    // Inconsistent (no solution at all): the stick is impossible.
    if (&kd * &x - &b).amax() > 1e-9 * (top * x.amax() + b.amax()) {
        return Err(singular);
    }
    let v_t = svd.v_t.as_ref().ok_or_else(|| singular.clone())?;
    let null: Vec<usize> = (0..A).filter(|&i| svd.singular_values[i] <= tol).collect();
    // The null directions `Z` (the accelerations do not move along them) and the loads.
    let z = DMatrix::from_fn(A, null.len(), |r, col| v_t[(null[col], r)]);
    let h: Vec<f64> = stuck.iter().map(|&j| x[N + M + j]).collect();
    let zh = DMatrix::from_fn(stuck.len(), null.len(), |r, col| z[(N + M + stuck[r], col)]);
    let bound: Vec<f64> = stuck
        .iter()
        .map(|&j| c.mu_s[j] * c.normal[j].abs())
        .collect();
    let x = x + z * even_split(&h, &zh, &bound);
    Ok(Vector::<A>::from_fn(|i, _| x[i]))
}

/// The `a` minimising `max_k |h_k + (Z a)_k| / b_k` (a zero bound admits only a zero load).
/// In `(a, r)` that is a linear programme (`|h_k + (Z a)_k| <= b_k r`, least `r`) whose
/// optimum lies at a vertex, where `rank + 1` of the constraints hold with equality
/// (`rank` that of `Z`, whose column space is the only part of `a` that matters): every
/// such choice of rows and signs is solved and the best kept. Only for stuck contacts tied
/// by constraints; a dozen contacts at most.
fn even_split(h: &[f64], z: &nalgebra::DMatrix<f64>, b: &[f64]) -> nalgebra::DVector<f64> {
    use nalgebra::{DMatrix, DVector};
    let (rows, dim) = z.shape();
    let worst = |a: &DVector<f64>| {
        let v = z * a;
        (0..rows)
            .map(|k| {
                let load = (h[k] + v[k]).abs();
                if b[k] > 0.0 {
                    load / b[k]
                } else if load <= 1e-12 * (h[k].abs() + 1.0) {
                    0.0
                } else {
                    f64::INFINITY
                }
            })
            .fold(0.0, f64::max)
    };
    let zero = DVector::<f64>::zeros(dim);
    if rows == 0 || dim == 0 {
        return zero;
    }
    // `a = V_r c`: the directions of `a` that move the loads.
    let svd = z.clone().svd(false, true);
    let Some(v_t) = svd.v_t.as_ref() else {
        return zero;
    };
    let big = svd.singular_values.max();
    let keep: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| svd.singular_values[i] > 1e-12 * big)
        .collect();
    let basis = DMatrix::from_fn(dim, keep.len(), |r, col| v_t[(keep[col], r)]);
    let zr = z * &basis;
    let n = keep.len() + 1;
    let mut best = (worst(&zero), zero);
    for mask in 0u32..(1 << rows) {
        if mask.count_ones() as usize != n {
            continue;
        }
        let picked: Vec<usize> = (0..rows).filter(|&k| mask & (1 << k) != 0).collect();
        for signs in 0u32..(1 << n) {
            // Row `i`: (Z_r c)_k - sigma b_k r = -h_k.
            let m = DMatrix::from_fn(n, n, |i, col| {
                if col < keep.len() {
                    zr[(picked[i], col)]
                } else if signs & (1 << i) != 0 {
                    b[picked[i]]
                } else {
                    -b[picked[i]]
                }
            });
            let rhs = DVector::from_fn(n, |i, _| -h[picked[i]]);
            let Some(sol) = m.lu().solve(&rhs) else {
                continue;
            };
            let a = &basis * sol.rows(0, keep.len());
            let w = worst(&a);
            if w < best.0 {
                best = (w, a);
            }
        }
    }
    best.1
}

/// [`solve_in`] without constraints and with a contact stuck: the stuck coordinates' rows
/// and columns of `M` replaced by the identity's (with `qdd_s = 0` on the right), an
/// `N x N` solve instead of the `(N + F) x (N + F)` one, the loads again the residuals.
fn held<const N: usize, const M: usize, const F: usize>(
    t: f64,
    c: &Contacts<N, M, F>,
    along: &[usize; F],
    modes: &[Slip; F],
    f: &Vector<N>,
) -> Result<InModes<N, M, F>> {
    let (mut k, mut rhs) = (c.mass, *f);
    for j in (0..F).filter(|&j| modes[j] == Slip::Stick) {
        let s = along[j];
        k.row_mut(s).fill(0.0);
        k.column_mut(s).fill(0.0);
        k[(s, s)] = 1.0;
        rhs[s] = 0.0;
    }
    let mut qdd = solve_mass(t, &k, &rhs)?;
    for j in (0..F).filter(|&j| modes[j] == Slip::Stick) {
        qdd[along[j]] = 0.0;
    }
    let residual = f - c.mass * qdd;
    let load = std::array::from_fn(|j| {
        if modes[j] == Slip::Stick {
            residual[along[j]]
        } else {
            0.0
        }
    });
    Ok(InModes {
        qdd,
        lambda: Vector::<M>::zeros(),
        load,
    })
}

/// The normal forces of a model with implicit ones at a state, as functions of `(qdd,
/// lambda)` ([`Frictional::normals`]).
pub type NormalsAt<'a, const N: usize, const M: usize, const F: usize> =
    &'a dyn Fn(&Vector<N>, &Vector<M>) -> Option<Normals<N, M, F>>;

/// Newton iterations allowed for implicit normal forces.
pub const MAX_NEWTON: usize = 50;

/// [`solve_in`] where the normal forces may depend on the solution (`normals`): the sliding
/// contacts' normals are solved with it ([`newton`]), the stuck contacts' (which do not
/// enter the solve, only their bounds) are evaluated at it; `c.normal` is set to them.
pub fn resolve<const N: usize, const M: usize, const F: usize, const A: usize>(
    t: f64,
    c: &mut Contacts<N, M, F>,
    along: &[usize; F],
    modes: &[Slip; F],
    normals: Option<NormalsAt<'_, N, M, F>>,
) -> Result<InModes<N, M, F>> {
    let Some(at) = normals else {
        return solve_in::<N, M, F, A>(t, c, along, modes);
    };
    if modes.iter().any(|m| *m != Slip::Stick) {
        newton::<N, M, F, A>(t, c, along, modes, at)?;
    }
    let s = solve_in::<N, M, F, A>(t, c, along, modes)?;
    let n = at(&s.qdd, &s.lambda).ok_or_else(|| no_normals(t))?;
    for k in (0..F).filter(|&k| modes[k] == Slip::Stick) {
        c.normal[k] = n.value[k];
    }
    Ok(s)
}

#[cold]
fn no_normals(t: f64) -> Error {
    Error::InvalidInput {
        what: "friction",
        detail: format!("implicit normal forces not available at t = {t}"),
    }
}

/// The sliding contacts' normals `nu = N(x(nu))`. The solution is affine in `|nu|` (each
/// normal adds `-mu_k |nu_k| dir_k` to one force), `x = x0 + sum_k |nu_k| G_k` with `G_k`
/// the response to a unit normal, so one solve per sliding contact sets up a Newton
/// iteration on `F` scalars with the exact Jacobian `I - (dN/dx) G diag(sign nu)`.
fn newton<const N: usize, const M: usize, const F: usize, const A: usize>(
    t: f64,
    c: &mut Contacts<N, M, F>,
    along: &[usize; F],
    modes: &[Slip; F],
    at: NormalsAt<'_, N, M, F>,
) -> Result<()> {
    let sliding: Vec<usize> = (0..F).filter(|&k| modes[k] != Slip::Stick).collect();
    for &k in &sliding {
        c.normal[k] = 0.0;
    }
    let x0 = solve_in::<N, M, F, A>(t, c, along, modes)?;
    let mut unit = Vec::with_capacity(sliding.len());
    for &k in &sliding {
        c.normal[k] = 1.0;
        let x1 = solve_in::<N, M, F, A>(t, c, along, modes)?;
        c.normal[k] = 0.0;
        unit.push((k, x1.qdd - x0.qdd, x1.lambda - x0.lambda));
    }
    let mut nu = at(&x0.qdd, &x0.lambda).ok_or_else(|| no_normals(t))?.value;
    let mut last = f64::INFINITY;
    for _ in 0..MAX_NEWTON {
        let (mut qdd, mut lambda) = (x0.qdd, x0.lambda);
        for (k, gq, gl) in &unit {
            qdd += gq * nu[*k].abs();
            lambda += gl * nu[*k].abs();
        }
        let n = at(&qdd, &lambda).ok_or_else(|| no_normals(t))?;
        // The size of the terms a normal is made of: where they cancel (a normal through
        // zero) its rounding is theirs, not `eps |nu|`.
        let terms = unit
            .iter()
            .map(|&(k, ..)| {
                n.d_qdd[k].abs().dot(&qdd.abs()) + n.d_lambda[k].abs().dot(&lambda.abs())
            })
            .fold(0.0f64, f64::max);
        let (mut jac, mut r) = (Matrix::<F, F>::identity(), Vector::<F>::zeros());
        for &(k, ..) in &unit {
            r[k] = nu[k] - n.value[k];
            for (j, gq, gl) in &unit {
                let sign = if nu[*j] < 0.0 { -1.0 } else { 1.0 };
                jac[(k, *j)] -= (n.d_qdd[k].dot(gq) + n.d_lambda[k].dot(gl)) * sign;
            }
        }
        let d = Lu::factor(jac)
            .map(|lu| lu.solve(&r))
            .filter(|d| d.iter().all(|v| v.is_finite()))
            .ok_or_else(|| not_converged(t))?;
        let (mut size, mut scale) = (0.0f64, terms);
        for &(k, ..) in &unit {
            nu[k] -= d[k];
            (size, scale) = (size.max(d[k].abs()), scale.max(nu[k].abs()));
        }
        // Converged to rounding: a step below 2 eps, or one that stopped halving near it.
        if size <= 2.0 * f64::EPSILON * scale || (size <= 1e-10 * scale && size > 0.5 * last) {
            for &k in &sliding {
                c.normal[k] = nu[k];
            }
            return Ok(());
        }
        last = size;
    }
    Err(not_converged(t))
}

#[cold]
fn not_converged(t: f64) -> Error {
    Error::InvalidInput {
        what: "friction",
        detail: format!(
            "the implicit normal force did not converge at t = {t} (friction too large for the \
             joint to have a solution?)"
        ),
    }
}

/// Whether the modes of the contacts marked `free` are consistent with the solution:
/// `strict`, a stuck load strictly inside its bound and a slide strictly accelerating (so
/// that the new mode's switching functions start positive, and a load exactly at the bound
/// slides when it can); otherwise with the boundaries included.
fn consistent<const N: usize, const M: usize, const F: usize>(
    c: &Contacts<N, M, F>,
    along: &[usize; F],
    modes: &[Slip; F],
    free: &[bool; F],
    s: &InModes<N, M, F>,
    strict: bool,
) -> bool {
    (0..F).filter(|&k| free[k]).all(|k| {
        let (margin, a) = (
            c.mu_s[k] * c.normal[k].abs() - s.load[k].abs(),
            s.qdd[along[k]],
        );
        match (modes[k], strict) {
            (Slip::Stick, true) => margin > 0.0,
            (Slip::Stick, false) => margin >= 0.0,
            (Slip::Forward, true) => a > 0.0,
            (Slip::Forward, false) => a >= 0.0,
            (Slip::Backward, true) => a < 0.0,
            (Slip::Backward, false) => a <= 0.0,
        }
    })
}

/// The modes at a state: `fixed[k]` where given (a sliding contact's direction, or a
/// forced breakaway), and for the others (at rest) the first consistent combination,
/// most contacts stuck first, strictly consistent ones before those on a boundary. Returns
/// the modes with their solution.
pub fn choose<const N: usize, const M: usize, const F: usize, const A: usize>(
    t: f64,
    c: &Contacts<N, M, F>,
    along: &[usize; F],
    fixed: &[Option<Slip>; F],
) -> Result<([Slip; F], InModes<N, M, F>)> {
    choose_in::<N, M, F, A>(t, c.clone(), along, fixed, None).map(|(m, _, s)| (m, s))
}

/// [`choose`] with implicit normals ([`resolve`]); also returns the contacts with the
/// normals of the chosen modes.
pub fn choose_in<const N: usize, const M: usize, const F: usize, const A: usize>(
    t: f64,
    mut c: Contacts<N, M, F>,
    along: &[usize; F],
    fixed: &[Option<Slip>; F],
    normals: Option<NormalsAt<'_, N, M, F>>,
) -> Result<([Slip; F], Contacts<N, M, F>, InModes<N, M, F>)> {
    let free: [bool; F] = std::array::from_fn(|k| fixed[k].is_none());
    let resting: Vec<usize> = (0..F).filter(|&k| free[k]).collect();
    if resting.len() > MAX_RESTING {
        return Err(Error::InvalidInput {
            what: "friction",
            detail: format!(
                "{} contacts at rest at once (at most {MAX_RESTING})",
                resting.len()
            ),
        });
    }
    let combos = 3usize.pow(resting.len() as u32);
    for (strict, sliding) in [true, false]
        .into_iter()
        .flat_map(|strict| (0..=resting.len()).map(move |n| (strict, n)))
    {
        for code in 0..combos {
            let mut modes: [Slip; F] = std::array::from_fn(|k| fixed[k].unwrap_or(Slip::Stick));
            let (mut rest, mut n_sliding) = (code, 0);
            for &k in &resting {
                modes[k] = match rest % 3 {
                    0 => Slip::Stick,
                    1 => Slip::Forward,
                    _ => Slip::Backward,
                };
                n_sliding += usize::from(rest % 3 != 0);
                rest /= 3;
            }
            if n_sliding != sliding {
                continue;
            }
            let sticks = resting.iter().any(|&k| modes[k] == Slip::Stick);
            let s = match resolve::<N, M, F, A>(t, &mut c, along, &modes, normals) {
                Ok(s) => s,
                // A stuck row dependent on the constraints (a slider-crank's piston at a dead
                // centre, where the loop moves it at second order only): that contact cannot
                // stick there; the other combinations decide.
                Err(Error::SingularConstraintJacobian { .. }) if sticks => continue,
                Err(e) => return Err(e),
            };
            if consistent(&c, along, &modes, &free, &s, strict) {
                return Ok((modes, c, s));
            }
        }
    }
    Err(Error::InvalidInput {
        what: "friction",
        detail: format!("no consistent stick/slip modes at t = {t} (a frictional paradox?)"),
    })
}

/// `q` and `qd` of `y = [q; qd]`.
fn split<const N: usize, const D: usize>(y: &Vector<D>) -> (Vector<N>, Vector<N>) {
    const { assert!(D == 2 * N, "first-order state must be [q; qd]") };
    (
        Vector::<N>::from_fn(|i, _| y[i]),
        Vector::<N>::from_fn(|i, _| y[N + i]),
    )
}

/// The sliding contacts' directions from the velocities; `None` at rest.
fn moving<const N: usize, const F: usize>(along: &[usize; F], qd: &Vector<N>) -> [Option<Slip>; F] {
    std::array::from_fn(|k| match direction(qd[along[k]]) {
        d if d > 0.0 => Some(Slip::Forward),
        d if d < 0.0 => Some(Slip::Backward),
        _ => None,
    })
}

/// `f` of a model's contacts at `(t, q, qd)` and, where it has implicit normal forces,
/// them as functions of the solution ([`resolve`]).
fn at_state<S, R, const N: usize, const M: usize, const F: usize, const A: usize>(
    sys: &S,
    t: f64,
    (q, qd): (&Vector<N>, &Vector<N>),
    f: impl FnOnce(Contacts<N, M, F>, Option<NormalsAt<'_, N, M, F>>) -> R,
) -> R
where
    S: Frictional<N, M, F, A>,
{
    let at = |qdd: &Vector<N>, lambda: &Vector<M>| sys.normals(t, q, qd, qdd, lambda);
    f(
        sys.contacts(t, q, qd),
        S::IMPLICIT.then_some(&at as NormalsAt<'_, N, M, F>),
    )
}

/// The accelerations and multipliers of the plain model at a state: the modes from
/// [`choose`] (at rest from the loads, never from the sign of a zero velocity).
pub fn acceleration_and_multipliers<
    S,
    const N: usize,
    const M: usize,
    const F: usize,
    const A: usize,
>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> Result<(Vector<N>, Vector<M>)>
where
    S: Frictional<N, M, F, A>,
{
    let fixed = moving(&S::ALONG, qd);
    let (_, _, s) = at_state(sys, t, (q, qd), |c, n| {
        choose_in::<N, M, F, A>(t, c, &S::ALONG, &fixed, n)
    })?;
    Ok((s.qdd, s.lambda))
}

/// `y' = [qd; qdd]` with the contacts in `modes` ([`crate::model::Hybrid::rhs_in`]).
pub fn rhs_in<S, const N: usize, const M: usize, const F: usize, const A: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    modes: &[Slip; F],
) -> Result<Vector<D>>
where
    S: Frictional<N, M, F, A>,
{
    let (q, qd) = split::<N, D>(y);
    let s = at_state(sys, t, (&q, &qd), |mut c, n| {
        resolve::<N, M, F, A>(t, &mut c, &S::ALONG, modes, n)
    })?;
    Ok(Vector::<D>::from_fn(|i, _| {
        if i < N { qd[i] } else { s.qdd[i - N] }
    }))
}

/// Switching function `k` ([`crate::model::Hybrid::switching`]): the sliding velocity in
/// the sliding direction, or, stuck, the margin `mu_s |N| - |h|` of the holding force.
pub fn switching<
    S,
    const N: usize,
    const M: usize,
    const F: usize,
    const A: usize,
    const D: usize,
>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    modes: &[Slip; F],
    k: usize,
) -> f64
where
    S: Frictional<N, M, F, A>,
{
    let v = y[N + S::ALONG[k]];
    match modes[k] {
        Slip::Forward => v,
        Slip::Backward => -v,
        Slip::Stick => {
            let (q, qd) = split::<N, D>(y);
            at_state(sys, t, (&q, &qd), |mut c, n| {
                resolve::<N, M, F, A>(t, &mut c, &S::ALONG, modes, n).map_or(f64::NAN, |s| {
                    c.mu_s[k] * c.normal[k].abs() - s.load[k].abs()
                })
            })
        }
    }
}

/// Kink function `k` ([`crate::model::Hybrid::kink`]): a sliding contact's normal force,
/// whose sign change is a kink in its friction `mu_k |N|` (the driver locates it and
/// restarts there); `1.0` for a stuck contact, whose holding load does not depend on `|N|`.
pub fn kink<S, const N: usize, const M: usize, const F: usize, const A: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    modes: &[Slip; F],
    k: usize,
) -> f64
where
    S: Frictional<N, M, F, A>,
{
    if modes[k] == Slip::Stick {
        return 1.0;
    }
    let (q, qd) = split::<N, D>(y);
    if !S::IMPLICIT {
        return sys.contacts(t, &q, &qd).normal[k];
    }
    at_state(sys, t, (&q, &qd), |mut c, n| {
        resolve::<N, M, F, A>(t, &mut c, &S::ALONG, modes, n).map_or(f64::NAN, |_| c.normal[k])
    })
}

/// Where switching function `k` is the sliding velocity (`modes[k]` slides):
/// `(N + along[k], +-1)` ([`crate::model::Hybrid::switching_state`]).
pub fn switching_state<const N: usize, const F: usize>(
    along: &[usize; F],
    modes: &[Slip; F],
    k: usize,
) -> Option<(usize, f64)> {
    match modes[k] {
        Slip::Forward => Some((N + along[k], 1.0)),
        Slip::Backward => Some((N + along[k], -1.0)),
        Slip::Stick => None,
    }
}

/// The modes at a state ([`crate::model::Hybrid::mode_at`]).
pub fn mode_at<S, const N: usize, const M: usize, const F: usize, const A: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
) -> Result<[Slip; F]>
where
    S: Frictional<N, M, F, A>,
{
    let (q, qd) = split::<N, D>(y);
    let fixed = moving(&S::ALONG, &qd);
    let chosen = at_state(sys, t, (&q, &qd), |c, n| {
        choose_in::<N, M, F, A>(t, c, &S::ALONG, &fixed, n)
    })?;
    Ok(chosen.0)
}

/// The modes after switching function `k` of `modes` crossed zero
/// ([`crate::model::Hybrid::switch`]): a sliding contact that stopped gets exactly zero
/// velocity and its mode from the loads; a stuck one that lost its hold (under a load) slides in the
/// direction of its load. The other contacts at rest are chosen again with them.
pub fn switch<S, const N: usize, const M: usize, const F: usize, const A: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &mut Vector<D>,
    modes: &[Slip; F],
    k: usize,
) -> Result<[Slip; F]>
where
    S: Frictional<N, M, F, A>,
{
    let along = &S::ALONG;
    let mut forced = None;
    if modes[k] == Slip::Stick {
        let (q, qd) = split::<N, D>(y);
        let held = at_state(sys, t, (&q, &qd), |mut c, n| {
            resolve::<N, M, F, A>(t, &mut c, along, modes, n)
        })?;
        // No load (the bound touched zero with the normal force): nothing to slide
        // towards; the modes at the state decide (forcing a direction there would start a
        // slide whose kinetic friction drives the body from rest).
        forced = match held.load[k] {
            h if h > 0.0 => Some(Slip::Forward),
            h if h < 0.0 => Some(Slip::Backward),
            _ => None,
        };
    } else {
        y[N + along[k]] = 0.0;
        stop_tied::<S, N, M, F, A, D>(sys, t, y, modes, k);
    }
    // Stuck contacts keep exactly zero velocity, so they count as at rest here.
    let (q, qd) = split::<N, D>(y);
    let mut fixed = moving(along, &qd);
    if forced.is_some() {
        fixed[k] = forced;
    }
    let chosen = at_state(sys, t, (&q, &qd), |c, n| {
        choose_in::<N, M, F, A>(t, c, along, &fixed, n)
    })?;
    Ok(chosen.0)
}

/// When sliding contact `k` stops, the contacts the constraints tie to it and to the stuck
/// ones (two blocks joined by a bar) stop with it: their velocities are then zero to
/// rounding only (the velocity constraint holds to the integration's accuracy), and taking
/// that rounding for sliding would give a contact at rest kinetic friction and the wrong
/// mode. A contact is tied when its velocity is zero on every velocity allowed by
/// `Phi_q qd = 0` with the stopped and stuck contacts at rest (its row lies in their span).
fn stop_tied<S, const N: usize, const M: usize, const F: usize, const A: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &mut Vector<D>,
    modes: &[Slip; F],
    k: usize,
) where
    S: Frictional<N, M, F, A>,
{
    if M == 0 {
        return;
    }
    let (q, qd) = split::<N, D>(y);
    let phi_q = sys.contacts(t, &q, &qd).phi_q;
    let held: Vec<usize> = (0..F)
        .filter(|&j| j == k || modes[j] == Slip::Stick)
        .map(|j| S::ALONG[j])
        .collect();
    let mut g = nalgebra::DMatrix::<f64>::zeros(M + held.len(), N);
    g.view_mut((0, 0), (M, N)).copy_from(&phi_q);
    for (r, &s) in held.iter().enumerate() {
        g[(M + r, s)] = 1.0;
    }
    // The allowed velocities: the null space of `g`, from the eigenvectors of `g^T g`.
    let Some(eig) = nalgebra::SymmetricEigen::try_new(g.transpose() * &g, f64::EPSILON, 10_000)
    else {
        return;
    };
    let top = eig.eigenvalues.amax();
    if !top.is_finite() {
        return;
    }
    let free: Vec<usize> = (0..N)
        .filter(|&i| eig.eigenvalues[i] <= 1e-10 * top)
        .collect();
    for j in (0..F).filter(|&j| modes[j] != Slip::Stick && j != k) {
        let s = S::ALONG[j];
        if free.iter().all(|&i| eig.eigenvectors[(s, i)].abs() <= 1e-9) {
            y[N + s] = 0.0;
        }
    }
}

/// The accelerations in given modes ([`resolve`]): the sliding view of a model whose
/// normal forces are implicit.
pub fn acceleration_in<S, const N: usize, const M: usize, const F: usize, const A: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
    modes: &[Slip; F],
) -> Result<Vector<N>>
where
    S: Frictional<N, M, F, A>,
{
    at_state(sys, t, (q, qd), |mut c, n| {
        resolve::<N, M, F, A>(t, &mut c, &S::ALONG, modes, n)
    })
    .map(|s| s.qdd)
}

/// Whether static friction holds contact `k` at rest at `(t, y)`: stuck, the others in
/// the modes of their velocities (stuck at rest), `|h_k| <= mu_s |N_k|` with the normals
/// at that solution.
pub fn sticks<S, const N: usize, const M: usize, const F: usize, const A: usize, const D: usize>(
    sys: &S,
    t: f64,
    y: &Vector<D>,
    k: usize,
) -> Result<bool>
where
    S: Frictional<N, M, F, A>,
{
    let (q, qd) = split::<N, D>(y);
    let mut modes = moving(&S::ALONG, &qd).map(|m| m.unwrap_or(Slip::Stick));
    modes[k] = Slip::Stick;
    at_state(sys, t, (&q, &qd), |mut c, n| {
        let s = resolve::<N, M, F, A>(t, &mut c, &S::ALONG, &modes, n)?;
        Ok(s.load[k].abs() <= c.mu_s[k] * c.normal[k].abs())
    })
}

/// A constrained model's projection in `modes`: the model's own, after which the stuck
/// contacts' velocities are set back to exactly zero.
pub fn project_in<const N: usize, const F: usize, const D: usize>(
    along: &[usize; F],
    y: &mut Vector<D>,
    modes: &[Slip; F],
) {
    for k in 0..F {
        if modes[k] == Slip::Stick {
            y[N + along[k]] = 0.0;
        }
    }
}

/// The generalised forces of the plain model at a state, friction included: kinetic
/// friction at sliding contacts and, at contacts at rest, the force the chosen mode puts
/// there (the holding force when stuck), so that `M qdd (+ Phi_q^T lambda) = f` holds with
/// the accelerations of [`acceleration_and_multipliers`]. Where no mode is consistent (or
/// the solve fails), its error, as the accelerations give it.
pub fn forces<S, const N: usize, const M: usize, const F: usize, const A: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> Result<Vector<N>>
where
    S: Frictional<N, M, F, A>,
{
    let (mut f, (_, friction)) = with_contact_forces(sys, t, q, qd)?;
    for k in 0..F {
        f[S::ALONG[k]] += friction[k];
    }
    Ok(f)
}

/// Each contact's friction force at a state, along its coordinate (a generalised force: a
/// torque on an angle), with the modes at that state: `-mu_k |N| sign(qd_s)` sliding, and
/// at rest the force the chosen mode puts there (stuck, the holding force, `-h`). Its
/// product with `qd_s` is the friction's power, so its integral over a run is the energy
/// friction took. The same modes and solve as [`forces`].
pub fn contact_forces<S, const N: usize, const M: usize, const F: usize, const A: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> Result<([Slip; F], [f64; F])>
where
    S: Frictional<N, M, F, A>,
{
    with_contact_forces(sys, t, q, qd).map(|(_, r)| r)
}

/// The forces without friction, and the modes and friction forces ([`contact_forces`]).
#[allow(clippy::type_complexity, reason = "one tuple, named by its callers")]
fn with_contact_forces<S, const N: usize, const M: usize, const F: usize, const A: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
    qd: &Vector<N>,
) -> Result<(Vector<N>, ([Slip; F], [f64; F]))>
where
    S: Frictional<N, M, F, A>,
{
    let fixed = moving(&S::ALONG, qd);
    // The normals the chosen modes resolved (implicit ones need the solution).
    let (modes, c, s) = at_state(sys, t, (q, qd), |c, n| {
        choose_in::<N, M, F, A>(t, c, &S::ALONG, &fixed, n)
    })?;
    let friction = std::array::from_fn(|k| match modes[k] {
        Slip::Forward => -c.mu_k[k] * c.normal[k].abs(),
        Slip::Backward => c.mu_k[k] * c.normal[k].abs(),
        Slip::Stick => -s.load[k],
    });
    Ok((c.forces, (modes, friction)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One block on a floor (`m = 2`, `N = 19.62`, `mu_k = 0.4`, `mu_s = 0.5`) pushed by `p`.
    fn floor(p: f64) -> Contacts<1, 0, 1> {
        Contacts {
            mass: Matrix::<1, 1>::new(2.0),
            forces: Vector::<1>::new(p),
            phi_q: Matrix::<0, 1>::zeros(),
            gamma: Vector::<0>::zeros(),
            normal: [19.62],
            mu_k: [0.4],
            mu_s: [0.5],
        }
    }

    #[test]
    fn direction_of_zero_is_zero() {
        assert_eq!(direction(0.0), 0.0);
        assert_eq!(direction(-0.0), 0.0);
        assert_eq!(direction(1e-300), 1.0);
        assert_eq!(direction(-1e-300), -1.0);
    }

    #[test]
    fn modes_at_rest_follow_the_load() {
        let free = [None];
        for (p, mode, a) in [
            (0.0, Slip::Stick, 0.0),
            (9.8, Slip::Stick, 0.0),
            (-9.8, Slip::Stick, 0.0),
            (12.0, Slip::Forward, (12.0 - 0.4 * 19.62) / 2.0),
            (-12.0, Slip::Backward, (-12.0 + 0.4 * 19.62) / 2.0),
        ] {
            let (modes, s) = choose::<1, 0, 1, 2>(0.0, &floor(p), &[0], &free).unwrap();
            assert_eq!(modes, [mode], "p = {p}");
            assert!((s.qdd[0] - a).abs() <= 1e-15, "p = {p}");
            if mode == Slip::Stick {
                assert_eq!(s.load[0], p);
            }
        }
    }

    /// A load exactly at the static bound slides when kinetic friction is lower (sticking
    /// would start its switching function at zero, where no crossing can be seen), and
    /// sticks when the two coefficients are equal (no slide accelerates).
    #[test]
    fn a_load_at_the_bound_slides_if_it_can() {
        let bound = 0.5 * 19.62;
        let (modes, _) = choose::<1, 0, 1, 2>(0.0, &floor(bound), &[0], &[None]).unwrap();
        assert_eq!(modes, [Slip::Forward]);
        let mut c = floor(bound);
        c.mu_k = [0.5];
        let (modes, s) = choose::<1, 0, 1, 2>(0.0, &c, &[0], &[None]).unwrap();
        assert_eq!(modes, [Slip::Stick]);
        assert_eq!(s.qdd[0], 0.0);
    }

    #[test]
    fn static_below_kinetic_is_refused() {
        let mut c = floor(0.0);
        c.mu_s = [0.3];
        assert!(matches!(
            solve_in::<1, 0, 1, 2>(0.0, &c, &[0], &[Slip::Stick]),
            Err(Error::InvalidInput { .. })
        ));
    }
}
