//! Dense LU with partial pivoting on fixed-size matrices, real or complex.
//!
//! nalgebra's own `LU` needs `Const<N>: DimMin` bounds (typenum conversions) that do not
//! hold for a bare `const N: usize` in generic code; this small factorisation needs none,
//! and serves both the real systems and Radau IIA's complex one.

use nalgebra::{ComplexField, SMatrix, SVector};

/// `P A = L U`, stored in place (unit lower `L` below the diagonal).
#[derive(Debug, Clone)]
pub struct Lu<T: ComplexField, const N: usize> {
    lu: SMatrix<T, N, N>,
    perm: [usize; N],
}

impl<T: ComplexField<RealField = f64> + Copy, const N: usize> Lu<T, N> {
    /// Factor `a`; `None` when a pivot is zero or not finite (the matrix is singular).
    pub fn factor(mut a: SMatrix<T, N, N>) -> Option<Self> {
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.modulus()));
        for k in 0..N {
            let (p, pivot) =
                (k..N)
                    .map(|i| (i, a[(i, k)].modulus()))
                    .fold(
                        (k, -1.0),
                        |best, cur| if cur.1 > best.1 { cur } else { best },
                    );
            // Written so that a NaN pivot also counts as singular.
            if pivot.is_nan() || pivot <= scale * f64::EPSILON * N as f64 || !pivot.is_finite() {
                return None;
            }
            if p != k {
                a.swap_rows(p, k);
                perm.swap(p, k);
            }
            let akk = a[(k, k)];
            for i in k + 1..N {
                let l = a[(i, k)] / akk;
                a[(i, k)] = l;
                for j in k + 1..N {
                    let akj = a[(k, j)];
                    a[(i, j)] -= l * akj;
                }
            }
        }
        Some(Lu { lu: a, perm })
    }

    /// `min |U_ii| / max |U_ii|`: small when `A` is nearly singular (a cheap condition
    /// indicator; the pivots of a partially pivoted LU).
    pub fn pivot_ratio(&self) -> f64 {
        let (lo, hi) = (0..N).fold((f64::INFINITY, 0.0f64), |(lo, hi), i| {
            let p = self.lu[(i, i)].modulus();
            (lo.min(p), hi.max(p))
        });
        if hi > 0.0 { lo / hi } else { 0.0 }
    }

    /// `det A`: the product of `U`'s diagonal, with the row swaps' sign.
    pub fn determinant(&self) -> T {
        let mut perm = self.perm;
        let mut det = T::one();
        for i in 0..N {
            det *= self.lu[(i, i)];
            while perm[i] != i {
                let j = perm[i];
                perm.swap(i, j);
                det = -det;
            }
        }
        det
    }

    /// Solve `A x = b` with the stored factors.
    pub fn solve(&self, b: &SVector<T, N>) -> SVector<T, N> {
        let mut x = SVector::<T, N>::from_fn(|i, _| b[self.perm[i]]);
        for i in 0..N {
            for j in 0..i {
                let xj = x[j];
                x[i] -= self.lu[(i, j)] * xj;
            }
        }
        for i in (0..N).rev() {
            for j in i + 1..N {
                let xj = x[j];
                x[i] -= self.lu[(i, j)] * xj;
            }
            x[i] /= self.lu[(i, i)];
        }
        x
    }
}

/// Solve `A x = b` for a symmetric positive definite `A` by `L D L^T` (no square roots,
/// one pass, everything on the stack): the mass-matrix solve of every generated model.
/// `None` when a pivot is not positive (not positive definite) or not finite.
#[inline]
pub fn solve_spd<const N: usize>(
    a: &SMatrix<f64, N, N>,
    b: &SVector<f64, N>,
) -> Option<SVector<f64, N>> {
    Some(Ldl::factor(a)?.solve(b))
}

/// The `L D L^T` factors of a symmetric positive definite matrix (unit lower `L` below the
/// diagonal, `D` on it), for several solves with one matrix (an acceleration Jacobian's
/// `2 N` columns).
#[derive(Debug, Clone)]
pub struct Ldl<const N: usize> {
    l: SMatrix<f64, N, N>,
}

impl<const N: usize> Ldl<N> {
    /// `None` when a pivot is not positive (not positive definite) or not finite.
    #[inline]
    pub fn factor(a: &SMatrix<f64, N, N>) -> Option<Self> {
        let mut l = *a;
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for j in 0..N {
            let mut d = l[(j, j)];
            for k in 0..j {
                d -= l[(j, k)] * l[(j, k)] * l[(k, k)];
            }
            // Not `d > tol` negated: a NaN pivot must fail too.
            if d.is_nan() || d <= scale * f64::EPSILON * N as f64 || !d.is_finite() {
                return None;
            }
            l[(j, j)] = d;
            for i in j + 1..N {
                let mut v = l[(i, j)];
                for k in 0..j {
                    v -= l[(i, k)] * l[(j, k)] * l[(k, k)];
                }
                l[(i, j)] = v / d;
            }
        }
        Some(Self { l })
    }

    /// `x` with `A x = b`.
    #[inline]
    pub fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        let l = &self.l;
        let mut x = *b;
        for i in 0..N {
            for k in 0..i {
                x[i] -= l[(i, k)] * x[k];
            }
        }
        for i in 0..N {
            x[i] /= l[(i, i)];
        }
        for i in (0..N).rev() {
            for k in i + 1..N {
                x[i] -= l[(k, i)] * x[k];
            }
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::{Complex, Matrix3, Vector3};

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // Zero leading pivot: fails without row exchanges.
        let a = Matrix3::new(0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0);
        let x = Vector3::new(1.0, -2.0, 0.5);
        let lu = Lu::factor(a).unwrap();
        assert_relative_eq!(lu.solve(&(a * x)), x, epsilon = 1e-14);
    }

    /// With row exchanges the sign follows the permutation: `det` by cofactors is
    /// `0 (3 - 1) - 2 (3 - 2) + 1 (1 - 2) = -3`; one more swap of rows flips it.
    #[test]
    fn determinant_keeps_the_sign_of_the_row_exchanges() {
        let a = Matrix3::new(0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0);
        assert_relative_eq!(Lu::factor(a).unwrap().determinant(), -3.0, epsilon = 1e-14);
        let mut b = a;
        b.swap_rows(0, 2);
        assert_relative_eq!(Lu::factor(b).unwrap().determinant(), 3.0, epsilon = 1e-14);
    }

    #[test]
    fn ldlt_solves_a_positive_definite_system_and_refuses_an_indefinite_one() {
        let a = Matrix3::new(4.0, 1.0, 0.5, 1.0, 3.0, -0.2, 0.5, -0.2, 2.0);
        let x = Vector3::new(1.0, -2.0, 0.5);
        assert_relative_eq!(solve_spd(&a, &(a * x)).unwrap(), x, epsilon = 1e-14);
        let indefinite = Matrix3::new(1.0, 2.0, 0.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0);
        assert!(solve_spd(&indefinite, &x).is_none());
    }

    #[test]
    fn reports_a_singular_matrix() {
        let a = Matrix3::new(1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0);
        assert!(Lu::factor(a).is_none());
    }

    #[test]
    fn solves_a_complex_system() {
        let i = Complex::new(0.0, 1.0);
        let one = Complex::new(1.0, 0.0);
        let a = nalgebra::Matrix2::new(one + i, 2.0 * one, -i, 3.0 * one);
        let x = nalgebra::Vector2::new(one - i, 2.0 * i);
        let lu = Lu::factor(a).unwrap();
        let err = (lu.solve(&(a * x)) - x).norm();
        assert!(err < 1e-14, "error {err}");
    }
}
