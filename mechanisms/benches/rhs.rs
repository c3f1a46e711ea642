//! Generated vs hand-written right-hand sides, same run: simple pendulum, double pendulum,
//! and a constrained slider-crank (index-1 form with the augmented solve).
//!
//! `cargo bench -p mechanisms --bench rhs`. The hand-written models are what a careful
//! engineer writes for each: the closed-form acceleration for the pendulum, a 2x2 solve for
//! the double pendulum, and M, f, Phi_q, gamma with the same augmented LU for the
//! slider-crank, so the ratio measures the generated code, not a different algorithm.

use criterion::{Criterion, criterion_group, criterion_main};
use mbd::nalgebra::{Matrix2, SVector, Vector2};
use mbd::prelude::*;
use std::hint::black_box;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(theta)]
#[particle(bob, mass = m, at = [l * sin(theta), -l * cos(theta)])]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

fn pendulum_by_hand(p: &Pendulum, y: &SVector<f64, 2>) -> SVector<f64, 2> {
    SVector::<f64, 2>::new(y[1], -p.g / p.l * y[0].sin())
}

/// Two point masses on massless rods, angles from the downward vertical.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(a, b)]
#[particle(p1, mass = m1, at = [l1 * sin(a), -l1 * cos(a)])]
#[particle(p2, mass = m2, at = [l1 * sin(a) + l2 * sin(b), -l1 * cos(a) - l2 * cos(b)])]
pub struct DoublePendulum {
    pub m1: f64,
    pub m2: f64,
    pub l1: f64,
    pub l2: f64,
    pub g: f64,
}

/// Lagrange's equations of the double pendulum written out by hand:
/// `M = [[(m1+m2) l1^2, m2 l1 l2 c], [m2 l1 l2 c, m2 l2^2]]`, `c = cos(a - b)`,
/// `f = [-m2 l1 l2 s b'^2 - (m1+m2) g l1 sin a, m2 l1 l2 s a'^2 - m2 g l2 sin b]`, `s = sin(a - b)`.
fn double_by_hand(p: &DoublePendulum, y: &SVector<f64, 4>) -> SVector<f64, 4> {
    let (a, b, ad, bd) = (y[0], y[1], y[2], y[3]);
    let (s, c) = (a - b).sin_cos();
    let m12 = p.m2 * p.l1 * p.l2 * c;
    let m = Matrix2::new((p.m1 + p.m2) * p.l1 * p.l1, m12, m12, p.m2 * p.l2 * p.l2);
    let f = Vector2::new(
        -p.m2 * p.l1 * p.l2 * s * bd * bd - (p.m1 + p.m2) * p.g * p.l1 * a.sin(),
        p.m2 * p.l1 * p.l2 * s * ad * ad - p.m2 * p.g * p.l2 * b.sin(),
    );
    let acc = m.cholesky().expect("positive definite").solve(&f);
    SVector::<f64, 4>::new(ad, bd, acc[0], acc[1])
}

/// A free slider-crank: crank (inertia about O), rod, piston; three coordinates, two loop
/// constraints, gravity.
#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[coords(theta, beta, x)]
#[constraint(x == l * cos(beta) + r * cos(theta))]
#[constraint(l * sin(beta) == r * sin(theta))]
#[rigid(crank, mass = m_c, inertia = m_c * r * r / 12.0, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
#[rigid(rod, mass = m_r, inertia = m_r * l * l / 12.0,
        at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
        angle = -beta)]
#[particle(piston, mass = m_p, at = [x, 0.0])]
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub m_c: f64,
    pub m_r: f64,
    pub m_p: f64,
    pub g: f64,
}

/// The same slider-crank by hand: Kane's form with the Jacobians written out.
fn slider_by_hand(p: &SliderCrank, y: &SVector<f64, 6>) -> SVector<f64, 6> {
    let (th, be, thd, bed, xd) = (y[0], y[1], y[3], y[4], y[5]);
    let (st, ct) = th.sin_cos();
    let (sb, cb) = be.sin_cos();
    let (r, l) = (p.r, p.l);
    // Crank centre (r/2)(ct, st); rod centre (r ct + l/2 cb, r st - l/2 sb); piston (x, 0).
    let ic = p.m_c * r * r / 12.0;
    let ir = p.m_r * l * l / 12.0;
    let mut m = mbd::Matrix::<3, 3>::zeros();
    // Crank: J = (r/2)(-st, ct) on theta, angle theta.
    m[(0, 0)] += p.m_c * r * r / 4.0 + ic;
    // Rod: J_theta = r(-st, ct), J_beta = (l/2)(-sb, -cb), angle -beta.
    m[(0, 0)] += p.m_r * r * r;
    let jtb = p.m_r * r * l / 2.0 * (st * sb - ct * cb);
    m[(0, 1)] += jtb;
    m[(1, 0)] += jtb;
    m[(1, 1)] += p.m_r * l * l / 4.0 + ir;
    m[(2, 2)] += p.m_p;
    // Velocity-product terms: a0 = d(J)/dt qd; gravity (0, -g).
    let a0c = [-r / 2.0 * ct * thd * thd, -r / 2.0 * st * thd * thd];
    let a0r = [
        -r * ct * thd * thd - l / 2.0 * cb * bed * bed,
        -r * st * thd * thd + l / 2.0 * sb * bed * bed,
    ];
    let mut f = mbd::Vector::<3>::zeros();
    f[0] = -p.m_c * (r / 2.0 * (-st) * a0c[0] + r / 2.0 * ct * (a0c[1] + p.g))
        - p.m_r * (r * (-st) * a0r[0] + r * ct * (a0r[1] + p.g));
    f[1] = -p.m_r * (l / 2.0 * (-sb) * a0r[0] + l / 2.0 * (-cb) * (a0r[1] + p.g));
    // Phi = [x - l cb - r ct, l sb - r st].
    let phi_q = mbd::Matrix::<2, 3>::new(r * st, l * sb, 1.0, -r * ct, l * cb, 0.0);
    let gamma = mbd::Vector::<2>::new(
        -(r * ct * thd * thd + l * cb * bed * bed),
        -(r * st * thd * thd - l * sb * bed * bed),
    );
    let _ = xd;
    let (acc, _) =
        mbd::solve::solve_augmented::<3, 2, 5>(0.0, &m, &f, &phi_q, &gamma).expect("regular");
    SVector::<f64, 6>::new(y[3], y[4], y[5], acc[0], acc[1], acc[2])
}

fn benches(c: &mut Criterion) {
    let p = Pendulum {
        m: 1.0,
        l: 0.8,
        g: 9.81,
    };
    let y = SVector::<f64, 2>::new(0.7, 0.3);
    assert!((p.rhs(0.0, &y).unwrap() - pendulum_by_hand(&p, &y)).norm() < 1e-14);
    c.bench_function("pendulum/generated", |b| {
        b.iter(|| p.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("pendulum/hand-written", |b| {
        b.iter(|| pendulum_by_hand(&p, black_box(&y)))
    });

    let d = DoublePendulum {
        m1: 1.0,
        m2: 0.7,
        l1: 0.8,
        l2: 0.6,
        g: 9.81,
    };
    let y = SVector::<f64, 4>::new(0.7, -0.4, 0.3, 1.1);
    assert!((d.rhs(0.0, &y).unwrap() - double_by_hand(&d, &y)).norm() < 1e-12);
    c.bench_function("double_pendulum/generated", |b| {
        b.iter(|| d.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("double_pendulum/hand-written", |b| {
        b.iter(|| double_by_hand(&d, black_box(&y)))
    });

    let s = SliderCrank {
        r: 0.125,
        l: 0.35,
        m_c: 1.0,
        m_r: 0.6,
        m_p: 0.82,
        g: 9.81,
    };
    let (th, be) = (0.6f64, (0.125 * 0.6f64.sin() / 0.35).asin());
    let x = 0.35 * be.cos() + 0.125 * th.cos();
    // Consistent velocities for thd = 5: bed = r ct thd / (l cb), xd = -r st thd - l sb bed.
    let bed = 0.125 * th.cos() * 5.0 / (0.35 * be.cos());
    let xd = -0.125 * th.sin() * 5.0 - 0.35 * be.sin() * bed;
    let y = SVector::<f64, 6>::new(th, be, x, 5.0, bed, xd);
    assert!((s.rhs(0.0, &y).unwrap() - slider_by_hand(&s, &y)).norm() < 1e-9);
    c.bench_function("slider_crank/generated", |b| {
        b.iter(|| s.rhs(0.0, black_box(&y)).unwrap())
    });
    c.bench_function("slider_crank/hand-written", |b| {
        b.iter(|| slider_by_hand(&s, black_box(&y)))
    });
}

criterion_group!(rhs, benches);
criterion_main!(rhs);
