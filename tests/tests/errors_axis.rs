//! A prismatic joint's axis given by parameters that evaluate to zero length: the joint
//! moves its body by `s axis` (the language's `prismatic(s, axis)`), so the coordinate has
//! no inertia. The recursive form ended in `NonFinite` ("a state became NaN") though the
//! state was finite; every form now names the joint's axis (`InvalidParameter`). A non-zero
//! axis need not be a unit one: `s` is measured in units of `|axis|`, and a block sliding
//! under gravity has `m |a|^2 s'' = m g . a`, i.e. `s'' = g . a / |a|^2`, and its
//! displacement along the unit axis `d = |a| s` has `d'' = g . a_hat` (the closed form the
//! tests compare with).

use mbd::integrate::{Dopri5, Integrator};
use mbd::prelude::*;

macro_rules! sled {
    ($name:ident, $form:ident, spatial) => {
        /// A block on a prismatic joint of axis `(ax, ay, az)`, with a pendulum on it (a
        /// tree), under gravity `(gx, gy, gz)`; the pendulum hangs at rest along `-z`.
        #[derive(Debug, Mechanism)]
        #[mechanism(spatial, $form)]
        #[gravity(gx, gy, gz)]
        #[body(block, joint = prismatic(s, [ax, ay, az]), mass = m)]
        #[body(bob, parent = block, joint = revolute(q, y), com = [0.0, 0.0, -l], mass = mb)]
        pub struct $name {
            pub m: f64,
            pub mb: f64,
            pub l: f64,
            pub ax: f64,
            pub ay: f64,
            pub az: f64,
            pub gx: f64,
            pub gy: f64,
            pub gz: f64,
        }
    };
    ($name:ident, $form:ident, planar) => {
        /// The planar block: axis `(ax, ay)`, gravity `(gx, gy)`, a pendulum on a revolute.
        #[derive(Debug, Mechanism)]
        #[mechanism(planar, $form)]
        #[gravity(gx, gy)]
        #[body(block, joint = prismatic(s, [ax, ay]), mass = m)]
        #[body(bob, parent = block, joint = revolute(q), com = [0.0, -l], mass = mb)]
        pub struct $name {
            pub m: f64,
            pub mb: f64,
            pub l: f64,
            pub ax: f64,
            pub ay: f64,
            pub gx: f64,
            pub gy: f64,
        }
    };
}

sled!(SpatialAba, recursive, spatial);
sled!(SpatialMass, mass_matrix, spatial);
sled!(PlanarAba, recursive, planar);
sled!(PlanarMass, mass_matrix, planar);

/// The named error every evaluation must give.
fn names_the_axis(err: Error) {
    match err {
        Error::InvalidParameter {
            what,
            value,
            requirement,
        } => {
            assert!(what.contains("prismatic joint axis of `block`"), "{what}");
            assert_eq!(value, 0.0);
            assert_eq!(requirement, "positive");
        }
        other => panic!("expected the zero axis to be named, got {other:?}"),
    }
}

/// The rhs and a DOPRI5 solve of a model with a zero axis both name it.
fn refused<M: OdeSystem<4>>(model: &M, y: Vector<4>) {
    names_the_axis(model.rhs(0.0, &y).unwrap_err());
    let solve = Dopri5::new(Options::default()).solve(model, 0.0, y, 1.0, &[]);
    names_the_axis(solve.unwrap_err());
}

/// `s(t)` after one second from rest at zero by DOPRI5, against `s = (g . a / |a|^2) t^2 / 2`
/// and `q = 0`: the block and the bob move together when gravity less the block's
/// acceleration `(g . a_hat) a_hat` has no component the pendulum swings in (each case says
/// why), so the bob's mass only adds to the block's.
fn slides<M: OdeSystem<4>>(model: &M, g: &[f64], a: &[f64]) {
    let ga: f64 = g.iter().zip(a).map(|(g, a)| g * a).sum();
    let a2: f64 = a.iter().map(|a| a * a).sum();
    let sdd = ga / a2;
    let y0 = Vector::<4>::zeros();
    let dy = model.rhs(0.0, &y0).unwrap();
    assert!((dy[2] - sdd).abs() < 1e-12, "{} vs {sdd}", dy[2]);
    // The displacement along the unit axis: d'' = g . a_hat.
    assert!((dy[2] * a2.sqrt() - ga / a2.sqrt()).abs() < 1e-12);
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-12,
        ..Options::default()
    };
    let sol = Dopri5::new(opts).solve(model, 0.0, y0, 1.0, &[]).unwrap();
    let (t, y) = sol.last();
    assert_eq!(t, 1.0);
    assert!((y[0] - sdd / 2.0).abs() < 1e-9, "{} vs {}", y[0], sdd / 2.0);
    assert!((y[2] - sdd).abs() < 1e-9);
    assert!(y[1].abs() < 1e-12 && y[3].abs() < 1e-12, "{y:?}");
}

fn spatial_aba(a: [f64; 3]) -> SpatialAba {
    SpatialAba {
        m: 2.0,
        mb: 0.5,
        l: 0.7,
        ax: a[0],
        ay: a[1],
        az: a[2],
        gx: 0.0,
        gy: -1.0,
        gz: -9.81,
    }
}

fn spatial_mass(a: [f64; 3]) -> SpatialMass {
    let p = spatial_aba(a);
    SpatialMass {
        m: p.m,
        mb: p.mb,
        l: p.l,
        ax: p.ax,
        ay: p.ay,
        az: p.az,
        gx: p.gx,
        gy: p.gy,
        gz: p.gz,
    }
}

fn planar_aba(a: [f64; 2]) -> PlanarAba {
    PlanarAba {
        m: 2.0,
        mb: 0.5,
        l: 0.7,
        ax: a[0],
        ay: a[1],
        gx: 3.0 * 9.81 / 5.0,
        gy: -4.0 * 9.81 / 5.0,
    }
}

fn planar_mass(a: [f64; 2]) -> PlanarMass {
    let p = planar_aba(a);
    PlanarMass {
        m: p.m,
        mb: p.mb,
        l: p.l,
        ax: p.ax,
        ay: p.ay,
        gx: p.gx,
        gy: p.gy,
    }
}

#[test]
fn a_zero_axis_of_parameters_is_named_in_both_forms() {
    let y = Vector::<4>::new(0.1, 0.2, 0.3, -0.4);
    refused(&spatial_aba([0.0; 3]), y);
    refused(&spatial_mass([0.0; 3]), y);
    refused(&planar_aba([0.0; 2]), y);
    refused(&planar_mass([0.0; 2]), y);
    names_the_axis(spatial_aba([0.0; 3]).check_parameters().unwrap_err());
    names_the_axis(planar_mass([0.0; 2]).check_parameters().unwrap_err());
}

#[test]
fn unit_and_non_unit_axes_slide_as_the_closed_form() {
    // Spatial: gravity (0, -1, -9.81) and axes in the y-z plane: what is left of gravity has
    // no x component, so no moment about the pendulum's y axis. A unit axis along y, a unit
    // one in the y-z plane, then one of length sqrt(8.5).
    let g = [0.0, -1.0, -9.81];
    for a in [[0.0, 1.0, 0.0], [0.0, 0.6, -0.8], [0.0, -2.5, 1.5]] {
        slides(&spatial_aba(a), &g, &a);
        slides(&spatial_mass(a), &g, &a);
    }
    // Planar: gravity 9.81 along (3, -4) / 5 and axes along it: the block falls freely
    // along its axis, so the pendulum feels no gravity. A unit axis, then (-3, 4) (length 5).
    let g = [3.0 * 9.81 / 5.0, -4.0 * 9.81 / 5.0];
    for a in [[0.6, -0.8], [-3.0, 4.0]] {
        slides(&planar_aba(a), &g, &a);
        slides(&planar_mass(a), &g, &a);
    }
}
