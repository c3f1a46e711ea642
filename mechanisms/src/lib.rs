//! The 30 cases of the validation manual ("Dynamics of Rigid Bodies", Meriam & Kraige 7th
//! ed. problems checked against RecurDyn) as generated mbd models.
//!
//! Each `caseNN_*` module documents its problem, the geometry reconstructed from the worked
//! solution (the manual's figures were lost), the model, and the exact references with every
//! discrepancy found in the manual; its tests run with `cargo test -p mechanisms caseNN`.

pub mod sim;
pub mod svg;
pub mod validation;

pub mod case01_vertical_throw;

use validation::Case;

/// Every case, in the manual's order.
pub fn cases() -> Vec<Case> {
    vec![Case {
        id: "01",
        title: "Vertical throw: height, time and speed at B",
        generated: &[case01_vertical_throw::VerticalThrow::GENERATED],
        run: case01_vertical_throw::run,
    }]
}
