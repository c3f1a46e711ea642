//! Joints that close a loop of a joint tree (`#[close(..)]`): their constraint rows.
//!
//! Each side of the joint is a body frame in ground coordinates (origin `o`, rotation `R`,
//! body to ground) or the ground itself, with a point and, for an axial joint, body-fixed
//! directions in that frame. With `d = p_a - p_b` (the two points in the ground frame) and
//! `u = R u_local` for every direction:
//!
//! - spherical (the default in space): `d = 0`, three rows;
//! - revolute: `d = 0` and the axes parallel, `u_a . n1_b = u_a . n2_b = 0` with `n1_b`,
//!   `n2_b` two unit directions of body `b` normal to `u_b`, five rows;
//! - universal: `d = 0` and the two axes (the cross's two pins) perpendicular, `u_a . u_b = 0`,
//!   four rows;
//! - prismatic: `p_a` on the line through `p_b` along `u_b`, `d . n_b = d . m_b = 0`
//!   (`m_b = u_b x n_b`), and the orientation locked, `u_a . n_b = u_a . m_b = n_a . m_b = 0`
//!   (the axes and the normals parallel), five rows.
//!
//! Every direction is a constant vector (numbers and named constants), normalised here; the
//! normal pair of a revolute joint's `u_b` is picked numerically, so every row is a
//! well-scaled function whose Jacobian has full rank at the joint's own configurations: no
//! constraint is redundant by construction (a cross product `u_a x u_b = 0` would be three
//! rows of rank two).

use crate::lowered::Term;
use crate::parse::{CloseJoint, Closure, Dim, Errors};
use crate::sym::{Expr, Graph};

/// One side of a closing joint: the body frame's rotation (body to ground; `None`: the
/// ground) and the joint point in ground coordinates.
pub struct Side {
    pub rot: Option<[[Expr; 3]; 3]>,
    pub point: Vec<Expr>,
}

/// How many equations a `close` adds (before its rows are built: for the skeleton).
pub fn equations<E>(cl: &Closure<E>, dim: Dim) -> usize {
    match (dim, cl.joint.map(|j| j.0)) {
        (Dim::Planar, _) => 2,
        (Dim::Spatial, None | Some(CloseJoint::Spherical)) => 3,
        (Dim::Spatial, Some(CloseJoint::Universal)) => 4,
        (Dim::Spatial, Some(CloseJoint::Revolute | CloseJoint::Prismatic)) => 5,
    }
}

/// Lowers a term to a constant vector of three components (`None` after an
/// error).
pub type Lower3<'a> = dyn FnMut(&mut Graph, &mut Errors, &Term) -> Option<Vec<Expr>> + 'a;

/// The arguments a joint kind takes beyond the points, and which it requires.
fn check_keys(cl: &Closure<Term>, dim: Dim, errors: &mut Errors) -> Option<CloseJoint> {
    if let (Some(a), Some(b)) = (&cl.a, &cl.b)
        && a == b
    {
        errors.at(b.span(), format!("`{b}` closed on itself: two points of one body never move relative to each other, so the joint either always holds or never does; close it on another body or `ground`"));
        return None;
    }
    let given = [
        ("axis_a", &cl.axis_a),
        ("axis_b", &cl.axis_b),
        ("normal_a", &cl.normal_a),
        ("normal_b", &cl.normal_b),
    ];
    let (kind, span) = match (dim, cl.joint) {
        (Dim::Planar, None | Some((CloseJoint::Revolute, _))) => {
            let mut ok = true;
            for (key, e) in given.iter().filter_map(|(k, e)| Some((k, e.as_ref()?))) {
                ok = false;
                errors.over(e, format!("`{key}` is spatial: a planar `close` is a revolute joint about the plane's normal"));
            }
            return ok.then_some(CloseJoint::Revolute);
        }
        (Dim::Planar, Some((_, span))) => {
            errors.at(span, "a planar `close` is a revolute joint (two equations); `spherical`, `universal` and `prismatic` closing joints are spatial (`#[mechanism(spatial)]`)");
            return None;
        }
        // The span is for a missing key, and a spherical joint needs none.
        (Dim::Spatial, None) => (CloseJoint::Spherical, proc_macro2::Span::call_site()),
        (Dim::Spatial, Some(j)) => j,
    };
    let needs: &[&str] = match kind {
        CloseJoint::Spherical => &[],
        CloseJoint::Revolute | CloseJoint::Universal => &["axis_a", "axis_b"],
        CloseJoint::Prismatic => &["axis_a", "axis_b", "normal_a", "normal_b"],
    };
    let what = match kind {
        CloseJoint::Spherical => "a spherical",
        CloseJoint::Revolute => "a revolute",
        CloseJoint::Universal => "a universal",
        CloseJoint::Prismatic => "a prismatic",
    };
    let mut ok = true;
    for (key, e) in given {
        match (needs.contains(&key), e) {
            (true, None) => {
                ok = false;
                errors.at(
                    span,
                    format!("{what} `close` needs `{key}`: {}", meaning(key)),
                );
            }
            (false, Some(e)) => {
                ok = false;
                errors.over(
                    e,
                    format!("{what} `close` takes no `{key}` (it takes {})", list(needs)),
                );
            }
            _ => {}
        }
    }
    ok.then_some(kind)
}

fn meaning(key: &str) -> &'static str {
    match key {
        "axis_a" => "the joint axis in body `a`'s frame, e.g. `axis_a = [1.0, 0.0, 0.0]`",
        "axis_b" => "the joint axis in body `b`'s frame, e.g. `axis_b = [1.0, 0.0, 0.0]`",
        "normal_a" => {
            "a direction normal to `axis_a` in body `a`'s frame (it locks the rotation about the axis)"
        }
        _ => {
            "a direction normal to `axis_b` in body `b`'s frame (it locks the rotation about the axis)"
        }
    }
}

fn list(keys: &[&str]) -> String {
    if keys.is_empty() {
        "only the points `at_a`, `at_b`".to_string()
    } else {
        format!("`{}`", keys.join("`, `"))
    }
}

/// A direction as a unit vector of numbers, or a spanned error.
fn direction(
    g: &mut Graph,
    errors: &mut Errors,
    lower: &mut Lower3<'_>,
    e: &Term,
) -> Option<[f64; 3]> {
    let v = lower(g, errors, e)?;
    let Some(v) = v
        .iter()
        .map(|x| g.as_const(*x))
        .collect::<Option<Vec<f64>>>()
    else {
        errors.over(e, "a closing joint's direction is a constant vector (numbers and named constants such as `FRAC_1_SQRT_2`): the derive picks the directions normal to it at compile time");
        return None;
    };
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if !(n > 0.0 && n.is_finite()) {
        errors.over(
            e,
            "a closing joint's direction must be a non-zero finite vector",
        );
        return None;
    }
    Some([v[0] / n, v[1] / n, v[2] / n])
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = dot(v, v).sqrt();
    [v[0] / n, v[1] / n, v[2] / n]
}

/// Two unit directions normal to the unit `u` and to each other, with `n1 x n2 = u`: `n1`
/// from the coordinate axis least aligned with `u` (exact for an axis along `x`, `y`, `z`).
fn normals(u: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let k = (0..3)
        .min_by(|&i, &j| u[i].abs().total_cmp(&u[j].abs()))
        .expect("three");
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let n1 = unit(cross(u, e));
    (n1, cross(u, n1))
}

/// The normal of a prismatic joint made exactly normal to its axis, or an error.
fn normal_to(axis: [f64; 3], normal: [f64; 3], e: &Term, errors: &mut Errors) -> Option<[f64; 3]> {
    let c = dot(axis, normal);
    let n = [
        normal[0] - c * axis[0],
        normal[1] - c * axis[1],
        normal[2] - c * axis[2],
    ];
    if dot(n, n).sqrt() < 1e-6 {
        errors.over(
            e,
            "a prismatic `close`'s normal must not be parallel to its axis",
        );
        return None;
    }
    Some(unit(n))
}

/// `R v` for a side (the ground: `v`).
fn world(g: &mut Graph, side: &Side, v: [f64; 3]) -> Vec<Expr> {
    let v: Vec<Expr> = v.iter().map(|&x| g.constant(x)).collect();
    match &side.rot {
        Some(r) => r.iter().map(|row| g.dot(row, &v)).collect(),
        None => v,
    }
}

/// The constraint rows of one spatial `close`, with its span per row; `None` after an
/// error (reported).
pub fn rows(
    g: &mut Graph,
    errors: &mut Errors,
    cl: &Closure<Term>,
    (a, b): (&Side, &Side),
    lower: &mut Lower3<'_>,
) -> Option<Vec<Expr>> {
    let kind = check_keys(cl, Dim::Spatial, errors)?;
    let d: Vec<Expr> = a
        .point
        .iter()
        .zip(&b.point)
        .map(|(x, y)| g.sub(*x, *y))
        .collect();
    if kind == CloseJoint::Spherical {
        return nonzero(g, errors, cl, d);
    }
    let mut dir = |e: &Option<Term>| {
        let e = e.as_ref().expect("checked by check_keys");
        direction(g, errors, lower, e)
    };
    let (ua, ub) = (dir(&cl.axis_a), dir(&cl.axis_b));
    let (na, nb) = match kind {
        CloseJoint::Prismatic => (dir(&cl.normal_a), dir(&cl.normal_b)),
        _ => (None, None),
    };
    let (ua, ub) = (ua?, ub?);
    let rows = match kind {
        CloseJoint::Spherical => unreachable!("returned above"),
        CloseJoint::Revolute => {
            let (n1, n2) = normals(ub);
            let wa = world(g, a, ua);
            let (w1, w2) = (world(g, b, n1), world(g, b, n2));
            let mut rows = d;
            rows.push(g.dot(&wa, &w1));
            rows.push(g.dot(&wa, &w2));
            rows
        }
        CloseJoint::Universal => {
            let (wa, wb) = (world(g, a, ua), world(g, b, ub));
            let mut rows = d;
            rows.push(g.dot(&wa, &wb));
            rows
        }
        CloseJoint::Prismatic => {
            let na = normal_to(ua, na?, cl.normal_a.as_ref().expect("checked"), errors);
            let nb = normal_to(ub, nb?, cl.normal_b.as_ref().expect("checked"), errors);
            let (na, nb) = (na?, nb?);
            let mb = cross(ub, nb);
            let (wua, wna) = (world(g, a, ua), world(g, a, na));
            let (wnb, wmb) = (world(g, b, nb), world(g, b, mb));
            vec![
                g.dot(&d, &wnb),
                g.dot(&d, &wmb),
                g.dot(&wua, &wnb),
                g.dot(&wua, &wmb),
                g.dot(&wna, &wmb),
            ]
        }
    };
    nonzero(g, errors, cl, rows)
}

/// The rows that are not identically zero, or an error when none is (the joint closes
/// nothing). A row that is zero whatever the coordinates constrains nothing: the tree's own
/// joints keep it (a Sarrus linkage's closing hinge, whose axis the legs keep normal to the
/// plate's; a planar loop written in space), so it is dropped rather than left to make the
/// constraint Jacobian singular everywhere.
fn nonzero(
    g: &Graph,
    errors: &mut Errors,
    cl: &Closure<Term>,
    rows: Vec<Expr>,
) -> Option<Vec<Expr>> {
    let kept: Vec<Expr> = rows.iter().copied().filter(|r| !g.is_zero(*r)).collect();
    if kept.is_empty() {
        errors.over(&cl.tokens, format!("all {} of this joint's equations are identically zero: the tree's own joints already keep what it would (a `close` of a body at its own joint closes no loop); remove it", rows.len()));
        return None;
    }
    Some(kept)
}

/// The rows of a planar `close` (a revolute joint: the two points coincide); `None` after
/// an error (another joint kind, or a direction).
pub fn planar_rows(
    g: &mut Graph,
    errors: &mut Errors,
    cl: &Closure<Term>,
    (a, b): (&Side, &Side),
) -> Option<Vec<Expr>> {
    check_keys(cl, Dim::Planar, errors)?;
    Some(
        a.point
            .iter()
            .zip(&b.point)
            .map(|(x, y)| g.sub(*x, *y))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normals_are_orthonormal_and_right_handed() {
        for u in [
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            unit([1.0, 2.0, -3.0]),
            unit([0.3, 0.3, 0.3]),
        ] {
            let (n1, n2) = normals(u);
            for (x, y) in [(u, n1), (u, n2), (n1, n2)] {
                assert!(dot(x, y).abs() < 1e-15);
            }
            assert!((dot(n1, n1) - 1.0).abs() < 1e-15 && (dot(n2, n2) - 1.0).abs() < 1e-15);
            let c = cross(n1, n2);
            assert!((0..3).all(|i| (c[i] - u[i]).abs() < 1e-15));
        }
    }
}
