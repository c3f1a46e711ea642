//! Dense output of one accepted step: a polynomial in the normalised time `theta`.

use crate::model::Vector;

/// Coefficients of a [`Segment`]: degree 9, Verner's interpolant (the highest of any method).
pub const TERMS: usize = 10;

/// The continuous solution over one accepted step `[t0, t0 + h]`:
/// `y(t0 + theta h) = sum_k coeffs[k] theta^k`, `theta` in `[0, 1]` (monomial basis,
/// degree at most 9, unused coefficients zero).
///
/// Every method converts its own interpolant (Hermite, Hairer's DOPRI5 continuous
/// extension, DOP853's seventh-order one, Verner's ninth-order one, Radau's collocation polynomial) into this one basis, so event location and
/// `Solution::at` need to know nothing about the method.
#[derive(Debug, Clone)]
pub struct Segment<const D: usize> {
    /// Start of the step.
    pub t0: f64,
    /// Step size (positive).
    pub h: f64,
    /// Monomial coefficients in `theta = (t - t0) / h`, lowest degree first.
    pub coeffs: [Vector<D>; TERMS],
}

impl<const D: usize> Segment<D> {
    /// End of the step, `t0 + h`.
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }

    /// `y(t)` by Horner's rule in `theta = (t - t0) / h`. Meant for `t` in `[t0, t1]`;
    /// outside it extrapolates.
    pub fn eval(&self, t: f64) -> Vector<D> {
        self.eval_theta((t - self.t0) / self.h)
    }

    /// `y(t0 + theta h)` by Horner's rule.
    pub fn eval_theta(&self, theta: f64) -> Vector<D> {
        let mut y = self.coeffs[TERMS - 1];
        for c in self.coeffs[..TERMS - 1].iter().rev() {
            y = y * theta + c;
        }
        y
    }

    /// The cubic Hermite interpolant through `(t0, y0, f0)` and `(t0 + h, y1, f1)`
    /// (Hairer–Nørsett–Wanner I, Sect. II.6, eq. (6.7)), in the monomial basis:
    /// `y0 + theta h f0 + theta^2 (3 d - h (2 f0 + f1)) + theta^3 (h (f0 + f1) - 2 d)`,
    /// `d = y1 - y0`. Third order; exact for cubics.
    pub fn hermite(
        t0: f64,
        h: f64,
        y0: &Vector<D>,
        f0: &Vector<D>,
        y1: &Vector<D>,
        f1: &Vector<D>,
    ) -> Self {
        let d = y1 - y0;
        let hf0 = f0 * h;
        let hf1 = f1 * h;
        Self::polynomial(
            t0,
            h,
            &[*y0, hf0, d * 3.0 - hf0 * 2.0 - hf1, hf0 + hf1 - d * 2.0],
        )
    }

    /// The polynomial `sum_k c[k] theta^k` over `[t0, t0 + h]` (higher coefficients zero).
    pub fn polynomial<const N: usize>(t0: f64, h: f64, c: &[Vector<D>; N]) -> Self {
        const { assert!(N <= TERMS) };
        let mut coeffs = [Vector::<D>::zeros(); TERMS];
        coeffs[..N].copy_from_slice(c);
        Segment { t0, h, coeffs }
    }

    /// The polynomial `r[0] + s (r[1] + s1 (r[2] + s (r[3] + s1 (...))))`, `s = theta`,
    /// `s1 = 1 - theta`, factors alternating from `s` (Hairer's form of the DOPRI5 and
    /// DOP853 continuous extensions), expanded into monomials.
    pub fn from_nested<const N: usize>(t0: f64, h: f64, r: &[Vector<D>; N]) -> Self {
        const { assert!(N >= 1 && N <= TERMS) };
        let zero = Vector::<D>::zeros();
        let mut c = [zero; TERMS];
        c[0] = r[N - 1];
        for j in (0..N - 1).rev() {
            // c <- r[j] + factor * c, factor = s when j is even, 1 - s when odd.
            if j % 2 == 0 {
                c.rotate_right(1);
                c[0] = zero;
            } else {
                for k in (1..TERMS).rev() {
                    c[k] -= c[k - 1];
                }
            }
            c[0] += r[j];
        }
        Segment { t0, h, coeffs: c }
    }

    /// The same polynomial restricted to `[t0, t_end]` (`t_end` inside the step): the
    /// coefficients are rescaled by `s^k`, `s = (t_end - t0) / h`, so values are unchanged.
    pub fn truncated(&self, t_end: f64) -> Self {
        let s = (t_end - self.t0) / self.h;
        let mut coeffs = self.coeffs;
        let mut sk = 1.0;
        for c in coeffs.iter_mut() {
            *c *= sk;
            sk *= s;
        }
        Segment {
            t0: self.t0,
            h: t_end - self.t0,
            coeffs,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hermite cubic reproduces any cubic exactly: y = 1 + 2 t - t^2 + 0.5 t^3.
    #[test]
    fn hermite_is_exact_for_a_cubic() {
        let y = |t: f64| Vector::<1>::new(1.0 + 2.0 * t - t * t + 0.5 * t * t * t);
        let f = |t: f64| Vector::<1>::new(2.0 - 2.0 * t + 1.5 * t * t);
        let (t0, h) = (0.3, 0.7);
        let seg = Segment::hermite(t0, h, &y(t0), &f(t0), &y(t0 + h), &f(t0 + h));
        for i in 0..=10 {
            let t = t0 + h * i as f64 / 10.0;
            assert!((seg.eval(t)[0] - y(t)[0]).abs() < 1e-14);
        }
        assert_eq!(seg.t1(), t0 + h);
    }

    /// Truncation keeps the values: the truncated segment agrees with the original inside.
    #[test]
    fn truncation_keeps_values() {
        let seg = Segment::polynomial(1.0, 2.0, &[1.0, -2.0, 0.5, 3.0, -1.0].map(Vector::<1>::new));
        let cut = seg.truncated(2.2);
        for t in [1.0, 1.5, 2.0, 2.2] {
            assert!((cut.eval(t)[0] - seg.eval(t)[0]).abs() < 1e-13);
        }
        assert!((cut.t1() - 2.2).abs() < 1e-15);
    }
}
