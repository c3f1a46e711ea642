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
