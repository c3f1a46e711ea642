//! Static equilibrium: the configuration where the generalised forces balance at rest,
//! `f(q, 0, t) = 0`, or for closed loops `f(q, 0, t) - Phi_q^T lambda = 0`, `Phi(q, t) = 0`
//! (the equations of motion with `qd = qdd = 0`; Haug 1989, ch. 6).
//!
//! Newton's method with the Jacobian of the residual by forward differences
//! ([`jacobian::forward_difference`](crate::jacobian::forward_difference)): statics is
//! called once, not per step, so exactness of the Jacobian is not worth generated code.
//! The equilibrium found is the one Newton reaches from the guess; it may be unstable.

use super::{NewtonOptions, max_norm};
use crate::error::{Error, Result};
use crate::jacobian::forward_difference;
use crate::linalg::Lu;
use crate::model::{Constrained, Mechanism, Vector};

/// The equilibrium `q` of an unconstrained mechanism, `f(q, 0, t) = 0`, from `q_guess`.
///
/// Converged when the Newton step satisfies `max |dq_i| <= tol (1 + max |q_i|)`. A step
/// that leaves a minimal closed loop's domain is halved back into it.
/// A model with constraint rows is refused ([`Error::InvalidInput`]): its equilibrium is
/// [`static_equilibrium_constrained`]'s.
/// Errors: [`Error::StaticsFailed`] when the iterations run out or the stiffness
/// `-df/dq` is singular (neutral equilibrium, or a coordinate nothing holds) and no
/// equilibrium is reached; where a singular stiffness has a family of equilibria (a free
/// body under balanced loads) the one returned is one of them, which one left to rounding;
/// [`Error::SingularPosition`] when `f` cannot be evaluated at an iterate (a closed loop
/// outside its domain, naming the coordinate and the configuration); the model's errors.
pub fn static_equilibrium<S: Mechanism<N>, const N: usize>(
    sys: &S,
    t: f64,
    q_guess: &Vector<N>,
    opts: &NewtonOptions,
) -> Result<Vector<N>> {
    crate::model::unconstrained::<S, N>("static_equilibrium", "static_equilibrium_constrained")?;
    let zero = Vector::<N>::zeros();
    newton(t, q_guess, |q| sys.forces(t, q, &zero), opts)
}

/// The equilibrium `(q, lambda)` of a constrained mechanism from `q_guess` (`A = N + M`):
/// `f(q, 0, t) - Phi_q^T lambda = 0` and `Phi(q, t) = 0`, Newton on `(q, lambda)` from the
/// least-squares multipliers at the guess (`Phi_q Phi_q^T lambda = Phi_q f`; zero where
/// `Phi_q` lacks rank there). Not from `lambda = 0`: with loads that do not depend on the
/// configuration (a press's load and torque) the residual's Jacobian at `lambda = 0` is
/// `[[0, -Phi_q^T], [Phi_q, 0]]`, singular, since the stiffness `lambda . Phi_qq` is
/// missing. The multipliers follow the convention of [`Constrained`] (`-Phi_q^T lambda` is
/// the constraint force).
///
/// Converged when every component of the step satisfies `|dz_i| <= tol (1 + |z_i|)`,
/// `z = (q, lambda)`. Errors as [`static_equilibrium`].
pub fn static_equilibrium_constrained<
    S: Constrained<N, M>,
    const N: usize,
    const M: usize,
    const A: usize,
>(
    sys: &S,
    t: f64,
    q_guess: &Vector<N>,
    opts: &NewtonOptions,
) -> Result<(Vector<N>, Vector<M>)> {
    const { assert!(A == N + M, "the unknowns are (q, lambda): A = N + M") };
    let zero = Vector::<N>::zeros();
    let residual = |z: &Vector<A>| {
        let q = z.fixed_rows::<N>(0).into_owned();
        let lambda = z.fixed_rows::<M>(N).into_owned();
        let mut r = Vector::<A>::zeros();
        r.fixed_rows_mut::<N>(0)
            .copy_from(&(sys.forces(t, &q, &zero)? - sys.phi_q(t, &q).transpose() * lambda));
        r.fixed_rows_mut::<M>(N).copy_from(&sys.phi(t, &q));
        Ok(r)
    };
    let mut z0 = Vector::<A>::zeros();
    z0.fixed_rows_mut::<N>(0).copy_from(q_guess);
    let jac = sys.phi_q(t, q_guess);
    if let Some(lu) = Lu::factor(jac * jac.transpose()) {
        let lambda = lu.solve(&(jac * sys.forces(t, q_guess, &zero)?));
        if lambda.iter().all(|v| v.is_finite()) {
            z0.fixed_rows_mut::<M>(N).copy_from(&lambda);
        }
    }
    let z = newton(t, &z0, residual, opts)?;
    Ok((
        z.fixed_rows::<N>(0).into_owned(),
        z.fixed_rows::<M>(N).into_owned(),
    ))
}

/// Halvings of a Newton step that left a closed loop's domain before the step is taken
/// as it is (and the next residual reports the singular position).
const HALVINGS: usize = 30;

/// `dz`, halved while `z + dz` lies outside a minimal closed loop's domain (the residual
/// there is [`Error::SingularPosition`]): the guess is inside, so is the equilibrium
/// sought, and a full step out of the domain (where the stiffness nearly vanishes) would
/// end the search at a configuration that cannot assemble.
fn into_domain<const K: usize>(
    r: &impl Fn(&Vector<K>) -> Result<Vector<K>>,
    z: &Vector<K>,
    dz: Vector<K>,
) -> Vector<K> {
    let mut step = dz;
    for _ in 0..HALVINGS {
        if !matches!(r(&(z + step)), Err(Error::SingularPosition { .. })) {
            return step;
        }
        step *= 0.5;
    }
    dz
}

/// Newton on `r(z) = 0` with a forward-difference Jacobian refreshed every iteration.
fn newton<const K: usize>(
    t: f64,
    z0: &Vector<K>,
    r: impl Fn(&Vector<K>) -> Result<Vector<K>>,
    opts: &NewtonOptions,
) -> Result<Vector<K>> {
    opts.validate()?;
    let mut z = *z0;
    for iteration in 0..opts.max_iterations {
        let rz = r(&z)?;
        let residual = max_norm(&rz);
        if !residual.is_finite() {
            return Err(Error::NonFinite { t });
        }
        let failed = Error::StaticsFailed {
            t,
            iterations: iteration,
            residual,
        };
        let jac = forward_difference(&r, &z).map_err(|e| match e {
            Error::NonFinite { .. } => Error::NonFinite { t },
            e => e,
        })?;
        let dz = Lu::factor(jac).ok_or(failed)?.solve(&(-rz));
        if !dz.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFinite { t });
        }
        let step = into_domain(&r, &z, dz);
        z += step;
        if step == dz
            && dz
                .iter()
                .zip(z.iter())
                .all(|(d, v)| d.abs() <= opts.tol * (1.0 + v.abs()))
        {
            return Ok(z);
        }
    }
    Err(Error::StaticsFailed {
        t,
        iterations: opts.max_iterations,
        residual: max_norm(&r(&z)?),
    })
}
