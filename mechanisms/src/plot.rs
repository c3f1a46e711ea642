//! The reports' plots, drawn with `plotters` (SVG backend): round ticks chosen by the
//! library, label areas sized to their labels, a marker shape and colour per series.

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::ops::Range;

const SIZE: (u32, u32) = (640, 400);

/// Colours of the series, in order: distinguishable (Okabe and Ito's palette) and dark
/// enough for white paper.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(230, 159, 0),
    RGBColor(0, 0, 0),
    RGBColor(120, 120, 120),
];

/// A marker shape; series cycle through them so that curves of similar colour differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Triangle,
    Square,
    Cross,
    Diamond,
}

const MARKERS: [Marker; 5] = [
    Marker::Circle,
    Marker::Triangle,
    Marker::Square,
    Marker::Cross,
    Marker::Diamond,
];

/// One series of a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// Draw a line through the points (else markers only).
    pub line: bool,
    /// Draw a marker on every point.
    pub markers: bool,
}

/// A value marked on a curve: (legend text, x, y). Each gets its own marker and colour.
pub type Mark = (String, f64, f64);

/// A tick label: plain for moderate magnitudes, scientific otherwise, never more digits
/// than the tick needs (the ticks are round numbers).
pub fn tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if v.abs() >= 1e5 || v.abs() < 1e-3 {
        let s = format!("{v:.2e}");
        return s.replace(".00e", "e").replace("0e", "e");
    }
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A tick at a power of ten: `1e-6`.
fn decade(v: f64) -> String {
    format!("1e{}", v.log10().round() as i64)
}

/// About seven round values over `r` (steps of 1, 2 or 5 times a power of ten), as an axis
/// would tick it: what the tick labels' width is estimated from.
fn round_ticks(r: &Range<f64>) -> Vec<f64> {
    let raw = (r.end - r.start) / 7.0;
    let p = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|k| k * p)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * p);
    let first = (r.start / step).ceil() as i64;
    let last = (r.end / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

fn widest(labels: impl Iterator<Item = String>) -> u32 {
    labels.map(|s| s.chars().count()).max().unwrap_or(1) as u32
}

/// Padded range of `values` (a constant gets a unit-wide or relative margin).
fn range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return 0.0..1.0;
    }
    let pad = if hi - lo > 1e-12 * hi.abs().max(lo.abs()) {
        0.05 * (hi - lo)
    } else {
        0.5 * hi.abs().max(1.0)
    };
    lo - pad..hi + pad
}

/// A marker's outline around its centre, in pixels (one polygon, so that a legend can
/// draw it too).
fn outline(m: Marker, size: i32) -> Vec<(i32, i32)> {
    let (r, w) = (size, (size / 3).max(1));
    match m {
        Marker::Circle => (0..12)
            .map(|i| {
                let a = f64::from(i) * std::f64::consts::PI / 6.0;
                let r = f64::from(r);
                ((r * a.cos()).round() as i32, (r * a.sin()).round() as i32)
            })
            .collect(),
        Marker::Triangle => vec![(0, -r - 1), (r + 1, r), (-r - 1, r)],
        Marker::Square => vec![(-r, -r), (r, -r), (r, r), (-r, r)],
        Marker::Diamond => vec![(0, -r - 1), (r + 1, 0), (0, r + 1), (-r - 1, 0)],
        Marker::Cross => vec![
            (-w, -r - 1),
            (w, -r - 1),
            (w, -w),
            (r + 1, -w),
            (r + 1, w),
            (w, w),
            (w, r + 1),
            (-w, r + 1),
            (-w, w),
            (-r - 1, w),
            (-r - 1, -w),
            (-w, -w),
        ],
    }
}

/// A marker for a legend, at pixel `c`.
fn legend_marker(m: Marker, c: (i32, i32), colour: RGBColor) -> Polygon<(i32, i32)> {
    let pts = outline(m, 4).into_iter().map(|(x, y)| (c.0 + x, c.1 + y));
    Polygon::new(pts.collect::<Vec<_>>(), colour.filled())
}

/// A tick label's format.
type Format<'a> = &'a dyn Fn(&f64) -> String;
/// A value's place along an axis: 0 at its start, 1 at its end.
type Unit<'a> = &'a dyn Fn(f64) -> f64;

/// Draws `series` and `marks` on axes built from `x` and `y`, with a legend.
#[allow(clippy::too_many_arguments, reason = "one plot's parts")]
fn draw<X, Y>(
    buf: &mut String,
    (x_unit, y_unit): (Unit<'_>, Unit<'_>),
    title: &str,
    labels: (&str, &str),
    x: X,
    y: Y,
    y_area: u32,
    formats: (Format<'_>, Format<'_>),
    series: &[Series],
    marks: &[Mark],
) -> Result<(), String>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let e = |e: &dyn std::fmt::Display| e.to_string();
    let (corner, _) = legend_corner(series, marks, x_unit, y_unit);
    let root = SVGBackend::with_string(buf, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(y_area)
        .build_cartesian_2d(x, y)
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc(labels.0)
        .y_desc(labels.1)
        .x_labels(7)
        .y_labels(7)
        .x_label_formatter(formats.0)
        .y_label_formatter(formats.1)
        .light_line_style(WHITE.mix(0.0))
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .draw()
        .map_err(|x| e(&x))?;
    for (i, s) in series
        .iter()
        .enumerate()
        .filter(|(_, s)| !s.points.is_empty())
    {
        let colour = PALETTE[i % PALETTE.len()];
        let shape = MARKERS[i % MARKERS.len()];
        if s.line {
            chart
                .draw_series(LineSeries::new(
                    s.points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|x| e(&x))?;
        }
        let on = if s.markers { s.points.as_slice() } else { &[] };
        let markers = s.markers;
        chart
            .draw_series(
                on.iter().map(|&p| {
                    EmptyElement::at(p) + Polygon::new(outline(shape, 3), colour.filled())
                }),
            )
            .map_err(|x| e(&x))?
            .label(s.name.as_str())
            .legend(move |(x, y)| {
                let glyph = if markers {
                    outline(shape, 3)
                } else {
                    Vec::new()
                };
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(-8, 0), (8, 0)], colour.stroke_width(2))
                    + Polygon::new(glyph, colour.filled())
            });
    }
    for (i, (name, mx, my)) in marks.iter().enumerate() {
        // Marks take the palette from its far end, so they never share a series' colour.
        let colour = PALETTE[(PALETTE.len() - 1 - i) % PALETTE.len()];
        let colour = if i == 0 { RGBColor(200, 0, 0) } else { colour };
        let shape = MARKERS[(i + 1) % MARKERS.len()];
        let size = 7 - 2 * i.min(2) as i32;
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((*mx, *my)) + Polygon::new(outline(shape, size), colour.filled()),
            ))
            .map_err(|x| e(&x))?
            .label(name.as_str())
            .legend(move |c| legend_marker(shape, c, colour));
    }
    chart
        .configure_series_labels()
        .position(corner)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .label_font(("sans-serif", 12))
        .draw()
        .map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))
}

/// The corner of the plot where the legend covers the fewest points: `x_unit` and `y_unit`
/// map a value to its place along the axis, 0 at the start and 1 at the end.
fn legend_corner(
    series: &[Series],
    marks: &[Mark],
    x_unit: Unit<'_>,
    y_unit: Unit<'_>,
) -> (SeriesLabelPosition, usize) {
    let points: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .chain(marks.iter().map(|m| (m.1, m.2)))
        .map(|(x, y)| (x_unit(x), y_unit(y)))
        .collect();
    let covered = |right: bool, top: bool| {
        points
            .iter()
            .filter(|(u, v)| {
                (if right { *u > 0.6 } else { *u < 0.4 })
                    && (if top { *v > 0.65 } else { *v < 0.35 })
            })
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, covered(true, true)),
        (SeriesLabelPosition::UpperLeft, covered(false, true)),
        (SeriesLabelPosition::LowerRight, covered(true, false)),
        (SeriesLabelPosition::LowerLeft, covered(false, false)),
    ]
    .into_iter()
    .min_by_key(|c| c.1)
    .unwrap_or((SeriesLabelPosition::UpperRight, 0))
}

/// One or more curves over linear axes, with reference values marked.
pub fn line_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    marks: &[Mark],
) -> Result<String, String> {
    let all = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .chain(marks.iter().map(|m| (m.1, m.2)))
    };
    let (x, mut y) = (range(all().map(|p| p.0)), range(all().map(|p| p.1)));
    // No corner free for the legend: room above the curves for it.
    let unit = |r: &Range<f64>, v: f64| (v - r.start) / (r.end - r.start);
    if legend_corner(series, marks, &|v| unit(&x, v), &|v| unit(&y, v)).1 > 0 {
        y.end += 0.45 * (y.end - y.start);
    }
    let y_area = 34 + 7 * widest(round_ticks(&y).into_iter().map(tick));
    let mut buf = String::new();
    let (xu, yu) = (x.clone(), y.clone());
    draw(
        &mut buf,
        (&|v| (v - xu.start) / (xu.end - xu.start), &|v| {
            (v - yu.start) / (yu.end - yu.start)
        }),
        title,
        (x_label, y_label),
        x,
        y,
        y_area,
        (&|v| tick(*v), &|v| tick(*v)),
        series,
        marks,
    )?;
    Ok(buf)
}

/// Curves on log-log axes (a work-precision diagram): non-positive and non-finite points are
/// left out; the axes span whole decades; every point has its series' marker.
pub fn log_log_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<String, String> {
    let series: Vec<Series> = series
        .iter()
        .map(|s| Series {
            points: s
                .points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
                .collect(),
            ..s.clone()
        })
        .collect();
    let decades = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x.log10()), b.max(x.log10()))
        });
        if lo > hi {
            return 1.0..10.0;
        }
        let (lo, hi) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
        10f64.powf(lo)..10f64.powf(hi)
    };
    let pts = || series.iter().flat_map(|s| s.points.iter().copied());
    let x = decades(&mut pts().map(|p| p.0));
    let y = decades(&mut pts().map(|p| p.1));
    let mut buf = String::new();
    let unit = |r: &Range<f64>, v: f64| (v.log10() - r.start.log10()) / (r.end / r.start).log10();
    let (xu, yu) = (x.clone(), y.clone());
    draw(
        &mut buf,
        (&|v| unit(&xu, v), &|v| unit(&yu, v)),
        title,
        (x_label, y_label),
        x.log_scale(),
        y.clone().log_scale(),
        30 + 8 * widest([y.start, y.end].iter().map(|v| decade(*v))),
        (&|v| decade(*v), &|v| decade(*v)),
        &series,
        &[],
    )?;
    Ok(buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_short_and_round() {
        assert_eq!(tick(0.5), "0.5");
        assert_eq!(tick(31.0), "31");
        assert_eq!(tick(-2.25), "-2.25");
        assert_eq!(tick(0.0), "0");
        assert_eq!(tick(2e-6), "2e-6");
    }

    #[test]
    fn a_plot_has_its_series_marks_and_labels() {
        let s = Series {
            name: "mbd".into(),
            points: (0..=10).map(|i| (f64::from(i), f64::from(i * i))).collect(),
            line: true,
            markers: false,
        };
        let svg = line_plot(
            "t",
            "t [s]",
            "x [m]",
            &[s],
            &[("theory: 25".into(), 5.0, 25.0)],
        )
        .unwrap();
        assert!(svg.starts_with("<svg"));
        for text in ["t [s]", "x [m]", "mbd", "theory: 25"] {
            assert!(svg.contains(text), "{text} missing");
        }
    }
}
