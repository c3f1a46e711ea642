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
    let mut rows: Vec<Vector<N>> = (0..M).map(|k| phi_q.row(k).transpose()).collect();
    let scale = rows.iter().map(|r| r.norm()).fold(0.0, f64::max);
    let mut left: Vec<usize> = (0..M).collect();
    let mut rank = 0;
    while !left.is_empty() {
        let (pos, norm) = left
            .iter()
            .enumerate()
            .map(|(p, &k)| (p, rows[k].norm()))
            .fold((0, -1.0), |b, c| if c.1 > b.1 { c } else { b });
        if norm.is_nan() || norm <= RANK_TOL * scale {
            break;
        }
        let k = left.swap_remove(pos);
        let e = rows[k] / norm;
        for &j in &left {
            for _pass in 0..2 {
                let c = e.dot(&rows[j]);
                rows[j] -= e * c;
            }
        }
        rank += 1;
    }
    left.sort_unstable();
    (rank, left)
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
