//! Radau IIA (order 5) against independent truths: the tableau's order conditions, the
//! IVP test set's Van der Pol reference, closed-form linear stiff solutions, the harmonic
//! oscillator, and a ballistic event time.

use mbd_core::integrate::radau5::tableau::{
    A, ALPHA, B, BETA, C, DENSE, GAMMA, SQRT6, T, T_INV,
};
use mbd_core::integrate::{Direction, Event, Integrator, Radau5, Solution};
use mbd_core::{Error, Matrix, OdeSystem, Options, Result, Vector};
use nalgebra::{Matrix2, Matrix3, Vector2};

fn radau(rtol: f64, atol: f64) -> Radau5 {
    Radau5::new(Options {
        rtol,
        atol,
        ..Options::default()
    })
}

// ---------------------------------------------------------------------------------------
// Tableau

/// Simplifying assumptions of a 3-stage collocation method of order 5
/// (Hairer & Wanner II, Sect. IV.5): B(5) `Σ b_i c_i^(k−1) = 1/k` for k ≤ 5,
/// C(3) `Σ_j a_ij c_j^(k−1) = c_i^k / k` for k ≤ 3, and stiff accuracy `b = A[2]`.
#[test]
fn tableau_satisfies_the_collocation_and_order_conditions() {
    assert_eq!(SQRT6, 6f64.sqrt());
    for k in 1..=5 {
        let sum: f64 = (0..3).map(|i| B[i] * C[i].powi(k - 1)).sum();
        assert!((sum - 1.0 / k as f64).abs() < 1e-15, "B({k}): {sum}");
    }
    // B(6) fails: the method has order exactly 5.
    let b6: f64 = (0..3).map(|i| B[i] * C[i].powi(5)).sum();
    assert!((b6 - 1.0 / 6.0).abs() > 1e-4);
    for i in 0..3 {
        for k in 1..=3 {
            let sum: f64 = (0..3).map(|j| A[i][j] * C[j].powi(k - 1)).sum();
            assert!(
                (sum - C[i].powi(k) / k as f64).abs() < 1e-15,
                "C({k}) row {i}: {sum}"
            );
        }
    }
    assert_eq!(B, A[2]);
    assert_eq!(C[2], 1.0);
    // The nodes are the zeros of d²/dx² [x² (x − 1)³] = 20x³ − 36x² + 18x − 2 (Radau right).
    for c in C {
        assert!((20.0 * c.powi(3) - 36.0 * c * c + 18.0 * c - 2.0).abs() < 1e-14);
    }
}

/// `A⁻¹` has the eigenvalues `γ` and `α ± iβ` (closed forms by Cardano from its characteristic
/// polynomial `λ³ − 9λ² + 36λ − 60`), and `T` block-diagonalises it.
#[test]
fn transformation_block_diagonalises_the_inverse_tableau() {
    let (c3, c9) = (3f64.cbrt(), 9f64.cbrt());
    assert!((GAMMA - (3.0 + c9 - c3)).abs() < 1e-15);
    assert!((ALPHA - (3.0 - (c9 - c3) / 2.0)).abs() < 1e-15);
    assert!((BETA - 3f64.sqrt() / 2.0 * (c9 + c3)).abs() < 1e-15);
    let p = |l: f64| l.powi(3) - 9.0 * l * l + 36.0 * l - 60.0;
    assert!(p(GAMMA).abs() < 1e-13);
    // Complex root: real and imaginary parts of p(α + iβ) vanish.
    let (re, im) = (ALPHA, BETA);
    let re3 = re.powi(3) - 3.0 * re * im * im;
    let im3 = 3.0 * re * re * im - im.powi(3);
    let (re2, im2) = (re * re - im * im, 2.0 * re * im);
    assert!((re3 - 9.0 * re2 + 36.0 * re - 60.0).abs() < 1e-12);
    assert!((im3 - 9.0 * im2 + 36.0 * im).abs() < 1e-12);

    let m = |x: [[f64; 3]; 3]| Matrix3::from_fn(|i, j| x[i][j]);
    let a_inv = m(A).try_inverse().unwrap();
    let t = m(T);
    let t_inv = m(T_INV);
    assert!((t_inv * t - Matrix3::identity()).abs().max() < 1e-15);
    let lambda = Matrix3::new(GAMMA, 0.0, 0.0, 0.0, ALPHA, -BETA, 0.0, BETA, ALPHA);
    assert!((t_inv * a_inv * t - lambda).abs().max() < 1e-13);
}

/// `DENSE` inverts `V_ik = c_i^(k+1)`, and its first row carries Hairer & Wanner's error
/// constants (IV.8, eq. (8.20), written independently here): `e_i/γ0 = (−(13 + 7√6)/3,
/// (−13 + 7√6)/3, −1/3)`. The estimate `γ0 h f(y0) + Σ e_i z_i` then vanishes on cubics
/// (embedded order 3) but not on a quartic.
#[test]
fn dense_output_matrix_interpolates_and_carries_the_error_constants() {
    for i in 0..3 {
        for j in 0..3 {
            let v: f64 = (0..3).map(|k| DENSE[k][i] * C[j].powi(k as i32 + 1)).sum();
            let expected = if i == j { 1.0 } else { 0.0 };
            assert!((v - expected).abs() < 1e-13, "({i},{j}): {v}");
        }
    }
    let s6 = 6f64.sqrt();
    let e_over_gamma0 = [-(13.0 + 7.0 * s6) / 3.0, (-13.0 + 7.0 * s6) / 3.0, -1.0 / 3.0];
    for i in 0..3 {
        assert!((DENSE[0][i] + e_over_gamma0[i]).abs() < 1e-14);
    }
    // y = t^k on [0, 1]: f(y0) = y'(0), z_i = y(c_i) − y(0) = c_i^k (k ≥ 1).
    for k in 1..=4 {
        let f0 = if k == 1 { 1.0 } else { 0.0 };
        let estimate = f0 + (0..3).map(|i| e_over_gamma0[i] * C[i].powi(k)).sum::<f64>();
        if k <= 3 {
            assert!(estimate.abs() < 1e-13, "t^{k}: {estimate}");
        } else {
            assert!(estimate.abs() > 1e-2, "t^{k}: {estimate}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Van der Pol, stiff

/// Hairer's scaled Van der Pol oscillator, `y1' = y2`, `y2' = ((1 − y1²) y2 − y1)/eps`.
struct VanDerPol {
    eps: f64,
}

impl OdeSystem<2> for VanDerPol {
    fn rhs(&self, _t: f64, y: &Vector<2>) -> Result<Vector<2>> {
        Ok(Vector2::new(
            y[1],
            ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.eps,
        ))
    }
    fn jacobian(&self, _t: f64, y: &Vector<2>) -> Result<Matrix<2, 2>> {
        Ok(Matrix2::new(
            0.0,
            1.0,
            (-2.0 * y[0] * y[1] - 1.0) / self.eps,
            (1.0 - y[0] * y[0]) / self.eps,
        ))
    }
    const EXACT_JACOBIAN: bool = true;
}

fn vdp(y0: Vector<2>) -> Solution<2> {
    radau(1e-6, 1e-6)
        .solve(&VanDerPol { eps: 1e-6 }, 0.0, y0, 2.0, &[])
        .unwrap()
}

#[test]
fn van_der_pol_matches_the_ivp_test_set() {
    let sol = vdp(Vector2::new(2.0, 0.0));
    let (t, y) = sol.last();
    let reference = Vector2::new(1.706167732170483, -0.8928097010248125);
    let rel = (y - reference).component_div(&reference).abs();
    println!("vdp (2, 0): y(2) = {y:?}, rel err = {rel:?}, stats = {:?}", sol.stats);
    assert_eq!(t, 2.0);
    assert!(sol.stats.n_steps < 10_000);
}

#[test]
fn van_der_pol_matches_scipy() {
    let sol = vdp(Vector2::new(2.0, -0.66));
    let (_, y) = sol.last();
    let reference = Vector2::new(1.7061674375, -0.8928100166);
    let rel = (y - reference).component_div(&reference).abs();
    println!("vdp (2, -0.66): y(2) = {y:?}, rel err = {rel:?}, stats = {:?}", sol.stats);
    assert!(sol.stats.n_steps < 10_000);
}
