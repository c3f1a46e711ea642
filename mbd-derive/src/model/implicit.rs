//! Residual Jacobians for implicit methods: `R = M qdd + Phi_q^T lambda - f` and
//! `C = Phi_q qdd - gamma`, differentiated by `q` and `qd`.

use super::ResidualJacobian;
use super::constraints::InFree;
use crate::sym::{Expr, Graph, Sym};

pub(super) fn residual_jacobian(
    g: &mut Graph,
    (mass, forces): (&[Vec<Expr>], &[Expr]),
    con: &InFree,
    (qsyms, qd, qdd): (&[Sym], &[Expr], &[Expr]),
) -> ResidualJacobian {
    let (n, m_con) = (forces.len(), con.lambdas.len());
    let qdsyms: Vec<Sym> = qd.iter().map(|e| g.as_sym(*e).expect("symbol")).collect();
    let mut r = Vec::new();
    for a in 0..n {
        let ma = g.dot(&mass[a], qdd);
        let mut ra = g.sub(ma, forces[a]);
        for k in 0..m_con {
            let pl = g.mul(con.phi_q[k][a], con.lambdas[k]);
            ra = g.add(ra, pl);
        }
        r.push(ra);
    }
    let c: Vec<Expr> = (0..m_con)
        .map(|k| {
            let pa = g.dot(&con.phi_q[k], qdd);
            g.sub(pa, con.gamma[k])
        })
        .collect();
    let jac = |g: &mut Graph, rows: &[Expr], by: &[Sym]| -> Vec<Vec<Expr>> {
        rows.iter()
            .map(|e| by.iter().map(|s| g.diff(*e, *s)).collect())
            .collect()
    };
    ResidualJacobian {
        r_q: jac(g, &r, qsyms),
        r_qd: jac(g, &r, &qdsyms),
        c_q: jac(g, &c, qsyms),
        c_qd: jac(g, &c, &qdsyms),
    }
}
