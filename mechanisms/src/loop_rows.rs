//! The closed loops' rows of the work-precision report: the IFToMM A02 assembly of 40
//! four-bar loops (its first second and its first singular position, bridged by `mbd::passage`)
//! against its one-coordinate reduction, and the Bricard linkage (IFToMM A04, redundant
//! constraints) against its conserved energy.

use crate::bricard::Bricard;
use crate::fourbar_assembly::{self as fa, FourBarAssembly};
use crate::workprecision::{Failure, Measured, Method, Problem, Quantity, Setting};
use mbd::integrate::{GeneralizedAlpha, Integrator};
use mbd::passage::{self, Settings};
use mbd::{Mechanism, Options, Vector};

/// The loops' problems (appended to [`crate::workprecision::cases`]).
pub fn problems() -> Vec<Problem> {
    vec![
        Problem {
            name: "fourbar_assembly",
            title: "IFToMM A02, 40 four-bar loops: crank 0's tip at 1 s (a singular position bridged)",
            methods: &[
                Method::Dopri5,
                Method::Dop853,
                Method::Vern9,
                Method::GeneralizedAlpha,
            ],
            run: assembly,
        },
        Problem {
            name: "bricard",
            title: "IFToMM A04 Bricard linkage (a redundant constraint): energy after 10 s",
            methods: &[
                Method::Dopri5,
                Method::Dop853,
                Method::Vern9,
                Method::Radau5,
            ],
            run: bricard,
        },
    ]
}

const T_ASSEMBLY: f64 = 1.0;

fn options(s: &Setting) -> Options {
    Options {
        rtol: s.value,
        atol: s.value,
        dense: false,
        record: mbd::Record::Final,
        ..Default::default()
    }
}

fn assembly(s: &Setting) -> Result<Measured, Failure> {
    let a = FourBarAssembly::benchmark();
    let y0 = a.benchmark_state(1.0);
    let reference = fa::reference(&a, 1.0, T_ASSEMBLY)?;
    let th = reference.y_end[0];
    let run = match s.method {
        Method::Dopri5 => passage::solve(
            &mbd::Dopri5::new(options(s)),
            &a,
            0.0,
            y0,
            T_ASSEMBLY,
            &[],
            &Settings::new(s.value),
        )?,
        Method::Dop853 => passage::solve(
            &mbd::Dop853::new(options(s)),
            &a,
            0.0,
            y0,
            T_ASSEMBLY,
            &[],
            &Settings::new(s.value),
        )?,
        Method::Vern9 => passage::solve(
            &mbd::Vern9::new(options(s)),
            &a,
            0.0,
            y0,
            T_ASSEMBLY,
            &[],
            &Settings::new(s.value),
        )?,
        // Index 3, its Newton matrix from `M` and `Phi_q`: passes the flat positions itself.
        Method::GeneralizedAlpha => {
            passage::solve_generalized_alpha::<_, { fa::N }, { fa::M }, { fa::N + fa::M }, { fa::D }>(
                &GeneralizedAlpha::new(crate::workprecision::RHO_INF, s.value)
                    .recording(mbd::Record::Final, false),
                &a,
                0.0,
                y0,
                T_ASSEMBLY,
                &[],
                &Settings::new(s.value * s.value),
            )?
        }
        other => return Err(Failure::Unsupported(format!("{other} is not swept here"))),
    };
    let tip = a.tip(&run.solution.y_end);
    Ok(Measured {
        quantities: vec![
            Quantity {
                name: "x_B0",
                value: tip[0],
                reference: a.l * th.cos(),
            },
            Quantity {
                name: "y_B0",
                value: tip[1],
                reference: a.l * th.sin(),
            },
        ],
        stats: run.solution.stats,
        span: T_ASSEMBLY,
    })
}

fn bricard(s: &Setting) -> Result<Measured, Failure> {
    let b = Bricard::benchmark();
    let y0 = Vector::<10>::zeros();
    let energy = |y: &Vector<10>| {
        b.energy(
            0.0,
            &y.fixed_rows::<5>(0).into_owned(),
            &y.fixed_rows::<5>(5).into_owned(),
        )
    };
    let sol = match s.method {
        Method::Dopri5 => mbd::Dopri5::new(options(s)).solve(&b, 0.0, y0, 10.0, &[])?,
        Method::Dop853 => mbd::Dop853::new(options(s)).solve(&b, 0.0, y0, 10.0, &[])?,
        Method::Vern9 => mbd::Vern9::new(options(s)).solve(&b, 0.0, y0, 10.0, &[])?,
        Method::Radau5 => mbd::integrate::Radau5::new(options(s)).solve(&b, 0.0, y0, 10.0, &[])?,
        other => return Err(Failure::Unsupported(format!("{other} is not swept here"))),
    };
    Ok(Measured {
        quantities: vec![Quantity {
            name: "energy",
            value: energy(&sol.y_end)?,
            reference: energy(&y0)?,
        }],
        stats: sol.stats,
        span: 10.0,
    })
}
