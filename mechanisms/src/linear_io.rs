//! Inputs, outputs and parameter sensitivities from the generated derivatives
//! ([`mbd::analysis::sensitivity`]), against closed forms derived beside each test and
//! against finite differences (of the right-hand side, of the outputs, of whole runs).

use mbd::prelude::*;

/// A cart (mass `m_cart`) on a horizontal rail pushed by `push` along `x`, with a bob
/// (mass `m_bob`) on a light rod `l` hinged on it, `theta` from upright, driven by the
/// hinge torque `tau`. Inputs `push` and `tau`; outputs the cart's acceleration (which
/// depends on the inputs directly: `D != 0`) and the bob's horizontal position.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(x, theta)]
#[particle(cart, mass = m_cart, at = [x, 0.0])]
#[particle(bob, mass = m_bob, at = [x + l * sin(theta), l * cos(theta)])]
#[generalized_force(pushing, along = x, value = push)]
#[generalized_force(hinge, along = theta, value = tau)]
#[input(push, tau)]
#[output(a_x = der(der(x)))]
#[output(bob_x = position(bob)[0])]
pub struct CartPole {
    pub m_cart: f64,
    pub m_bob: f64,
    pub l: f64,
    pub g: f64,
    pub push: f64,
    pub tau: f64,
}

/// `M = 2 kg`, `m = 0.5 kg`, `l = 0.8 m`, unforced.
pub const CART_POLE: CartPole = CartPole {
    m_cart: 2.0,
    m_bob: 0.5,
    l: 0.8,
    g: 9.81,
    push: 0.0,
    tau: 0.0,
};

/// A pendulum (point mass `m` on a light rod `l`, `theta` from the downward vertical) held
/// off the vertical by a constant hinge torque `tau`: the equilibrium of the sensitivity
/// test.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[particle(bob, mass = m, at = [l * sin(theta), -l * cos(theta)])]
#[generalized_force(hinge, along = theta, value = tau)]
#[input(tau)]
#[output(bob_x = position(bob)[0])]
pub struct TorquedPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub tau: f64,
}

/// A pendulum in Cartesian coordinates closed by its rod (augmented form: one constraint
/// and its multiplier), the rod's length relaxed so that `reaction(e)` is its tension; a
/// horizontal push on the bob as input. The tension depends on the multiplier: the outputs'
/// derivatives through `lambda`.
#[derive(Debug, Clone, Mechanism)]
#[mechanism(jacobian, augmented)]
#[gravity(0.0, -g)]
#[coords(x, y)]
#[relaxed(e)]
#[constraint(x * x + y * y == (l + e) * (l + e))]
#[particle(bob, mass = m, at = [x, y])]
#[generalized_force(pushing, along = x, value = push)]
#[input(push)]
#[output(tension = reaction(e))]
#[output(a_y = der(der(y)))]
pub struct RodPendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
    pub push: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case30_damped_vibration::{self as case30, DampedBlock};
    use mbd::analysis::sensitivity::{Parametric, Sensitivity, equilibrium_sensitivity};
    use mbd::analysis::{StateSpace, state_space};
    use mbd::integrate::{Dopri5, Integrator, Options, Radau5};
    use mbd::nalgebra::DMatrix;

    /// The cart-pole's `A, B, C, D` at rest upright, by hand. `T = (M + m) x'^2 / 2 +
    /// m l cos(theta) x' theta' + m l^2 theta'^2 / 2`, `V = m g l cos(theta)`; at
    /// `theta = 0` the mass matrix is `[[M + m, m l], [m l, m l^2]]`, determinant
    /// `M m l^2`, inverse `[[m l^2, -m l], [-m l, M + m]] / (M m l^2)`. The generalised
    /// forces are `(push, tau + m g l theta)` to first order, so
    /// `qdd = M^-1 (push, tau + m g l theta)`:
    /// `x'' = push / M - tau / (M l) - m g theta / M`,
    /// `theta'' = -push / (M l) + (M + m) tau / (M m l^2) + (M + m) g theta / (M l)`.
    /// Outputs: `a_x = x''` (row 3 of `A`, and `D = (1/M, -1/(M l))`), `bob_x = x + l theta`.
    fn cart_pole_by_hand() -> StateSpace {
        let CartPole {
            m_cart: mc,
            m_bob: mb,
            l,
            g,
            ..
        } = CART_POLE;
        #[rustfmt::skip]
        let a = DMatrix::from_row_slice(4, 4, &[
            0.0, 0.0, 1.0, 0.0,
            0.0, 0.0, 0.0, 1.0,
            0.0, -mb * g / mc, 0.0, 0.0,
            0.0, (mc + mb) * g / (mc * l), 0.0, 0.0,
        ]);
        #[rustfmt::skip]
        let b = DMatrix::from_row_slice(4, 2, &[
            0.0, 0.0,
            0.0, 0.0,
            1.0 / mc, -1.0 / (mc * l),
            -1.0 / (mc * l), (mc + mb) / (mc * mb * l * l),
        ]);
        #[rustfmt::skip]
        let c = DMatrix::from_row_slice(2, 4, &[
            0.0, -mb * g / mc, 0.0, 0.0,
            1.0, l, 0.0, 0.0,
        ]);
        let d = DMatrix::from_row_slice(2, 2, &[1.0 / mc, -1.0 / (mc * l), 0.0, 0.0]);
        StateSpace {
            a,
            b,
            c,
            d,
            inputs: vec!["push", "tau"],
            outputs: vec!["a_x", "bob_x"],
        }
    }

    #[test]
    fn cart_pole_state_space_is_the_closed_form() {
        let ss = state_space(&CART_POLE, 0.0, &Vector::<4>::zeros()).unwrap();
        let exact = cart_pole_by_hand();
        assert_eq!(
            (ss.inputs.clone(), ss.outputs.clone()),
            (exact.inputs, exact.outputs)
        );
        for (got, want) in [
            (&ss.a, &exact.a),
            (&ss.b, &exact.b),
            (&ss.c, &exact.c),
            (&ss.d, &exact.d),
        ] {
            assert!((got - want).amax() <= 1e-14 * want.amax(), "{got} {want}");
        }
    }

    /// A model with the inputs set, at a moving state: `B`, `C`, `D` against central
    /// differences (of `rhs` by the input fields, of the outputs by the state and the
    /// inputs). The difference falls as `h^2` (by 4 when `h` halves, to 10%): it is the
    /// differences' truncation error, and the generated matrices are their limit.
    #[test]
    fn cart_pole_state_space_is_the_limit_of_central_differences() {
        let model = CartPole {
            push: 0.7,
            tau: -0.3,
            ..CART_POLE
        };
        let y = Vector::<4>::new(0.2, 0.9, -0.4, 1.7);
        let ss = state_space(&model, 0.0, &y).unwrap();
        let with = |push: f64, tau: f64| CartPole {
            push,
            tau,
            ..model.clone()
        };
        let fd = |h: f64| {
            let mut b = DMatrix::zeros(4, 2);
            let mut d = DMatrix::zeros(2, 2);
            for j in 0..2 {
                let (dp, dt) = if j == 0 { (h, 0.0) } else { (0.0, h) };
                let (p, m) = (with(0.7 + dp, -0.3 + dt), with(0.7 - dp, -0.3 - dt));
                let fb = (p.rhs(0.0, &y).unwrap() - m.rhs(0.0, &y).unwrap()) / (2.0 * h);
                b.column_mut(j).copy_from_slice(fb.as_slice());
                let (op, om) = (
                    p.output_values(0.0, &y).unwrap(),
                    m.output_values(0.0, &y).unwrap(),
                );
                for k in 0..2 {
                    d[(k, j)] = (op[k] - om[k]) / (2.0 * h);
                }
            }
            let mut c = DMatrix::zeros(2, 4);
            for j in 0..4 {
                let mut e = Vector::<4>::zeros();
                e[j] = h;
                let (op, om) = (
                    model.output_values(0.0, &(y + e)).unwrap(),
                    model.output_values(0.0, &(y - e)).unwrap(),
                );
                for k in 0..2 {
                    c[(k, j)] = (op[k] - om[k]) / (2.0 * h);
                }
            }
            [(b - &ss.b).amax(), (c - &ss.c).amax(), (d - &ss.d).amax()]
        };
        let (e1, e2) = (fd(2e-3), fd(1e-3));
        for i in 0..3 {
            assert!(e1[i] < 1e-4, "{e1:?}");
            // D is affine in the inputs here: its differences are exact to rounding.
            if e1[i] > 1e-10 {
                let ratio = e1[i] / e2[i];
                assert!(
                    (3.6..=4.4).contains(&ratio),
                    "{i}: ratio {ratio}, {e1:?} {e2:?}"
                );
            }
        }
        // A from the same evaluation is the model's exact Jacobian.
        let a = mbd::analysis::linearize(&model, 0.0, &y).unwrap();
        let a = DMatrix::from_column_slice(4, 4, a.as_slice());
        assert!((a - &ss.a).amax() <= 1e-13 * ss.a.amax());
    }

    /// The torqued pendulum's equilibrium `m g l sin(theta) = tau` and its sensitivities,
    /// by hand: `dtheta/dtau = 1 / (m g l cos)`, `dtheta/dl = -tau / (m g l^2 cos)`,
    /// `dtheta/dm = -tau / (m^2 g l cos)`; the bob's `x = l sin(theta) = tau / (m g)`, so
    /// `dx/dtau = 1 / (m g)`, `dx/dl = 0`, `dx/dm = -tau / (m^2 g)`, `dx/dg = -tau / (m g^2)`.
    #[test]
    fn equilibrium_sensitivities_are_the_closed_form() {
        let model = TorquedPendulum {
            m: 1.5,
            l: 0.7,
            g: 9.81,
            tau: 4.0,
        };
        let TorquedPendulum { m, l, g, tau } = model;
        let theta = (tau / (m * g * l)).asin();
        let c = theta.cos();
        let (dq, dout) = equilibrium_sensitivity(&model, 0.0, &[theta]).unwrap();
        assert_eq!(TorquedPendulum::PARAMETERS, ["m", "l", "g", "tau"]);
        let want_q = [
            -tau / (m * m * g * l * c),
            -tau / (m * g * l * l * c),
            -tau / (m * g * g * l * c),
            1.0 / (m * g * l * c),
        ];
        let want_x = [-tau / (m * m * g), 0.0, -tau / (m * g * g), 1.0 / (m * g)];
        for j in 0..4 {
            assert!(
                (dq[(0, j)] - want_q[j]).abs() <= 1e-14 * want_q[j].abs(),
                "{j}: {dq}"
            );
            assert!((dout[(0, j)] - want_x[j]).abs() <= 1e-15, "{j}: {dout}");
        }
        // Off the equilibrium: refused.
        assert!(equilibrium_sensitivity(&model, 0.0, &[theta + 0.1]).is_err());
    }

    /// Case 30, `m x'' + c x' + k x = 0`, `x(0) = x0`, `x'(0) = 0`:
    /// `x = x0 e^{-a t} (cos(w t) + (a / w) sin(w t))`, `a = c / (2 m)`,
    /// `w = sqrt(k / m - a^2)`. Its derivatives: `dw/dk = 1 / (2 m w)`, `da/dk = 0`;
    /// `da/dc = 1 / (2 m)`, `dw/dc = -a / (2 m w)`;
    /// `dx/dw = x0 e^{-a t} (-t sin + (a t / w) cos - (a / w^2) sin)`,
    /// `dx/da = x0 e^{-a t} (-t (cos + (a / w) sin) + sin / w)`. Returns `[dx/dk, dx/dc]`.
    fn block_sensitivity(t: f64) -> [f64; 2] {
        let DampedBlock { m, k, c, x_0, .. } = case30::MODEL;
        let a = c / (2.0 * m);
        let w = (k / m - a * a).sqrt();
        let (s, co, e) = ((w * t).sin(), (w * t).cos(), (-a * t).exp());
        let dx_dw = x_0 * e * (-t * s + a * t / w * co - a / (w * w) * s);
        let dx_da = x_0 * e * (-t * (co + a / w * s) + s / w);
        [
            dx_dw / (2.0 * m * w),
            dx_da / (2.0 * m) - dx_dw * a / (2.0 * m * w),
        ]
    }

    /// The forward sensitivity equations of case 30 by `k` and `c`, integrated with the
    /// state by DOPRI5 (rtol = atol = 1e-12), against the closed form above at five times
    /// and against central differences of whole runs (`h = 1e-4` relative: truncation
    /// `O(h^2)` about 1e-9 relative, the runs' own error over `2h` about 1e-8): agreement
    /// to 1e-9 of the sensitivity's scale with the closed form, 1e-6 with the differences;
    /// and through Radau IIA 5 at 1e-10, to 1e-7.
    #[test]
    fn trajectory_sensitivities_are_the_closed_form() {
        let model = case30::MODEL;
        let (ik, ic) = (2, 3);
        assert_eq!(DampedBlock::PARAMETERS[ik], "k");
        assert_eq!(DampedBlock::PARAMETERS[ic], "c");
        let sens = Sensitivity::new(&model, [ik, ic]).unwrap();
        let opts = Options {
            rtol: 1e-12,
            atol: 1e-12,
            ..Options::default()
        };
        let y0 = model.initial_state();
        let ya0: Vector<6> = sens.initial(&y0);
        let run = |sys: &DampedBlock, t1: f64| -> f64 {
            Dopri5::new(opts.clone())
                .solve(sys, 0.0, sys.initial_state(), t1, &[])
                .unwrap()
                .last()
                .1[0]
        };
        let scale = block_sensitivity(0.3)
            .iter()
            .fold(0.0f64, |s, v| s.max(v.abs()));
        for t1 in [0.1, 0.3, 0.6, 1.0, 1.5] {
            let ya = *Dopri5::new(opts.clone())
                .solve(&sens, 0.0, ya0, t1, &[])
                .unwrap()
                .last()
                .1;
            let s = sens.sensitivities(&ya);
            let exact = block_sensitivity(t1);
            for (j, (p, h)) in [(ik, 1e-4 * model.k), (ic, 1e-4 * model.c)]
                .into_iter()
                .enumerate()
            {
                let got = s[(0, j)];
                assert!(
                    (got - exact[j]).abs() <= 1e-9 * scale,
                    "t {t1} p {p}: {got} vs {}",
                    exact[j]
                );
                let shifted = |dv: f64| {
                    let mut m = model.clone();
                    if j == 0 {
                        m.k += dv
                    } else {
                        m.c += dv
                    }
                    run(&m, t1)
                };
                let fd = (shifted(h) - shifted(-h)) / (2.0 * h);
                assert!(
                    (got - fd).abs() <= 1e-6 * scale,
                    "t {t1} p {p}: {got} vs fd {fd}"
                );
            }
        }
        // The same augmented system through an implicit method (Radau IIA 5, Jacobian of
        // the augmented right-hand side by differences), rtol = atol = 1e-10.
        let loose = Options {
            rtol: 1e-10,
            atol: 1e-10,
            ..Options::default()
        };
        let ya = *Radau5::new(loose)
            .solve(&sens, 0.0, ya0, 1.0, &[])
            .unwrap()
            .last()
            .1;
        let s = sens.sensitivities(&ya);
        let exact = block_sensitivity(1.0);
        for j in 0..2 {
            assert!(
                (s[(0, j)] - exact[j]).abs() <= 1e-7 * scale,
                "{} vs {}",
                s[(0, j)],
                exact[j]
            );
        }
    }

    /// The sprung four-bar (a closed loop, augmented form) in independent coordinates,
    /// with the crank torque `tau` as input and pin A's `x = r sin(phi)` as output `xa`.
    /// On the loop `phi = psi`: `T = m r^2 phi'^2 / 2`, stiffness `m g r + k r^2` (see
    /// `modes::four_bar_reference`), generalised force `tau`. So `phi'' = tau / (m r^2)`
    /// (both cranks: `T B_r = (0, 0, 1, 1) / (m r^2)`), and the static gain from `tau` to
    /// `xa`, `D - C_r A_r^-1 B_r`, is `r / (m g r + k r^2) = 1 / (m g + k r)`.
    #[test]
    fn four_bar_state_space_in_independent_coordinates() {
        use crate::modes::{FOUR_BAR, SprungFourBar};
        use mbd::analysis::constrained_state_space;
        let SprungFourBar { m, r, k, g, .. } = FOUR_BAR;
        let (ss, tm) = constrained_state_space(&FOUR_BAR, 0.0, &Vector::<2>::zeros()).unwrap();
        assert_eq!(
            (ss.a.nrows(), ss.b.ncols(), ss.inputs.clone()),
            (2, 1, vec!["tau"])
        );
        let b_full = &tm * &ss.b;
        let phi_dd = 1.0 / (m * r * r);
        for (i, want) in [0.0, 0.0, phi_dd, phi_dd].into_iter().enumerate() {
            assert!((b_full[(i, 0)] - want).abs() <= 1e-14 * phi_dd, "{b_full}");
        }
        let xa = ss.outputs.iter().position(|o| *o == "xa").unwrap();
        let gain =
            ss.d[(xa, 0)] - (ss.c.row(xa) * ss.a.clone().try_inverse().unwrap() * &ss.b)[(0, 0)];
        let want = 1.0 / (m * g + k * r);
        assert!((gain - want).abs() <= 1e-13 * want, "{gain} vs {want}");
    }

    /// The rod pendulum at a moving state on its constraint, pushed: `B`, `C`, `D` against
    /// central differences (their error falls as `h^2`), the tension's through the
    /// multiplier. By hand, hanging at rest at `(0, -l)`: the tension is `m g`; a push `u`
    /// gives `x'' = u / m`, `y'' = 0` and leaves the tension (`m g + m l theta'^2`) alone,
    /// so `B = (0, 0, 1/m, 0)` and `D = 0`.
    #[test]
    fn outputs_through_the_multiplier() {
        let model = RodPendulum {
            m: 1.3,
            l: 0.9,
            g: 9.81,
            push: 0.4,
        };
        let (c, s) = (0.6f64, -0.8f64);
        let (w, l) = (1.7, model.l);
        // On the constraint and tangent to it: (x, y) = l (c, s), v = w l (-s, c).
        let y = Vector::<4>::new(l * c, l * s, -w * l * s, w * l * c);
        let ss = state_space(&model, 0.0, &y).unwrap();
        let with = |push: f64| RodPendulum {
            push,
            ..model.clone()
        };
        let fd = |h: f64| {
            let (p, m) = (with(0.4 + h), with(0.4 - h));
            let fb = (p.rhs(0.0, &y).unwrap() - m.rhs(0.0, &y).unwrap()) / (2.0 * h);
            let (op, om) = (
                p.output_values(0.0, &y).unwrap(),
                m.output_values(0.0, &y).unwrap(),
            );
            let mut err_c = 0.0f64;
            for j in 0..4 {
                let mut e = Vector::<4>::zeros();
                e[j] = h;
                let (cp, cm) = (
                    model.output_values(0.0, &(y + e)).unwrap(),
                    model.output_values(0.0, &(y - e)).unwrap(),
                );
                for k in 0..2 {
                    err_c = err_c.max(((cp[k] - cm[k]) / (2.0 * h) - ss.c[(k, j)]).abs());
                }
            }
            let err_b = (0..4)
                .map(|i| (fb[i] - ss.b[(i, 0)]).abs())
                .fold(0.0, f64::max);
            let err_d = (0..2)
                .map(|k| ((op[k] - om[k]) / (2.0 * h) - ss.d[(k, 0)]).abs())
                .fold(0.0, f64::max);
            [err_b, err_c, err_d]
        };
        let (e1, e2) = (fd(2e-3), fd(1e-3));
        for i in 0..3 {
            assert!(e1[i] < 1e-4, "{e1:?}");
            if e1[i] > 1e-10 {
                let ratio = e1[i] / e2[i];
                assert!(
                    (3.6..=4.4).contains(&ratio),
                    "{i}: ratio {ratio}, {e1:?} {e2:?}"
                );
            }
        }
        // Hanging at rest: tension m g, no dependence on the push.
        let hanging = Vector::<4>::new(0.0, -l, 0.0, 0.0);
        let ss = state_space(&model, 0.0, &hanging).unwrap();
        let out = model.output_values(0.0, &hanging).unwrap();
        assert!((out[0].abs() - model.m * model.g).abs() <= 1e-12 * model.m * model.g);
        assert!(ss.d.amax() <= 1e-14, "{}", ss.d);
        assert!((ss.b[(2, 0)] - 1.0 / model.m).abs() <= 1e-14 && ss.b[(3, 0)].abs() <= 1e-14);
    }
}
