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
}

/// A curve of the case (the manual's plot), with the measured point marked.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Plot {
    pub x_label: &'static str,
    pub y_label: &'static str,
    pub points: Vec<(f64, f64)>,
    pub mark: Option<(f64, f64)>,
}

/// The outcome of running one case.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Outcome {
    pub rows: Vec<Row>,
    pub plot: Plot,
}

/// The mechanism at one instant (`#[mechanism(geometry)]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    pub t: f64,
    pub shapes: Vec<mbd::Shape>,
    /// The model's outputs (`#[output]`) at `t`, by name.
    pub outputs: Vec<(&'static str, f64)>,
}

/// The mechanism over a run: uniform frames to animate, and stills at the compared instants.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Animation {
    pub frames: Vec<Frame>,
    pub stills: Vec<Frame>,
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
