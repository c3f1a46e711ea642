//! Mode shapes drawn: one SVG per planar mechanism of the `modes` report, a panel per mode
//! with the equilibrium (grey) and the two extreme configurations `q_eq +- a Re(v_q / v_k)`
//! (`v_k` its largest position entry)
//! (blue, red), each configuration drawn from the model's own outputs (body positions) at
//! that `q`. Self-contained (no dependence on the validation report's renderer).

use crate::modes::{DOUBLE, FOUR_BAR, SprungFourBar};
use mbd::analysis::linear::{Mode, ModeKind, constrained_modes, linearize, modes};
use mbd::prelude::*;
use std::fmt::Write;

/// Polylines in metres: the mechanism at one configuration.
pub type Figure = Vec<Vec<[f64; 2]>>;

/// The largest displacement of a drawn extreme: `a = AMPLITUDE / max |Re v_q|` (radians).
pub const AMPLITUDE: f64 = 0.3;

/// One panel: a mode's frequency and its three configurations.
#[derive(Debug, Clone)]
pub struct Panel {
    pub hz: f64,
    pub equilibrium: Figure,
    pub plus: Figure,
    pub minus: Figure,
}

/// The double pendulum at `q`: pivot, bob 1, bob 2, from its outputs.
pub fn double_pendulum(q: &[f64]) -> mbd::Result<Figure> {
    let o = DOUBLE.output_values(0.0, &Vector::<4>::new(q[0], q[1], 0.0, 0.0))?;
    Ok(vec![vec![[0.0, 0.0], [o[0], o[1]], [o[2], o[3]]]])
}

/// The sprung four-bar at `q`: crank, coupler, crank, and the spring to its anchor.
pub fn four_bar(q: &[f64]) -> mbd::Result<Figure> {
    let SprungFourBar { r, d, w, .. } = FOUR_BAR;
    let o = FOUR_BAR.output_values(0.0, &Vector::<4>::new(q[0], q[1], 0.0, 0.0))?;
    let (a, b) = ([o[0], o[1]], [o[2], o[3]]);
    Ok(vec![vec![[0.0, 0.0], a, b, [d, 0.0]], vec![[-w, -r], a]])
}

/// The panels of the oscillatory modes in `found` (positions: the first `n` entries of each
/// shape) about `q_eq`.
pub fn panels(
    found: &[Mode],
    q_eq: &[f64],
    draw: impl Fn(&[f64]) -> mbd::Result<Figure>,
) -> mbd::Result<Vec<Panel>> {
    let n = q_eq.len();
    let mut out = Vec::new();
    for m in found.iter().filter(|m| m.kind == ModeKind::Oscillatory) {
        // The positions in phase with their largest entry (the shape's own phase is
        // arbitrary: scaled by its largest entry, often a velocity).
        let k = (0..n)
            .max_by(|&i, &j| m.shape[i].norm().total_cmp(&m.shape[j].norm()))
            .unwrap_or(0);
        let pivot = m.shape[k];
        if pivot.norm().is_nan() || pivot.norm() == 0.0 {
            continue;
        }
        let v: Vec<f64> = (0..n).map(|i| (m.shape[i] / pivot).re).collect();
        let big = v.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let a = if big > 0.0 { AMPLITUDE / big } else { 0.0 };
        let at = |sign: f64| -> Vec<f64> { (0..n).map(|i| q_eq[i] + sign * a * v[i]).collect() };
        out.push(Panel {
            hz: m.frequency_hz(),
            equilibrium: draw(q_eq)?,
            plus: draw(&at(1.0))?,
            minus: draw(&at(-1.0))?,
        });
    }
    Ok(out)
}

/// The SVG of one mechanism's panels, side by side, 240 px square each, a common scale.
pub fn svg(title: &str, panels: &[Panel]) -> String {
    let points = panels
        .iter()
        .flat_map(|p| [&p.equilibrium, &p.plus, &p.minus])
        .flatten()
        .flatten();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9) * 1.15;
    let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let size = 240.0;
    let width = size * panels.len().max(1) as f64;
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{h}" font-family="sans-serif" font-size="12">"#,
        h = size + 40.0
    );
    let _ = write!(s, r#"<text x="6" y="16">{title}</text>"#);
    for (i, p) in panels.iter().enumerate() {
        let x0 = i as f64 * size;
        let map = |q: &[f64; 2]| {
            let x = x0 + size / 2.0 + (q[0] - mid[0]) / span * size;
            let y = 30.0 + size / 2.0 - (q[1] - mid[1]) / span * size;
            format!("{x:.2},{y:.2}")
        };
        for (fig, colour, width) in [
            (&p.equilibrium, "#999", 3.0),
            (&p.plus, "#1f5fbf", 1.5),
            (&p.minus, "#c0392b", 1.5),
        ] {
            for line in fig {
                let pts: Vec<String> = line.iter().map(map).collect();
                let _ = write!(
                    s,
                    r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="{width}"/>"#,
                    pts.join(" ")
                );
            }
        }
        let _ = write!(
            s,
            r#"<text x="{x:.1}" y="{y:.1}" text-anchor="middle">mode {k}: {hz:.4} Hz</text>"#,
            x = x0 + size / 2.0,
            y = size + 34.0,
            k = i + 1,
            hz = p.hz
        );
    }
    s.push_str("</svg>\n");
    s
}

/// `(file name, SVG)` for each planar mechanism of the report drawn here.
pub fn drawings() -> mbd::Result<Vec<(&'static str, String)>> {
    let a = linearize(&DOUBLE, 0.0, &Vector::<4>::zeros())?;
    let dp = panels(&modes(&a)?, &[0.0, 0.0], double_pendulum)?;
    let fb = panels(
        &constrained_modes(&FOUR_BAR, 0.0, &Vector::<2>::zeros())?,
        &[0.0, 0.0],
        four_bar,
    )?;
    Ok(vec![
        (
            "double_pendulum_modes.svg",
            svg("double pendulum, hanging: mode shapes", &dp),
        ),
        (
            "sprung_four_bar_modes.svg",
            svg("sprung parallelogram four-bar: mode shape", &fb),
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The drawn configurations are the model's: at the equilibrium the bobs hang at
    /// `(0, -l)`, `(0, -2 l)`; the slow mode's extremes swing both links the same way
    /// (`b / a = sqrt(2)`: the larger displacement, `AMPLITUDE`, on the lower link), the
    /// fast one's against each other; the four-bar's cranks stay parallel (`phi = psi`).
    #[test]
    fn drawn_shapes_are_the_modes() {
        let a = linearize(&DOUBLE, 0.0, &Vector::<4>::zeros()).unwrap();
        let ps = panels(&modes(&a).unwrap(), &[0.0, 0.0], double_pendulum).unwrap();
        assert_eq!(ps.len(), 2);
        let l = DOUBLE.l;
        let eq = &ps[0].equilibrium[0];
        assert!((eq[1][1] + l).abs() < 1e-15 && (eq[2][1] + 2.0 * l).abs() < 1e-15);
        let angle = |p: &[f64; 2], o: &[f64; 2]| (p[0] - o[0]).atan2(o[1] - p[1]);
        let s = 2f64.sqrt();
        for (panel, ratio) in ps.iter().zip([s, -s]) {
            let f = &panel.plus[0];
            let (a1, b1) = (angle(&f[1], &f[0]), angle(&f[2], &f[1]));
            assert!((b1.abs() - AMPLITUDE).abs() < 1e-12, "{a1} {b1}");
            assert!((b1 / a1 - ratio).abs() < 1e-9, "{a1} {b1}");
        }
        let fb = panels(
            &constrained_modes(&FOUR_BAR, 0.0, &Vector::<2>::zeros()).unwrap(),
            &[0.0, 0.0],
            four_bar,
        )
        .unwrap();
        assert_eq!(fb.len(), 1);
        let f = &fb[0].plus[0];
        // Crank A from (0, 0), crank B from (d, 0): equal angles.
        let d = FOUR_BAR.d;
        let (pa, pb) = (angle(&f[1], &f[0]), angle(&f[2], &[d, 0.0]));
        assert!((pa - pb).abs() < 1e-9 && (pa.abs() - AMPLITUDE).abs() < 1e-12);
        let svg = svg("t", &fb);
        assert_eq!(svg.matches("<polyline").count(), 6);
    }
}
