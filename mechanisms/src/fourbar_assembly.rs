//! The IFToMM multibody benchmark A02: an assembly of 40 four-bar loops (81 links).
//!
//! **Problem.** 41 cranks of length `l` pinned to the ground at `x = 0, l, .., 40 l`, and 40
//! couplers: coupler `i` is pinned to the tip of crank `i` and to the tip of crank `i + 1`.
//! Every link is a uniform bar of length `l = 1 m` and mass `m = 1 kg`; gravity `9.81 m/s^2`
//! along `-y`. At `t = 0` the cranks are vertical (the couplers horizontal, on top) and the
//! tip `B0` of crank 0 moves at `1 m/s` along `+x`; the benchmark asks for the motion of `B0`
//! over 20 s (400 outputs, error allowed `1e-3` for "high precision").
//!
//! **Model.** Written as the benchmark draws it, a tree of 81 bodies (crank `i` on the ground,
//! coupler `i` on crank `i`) with 40 closing pins: 81 angles, 80 closure equations, one
//! degree of freedom. Crank `i`'s coordinate `c_i` is its absolute angle, coupler `i`'s `k_i`
//! its angle relative to crank `i`. Whenever the cranks are horizontal (every 1 s or so) the
//! whole assembly lies on one line, the closure Jacobian loses 40 of its 80 ranks, and the
//! mechanism instantaneously has 41 degrees of freedom: the benchmark's point.
//!
//! **Reference (one coordinate, by hand).** Started as a parallelogram, the assembly stays one:
//! every crank turns by the same angle `th` and every coupler translates (`k_i = -th + const`).
//! Then crank `i` is a bar turning about its pin (`T = m l^2 th'^2 / 6`, `V = m g l sin(th) / 2`)
//! and coupler `i` translates with the crank tips (`T = m l^2 th'^2 / 2`, `V = m g l sin th`), so
//! Lagrange's equation of the whole is
//! `(41/3 + 40) m l^2 th'' = -(41/2 + 40) m g l cos th`,
//! with `th(0) = pi/2`, `th'(0) = -1 rad/s` (`B0 = l (cos th, sin th)`, `B0' = (1, 0) m/s`).
//! [`reference`] integrates it; the tests compare crank 0's tip with it.

use mbd::prelude::*;

/// Emits the assembly's struct with one `#[body]` pair and one `#[close]` per loop.
macro_rules! assembly {
    ($(($c:ident, $crank:ident, $x:expr, $k:ident, $cpl:ident, $next:ident, $pin:ident),)*
     last($cl:ident, $crankl:ident, $xl:expr)) => {
        /// The 40-loop assembly (IFToMM A02) as a joint tree closed by 40 pins.
        #[derive(Debug, Clone, Mechanism)]
        #[gravity(0.0, -g)]
        $(
            #[body($crank, joint = revolute($c), at = [$x * l, 0.0], com = [0.5 * l, 0.0],
                   mass = m, inertia = m * l * l / 12.0)]
            #[body($cpl, parent = $crank, joint = revolute($k), at = [l, 0.0],
                   com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0)]
            #[close($pin, a = $cpl, at_a = [l, 0.0], b = $next, at_b = [l, 0.0])]
        )*
        #[body($crankl, joint = revolute($cl), at = [$xl * l, 0.0], com = [0.5 * l, 0.0],
               mass = m, inertia = m * l * l / 12.0)]
        pub struct FourBarAssembly {
            /// Mass of every link.
            pub m: f64,
            /// Length of every link and the pin spacing.
            pub l: f64,
            pub g: f64,
        }
    };
}

assembly! {
    (c0, crank0, 0.0, k0, coupler0, crank1, pin0),
    (c1, crank1, 1.0, k1, coupler1, crank2, pin1),
    (c2, crank2, 2.0, k2, coupler2, crank3, pin2),
    (c3, crank3, 3.0, k3, coupler3, crank4, pin3),
    (c4, crank4, 4.0, k4, coupler4, crank5, pin4),
    (c5, crank5, 5.0, k5, coupler5, crank6, pin5),
    (c6, crank6, 6.0, k6, coupler6, crank7, pin6),
    (c7, crank7, 7.0, k7, coupler7, crank8, pin7),
    (c8, crank8, 8.0, k8, coupler8, crank9, pin8),
    (c9, crank9, 9.0, k9, coupler9, crank10, pin9),
    (c10, crank10, 10.0, k10, coupler10, crank11, pin10),
    (c11, crank11, 11.0, k11, coupler11, crank12, pin11),
    (c12, crank12, 12.0, k12, coupler12, crank13, pin12),
    (c13, crank13, 13.0, k13, coupler13, crank14, pin13),
    (c14, crank14, 14.0, k14, coupler14, crank15, pin14),
    (c15, crank15, 15.0, k15, coupler15, crank16, pin15),
    (c16, crank16, 16.0, k16, coupler16, crank17, pin16),
    (c17, crank17, 17.0, k17, coupler17, crank18, pin17),
    (c18, crank18, 18.0, k18, coupler18, crank19, pin18),
    (c19, crank19, 19.0, k19, coupler19, crank20, pin19),
    (c20, crank20, 20.0, k20, coupler20, crank21, pin20),
    (c21, crank21, 21.0, k21, coupler21, crank22, pin21),
    (c22, crank22, 22.0, k22, coupler22, crank23, pin22),
    (c23, crank23, 23.0, k23, coupler23, crank24, pin23),
    (c24, crank24, 24.0, k24, coupler24, crank25, pin24),
    (c25, crank25, 25.0, k25, coupler25, crank26, pin25),
    (c26, crank26, 26.0, k26, coupler26, crank27, pin26),
    (c27, crank27, 27.0, k27, coupler27, crank28, pin27),
    (c28, crank28, 28.0, k28, coupler28, crank29, pin28),
    (c29, crank29, 29.0, k29, coupler29, crank30, pin29),
    (c30, crank30, 30.0, k30, coupler30, crank31, pin30),
    (c31, crank31, 31.0, k31, coupler31, crank32, pin31),
    (c32, crank32, 32.0, k32, coupler32, crank33, pin32),
    (c33, crank33, 33.0, k33, coupler33, crank34, pin33),
    (c34, crank34, 34.0, k34, coupler34, crank35, pin34),
    (c35, crank35, 35.0, k35, coupler35, crank36, pin35),
    (c36, crank36, 36.0, k36, coupler36, crank37, pin36),
    (c37, crank37, 37.0, k37, coupler37, crank38, pin37),
    (c38, crank38, 38.0, k38, coupler38, crank39, pin38),
    (c39, crank39, 39.0, k39, coupler39, crank40, pin39),
    last(c40, crank40, 40.0)
}

/// Loops, coordinates (`c_i`, `k_i` interleaved, `c_40` last), constraints, state size.
pub const LOOPS: usize = 40;
pub const N: usize = 2 * LOOPS + 1;
pub const M: usize = 2 * LOOPS;
pub const D: usize = 2 * N;

impl FourBarAssembly {
    /// The benchmark's links: `m = 1 kg`, `l = 1 m`, `g = 9.81 m/s^2`.
    pub fn benchmark() -> Self {
        FourBarAssembly {
            m: 1.0,
            l: 1.0,
            g: 9.81,
        }
    }

    /// The benchmark's start: cranks vertical (`c_i = pi/2`), couplers horizontal
    /// (`k_i = -pi/2`), `B0' = (v0, 0)`: every crank at `c_i' = -v0 / l`, every coupler
    /// translating (`k_i' = v0 / l`).
    pub fn benchmark_state(&self, v0: f64) -> mbd::Vector<D> {
        let w = v0 / self.l;
        mbd::Vector::<D>::from_fn(|i, _| {
            let (coord, rate) = (i % N, i >= N);
            let crank = coord % 2 == 0;
            match (crank, rate) {
                (true, false) => std::f64::consts::FRAC_PI_2,
                (false, false) => -std::f64::consts::FRAC_PI_2,
                (true, true) => -w,
                (false, true) => w,
            }
        })
    }

    /// Crank 0's tip `B0 = l (cos c_0, sin c_0)`.
    pub fn tip(&self, y: &mbd::Vector<D>) -> [f64; 2] {
        [self.l * y[0].cos(), self.l * y[0].sin()]
    }

    /// `max_i |c_i - c_0|` and `max_i |c_i' - c_0'|`: how far the assembly is from a
    /// parallelogram (zero on the physical motion).
    pub fn spread(&self, y: &mbd::Vector<D>) -> (f64, f64) {
        (0..=LOOPS).fold((0.0f64, 0.0f64), |(a, b), i| {
            (
                a.max((y[2 * i] - y[0]).abs()),
                b.max((y[N + 2 * i] - y[N]).abs()),
            )
        })
    }
}

/// The one-coordinate reduction of the module docs:
/// `(41/3 + 40) m l^2 th'' = -(41/2 + 40) m g l cos th`, the crank angle `th`.
#[derive(Debug, Clone, Copy)]
pub struct Reduced {
    /// `(41/3 + 40) m l^2`.
    pub inertia: f64,
    /// `(41/2 + 40) m g l`.
    pub moment: f64,
}

impl Reduced {
    pub fn of(a: &FourBarAssembly) -> Self {
        let n = LOOPS as f64;
        Reduced {
            inertia: ((n + 1.0) / 3.0 + n) * a.m * a.l * a.l,
            moment: ((n + 1.0) / 2.0 + n) * a.m * a.g * a.l,
        }
    }
}

impl Reduced {
    /// Crank 0's angle and rate at `t` from `th(0) = pi/2`, `th'(0) = w0 != 0`, by quadrature
    /// instead of integration (the reference for tolerances where DOPRI5's own error on the
    /// reduction, about 1e-9 after the first slow turn over the top at 1e-13, would show).
    /// Energy gives the rate as a function of the angle `u` turned, `|th'| = w(u) =
    /// sqrt(w0^2 + 4 k sin^2(u/2))` with `k = moment / inertia`, never below `|w0|`: the
    /// assembly turns for ever, and `t(u) = int_0^u dv / w(v)`, a smooth quadrature (5-point
    /// Gauss–Legendre on panels of at most 0.01 rad) inverted by Newton, periodic with one
    /// turn's time.
    pub fn exact(&self, w0: f64, t: f64) -> (f64, f64) {
        let k = self.moment / self.inertia;
        let w = |u: f64| (w0 * w0 + 4.0 * k * (0.5 * u).sin().powi(2)).sqrt();
        let time = |u: f64| gauss_legendre(|v| 1.0 / w(v), u);
        let turn = std::f64::consts::TAU;
        let period = time(turn);
        let turns = (t / period).floor();
        let r = t - turns * period;
        // t(u) is increasing with slope 1/w in [1/w_max, 1/|w0|]: Newton from the
        // proportional guess, kept inside one turn.
        let mut u = turn * r / period;
        for _ in 0..60 {
            let du = (r - time(u)) * w(u);
            u = (u + du).clamp(0.0, turn);
            if du.abs() <= 1e-15 * (1.0 + u) {
                break;
            }
        }
        let s = w0.signum();
        (
            std::f64::consts::FRAC_PI_2 + s * (turns * turn + u),
            s * w(u),
        )
    }
}

/// `int_0^u f` by the 5-point Gauss–Legendre rule on equal panels of at most 0.01.
fn gauss_legendre(f: impl Fn(f64) -> f64, u: f64) -> f64 {
    const X: [f64; 5] = [
        0.0,
        -0.538_469_310_105_683_1,
        0.538_469_310_105_683_1,
        -0.906_179_845_938_664,
        0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.568_888_888_888_888_9,
        0.478_628_670_499_366_5,
        0.478_628_670_499_366_5,
        0.236_926_885_056_189_1,
        0.236_926_885_056_189_1,
    ];
    let panels = (u / 0.01).ceil().max(1.0);
    let half = 0.5 * u / panels;
    (0..panels as usize)
        .map(|p| {
            let mid = (2.0 * p as f64 + 1.0) * half;
            X.iter()
                .zip(W)
                .map(|(x, w)| w * f(mid + half * x))
                .sum::<f64>()
                * half
        })
        .sum()
}

/// `max |B0 - B0_exact|` over `n + 1` equally spaced outputs of `[0, t1]` of a run that
/// recorded them ([`mbd::Record::Times`]) or kept its dense output, against
/// [`Reduced::exact`] (crank 0's tip starting at `v0` along `+x`).
pub fn tip_error_exact(
    a: &FourBarAssembly,
    sol: &mbd::Solution<D>,
    v0: f64,
    t1: f64,
    n: usize,
) -> f64 {
    let reduced = Reduced::of(a);
    (0..=n)
        .map(|k| {
            let t = t1 * k as f64 / n as f64;
            let recorded = sol.t.iter().position(|&s| s == t).map(|k| sol.y[k]);
            match recorded.or_else(|| sol.at(t)) {
                Some(y) => {
                    let p = a.tip(&y);
                    let th = reduced.exact(-v0 / a.l, t).0;
                    (p[0] - a.l * th.cos()).hypot(p[1] - a.l * th.sin())
                }
                None => f64::INFINITY,
            }
        })
        .fold(0.0, f64::max)
}

impl mbd::OdeSystem<2> for Reduced {
    fn rhs(&self, _t: f64, y: &mbd::Vector<2>) -> mbd::Result<mbd::Vector<2>> {
        Ok(mbd::Vector::<2>::new(
            y[1],
            -self.moment * y[0].cos() / self.inertia,
        ))
    }
}

/// The reference motion of crank 0's angle: the reduced equation integrated by DOPRI5 at
/// `rtol = atol = 1e-13`, with dense output (evaluate with [`mbd::Solution::at`]).
pub fn reference(a: &FourBarAssembly, v0: f64, t1: f64) -> mbd::Result<mbd::Solution<2>> {
    let opts = mbd::Options {
        rtol: 1e-13,
        atol: 1e-13,
        ..Default::default()
    };
    let y0 = mbd::Vector::<2>::new(std::f64::consts::FRAC_PI_2, -v0 / a.l);
    mbd::integrate::Integrator::solve(&mbd::Dopri5::new(opts), &Reduced::of(a), 0.0, y0, t1, &[])
}

/// `max |B0 - B0_ref|` over `n + 1` equally spaced outputs of `[0, t1]` (the benchmark
/// measures 400 outputs over 20 s).
pub fn tip_error(
    a: &FourBarAssembly,
    sol: &mbd::Solution<D>,
    reference: &mbd::Solution<2>,
    t1: f64,
    n: usize,
) -> f64 {
    (0..=n)
        .map(|k| {
            let t = t1 * k as f64 / n as f64;
            match (sol.at(t), reference.at(t)) {
                (Some(y), Some(r)) => {
                    let p = a.tip(&y);
                    (p[0] - a.l * r[0].cos()).hypot(p[1] - a.l * r[0].sin())
                }
                _ => f64::INFINITY,
            }
        })
        .fold(0.0, f64::max)
}
