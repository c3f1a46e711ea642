//! The ball joint: a spherical joint in modified Rodrigues parameters (MRP), the chart of
//! the rotation group that has no singularity where Euler angles have theirs.
//!
//! A rotation by `phi` about the unit axis `n` has the coordinates `sigma = tan(phi / 4) n`.
//! With `s2 = sigma . sigma` and `[a]x` the cross-product matrix (Shuster, "A survey of
//! attitude representations", J. Astronaut. Sci. 41, 1993, sec. 6.3; Schaub and Junkins,
//! "Analytical Mechanics of Space Systems", sec. 3.7):
//!
//! - child-to-parent rotation `R = 1 + (8 [sigma]x^2 + 4 (1 - s2) [sigma]x) / (1 + s2)^2`;
//! - the child's angular velocity relative to the parent, in the child's frame,
//!   `w = E sigma'` with `E = 4 B^T / (1 + s2)^2` and
//!   `B = (1 - s2) 1 + 2 [sigma]x + 2 sigma sigma^T`; `B B^T = (1 + s2)^2 1`, so
//!   `sigma' = B w / 4` and `E` is invertible for every finite `sigma`;
//! - `E' sigma' = -E B' w / 4` (from `sigma' = B w / 4`), with
//!   `B' = -2 (sigma . sigma') 1 + 2 [sigma']x + 2 (sigma' sigma^T + sigma sigma'^T)`.
//!
//! Everything is rational in `sigma`: no `sin`/`cos`, no `0/0` at the identity. The chart
//! covers every rotation but the full turn `phi = 2π` (`|sigma| -> oo`); the *shadow set*
//! `-sigma / s2` describes the same rotation with `phi - 2π`, so switching to it whenever
//! `s2 > 1` (`phi > π`) keeps `|sigma| <= 1`. The integrators do that where they project an
//! accepted step (`mbd::chart::shadow`); the orientation, the angular velocity and so every
//! output are the same on both sides of the switch.

use crate::lower;
use crate::parse::Mechanism;
use crate::sym::{Expr, Graph};
use proc_macro2::TokenStream;
use quote::quote;

type V3 = [Expr; 3];
type M3 = [[Expr; 3]; 3];

/// `[a]x`.
fn skew(g: &mut Graph, a: V3) -> M3 {
    let z = g.zero();
    let n = a.map(|x| g.neg(x));
    [[z, n[2], a[1]], [a[2], z, n[0]], [n[1], a[0], z]]
}

/// `sum_k c_k m_k` entry by entry.
fn combine(g: &mut Graph, terms: &[(Expr, M3)]) -> M3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|k| {
            let parts: Vec<Expr> = terms.iter().map(|(c, m)| g.mul(*c, m[i][k])).collect();
            g.sum(parts)
        })
    })
}

fn identity(g: &mut Graph) -> M3 {
    let (o, z) = (g.one(), g.zero());
    [[o, z, z], [z, o, z], [z, z, o]]
}

fn outer(g: &mut Graph, a: V3, b: V3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|k| g.mul(a[i], b[k])))
}

/// `1 + s2`.
fn one_plus_s2(g: &mut Graph, sigma: V3) -> Expr {
    let s2 = g.dot(&sigma, &sigma);
    let one = g.one();
    g.add(one, s2)
}

/// The child-to-parent rotation `R(sigma)`.
pub fn rotation(g: &mut Graph, sigma: V3) -> M3 {
    let sx = skew(g, sigma);
    let sx2 = lower::matmul(g, &sx, &sx);
    let p = one_plus_s2(g, sigma);
    let p2 = g.mul(p, p);
    let one = g.one();
    let two = g.constant(2.0);
    let (c8, c4) = (g.constant(8.0), g.constant(4.0));
    let k2 = g.div(c8, p2);
    let one_minus = g.sub(two, p); // 1 - s2
    let num = g.mul(c4, one_minus);
    let k1 = g.div(num, p2);
    let id = identity(g);
    combine(g, &[(one, id), (k1, sx), (k2, sx2)])
}

/// `B(sigma) = (1 - s2) 1 + 2 [sigma]x + 2 sigma sigma^T`: `sigma' = B w / 4`.
pub fn b_matrix(g: &mut Graph, sigma: V3) -> M3 {
    let s2 = g.dot(&sigma, &sigma);
    let one = g.one();
    let one_minus = g.sub(one, s2);
    let two = g.constant(2.0);
    let (id, sx, ss) = (identity(g), skew(g, sigma), outer(g, sigma, sigma));
    combine(g, &[(one_minus, id), (two, sx), (two, ss)])
}

/// `E(sigma) = 4 B^T / (1 + s2)^2`: the joint's angular velocity `w = E sigma'` in the
/// child's frame; its columns are the joint's motion subspace.
pub fn rate_matrix(g: &mut Graph, sigma: V3) -> M3 {
    let b = b_matrix(g, sigma);
    let p = one_plus_s2(g, sigma);
    let p2 = g.mul(p, p);
    let c4 = g.constant(4.0);
    let k = g.div(c4, p2);
    std::array::from_fn(|i| std::array::from_fn(|j| g.mul(k, b[j][i])))
}

/// `B'(sigma, sigma')`, the time derivative of `B`.
fn b_dot(g: &mut Graph, sigma: V3, rate: V3) -> M3 {
    let sd = g.dot(&sigma, &rate);
    let m2 = g.constant(-2.0);
    let k = g.mul(m2, sd);
    let two = g.constant(2.0);
    let (id, rx) = (identity(g), skew(g, rate));
    let (a, b) = (outer(g, rate, sigma), outer(g, sigma, rate));
    combine(g, &[(k, id), (two, rx), (two, a), (two, b)])
}

fn mat_vec(g: &mut Graph, m: &M3, v: V3) -> V3 {
    [g.dot(&m[0], &v), g.dot(&m[1], &v), g.dot(&m[2], &v)]
}

/// The joint's angular velocity `w = E sigma'` (child frame).
pub fn omega(g: &mut Graph, sigma: V3, rate: V3) -> V3 {
    let e = rate_matrix(g, sigma);
    mat_vec(g, &e, rate)
}

/// `E' sigma' = -E B' w / 4`: the angular acceleration of the joint at `sigma'' = 0`.
pub fn bias(g: &mut Graph, sigma: V3, rate: V3) -> V3 {
    let e = rate_matrix(g, sigma);
    let w = mat_vec(g, &e, rate);
    let bd = b_dot(g, sigma, rate);
    let bw = mat_vec(g, &bd, w);
    let ebw = mat_vec(g, &e, bw);
    let k = g.constant(-0.25);
    ebw.map(|x| g.mul(k, x))
}

/// `sigma'' = (B w' + B' w) / 4` from the joint's angular acceleration `w'` (child frame).
pub fn sigma_dd(g: &mut Graph, sigma: V3, rate: V3, w_dot: V3) -> V3 {
    let e = rate_matrix(g, sigma);
    let w = mat_vec(g, &e, rate);
    let (b, bd) = (b_matrix(g, sigma), b_dot(g, sigma, rate));
    let (bwd, bdw) = (mat_vec(g, &b, w_dot), mat_vec(g, &bd, w));
    let k = g.constant(0.25);
    std::array::from_fn(|i| {
        let s = g.add(bwd[i], bdw[i]);
        g.mul(k, s)
    })
}

/// The moment about the joint that does the work of the generalised forces `tau` on
/// `sigma`: `tau . sigma' = (B^T tau / 4) . w`.
pub fn moment(g: &mut Graph, sigma: V3, tau: V3) -> V3 {
    let b = b_matrix(g, sigma);
    let k = g.constant(0.25);
    std::array::from_fn(|i| {
        let col = [b[0][i], b[1][i], b[2][i]];
        let d = g.dot(&col, &tau);
        g.mul(k, d)
    })
}

/// The generated chart switch of a model's ball joints and free joints' rotations (`None`:
/// it has none): each joint's state indices, for `mbd::chart::shadow` in
/// `OdeSystem::project`. A ball joint whose coordinates are not all free coordinates (a closure made one dependent) keeps its chart.
pub fn switch(ast: &Mechanism, free: &[syn::Ident], n: usize) -> Option<TokenStream> {
    let balls = charts(ast, free)?;
    Some(quote!(::mbd::__private::chart::shadow(y, #n, #balls);))
}

/// The same joints' coordinate indices as a slice literal `&[[a, b, c], ..]` (`None`: it has
/// none), for `rotation_charts`, through which generalized-alpha switches its positions,
/// rates and accelerations (`mbd::chart::shadow_motion`).
pub fn charts(ast: &Mechanism, free: &[syn::Ident]) -> Option<TokenStream> {
    let balls: Vec<TokenStream> = ast
        .tree
        .iter()
        .filter_map(|tb| {
            let [a, b, c] = tb.joint.ball_coords()?;
            let at = |x: &syn::Ident| free.iter().position(|f| f == x);
            let (a, b, c) = (at(a)?, at(b)?, at(c)?);
            Some(quote!([#a, #b, #c]))
        })
        .collect();
    (!balls.is_empty()).then(|| quote!(&[#(#balls),*]))
}
