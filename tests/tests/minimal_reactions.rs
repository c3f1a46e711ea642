//! Reactions on the minimal form: a free slider-crank whose wrist pin is relaxed
//! (`reaction(ux)`, `reaction(uy)`) is generated in minimal coordinates (`theta` alone), and its
//! pin force equals Newton–Euler by hand on each link and the augmented form of the same
//! attributes.
//!
//! **Why no multipliers are needed.** With the closure solved, `z = phi(theta, u)` (the
//! relaxed `u` kept as coordinates until the end), every constraint force is workless along
//! `T = dphi/d(theta, u)`: `T^T Phi_z^T = 0`. Projecting the augmented equations
//! `M z'' - f + Phi_z^T lambda = (0, .., r_u)` on `T` leaves `(T^T (M z'' - f))_u = r_u`, and
//! `T^T (M z'' - f)` is what Kane's projection of the closed-form kinematics is. So the rows
//! of the relaxed coordinates in minimal coordinates are the reactions themselves, and they
//! are unique wherever the closed form is regular (`Phi` solved for the dependent
//! coordinates: the constraint rows and the rows `u = 0` are independent).

use mbd::prelude::*;
use mbd::{Matrix, Vector};

macro_rules! slider_crank {
    ($name:ident $(, $form:ident)?) => {
        /// A free slider-crank: crank `theta` (pivot at the origin), rod angle `-beta`,
        /// piston at `(x, 0)`; the rod's end is the piston's position plus the relaxed
        /// `(ux, uy)`, so `reaction(ux)`, `reaction(uy)` are the piston's force on the rod.
        #[derive(Debug, Clone, Mechanism)]
        $(#[mechanism($form)])?
        #[gravity(0.0, -g)]
        #[coords(theta, beta, x)]
        #[relaxed(ux, uy)]
        #[constraint(r * cos(theta) + l * cos(beta) == x + ux)]
        #[constraint(r * sin(theta) - l * sin(beta) == uy)]
        #[rigid(crank, mass = m_c, inertia = m_c * r * r / 12.0,
                at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
        #[rigid(rod, mass = m_r, inertia = i_r,
                at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
                angle = -beta)]
        #[particle(piston, mass = m_p, at = [x, 0.0])]
        #[init(theta = 0.6)]
        #[output(pin_x = reaction(ux))]
        #[output(pin_y = reaction(uy))]
        pub struct $name {
            #[default(0.3)]
            pub r: f64,
            #[default(1.0)]
            pub l: f64,
            #[default(2.0)]
            pub m_c: f64,
            #[default(3.0)]
            pub m_r: f64,
            #[default(0.4)]
            pub i_r: f64,
            #[default(1.5)]
            pub m_p: f64,
            #[default(9.81)]
            pub g: f64,
        }
    };
}
slider_crank!(Pinned);
slider_crank!(PinnedAugmented, augmented);

const P: Pinned = Pinned {
    r: 0.3,
    l: 1.0,
    m_c: 2.0,
    m_r: 3.0,
    i_r: 0.4,
    m_p: 1.5,
    g: 9.81,
};
const PA: PinnedAugmented = PinnedAugmented {
    r: 0.3,
    l: 1.0,
    m_c: 2.0,
    m_r: 3.0,
    i_r: 0.4,
    m_p: 1.5,
    g: 9.81,
};

/// Newton–Euler on each link at `(theta, theta')`: `[theta'', F_x, F_y]` with `F` the piston's
/// force on the rod at the pin A.
///
/// Closure: `u = r sin(theta) / l = sin(beta)`, `k = cos(beta)`; `beta' = b1 theta'` with
/// `b1 = r cos(theta) / (l k)`, `beta'' = b1 theta'' + b2 theta'^2`, `b2 = u (b1^2 - 1) / k`.
/// Positions: `B = r (cos, sin)(theta)`, `A = (x, 0)` with `x = r cos(theta) + l k`, rod centre
/// `G = (r cos(theta) + l k / 2, r sin(theta) / 2)`, rod angle `-beta`. Every acceleration is
/// `p_1 theta'' + p_2 theta'^2` with `p_1 = dp/dtheta`, `p_2 = d^2p/dtheta^2`:
/// `x_1 = -r sin - l u b1`, `x_2 = -r cos - l (k b1^2 + u b2)`, `Gx` the same with `l / 2`,
/// `Gy_1 = r cos / 2`, `Gy_2 = -r sin / 2`.
///
/// Unknowns `theta''`, `F_B` (the crank's force on the rod at B), `F = F_A`, `N` (the ground's
/// on the piston), six equations:
/// - crank, moments about O: `(m_c r^2 / 3) theta'' = B x (-F_B) - (r cos / 2) m_c g`;
/// - rod: `m_r a_G = F_B + F + (0, -m_r g)`, `I_r (-beta'') = (B - G) x F_B + (A - G) x F`;
/// - piston: `m_p x'' = -F_x`, `0 = -F_y + N - m_p g`.
fn newton_euler(th: f64, thd: f64) -> [f64; 3] {
    let Pinned {
        r,
        l,
        m_c,
        m_r,
        i_r,
        m_p,
        g,
    } = P;
    let (s, c) = th.sin_cos();
    let u = r * s / l;
    let k = (1.0 - u * u).sqrt();
    let b1 = r * c / (l * k);
    let b2 = u * (b1 * b1 - 1.0) / k;
    let w2 = thd * thd;
    let b = [r * c, r * s];
    let a = [r * c + l * k, 0.0];
    let gr = [r * c + l * k / 2.0, r * s / 2.0];
    let (x1, x2) = (-r * s - l * u * b1, -r * c - l * (k * b1 * b1 + u * b2));
    let (gx1, gx2) = (
        -r * s - l / 2.0 * u * b1,
        -r * c - l / 2.0 * (k * b1 * b1 + u * b2),
    );
    let (gy1, gy2) = (r * c / 2.0, -r * s / 2.0);
    let (bg, ag) = ([b[0] - gr[0], b[1] - gr[1]], [a[0] - gr[0], a[1] - gr[1]]);
    // Unknowns [theta'', F_Bx, F_By, F_x, F_y, N]; cross(p, f) = p_x f_y - p_y f_x.
    #[rustfmt::skip]
    let m = Matrix::<6, 6>::from_row_slice(&[
        m_c * r * r / 3.0, -b[1], b[0], 0.0, 0.0, 0.0,
        m_r * gx1, -1.0, 0.0, -1.0, 0.0, 0.0,
        m_r * gy1, 0.0, -1.0, 0.0, -1.0, 0.0,
        -i_r * b1, bg[1], -bg[0], ag[1], -ag[0], 0.0,
        m_p * x1, 0.0, 0.0, 1.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 0.0, -1.0, 1.0,
    ]);
    let rhs = Vector::<6>::from_row_slice(&[
        -(r * c / 2.0) * m_c * g,
        -m_r * gx2 * w2,
        -m_r * gy2 * w2 - m_r * g,
        i_r * b2 * w2,
        -m_p * x2 * w2,
        m_p * g,
    ]);
    let x = m.lu().solve(&rhs).expect("regular");
    [x[0], x[3], x[4]]
}

const STATES: [(f64, f64); 6] = [
    (0.6, 0.0),
    (0.0, 2.0),
    (1.2, -3.0),
    (2.8, 1.0),
    (-1.9, 4.0),
    (4.4, -0.5),
];

#[test]
fn the_model_with_reactions_is_generated_in_minimal_coordinates() {
    assert!(Pinned::GENERATED.parts.contains(&"minimal_closed_form"));
    assert_eq!(Pinned::GENERATED.constraints, 0);
    assert!(PinnedAugmented::GENERATED.parts.contains(&"augmented"));
}

#[test]
fn pin_reaction_equals_newton_euler_in_both_forms() {
    for (th, thd) in STATES {
        let [th_dd, fx, fy] = newton_euler(th, thd);
        // Minimal form: the state is theta alone.
        let out = P.outputs(0.0, &Vector::<2>::from([th, thd])).unwrap();
        let qdd = P
            .acceleration(0.0, &Vector::from([th]), &Vector::from([thd]))
            .unwrap()[0];
        // Augmented form: (theta, beta, x) assembled by the closed form.
        let (s, c) = th.sin_cos();
        let u = P.r * s / P.l;
        let k = (1.0 - u * u).sqrt();
        let b1 = P.r * c / (P.l * k);
        let beta = u.asin();
        let y = Vector::<6>::from([
            th,
            beta,
            P.r * c + P.l * k,
            thd,
            b1 * thd,
            (-P.r * s - P.l * u * b1) * thd,
        ]);
        let out_a = PA.outputs(0.0, &y).unwrap();
        let scale = fx.abs().max(fy.abs());
        eprintln!(
            "theta = {th}: F = ({fx}, {fy}); minimal - hand ({:e}, {:e}), augmented - hand ({:e}, {:e}), minimal - augmented ({:e}, {:e}); theta'' {:e}",
            out.pin_x - fx,
            out.pin_y - fy,
            out_a.pin_x - fx,
            out_a.pin_y - fy,
            out.pin_x - out_a.pin_x,
            out.pin_y - out_a.pin_y,
            qdd - th_dd,
        );
        assert!((qdd - th_dd).abs() < 1e-12 * th_dd.abs().max(1.0));
        for (got, want) in [
            (out.pin_x, fx),
            (out.pin_y, fy),
            (out_a.pin_x, fx),
            (out_a.pin_y, fy),
        ] {
            assert!((got - want).abs() < 1e-10 * scale, "{got} vs {want}");
        }
        assert!((out.pin_x - out_a.pin_x).abs() < 1e-10 * scale);
        assert!((out.pin_y - out_a.pin_y).abs() < 1e-10 * scale);
    }
}

/// Along a motion: both forms integrated 2 s from rest at `theta = 0.6` (DOPRI5, 1e-12): the
/// pin force at the end agrees with Newton–Euler at the state reached, and the two forms agree.
#[test]
fn pin_reaction_along_a_motion() {
    use mbd::integrate::{Dopri5, Integrator};
    let o = Options {
        rtol: 1e-12,
        atol: 1e-12,
        ..Options::default()
    };
    let y = Dopri5::new(o.clone())
        .solve(&P, 0.0, P.initial_state(), 2.0, &[])
        .unwrap()
        .y_end;
    let [_, fx, fy] = newton_euler(y[0], y[1]);
    let out = P.outputs(2.0, &y).unwrap();
    // The augmented form's state assembled by the closure (its `init` names theta only).
    let beta0 = (P.r * 0.6f64.sin() / P.l).asin();
    let x0 = P.r * 0.6f64.cos() + P.l * beta0.cos();
    let ya0 = Vector::<6>::from([0.6, beta0, x0, 0.0, 0.0, 0.0]);
    let ya = Dopri5::new(o.clone())
        .solve(&PA, 0.0, ya0, 2.0, &[])
        .unwrap()
        .y_end;
    let out_a = PA.outputs(2.0, &ya).unwrap();
    eprintln!(
        "t = 2: theta {} (augmented {}), F = ({fx}, {fy}); minimal - hand ({:e}, {:e}), augmented - minimal ({:e}, {:e})",
        y[0],
        ya[0],
        out.pin_x - fx,
        out.pin_y - fy,
        out_a.pin_x - out.pin_x,
        out_a.pin_y - out.pin_y
    );
    assert!((out.pin_x - fx).abs() < 1e-10 * fy.abs() && (out.pin_y - fy).abs() < 1e-10 * fy.abs());
    assert!((ya[0] - y[0]).abs() < 1e-10, "{} vs {}", ya[0], y[0]);
    assert!((out_a.pin_x - out.pin_x).abs() < 1e-8 && (out_a.pin_y - out.pin_y).abs() < 1e-8);
}
