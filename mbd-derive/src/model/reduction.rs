//! Reduction from full to free coordinates in one pass over the shared graph: driven
//! `z -> s(t)` (with `s'`, `s''`, `s'''`), relaxed `z -> 0`, dependent rates by the closure
//! (minimal coordinates: the equations projected first, the closed form substituted last); the
//! driven coordinates' known accelerations move to the right side.

use super::inertial::Inertial;
use super::scope::Scope;
use super::{Coord, CoordKind, Role};
use crate::spatial;
use crate::sym::{Expr, Sym};
use crate::tree;
use crate::velocity;
use std::collections::HashMap;

/// The equations in the free coordinates.
pub(super) struct Reduced {
    /// Full-coordinate symbol -> its value in the free coordinates (for outputs later).
    pub map: HashMap<Sym, Expr>,
    /// Indices of the free coordinates among the full ones, in state order.
    pub free_idx: Vec<usize>,
    pub mass: Vec<Vec<Expr>>,
    pub forces: Vec<Expr>,
    pub energy: Expr,
    pub phi: Vec<Expr>,
    pub recursive_qdd: Option<Vec<Expr>>,
    pub mass_times: Option<Vec<Expr>>,
    /// `M qdd - f` over the free coordinates by recursive Newton-Euler (pure trees).
    pub inverse: Option<Vec<Expr>>,
    pub rolled: Option<(tree::Rolled, usize)>,
}

pub(super) fn reduce(
    scope: &mut Scope,
    coords: &[Coord],
    inertial: &mut Inertial,
    phi_full: &[Expr],
    minimal: Option<&velocity::Minimal>,
) -> Reduced {
    if minimal.is_some() {
        super::minimal::project(
            &mut scope.g,
            coords,
            &mut inertial.m_full,
            &mut inertial.f_full,
        );
    }
    let map = reduction_map(scope, coords);
    let g = &mut scope.g;
    let zero = g.zero();
    let free_idx: Vec<usize> = coords
        .iter()
        .enumerate()
        .filter(|(_, c)| matches!(c.kind, CoordKind::Free))
        .map(|(i, _)| i)
        .collect();
    let n = free_idx.len();
    let rolled = inertial.rolled.take();
    let Inertial {
        m_full,
        f_full,
        energy_full,
        recursive,
        lazy_mass,
        qdd_recursive,
        steps,
        inverse_full,
        ..
    } = inertial;
    let (recursive, lazy_mass) = (*recursive, *lazy_mass);
    // Reduce everything in one pass over the shared graph (one rebuild, not one per entry).
    let mut full_rows = Vec::with_capacity(n * n + n + 1 + phi_full.len());
    for &i in &free_idx {
        full_rows.extend(free_idx.iter().map(|&j| m_full[i][j]));
    }
    // Move the driven coordinates' known accelerations to the right side (through `M a`
    // where `M` is not written out).
    let driven: Vec<Expr> = coords
        .iter()
        .map(|c| match c.kind {
            CoordKind::Driven(_) => c.zdd,
            _ => zero,
        })
        .collect();
    let driven_rows = (lazy_mass && driven.iter().any(|&a| !g.is_zero(a)))
        .then(|| spatial::mass_times(g, steps, &driven));
    for &i in &free_idx {
        let mut fi = f_full[i];
        if let Some(rows) = &driven_rows {
            fi = g.sub(fi, rows[i]);
        } else if !lazy_mass {
            for (j, c) in coords.iter().enumerate() {
                if let CoordKind::Driven(_) = c.kind {
                    let mz = g.mul(m_full[i][j], c.zdd);
                    fi = g.sub(fi, mz);
                }
            }
        }
        full_rows.push(fi);
    }
    full_rows.push(*energy_full);
    full_rows.extend(phi_full);
    let n_rows = full_rows.len();
    if recursive {
        // Every free coordinate is a joint's (a pure tree): the recursion gives each one.
        full_rows.extend(free_idx.iter().map(|&i| qdd_recursive[i].unwrap_or(zero)));
    }
    // A rolled chain's expressions around its loops (the carried values' starts) are in
    // full coordinates too.
    let run_inits: Vec<Expr> = rolled
        .iter()
        .flat_map(|r| r.loops.iter())
        .flat_map(|l| l.carried.iter().map(|c| c.1))
        .collect();
    let n_rows_recursive = full_rows.len();
    full_rows.extend(&run_inits);
    // A long tree's mass matrix as `M qdd` (free coordinates' accelerations; driven ones at
    // rest), formed column by column at run time: O(n) code instead of O(n d) entries.
    let n_rows_inits = full_rows.len();
    if lazy_mass {
        let accel: Vec<Expr> = coords
            .iter()
            .map(|c| match c.kind {
                CoordKind::Free => c.zdd,
                _ => zero,
            })
            .collect();
        let rows = spatial::mass_times(g, steps, &accel);
        full_rows.extend(free_idx.iter().map(|&i| rows[i]));
    }
    let n_rows_lazy = full_rows.len();
    if let Some(rows) = inverse_full {
        full_rows.extend(free_idx.iter().map(|&i| rows[i]));
    }
    let mut reduced = g.substitute_all(&full_rows, &map);
    if let Some(min) = minimal {
        reduced = min.reduced(g, &map).close(g, &reduced);
    }
    let inverse = inverse_full
        .is_some()
        .then(|| reduced.split_off(n_rows_lazy));
    let mass_times = lazy_mass.then(|| reduced.split_off(n_rows_inits));
    let reduced_inits = reduced.split_off(n_rows_recursive);
    let recursive_qdd = recursive.then(|| reduced.split_off(n_rows));
    let rolled = rolled.map(|r| roll(scope, r, reduced_inits, &free_idx));
    let mass: Vec<Vec<Expr>> = reduced[..n * n]
        .chunks(n.max(1))
        .take(n)
        .map(<[Expr]>::to_vec)
        .collect();
    Reduced {
        map,
        forces: reduced[n * n..n * n + n].to_vec(),
        energy: reduced[n * n + n],
        phi: reduced[n * n + n + 1..].to_vec(),
        mass,
        free_idx,
        recursive_qdd,
        mass_times,
        inverse,
        rolled,
    }
}

/// Every driven, relaxed and dependent coordinate's symbols -> their values.
fn reduction_map(scope: &mut Scope, coords: &[Coord]) -> HashMap<Sym, Expr> {
    let g = &mut scope.g;
    let ts = g.as_sym(scope.t).expect("symbol");
    let zero = g.zero();
    let mut map: HashMap<Sym, Expr> = HashMap::new();
    // Dependent coordinates last: their closed forms may name relaxed and driven ones.
    let dependent = |c: &&Coord| matches!(c.kind, CoordKind::Dependent(_));
    let dependent_last =
        (coords.iter().filter(|c| !dependent(c))).chain(coords.iter().filter(dependent));
    for c in dependent_last {
        let (z, zd, zdd, zddd) = match &c.kind {
            CoordKind::Free => continue,
            CoordKind::Driven(law) => {
                let d1 = g.diff(*law, ts);
                let d2 = g.diff(d1, ts);
                let d3 = g.diff(d2, ts);
                (*law, d1, d2, d3)
            }
            CoordKind::Relaxed => (zero, zero, zero, zero),
            // The position stays a symbol until `velocity::Minimal::close`; its rates are
            // reduced like every other expression.
            CoordKind::Dependent([_, hd, hdd]) => {
                let [hd, hdd] = [*hd, *hdd].map(|e| g.substitute(e, &map));
                (c.z, hd, hdd, zero)
            }
        };
        for (s, v) in [(c.z, z), (c.zd, zd), (c.zdd, zdd), (c.zddd, zddd)] {
            map.insert(g.as_sym(s).expect("symbol"), v);
        }
    }
    map
}

/// A rolled chain with its loops' reduced starts, and the state index of its first joint.
fn roll(
    scope: &mut Scope,
    mut r: tree::Rolled,
    reduced_inits: Vec<Expr>,
    free_idx: &[usize],
) -> (tree::Rolled, usize) {
    let mut inits = reduced_inits.into_iter();
    for l in &mut r.loops {
        for c in &mut l.carried {
            c.1 = inits.next().expect("one reduced start per carried value");
        }
    }
    for (e, per_link) in r.placeholders() {
        scope.role(e, Role::RunLocal { per_link });
    }
    let first = free_idx.iter().position(|&i| i == r.first_coord);
    let consecutive = first.is_some_and(|f| {
        (0..r.len * r.per).all(|k| free_idx.get(f + k) == Some(&(r.first_coord + k)))
    });
    match (first, consecutive) {
        (Some(f), true) => (r, f),
        _ => unreachable!("a rolled run's joints are free, consecutive coordinates"),
    }
}
