//! The items a model's derive emits: the `Mechanism`, `Constrained` and `OdeSystem`
//! impls, outputs, events, the friction views, the typed state and `GENERATED`. Each
//! function builds one item from the equations and the shared `Shape`.

use super::{
    Block, chart_margin, checked_value, closure_check, closure_domain, domain_checks,
    mass_matrix_body, parameter_checks, rolled_recursion, uses,
};
use crate::model::{Equations, Role};
use crate::parse::{Direction, Mechanism};
use crate::sym::Expr;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Saddle-point systems larger than this (`N + M`) are emitted with sparse `M` and `Phi_q`
/// (`solve::solve_augmented_sparse`); smaller ones keep the dense stack matrices.
const SPARSE_FROM: usize = 24;

/// Counts what was generated, for the validation report.
struct Parts {
    names: Vec<&'static str>,
    statements: usize,
}

/// What the items share: sizes, the state split, the checks, the solve for `qdd` and
/// `lambda`, and the count of what was generated.
struct Shape<'a> {
    ident: &'a syn::Ident,
    n: usize,
    m: usize,
    d: usize,
    a: usize,
    constrained: bool,
    nf: usize,
    split: TokenStream,
    check: Option<TokenStream>,
    /// `chart_margin` for `Mechanism` and `OdeSystem` (minimal closed loops).
    margin: Option<(TokenStream, TokenStream)>,
    direction: Option<TokenStream>,
    solve_qdd_lambda: TokenStream,
    parts: Parts,
    /// The ball joints' chart switch, when the model has one (`ball.rs`).
    charts: Option<TokenStream>,
    /// `rotation_charts` for `Mechanism` and `OdeSystem`, when the model has ball joints.
    rotation_charts: Option<TokenStream>,
}

pub fn emit(ast: &Mechanism, eq: &Equations) -> TokenStream {
    let mut sh = Shape::new(ast, eq);
    let accel = acceleration(eq, &mut sh);
    let (check_parameters, check_elements) = parameter_checks(ast, eq, accel.recursion.is_some());
    let mechanism_impl = mechanism_impl(eq, &sh, &accel, &check_elements);
    let constrained_impl = constrained_impl(eq, &mut sh, &accel);
    let jacobian = jacobian(eq, &mut sh);
    let ode_impl = ode_impl(&sh, &accel, &check_elements, jacobian);
    let outputs = outputs(eq, &mut sh);
    let events = events(eq, &mut sh);
    let frictions = frictions(eq, &mut sh, &check_elements);
    let geometry = ast.geometry.then(|| {
        sh.parts.names.push("geometry");
        let (code, statements) = crate::geometry::emit(sh.ident, eq, sh.d, &sh.split, &sh.check);
        sh.parts.statements += statements;
        code
    });
    let outputs = Some(quote!(#outputs #geometry));
    sh.parts.statements += accel.statements;
    let differentiable = differentiable(eq, &sh.direction);
    let linear = crate::linear::emit(
        eq,
        sh.ident,
        &sh.split,
        &sh.solve_qdd_lambda,
        &differentiable,
    )
    .map(|(code, len)| {
        sh.parts.names.push("linear");
        sh.parts.statements += len;
        code
    });
    let items = [
        mechanism_impl,
        constrained_impl.unwrap_or_default(),
        ode_impl,
    ];
    let observed = [outputs, events, frictions, linear].map(Option::unwrap_or_default);
    state(eq, sh, check_parameters, items, observed)
}

impl<'a> Shape<'a> {
    fn new(ast: &'a Mechanism, eq: &Equations) -> Shape<'a> {
        let ident = &ast.ident;
        let n = eq.free.len();
        let m = eq.phi.len();
        let d = 2 * n;
        let a = n + m;
        let constrained = m > 0;
        let mut parts = Parts {
            names: vec!["mass_matrix", "forces", "energy"],
            statements: 0,
        };
        let check = closure_check(eq, n);
        match (&eq.closure_domain, constrained) {
            (Some(_), _) => parts.names.push("minimal_closed_form"),
            (None, true) => parts.names.push("augmented"),
            (None, false) => {}
        }
        // Friction directions: the sign of the sliding velocities (sliding view: given).
        let friction_coords: Vec<usize> = eq.frictions.iter().map(|f| f.coord).collect();
        let nf = friction_coords.len();
        // At rest (`+0.0` or `-0.0`) the direction is 0: the friction force there is a reaction,
        // found with the accelerations (`mbd_core::friction`), not a sign bit's guess.
        let direction = (nf > 0).then(|| {
            quote!(let direction: [f64; #nf] = [#(::mbd::__private::friction::direction(qd[#friction_coords])),*];)
        });
        let split = quote! {
            let q = y.fixed_rows::<#n>(0).into_owned();
            let qd = y.fixed_rows::<#n>(#n).into_owned();
        };

        // `qdd` and `lambda` for code that needs them (outputs, events, Jacobians).
        let solve_qdd_lambda = if constrained {
            quote!(let (qdd, lambda) = ::mbd::__private::Constrained::<#n, #m>::acceleration_and_multipliers(self, t, &q, &qd)?;)
        } else {
            quote! {
                let qdd = ::mbd::__private::Mechanism::<#n>::acceleration(self, t, &q, &qd)?;
                let lambda = ::mbd::__private::Vector::<0>::zeros();
            }
        };

        Shape {
            ident,
            n,
            m,
            d,
            a,
            constrained,
            nf,
            split,
            check,
            margin: chart_margin(eq, n),
            direction,
            solve_qdd_lambda,
            parts,
            charts: crate::ball::switch(ast, &eq.free, n),
            rotation_charts: crate::ball::charts(ast, &eq.free)
                .map(|balls| quote!(fn rotation_charts(&self) -> &[[usize; 3]] { #balls })),
        }
    }
}

/// How `acceleration` is evaluated, and the blocks the other items reuse.
struct Acceleration {
    /// `M` and `f`'s roots, shared with the constrained solve.
    mf_roots: Vec<Expr>,
    mass_matrix: TokenStream,
    forces: TokenStream,
    energy: TokenStream,
    /// The articulated-body recursion writing `qdd[i]`.
    recursion: Option<TokenStream>,
    friction_acceleration: Option<TokenStream>,
    body: TokenStream,
    /// Whether `body` makes the closed loop's domain checks itself (else `acceleration`
    /// appends [`closure_check`]'s).
    checked: bool,
    /// Statements of `mass_matrix`, `forces` and `energy`.
    statements: usize,
    /// `inverse_dynamics` by recursive Newton-Euler (a pure joint tree).
    inverse: Option<TokenStream>,
}

fn acceleration(eq: &Equations, sh: &mut Shape<'_>) -> Acceleration {
    let (n, m, nf, constrained) = (sh.n, sh.m, sh.nf, sh.constrained);
    let parts = &mut sh.parts;
    // M and f from one block, so that they share subexpressions.
    let mf_roots: Vec<Expr> = eq
        .mass
        .iter()
        .flatten()
        .chain(&eq.forces)
        .copied()
        .collect();
    // (Only where the acceleration is a mass-matrix solve.)
    let mass_solve = eq.recursive_qdd.is_none() && eq.single_qdd.is_none() && !constrained;
    // A closed loop's domain checks, on the arguments the body computes anyway.
    let domain = closure_domain(eq, mass_solve || eq.single_qdd.is_some());
    let args: Vec<Expr> = domain.iter().map(|d| d.arg).collect();
    let (mf_stmts, mass_fill, force_fill, domain_checks) = if mass_solve {
        let roots: Vec<Expr> = mf_roots.iter().chain(&args).copied().collect();
        let mf = Block::new(eq, &roots);
        parts.statements += mf.len();
        (
            mf.stmts(),
            mf.matrix("mass", n, n, &eq.mass),
            mf.vector("f", n, &eq.forces),
            domain_checks(&mf, domain, n),
        )
    } else {
        Default::default()
    };
    let (mass_matrix, mass_len) = mass_matrix_body(eq, n);
    let (forces_only, forces_len) = checked_value(
        eq,
        n,
        &eq.forces,
        |b| b.vector("f", n, &eq.forces),
        quote!(f),
    );
    let (energy, energy_len) = checked_value(
        eq,
        n,
        &[eq.energy],
        |b| {
            let e = b.leaf(eq.energy);
            quote!(let e: f64 = #e;)
        },
        quote!(e),
    );

    // The articulated-body recursion writes `qdd[i]` into a vector declared around it: a
    // fresh one in `acceleration`, the lower half of `y'` in `rhs` (no copies of the state).
    let recursion = if constrained {
        None
    } else if let (Some((rolled, first)), Some(qdd)) = (&eq.rolled, &eq.recursive_qdd) {
        parts.names.extend(["articulated_body", "rolled_chain"]);
        let (code, statements) = rolled_recursion(eq, rolled, *first, qdd);
        parts.statements += statements;
        Some(code)
    } else if let Some(qdd) = &eq.recursive_qdd {
        parts.names.push("articulated_body");
        let (angles, known) = super::batched_trig(eq, qdd, None);
        let b = Block::after(eq, qdd, &known, 0);
        parts.statements += b.len();
        let (s, fill) = (b.stmts(), b.sets("qdd", qdd));
        Some(quote!(#angles #s #fill))
    } else {
        None
    };
    let friction_acceleration = (nf > 0).then(|| crate::friction::acceleration(eq));
    let acceleration = if let Some(solve) = &friction_acceleration {
        quote!(#solve.map(|(qdd, _)| qdd).map_err(|e| self.diagnose(e)))
    } else if constrained {
        quote!(::mbd::__private::Constrained::<#n, #m>::acceleration_and_multipliers(self, t, q, qd).map(|(qdd, _)| qdd))
    } else if let Some(code) = &recursion {
        quote! {
            self.check_masses()?;
            let mut qdd = ::mbd::__private::Vector::<#n>::zeros();
            #code
            ::mbd::__private::solve::finite(t, qdd).map_err(|e| self.diagnose(e))
        }
    } else if let Some(qdd) = eq.single_qdd {
        let mass = eq.mass[0][0];
        let roots: Vec<Expr> = [mass, qdd].into_iter().chain(args).collect();
        let b = Block::new(eq, &roots);
        let (s, m, a) = (b.stmts(), b.leaf(mass), b.leaf(qdd));
        let solve = if domain.is_empty() {
            quote!(::mbd::__private::solve::one_coordinate(t, #m, #a))
        } else {
            // Every check in one branch (see `closure::one_coordinate_in_domain`).
            let args = domain.iter().map(|d| b.leaf(d.arg));
            let coords = domain.iter().map(|d| &d.coord);
            quote! {
                ::mbd::__private::closure::one_coordinate_in_domain(t, #m, #a, [#(#args),*], [#(#coords),*],
                    &<Self as ::mbd::__private::Mechanism<#n>>::COORDINATES, q.as_slice())
            }
        };
        quote!(#s #solve.map_err(|e| self.diagnose(e)))
    } else {
        quote! {
            #mf_stmts
            #mass_fill
            #force_fill
            #domain_checks
            ::mbd::__private::solve::solve_mass::<#n>(t, &mass, &f).map_err(|e| self.diagnose(e))
        }
    };

    let forces_body = match nf {
        0 => forces_only,
        _ => {
            let (check, forces) = (closure_check(eq, n), crate::friction::forces(eq));
            quote! {
                #check
                ::mbd::__private::closure::finite_value(t, #forces?).map_err(|e| self.diagnose(e))
            }
        }
    };
    Acceleration {
        mf_roots,
        mass_matrix,
        forces: forces_body,
        energy,
        recursion,
        friction_acceleration,
        body: acceleration,
        checked: !domain.is_empty(),
        statements: mass_len + forces_len + energy_len,
        inverse: inverse_dynamics(eq, sh),
    }
}

/// A joint tree's `inverse_dynamics`: recursive Newton-Euler with the given `qdd`, O(n)
/// code in place of the trait's `M qdd - f` (O(n^2) work and a mass matrix). `#[inline]`, so
/// that a crate which never calls it never compiles it.
fn inverse_dynamics(eq: &Equations, sh: &mut Shape<'_>) -> Option<TokenStream> {
    let rows = eq.inverse_dynamics.as_ref()?;
    let n = sh.n;
    let b = Block::new(eq, rows);
    sh.parts.names.push("inverse_dynamics");
    sh.parts.statements += b.len();
    let (s, fill) = (b.stmts(), b.vector("tau", n, rows));
    Some(quote! {
        #[inline]
        fn inverse_dynamics(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>,
            qdd: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Result<::mbd::__private::Vector<#n>> {
            #s
            #fill
            ::mbd::__private::closure::finite_value(t, tau).map_err(|e| self.diagnose(e))
        }
    })
}

fn mechanism_impl(
    eq: &Equations,
    sh: &Shape<'_>,
    accel: &Acceleration,
    check_elements: &Option<TokenStream>,
) -> TokenStream {
    let (ident, n) = (sh.ident, sh.n);
    let coord_names: Vec<String> = eq.free.iter().map(|c| c.to_string()).collect();
    let (check, direction) = (sh.check.as_ref().filter(|_| !accel.checked), &sh.direction);
    let margin = sh.margin.as_ref().map(|(m, _)| m);
    let (mass_matrix, forces_body, energy) = (&accel.mass_matrix, &accel.forces, &accel.energy);
    let (acceleration, inverse) = (&accel.body, &accel.inverse);
    // A one-coordinate acceleration is a few operations: called out of line from another
    // crate (where integrators and `rhs` are instantiated), the call costs as much as the body.
    let inline_acceleration = eq.single_qdd.is_some().then(|| quote!(#[inline]));
    let rows = (sh.constrained).then(|| {
        let m = sh.m;
        quote!(const CONSTRAINTS: usize = #m;)
    });
    let rotation_charts = &sh.rotation_charts;
    quote! {
        impl ::mbd::__private::Mechanism<#n> for #ident {
            const COORDINATES: [&'static str; #n] = [#(#coord_names),*];
            #rows
            #rotation_charts
            fn mass_matrix(&self, t: f64, q: &::mbd::__private::Vector<#n>)
                -> ::mbd::__private::Result<::mbd::__private::Matrix<#n, #n>> {
                #mass_matrix
            }
            fn forces(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>)
                -> ::mbd::__private::Result<::mbd::__private::Vector<#n>> {
                #forces_body
            }
            #inline_acceleration
            fn acceleration(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>)
                -> ::mbd::__private::Result<::mbd::__private::Vector<#n>> {
                #check_elements
                #direction
                let qdd = { #acceleration };
                #check
                qdd
            }
            fn energy(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>)
                -> ::mbd::__private::Result<f64> {
                #energy
            }
            #margin
            #inverse
        }
    }
}

/// Constraints: only in a model that has them.
fn constrained_impl(
    eq: &Equations,
    sh: &mut Shape<'_>,
    accel: &Acceleration,
) -> Option<TokenStream> {
    let (ident, n, m, a, constrained) = (sh.ident, sh.n, sh.m, sh.a, sh.constrained);
    let parts = &mut sh.parts;
    let (mf_roots, friction_acceleration) = (&accel.mf_roots, &accel.friction_acceleration);
    constrained.then(|| {
        parts.names.extend(["phi", "phi_q", "phi_t", "gamma", "multipliers", "projection"]);
        let phi = Block::new(eq, &eq.phi);
        let phi_q_roots: Vec<Expr> = eq.phi_q.iter().flatten().copied().collect();
        let phi_q = Block::new(eq, &phi_q_roots);
        let phi_t = Block::new(eq, &eq.phi_t);
        let gamma = Block::new(eq, &eq.gamma);
        let all: Vec<Expr> = mf_roots.iter().chain(&phi_q_roots).chain(&eq.gamma).copied().collect();
        let full = Block::new(eq, &all);
        parts.statements += full.len() + phi.len();
        let (p_s, p_f) = (phi.stmts(), phi.vector("phi", m, &eq.phi));
        let (pq_s, pq_f) = (phi_q.stmts(), phi_q.matrix("phi_q", m, n, &eq.phi_q));
        let (pt_s, pt_f) = (phi_t.stmts(), phi_t.vector("phi_t", m, &eq.phi_t));
        let (g_s, g_f) = (gamma.stmts(), gamma.vector("gamma", m, &eq.gamma));
        let (f_s, f_m, f_f, f_pq, f_g) = (
            full.stmts(),
            full.matrix("mass", n, n, &eq.mass),
            full.vector("f", n, &eq.forces),
            full.matrix("phi_q", m, n, &eq.phi_q),
            full.vector("gamma", m, &eq.gamma),
        );
        let solve_full = match &friction_acceleration {
            Some(solve) => solve.clone(),
            // A large assembly: `M` and `Phi_q` by their non-zeros (a banded solve).
            None if a > SPARSE_FROM => {
                let f_m = full.triplets("mass", &eq.mass, true);
                let f_pq = full.triplets("phi_q", &eq.phi_q, false);
                quote! {
                    #f_s #f_m #f_f #f_pq #f_g
                    ::mbd::__private::solve::solve_augmented_sparse::<Self, #n, #m, #a>(self, t, q, qd, &mass, &f, &phi_q, &gamma).map_err(|e| self.diagnose(e))
                }
            }
            None => quote! {
                #f_s #f_m #f_f #f_pq #f_g
                ::mbd::__private::solve::solve_constrained::<Self, #n, #m, #a>(self, t, q, qd, &mass, &f, &phi_q, &gamma).map_err(|e| self.diagnose(e))
            },
        };
        quote! {
            impl ::mbd::__private::Constrained<#n, #m> for #ident {
                fn phi(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#m> { #p_s #p_f phi }
                fn phi_q(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Matrix<#m, #n> { #pq_s #pq_f phi_q }
                fn phi_t(&self, t: f64, q: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#m> { #pt_s #pt_f phi_t }
                fn gamma(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>) -> ::mbd::__private::Vector<#m> { #g_s #g_f gamma }
                fn acceleration_and_multipliers(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>)
                    -> ::mbd::__private::Result<(::mbd::__private::Vector<#n>, ::mbd::__private::Vector<#m>)> {
                    #solve_full
                }
            }
        }
    })
}

/// The friction directions for code that differentiates the accelerations (the Jacobian,
/// the linear parts), refusing a contact at rest: there it sticks or breaks away by the load,
/// and the accelerations have no derivative (with the direction 0 the derivatives would be
/// the frictionless model's, a wrong `Ok`).
fn differentiable(eq: &Equations, direction: &Option<TokenStream>) -> Option<TokenStream> {
    let direction = direction.as_ref()?;
    let along: Vec<String> = (eq.frictions.iter())
        .map(|f| eq.free[f.coord].to_string())
        .collect();
    Some(quote! {
        #direction
        if let Some(k) = direction.iter().position(|d| *d == 0.0) {
            return Err(::mbd::__private::Error::InvalidInput {
                what: "friction at rest",
                detail: ::std::format!(
                    "the contact along `{}` is at rest: it sticks or breaks away by the load, so the \
                     accelerations have no derivative there; linearise a sliding state",
                    [#(#along),*][k]),
            });
        }
    })
}

fn jacobian(eq: &Equations, sh: &mut Shape<'_>) -> Option<TokenStream> {
    let (n, m, d) = (sh.n, sh.m, sh.d);
    let direction = differentiable(eq, &sh.direction);
    let (split, solve_qdd_lambda) = (&sh.split, &sh.solve_qdd_lambda);
    let parts = &mut sh.parts;
    let m_or_0 = if sh.constrained { m } else { 0 };
    eq.jacobian.as_ref().map(|jac| {
        parts.names.push("jacobian");
        let mut roots: Vec<Expr> = eq.mass.iter().flatten().copied().collect();
        roots.extend(eq.phi_q.iter().flatten());
        for mat in [&jac.r_q, &jac.r_qd, &jac.c_q, &jac.c_qd] {
            roots.extend(mat.iter().flatten());
        }
        let b = Block::new(eq, &roots);
        parts.statements += b.len();
        let (s, mass, pq, rq, rqd, cq, cqd) = (
            b.stmts(),
            b.matrix("mass", n, n, &eq.mass),
            b.matrix("phi_q", m_or_0, n, &eq.phi_q),
            b.matrix("r_q", n, n, &jac.r_q),
            b.matrix("r_qd", n, n, &jac.r_qd),
            b.matrix("c_q", m_or_0, n, &jac.c_q),
            b.matrix("c_qd", m_or_0, n, &jac.c_qd),
        );
        let a_or_n = n + m_or_0;
        quote! {
            const EXACT_JACOBIAN: bool = true;
            fn jacobian(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<::mbd::__private::Matrix<#d, #d>> {
                #split
                #solve_qdd_lambda
                #direction
                #s #mass #pq #rq #rqd #cq #cqd
                let (a_q, a_qd) = ::mbd::__private::solve::acceleration_jacobian::<#n, #m_or_0, #a_or_n>(
                    t, &mass, &phi_q, &r_q, &r_qd, &c_q, &c_qd)?;
                Ok(::mbd::__private::solve::second_order_jacobian::<#n, #d>(&a_q, &a_qd))
            }
        }
    })
}

fn ode_impl(
    sh: &Shape<'_>,
    accel: &Acceleration,
    check_elements: &Option<TokenStream>,
    jacobian: Option<TokenStream>,
) -> TokenStream {
    let (ident, n, m, d, constrained) = (sh.ident, sh.n, sh.m, sh.d, sh.constrained);
    let recursion = &accel.recursion;
    let onto_constraints = constrained.then(|| {
        quote!(::mbd::__private::analysis::projection::project_state::<Self, #n, #m, #d>(self, t, y)?;)
    });
    let (charts, rotation_charts) = (&sh.charts, &sh.rotation_charts);
    let margin = sh.margin.as_ref().map(|(_, o)| o);
    let project = (constrained || charts.is_some()).then(|| {
        quote! {
            fn project(&self, t: f64, y: &mut ::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<()> {
                #charts
                #onto_constraints
                Ok(())
            }
        }
    });
    // Only a model with constraints is its own bridge (a ball joint's charts alone are not).
    let passage = constrained.then(|| {
        quote! {
            fn passage(&self) -> ::core::option::Option<&dyn ::mbd::__private::passage::Bridge<#d>> {
                ::core::option::Option::Some(self)
            }
        }
    });
    // A closed loop's ordinary solve bridges its singular positions (mbd::passage).
    let bridge = constrained.then(|| {
        quote! {
            impl ::mbd::__private::passage::Bridge<#d> for #ident {
                fn pass(
                    &self,
                    start: (f64, ::mbd::__private::Vector<#d>, f64),
                    events: &[::mbd::__private::integrate::Event<'_, #d>],
                    settings: &::mbd::__private::passage::Settings,
                    run: &mut ::mbd::__private::passage::Run<'_, #d>,
                ) -> ::mbd::__private::Result<::mbd::__private::integrate::Solution<#d>> {
                    ::mbd::__private::passage::pass::<Self, #n, #m, #d>(self, start, events, settings, run)
                }
            }
        }
    });
    // Coulomb friction: the plain rhs switches modes, so the ordinary solve runs the model
    // mode by mode (mbd::hybrid).
    let hybrid = (accel.friction_acceleration.is_some()).then(|| {
        quote!(
            const HYBRID: bool = true;
            fn hybrid(&self) -> ::core::option::Option<&dyn ::mbd::__private::hybrid::Modes<#d>> {
                ::core::option::Option::Some(self)
            }
        )
    });
    let rhs_body = match &recursion {
        Some(code) => quote! {
            self.check_masses()?;
            #check_elements
            let q = y.fixed_rows::<#n>(0);
            let qd = y.fixed_rows::<#n>(#n);
            let mut dy = ::mbd::__private::Vector::<#d>::from_fn(|i, _| if i < #n { qd[i] } else { 0.0 });
            {
                let mut qdd = dy.fixed_rows_mut::<#n>(#n);
                #code
            }
            ::mbd::__private::solve::finite_accelerations::<#n, #d>(t, dy).map_err(|e| self.diagnose(e))
        },
        None => quote! {
            ::mbd::__private::solve::second_order_rhs::<#n, #d>(y, |q, qd| ::mbd::__private::Mechanism::<#n>::acceleration(self, t, q, qd))
        },
    };
    quote! {
        impl ::mbd::__private::OdeSystem<#d> for #ident {
            #[inline]
            fn rhs(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<::mbd::__private::Vector<#d>> {
                #rhs_body
            }
            #jacobian
            #hybrid
            #project
            #passage
            #margin
            #rotation_charts
        }
        #bridge
    }
}

/// Outputs: a struct of them and their evaluation.
fn outputs(eq: &Equations, sh: &mut Shape<'_>) -> Option<TokenStream> {
    let (ident, d) = (sh.ident, sh.d);
    let (split, check, solve_qdd_lambda) = (&sh.split, &sh.check, &sh.solve_qdd_lambda);
    let parts = &mut sh.parts;
    let outputs_struct = format_ident!("{}Outputs", ident);
    let out_names: Vec<_> = eq.outputs.iter().map(|o| o.name.clone()).collect();
    let out_strs: Vec<String> = out_names.iter().map(|o| o.to_string()).collect();
    let k = out_names.len();
    (!eq.outputs.is_empty()).then(|| {
        parts.names.push("outputs");
        let roots: Vec<Expr> = eq.outputs.iter().map(|o| o.expr).collect();
        let b = Block::new(eq, &roots);
        parts.statements += b.len();
        let needs_qdd = uses(eq, &roots, |r| matches!(r, Role::Qdd(_) | Role::Lambda(_)));
        let pre = needs_qdd.then(|| solve_qdd_lambda.clone());
        let s = b.stmts();
        let vals: Vec<TokenStream> = roots.iter().map(|e| b.leaf(*e)).collect();
        let doc = format!("The outputs of [`{ident}`], evaluated by [`{ident}::outputs`].");
        let eq = super::flat_partial_eq(&outputs_struct, &out_names.iter().collect::<Vec<_>>());
        quote! {
            #[doc = #doc]
            #[derive(Debug, Clone, Copy)]
            pub struct #outputs_struct { #(pub #out_names: f64,)* }
            #eq
            #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
            impl #ident {
                /// Names of the outputs, in declaration order.
                pub const OUTPUTS: [&'static str; #k] = [#(#out_strs),*];
                /// Evaluate the outputs at `(t, y)`, solving for accelerations and reactions when they need them.
                pub fn outputs(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<#outputs_struct> {
                    #split
                    #check
                    #pre
                    #s
                    Ok(#outputs_struct { #(#out_names: #vals,)* })
                }
                /// The outputs as an array, in the order of [`Self::OUTPUTS`].
                pub fn output_values(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<[f64; #k]> {
                    let o = self.outputs(t, y)?;
                    Ok([#(o.#out_names),*])
                }
            }
        }
    })
}

/// Event functions and the model's list of events.
fn events(eq: &Equations, sh: &mut Shape<'_>) -> Option<TokenStream> {
    let (ident, d) = (sh.ident, sh.d);
    let (split, check, solve_qdd_lambda) = (&sh.split, &sh.check, &sh.solve_qdd_lambda);
    let parts = &mut sh.parts;
    (!eq.events.is_empty()).then(|| {
        parts.names.push("events");
        let fns = eq.events.iter().map(|ev| {
            let b = Block::new(eq, &[ev.expr]);
            let needs_qdd = uses(eq, &[ev.expr], |r| matches!(r, Role::Qdd(_) | Role::Lambda(_)));
            let pre = needs_qdd.then(|| solve_qdd_lambda.clone());
            let (s, v) = (b.stmts(), b.leaf(ev.expr));
            let fname = format_ident!("event_{}", ev.name);
            let doc = format!("The event function `{}`: its zero crossings are the events.", ev.name);
            quote! {
                #[doc = #doc]
                pub fn #fname(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<f64> {
                    #split
                    #check
                    #pre
                    #s
                    Ok(#v)
                }
            }
        });
        let makes = eq.events.iter().map(|ev| {
            let fname = format_ident!("event_{}", ev.name);
            let name = ev.name.to_string();
            let dir = match ev.direction {
                Direction::Rising => quote!(Rising),
                Direction::Falling => quote!(Falling),
                Direction::Either => quote!(Either),
            };
            let terminal = ev.terminal.then(|| quote!(.terminal()));
            quote! {
                ::mbd::__private::integrate::Event::fallible(
                    #name,
                    // An event function that cannot be evaluated (singular position) stops
                    // the integration with its error.
                    move |t, y| self.#fname(t, y),
                    ::mbd::__private::integrate::Direction::#dir,
                ) #terminal
            }
        });
        quote! {
            #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
            impl #ident {
                #(#fns)*
                /// The model's events, for an integrator's `solve`.
                pub fn events(&self) -> ::std::vec::Vec<::mbd::__private::integrate::Event<'_, #d>> {
                    ::std::vec![#(#makes),*]
                }
            }
        }
    })
}

/// Coulomb friction: the stick test at rest, per friction, and the sliding view.
fn frictions(
    eq: &Equations,
    sh: &mut Shape<'_>,
    check_elements: &Option<TokenStream>,
) -> Option<TokenStream> {
    let (ident, n, m, d, a, nf) = (sh.ident, sh.n, sh.m, sh.d, sh.a, sh.nf);
    let (constrained, split) = (sh.constrained, &sh.split);
    let parts = &mut sh.parts;
    eq.frictionless.as_ref().map(|frictionless| {
        parts.names.push("friction");
        let m1 = m + 1;
        let a1 = n + m1;
        let fns = eq.frictions.iter().enumerate().map(|(k, fr)| {
            if let Some(item) = crate::friction::sticks(eq, k) {
                return item;
            }
            let mut roots: Vec<Expr> = eq.mass.iter().flatten().chain(frictionless).copied().collect();
            roots.extend(eq.phi_q.iter().flatten().chain(&eq.gamma));
            roots.extend([fr.normal, fr.mu_static]);
            let b = Block::new(eq, &roots);
            let (s, mass, f) = (b.stmts(), b.matrix("mass", n, n, &eq.mass), b.vector("f", n, frictionless));
            let mut rows = eq.phi_q.clone();
            let mut e_s = vec![eq.g_zero(); n];
            e_s[fr.coord] = eq.g_one();
            rows.push(e_s);
            let mut gamma = eq.gamma.clone();
            gamma.push(eq.g_zero());
            let (pq, gm) = (b.matrix("phi_q", m1, n, &rows), b.vector("gamma", m1, &gamma));
            let (normal, mu_static) = (b.leaf(fr.normal), b.leaf(fr.mu_static));
            let coord = &eq.free[fr.coord];
            let fname = format_ident!("{}_sticks", coord);
            let doc = format!(
                "At rest along `{coord}` (`der({coord}) = 0`): whether static friction can hold it, i.e. whether the \
                 force needed to keep `{coord}` still is at most `mu_static |N|`."
            );
            quote! {
                #[doc = #doc]
                pub fn #fname(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<bool> {
                    #split
                    #s #mass #f #pq #gm
                    let (_, lambda) = ::mbd::__private::solve::solve_augmented::<#n, #m1, #a1>(t, &mass, &f, &phi_q, &gamma)?;
                    Ok(lambda[#m].abs() <= #mu_static * (#normal).abs())
                }
            }
        });
        // The sliding view: friction directions fixed, so the right-hand side stays smooth
        // through the stop and the stop is found as an event (never `sign(0)` in a step).
        let sliding = format_ident!("{}Sliding", ident);
        let mut roots: Vec<Expr> = eq.mass.iter().flatten().chain(&eq.forces).copied().collect();
        roots.extend(eq.phi_q.iter().flatten().chain(&eq.gamma));
        let b = Block::new(eq, &roots);
        let (s, mass, f) = (b.stmts(), b.matrix("mass", n, n, &eq.mass), b.vector("f", n, &eq.forces));
        let solve = if constrained {
            let (pq, gm) = (b.matrix("phi_q", m, n, &eq.phi_q), b.vector("gamma", m, &eq.gamma));
            quote!(#pq #gm ::mbd::__private::solve::solve_augmented::<#n, #m, #a>(t, &mass, &f, &phi_q, &gamma).map(|(qdd, _)| qdd))
        } else {
            quote!(::mbd::__private::solve::solve_mass::<#n>(t, &mass, &f))
        };
        let sliding_body = crate::friction::sliding_acceleration(eq).unwrap_or(quote!(#s #mass #f #solve));
        let project = constrained.then(|| {
            quote! {
                fn project(&self, t: f64, y: &mut ::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<()> {
                    ::mbd::__private::analysis::projection::project_state::<#ident, #n, #m, #d>(self.model, t, y)
                }
            }
        });
        let doc = format!(
            "[`{ident}`] sliding in fixed directions (`+1`/`-1` per friction, in declaration order): integrate this \
             view from a sliding state to a stop event, then test [`{ident}`]'s `*_sticks`."
        );
        let (modes, statements) = crate::friction::emit(ident, eq, frictionless);
        parts.statements += statements;
        quote! {
            #modes
            #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
            impl #ident {
                #(#fns)*
                /// The accelerations with the friction directions given instead of `sign(qd)`.
                pub fn acceleration_sliding(&self, t: f64, q: &::mbd::__private::Vector<#n>, qd: &::mbd::__private::Vector<#n>,
                    direction: &[f64; #nf]) -> ::mbd::__private::Result<::mbd::__private::Vector<#n>> {
                    #check_elements
                    #sliding_body
                }
                /// The sliding view of this model (see its type).
                pub fn sliding(&self, direction: [f64; #nf]) -> #sliding<'_> {
                    #sliding { model: self, direction }
                }
            }
            #[doc = #doc]
            #[derive(Debug, Clone, Copy)]
            pub struct #sliding<'a> {
                pub model: &'a #ident,
                pub direction: [f64; #nf],
            }
            #[automatically_derived]
            impl ::mbd::__private::OdeSystem<#d> for #sliding<'_> {
                fn rhs(&self, t: f64, y: &::mbd::__private::Vector<#d>) -> ::mbd::__private::Result<::mbd::__private::Vector<#d>> {
                    ::mbd::__private::solve::second_order_rhs::<#n, #d>(y, |q, qd| self.model.acceleration_sliding(t, q, qd, &self.direction))
                }
                #project
            }
        }
    })
}

/// In the augmented form, the positions `init` does not give are assembled onto the
/// position constraints by Newton's method from zero (the given positions held), and the
/// rates it does not give follow from the velocity constraints (the least-norm consistent
/// ones, the given rates held), as the closure gives both in minimal coordinates:
/// `init(th = 0.3, der(th) = 2.0)` means the same in both forms. Left as given where the
/// held values do not determine them (the solve then refuses the start).
fn complete_init(eq: &Equations, sh: &Shape<'_>) -> TokenStream {
    let (n, m) = (sh.n, sh.m);
    let all = |v: &[bool]| v.iter().all(|&g| g);
    if !sh.constrained || (all(&eq.init_rate_given) && all(&eq.init_position_given)) {
        return TokenStream::new();
    }
    let (held_q, held) = (&eq.init_position_given, &eq.init_rate_given);
    let positions = (!all(held_q)).then(|| {
        quote! {
            let held_q: [bool; #n] = [#(#held_q),*];
            let q0 = y.fixed_rows::<#n>(0).into_owned();
            let newton = ::mbd::__private::analysis::NewtonOptions::default();
            if let Ok(q) = ::mbd::__private::analysis::assemble::<Self, #n, #m>(self, t, &q0, &held_q, &newton) {
                y.fixed_rows_mut::<#n>(0).copy_from(&q);
            }
        }
    });
    quote! {
        #positions
        let held: [bool; #n] = [#(#held),*];
        let q = y.fixed_rows::<#n>(0).into_owned();
        let qd = y.fixed_rows::<#n>(#n).into_owned();
        if let Ok(qd) = ::mbd::__private::analysis::assembly::consistent_velocities::<Self, #n, #m>(self, t, &q, &qd, &held) {
            y.fixed_rows_mut::<#n>(#n).copy_from(&qd);
        }
    }
}

/// The typed state, `GENERATED`, the parameter checks, the initial state, and the items.
fn state(
    eq: &Equations,
    sh: Shape<'_>,
    check_parameters: TokenStream,
    [mechanism_impl, constrained_impl, ode_impl]: [TokenStream; 3],
    [outputs, events, frictions, linear]: [TokenStream; 4],
) -> TokenStream {
    let (ident, n, m, d) = (sh.ident, sh.n, sh.m, sh.d);
    let init_roots: Vec<Expr> = eq.init_q.iter().chain(&eq.init_qd).copied().collect();
    let init = Block::new(eq, &init_roots);
    let (init_s, init_v) = (init.stmts(), init.vector("y", d, &init_roots));
    let init_rates = complete_init(eq, &sh);
    let state_struct = format_ident!("{}State", ident);
    let q_ids: Vec<_> = eq.free.clone();
    let qd_ids: Vec<_> = eq.free.iter().map(|c| format_ident!("{}_dot", c)).collect();
    let q_idx: Vec<usize> = (0..n).collect();
    let qd_idx: Vec<usize> = (n..d).collect();
    let part_names = &sh.parts.names;
    let statements = sh.parts.statements;
    let state_doc = format!(
        "The state of [`{ident}`] by coordinate name: positions, then velocities (`_dot`)."
    );

    let state_fields: Vec<&syn::Ident> = q_ids.iter().chain(&qd_ids).collect();
    let state_eq = super::flat_partial_eq(&state_struct, &state_fields);
    quote! {
        #[doc = #state_doc]
        #[derive(Debug, Clone, Copy, Default)]
        pub struct #state_struct { #(pub #q_ids: f64,)* #(pub #qd_ids: f64,)* }
        #state_eq
        impl ::core::convert::From<&::mbd::__private::Vector<#d>> for #state_struct {
            fn from(y: &::mbd::__private::Vector<#d>) -> Self {
                #state_struct { #(#q_ids: y[#q_idx],)* #(#qd_ids: y[#qd_idx],)* }
            }
        }
        impl ::core::convert::From<#state_struct> for ::mbd::__private::Vector<#d> {
            fn from(s: #state_struct) -> Self {
                let mut y = ::mbd::__private::Vector::<#d>::zeros();
                #(y[#q_idx] = s.#q_ids;)*
                #(y[#qd_idx] = s.#qd_ids;)*
                y
            }
        }
        #[allow(unused_variables, unused_mut, clippy::all, reason = "generated straight-line code")]
        impl #ident {
            /// Free coordinates.
            pub const DOF: usize = #n;
            /// What the derive generated for this model, and how many statements.
            pub const GENERATED: ::mbd::__private::Generated = ::mbd::__private::Generated {
                parts: &[#(#part_names),*],
                statements: #statements,
                constraints: #m,
            };
            #check_parameters
            /// The initial state `[q; qd]` given by `#[init(..)]` (zero where not given; in the
            /// augmented form the positions not given are assembled onto the constraints from
            /// zero and the rates not given follow from the velocity constraints).
            pub fn initial_state(&self) -> ::mbd::__private::Vector<#d> {
                let t = 0.0_f64;
                #init_s
                #init_v
                #init_rates
                y
            }
        }
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic, reason = "generated straight-line code")]
        const _: () = {
            #mechanism_impl
            #constrained_impl
            #ode_impl
        };
        #outputs
        #events
        #frictions
        #linear
    }
}
