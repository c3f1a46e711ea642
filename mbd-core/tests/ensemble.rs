//! Ensembles against the serial loop they replace: every member's result bitwise equal to
//! its serial run, results in input order, and a failing member leaving the others alone.

use mbd_core::ensemble::{self, Member};
use mbd_core::integrate::{Dopri5, Integrator, Options, Rk4, Solution};
use mbd_core::{Error, OdeSystem, Result, Vector};

/// A pendulum with a damper: `theta'' = -(g / l) sin theta - c theta'`, with the mass
/// matrix `m l^2` made explicit so that `m = 0` is a singular model that fails in `rhs`.
#[derive(Debug, Clone)]
struct Pendulum {
    m: f64,
    l: f64,
    g: f64,
    c: f64,
}

impl OdeSystem<2> for Pendulum {
    fn rhs(&self, t: f64, y: &Vector<2>) -> Result<Vector<2>> {
        let mass = self.m * self.l * self.l;
        if mass == 0.0 {
            return Err(Error::SingularMassMatrix { t });
        }
        let force = -self.m * self.g * self.l * y[0].sin() - mass * self.c * y[1];
        Ok(Vector::<2>::new(y[1], force / mass))
    }
}

fn members(n: usize) -> Vec<Member<Pendulum, 2>> {
    (0..n)
        .map(|k| {
            let x = k as f64;
            Member::new(
                Pendulum {
                    m: 1.0 + 0.1 * x,
                    l: 0.5 + 0.03 * x,
                    g: 9.81,
                    c: 0.01 * (k % 3) as f64,
                },
                Vector::<2>::new(0.1 + 0.09 * x, 0.5 - 0.05 * x),
            )
        })
        .collect()
}

fn dopri5() -> Dopri5 {
    Dopri5::new(Options {
        rtol: 1e-10,
        atol: 1e-10,
        ..Options::default()
    })
}

/// Bitwise equality of two solutions: step times, states, dense segments' ends, counters.
fn assert_identical(a: &Solution<2>, b: &Solution<2>, k: usize) {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.t), bits(&b.t), "member {k}: step times differ");
    assert_eq!(a.y.len(), b.y.len(), "member {k}");
    for (ya, yb) in a.y.iter().zip(&b.y) {
        assert_eq!(
            bits(ya.as_slice()),
            bits(yb.as_slice()),
            "member {k}: states differ"
        );
    }
    assert_eq!(a.segments.len(), b.segments.len(), "member {k}");
    for (sa, sb) in a.segments.iter().zip(&b.segments) {
        let (ta, tb) = (sa.t1(), sb.t1());
        assert_eq!(ta.to_bits(), tb.to_bits(), "member {k}");
        let mid = 0.5 * (sa.t0 + ta);
        assert_eq!(
            bits(sa.eval(mid).as_slice()),
            bits(sb.eval(mid).as_slice()),
            "member {k}: dense output differs"
        );
    }
    assert_eq!(a.stats, b.stats, "member {k}: counters differ");
}

/// A pool of four threads whatever the machine, so the test runs members concurrently even
/// on one core.
fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .expect("a thread pool")
}

#[test]
fn map_keeps_input_order() {
    // Uneven work (member k does k^2 iterations), so members finish out of order.
    let inputs: Vec<u64> = (0..200).collect();
    let work = |&k: &u64| {
        let mut acc = k;
        for i in 0..k * k {
            acc = acc.wrapping_mul(6364136223846793005).wrapping_add(i);
        }
        (k, acc)
    };
    let parallel = pool().install(|| ensemble::map(&inputs, work));
    let serial: Vec<_> = inputs.iter().map(work).collect();
    assert_eq!(parallel, serial);
    assert!(
        parallel
            .iter()
            .enumerate()
            .all(|(i, &(k, _))| k == i as u64)
    );
}

#[test]
fn map_of_nothing_is_empty() {
    let none: [f64; 0] = [];
    assert!(ensemble::map(&none, |x| x * 2.0).is_empty());
}

#[test]
fn integrate_is_bitwise_the_serial_loop_in_order() {
    let members = members(24);
    let method = dopri5();
    let (t0, t1) = (0.0, 5.0);
    let parallel = pool().install(|| ensemble::integrate(&method, &members, t0, t1));
    assert_eq!(parallel.len(), members.len());
    for (k, (m, par)) in members.iter().zip(&parallel).enumerate() {
        let serial = method
            .solve(&m.model, t0, m.y0, t1, &[])
            .expect("serial run");
        let par = par.as_ref().expect("parallel run");
        assert_identical(par, &serial, k);
    }
    // The members differ, so equal results in input order are not an accident of symmetry.
    let ends: Vec<u64> = parallel
        .iter()
        .map(|s| s.as_ref().unwrap().last().1[0].to_bits())
        .collect();
    let mut unique = ends.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), ends.len());
}

#[test]
fn final_states_match_the_serial_loop_with_a_fixed_step_method() {
    let members = members(16);
    let method = Rk4::new(1e-3);
    let finals = pool().install(|| ensemble::final_states(&method, &members, 0.0, 2.0));
    for (k, (m, fin)) in members.iter().zip(&finals).enumerate() {
        let serial = method.solve(&m.model, 0.0, m.y0, 2.0, &[]).unwrap();
        let (ts, ys) = serial.last();
        let (tp, yp) = fin.as_ref().unwrap();
        assert_eq!(tp.to_bits(), ts.to_bits(), "member {k}");
        assert_eq!(yp[0].to_bits(), ys[0].to_bits(), "member {k}");
        assert_eq!(yp[1].to_bits(), ys[1].to_bits(), "member {k}");
    }
}

#[test]
fn a_failing_member_leaves_the_others_alone() {
    let mut members = members(9);
    members[4].model.m = 0.0; // singular: fails at the first rhs call
    let method = dopri5();
    let results = pool().install(|| ensemble::integrate(&method, &members, 0.0, 3.0));
    for (k, (m, r)) in members.iter().zip(&results).enumerate() {
        if k == 4 {
            assert_eq!(
                r.as_ref().unwrap_err(),
                &Error::SingularMassMatrix { t: 0.0 }
            );
        } else {
            let serial = method.solve(&m.model, 0.0, m.y0, 3.0, &[]).unwrap();
            assert_identical(r.as_ref().expect("healthy member"), &serial, k);
            assert_eq!(r.as_ref().unwrap().last().0, 3.0);
        }
    }
}

#[test]
fn invalid_input_of_one_member_is_its_error() {
    let mut members = members(3);
    members[1].y0[0] = f64::NAN;
    let results = ensemble::final_states(&dopri5(), &members, 0.0, 1.0);
    assert!(results[0].is_ok() && results[2].is_ok());
    assert!(matches!(
        results[1],
        Err(Error::InvalidInput { what: "y0", .. })
    ));
}
