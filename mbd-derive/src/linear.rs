//! Linear models and parameter sensitivities, exact: with `#[mechanism(jacobian)]` the derive
//! also differentiates the residuals `R = M qdd + Phi_q^T lambda - f`, `C = Phi_q qdd -
//! gamma` by every parameter (the struct's fields) and the outputs by `q`, `qd`, `qdd`,
//! `lambda` and the parameters, and generates `impl Parametric` (mbd-core
//! `analysis::sensitivity`), whose `linear_parts` solves for the derivatives of the
//! accelerations and applies the chain rule.
//!
//! `#[input(u, ..)]` names parameters that are the model's inputs: generalised forces,
//! torques, drive accelerations written with them in loads, forces, drives. An input is a
//! field like any parameter, so the plain right-hand side uses the struct's value (0 for
//! an unforced model) and `B = d(y')/du` is a set of columns of `d(y')/dp`.

use crate::codegen::Block;
use crate::model::{Equations, OutputEq};
use crate::parse::{Errors, Mechanism};
use crate::sym::{Expr, Graph, Sym};
use proc_macro2::TokenStream;
use quote::quote;
use syn::Ident;

/// The parameter derivatives of a model (`N` coordinates, `M` constraints, `P` parameters,
/// `K` outputs).
pub struct LinearEq {
    pub params: Vec<Ident>,
    /// Indices into `params`.
    pub inputs: Vec<usize>,
    /// `dR/dp` (`N x P`), `dC/dp` (`M x P`).
    pub r_p: Vec<Vec<Expr>>,
    pub c_p: Vec<Vec<Expr>>,
    /// The outputs' partial derivatives (`K x N`, `K x N`, `K x N`, `K x M`, `K x P`).
    pub o_q: Vec<Vec<Expr>>,
    pub o_qd: Vec<Vec<Expr>>,
    pub o_qdd: Vec<Vec<Expr>>,
    pub o_l: Vec<Vec<Expr>>,
    pub o_p: Vec<Vec<Expr>>,
}

/// What [`derive`] reads of the mechanics.
pub struct Parts<'a> {
    pub mass: &'a [Vec<Expr>],
    pub forces: &'a [Expr],
    pub phi_q: &'a [Vec<Expr>],
    pub gamma: &'a [Expr],
    pub q: &'a [Sym],
    pub qd: &'a [Expr],
    pub qdd: &'a [Expr],
    pub lambdas: &'a [Expr],
    pub outputs: &'a [OutputEq],
}

/// The inputs as parameter indices: each must name a parameter, once, and needs the
/// generated Jacobian (spanned errors otherwise).
fn inputs<E>(ast: &Mechanism<E>, errors: &mut Errors) -> Vec<usize> {
    let mut out = Vec::new();
    for u in &ast.inputs {
        match ast.params.iter().position(|p| p.name == *u) {
            None => errors.at(
                u.span(),
                format!(
                    "input `{u}` is not a parameter: declare it as an `f64` field of the struct"
                ),
            ),
            Some(i) if out.contains(&i) => {
                errors.at(u.span(), format!("input `{u}` is declared twice"))
            }
            Some(i) => out.push(i),
        }
        if !ast.jacobian {
            errors.at(
                u.span(),
                "inputs need the generated derivatives: add `#[mechanism(jacobian)]`",
            );
        }
    }
    out
}

/// The parameter derivatives, when the model asks for exact Jacobians.
pub fn derive<E>(
    g: &mut Graph,
    ast: &Mechanism<E>,
    errors: &mut Errors,
    parts: Parts,
) -> Option<LinearEq> {
    let inputs = inputs(ast, errors);
    if !ast.jacobian {
        return None;
    }
    let sym = |g: &Graph, e: &Expr| g.as_sym(*e).expect("symbol");
    let params: Vec<Ident> = ast.params.iter().map(|p| p.name.clone()).collect();
    let psyms: Vec<Sym> = params
        .iter()
        .map(|p| {
            let e = g.symbol(&p.to_string());
            sym(g, &e)
        })
        .collect();
    let (n, m) = (parts.forces.len(), parts.gamma.len());
    let r: Vec<Expr> = (0..n)
        .map(|a| {
            let ma = g.dot(&parts.mass[a], parts.qdd);
            let mut ra = g.sub(ma, parts.forces[a]);
            for k in 0..m {
                let pl = g.mul(parts.phi_q[k][a], parts.lambdas[k]);
                ra = g.add(ra, pl);
            }
            ra
        })
        .collect();
    let c: Vec<Expr> = (0..m)
        .map(|k| {
            let pa = g.dot(&parts.phi_q[k], parts.qdd);
            g.sub(pa, parts.gamma[k])
        })
        .collect();
    let jac = |g: &mut Graph, rows: &[Expr], by: &[Sym]| -> Vec<Vec<Expr>> {
        rows.iter()
            .map(|e| by.iter().map(|s| g.diff(*e, *s)).collect())
            .collect()
    };
    let qd: Vec<Sym> = parts.qd.iter().map(|e| sym(g, e)).collect();
    let qdd: Vec<Sym> = parts.qdd.iter().map(|e| sym(g, e)).collect();
    let lambdas: Vec<Sym> = parts.lambdas.iter().map(|e| sym(g, e)).collect();
    let outs: Vec<Expr> = parts.outputs.iter().map(|o| o.expr).collect();
    Some(LinearEq {
        params,
        inputs,
        r_p: jac(g, &r, &psyms),
        c_p: jac(g, &c, &psyms),
        o_q: jac(g, &outs, parts.q),
        o_qd: jac(g, &outs, &qd),
        o_qdd: jac(g, &outs, &qdd),
        o_l: jac(g, &outs, &lambdas),
        o_p: jac(g, &outs, &psyms),
    })
}

/// `impl Parametric` (one shared block for the residual and output derivatives), and its
/// statement count. `split` binds `q`, `qd`; `solve` binds `qdd`, `lambda`.
pub fn emit(
    eq: &Equations,
    ident: &Ident,
    split: &TokenStream,
    solve: &TokenStream,
    direction: &Option<TokenStream>,
) -> Option<(TokenStream, usize)> {
    let (lin, jac) = (eq.linear.as_ref()?, eq.jacobian.as_ref()?);
    let (n, m, p, k) = (
        eq.free.len(),
        eq.phi.len(),
        lin.params.len(),
        eq.outputs.len(),
    );
    let (d, a) = (2 * n, n + m);
    let outs: Vec<Expr> = eq.outputs.iter().map(|o| o.expr).collect();
    let mut roots: Vec<Expr> = eq.mass.iter().flatten().copied().collect();
    roots.extend(outs.iter().copied());
    let mats = [
        ("phi_q", m, n, &eq.phi_q),
        ("r_q", n, n, &jac.r_q),
        ("r_qd", n, n, &jac.r_qd),
        ("c_q", m, n, &jac.c_q),
        ("c_qd", m, n, &jac.c_qd),
        ("r_p", n, p, &lin.r_p),
        ("c_p", m, p, &lin.c_p),
        ("o_q", k, n, &lin.o_q),
        ("o_qd", k, n, &lin.o_qd),
        ("o_qdd", k, n, &lin.o_qdd),
        ("o_l", k, m, &lin.o_l),
        ("o_p", k, p, &lin.o_p),
    ];
    for (_, _, _, e) in &mats {
        roots.extend(e.iter().flatten());
    }
    let b = Block::new(eq, &roots);
    let stmts = b.stmts();
    let mass = b.matrix("mass", n, n, &eq.mass);
    let out = b.vector("out", k, &outs);
    let fills = mats.iter().map(|(name, r, c, e)| b.matrix(name, *r, *c, e));
    let names = mats
        .iter()
        .map(|(name, ..)| quote::format_ident!("{}", name));
    let params: Vec<String> = lin.params.iter().map(|p| p.to_string()).collect();
    let inputs = &lin.inputs;
    let out_names: Vec<String> = eq.outputs.iter().map(|o| o.name.to_string()).collect();
    let code = quote! {
        #[automatically_derived]
        #[allow(unused_variables, unused_mut, clippy::all, clippy::pedantic, reason = "generated straight-line code")]
        impl ::mbd::__private::analysis::sensitivity::Parametric<#d> for #ident {
            const PARAMETERS: &'static [&'static str] = &[#(#params),*];
            const INPUTS: &'static [usize] = &[#(#inputs),*];
            const OUTPUT_NAMES: &'static [&'static str] = &[#(#out_names),*];
            fn linear_parts(&self, t: f64, y: &::mbd::__private::Vector<#d>)
                -> ::mbd::__private::Result<::mbd::__private::analysis::sensitivity::LinearParts> {
                #split
                #solve
                #direction
                #stmts #mass #out #(#fills)*
                ::mbd::__private::analysis::sensitivity::Residuals::<#n, #m, #p, #k> {
                    mass, qd, qdd, out, #(#names,)*
                }
                .assemble::<#a>(t)
            }
        }
    };
    Some((code, b.len()))
}
