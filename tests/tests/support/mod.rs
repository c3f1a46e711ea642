//! A four-bar reduced to its crank angle by hand, the reference of the closed-loop tests.
//!
//! Four-bar `(a, b, c, d)`: crank `th` about the origin, coupler `be`, rocker `ga` about
//! `(d, 0)`, all absolute angles, uniform bars of mass `m`; the rocker tip is the two-circle
//! intersection (`+` the elbow above `AD`). The rate equations solved by Cramer's rule give
//! `be' = kb th'`, `ga' = kg th'`; with one coordinate, Lagrange's equation is
//! `J th'' + J'(th) th'^2 / 2 + V'(th) = 0`, `J = sum m |dp/dth|^2 + I (dphi/dth)^2` over the
//! bodies, `V` gravity's potential; `J'` by a central difference of the analytic `J`.
#![allow(
    dead_code,
    reason = "each test file uses the part of the reference it needs"
)]

#[derive(Clone, Copy)]
pub struct Bar4 {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub m: f64,
    pub g: f64,
}

impl Bar4 {
    /// `(be, ga)` at crank angle `th`, elbow `sign` (+1 above `AD`).
    pub fn close(&self, th: f64, sign: f64) -> (f64, f64) {
        let (ax, ay) = (self.a * th.cos(), self.a * th.sin());
        let (dx, dy) = (self.d - ax, -ay);
        let l = dx.hypot(dy);
        let alpha = ((self.b * self.b + l * l - self.c * self.c) / (2.0 * self.b * l)).acos();
        let be = dy.atan2(dx) + sign * alpha;
        let (cx, cy) = (ax + self.b * be.cos(), ay + self.b * be.sin());
        (be, cy.atan2(cx - self.d))
    }

    /// `(kb, kg)`: `be' / th'` and `ga' / th'` by Cramer's rule on the rate equations.
    pub fn rates(&self, th: f64, be: f64, ga: f64) -> (f64, f64) {
        let (j11, j12, j21, j22) = (
            -self.b * be.sin(),
            self.c * ga.sin(),
            self.b * be.cos(),
            -self.c * ga.cos(),
        );
        let (r1, r2) = (self.a * th.sin(), -self.a * th.cos());
        let det = j11 * j22 - j12 * j21;
        ((r1 * j22 - j12 * r2) / det, (j11 * r2 - j21 * r1) / det)
    }

    /// The generalised inertia `J(th)` and gravity's `dV/dth`.
    pub fn inertia_and_gravity(&self, th: f64, sign: f64) -> (f64, f64) {
        let (a, b, c, m) = (self.a, self.b, self.c, self.m);
        let (be, ga) = self.close(th, sign);
        let (kb, kg) = self.rates(th, be, ga);
        let crank = (-a / 2.0 * th.sin(), a / 2.0 * th.cos());
        let coupler = (
            -a * th.sin() - b / 2.0 * be.sin() * kb,
            a * th.cos() + b / 2.0 * be.cos() * kb,
        );
        let rocker = (-c / 2.0 * ga.sin() * kg, c / 2.0 * ga.cos() * kg);
        let sq = |v: (f64, f64)| v.0 * v.0 + v.1 * v.1;
        let j = m * (sq(crank) + sq(coupler) + sq(rocker))
            + m * a * a / 12.0
            + m * b * b / 12.0 * kb * kb
            + m * c * c / 12.0 * kg * kg;
        (j, m * self.g * (crank.1 + coupler.1 + rocker.1))
    }

    /// Gravity's potential `m g` times the mass centres' heights.
    pub fn potential(&self, th: f64, sign: f64) -> f64 {
        let (be, ga) = self.close(th, sign);
        let heights = self.a / 2.0 * th.sin()
            + self.a * th.sin()
            + self.b / 2.0 * be.sin()
            + self.c / 2.0 * ga.sin();
        self.m * self.g * heights
    }

    /// `th''` by Lagrange's equation in the crank angle.
    pub fn crank_acceleration(&self, th: f64, thd: f64, sign: f64) -> f64 {
        let h = 1e-5;
        let (j, dv) = self.inertia_and_gravity(th, sign);
        let dj = (self.inertia_and_gravity(th + h, sign).0
            - self.inertia_and_gravity(th - h, sign).0)
            / (2.0 * h);
        -(0.5 * dj * thd * thd + dv) / j
    }
}
