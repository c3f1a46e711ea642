//! What a case reports to the validation report: measured quantities against their
//! references, and the curve to plot.

use mbd::Generated;

/// One measured quantity of a case.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The quantity's name as in `data/comparison-tables.csv` (e.g. `t_stop_15`).
    pub quantity: &'static str,
    /// mbd's value, in the table's unit.
    pub value: f64,
    /// The value mbd is judged against: the manual's theory where it is right, else the
    /// corrected exact value derived in the case's documentation.
    pub reference: f64,
    /// How mbd obtained it (integrator and tolerance, or analysis).
    pub method: &'static str,
    /// The quantity's curve from the same run, and where on it the value is read.
    pub curve: Curve,
}

/// Where a row's value sits on its curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Read {
    /// The value is the curve's ordinate at this abscissa (the compared instant, or the
    /// parameter's value); the curve's y is the quantity in the row's unit.
    Ordinate { at: f64 },
    /// The value is the abscissa of the curve's point of ordinate `y` (an event's instant,
    /// the angle of an extremum); the curve's x is the quantity in the row's unit.
    Abscissa { y: f64 },
}

/// A curve of a case's own run (over time) or sweep (over a parameter, named in
/// `x_label`), on which a row's value is marked.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    pub x_label: &'static str,
    pub y_label: &'static str,
    pub points: Vec<(f64, f64)>,
    pub read: Read,
}

/// The label of a curve over time in seconds (what the drawing animates).
pub const SECONDS: &str = "t [s]";
/// The label of a curve over time in milliseconds.
pub const MILLISECONDS: &str = "t [ms]";

impl Curve {
    /// A quantity over time, compared at the instant `t`.
    pub fn at_instant(y_label: &'static str, points: Vec<(f64, f64)>, t: f64) -> Self {
        Curve {
            x_label: SECONDS,
            y_label,
            points,
            read: Read::Ordinate { at: t },
        }
    }

    /// A curve over time whose compared value is the instant where it takes `y`.
    pub fn instant_of(y_label: &'static str, points: Vec<(f64, f64)>, y: f64) -> Self {
        Curve {
            x_label: SECONDS,
            y_label,
            points,
            read: Read::Abscissa { y },
        }
    }

    /// The point marked for `value`: (abscissa, ordinate).
    pub fn point(&self, value: f64) -> (f64, f64) {
        match self.read {
            Read::Ordinate { at } => (at, value),
            Read::Abscissa { y } => (value, y),
        }
    }

    /// The curve's ordinate at `x`, linear between samples (`None` outside the curve).
    pub fn ordinate(&self, x: f64) -> Option<f64> {
        self.points.windows(2).find_map(|w| {
            let ((x0, y0), (x1, y1)) = (w[0], w[1]);
            let inside = (x0.min(x1)..=x0.max(x1)).contains(&x);
            inside.then(|| {
                if x1 == x0 {
                    y0
                } else {
                    y0 + (y1 - y0) * (x - x0) / (x1 - x0)
                }
            })
        })
    }

    /// How far the marked point of `value` lies off the curve, as a fraction of the
    /// curve's height (`None`: its abscissa is outside the curve). The report shows a
    /// value more than [`OFF_CURVE`] off as an error: the row and its curve disagree.
    pub fn offset(&self, value: f64) -> Option<f64> {
        let (x, y) = self.point(value);
        let on = self.ordinate(x)?;
        let (lo, hi) = self
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        let height = (hi - lo).max(1e-6 * y.abs()).max(1e-300);
        Some((on - y).abs() / height)
    }

    /// The compared instant in seconds, where the curve is over time.
    pub fn instant(&self, value: f64) -> Option<f64> {
        Some(self.point(value).0 * self.seconds()?)
    }

    /// The end of the curve in seconds, where it is over time.
    pub fn end(&self) -> Option<f64> {
        Some(self.points.last()?.0 * self.seconds()?)
    }

    /// Seconds per unit of the abscissa, where it is time.
    fn seconds(&self) -> Option<f64> {
        match self.x_label {
            SECONDS => Some(1.0),
            MILLISECONDS => Some(1e-3),
            _ => None,
        }
    }
}

/// The largest offset of a marked value from its curve the report accepts, as a fraction of
/// the curve's height: sampling error only (linear interpolation between a few hundred
/// samples).
pub const OFF_CURVE: f64 = 2e-3;

/// The outcome of running one case.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Outcome {
    pub rows: Vec<Row>,
}

/// `f` of each sample `(x, o)`, as plot points.
pub fn series<O>(samples: &[(f64, O)], f: impl Fn(&O) -> f64) -> Vec<(f64, f64)> {
    samples.iter().map(|(x, o)| (*x, f(o))).collect()
}

/// The mechanism at one instant (`#[mechanism(geometry)]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    pub t: f64,
    pub shapes: Vec<mbd::Shape>,
    /// The model's outputs (`#[output]`) at `t`, by name.
    pub outputs: Vec<(&'static str, f64)>,
    /// What the case's sketch adds, from `shapes` ([`crate::drawing`]).
    pub added: Vec<crate::drawing::Drawn>,
}

/// The mechanism over a run: uniform frames to animate, and stills at the compared instants;
/// the guides' paths and the ground pivots, which do not move.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Animation {
    pub frames: Vec<Frame>,
    pub stills: Vec<Frame>,
    pub guides: Vec<crate::drawing::Guide>,
    pub pivots: Vec<[f64; 3]>,
}

/// Draws a case's model over `[0, span]` with stills at the given instants.
pub type Draw = fn(span: f64, at: &[f64]) -> mbd::Result<Animation>;

/// A case of the validation manual.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// "01" to "30".
    pub id: &'static str,
    /// Short title.
    pub title: &'static str,
    /// What the derive generated for the case's model(s).
    pub generated: &'static [Generated],
    /// Runs the case.
    pub run: fn() -> mbd::Result<Outcome>,
    /// Draws its model (`MODEL`) from its initial state.
    pub draw: Draw,
    /// The case's source file, whose module documentation the report quotes.
    pub source: &'static str,
}

impl Case {
    /// The first paragraph of the case's documentation: the problem and its reference.
    pub fn summary(&self) -> String {
        doc_paragraphs(self.source)
            .into_iter()
            .next()
            .unwrap_or_default()
    }

    /// The documentation's paragraph on the manual's discrepancies (where the manual is
    /// wrong, and why), without its heading.
    pub fn discrepancies(&self) -> Option<String> {
        const HEAD: &str = "**Discrepancies in the manual.**";
        doc_paragraphs(self.source)
            .into_iter()
            .find_map(|p| p.strip_prefix(HEAD).map(|r| r.trim().to_string()))
    }
}

/// The paragraphs of a file's `//!` documentation, each joined into one line.
fn doc_paragraphs(source: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    for line in source.lines().map_while(|l| l.strip_prefix("//!")) {
        let line = line.trim();
        let last = out.last_mut().expect("one paragraph");
        if line.is_empty() {
            if !last.is_empty() {
                out.push(String::new());
            }
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(line);
        }
    }
    out.retain(|p| !p.is_empty());
    out
}

/// A row of the manual's comparison tables, as transcribed in `data/comparison-tables.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct ManualRow {
    pub case: String,
    pub quantity: String,
    pub unit: String,
    pub theory: Option<f64>,
    pub recurdyn: Option<f64>,
}

/// The manual's comparison tables (the project's own copy of the transcription).
pub fn manual_rows() -> Vec<ManualRow> {
    include_str!("../data/comparison-tables.csv")
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            ManualRow {
                case: f[0].to_string(),
                quantity: f[1].to_string(),
                unit: f[2].to_string(),
                theory: f[3].trim().parse().ok(),
                recurdyn: f[4].trim().parse().ok(),
            }
        })
        .collect()
}

/// Relative error in percent.
pub fn error_pct(value: f64, reference: f64) -> f64 {
    if reference == 0.0 {
        value.abs() * 100.0
    } else {
        ((value - reference) / reference).abs() * 100.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_off_its_curve_is_seen() {
        let points: Vec<(f64, f64)> = (0..=100)
            .map(|i| (f64::from(i) / 100.0, f64::from(i)))
            .collect();
        let at = Curve::at_instant("y", points.clone(), 0.5);
        assert!(at.offset(50.0).unwrap() < 1e-12);
        assert!(at.offset(51.0).unwrap() > OFF_CURVE);
        // An instant: where the curve takes 25 is t = 0.25, not 0.3.
        let of = Curve::instant_of("y", points, 25.0);
        assert!(of.offset(0.25).unwrap() < 1e-12);
        assert!(of.offset(0.3).unwrap() > OFF_CURVE);
        assert_eq!(of.offset(1.5), None);
        assert_eq!(of.instant(0.25), Some(0.25));
    }
}
