//! Stage 3: the lowered model (`lowered.rs`, no `syn`) -> the equations of motion, as
//! symbolic expressions.
//!
//! Everything is first derived in *full* coordinates `z = (free, driven, relaxed)` with
//! symbols for `z`, `zd`, `zdd` and `t`, then *reduced*: a driven coordinate becomes its
//! law `s(t)` (with `s'`, `s''`), a relaxed one becomes 0. Reducing after differentiating
//! keeps every time derivative exact, and the rows of the full equations that belong to
//! driven and relaxed coordinates are exactly their reactions:
//! `r_u = (M zdd - f + Phi_z^T lambda)_u` (Kane's projection form; docs/ARCHITECTURE.md, Mechanics).
//!
//! `derive_with` is the pipeline; each phase is a module and hands the next a typed value:
//! `scope` (names) -> `bodies`, `trees` (`Kinematics`) -> `constraints`, `minimal`
//! (`Constraints`) -> `loads` (`Forces`) -> `inertial` (`Inertial`) -> `reduction`
//! (`Reduced`) -> `constraints` again (`InFree`) -> `outputs`, `coulomb` (`Observed`) ->
//! `implicit`, `initial`, `checks` -> `Equations`.

mod bodies;
mod checks;
mod constraints;
mod coulomb;
mod fixed;
mod implicit;
mod inertial;
mod initial;
mod kinematics;
mod loads;
mod minimal;
mod outputs;
mod reduction;
mod scope;
mod trees;

use crate::closure;
use crate::lower::Binding;
use crate::lowered::{Lowered, Term};
use crate::parse::{self, Errors};
use crate::sym::{Expr, Graph, Sym};
use crate::tree;
use kinematics::Kinematics;
use proc_macro2::Span;
use scope::Scope;
use std::collections::HashMap;
use syn::Ident;

/// What a symbol stands for in generated code.
#[derive(Clone, Debug, PartialEq)]
pub enum Role {
    Time,
    Param(Ident),
    /// Free coordinate `i`: position, velocity, acceleration.
    Q(usize),
    Qd(usize),
    Qdd(usize),
    /// Multiplier of constraint `k`.
    Lambda(usize),
    /// Sliding direction (+1 or -1) of friction `k`: `sign(qd_s)` in the model itself,
    /// a fixed mode in its sliding view, so that no step integrates through `sign(0)`.
    FrictionDirection(usize),
    /// A loop-local value of a rolled joint chain ([`tree::Rolled`]): read as the variable
    /// itself, or (`per_link`) at the link's index of the array of that name.
    RunLocal {
        per_link: bool,
    },
}

#[derive(Clone, Debug)]
pub enum CoordKind {
    Free,
    /// A driven coordinate with its law `s(t)`.
    Driven(Expr),
    Relaxed,
    /// A coordinate the closure fixes in closed form (minimal coordinates): its position,
    /// velocity and acceleration in the independent coordinates.
    Dependent([Expr; 3]),
}

pub struct Coord {
    pub name: Ident,
    pub kind: CoordKind,
    pub z: Expr,
    pub zd: Expr,
    pub zdd: Expr,
    /// Third derivative: only reachable through `der(..)` of an acceleration in outputs.
    pub zddd: Expr,
}

/// Coulomb friction along free coordinate `coord` with the (reduced) normal force `normal`.
pub struct FrictionEq {
    pub coord: usize,
    pub mu: Expr,
    pub mu_static: Expr,
    pub normal: Expr,
    pub span: Span,
    /// An implicit normal force's derivatives by the accelerations and multipliers it names
    /// (`crate::friction`); `None` when it is explicit.
    pub implicit: Option<Vec<(Role, Expr)>>,
}

/// A value of parameters alone whose sign the mechanics needs (a mass, an inertia, a
/// stiffness, ..): checked at run time by the generated `check_parameters` when it did not
/// fold to a constant at compile time (a constant is checked by the `check` stage).
pub struct ParamCheck {
    /// What it is, for the message: "the mass of `bob`".
    pub what: String,
    pub expr: Expr,
    /// `> 0` (else `>= 0`).
    pub positive: bool,
    /// Checked on every acceleration: no solve would notice it (a negative stiffness,
    /// damping or friction coefficient), where a wrong mass or inertia makes the mass matrix
    /// fail its `L D L^T` and is named on that error path only.
    pub eager: bool,
}

pub struct OutputEq {
    pub name: Ident,
    pub expr: Expr,
}

pub struct EventEq {
    pub name: Ident,
    pub expr: Expr,
    pub direction: parse::Direction,
    pub terminal: bool,
}

/// The derived model, ready for code generation.
pub struct Equations {
    pub g: Graph,
    pub roles: HashMap<Sym, Role>,
    /// Names of the free coordinates, in state order.
    pub free: Vec<Ident>,
    pub mass: Vec<Vec<Expr>>,
    pub forces: Vec<Expr>,
    pub energy: Expr,
    pub phi: Vec<Expr>,
    pub phi_q: Vec<Vec<Expr>>,
    pub phi_t: Vec<Expr>,
    pub gamma: Vec<Expr>,
    /// `(dR/dq, dR/dqd, dC/dq, dC/dqd)` of the residuals `R = M qdd + Phi_q^T lambda - f`
    /// and `C = Phi_q qdd - gamma`, when exact Jacobians are asked for.
    pub jacobian: Option<ResidualJacobian>,
    /// Derivatives by the parameters and of the outputs (linear.rs), with `jacobian`.
    pub linear: Option<crate::linear::LinearEq>,
    pub outputs: Vec<OutputEq>,
    /// The drawn shapes (`#[mechanism(geometry)]`), reduced like the outputs.
    pub geometry: Vec<crate::geometry::Shape<Vec<Expr>>>,
    pub events: Vec<EventEq>,
    pub frictions: Vec<FrictionEq>,
    /// The forces without friction, for the stick test (present when there is friction).
    pub frictionless: Option<Vec<Expr>>,
    /// `qdd` of a joint tree by the articulated-body recursion, when that evaluates the
    /// accelerations instead of the mass matrix.
    pub recursive_qdd: Option<Vec<Expr>>,
    /// `(M qdd)_i` over the free coordinates (the `qdd` symbols standing for a column of the
    /// identity): a long tree's mass matrix, formed column by column at run time.
    pub mass_times: Option<Vec<Expr>>,
    /// `(M qdd - f)_i` by recursive Newton-Euler (a pure joint tree): inverse dynamics.
    pub inverse_dynamics: Option<Vec<Expr>>,
    /// `qdd` of a one-coordinate model without constraints, `f / m` with shared factors
    /// cancelled.
    pub single_qdd: Option<Expr>,
    /// The same recursion with a run of identical links rolled into loops (long chains),
    /// and the free-coordinate index of the run's first joint; `recursive_qdd` then holds
    /// the other free coordinates' accelerations, and zeros at the run's.
    pub rolled: Option<(tree::Rolled, usize)>,
    /// Initial positions and velocities of the free coordinates (parameters allowed).
    pub init_q: Vec<Expr>,
    pub init_qd: Vec<Expr>,
    /// Which of `init_qd` an `init` gives (the augmented form completes the others).
    pub init_rate_given: Vec<bool>,
    /// Which of `init_q` an `init` gives (the augmented form assembles the others).
    pub init_position_given: Vec<bool>,
    /// Minimal coordinates of a closed loop (closure.rs): the `asin`/`acos` arguments the
    /// generated code checks, `None` when the model is not one (no loop, or augmented).
    pub closure_domain: Option<Vec<closure::Domain>>,
    /// Parameter values to check at run time.
    pub checks: Vec<ParamCheck>,
    zero: Expr,
    one: Expr,
}

pub struct ResidualJacobian {
    pub r_q: Vec<Vec<Expr>>,
    pub r_qd: Vec<Vec<Expr>>,
    pub c_q: Vec<Vec<Expr>>,
    pub c_qd: Vec<Vec<Expr>>,
}

/// Names bound in user expressions.
type Names = HashMap<String, Binding>;

/// From how many tree bodies the articulated-body recursion replaces the mass-matrix solve
/// (measured with `cargo bench -p mechanisms --bench rhs`: see docs/ARCHITECTURE.md).
const RECURSIVE_FROM_BODIES: usize = 2;

/// From how many free coordinates a pure tree's mass matrix is formed at run time, column
/// by column (`Equations::mass_times`), instead of written out entry by entry: the entries
/// are O(n d) code, what bounds the build of long chains (`scaling`).
const LAZY_MASS_FROM: usize = 12;

/// Up to how many full coordinates Lagrange's form of the forces is derived as well, to take
/// it when it is shorter than Kane's (its Christoffel symbols are O(n^3)).
const LAGRANGE_MAX_COORDINATES: usize = 8;

/// Which form of the inertial forces `derive` builds (Kane's and Lagrange's are the same
/// functions, differently factored).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum InertialForm {
    /// Lagrange's when the system is scleronomic and it is shorter, else Kane's.
    Shorter,
    #[cfg(test)]
    Kane,
    #[cfg(test)]
    Lagrange,
}

/// The lowered model the mechanics reads: the parsed structure with every expression a
/// `syn`-free [`Term`].
pub(crate) type Ast = parse::Mechanism<Term>;

/// The equations of `lowered`; `errors`: those of its lowering, reported with the
/// mechanics' own.
pub fn derive(lowered: Lowered, errors: Errors) -> syn::Result<Equations> {
    derive_with(lowered, errors, InertialForm::Shorter)
}

/// Names and kinematics in full coordinates; what follows needs them complete, so their
/// errors (with the lowering's) stop here.
fn kinematics(ast: &Ast, errors: Errors) -> syn::Result<(Scope, Kinematics)> {
    let mut scope = Scope::new(ast, errors);
    scope.parameters(ast);
    let coords = scope.coordinates(ast);
    scope.points(ast);
    let mut bodies = bodies::free_bodies(ast, &mut scope);
    let planar = trees::planar(ast, &mut scope, &coords, &mut bodies);
    let spatial = trees::spatial(ast, &mut scope, &coords, &mut bodies);
    scope.element_names(ast);
    scope.errors_so_far()?;
    let kin = Kinematics {
        coords,
        bodies,
        planar,
        spatial,
    };
    fixed::declare(ast, &mut scope, &kin);
    scope.errors_so_far()?;
    Ok((scope, kin))
}

/// What the model observes of the motion, and its friction: outputs, events, shapes and
/// Coulomb forces, each in free (or minimal) coordinates, with the forces before friction.
struct Observed {
    outputs: Vec<OutputEq>,
    events: Vec<EventEq>,
    geometry: Vec<crate::geometry::Shape<Vec<Expr>>>,
    frictions: Vec<FrictionEq>,
    frictionless: Option<Vec<Expr>>,
}

/// The full model's rows an observation may need: reactions read the unprojected rows.
struct Full<'a> {
    kin: &'a Kinematics,
    unprojected: &'a (Vec<Vec<Expr>>, Vec<Expr>),
    phi: &'a [Expr],
}

/// Outputs, events, shapes and friction, with the reactions they ask for; friction's
/// forces are added to `red.forces`.
fn observe(
    (ast, shapes): (&Ast, Vec<crate::geometry::Shape<Term>>),
    scope: &mut Scope,
    full: Full<'_>,
    (red, con, minimal): (
        &mut reduction::Reduced,
        &constraints::InFree,
        Option<&crate::velocity::Minimal>,
    ),
    (reactions, checks): (&mut Vec<(usize, Expr)>, &mut Vec<ParamCheck>),
) -> Observed {
    let kin = full.kin;
    let free_idx = &red.free_idx;
    let mut answers = kin.kin(scope.t, scope.dim, reactions);
    let (mut outputs, mut events) = outputs::lower(ast, scope, &mut answers);
    let dims = scope.dim.len();
    let mut geometry = crate::geometry::lower(shapes, |e| {
        let context = crate::lower::Context::Output;
        scope.lowerer(Some(&mut answers)).vector(e, context, dims)
    });
    let at = (&kin.coords[..], &free_idx[..]);
    let mut frictions = coulomb::lower(ast, scope, &mut answers, at, checks);
    let rows = outputs::FullRows {
        m: &full.unprojected.0,
        f: &full.unprojected.1,
        phi: full.phi,
        lambdas: &con.lambdas,
    };
    let finisher = outputs::reactions(&mut scope.g, &kin.coords, reactions, &rows, &red.map);
    let observed = (&mut outputs[..], &mut events[..]);
    outputs::finish(scope, &finisher, observed, &kin.coords, free_idx);
    crate::geometry::map(&mut geometry, |x| finisher.finish(&mut scope.g, x));
    if let Some(min) = minimal {
        let observed = outputs.iter_mut().map(|o| &mut o.expr);
        for e in observed.chain(events.iter_mut().map(|e| &mut e.expr)) {
            *e = min.close(&mut scope.g, &[*e])[0];
        }
        crate::geometry::map(&mut geometry, |x| min.close(&mut scope.g, &[x])[0]);
    }
    let frictionless = coulomb::apply(
        scope,
        &finisher,
        (&mut frictions, ast.jacobian),
        &mut red.forces,
    );
    Observed {
        outputs,
        events,
        geometry,
        frictions,
        frictionless,
    }
}

fn derive_with(lowered: Lowered, errors: Errors, form: InertialForm) -> syn::Result<Equations> {
    let Lowered { ast, shapes } = lowered;
    let ast = &ast;
    let (mut scope, mut kin) = kinematics(ast, errors)?;
    let mut checks = checks::body_checks(&mut scope.g, &scope.names, &kin.bodies);
    for axes in [&kin.planar.axes, &kin.spatial.axes] {
        checks.extend(checks::axis_checks(&mut scope.g, axes));
    }
    let mut reactions: Vec<(usize, Expr)> = Vec::new();

    // Constraints, closed in minimal coordinates where the loop has a closed form.
    let mut loops = constraints::gather(ast, &mut scope, &kin);
    let minimal = minimal::minimal_coordinates(ast, &mut scope, &mut kin, &mut loops);

    // Forces and inertial forms in full coordinates.
    let loads = loads::lower(ast, &mut scope, &kin, &mut reactions);
    let forces = loads::generalized(&mut scope, &kin, loads, &mut checks);
    let closed = inertial::Closed {
        constrained: !loops.phi.is_empty(),
        minimal: minimal.is_some(),
    };
    let mut inertial = inertial::inertial(ast, &mut scope, &mut kin, &forces, closed, form);

    // Reduction to the free coordinates; the constraints there.
    // The full rows before the projection on minimal coordinates: reactions read them.
    let unprojected = (inertial.m_full.clone(), inertial.f_full.clone());
    let mut red = reduction::reduce(
        &mut scope,
        &kin.coords,
        &mut inertial,
        &loops.phi,
        minimal.as_ref(),
    );
    let minimal = minimal.map(|m| m.reduced(&mut scope.g, &red.map));
    let free_idx = &red.free_idx;
    let zsyms = kin.z_syms(&scope.g);
    let qsyms: Vec<Sym> = free_idx.iter().map(|&i| zsyms[i]).collect();
    let con = constraints::in_free_coordinates(&mut scope, &kin.coords, free_idx, &qsyms, &red.phi);
    let phi = (&red.phi[..], &loops.tokens[..]);
    constraints::check(&mut scope, &kin.coords, free_idx, phi, &qsyms, &red.mass);

    // Outputs, events and friction, with reactions on request.
    let full = Full {
        kin: &kin,
        unprojected: &unprojected,
        phi: &loops.phi,
    };
    let parts = (&mut red, &con, minimal.as_ref());
    let watched = (&mut reactions, &mut checks);
    let Observed {
        outputs,
        events,
        geometry,
        frictions,
        frictionless,
    } = observe((ast, shapes), &mut scope, full, parts, watched);
    let free_idx = &red.free_idx;

    // One free coordinate without constraints: `qdd = f / m` with the factors the two share
    // cancelled and the parameters' quotient apart (`-m g l sin(theta) / (m l^2)` is
    // `(-g / l) sin(theta)`), as one writes it by hand; generated code checks `m` first.
    let (n, mass, forces) = (free_idx.len(), &red.mass, &red.forces);
    let single = n == 1 && red.phi.is_empty() && red.recursive_qdd.is_none();
    let single_qdd = (single && frictions.is_empty()).then(|| {
        let roles = &scope.roles;
        let parameters_only =
            |g: &Graph, e: Expr| !uses_roles(g, roles, e, |r| !matches!(r, Role::Param(_)));
        scope
            .g
            .quotient_cancelled(forces[0], mass[0][0], parameters_only)
    });
    let qd: Vec<Expr> = free_idx.iter().map(|&i| kin.coords[i].zd).collect();
    let qdd: Vec<Expr> = free_idx.iter().map(|&i| kin.coords[i].zdd).collect();
    let jacobian = ast.jacobian.then(|| {
        let by = (&qsyms[..], &qd[..], &qdd[..]);
        implicit::residual_jacobian(&mut scope.g, (mass, forces), &con, by)
    });
    let linear_parts = crate::linear::Parts {
        mass,
        forces,
        phi_q: &con.phi_q,
        gamma: &con.gamma,
        q: &qsyms,
        qd: &qd,
        qdd: &qdd,
        lambdas: &con.lambdas,
        outputs: &outputs,
    };
    let linear = crate::linear::derive(&mut scope.g, ast, &mut scope.errors, linear_parts);
    let (init_q, init_qd, [init_position_given, init_rate_given]) =
        initial::initial_conditions(ast, &mut scope, &kin.coords, free_idx);
    let free = free_idx
        .iter()
        .map(|&i| kin.coords[i].name.clone())
        .collect();
    let Scope {
        mut g,
        roles,
        mut errors,
        ..
    } = scope;
    let zero = g.zero();
    let mut eqs = Equations {
        zero,
        // Interned after the last check, as it always was (`g.one()` may add the node).
        one: zero,
        free,
        g,
        roles,
        mass: red.mass,
        forces: red.forces,
        energy: red.energy,
        phi: red.phi,
        phi_q: con.phi_q,
        phi_t: con.phi_t,
        gamma: con.gamma,
        jacobian,
        linear,
        outputs,
        geometry,
        events,
        frictions,
        frictionless,
        recursive_qdd: red.recursive_qdd,
        mass_times: red.mass_times,
        inverse_dynamics: red.inverse,
        single_qdd,
        rolled: red.rolled,
        init_q,
        init_qd,
        init_rate_given,
        init_position_given,
        closure_domain: minimal.map(|m| m.domain),
        checks,
    };
    checks::non_finite(ast, &eqs, &mut errors);
    checks::check_default_configuration(ast, &mut eqs, &loops.tokens, &mut errors);
    errors.finish()?;
    eqs.one = eqs.g.one();
    Ok(eqs)
}

impl Equations {
    /// The constant 0 of this model's graph (already interned: every graph has it).
    pub fn g_zero(&self) -> Expr {
        self.zero
    }
    /// The constant 1 of this model's graph.
    pub fn g_one(&self) -> Expr {
        self.one
    }
}

/// Whether `e` uses a symbol whose role satisfies `pred`.
pub fn uses_roles(
    g: &Graph,
    roles: &HashMap<Sym, Role>,
    e: Expr,
    pred: impl Fn(&Role) -> bool,
) -> bool {
    g.free_symbols(e)
        .iter()
        .any(|s| roles.get(s).is_some_and(&pred))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value for every symbol, the same for one name in every graph.
    fn value_of(g: &Graph, s: Sym) -> f64 {
        let h = g
            .sym_name(s)
            .bytes()
            .fold(7u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b)));
        0.3 + (h % 1000) as f64 / 1000.0
    }

    /// Kane's and Lagrange's forces of `input`, evaluated at one state: two derivations of
    /// the same equations, so they must agree to rounding.
    fn forms_agree(input: syn::DeriveInput) {
        let ast = parse::Mechanism::from_syn(&input).expect("parses");
        let lowered = |ast| {
            let mut errors = Errors::default();
            (crate::lowered::lower(ast, &mut errors), errors)
        };
        let (l, e) = lowered(&ast);
        let kane = derive_with(l, e, InertialForm::Kane).expect("derives");
        let (l, e) = lowered(&ast);
        let lagrange = derive_with(l, e, InertialForm::Lagrange).expect("derives");
        assert_eq!(kane.forces.len(), lagrange.forces.len());
        for (&k, &l) in kane.forces.iter().zip(&lagrange.forces) {
            let fk = kane.g.eval(k, &|s| value_of(&kane.g, s));
            let fl = lagrange.g.eval(l, &|s| value_of(&lagrange.g, s));
            assert!(fk.is_finite() && fl.is_finite());
            assert!(
                (fk - fl).abs() <= 1e-12 * fk.abs().max(1.0),
                "{}: Kane {fk}, Lagrange {fl}",
                input.ident
            );
        }
    }

    /// A spatial chain of `n` bodies on universal joints, each of its own mass (so that no
    /// tail is rolled into loops), the graph's size after the mechanics.
    fn chain_nodes(n: usize) -> usize {
        let mut src = String::from("#[mechanism(spatial)]\n#[gravity(0.0, 0.0, -g)]\n");
        for k in 1..=n {
            let parent = if k == 1 {
                String::new()
            } else {
                format!("parent = u{}, at = [0.0, 0.0, -l], ", k - 1)
            };
            src += &format!(
                "#[body(u{k}, {parent}joint = universal(a{k}, b{k}), com = [0.0, 0.0, -l / 2.0], \
                 mass = m * {k}.0, inertia = diag(i, i, j))]\n"
            );
        }
        src += "struct Chain { m: f64, l: f64, i: f64, j: f64, g: f64 }";
        let input: syn::DeriveInput = syn::parse_str(&src).expect("parses");
        let ast = parse::Mechanism::from_syn(&input).expect("parses");
        let mut errors = Errors::default();
        let lowered = crate::lowered::lower(&ast, &mut errors);
        let eq = derive_with(lowered, errors, InertialForm::Shorter).expect("derives");
        assert!(eq.mass_times.is_some(), "a long tree's M by columns");
        eq.g.len()
    }

    /// The mechanics of a long pure tree is O(n): neither gravity's virtual work (a
    /// derivative of every body's position by every coordinate) nor the written-out
    /// composite-rigid-body `M` (every column carried to the root), both O(n^2) in a chain
    /// and unused where the recursions give `f` and `M qdd`, may be built. Measured: 32 -> 64
    /// bodies 138 445 -> 482 701 nodes (3.5x) with both, 41 811 -> 84 723 (2.0x) without.
    #[test]
    fn a_long_trees_mechanics_grows_linearly() {
        let (a, b) = (chain_nodes(32), chain_nodes(64));
        let ratio = b as f64 / a as f64;
        assert!(
            ratio < 2.1,
            "32 bodies {a} nodes, 64 bodies {b}: ratio {ratio}"
        );
    }

    #[test]
    fn kane_and_lagrange_give_the_same_forces() {
        forms_agree(syn::parse_quote! {
            #[gravity(0.0, -g)]
            #[coords(a, b)]
            #[particle(p1, mass = m1, at = [l1 * sin(a), -l1 * cos(a)])]
            #[particle(p2, mass = m2, at = [l1 * sin(a) + l2 * sin(b), -l1 * cos(a) - l2 * cos(b)])]
            struct DoublePendulum { m1: f64, m2: f64, l1: f64, l2: f64, g: f64 }
        });
        forms_agree(syn::parse_quote! {
            #[gravity(0.0, -g)]
            #[coords(theta, beta, x)]
            #[constraint(x == l * cos(beta) + r * cos(theta))]
            #[constraint(l * sin(beta) == r * sin(theta))]
            #[rigid(crank, mass = m_c, inertia = m_c * r * r / 12.0, at = [r / 2.0 * cos(theta), r / 2.0 * sin(theta)], angle = theta)]
            #[rigid(rod, mass = m_r, inertia = m_r * l * l / 12.0,
                    at = [r * cos(theta) + l / 2.0 * cos(beta), r * sin(theta) - l / 2.0 * sin(beta)],
                    angle = -beta)]
            #[particle(piston, mass = m_p, at = [x, 0.0])]
            struct SliderCrank { r: f64, l: f64, m_c: f64, m_r: f64, m_p: f64, g: f64 }
        });
        // A heavy top: spatial rotation, gyroscopic terms.
        forms_agree(syn::parse_quote! {
            #[mechanism(spatial)]
            #[gravity(0.0, 0.0, -g)]
            #[coords(psi, theta, phi)]
            #[rigid3(top, mass = m, inertia = diag(a, a, c),
                     at = rot_z(psi) * rot_y(theta) * [0.0, 0.0, h],
                     rotation = rot_z(psi) * rot_y(theta) * rot_z(phi))]
            struct Top { m: f64, a: f64, c: f64, h: f64, g: f64 }
        });
        // Elastic pendulum with a damper, a driven cart carrying it, and a torque.
        forms_agree(syn::parse_quote! {
            #[gravity(0.0, -g)]
            #[coords(r, u)]
            #[drive(x = a * sin(w * t))]
            #[particle(cart, mass = m0, at = [x, 0.0])]
            #[rigid(bob, mass = m, inertia = j, at = [x + r * sin(u), -r * cos(u)], angle = u)]
            #[spring(s, from = cart, to = bob, k = k, length = l0)]
            #[damper(d, from = cart, to = bob, c = c)]
            #[torque(tq, on = bob, value = -c * der(u))]
            struct Elastic { m0: f64, m: f64, j: f64, k: f64, l0: f64, c: f64, a: f64, w: f64, g: f64 }
        });
    }
}
