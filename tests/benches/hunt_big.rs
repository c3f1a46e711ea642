//! The right-hand side of the 30-dof humanoid-like spatial tree of `hunt_big_humanoid`
//! (generated articulated-body recursion, 14 bodies), and of the same tree on a floating
//! base (`floating_humanoid`: the torso on a free joint, 33 dof): the least time per call
//! over batches, which background load does not skew. For scale: RigidBodyDynamics.jl
//! reports 17.7 us for the forward dynamics of a 30-dof humanoid (Atlas, floating base);
//! that is another model on another machine, a yardstick, not a same-run ratio.
//!
//! `cargo bench -p tests --bench hunt_big`

#[path = "../tests/support/floating_humanoid.rs"]
mod floating_humanoid;
#[path = "../tests/support/humanoid.rs"]
mod humanoid;

use floating_humanoid::FloatingHumanoid;
use humanoid::Humanoid;
use mbd::prelude::*;
use std::hint::black_box;
use std::time::Instant;

fn least_ns(run: &dyn Fn()) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..300 {
        let start = Instant::now();
        for _ in 0..1000 {
            run();
        }
        best = best.min(start.elapsed().as_secs_f64() * 1e9 / 1000.0);
    }
    best
}

/// One free body (a satellite), through the articulated-body recursion and through the
/// mass-matrix form: which one `mechanism(spatial)` should pick by itself.
#[derive(Debug, Mechanism)]
#[mechanism(spatial, recursive)]
#[gravity(0.0, 0.0, -g)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [0.1, -0.05, 0.2], mass = 3.0,
       inertia = [[0.8, 0.02, 0.01], [0.02, 1.3, 0.03], [0.01, 0.03, 1.9]])]
pub struct FreeRecursive {
    pub g: f64,
}

#[derive(Debug, Mechanism)]
#[mechanism(spatial, mass_matrix)]
#[gravity(0.0, 0.0, -g)]
#[body(sat, joint = free(x, y, z, s1, s2, s3), com = [0.1, -0.05, 0.2], mass = 3.0,
       inertia = [[0.8, 0.02, 0.01], [0.02, 1.3, 0.03], [0.01, 0.03, 1.9]])]
pub struct FreeMassMatrix {
    pub g: f64,
}

/// The least times of `p`'s rhs, mass matrix and forces at one fixed state, printed.
fn time_model<S, const N: usize, const D: usize>(name: &str, p: &S)
where
    S: MechanismModel<N> + OdeSystem<D>,
{
    let y = Vector::<D>::from_fn(|i, _| 0.5 * (1.3 * i as f64).sin());
    let (q, qd) = (
        y.fixed_rows::<N>(0).into_owned(),
        y.fixed_rows::<N>(N).into_owned(),
    );
    let rhs = least_ns(&|| {
        let _ = black_box(p.rhs(0.0, black_box(&y)));
    });
    let mass = least_ns(&|| {
        let _ = black_box(p.mass_matrix(0.0, black_box(&q)));
    });
    let forces = least_ns(&|| {
        let _ = black_box(p.forces(0.0, black_box(&q), black_box(&qd)));
    });
    println!(
        "{name}: rhs {rhs:.0} ns, mass matrix {mass:.0} ns, forces {forces:.0} ns (least of 300 batches of 1000)"
    );
}

fn main() {
    time_model::<_, 30, 60>("humanoid (30 dof, 14 bodies)", &Humanoid { g: 9.81 });
    time_model::<_, 33, 66>(
        "floating humanoid (33 dof, 14 bodies)",
        &FloatingHumanoid { g: 9.81 },
    );
    let y = Vector::<12>::from_fn(|i, _| 0.5 * (1.3 * i as f64).sin());
    let (a, b) = (FreeRecursive { g: 9.81 }, FreeMassMatrix { g: 9.81 });
    let recursive = least_ns(&|| {
        let _ = black_box(a.rhs(0.0, black_box(&y)));
    });
    let mass_matrix = least_ns(&|| {
        let _ = black_box(b.rhs(0.0, black_box(&y)));
    });
    println!(
        "one free body: rhs {recursive:.0} ns by the recursion, {mass_matrix:.0} ns by the mass matrix"
    );
}
