use mbd::integrate::{Auto, Dop853, Dopri5, Integrator, Radau5, Vern9, Rk4, Gauss};
use mbd::prelude::*;

#[derive(Debug, Mechanism)]
#[gravity(0.0, -g)]
#[body(bar, joint = revolute(q), com = [0.0, -l], mass = m)]
#[init(q = 0.5)]
pub struct Pend { pub m: f64, pub l: f64, pub g: f64 }

#[derive(Debug, Mechanism)]
#[coords(x)]
#[particle(block, mass = 1.0, at = [x, 0.0])]
#[generalized_force(spring, along = x, value = -4.0 * x)]
#[init(x = 1.0)]
pub struct Osc {}

fn errs(name: &str, s: &Solution<2>) {
    let ends = s.t.iter().zip(&s.y).map(|(t, y)| (y[0] - (2.0 * t).cos()).abs()).fold(0.0, f64::max);
    let dense = (0..=1000).map(|k| { let t = 3.0 * k as f64 / 1000.0; (s.at(t).unwrap()[0] - (2.0 * t).cos()).abs() }).fold(0.0, f64::max);
    println!("{name}: steps {} ends {ends:.2e} dense {dense:.2e}", s.t.len());
}

#[test]
fn p() {
    let p = Osc {};
    for tol in [1e-6, 1e-9, 1e-12] {
        let o = Options { rtol: tol, atol: tol, ..Options::default() };
        println!("tol {tol}");
        errs("dopri5", &Dopri5::new(o.clone()).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
        errs("dop853", &Dop853::new(o.clone()).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
        errs("vern9", &Vern9::new(o.clone()).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
        errs("radau5", &Radau5::new(o.clone()).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
        errs("auto", &Auto::new(o.clone()).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
    }
    errs("rk4 1e-2", &Rk4::new(1e-2).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
    errs("gauss 1e-1", &Gauss::new(1e-1).solve(&p, 0.0, p.initial_state(), 3.0, &[]).unwrap());
    let _ = Pend { m: 1.0, l: 1.0, g: 9.81 };
}
