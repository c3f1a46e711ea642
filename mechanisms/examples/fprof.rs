use mbd::integrate::{Dopri5, Integrator, Radau5};
use mbd::Options;
use mechanisms::stick_slip;
fn main() {
    if std::env::args().nth(4).is_some() { counts(std::env::args().nth(1).unwrap().parse().unwrap()); return; }
    let tol: f64 = std::env::args().nth(1).map_or(1e-6, |s| s.parse().unwrap());
    let free_run = std::env::args().nth(2).is_some_and(|s| s == "free");
    let radau = std::env::args().nth(3).is_some();
    let opts = Options { rtol: tol, atol: tol, dense: true, ..Options::default() };
    let b = stick_slip::belt();
    let free = stick_slip::without_friction(&b);
    let (_, ts, tl) = stick_slip::limit_cycle(&b);
    let t1 = 100.0 * (ts + tl) + 0.5 * ts;
    let t0 = std::time::Instant::now();
    let mut n = 0;
    for _ in 0..300 {
        n += if radau {
            let i = Radau5::new(opts.clone());
            if free_run { i.solve(&free, 0.0, free.initial_state(), t1, &[]).unwrap().stats.n_rhs }
            else { stick_slip::run(&i, &b, 100, false).unwrap().solution.stats.n_rhs }
        } else {
            let i = Dopri5::new(opts.clone());
            if free_run { i.solve(&free, 0.0, free.initial_state(), t1, &[]).unwrap().stats.n_rhs }
            else { stick_slip::run(&i, &b, 100, false).unwrap().solution.stats.n_rhs }
        };
    }
    println!("{n} {:?}", t0.elapsed() / 300);
}
use mbd::Slip;
use std::cell::Cell;
pub struct Count<'a> { pub b: &'a stick_slip::Belt, pub sw: [Cell<usize>; 2], pub rhs: [Cell<usize>; 2] }
impl mbd::Hybrid<2> for Count<'_> {
    type Mode = [Slip; 1];
    const SWITCHES: usize = 1;
    fn rhs_in(&self, t: f64, y: &mbd::Vector<2>, m: &Self::Mode) -> mbd::Result<mbd::Vector<2>> {
        let i = usize::from(m[0] == Slip::Stick); self.rhs[i].set(self.rhs[i].get() + 1);
        self.b.rhs_in(t, y, m)
    }
    fn switching(&self, t: f64, y: &mbd::Vector<2>, m: &Self::Mode, k: usize) -> f64 {
        let i = usize::from(m[0] == Slip::Stick); self.sw[i].set(self.sw[i].get() + 1);
        self.b.switching(t, y, m, k)
    }
    fn mode_at(&self, t: f64, y: &mbd::Vector<2>) -> mbd::Result<Self::Mode> { self.b.mode_at(t, y) }
    fn switch(&self, t: f64, y: &mut mbd::Vector<2>, m: &Self::Mode, k: usize) -> mbd::Result<Self::Mode> { self.b.switch(t, y, m, k) }
}
pub fn counts(tol: f64) {
    let b = stick_slip::belt();
    let c = Count { b: &b, sw: Default::default(), rhs: Default::default() };
    let (_, ts, tl) = stick_slip::limit_cycle(&b);
    let t1 = 100.0 * (ts + tl) + 0.5 * ts;
    let opts = Options { rtol: tol, atol: tol, dense: true, ..Options::default() };
    let r = mbd::hybrid::solve(&Dopri5::new(opts), &c, 0.0, b.initial_state(), t1, &[]).unwrap();
    let stick_steps: usize = r.switches.iter().filter(|s| s.from[0] == Slip::Stick).map(|s| s.steps).sum();
    println!("switching slip {} stick {}; rhs slip {} stick {}; steps {} stick steps {}", c.sw[0].get(), c.sw[1].get(), c.rhs[0].get(), c.rhs[1].get(), r.solution.stats.n_accepted, stick_steps);
}
