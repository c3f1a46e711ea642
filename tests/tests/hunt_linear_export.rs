//! Hunting linear analysis as a controls engineer: the cart-pole linearised upright
//! (`A`, `B` against the textbook, controllability, the unstable eigenvalue) and the
//! export of `A, B, C, D` to a control design tool. The references are derived beside
//! the tests.

use mbd::analysis::linear::{ModeKind, StateSpace, linearize, modes, state_space};
use mbd::prelude::*;
use nalgebra::DMatrix;

/// A cart (mass `mc`) on a rail pushed by `force`, a bob (mass `mb`) on a massless rod
/// `l` hinged on it, `theta` from upright; outputs the cart's position and the angle.
#[derive(Debug, Mechanism)]
#[mechanism(jacobian)]
#[gravity(0.0, -g)]
#[coords(x, theta)]
#[particle(cart, mass = mc, at = [x, 0.0])]
#[particle(bob, mass = mb, at = [x + l * sin(theta), l * cos(theta)])]
#[generalized_force(push, along = x, value = force)]
#[input(force)]
#[output(cart_x = x)]
#[output(angle = theta)]
pub struct CartPole {
    pub mc: f64,
    pub mb: f64,
    pub l: f64,
    pub g: f64,
    pub force: f64,
}

const CP: CartPole = CartPole {
    mc: 1.2,
    mb: 0.3,
    l: 0.6,
    g: 9.81,
    force: 0.0,
};

/// Lagrange's equations linearised upright: `(M + m) x'' + m l theta'' = F`,
/// `x'' + l theta'' - g theta = 0`; eliminating, `x'' = -(m g / M) theta + F / M`,
/// `theta'' = g (M + m) / (M l) theta - F / (M l)`. So with the state
/// `(x, theta, x', theta')`: `A = [[0, 0, 1, 0], [0, 0, 0, 1], [0, -m g / M, 0, 0],
/// [0, g (M + m) / (M l), 0, 0]]`, `B = (0, 0, 1 / M, -1 / (M l))`, `C = [I 0]`, `D = 0`;
/// eigenvalues `0, 0, +-s`, `s = sqrt(g (M + m) / (M l))`. The controllability matrix
/// `[B, A B, A^2 B, A^3 B]` has columns `B = (0, 0, b3, b4)`, `A B = (b3, b4, 0, 0)`,
/// `A^2 B = (0, 0, c3, c4)`, `A^3 B = (c3, c4, 0, 0)` with `c3 = a32 b4`, `c4 = a42 b4`.
/// Swapping its middle columns gives `[[0, X], [X, 0]]`, `X = [[b3, c3], [b4, c4]]`, whose
/// determinant is `det(X)^2`: so `det = -det(X)^2 = -b4^2 (b3 a42 - a32 b4)^2`, and
/// `b3 a42 - a32 b4 = g (M + m) / (M^2 l) - m g / (M^2 l) = g / (M l)`:
/// `det = -g^2 / (M^4 l^4)`, nonzero: controllable from the cart's force alone.
fn textbook() -> StateSpace {
    let CartPole { mc, mb, l, g, .. } = CP;
    let a32 = -mb * g / mc;
    let a42 = g * (mc + mb) / (mc * l);
    StateSpace {
        a: DMatrix::from_row_slice(
            4,
            4,
            &[
                0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, a32, 0.0, 0.0, 0.0, a42, 0.0, 0.0,
            ],
        ),
        b: DMatrix::from_row_slice(4, 1, &[0.0, 0.0, 1.0 / mc, -1.0 / (mc * l)]),
        c: DMatrix::from_row_slice(2, 4, &[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0]),
        d: DMatrix::zeros(2, 1),
        inputs: vec!["force"],
        outputs: vec!["cart_x", "angle"],
    }
}

#[test]
fn cart_pole_upright_is_the_textbook_model_controllable_and_unstable() {
    let ss = state_space(&CP, 0.0, &Vector::<4>::zeros()).unwrap();
    let want = textbook();
    assert_eq!(ss.inputs, want.inputs);
    assert_eq!(ss.outputs, want.outputs);
    for (got, w, name) in [
        (&ss.a, &want.a, "A"),
        (&ss.b, &want.b, "B"),
        (&ss.c, &want.c, "C"),
        (&ss.d, &want.d, "D"),
    ] {
        assert!(
            (got - w).amax() < 1e-14 * (1.0 + w.amax()),
            "{name}: {got} vs {w}"
        );
    }
    let ctrb = DMatrix::from_columns(&[
        ss.b.column(0).into_owned(),
        (&ss.a * &ss.b).column(0).into_owned(),
        (&ss.a * &ss.a * &ss.b).column(0).into_owned(),
        (&ss.a * &ss.a * &ss.a * &ss.b).column(0).into_owned(),
    ]);
    let CartPole { mc, l, g, mb, .. } = CP;
    let b4 = -1.0 / (mc * l);
    let det = -(b4 * g / (mc * l)).powi(2);
    assert!(
        (ctrb.determinant() - det).abs() < 1e-12 * det.abs(),
        "{} vs {det}",
        ctrb.determinant()
    );

    let s = (g * (mc + mb) / (mc * l)).sqrt();
    let found = modes(&linearize(&CP, 0.0, &Vector::<4>::zeros()).unwrap()).unwrap();
    let unstable: Vec<_> = found.iter().filter(|m| m.unstable).collect();
    assert_eq!(unstable.len(), 1, "{found:?}");
    assert_eq!(unstable[0].kind, ModeKind::Real);
    assert!((unstable[0].eigenvalue.re - s).abs() < 1e-12 * s);
    let neutral = found.iter().filter(|m| m.kind == ModeKind::Neutral).count();
    assert_eq!(neutral, 2, "the cart's free drift: {found:?}");
}

/// The numbers of a JSON array of arrays, row by row (enough of a reader for the export:
/// brackets and commas only).
fn numbers(field: &str, json: &str) -> Vec<Vec<f64>> {
    let start = json.find(&format!("\"{field}\": [")).unwrap() + field.len() + 4;
    let mut depth = 0;
    let mut end = start;
    for (i, ch) in json[start..].char_indices() {
        match ch {
            '[' => depth += 1,
            ']' => {
                depth -= 1;
                if depth == 0 {
                    end = start + i + 1;
                    break;
                }
            }
            _ => {}
        }
    }
    let inner = &json[start + 1..end - 1];
    inner
        .split(']')
        .map(|r| r.trim_start_matches([',', ' ', '[']).trim())
        .filter(|r| !r.is_empty())
        .map(|r| {
            r.split(',')
                .map(|v| v.trim().parse::<f64>().unwrap())
                .collect()
        })
        .collect()
}

/// `to_json` writes `A, B, C, D` with the names, and every number reads back as the
/// same `f64` (bit for bit); a non-finite entry is refused (JSON has no NaN).
#[test]
fn state_space_exports_to_json_that_reads_back_exactly() {
    let ss = state_space(&CP, 0.0, &Vector::<4>::new(0.1, 0.2, -0.3, 0.4)).unwrap();
    let json = ss.to_json().unwrap();
    assert!(json.contains("\"inputs\": [\"force\"]"), "{json}");
    assert!(
        json.contains("\"outputs\": [\"cart_x\", \"angle\"]"),
        "{json}"
    );
    for (name, m) in [("a", &ss.a), ("b", &ss.b), ("c", &ss.c), ("d", &ss.d)] {
        let rows = numbers(name, &json);
        assert_eq!(rows.len(), m.nrows(), "{name}: {json}");
        for (i, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), m.ncols(), "{name}: {json}");
            for (j, v) in row.iter().enumerate() {
                assert_eq!(v.to_bits(), m[(i, j)].to_bits(), "{name}[{i}, {j}]");
            }
        }
    }
    let mut broken = ss.clone();
    broken.c[(0, 0)] = f64::NAN;
    match broken.to_json() {
        Err(Error::InvalidInput { what, detail }) => {
            assert_eq!(what, "to_json");
            assert!(detail.contains("non-finite"), "{detail}");
        }
        other => panic!("{other:?}"),
    }
}
