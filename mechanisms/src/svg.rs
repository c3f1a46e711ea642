//! A minimal SVG line plot: one curve, labelled axes with ticks, an optional marked point.
//! Enough for the report's per-case plots without a plotting dependency.

use std::fmt::Write;

const W: f64 = 640.0;
const H: f64 = 400.0;
const PAD_L: f64 = 70.0;
const PAD_R: f64 = 20.0;
const PAD_T: f64 = 30.0;
const PAD_B: f64 = 50.0;

/// `points` as an SVG document, with `mark` drawn as a red dot and its coordinates.
pub fn line_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    points: &[(f64, f64)],
    mark: Option<(f64, f64)>,
) -> String {
    let finite: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let all = finite.iter().chain(mark.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 < 1e-300 {
        x1 = x0 + 1.0;
    }
    if y1 - y0 < 1e-12 * y0.abs().max(1e-300) {
        y0 -= 0.5 * y0.abs().max(1.0);
        y1 += 0.5 * y1.abs().max(1.0);
    }
    let sx = |x: f64| PAD_L + (x - x0) / (x1 - x0) * (W - PAD_L - PAD_R);
    let sy = |y: f64| H - PAD_B - (y - y0) / (y1 - y0) * (H - PAD_T - PAD_B);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">"#
    );
    let _ = write!(s, r#"<rect width="{W}" height="{H}" fill="white"/>"#);
    let _ = write!(
        s,
        r#"<text x="{}" y="18" text-anchor="middle" font-size="14">{}</text>"#,
        W / 2.0,
        esc(title)
    );
    let (bx, by) = (sx(x0), sy(y0));
    let _ = write!(
        s,
        r#"<polyline fill="none" stroke="black" points="{bx},{} {bx},{by} {},{by}"/>"#,
        sy(y1),
        sx(x1)
    );
    for i in 0..=5 {
        let (xv, yv) = (
            x0 + (x1 - x0) * i as f64 / 5.0,
            y0 + (y1 - y0) * i as f64 / 5.0,
        );
        let _ = write!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            sx(xv),
            by + 18.0,
            tick(xv)
        );
        let _ = write!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
            bx - 6.0,
            sy(yv) + 4.0,
            tick(yv)
        );
    }
    let _ = write!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        W / 2.0,
        H - 10.0,
        esc(x_label)
    );
    let _ = write!(
        s,
        r#"<text x="16" y="{}" text-anchor="middle" transform="rotate(-90 16 {})">{}</text>"#,
        H / 2.0,
        H / 2.0,
        esc(y_label)
    );
    let path: Vec<String> = finite
        .iter()
        .map(|&(x, y)| format!("{:.2},{:.2}", sx(x), sy(y)))
        .collect();
    let _ = write!(
        s,
        r#"<polyline fill="none" stroke="steelblue" stroke-width="1.5" points="{}"/>"#,
        path.join(" ")
    );
    if let Some((x, y)) = mark {
        let _ = write!(
            s,
            r#"<circle cx="{:.2}" cy="{:.2}" r="4" fill="crimson"/>"#,
            sx(x),
            sy(y)
        );
        let _ = write!(
            s,
            r#"<text x="{:.2}" y="{:.2}" fill="crimson">({}, {})</text>"#,
            sx(x) + 6.0,
            sy(y) - 6.0,
            tick(x),
            tick(y)
        );
    }
    s.push_str("</svg>\n");
    s
}

fn tick(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.3e}")
    } else {
        format!("{v:.4}")
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Colours of the curves of [`log_log_plot`], in order.
const PALETTE: [&str; 8] = [
    "steelblue",
    "crimson",
    "darkgreen",
    "darkorange",
    "purple",
    "saddlebrown",
    "teal",
    "black",
];

/// Several curves on log-log axes (a work-precision diagram): `series` are `(name, points)`
/// with positive `(x, y)`; non-positive or non-finite points are left out. The `i`-th series
/// has the `i`-th colour whether or not it has points (so that one caller's plots agree);
/// a series without points is not drawn nor listed. Ticks at the powers of ten, a legend in
/// the top right corner, a dot on every point.
pub fn log_log_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[(String, Vec<(f64, f64)>)],
) -> String {
    let logs: Vec<(&str, Vec<(f64, f64)>)> = series
        .iter()
        .map(|(name, pts)| {
            let l = pts
                .iter()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
                .map(|(x, y)| (x.log10(), y.log10()))
                .collect();
            (name.as_str(), l)
        })
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in logs.iter().flat_map(|(_, p)| p.iter()) {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    // Whole decades, at least one wide.
    let (x0, x1) = (x0.floor(), x1.ceil().max(x0.floor() + 1.0));
    let (y0, y1) = (y0.floor(), y1.ceil().max(y0.floor() + 1.0));
    let sx = |x: f64| PAD_L + (x - x0) / (x1 - x0) * (W - PAD_L - PAD_R);
    let sy = |y: f64| H - PAD_B - (y - y0) / (y1 - y0) * (H - PAD_T - PAD_B);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">"#
    );
    let _ = write!(s, r#"<rect width="{W}" height="{H}" fill="white"/>"#);
    let _ = write!(
        s,
        r#"<text x="{}" y="18" text-anchor="middle" font-size="14">{}</text>"#,
        W / 2.0,
        esc(title)
    );
    let (bx, by) = (sx(x0), sy(y0));
    let _ = write!(
        s,
        r#"<polyline fill="none" stroke="black" points="{bx},{} {bx},{by} {},{by}"/>"#,
        sy(y1),
        sx(x1)
    );
    let decades = |lo: f64, hi: f64| {
        let step = ((hi - lo) / 8.0).ceil().max(1.0);
        let mut v = Vec::new();
        let mut d = lo;
        while d <= hi + 1e-9 {
            v.push(d);
            d += step;
        }
        v
    };
    for d in decades(x0, x1) {
        let _ = write!(
            s,
            r##"<line x1="{0:.1}" y1="{1:.1}" x2="{0:.1}" y2="{2:.1}" stroke="#ddd"/><text x="{0:.1}" y="{3:.1}" text-anchor="middle">1e{4}</text>"##,
            sx(d),
            by,
            sy(y1),
            by + 18.0,
            d as i64
        );
    }
    for d in decades(y0, y1) {
        let _ = write!(
            s,
            r##"<line x1="{0:.1}" y1="{1:.1}" x2="{2:.1}" y2="{1:.1}" stroke="#ddd"/><text x="{3:.1}" y="{4:.1}" text-anchor="end">1e{5}</text>"##,
            bx,
            sy(d),
            sx(x1),
            bx - 6.0,
            sy(d) + 4.0,
            d as i64
        );
    }
    let _ = write!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        W / 2.0,
        H - 10.0,
        esc(x_label)
    );
    let _ = write!(
        s,
        r#"<text x="16" y="{}" text-anchor="middle" transform="rotate(-90 16 {})">{}</text>"#,
        H / 2.0,
        H / 2.0,
        esc(y_label)
    );
    let mut drawn = 0usize;
    for (i, (name, pts)) in logs.iter().enumerate() {
        if pts.is_empty() {
            continue;
        }
        let colour = PALETTE[i % PALETTE.len()];
        let path: Vec<String> = pts
            .iter()
            .map(|&(x, y)| format!("{:.2},{:.2}", sx(x), sy(y)))
            .collect();
        let _ = write!(
            s,
            r#"<polyline fill="none" stroke="{colour}" stroke-width="1.5" points="{}"/>"#,
            path.join(" ")
        );
        for &(x, y) in pts {
            let _ = write!(
                s,
                r#"<circle cx="{:.2}" cy="{:.2}" r="2.5" fill="{colour}"/>"#,
                sx(x),
                sy(y)
            );
        }
        let ly = PAD_T + 14.0 + 16.0 * drawn as f64;
        drawn += 1;
        let lx = W - PAD_R - 170.0;
        let _ = write!(
            s,
            r#"<line x1="{lx}" y1="{0}" x2="{1}" y2="{0}" stroke="{colour}" stroke-width="2"/><text x="{2}" y="{3}">{4}</text>"#,
            ly,
            lx + 20.0,
            lx + 26.0,
            ly + 4.0,
            esc(name)
        );
    }
    s.push_str("</svg>\n");
    s
}
