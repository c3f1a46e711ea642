//! Rank of the constraint Jacobian at run time: which constraint equations are redundant
//! (dependent on the others) at a configuration.
//!
//! Modified Gram–Schmidt on the rows of `Phi_q` with row pivoting (the largest remaining row
//! first; Golub & Van Loan, *Matrix Computations*, 4th ed., Sect. 5.4.2, applied to
//! `Phi_q^T`): a row whose remainder is below [`RANK_TOL`] times the largest row norm is
//! in the span of the rows taken before it.

use super::RANK_TOL;
use crate::model::{Constrained, Matrix, Vector};

/// The rank of `Phi_q` and the indices of the rows left over when it was reached (each a
/// combination of the others): empty when `Phi_q` has full row rank.
pub fn rank_and_redundant<const M: usize, const N: usize>(
    phi_q: &Matrix<M, N>,
) -> (usize, Vec<usize>) {
    rank_with(phi_q, RANK_TOL)
}

/// [`rank_and_redundant`] with a row counting as dependent when its remainder is below
/// `tol` times the largest row norm (a numerical rank: near a singular position the rows
/// about to vanish).
pub fn rank_with<const M: usize, const N: usize>(
    phi_q: &Matrix<M, N>,
    tol: f64,
) -> (usize, Vec<usize>) {
    let (norms, order) = pivots(phi_q);
    let rank = norms.iter().take_while(|&&r| r > tol).count();
    let mut rest: Vec<usize> = order[rank..].to_vec();
    rest.sort_unstable();
    (rank, rest)
}

/// The remainders of the rows of `Phi_q` in pivot order (largest remaining row first),
/// relative to the largest row norm: `r[k]` is how far the `k+1`-th row taken is from the
/// span of those before it. Near a singular position the last of the first `rank` ones
/// shrinks like the distance to it.
pub fn pivot_remainders<const M: usize, const N: usize>(phi_q: &Matrix<M, N>) -> Vec<f64> {
    pivots(phi_q).0
}

/// Modified Gram–Schmidt with row pivoting: the relative remainders and the row order.
fn pivots<const M: usize, const N: usize>(phi_q: &Matrix<M, N>) -> (Vec<f64>, Vec<usize>) {
    let mut rows: Vec<Vector<N>> = (0..M).map(|k| phi_q.row(k).transpose()).collect();
    let scale = rows.iter().map(|r| r.norm()).fold(0.0, f64::max);
    let mut left: Vec<usize> = (0..M).collect();
    let (mut norms, mut order) = (Vec::with_capacity(M), Vec::with_capacity(M));
    while !left.is_empty() {
        let (pos, norm) = left
            .iter()
            .enumerate()
            .map(|(p, &k)| (p, rows[k].norm()))
            .fold((0, -1.0), |b, c| if c.1 > b.1 { c } else { b });
        let k = left.swap_remove(pos);
        order.push(k);
        let relative = if scale > 0.0 { norm / scale } else { 0.0 };
        norms.push(if relative.is_nan() { 0.0 } else { relative });
        if norm.is_nan() || norm <= 0.0 {
            continue;
        }
        let e = rows[k] / norm;
        for &j in &left {
            for _pass in 0..2 {
                let c = e.dot(&rows[j]);
                rows[j] -= e * c;
            }
        }
    }
    (norms, order)
}

/// The constraint equations that are redundant at `(q, t)`: dependent on the others, so
/// their multipliers are not unique (the solves return the minimum-norm ones).
pub fn redundant_constraints<S: Constrained<N, M>, const N: usize, const M: usize>(
    sys: &S,
    t: f64,
    q: &Vector<N>,
) -> Vec<usize> {
    rank_and_redundant(&sys.phi_q(t, q)).1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A repeated row and a row that is the sum of two others are found; a regular matrix has none.
    #[test]
    fn finds_dependent_rows() {
        let j = Matrix::<4, 3>::new(
            1.0, 0.0, 2.0, //
            0.0, 1.0, 1.0, //
            1.0, 1.0, 3.0, //
            2.0, 0.0, 4.0,
        );
        let (rank, redundant) = rank_and_redundant(&j);
        assert_eq!(rank, 2);
        assert_eq!(redundant.len(), 2);
        let regular = Matrix::<2, 3>::new(1.0, 0.0, 2.0, 0.0, 1.0, 1.0);
        assert_eq!(rank_and_redundant(&regular), (2, vec![]));
    }
}
