//! mbd: write a mechanism once, as a `#[derive(Mechanism)]` on a struct of parameters, and
//! get its equations of motion, constraint Jacobians and everything the numerics need as
//! specialised straight-line Rust, derived symbolically at compile time.
//!
//! ```
//! use mbd::prelude::*; // the derive, the model traits, the integrators, `Options`, ..
//!
//! /// A ball thrown straight up at `v0`; the event is its passing 15 m on the way down.
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[coords(y)]
//! #[particle(ball, mass = m, at = [0.0, y])]
//! #[init(y = 0.0, der(y) = v0)]
//! #[event(at_15m = y - 15.0, falling, terminal)]
//! pub struct Throw { pub m: f64, pub g: f64, pub v0: f64 }
//!
//! let ball = Throw { m: 1.0, g: 9.807, v0: 25.0 };
//! let opts = Options { rtol: 1e-12, atol: 1e-12, ..Options::default() };
//! let events = ball.events();
//! let sol = Dopri5::new(opts).solve(&ball, 0.0, ball.initial_state(), 10.0, &events)?;
//! let t = sol.events[0].t;
//! let exact = 25.0 / 9.807 + (2.0 * (25.0f64.powi(2) / (2.0 * 9.807) - 15.0) / 9.807).sqrt();
//! assert!((t - exact).abs() < 1e-10 * exact);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # The mechanism language
//!
//! Every attribute below, with its units, frames, signs and defaults, appears in a checked
//! example in [`language`], which also lists the functions and constants.
//!
//! The struct's fields are the parameters (`f64`; `#[default(value)]` on a field gives a
//! default). Attributes on the struct describe the mechanism; every expression is a small,
//! smooth subset of Rust over the parameters, the coordinates and time `t`.
//!
//! | attribute | meaning |
//! |---|---|
//! | `#[gravity(gx, gy)]` / `#[gravity(gx, gy, gz)]` | gravity; 3 components make the mechanism spatial |
//! | `#[mechanism(planar \| spatial, jacobian, geometry, inverse_dynamics, recursive \| mass_matrix, augmented \| minimal)]` | dimension; `jacobian` generates exact `d qdd/dq`, `d qdd/dqd` for implicit methods; `inverse_dynamics` generates a joint tree's `inverse_dynamics(t, q, qd, qdd)` by recursive Newton-Euler (otherwise the trait's `M qdd - f` answers); `geometry` generates `impl Drawable` (`geometry(t, y)`: each body, point, spring and damper as points in ground coordinates, for drawings and animations); a joint tree's accelerations come from the articulated-body recursion (O(n), chosen from 2 tree bodies) or the mass-matrix solve: force either; closed loops: `augmented` keeps every coordinate with the constraints and multipliers, `minimal` demands minimal coordinates (a compile error says why not), default: minimal where the closure has a closed form |
//! | `#[coords(a, b, ..)]` | free generalised coordinates; with constraints that the derive solves in closed form the state is the first-listed ones, in this order, and the others follow from the closure (`X::COORDINATES` names the state); where the closure has no closed form that leaves the first-listed, the loop stays augmented (`minimal` takes any closed form) |
//! | `#[drive(theta = omega * t)]` | a driven coordinate: a known function of time (not in `coords`) |
//! | `#[relaxed(ux, uy)]` | coordinates pinned at zero, kept only so that `reaction(ux)` is the joint's reaction |
//! | `#[constraint(lhs == rhs)]` | a holonomic constraint (loop closure) |
//! | `#[particle(name, mass = m, at = [x, y])]` | a point mass |
//! | `#[rigid(name, mass = m, inertia = i, at = [x, y], angle = phi)]` | a planar rigid body (inertia about its mass centre) |
//! | `#[rigid3(name, mass = m, inertia = diag(a, b, c), at = [x, y, z], rotation = rot_z(psi) * rot_y(phi))]` | a spatial rigid body; angular velocity and acceleration are derived |
//! | `#[body(name, parent = p, joint = revolute(q), at = [x, y], angle = a0, com = [cx, cy], mass = m, inertia = i)]` | a body of a planar joint tree: its frame is its parent's (`ground` by default) moved by the joint at `at` (parent frame); `joint` is `revolute(q)`, `prismatic(s, [ax, ay])` (axis in the parent frame) or `fixed`; the joint brings its coordinate (free, or driven if a `drive` names it); `com` is in the body frame |
//! | `#[body(name, parent = p, joint = spherical(a, b, c), at = [x, y, z], com = [cx, cy, cz], mass = m, inertia = diag(ia, ib, ic))]` | a body of a spatial joint tree (`#[mechanism(spatial)]`): rotation `R = R_parent R_joint`, origin `o_parent + R_parent at`; `joint` is `revolute(q, x \| y \| z)` (about the parent's axis at the joint), `prismatic(s, [ax, ay, az])`, `universal(a, b)` (`rot_x(a) rot_y(b)`), `spherical(a, b, c)` (`rot_z(a) rot_y(b) rot_x(c)`, singular at `b = ±π/2`), `ball(s1, s2, s3)` (modified Rodrigues parameters, no singular orientation: see [Ball joints](crate::language#ball-joints)) or `fixed`; without `inertia` the body is a point mass; no `angle` |
//! | `#[body(.., reaction)]` | frees the joint origin by two relaxed coordinates `name_rx`, `name_ry` (three in space, with `name_rz`), so that `reaction(name_rx)`, ... are the joint's force on the body (ground frame) |
//! | `#[close(pin, a = coupler, at_a = [x, y], b = rocker \| ground, at_b = [x, y])]` | a joint closing a loop of the tree: the two points (in the bodies' frames) coincide; planar, a revolute joint (two constraint equations); spatial, a spherical joint (`[x, y, z]`, three) by default, or `joint = revolute \| universal \| prismatic` with body-fixed `axis_a`, `axis_b` (and `normal_a`, `normal_b`): five, four, five equations (see [Closing joints in space](#closing-joints-in-space)); where the closure has no closed form (a four-bar's three angles) every joint coordinate stays in the state, augmented: start a run from a consistent state with `analysis::assemble` and `analysis::consistent_velocities` (`X::COORDINATES` names the state) |
//! | `#[chain(link, n = 16, joint = revolute, length = l, mass = m, inertia = i)]` | `n` identical links `link_1 ..= link_n` hanging from `at` on `parent` (the ground's origin by default), relative angles `link_q1 ..` (zero: straight down), mass centres at mid-length |
//! | `#[point(name, at = [x, y])]` | a named point, fixed or moving, in ground coordinates |
//! | `#[point(name, on = body, at = [dx, dy])]` | a body-fixed point of any body (free or joint-tree, planar or spatial): `at` is in the body's frame, from its origin (see the offsets rule below); usable wherever a point is after the bodies (spring, damper and force ends, potentials, constraints, outputs), not in a body's or a plain point's `at` |
//! | `#[spring(name, from = a, to = b, k = k, length = l0)]` | a linear spring between points, bodies (their mass centres) or positions; `ground` is not a point: a fixed end is a position `[x, y]` or a `#[point]` |
//! | `#[damper(name, from = a, to = b, c = c)]` | a viscous damper on the rate of change of the distance |
//! | `#[force(name, at = [x, y], value = [fx, fy])]` | a force applied at a point |
//! | `#[torque(name, on = body, value = tau)]` | a torque on a body |
//! | `#[generalized_force(name, along = q, value = f)]` | a generalised force on a coordinate |
//! | `#[potential(expr)]` | a potential energy term (nonlinear springs) |
//! | `#[friction(along = s, mu = mu, normal = reaction(n))]` / `#[friction(along = s, mu_k = a, mu_s = b, normal = ..)]` | Coulomb friction along a free coordinate, exact stick and slip (see [Friction](#friction)); `mu` sets both coefficients, `mu_k`/`mu_s` each; the normal force may be a reaction |
//! | `#[output(name = expr)]` | an output: any expression, with `der(..)`, `position(b)`, `velocity(b)`, `acceleration(b)`, `angle(b)`, `angular_velocity(b)`, `angular_acceleration(b)` (optionally at a body-fixed offset `velocity(b, [dx, dy])`), `reaction(u)`, `norm`, `dot`, `cross`, `v[i]`; a vector-valued output `p = position(b)` becomes its ground-frame components `p_x`, `p_y` (, `p_z`) in `X::OUTPUTS` and the outputs struct |
//! | `#[input(u, ..)]` | parameters that are inputs (forces, torques, drive laws written with them): with `#[mechanism(jacobian)]`, `analysis::state_space` gives `B = d(y')/du` and `D = d(out)/du` exactly; the right-hand side uses the field's value |
//! | `#[event(name = expr, rising \| falling, terminal)]` | a zero crossing of `expr`, located on the dense output |
//! | `#[init(q = value, der(q) = value)]` | initial conditions |
//! | `#[repeat(i in 0..n, attr(..), attr(..), ..)]` | `n` identical cells: the listed attributes stamped once per index, in order (`a..b` or `a..=b`, integer literals); in them `name[expr of i]` is the name with the index appended (`crank[i + 1]` -> `crank1` at `i = 0`), a bare `i` its value (`i * l` -> `0.0 * l`); `v[0]` without `i` stays a component; not nested. The result is exactly the model written out (see the example below) |
//!
//! # Conventions: frames, offsets, signs, defaults
//!
//! - **Units** are the user's: the derive never converts. Use one consistent system (SI).
//! - **Frames.** Positions, `at` of free bodies and points, `force` values, gravity and
//!   every vector output (`position`, `velocity`, `acceleration`, a spatial
//!   `angular_velocity`/`angular_acceleration`) are in the **ground frame**. A tree body's
//!   `at` and `prismatic` axis are in its parent's frame, its `com` and every body-fixed
//!   offset in its own.
//! - **Body-fixed offsets: one rule.** `position(b, [dx, dy])` (and `velocity`,
//!   `acceleration`, `close`'s `at_a`/`at_b`) is the point `[dx, dy]` of body `b`'s *frame*,
//!   measured **from the frame's origin** in the frame's axes. A free `particle`, `rigid` or
//!   `rigid3` has its frame at its `at` (its mass centre), turned by its `angle`/`rotation`;
//!   a tree body (`body`, `chain`) has its frame at its **joint**, so a `chain` link's tip
//!   is `position(link_1, [0.0, -l])` and its mass centre `[0.0, -l / 2.0]` (= `position(link_1)`).
//!   A tree body without `inertia` (a point mass) still has its frame; a free `particle` has
//!   none, and an offset on it is an error. `position(b)` without
//!   offset is the mass centre. A spring or damper between bodies acts between their mass
//!   centres; for another point, fix it to the body with `#[point(hook, on = b, at = [dx, dy])]`
//!   or write `position(b, [dx, dy])` as the end (also a `force`'s `at`). Body queries are
//!   kinematics where they can be: `position` and `angle` also in points, spring and damper
//!   ends, potentials and a `force`'s `at`; `velocity` and `angular_velocity` also in force
//!   values; accelerations and `reaction` only in outputs and events.
//! - **Signs.** Angles and torques are positive counter-clockwise about the plane's normal
//!   `z = x × y` (right-handed); spatial rotations are right-handed (`rot_z(a)` turns `x`
//!   towards `y`), `R` maps body to ground coordinates, and a spatial `torque` value is a
//!   ground-frame vector. A `chain` angle of zero hangs straight down (`-y` of the parent),
//!   and each `link_qk` is relative to the link before. `generalized_force` acts along its
//!   coordinate's positive direction. Multipliers: `M qdd + Phi_q^T lambda = f`, so
//!   `-Phi_q^T lambda` is the constraint force; `reaction(u)` of a relaxed or driven
//!   coordinate is `(M qdd - f + Phi_q^T lambda)_u`, the generalised force that must act
//!   along `u`'s positive direction to keep it on its law (a joint's force on the body, a
//!   drive's effort). A closed loop reduced to minimal coordinates gives the same force as
//!   `u`'s own row of its equations, with no multipliers (they are unique there).
//! - **`#[default(v)]`** on a parameter does not make `Default`: it gives the value the
//!   compile-time checks use. Constants are folded with it (`mass = -m` with
//!   `#[default(1.0)] m` is refused like `mass = -1.0`), and with every parameter defaulted
//!   and every coordinate's `init` given, the constraints are checked at that configuration.
//!   A default must be a finite constant.
//! - **Named constants**: those of `std::f64::consts`, bare (`PI`, `TAU`, `FRAC_PI_2`, ..) or
//!   by path (`std::f64::consts::FRAC_PI_2`). **Functions**: `sin cos tan asin acos atan sinh
//!   cosh tanh exp ln sqrt abs signum atan2 hypot powi powf min max norm dot cross rot_x rot_y
//!   rot_z diag`, and in outputs and events `der reaction` and the body queries; kinematics
//!   must be smooth (no `abs`, `signum`, `min`, `max`).
//! - **Names** are Rust identifiers: Unicode letters are fine (`θ`, `μ`; rustc's
//!   `mixed_script_confusables` lint warns on a lone Greek letter, `#![allow(..)]` it),
//!   keywords are not (`type`, `fn`). Time is `t`; a coordinate's rate is `der(x)` in every
//!   expression and in `init(der(x) = ..)` (`x_dot` only names the state's component); the
//!   fixed frame is `ground` (a `parent`, a `close` end), which no body may be called.
//! - **Generated names are reserved**: `chain(link, n = 3, ..)` makes bodies `link_1 ..
//!   link_3` and coordinates `link_q1 .. link_q3`; `body(b, .., reaction)` makes `b_rx`,
//!   `b_ry` (`b_rz`); the state names velocities `x_dot`. Declaring one of these yourself is
//!   an error; reading them (`init`, outputs) and driving a chain joint
//!   (`#[drive(link_q1 = ..)]`) is what they are for.
//!
//! # What the derive refuses
//!
//! A wrong model is a compile error at the offending tokens, saying what to write instead:
//! unknown names and functions (with hints such as `pi` -> `PI`), coordinates that move no
//! mass, more constraints than coordinates, non-smooth functions in kinematics,
//! planar/spatial mismatches, duplicate and reserved names, repeated or contradicting
//! attributes (two `gravity`, `planar` with `spatial`, `recursive` with `mass_matrix`,
//! `rising` with `falling`), physically impossible constants (a non-positive mass, a
//! negative inertia, stiffness, spring length, damping or friction coefficient, an inertia
//! tensor that is not positive definite, a rotation that is not one, NaN or infinite
//! values), a mass or inertia that depends on time, a load or friction along a driven or
//! relaxed coordinate (friction also along a ball joint's coordinate), a model of more than
//! 512 bodies (the derive's size limit), a default configuration that violates a
//! constraint, and more (see
//! `tests/ui/` and `docs/RELIABILITY.md`). A failed derive still defines the items it would
//! have generated, so only the real errors are reported.
//!
//! At run time, what the derive could not fold is checked: `X::check_parameters()` (every
//! parameter finite; masses, inertias, stiffnesses, lengths, dampings and friction
//! coefficients of their sign; a stiffness, damping or coefficient written as a law in time
//! at the time of each evaluation) is reported by the accelerations as
//! [`Error::InvalidParameter`] naming the parameter or the body; a mass matrix that is not
//! positive definite is [`Error::MassMatrixNotPositiveDefinite`], never solved; an event
//! function that fails or turns NaN ends the integration with [`Error::EventFailed`].
//!
//! ```
//! use mbd::prelude::*;
//!
//! /// A bar hanging from a pivot: its frame is at the joint, so its tip is `[0, -l]`.
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -9.81)]
//! #[body(bar, joint = revolute(q), com = [0.0, -l / 2.0], mass = m, inertia = m * l * l / 12.0)]
//! #[output(tip_y = position(bar, [0.0, -l])[1], com = position(bar))]
//! pub struct Bar { pub m: f64, pub l: f64 }
//!
//! let bar = Bar { m: 1.0, l: 2.0 };
//! assert_eq!(bar.outputs(0.0, &mbd::Vector::<2>::zeros())?.tip_y, -2.0);
//! assert_eq!(Bar::OUTPUTS, ["tip_y", "com_x", "com_y"]); // a vector output: its components
//! let wrong = Bar { m: -1.0, l: 2.0 };
//! let err = wrong.acceleration(0.0, &mbd::Vector::<1>::new(0.1), &mbd::Vector::<1>::zeros());
//! assert_eq!(err.unwrap_err().to_string(), "the mass of `bar` is -1: it must be positive");
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! A spring from a point of a joint-tree body, given in that body's frame (no chain of
//! rotations written by hand):
//!
//! ```
//! use mbd::prelude::*;
//!
//! /// A pendulum held by a zero-length spring from a point `d` down its arm to the
//! /// ground point `(0, -c)`: `m l^2 q'' = -(m g l + k c d) sin q`.
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[body(arm, joint = revolute(q), com = [0.0, -l], mass = m)]
//! #[point(hook, on = arm, at = [0.0, -d])]
//! #[spring(s, from = hook, to = [0.0, -c], k = k)]
//! #[output(bob = position(arm))]
//! pub struct Held { pub m: f64, pub l: f64, pub g: f64, pub d: f64, pub c: f64, pub k: f64 }
//!
//! let p = Held { m: 1.0, l: 2.0, g: 9.81, d: 0.5, c: 1.0, k: 10.0 };
//! let q = 0.3;
//! let qdd = p.acceleration(0.0, &mbd::Vector::<1>::new(q), &mbd::Vector::<1>::zeros())?[0];
//! let want = -(p.m * p.g * p.l + p.k * p.c * p.d) * q.sin() / (p.m * p.l * p.l);
//! assert!((qdd - want).abs() < 1e-14);
//! assert_eq!(Held::OUTPUTS, ["bob_x", "bob_y"]);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! Repeated closed-loop cells: a row of four-bars sharing their cranks, each cell a crank,
//! a coupler on it and the pin closing the coupler on the next crank (here two cells; the
//! 40-loop IFToMM assembly is the same five lines with `0..40`):
//!
//! ```
//! use mbd::prelude::*;
//!
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[repeat(i in 0..2,
//!     body(crank[i], joint = revolute(c[i]), at = [i * l, 0.0], com = [0.5 * l, 0.0],
//!          mass = m, inertia = m * l * l / 12.0),
//!     body(coupler[i], parent = crank[i], joint = revolute(k[i]), at = [l, 0.0],
//!          com = [0.5 * l, 0.0], mass = m, inertia = m * l * l / 12.0),
//!     close(pin[i], a = coupler[i], at_a = [l, 0.0], b = crank[i + 1], at_b = [l, 0.0]))]
//! #[body(crank2, joint = revolute(c2), at = [2.0 * l, 0.0], com = [0.5 * l, 0.0],
//!        mass = m, inertia = m * l * l / 12.0)]
//! pub struct Row { pub m: f64, pub l: f64, pub g: f64 }
//!
//! assert_eq!(Row::GENERATED.constraints, 4); // two pins, two equations each
//! assert!(Row::COORDINATES.contains(&"k1"));
//! ```
//!
//! Big models are welcome (machine-generated potentials of thousands of terms): the derive
//! runs on its own stack, grown as the lowering recurses, so it never overflows rustc's. Its
//! limits, each refused with an error at the tokens that exceed it: at most 2 000 000 tokens
//! in one derive input, and at most 2000 levels of nesting, counting brackets, runs of prefix
//! operators (`- - x`) and closures or generic arguments. rustc itself expands the struct's
//! attributes one nesting level each: a model written out in more than about 120 attributes
//! (a body, output, spring, .. each) stops with rustc's "recursion limit reached while
//! expanding `#[body]`" unless the crate root raises the limit above the attribute count,
//! `#![recursion_limit = "512"]`; `chain` and `repeat` stamp many bodies from one attribute.
//!
//! # Closing joints in space
//!
//! In a spatial tree, `#[close(name, joint = .., a = A, at_a = [..], b = B | ground, at_b = [..], ..)]`
//! closes a loop by one of four joints. `at_a` is a point of `A`'s frame, `at_b` of `B`'s
//! (each measured from its frame's origin, the body's joint; default the origin), and every
//! direction is given in its own body's frame: `axis_a`, `normal_a` in `A`'s, `axis_b`,
//! `normal_b` in `B`'s (the ground's frame for `ground`). Directions are constant vectors
//! (numbers and named constants), of any non-zero length: they are normalised, and a
//! prismatic joint's normal is made normal to its axis. With `p_a`, `p_b` the two points
//! and `u_a = R_a axis_a` (and so on) in the ground frame:
//!
//! | `joint =` | keys | equations | what it keeps |
//! |---|---|---|---|
//! | `spherical` (default) | | 3 | `p_a = p_b` |
//! | `revolute` | `axis_a`, `axis_b` | 5 | `p_a = p_b`; `u_a` parallel to `u_b` (two rows `u_a . n = 0` for two directions `n` of `B` normal to `axis_b`) |
//! | `universal` | `axis_a`, `axis_b` (the cross's two pins) | 4 | `p_a = p_b`; `u_a . u_b = 0` |
//! | `prismatic` | `axis_a`, `axis_b`, `normal_a`, `normal_b` | 5 | `p_a` on the line through `p_b` along `u_b` (two rows); `u_a` parallel to `u_b` and `n_a` to `n_b` (three rows: the rotation locked) |
//!
//! Signs: the revolute joint keeps the axes parallel *or* antiparallel and the prismatic
//! joint the two frames aligned or turned by a half turn about one of its directions: the rows cannot tell a configuration
//! from its flip, so the joint stays on the one it is assembled in (the solver follows it
//! continuously). Its own rotation (revolute), its two angles (universal) or its travel
//! (prismatic) are not coordinates: they follow from the tree's. A planar `close` is a
//! revolute joint about the plane's normal and takes no `joint` but `revolute` and no
//! directions. A row that is identically zero constrains nothing and is dropped: the
//! tree's own joints keep it (a Sarrus linkage's closing hinge, whose axis the legs keep
//! normal to the plate's; a planar four-bar on revolute joints about `z` written in space
//! and closed by a revolute `close`, whose points' `z` and axes' tilt never change: write
//! it planar for speed); a `close` all of whose rows vanish closes no loop and is refused. Redundant rows that are not identically zero (Bricard's
//! linkage: five equations of rank four) are found at run time and the multipliers are the
//! minimum-norm ones.
//!
//! ```
//! use mbd::prelude::*;
//!
//! /// A slider-crank in the `yz` plane built in space: a crank about `x`, a rod on a
//! /// spherical joint, and a slider on the `z` axis joined to the rod's end by a universal
//! /// joint (the rod's `x` pin across the slider's `y` pin).
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial)]
//! #[gravity(0.0, 0.0, -9.81)]
//! #[body(crank, joint = revolute(th, x), com = [0.0, r / 2.0, 0.0], mass = 2.0,
//!        inertia = diag(0.02, 0.001, 0.02))]
//! #[body(rod, parent = crank, joint = spherical(a, b, c), at = [0.0, r, 0.0],
//!        com = [0.0, 0.0, l / 2.0], mass = 3.0, inertia = diag(0.25, 0.25, 0.002))]
//! #[body(slider, joint = prismatic(s, [0.0, 0.0, 1.0]), mass = 1.5)]
//! #[close(cross, joint = universal, a = rod, at_a = [0.0, 0.0, l], axis_a = [1.0, 0.0, 0.0],
//!         b = slider, axis_b = [0.0, 1.0, 0.0])]
//! pub struct SliderCrank { pub r: f64, pub l: f64 }
//!
//! let m = SliderCrank { r: 0.3, l: 1.0 };
//! // Assembled with the crank along y: the rod turns by asin(r / l) about x, from z towards -y,
//! // to reach the slider on the z axis.
//! let c = (m.r / m.l).asin();
//! let q = mbd::Vector::<5>::from([0.0, 0.0, 0.0, c, (m.l * m.l - m.r * m.r).sqrt()]);
//! assert!(Constrained::<5, 4>::phi(&m, 0.0, &q).amax() < 1e-15);
//! // From rest the crank falls: it starts along +y, so gravity turns it towards -z.
//! let qdd = m.acceleration(0.0, &q, &mbd::Vector::<5>::zeros())?;
//! assert!(qdd[0] < 0.0);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # Friction
//!
//! `#[friction(along = s, mu_k = a, mu_s = b, normal = n)]` is a Coulomb contact on the free
//! coordinate `s`, with the generalised normal force `n` (any expression of the state and
//! time, a reaction included, even one that depends on the accelerations) and kinetic and static
//! coefficients `0 <= mu_k <= mu_s` (`mu = c` sets both; literal coefficients with
//! `mu_s < mu_k` are a compile error, parameters a run-time `InvalidInput`). Exactly:
//! - sliding (`s' != 0`), the generalised force along `s` is `-mu_k |n| sign(s')`;
//! - at rest (`s' == 0`, either signed zero), the contact sticks if the force needed to keep
//!   `s'' = 0` (solved with the other accelerations and the multipliers) is below
//!   `mu_s |n|`; otherwise it slides off in the direction of that force, under kinetic
//!   friction (exactly at `mu_s |n|` it slides when `mu_k < mu_s` and sticks when they are
//!   equal). With several contacts at rest, the first consistent combination of stick and
//!   slip is taken, most contacts stuck first. A body at rest with no tangential load has
//!   zero acceleration. Contacts that constraints tie together (blocks joined by a bar)
//!   stick and stop together, and hold while some split of the load between them is within
//!   their bounds (the split reported spreads it evenly relative to them).
//!
//! That is what `acceleration`, `forces` (the friction at rest is the holding force) and
//! `rhs` of the model compute at any state. Integrating `rhs` straight through a stop would
//! put the jump of the friction force inside a step, so a model with friction is also a
//! [`Hybrid`] system: its modes are slip forward, slip backward or stick per contact
//! (`[Slip; F]`), and any integrator's ordinary `solve` integrates it one mode at a time
//! ([`hybrid::solve`] is the same driver with its settings and typed modes),
//! stopping where a sliding velocity reaches zero or a holding force reaches `mu_s |n|`
//! (located on the dense output to adjacent doubles), choosing the next mode there as above,
//! and restarting. While stuck, `s'' = 0` exactly. Stops and breakaways are found where a
//! switching function changes sign between step ends and, inside each step, at samples
//! spaced by the function's own slope and curvature: a body stuck under a load that varies
//! in time has a constant state, so its steps grow, and a breakaway that comes and goes
//! within one step is still found, without `Options::h_max` (a pulse shorter than the
//! sample spacing its approach allows is the limit). A sliding contact's normal force
//! passing through zero (a kink in `mu_k |n|`) is located the same way and the method
//! restarted there, in the same mode. `mbd::friction::contact_forces` gives each contact's
//! friction force and mode at a state. One `friction` per coordinate. Each
//! contact is one-dimensional: two contacts on a body's `x` and `y` (a puck sliding on a
//! table) act separately, a box rather than a disc (a diagonal slide meets `sqrt(2) mu |n|`);
//! isotropic planar friction is not available. Friction on a moving surface (a belt) is
//! written along the body's place on it (`x = v t + s`, friction along `s`). With
//! `#[mechanism(jacobian)]` the exact Jacobian and the linear parts are those of a sliding
//! state; at a contact at rest, where the accelerations have no derivative, they return
//! `InvalidInput { what: "friction at rest", .. }`. The friction
//! of a joint is written on the joint's coordinate: a prismatic joint's slide, or a revolute
//! joint's angle with `mu` a friction radius times the coefficient (a torque `mu r |n|`);
//! with `#[body(.., reaction)]` the normal force can be the joint's force projected across
//! the axis (`reaction(sled_rx) * sin(a) + reaction(sled_ry) * cos(a)`) or along a
//! pendulum's rod, or be the full magnitude of the joint's force,
//! `hypot(reaction(arm_rx), reaction(arm_ry))`. Where a normal force names accelerations or
//! multipliers and they drop out (its derivatives by them vanish), it is explicit. Where
//! they do not (the full magnitude of a revolute joint's reaction, whose tangential part
//! carries the accelerations the friction torque changes), the friction is implicit and is
//! solved with them: sliding, a Newton iteration on the normal forces of the sliding
//! contacts with the derivatives the derive generates (`impl Frictional`: `IMPLICIT`,
//! `normals`), to rounding, or a typed `InvalidInput` where it has no solution (a friction
//! too large for the joint); stuck, the holding torque is solved first and the contact holds
//! while it is within `mu_s |n|` with `n` at that solution. Every integrator runs the modes,
//! generalized-alpha included (as an `Integrator` it integrates `y = [q; qd]` as
//! `qdd = a(t, q, qd)`).
//!
//! ```
//! use mbd::prelude::*;
//!
//! /// A crate launched down a 15 degree incline; `n` normal to it, relaxed, so that
//! /// `reaction(n)` is the normal force.
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[coords(s)]
//! #[relaxed(n)]
//! #[particle(body, mass = m, at = [s * cos(a) + n * sin(a), -s * sin(a) + n * cos(a)])]
//! #[friction(along = s, mu = mu, normal = reaction(n))]
//! #[init(der(s) = v0)]
//! pub struct Incline { pub m: f64, pub g: f64, pub a: f64, pub mu: f64, pub v0: f64 }
//!
//! let c = Incline { m: 50.0, g: 9.81, a: 15f64.to_radians(), mu: 0.4, v0: 7.0 };
//! // At rest it stays: static friction holds the load m g sin a < mu m g cos a.
//! let zero = mbd::Vector::<1>::zeros();
//! assert_eq!(c.acceleration(0.0, &zero, &zero)?[0], 0.0);
//! // Launched, it slides, stops where constant deceleration says, and stays.
//! let opts = Options { rtol: 1e-12, atol: 1e-12, ..Options::default() };
//! let run = Dopri5::new(opts).solve(&c, 0.0, c.initial_state(), 10.0, &[])?;
//! let a = 9.81 * (c.a.sin() - 0.4 * c.a.cos());
//! assert_eq!(run.switches.len(), 1);
//! assert_eq!(run.switches[0].to.get(), Some(&[Slip::Stick]));
//! assert!((run.switches[0].t - 7.0 / -a).abs() < 1e-12);
//! assert_eq!(run.last().1[1], 0.0);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! # What is generated
//!
//! For a model `X` with `N` free coordinates and `M` constraints: `impl Mechanism<N>`
//! (mass matrix, forces, accelerations, energy), `impl OdeSystem<2N>` (the first-order form
//! every integrator advances), and only when the model has them: `impl Constrained<N, M>`
//! (`Phi`, `Phi_q`, `Phi_t`, `gamma`, multipliers) with projection onto the constraint
//! manifolds, the exact Jacobian, `X::outputs()` returning an `XOutputs` struct,
//! `X::events()`, and for friction `impl Frictional` and `impl Hybrid` (the modes, above),
//! the stick test `X::s_sticks` and the sliding view `X::sliding`. `XState` names the state's components.
//! `X::GENERATED` lists the parts that were generated.
//!
//! A joint tree (`body`, `chain`) without constraints, friction or free-standing bodies
//! gets its accelerations from Featherstone's articulated-body algorithm, unrolled at
//! compile time into straight-line code (part `articulated_body`): O(n) in the bodies,
//! against the O(n^3) of forming and factoring the mass matrix. A run of 6 or more
//! identical links at the end of the tree (a `chain`'s) is generated once, as loops over the
//! links (part `rolled_chain`), so the code stays small however long the chain. Spatial
//! trees (`#[mechanism(spatial)]` with `body`) get the same recursion in 6D, unrolled. The
//! mass matrix and forces of a pure tree are generated too (analyses and the exact Jacobian
//! use them), by recursion: composite rigid bodies for `M`, Newton-Euler for `f`.
//!
//! ```
//! use mbd::prelude::*;
//!
//! /// A triple pendulum of uniform bars, released with its first joint at 0.5 rad.
//! #[derive(Debug, Mechanism)]
//! #[gravity(0.0, -g)]
//! #[chain(link, n = 3, joint = revolute, length = l, mass = m, inertia = m * l * l / 12.0)]
//! #[init(link_q1 = 0.5)]
//! pub struct Triple { pub m: f64, pub l: f64, pub g: f64 }
//!
//! let p = Triple { m: 1.0, l: 0.5, g: 9.81 };
//! assert!(Triple::GENERATED.parts.contains(&"articulated_body"));
//! let y = p.initial_state();
//! let sol = Dopri5::new(Options { rtol: 1e-10, atol: 1e-10, ..Options::default() })
//!     .solve(&p, 0.0, y, 2.0, &[])?;
//! let energy = |y: &mbd::Vector<6>| {
//!     p.energy(0.0, &y.fixed_rows::<3>(0).into_owned(), &y.fixed_rows::<3>(3).into_owned())
//! };
//! assert!((energy(sol.y.last().unwrap())? - energy(&y)?).abs() < 1e-8);
//! # Ok::<(), mbd::Error>(())
//! ```
//!
//! In a spatial mechanism the same `body` attribute composes rotation matrices, with
//! revolute joints about a named axis, universal and spherical joints; such a tree is
//! evaluated by the articulated-body recursion in 6D spatial vectors.
//!
//! ```
//! use mbd::prelude::*;
//!
//! /// A bar on a universal joint, a second bar on a hinge about its `x` axis below it.
//! #[derive(Debug, Mechanism)]
//! #[mechanism(spatial)]
//! #[gravity(0.0, 0.0, -g)]
//! #[body(upper, joint = universal(a, b), com = [0.0, 0.0, -l / 2.0], mass = m,
//!        inertia = diag(m * l * l / 12.0, m * l * l / 12.0, 1e-4))]
//! #[body(lower, parent = upper, joint = revolute(c, x), at = [0.0, 0.0, -l],
//!        com = [0.0, 0.0, -l / 2.0], mass = m, inertia = diag(m * l * l / 12.0, m * l * l / 12.0, 1e-4))]
//! #[output(depth = position(lower)[2])]
//! pub struct Cardan { pub m: f64, pub l: f64, pub g: f64 }
//!
//! let p = Cardan { m: 1.0, l: 0.5, g: 9.81 };
//! assert!(Cardan::GENERATED.parts.contains(&"articulated_body"));
//! // Hanging straight down: the lower bar's centre is 1.5 l below the joint, and it stays.
//! let rest = mbd::Vector::<6>::zeros();
//! assert!((p.outputs(0.0, &rest)?.depth + 0.75).abs() < 1e-15);
//! assert_eq!(p.rhs(0.0, &rest)?, rest);
//! # Ok::<(), mbd::Error>(())
//! ```

pub mod language;

pub use mbd_core::*;
pub use mbd_derive::Mechanism;
pub use nalgebra;

/// What a mechanism file needs in scope: the derive, the model traits (their methods:
/// `acceleration`, `outputs`, `rhs`, `phi`, ..), the vector types, the integrators with
/// their `solve` ([`Integrator`]) and [`Options`], the run's [`Solution`], friction's
/// [`Slip`] and the [`Error`]. Analyses are called by path (`mbd::analysis::..`).
pub mod prelude {
    pub use crate::Mechanism;
    pub use mbd_core::ensemble::{self, Member};
    pub use mbd_core::geometry::Drawable;
    pub use mbd_core::integrate::{
        Auto, Dop853, Dopri5, GeneralizedAlpha, Integrator, Radau5, Rk4,
    };
    pub use mbd_core::{
        Constrained, Error, Matrix, Mechanism as MechanismModel, OdeSystem, Options, Slip,
        Solution, Vector,
    };
}

/// Items generated code calls. Not part of the public API.
#[doc(hidden)]
pub mod __private {
    pub use mbd_core::*;
    pub use nalgebra;
}

/// The README's examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
