//! Explicit Runge–Kutta tableaus as data, and the one stage routine that runs any of them.

use crate::error::{Error, Result};
use crate::model::{OdeSystem, Vector};

/// An explicit Butcher tableau with `S` stages: nodes `c`, strictly lower-triangular
/// coefficients `a`, weights `b`, and the error weights `e = b - b_hat` of an embedded
/// method (all zero when there is none).
#[derive(Debug, Clone, PartialEq)]
pub struct Erk<const S: usize> {
    /// Nodes `c_i = sum_j a_ij`.
    pub c: [f64; S],
    /// Stage coefficients, `a[i][j] = 0` for `j >= i`.
    pub a: [[f64; S]; S],
    /// Weights of the propagated solution.
    pub b: [f64; S],
    /// `b - b_hat`: the local error estimate is `h sum_i e_i k_i`.
    pub e: [f64; S],
    /// Order of the propagated solution.
    pub order: usize,
    /// Order of the embedded solution (`0` when there is none).
    pub embedded_order: usize,
    /// First same as last: the last stage is `f(t + h, y1)`, reused as the next step's first.
    pub fsal: bool,
}

/// The classic fourth-order Runge–Kutta method (Kutta 1901; Hairer–Nørsett–Wanner I,
/// Sect. II.1, Table 1.2, left).
pub const RK4: Erk<4> = Erk {
    c: [0.0, 1.0 / 2.0, 1.0 / 2.0, 1.0],
    a: [
        [0.0, 0.0, 0.0, 0.0],
        [1.0 / 2.0, 0.0, 0.0, 0.0],
        [0.0, 1.0 / 2.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
    e: [0.0; 4],
    order: 4,
    embedded_order: 0,
    fsal: false,
};

/// Dormand & Prince 5(4) (J. Comput. Appl. Math. 6 (1980) 19–26; Hairer–Nørsett–Wanner I,
/// Sect. II.5, Table 5.2), with the coefficients of Hairer's `dopri5.f`.
pub const DOPRI5: Erk<7> = Erk {
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: [
        [0.0; 7],
        [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
            0.0,
        ],
        [
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
            0.0,
        ],
    ],
    b: [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
        0.0,
    ],
    e: [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ],
    order: 5,
    embedded_order: 4,
    fsal: true,
};

/// Shampine's (1986) fourth-order continuous extension of DOPRI5 as in `dopri5.f`
/// (`D1..D7`): the fifth coefficient of Hairer's dense output is `h sum_i d_i k_i`.
pub const DOPRI5_DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// Largest state dimension whose stage arguments are formed component by component
/// (`f64::mul_add`, a library call per component without the `fma` target feature) instead
/// of in vector registers. Packing the components into one register makes every component
/// of the next argument wait for the whole last call; one at a time, a position component
/// (`q' = v`) waits only for the velocity, so consecutive calls overlap. Measured
/// (`overhead` bench, `work-precision -- --time-to-accuracy`): faster for `D = 2`
/// (pendulum DOPRI5 19.6 -> 18.0 ns per call, DOP853 17.7 -> 16.4; slider-crank in one
/// coordinate 52 -> 45 ns), slower from `D = 6` (8-link chain 197 -> 226 ns).
const SCALAR_STAGES: usize = 2;

impl<const S: usize> Erk<S> {
    /// Evaluate stages `1..S` of a step of size `h` from `(t, y)`. On entry `k[0]` holds
    /// `f(t, y)`; on return `k[i] = f(t + c_i h, z[i])` with the stage arguments
    /// `z[i] = y + h sum_{j<i} a_ij k_j` (`z[0] = y`). Makes `S - 1` calls of `rhs`; a
    /// non-finite stage value stops with [`Error::NonFinite`]. Stage storage is the caller's
    /// fixed arrays, so a step does not allocate.
    ///
    /// The stages form a dependent chain (each argument needs the stage before), so the
    /// argument is summed as `(y + h sum_{j<i-1} a_ij k_j) + (h a_{i,i-1}) k_{i-1}`: only one
    /// product and one sum stand between one call's result and the next call (four, as
    /// `y + h (sum_j a_ij k_j)`). From `D = 3` the older part of the next stage's argument is
    /// summed just before each call, so that it runs beside the call rather than after it
    /// (8-link chain, Vern9 at 1.8e-9: 204 -> 187-192 ns per call, the loop's share 41 -> 28
    /// ns); for `D <= 2` after the call, where it delayed the small call's start (pendulum:
    /// 15.7 -> 16.2 ns). The same operations in the same order: results are bit for bit.
    #[inline]
    pub fn stages<F: OdeSystem<D>, const D: usize>(
        &self,
        sys: &F,
        t: f64,
        y: &Vector<D>,
        h: f64,
        k: &mut [Vector<D>; S],
        z: &mut [Vector<D>; S],
    ) -> Result<()> {
        z[0] = *y;
        // The newest stage kept as a value (not re-read from `k`), so it stays in registers.
        let mut newest = k[0];
        let mut base = *y;
        for i in 1..S {
            let coef = h * self.a[i][i - 1];
            let zi = if D <= SCALAR_STAGES {
                newest.zip_map(&base, |n, b| n.mul_add(coef, b))
            } else {
                base + newest * coef
            };
            z[i] = zi;
            let next = i + 1 < S;
            if next && D > SCALAR_STAGES {
                base = self.older_terms(i + 1, y, k, h);
            }
            let ti = t + self.c[i] * h;
            newest = sys.rhs(ti, &zi)?;
            k[i] = newest;
            if next && D <= SCALAR_STAGES {
                base = self.older_terms(i + 1, y, k, h);
            }
            if !newest.iter().all(|v| v.is_finite()) {
                return Err(Error::NonFinite { t: ti });
            }
        }
        Ok(())
    }

    /// `y + h sum_{j<i-1} a_ij k_j`: stage `i`'s argument without its newest term.
    #[inline]
    fn older_terms<const D: usize>(
        &self,
        i: usize,
        y: &Vector<D>,
        k: &[Vector<D>; S],
        h: f64,
    ) -> Vector<D> {
        let row = &self.a[i];
        let mut acc = Vector::<D>::zeros();
        for j in 0..i - 1 {
            if row[j] != 0.0 {
                acc += k[j] * row[j];
            }
        }
        y + acc * h
    }

    /// The propagated solution `y + h sum_i b_i k_i`, summed as the stage arguments are
    /// ([`Self::stages`]): the last stage's term last, so that it alone waits for the last
    /// call.
    #[inline]
    pub fn advance<const D: usize>(&self, y: &Vector<D>, k: &[Vector<D>; S], h: f64) -> Vector<D> {
        let mut acc = Vector::<D>::zeros();
        for (b, kj) in self.b[..S - 1].iter().zip(k) {
            if *b != 0.0 {
                acc += kj * *b;
            }
        }
        (y + acc * h) + k[S - 1] * (h * self.b[S - 1])
    }

    /// `h sum_i w_i k_i` for weights `w` (the increment `b`, or the error `e`).
    #[inline]
    pub fn combine<const D: usize>(w: &[f64; S], k: &[Vector<D>; S], h: f64) -> Vector<D> {
        let mut acc = Vector::<D>::zeros();
        for (wi, ki) in w.iter().zip(k) {
            if *wi != 0.0 {
                acc += ki * *wi;
            }
        }
        acc * h
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rooted tree as the list of its subtrees (a leaf has none).
    #[derive(Debug, Clone)]
    struct Tree(Vec<Tree>);

    impl Tree {
        fn order(&self) -> usize {
            1 + self.0.iter().map(Tree::order).sum::<usize>()
        }
        /// gamma(t) = |t| prod gamma(t_k) (Hairer–Nørsett–Wanner I, Def. II.2.10).
        fn density(&self) -> f64 {
            self.order() as f64 * self.0.iter().map(Tree::density).product::<f64>()
        }
        /// Internal weights g_i(t) = prod_k (A g(t_k))_i, so that the elementary weight is
        /// Phi(t) = sum_i b_i g_i(t) (Hairer–Nørsett–Wanner I, Def. II.2.9).
        fn weights<const S: usize>(&self, a: &[[f64; S]; S]) -> [f64; S] {
            let mut g = [1.0; S];
            for child in &self.0 {
                let gc = child.weights(a);
                for (i, gi) in g.iter_mut().enumerate() {
                    *gi *= (0..S).map(|j| a[i][j] * gc[j]).sum::<f64>();
                }
            }
            g
        }
    }

    /// All rooted trees of order `n`, as multisets of subtrees (non-decreasing index order
    /// in a canonical list, so every tree appears once).
    fn trees(n: usize) -> Vec<Tree> {
        // by_order[m] lists the trees of order m.
        let mut by_order: Vec<Vec<Tree>> = vec![vec![], vec![Tree(vec![])]];
        for m in 2..=n {
            let all: Vec<(usize, Tree)> = (1..m)
                .flat_map(|o| by_order[o].iter().cloned().map(move |t| (o, t)))
                .collect();
            let mut out = Vec::new();
            // Choose a multiset of subtrees from `all` with total order m - 1.
            fn pick(
                all: &[(usize, Tree)],
                from: usize,
                left: usize,
                cur: &mut Vec<Tree>,
                out: &mut Vec<Tree>,
            ) {
                if left == 0 {
                    out.push(Tree(cur.clone()));
                    return;
                }
                for idx in from..all.len() {
                    if all[idx].0 <= left {
                        cur.push(all[idx].1.clone());
                        pick(all, idx, left - all[idx].0, cur, out);
                        cur.pop();
                    }
                }
            }
            pick(&all, 0, m - 1, &mut Vec::new(), &mut out);
            by_order.push(out);
        }
        by_order.swap_remove(n)
    }

    fn check_order<const S: usize>(a: &[[f64; S]; S], b: &[f64; S], p: usize) {
        check_order_to(a, b, p, 1e-14);
    }

    /// The order conditions up to order `p`, each to `tol`.
    fn check_order_to<const S: usize>(a: &[[f64; S]; S], b: &[f64; S], p: usize, tol: f64) {
        for n in 1..=p {
            for t in trees(n) {
                let phi: f64 = t.weights(a).iter().zip(b).map(|(g, b)| g * b).sum();
                let want = 1.0 / t.density();
                assert!(
                    (phi - want).abs() < tol,
                    "order condition for {t:?}: {phi} != {want}"
                );
            }
        }
    }

    fn check_tableau<const S: usize>(tab: &Erk<S>) {
        for i in 0..S {
            let row: f64 = tab.a[i].iter().sum();
            assert!(
                (row - tab.c[i]).abs() < 1e-15,
                "row {i}: {row} != {}",
                tab.c[i]
            );
            assert!(
                tab.a[i][i..].iter().all(|&a| a == 0.0),
                "row {i} not explicit"
            );
        }
        assert!((tab.b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        check_order(&tab.a, &tab.b, tab.order);
        if tab.embedded_order > 0 {
            let b_hat: [f64; S] = std::array::from_fn(|i| tab.b[i] - tab.e[i]);
            check_order(&tab.a, &b_hat, tab.embedded_order);
        }
        if tab.fsal {
            assert_eq!(tab.a[S - 1], tab.b);
            assert_eq!(tab.c[S - 1], 1.0);
        }
    }

    /// The number of rooted trees of orders 1..=5 is 1, 1, 2, 4, 9 (OEIS A000081).
    #[test]
    fn tree_counts() {
        let counts: Vec<usize> = (1..=5).map(|n| trees(n).len()).collect();
        assert_eq!(counts, [1, 1, 2, 4, 9]);
    }

    #[test]
    fn rk4_tableau_is_consistent_and_of_order_4() {
        check_tableau(&RK4);
    }

    /// Order 5 for `b`, order 4 for `b_hat`, FSAL row, and that it is not of order 6
    /// (so the order check can fail).
    #[test]
    fn dopri5_tableau_is_consistent_and_of_order_5_4() {
        check_tableau(&DOPRI5);
        let fails_order_6 = trees(6).iter().any(|t| {
            let phi: f64 = t
                .weights(&DOPRI5.a)
                .iter()
                .zip(&DOPRI5.b)
                .map(|(g, b)| g * b)
                .sum();
            (phi - 1.0 / t.density()).abs() > 1e-6
        });
        assert!(fails_order_6);
    }

    /// Shampine's dense weights at theta = 1 reproduce nothing new: the fifth dense
    /// coefficient must vanish for a linear test function with k_i = 1 (sum d_i = 0),
    /// since the dense polynomial of y' = 1 is exactly y0 + theta h.
    #[test]
    fn dopri5_dense_weights_sum_to_zero() {
        assert!(DOPRI5_DENSE.iter().sum::<f64>().abs() < 1e-13);
    }

    /// DOP853 (`dop853.f`'s 30-digit coefficients): rows sum to the nodes, `b` satisfies
    /// all 200 order conditions of orders 1..=8 and fails one of order 9, `b - e` (the
    /// fifth-order estimate) those of order 5, `bhh` those of order 3. The tolerance 1e-13
    /// covers the rounding of sums of coefficients up to ~40 in size (the conditions hold to
    /// the published digits; a wrong digit in any coefficient past the fourth breaks one).
    #[test]
    fn dop853_tableau_has_orders_8_5_3() {
        use super::super::dop853_tableau::{DOP853, DOP853_BHH};
        for i in 0..12 {
            // Rounding of a sum of terms up to 43 in size: a few units of the largest.
            let row: f64 = DOP853.a[i].iter().sum();
            let size: f64 = DOP853.a[i].iter().map(|a| a.abs()).sum();
            assert!(
                (row - DOP853.c[i]).abs() < 2.0 * f64::EPSILON * size.max(1.0),
                "row {i}"
            );
            assert!(DOP853.a[i][i..].iter().all(|&a| a == 0.0));
        }
        assert_eq!(trees(8).len(), 115);
        check_order_to(&DOP853.a, &DOP853.b, 8, 1e-13);
        let fails_order_9 = trees(9).iter().any(|t| {
            let phi: f64 = t
                .weights(&DOP853.a)
                .iter()
                .zip(&DOP853.b)
                .map(|(g, b)| g * b)
                .sum();
            (phi - 1.0 / t.density()).abs() > 1e-8
        });
        assert!(fails_order_9);
        let b5: [f64; 12] = std::array::from_fn(|i| DOP853.b[i] - DOP853.e[i]);
        check_order_to(&DOP853.a, &b5, 5, 1e-13);
        check_order_to(&DOP853.a, &DOP853_BHH, 3, 1e-13);
    }

    /// The dense stages are consistent (rows sum to their nodes) and the dense output's
    /// weights `d` of each coefficient sum to zero (the polynomial of `y' = 1` is exact).
    #[test]
    fn dop853_dense_rows_are_consistent() {
        use super::super::dop853_tableau::{DOP853_DENSE_A, DOP853_DENSE_C, DOP853_DENSE_D};
        for (row, c) in DOP853_DENSE_A.iter().zip(DOP853_DENSE_C) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14, "{c}");
        }
        for d in &DOP853_DENSE_D {
            assert!(d.iter().sum::<f64>().abs() < 1e-12);
        }
    }

    /// Verner's 9(8) pair: rows sum to the nodes, `b` satisfies all 486 order conditions
    /// of orders 1..=9 and fails one of order 10, `b - e` (the eighth-order estimate)
    /// those of order 8 and fails one of order 9.
    #[test]
    fn vern9_tableau_has_orders_9_8() {
        use super::super::vern9_tableau::VERN9;
        for i in 0..16 {
            let row: f64 = VERN9.a[i].iter().sum();
            let size: f64 = VERN9.a[i].iter().map(|a| a.abs()).sum();
            assert!(
                (row - VERN9.c[i]).abs() < 2.0 * f64::EPSILON * size.max(1.0),
                "row {i}"
            );
            assert!(VERN9.a[i][i..].iter().all(|&a| a == 0.0));
        }
        assert_eq!(trees(9).len(), 286);
        check_order_to(&VERN9.a, &VERN9.b, 9, 1e-13);
        let fails_order_10 = trees(10).iter().any(|t| {
            let phi: f64 = t
                .weights(&VERN9.a)
                .iter()
                .zip(&VERN9.b)
                .map(|(g, b)| g * b)
                .sum();
            (phi - 1.0 / t.density()).abs() > 1e-9
        });
        assert!(fails_order_10);
        let b8: [f64; 16] = std::array::from_fn(|i| VERN9.b[i] - VERN9.e[i]);
        check_order_to(&VERN9.a, &b8, 8, 1e-13);
        let fails_order_9 = trees(9).iter().any(|t| {
            let phi: f64 = t
                .weights(&VERN9.a)
                .iter()
                .zip(&b8)
                .map(|(g, b)| g * b)
                .sum();
            (phi - 1.0 / t.density()).abs() > 1e-9
        });
        assert!(fails_order_9);
    }

    /// Verner's interpolant is of order 9 at every theta: over the extended tableau of 26
    /// stages, the weights `b_i(theta)` satisfy `sum_i b_i(theta) Phi_i(t) =
    /// theta^|t| / gamma(t)` for every tree of order 1..=9 (Hairer–Nørsett–Wanner I,
    /// Sect. II.6, Theorem 6.1), and it ends on the step's solution, `b_i(1) = b_i`.
    #[test]
    fn vern9_interpolant_has_order_9() {
        use super::super::vern9_tableau::{VERN9, VERN9_DENSE_A, VERN9_DENSE_C, VERN9_DENSE_R};
        let mut a = [[0.0; 26]; 26];
        for (row, vern) in a.iter_mut().zip(&VERN9.a) {
            row[..16].copy_from_slice(vern);
        }
        for (j, row) in VERN9_DENSE_A.iter().enumerate() {
            a[17 + j] = *row;
            a[17 + j][17 + j..].iter().for_each(|x| assert_eq!(*x, 0.0));
            let c = VERN9_DENSE_C[j];
            let sum: f64 = row.iter().sum();
            assert!((sum - c).abs() < 1e-14, "dense row {j}: {sum} != {c}");
        }
        a[16][..16].copy_from_slice(&VERN9.b);
        for theta in [0.1f64, 0.37, 0.5, 0.81, 1.0] {
            let b: [f64; 26] = std::array::from_fn(|i| {
                VERN9_DENSE_R
                    .iter()
                    .enumerate()
                    .map(|(m, r)| r[i] * theta.powi(m as i32 + 1))
                    .sum()
            });
            for n in 1..=9 {
                for t in trees(n) {
                    let phi: f64 = t.weights(&a).iter().zip(&b).map(|(g, b)| g * b).sum();
                    let want = theta.powi(n as i32) / t.density();
                    assert!(
                        (phi - want).abs() < 1e-12,
                        "theta {theta}, {t:?}: {phi} != {want}"
                    );
                }
            }
            if theta == 1.0 {
                for (i, (bi, want)) in b.iter().zip(&VERN9.b).enumerate() {
                    assert!((bi - want).abs() < 1e-12, "b_{i}(1)");
                }
            }
        }
    }

    /// The stability function `R(z) = 1 + z b^T (I - z A)^-1 1` of Vern9's ninth-order
    /// solution keeps `|R(-x)| <= 1` on `0 < x <= 4.47` and exceeds it at 4.48: the
    /// stiffness limit `Vern9::STIFF_HLAMBDA` = 4.4 sits just inside.
    #[test]
    fn vern9_real_stability_interval() {
        use super::super::vern9::Vern9;
        use super::super::vern9_tableau::VERN9;
        // R(z) = sum_j z^j b^T A^(j-1) 1 (explicit: a polynomial of degree 16).
        let mut coef = vec![1.0];
        let mut v = [1.0; 16];
        for _ in 0..16 {
            coef.push(VERN9.b.iter().zip(&v).map(|(b, v)| b * v).sum::<f64>());
            v = std::array::from_fn(|i| (0..16).map(|j| VERN9.a[i][j] * v[j]).sum());
        }
        let r = |x: f64| coef.iter().rev().fold(0.0, |acc, c| acc * -x + c);
        for i in 1..=447 {
            let x = f64::from(i) / 100.0;
            assert!(r(x).abs() <= 1.0, "|R(-{x})| = {}", r(x).abs());
        }
        assert!(r(4.48).abs() > 1.0);
        const { assert!(Vern9::STIFF_HLAMBDA < 4.47) };
    }
}
