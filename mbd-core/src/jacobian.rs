//! Finite-difference Jacobians: the fallback where a model has no generated one.

use crate::error::{Error, Result};
use crate::model::{Matrix, Vector};

/// `df/dy` by forward differences with the increment `sqrt(eps * max(1e-5, |y_j|))`
/// of Hairer's `radau5.f`; errors of `f` are passed on, non-finite columns are an error.
pub fn forward_difference<const D: usize>(
    f: impl Fn(&Vector<D>) -> Result<Vector<D>>,
    y: &Vector<D>,
) -> Result<Matrix<D, D>> {
    let f0 = f(y)?;
    let mut jac = Matrix::<D, D>::zeros();
    let mut yj = *y;
    for j in 0..D {
        let delta = (f64::EPSILON * 1e-5f64.max(y[j].abs())).sqrt();
        yj[j] = y[j] + delta;
        let fj = f(&yj)?;
        yj[j] = y[j];
        let column = (fj - f0) / delta;
        if !column.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFinite { t: f64::NAN });
        }
        jac.set_column(j, &column);
    }
    Ok(jac)
}
