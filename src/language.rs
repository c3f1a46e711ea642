//! The mechanism language by example: every attribute of the [table](crate#the-mechanism-language)
//! in a model whose numbers are checked against a closed form written beside it.
//! This module holds documentation only.
//!
//! | example | attributes it exercises |
//! |---|---|
//! | [From other tools' words](#from-other-tools-words) | `body` with `inertia`, `generalized_force` as a torsional spring and damper, `torque` on a tree body, `init` in degrees, outputs in degrees and `norm(velocity(..))` |
//! | [Loads on a free body](#loads-on-a-free-body) | `#[default]`, `mechanism(planar, jacobian)`, `coords`, `rigid`, `point` (ground), `spring` (default and given `length`), `damper`, `force` (at a body-fixed point), `torque`, `generalized_force`, `potential`, scalar `output` with `der`, `angle`, `angular_velocity`, `position(b, [..])[i]`, named constants |
//! | [Constraints and multipliers](#constraints-and-multipliers) | `mechanism(augmented)`, `constraint`, `particle`, `init`, `event(rising)` |
//! | [Drives and reactions](#drives-and-reactions) | `drive`, `body` (`revolute`, `prismatic`, `reaction`), `reaction(u)` of a driven and of relaxed coordinates, `mechanism(mass_matrix)` |
//! | [Friction coefficients](#friction-coefficients) | `friction` with `mu_k`, `mu_s` and a normal force expression |
//! | [Trees: recursion or mass matrix](#trees-recursion-or-mass-matrix) | `mechanism(recursive)`, `mechanism(mass_matrix)`, planar `body` with `fixed` joint, a spring between a body's mass centre and a ground `point`, outputs `velocity`, `acceleration`, `angular_acceleration` |
//! | [Spatial bodies](#spatial-bodies) | `gravity` (3 components), `mechanism(spatial)`, `rigid3`, spatial `torque` and `force`, vector `output` (`angular_velocity`), spatial `body` (`spherical`, `prismatic`, `revolute(q, y)`), spatial `close`, `mechanism(augmented)` in space |
//! | [Ball joints](#ball-joints) | spatial `body` with `ball(s1, s2, s3)`, `mbd::chart` for its initial state |
//! | [Free joints](#free-joints) | spatial `body` with `free(x, y, z, s1, s2, s3)` (a floating base), outputs `velocity(b)` |
//!
//! The crate-level examples cover the rest: `gravity`, `coords`, `particle`, `init`,
//! `event(falling, terminal)` (the thrown ball); a planar `body` with a body-fixed offset and
//! a vector output (the bar); `point(.., on = b)` and a spring to it (the held pendulum);
//! `repeat` and planar `close` (the row of four-bars); `relaxed` and `friction` (the crate on
//! an incline); `chain` (the triple pendulum); spatial `body` with `universal` and
//! `revolute(q, x)` joints (the Cardan bar).
//!
//! # Units, frames, signs, origins, defaults
//!
//! The derive never converts units: write every number in one consistent system (SI: m, kg,
//! s, N, N m, rad). Angles are radians. The frame, sign and origin of each quantity:
//!
//! | attribute | frame and origin | sign | default |
//! |---|---|---|---|
//! | `gravity(gx, gy[, gz])` | ground | the acceleration of free fall (`-g` on `y` points down) | none: no gravity |
//! | `rigid`/`particle` `at` | ground, the mass centre | | |
//! | `rigid` `angle` | about `z` | counter-clockwise positive | |
//! | `rigid` `inertia` | about the mass centre | `>= 0` | |
//! | `rigid3` `rotation` | `R` maps body to ground coordinates | right-handed | |
//! | `body` `at` | parent's frame, from the parent's joint | | `[0, 0]` (`[0, 0, 0]`) |
//! | `body` `com`, body-fixed offsets | the body's own frame, from its joint | | `com = [0, 0]` |
//! | `body` `prismatic(s, axis)` | `axis` in the parent's frame: the joint moves `at` by `s axis` (not normalised: `s` counts lengths of `axis`) | `s` positive along `axis`; `axis` not zero (a constant one at compile time, one of parameters by `check_parameters` and every evaluation) | |
//! | `body` `revolute(q)` (planar) | the frame's angle is the parent's `+ q + angle` | counter-clockwise | |
//! | `body` `revolute(q, x \| y \| z)` (spatial) | about the parent's axis at the joint, `R = R_parent rot_x(q)` .. | right-handed | |
//! | `body` `free(x, y, z, s1, s2, s3)` (spatial) | the joint origin at `at + (x, y, z)` in the parent's axes; the body turned about it as by `ball(s1, s2, s3)` | right-handed | every coordinate `0`: at `at`, the parent's orientation |
//! | `body` `angle` (planar) | a constant angle added to the frame's | counter-clockwise | `0` |
//! | `body` `parent` | | | `ground` |
//! | `body` `inertia` | about the mass centre, body axes | | none: a point mass |
//! | `point(p, at = ..)` | ground | | |
//! | `point(p, on = b, at = ..)` | `b`'s frame, from its origin | | |
//! | `spring` `k`, `length` | force `k (d - length)` along the line of the ends, pulling them together when stretched | `k >= 0` | `length = 0` |
//! | `damper` `c` | force `c d'` (`d'` the rate of the ends' distance), resisting it | `c >= 0` | |
//! | `force` `at`, `value` | ground frame, a point in ground coordinates | | |
//! | `torque` `value` | planar: a scalar about `z`; spatial: a ground-frame vector | counter-clockwise / right-handed | |
//! | `generalized_force` | along the coordinate | positive increases it | |
//! | `potential` | an energy (J); its force is `-dV/dq` | | |
//! | `reaction(u)` | the generalised force along `u` that keeps `u` on its law; for `body(.., reaction)` the joint's force on the body, ground frame | positive along `u` | |
//! | `init` | | | every coordinate and rate `0`; in the augmented form of a closed loop the rates not given follow from the velocity constraints (the given ones held) |
//! | spring or damper end naming a body | its mass centre (a `point(.., on = b)` for another point) | | |
//! | `event` | a zero of the expression | `rising`: from negative to positive | both directions, not terminal |
//! | `mechanism` | | | planar unless `gravity` has 3 components; articulated-body recursion for a tree of 2 or more bodies or with a `free` joint; `minimal` where the closure has a closed form |
//! | `input(u, ..)` | struct fields used as inputs in loads or drive laws | as written | the field's value in the right-hand side; `B`, `D` need `mechanism(jacobian)` |
//! | `mechanism(inverse_dynamics)` | a joint tree's `inverse_dynamics(t, q, qd, qdd)` by Newton-Euler | the generalised forces that must act besides the model's loads | not generated: `M qdd - f` answers |
//!
//! # Expressions: operators, functions, constants
//!
//! An expression is a number (an integer literal is an `f64`), a parameter, a coordinate,
//! `t`, a named constant, or one of: `-x`, `x + y`, `x - y`, `x * y`, `x / y` (scalars;
//! vectors `[x, y]`/`[x, y, z]` add, subtract and scale; a 3x3 matrix `[[..], [..], [..]]`
//! multiplies matrices and vectors), `v[i]` with a literal index, `(x)`, `x as f64`, and
//! calls, written as functions or as methods (`sin(x)` or `x.sin()`, `powi(x, 2)` or
//! `x.powi(2)`):
//!
//! | functions | arguments |
//! |---|---|
//! | `sin cos tan asin acos atan sinh cosh tanh exp ln sqrt` | one scalar |
//! | `abs signum` | one scalar; not in kinematics (not smooth) |
//! | `atan2(y, x) hypot(x, y) powf(x, y)` | two scalars |
//! | `powi(x, n)` | `n` a constant integer, `abs(n) < 64` |
//! | `min max` | two scalars; not in kinematics |
//! | `norm(v)`, `dot(a, b)`, `cross(a, b)` | vectors (`cross` of 2-vectors is the scalar `a_x b_y - a_y b_x`) |
//! | `rot_x rot_y rot_z` (an angle), `diag(a, b, c)` | 3x3 matrices |
//! | `der(e)` | the time derivative; outputs, events and force values |
//! | `position velocity acceleration angle angular_velocity angular_acceleration` (`(b)` or `(b, [offset])`) | body queries, see [the conventions](crate#conventions-frames-offsets-signs-defaults) for where |
//! | `reaction(u)` | a relaxed or driven coordinate; outputs and events |
//!
//! The named constants are those of `std::f64::consts`: `PI E TAU FRAC_PI_2 FRAC_PI_3
//! FRAC_PI_4 FRAC_PI_6 FRAC_PI_8 FRAC_1_PI FRAC_2_PI FRAC_2_SQRT_PI SQRT_2 FRAC_1_SQRT_2 LN_2
//! LN_10 LOG2_E LOG10_E LOG2_10 LOG10_2`, bare or by path (`std::f64::consts::PI`,
//! `core::f64::consts::PI`, `f64::consts::PI`, `consts::PI`). `^` is refused (it is not a
//! power in Rust) with a hint to `powi`.
//!
//! # From other tools' words
//!
//! What a newcomer reaches for, and how it is written here (an unknown key or name such as
//! `rest_length`, `stiffness`, `m =`, `dth` or `th_dot` is refused with the spelling below):
//!
//! | you want | write |
//! |---|---|
//! | a coordinate's rate `q'`, `qdot`, `dq` | `der(q)` (in the state vector: `q_dot`) |
//! | gravity `g` downwards | a vector: `#[gravity(0.0, -g)]` (`y` up), `#[gravity(0.0, 0.0, -g)]` in space |
//! | a spring's stiffness and rest length | `k = ..`, `length = ..` |
//! | a torsional spring or damper at a joint | a `generalized_force` on its angle, `value = -kt * (q - q0) - ct * der(q)` (or `#[potential(0.5 * kt * q * q)]`); `spring` and `damper` act between two points |
//! | a motor torque on a crank | `#[torque(motor, on = crank, value = tau)]` on a rigid body (`rigid`, or a `body` with `inertia`), or a `generalized_force` along the crank's angle |
//! | a force input for control (`B`, `D` matrices) | `#[input(u)]` with `#[mechanism(jacobian)]`, then `mbd::analysis::linear::state_space` |
//! | degrees | radians everywhere: `#[init(th = 30.0 * PI / 180.0)]`; an output in degrees `th * 180.0 / PI` |
//! | a speed, a point of a body | `norm(velocity(b))`, `position(b, [dx, dy])` |
//! | the kinetic plus potential energy | `model.energy(t, &q, &qd)` at run time |
//! | a run | `Dopri5::new(Options { rtol, atol, ..Options::default() }).solve(&model, t0, model.initial_state(), t1, &events)`; then `sol.at(t)` (dense output), `sol.last()` |
//!
//! A pendulum with a torsional spring `kt` and damper `ct` at its pivot and a motor torque
//! `tau` on its arm (a `body` with `inertia`), released at 30 degrees:
//! `(m l^2 + j) th'' = -m g l sin th - kt th - ct th' + tau`.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[body(arm, joint = revolute(th), com = [0.0, -l], mass = m, inertia = j)]
//! #[generalized_force(pivot, along = th, value = -kt * th - ct * der(th))]
//! #[torque(motor, on = arm, value = tau)]
//! #[init(th = 30.0 * PI / 180.0)]
//! #[output(degrees = th * 180.0 / PI, speed = norm(velocity(arm)))]
//! pub struct Sprung { pub m: f64, pub l: f64, pub j: f64, pub g: f64, pub kt: f64, pub ct: f64, pub tau: f64 }
//!
//! let p = Sprung { m: 1.0, l: 0.5, j: 0.01, g: 9.81, kt: 2.0, ct: 0.3, tau: 0.4 };
//! let y = p.initial_state();
//! assert!((y[0] - std::f64::consts::FRAC_PI_6).abs() < 1e-15 && y[1] == 0.0);
//! let (th, thd) = (0.5_f64, 1.5);
//! let acc = p.acceleration(0.0, &Vector::<1>::new(th), &Vector::<1>::new(thd))?[0];
//! let want = (-p.m * p.g * p.l * th.sin() - p.kt * th - p.ct * thd + p.tau)
//!     / (p.m * p.l * p.l + p.j);
//! assert!((acc - want).abs() < 1e-13);
//! let out = p.outputs(0.0, &Vector::<2>::new(th, thd))?;
//! assert!((out.degrees - th.to_degrees()).abs() < 1e-12);
//! assert!((out.speed - p.l * thd).abs() < 1e-14);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Loads on a free body
//!
//! A rigid block on coordinates `x` (along the ground `x` axis) and `th` (its angle), with
//! every planar load at once. At a state `(x, th, x', th')`, with the spring from the wall
//! point `(-1, 0)` of rest length 1 and a force `[f, 0]` (ground frame) at the body-fixed
//! point `[0, h]`, which is at `(x - h sin th, h cos th)` in ground coordinates:
//!
//! - `m x'' = -k x - (c + b) x' + f`
//! - `j th'' = tau - f h cos th - kt (th - pi/4)` (torque and potential, and the force's
//!   moment `dp/dth . F`)
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(planar, jacobian)]
//! #[coords(x, th)]
//! #[rigid(block, mass = m, inertia = j, at = [x, 0.0], angle = th)]
//! #[point(wall, at = [-1.0, 0.0])]
//! #[spring(s, from = wall, to = block, k = k, length = 1.0)]
//! #[damper(d, from = wall, to = block, c = c)]
//! #[force(push, at = position(block, [0.0, h]), value = [f, 0.0])]
//! #[torque(motor, on = block, value = tau)]
//! #[generalized_force(drag, along = x, value = -b * der(x))]
//! #[potential(0.5 * kt * (th - std::f64::consts::FRAC_PI_4).powi(2))]
//! #[output(turn = angle(block), spin = angular_velocity(block), rate = der(x),
//!          push_x = position(block, [0.0, h])[0])]
//! pub struct Block {
//!     #[default(2.0)]
//!     pub m: f64,
//!     pub j: f64, pub k: f64, pub c: f64, pub b: f64,
//!     pub f: f64, pub h: f64, pub tau: f64, pub kt: f64,
//! }
//!
//! let p = Block { m: 2.0, j: 0.3, k: 50.0, c: 1.5, b: 0.5, f: 3.0, h: 0.2, tau: 0.7, kt: 4.0 };
//! let (x, th, xd, thd) = (0.1, 0.4, -0.3, 2.0);
//! let q = mbd::Vector::<2>::new(x, th);
//! let qd = mbd::Vector::<2>::new(xd, thd);
//! let a = p.acceleration(0.0, &q, &qd)?;
//! let xdd = (-p.k * x - (p.c + p.b) * xd + p.f) / p.m;
//! let thdd = (p.tau - p.f * p.h * th.cos() - p.kt * (th - PI / 4.0)) / p.j;
//! assert!((a[0] - xdd).abs() < 1e-13 && (a[1] - thdd).abs() < 1e-13);
//! // `jacobian` generates the exact d(rhs)/dy: here d x''/dx = -k/m, d x''/dx' = -(c+b)/m.
//! let y = mbd::Vector::<4>::new(x, th, xd, thd);
//! let jac = p.jacobian(0.0, &y)?;
//! assert!((jac[(2, 0)] + p.k / p.m).abs() < 1e-13);
//! assert!((jac[(2, 2)] + (p.c + p.b) / p.m).abs() < 1e-13);
//! let out = p.outputs(0.0, &y)?;
//! assert_eq!((out.turn, out.spin, out.rate), (th, thd, xd));
//! assert!((out.push_x - (x - p.h * th.sin())).abs() < 1e-15);
//! # use std::f64::consts::PI;
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Constraints and multipliers
//!
//! A pendulum in Cartesian coordinates, kept on its circle by a constraint. `augmented`
//! keeps both coordinates and the multiplier `lambda` of `M q'' + Phi_q^T lambda = f`. With
//! `Phi = x^2 + y^2 - l^2`, at the bottom `(0, -l)` moving at `v`: `y'' = v^2 / l` and the rod
//! tension `T = m (g + v^2 / l)` is `-Phi_q^T lambda = [0, 2 l lambda]`, so
//! `lambda = T / (2 l)`. Released from the horizontal at rest, the bob first rises through
//! `y = -l / 2` (a `rising` event on `-y - l / 2`) when `sin(angle swept) = 1/2`; energy
//! gives the speed there, `v^2 = g l`.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(planar, augmented)]
//! #[gravity(0.0, -g)]
//! #[coords(x, y)]
//! #[particle(bob, mass = m, at = [x, y])]
//! #[constraint(x * x + y * y == l * l)]
//! #[init(x = l, y = 0.0)]
//! #[event(half_way = -y - l / 2.0, rising)]
//! pub struct Cartesian { pub m: f64, pub l: f64, pub g: f64 }
//!
//! let p = Cartesian { m: 0.5, l: 2.0, g: 9.81 };
//! let v = 3.0;
//! let q = mbd::Vector::<2>::new(0.0, -p.l);
//! let qd = mbd::Vector::<2>::new(v, 0.0);
//! let (qdd, lambda) = p.acceleration_and_multipliers(0.0, &q, &qd)?;
//! assert!(qdd[0].abs() < 1e-14 && (qdd[1] - v * v / p.l).abs() < 1e-13);
//! let tension = p.m * (p.g + v * v / p.l);
//! assert!((lambda[0] - tension / (2.0 * p.l)).abs() < 1e-13);
//!
//! let opts = Options { rtol: 1e-11, atol: 1e-11, ..Options::default() };
//! let events = p.events();
//! let sol = Dopri5::new(opts).solve(&p, 0.0, p.initial_state(), 5.0, &events)?;
//! let hit = &sol.events[0];
//! let speed2 = hit.y[2].powi(2) + hit.y[3].powi(2);
//! assert!((speed2 - p.g * p.l).abs() < 1e-7);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Drives and reactions
//!
//! A bead on a rod turned at a constant rate `w` in a vertical plane: the rod's angle is
//! driven, `th = w t`, the bead slides along it on a prismatic joint (axis `[1, 0]` in the
//! rod's frame). Along the rod, `s'' = w^2 s - g sin(w t)`, so from `s(0) = s0` at rest
//! `s = s0 cosh(w t) - g / (2 w^2) (sinh(w t) - sin(w t))`. `reaction(th)` is the torque the
//! drive must give, `d/dt (J w) + gravity's moment = 2 m s s' w + g cos(w t) (ma r + m s)`
//! (the rod: mass `ma` at `r`, inertia `ia` constant). The bead's `reaction` coordinates
//! give the rod's force on it, normal to the rod: `N = m (2 s' w + g cos th)` along
//! `(-sin th, cos th)`.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(planar, mass_matrix)]
//! #[gravity(0.0, -g)]
//! #[drive(th = w * t)]
//! #[body(rod, joint = revolute(th), com = [r, 0.0], mass = ma, inertia = ia)]
//! #[body(bead, parent = rod, joint = prismatic(s, [1.0, 0.0]), mass = m, reaction)]
//! #[init(s = s0)]
//! #[output(motor = reaction(th), nx = reaction(bead_rx), ny = reaction(bead_ry))]
//! pub struct Bead { pub m: f64, pub ma: f64, pub ia: f64, pub r: f64, pub w: f64, pub g: f64, pub s0: f64 }
//!
//! let p = Bead { m: 0.2, ma: 1.0, ia: 0.1, r: 0.5, w: 3.0, g: 9.81, s0: 0.3 };
//! let opts = Options { rtol: 1e-12, atol: 1e-12, ..Options::default() };
//! let sol = Dopri5::new(opts).solve(&p, 0.0, p.initial_state(), 0.5, &[])?;
//! let (t, y) = (0.5, *sol.y.last().unwrap());
//! let wt = p.w * t;
//! let a = p.g / (2.0 * p.w * p.w);
//! let s = p.s0 * wt.cosh() - a * (wt.sinh() - wt.sin());
//! let sd = p.w * (p.s0 * wt.sinh() - a * (wt.cosh() - wt.cos()));
//! assert!((y[0] - s).abs() < 1e-9 && (y[1] - sd).abs() < 1e-8);
//!
//! let out = p.outputs(t, &y)?;
//! let motor = 2.0 * p.m * y[0] * y[1] * p.w + p.g * wt.cos() * (p.ma * p.r + p.m * y[0]);
//! assert!((out.motor - motor).abs() < 1e-12);
//! let n = p.m * (2.0 * y[1] * p.w + p.g * wt.cos());
//! assert!((out.nx + n * wt.sin()).abs() < 1e-12 && (out.ny - n * wt.cos()).abs() < 1e-12);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Friction coefficients
//!
//! A block pushed along a floor by a constant generalised force `p`, with kinetic and static
//! coefficients `mu_k < mu_s` and the normal force `m g` (the full rules are in
//! [Friction](crate#friction)): at rest it holds while `p <= mu_s m g`; sliding forward,
//! `m x'' = p - mu_k m g`, whatever `p`.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[coords(x)]
//! #[particle(block, mass = m, at = [x, 0.0])]
//! #[generalized_force(push, along = x, value = p)]
//! #[friction(along = x, mu_k = mk, mu_s = ms, normal = m * g)]
//! pub struct Pushed { pub m: f64, pub g: f64, pub p: f64, pub mk: f64, pub ms: f64 }
//!
//! let (x, rest, moving) = (
//!     mbd::Vector::<1>::zeros(),
//!     mbd::Vector::<1>::zeros(),
//!     mbd::Vector::<1>::new(0.5),
//! );
//! // 4.5 N: below static friction, 0.3 * 2 kg * 9.81 = 5.886 N, above kinetic, 3.924 N.
//! let held = Pushed { m: 2.0, g: 9.81, p: 4.5, mk: 0.2, ms: 0.3 };
//! assert_eq!(held.acceleration(0.0, &x, &rest)?[0], 0.0);
//! let sliding = held.acceleration(0.0, &x, &moving)?[0];
//! assert!((sliding - (4.5 - 0.2 * 2.0 * 9.81) / 2.0).abs() < 1e-14);
//! // 6 N breaks away from rest and slides under kinetic friction.
//! let breaks = Pushed { p: 6.0, ..held };
//! assert!((breaks.acceleration(0.0, &x, &rest)?[0] - (6.0 - 0.2 * 2.0 * 9.81) / 2.0).abs() < 1e-14);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Trees: recursion or mass matrix
//!
//! A bar (mass `m` at `l`, inertia `ia` about its centre) swinging from the ground's origin,
//! with a weight `m2` welded (`fixed`) at `[0, -2 l]` of its frame and a zero-length spring
//! `k` from the weight to the ground point `(0, -3 l)`. The spring's energy is
//! `k l^2 (13 - 12 cos q) / 2`, so
//! `(ia + m l^2 + 4 m2 l^2) q'' = -(g (m + 2 m2) l + 6 k l^2) sin q`. The weight's velocity
//! is `2 l q' (cos q, sin q)` and its acceleration `2 l q'' (cos q, sin q) + 2 l q'^2 (-sin q,
//! cos q)`. `recursive` (articulated bodies) and `mass_matrix` give the same accelerations.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(planar, recursive)]
//! #[gravity(0.0, -g)]
//! #[body(bar, joint = revolute(q), com = [0.0, -l], mass = m, inertia = ia)]
//! #[body(weight, parent = bar, joint = fixed, at = [0.0, -2.0 * l], mass = m2)]
//! #[point(anchor, at = [0.0, -3.0 * l])]
//! #[spring(s, from = weight, to = anchor, k = k)]
//! #[output(v = velocity(weight), a = acceleration(weight), alpha = angular_acceleration(bar))]
//! pub struct Welded { pub m: f64, pub m2: f64, pub ia: f64, pub l: f64, pub g: f64, pub k: f64 }
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(planar, mass_matrix)]
//! #[gravity(0.0, -g)]
//! #[body(bar, joint = revolute(q), com = [0.0, -l], mass = m, inertia = ia)]
//! #[body(weight, parent = bar, joint = fixed, at = [0.0, -2.0 * l], mass = m2)]
//! #[point(anchor, at = [0.0, -3.0 * l])]
//! #[spring(s, from = weight, to = anchor, k = k)]
//! pub struct WeldedByMatrix { pub m: f64, pub m2: f64, pub ia: f64, pub l: f64, pub g: f64, pub k: f64 }
//!
//! let p = Welded { m: 1.0, m2: 0.5, ia: 0.2, l: 0.4, g: 9.81, k: 30.0 };
//! let (q, qd): (f64, f64) = (0.7, -1.2);
//! let (l, s, c) = (p.l, q.sin(), q.cos());
//! let want = -(p.g * (p.m + 2.0 * p.m2) * l + 6.0 * p.k * l * l) * s
//!     / (p.ia + p.m * l * l + 4.0 * p.m2 * l * l);
//! let qv = mbd::Vector::<1>::new(q);
//! let qdv = mbd::Vector::<1>::new(qd);
//! let qdd = p.acceleration(0.0, &qv, &qdv)?[0];
//! assert!((qdd - want).abs() < 1e-13);
//! let by_matrix = WeldedByMatrix { m: 1.0, m2: 0.5, ia: 0.2, l: 0.4, g: 9.81, k: 30.0 };
//! assert!((by_matrix.acceleration(0.0, &qv, &qdv)?[0] - want).abs() < 1e-13);
//! assert!(Welded::GENERATED.parts.contains(&"articulated_body"));
//! assert!(!WeldedByMatrix::GENERATED.parts.contains(&"articulated_body"));
//!
//! let out = p.outputs(0.0, &mbd::Vector::<2>::new(q, qd))?;
//! let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
//! assert!(close(out.v_x, 2.0 * l * qd * c) && close(out.v_y, 2.0 * l * qd * s));
//! assert!(close(out.a_x, 2.0 * l * (qdd * c - qd * qd * s)));
//! assert!(close(out.a_y, 2.0 * l * (qdd * s + qd * qd * c)));
//! assert!(close(out.alpha, qdd));
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Spatial bodies
//!
//! A wheel turning about the ground `z` axis (`rotation = rot_z(psi)`, right-handed), driven
//! by a ground-frame torque `[0, 0, tau]` and a force `[0, fy, 0]` at its body-fixed rim
//! point `[r, 0, 0]`, which is at `r (cos psi, sin psi, 0)`: `c psi'' = tau + r fy cos psi`.
//! `angular_velocity` is a ground-frame vector, its components the outputs `w_x`, `w_y`, `w_z`.
//!
//! A spatial `close` is a spherical joint by default: three equations, the difference of the
//! two points (`joint = revolute | universal | prismatic` with body-fixed axes adds the axis
//! rows: see the crate docs, *Closing joints in space*). Two bars on spherical joints 1 m apart, their tips tied: hanging straight, the
//! tips are 1 m apart, so `|Phi| = 1`. `augmented` keeps all six joint angles and the three
//! equations; by default (`minimal`) this loop is solved in closed form and the state keeps
//! three angles.
//!
//! A trolley on a spatial `prismatic` joint along `x` with a pendulum on `revolute(q, y)`:
//! `rot_y(q)` takes the bob's `[0, 0, -l]` to `(-l sin q, 0, -l cos q)`, so a positive `q`
//! swings it towards `-x`. At rest, with `mu = m / (mc + m)`:
//! `q'' = -g sin q / (l (1 - mu cos^2 q))` and `x'' = mu l cos q q''`.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial)]
//! #[gravity(0.0, 0.0, -9.81)]
//! #[coords(psi)]
//! #[rigid3(wheel, mass = m, inertia = diag(a, a, c), at = [0.0, 0.0, 0.0], rotation = rot_z(psi))]
//! #[torque(motor, on = wheel, value = [0.0, 0.0, tau])]
//! #[force(tug, at = position(wheel, [r, 0.0, 0.0]), value = [0.0, fy, 0.0])]
//! #[output(w = angular_velocity(wheel))]
//! pub struct Wheel { pub m: f64, pub a: f64, pub c: f64, pub tau: f64, pub r: f64, pub fy: f64 }
//!
//! let p = Wheel { m: 3.0, a: 0.2, c: 0.4, tau: 0.5, r: 0.3, fy: 2.0 };
//! let (psi, psid) = (0.6, 1.5);
//! let acc = p.acceleration(0.0, &mbd::Vector::<1>::new(psi), &mbd::Vector::<1>::new(psid))?;
//! assert!((acc[0] - (p.tau + p.r * p.fy * psi.cos()) / p.c).abs() < 1e-14);
//! let out = p.outputs(0.0, &mbd::Vector::<2>::new(psi, psid))?;
//! assert!(out.w_x.abs() < 1e-15 && out.w_y.abs() < 1e-15 && (out.w_z - psid).abs() < 1e-15);
//! assert_eq!(Wheel::OUTPUTS, ["w_x", "w_y", "w_z"]);
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial, augmented)]
//! #[gravity(0.0, 0.0, -g)]
//! #[body(left, joint = spherical(a1, b1, c1), com = [0.0, 0.0, -l / 2.0], mass = m,
//!        inertia = diag(m * l * l / 12.0, m * l * l / 12.0, 1e-4))]
//! #[body(right, joint = spherical(a2, b2, c2), at = [1.0, 0.0, 0.0], com = [0.0, 0.0, -l / 2.0],
//!        mass = m, inertia = diag(m * l * l / 12.0, m * l * l / 12.0, 1e-4))]
//! #[close(tie, a = left, at_a = [0.0, 0.0, -l], b = right, at_b = [0.0, 0.0, -l])]
//! pub struct Tied { pub m: f64, pub l: f64, pub g: f64 }
//!
//! let tied = Tied { m: 1.0, l: 0.8, g: 9.81 };
//! assert_eq!(Tied::GENERATED.constraints, 3);
//! let phi = Constrained::<6, 3>::phi(&tied, 0.0, &mbd::Vector::<6>::zeros());
//! assert!((phi.norm() - 1.0).abs() < 1e-15);
//! assert_eq!(Tied::COORDINATES.len(), 6);
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial)]
//! #[gravity(0.0, 0.0, -g)]
//! #[body(cart, joint = prismatic(x, [1.0, 0.0, 0.0]), mass = mc)]
//! #[body(bob, parent = cart, joint = revolute(q, y), com = [0.0, 0.0, -l], mass = m)]
//! pub struct Trolley { pub mc: f64, pub m: f64, pub l: f64, pub g: f64 }
//!
//! let cp = Trolley { mc: 2.0, m: 0.5, l: 0.7, g: 9.81 };
//! let (x, q): (f64, f64) = (0.3, 0.4);
//! let acc = cp.acceleration(0.0, &mbd::Vector::<2>::new(x, q), &mbd::Vector::<2>::zeros())?;
//! let share = cp.m / (cp.mc + cp.m);
//! let qdd = -cp.g * q.sin() / (cp.l * (1.0 - share * q.cos().powi(2)));
//! assert!((acc[1] - qdd).abs() < 1e-13);
//! assert!((acc[0] - share * cp.l * q.cos() * qdd).abs() < 1e-13);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Ball joints
//!
//! `joint = ball(s1, s2, s3)` is a spherical joint without a singular orientation. Its
//! coordinates are the *modified Rodrigues parameters* of the joint's rotation: turned by
//! `phi` about the unit axis `n` (in the parent's frame, as the rotation of the child's
//! axes), `sigma = (s1, s2, s3) = tan(phi / 4) n`; zero is the joint's rest orientation, and
//! for small turns `sigma` is a quarter of the rotation vector. Their rates are
//! `sigma' = B w / 4`, `B = (1 - |sigma|^2) 1 + 2 [sigma]x + 2 sigma sigma^T`, with `w` the
//! child's angular velocity relative to the parent in the child's axes; `B` is invertible
//! at every finite `sigma`, so no orientation makes the mass matrix singular, whereas
//! `spherical(a, b, c)` (`rot_z(a) rot_y(b) rot_x(c)`) cannot move through `b = ±π/2` (its
//! mass matrix is singular there, and DOPRI5 crawls near it). The parameters grow without
//! bound towards a full turn; the *shadow set* `-sigma / |sigma|^2` is the same
//! orientation, and the generated model switches to it whenever `|sigma| > 1` (`phi > π`)
//! after each accepted step (`OdeSystem::project`; the rates are mapped too), so a
//! spinning body's coordinates jump once per turn while its orientation, angular velocity,
//! energy and every output that depends on them move smoothly. Read orientation from
//! outputs, not from `s1`, `s2`, `s3`; events on those coordinates would see the jumps. A
//! ball coordinate cannot be driven (a spanned error): its three coordinates are one
//! rotation. `spherical` keeps its meaning (Euler angles are what one drives and reads);
//! choose `ball` for free rotation.
//!
//! [`mbd::chart`](crate::chart) turns a known orientation and angular velocity into the
//! joint's state: `parameters(R)` (the set with `|sigma| <= 1`) and `rates(sigma, w)`,
//! `rotation(sigma)` back. Below, a rigid pendulum swings in a steady cone at `alpha`
//! from the downward vertical, turning at `Omega` about the vertical: with `A = a + m l^2`
//! about the joint and `c` about its own axis, `Omega^2 = m g l / ((A - c) cos alpha)`
//! (`g / (l cos alpha)` for a point mass), and its mass centre goes round a horizontal
//! circle.
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial)]
//! #[gravity(0.0, 0.0, -g)]
//! #[body(bob, joint = ball(s1, s2, s3), com = [0.0, 0.0, -l], mass = m, inertia = diag(a, a, c))]
//! #[output(centre = position(bob))]
//! pub struct Cone { pub m: f64, pub l: f64, pub a: f64, pub c: f64, pub g: f64 }
//!
//! let p = Cone { m: 1.5, l: 0.8, a: 0.02, c: 0.01, g: 9.81 };
//! let alpha: f64 = 0.5;
//! let big_a = p.a + p.m * p.l * p.l;
//! let omega = (p.m * p.g * p.l / ((big_a - p.c) * alpha.cos())).sqrt();
//! // Tilted by alpha about x, turning at omega about the vertical (in the body's axes: R^T w).
//! let rot = Matrix::<3, 3>::new(1.0, 0.0, 0.0, 0.0, alpha.cos(), -alpha.sin(), 0.0, alpha.sin(), alpha.cos());
//! let sigma = mbd::chart::parameters(&rot);
//! let rate = mbd::chart::rates(&sigma, &(rot.transpose() * Vector::<3>::new(0.0, 0.0, omega)));
//! let y0 = Vector::<6>::new(sigma[0], sigma[1], sigma[2], rate[0], rate[1], rate[2]);
//! let period = 2.0 * std::f64::consts::PI / omega;
//! let opts = Options { rtol: 1e-11, atol: 1e-11, ..Default::default() };
//! let sol = Dopri5::new(opts).solve(&p, 0.0, y0, period, &[])?;
//! for k in 1..=4 {
//!     let t = period * k as f64 / 4.0;
//!     let o = p.outputs(t, &sol.at(t).unwrap())?;
//!     let turn = omega * t;
//!     let want = [p.l * alpha.sin() * -turn.sin(), p.l * alpha.sin() * turn.cos(), -p.l * alpha.cos()];
//!     assert!((o.centre_x - want[0]).abs() < 1e-8 && (o.centre_y - want[1]).abs() < 1e-8);
//!     assert!((o.centre_z - want[2]).abs() < 1e-8);
//! }
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Free joints
//!
//! `joint = free(x, y, z, s1, s2, s3)` gives a body six degrees of freedom relative to its
//! parent: a floating base (a humanoid, a satellite with appendages) at the root of a
//! spatial tree, or a body flying relative to a moving one. `(x, y, z)` moves the joint
//! origin (`at`, default the parent's origin) along the parent's axes; `(s1, s2, s3)` turn
//! the body about it exactly as a `ball` joint does (modified Rodrigues parameters, the
//! shadow switch past a half turn, `mbd::chart` for the initial state). The state is
//! `[x, y, z, s1, s2, s3, ..; their rates, ..]`: `x'` is the origin's velocity in the
//! parent's axes, not the body's. The rotation's coordinates cannot be driven (its
//! translation can) and carry no friction. A tree with a free joint gets its accelerations
//! from the articulated-body recursion, even a single free body.
//!
//! Below, a base with a boom on a hinge is thrown, spinning: whatever the two bodies do
//! relative to each other, their common mass centre follows the parabola of its initial
//! position and velocity.
//!
//! ```
//! use mbd::integrate::{Dopri5, Integrator, Options};
//! use mbd::prelude::*;
//! use mbd::Vector;
//!
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial)]
//! #[gravity(0.0, 0.0, -g)]
//! #[body(base, joint = free(x, y, z, s1, s2, s3), com = [0.0, 0.0, 0.1], mass = m,
//!        inertia = diag(0.4, 0.5, 0.3))]
//! #[body(boom, parent = base, joint = revolute(q, y), at = [0.3, 0.0, 0.0],
//!        com = [0.25, 0.0, 0.0], mass = mb, inertia = diag(0.001, 0.02, 0.02))]
//! #[output(cb = position(base), cm = position(boom), vb = velocity(base), vm = velocity(boom))]
//! pub struct Thrown { pub m: f64, pub mb: f64, pub g: f64 }
//!
//! let p = Thrown { m: 4.0, mb: 1.0, g: 9.81 };
//! let sigma = Vector::<3>::new(0.1, -0.2, 0.05);
//! let rate = mbd::chart::rates(&sigma, &Vector::<3>::new(1.0, 0.5, 3.0)); // body axes
//! let y0 = Vector::<14>::from_column_slice(&[
//!     0.0, 0.0, 1.0, sigma[0], sigma[1], sigma[2], 0.3, // x, y, z, s1, s2, s3, q
//!     1.0, 0.0, 5.0, rate[0], rate[1], rate[2], -2.0, // their rates
//! ]);
//! let centre = |o: &ThrownOutputs| {
//!     let [b, m] = [[o.cb_x, o.cb_y, o.cb_z], [o.cm_x, o.cm_y, o.cm_z]];
//!     let [vb, vm] = [[o.vb_x, o.vb_y, o.vb_z], [o.vm_x, o.vm_y, o.vm_z]];
//!     let mass = p.m + p.mb;
//!     let c = |a: [f64; 3], b: [f64; 3]| Vector::<3>::from_fn(|i, _| (p.m * a[i] + p.mb * b[i]) / mass);
//!     (c(b, m), c(vb, vm))
//! };
//! let (c0, v0) = centre(&p.outputs(0.0, &y0)?);
//! let opts = Options { rtol: 1e-11, atol: 1e-11, ..Default::default() };
//! let sol = Dopri5::new(opts).solve(&p, 0.0, y0, 1.0, &[])?;
//! for (t, y) in sol.t.iter().zip(&sol.y) {
//!     let (c, _) = centre(&p.outputs(*t, y)?);
//!     let want = c0 + v0 * *t - Vector::<3>::new(0.0, 0.0, 0.5 * p.g * t * t);
//!     assert!((c - want).norm() < 1e-9);
//! }
//! # Ok::<(), mbd::Error>(())
//! ```
