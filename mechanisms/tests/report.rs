//! The HTML validation report: `validate --out DIR` writes a self-contained page whose
//! content comes from the run (drawing frames from the generated geometry, the table's
//! values, the plot's marks) and from the case's documentation (the manual's errors).

use mechanisms::cases;
use mechanisms::report::{ReportRow, summary};
use mechanisms::validation::{Case, OFF_CURVE, error_pct};
use std::process::Command;

fn case(id: &str) -> Case {
    cases()
        .into_iter()
        .find(|c| c.id == id)
        .expect("the case exists")
}

#[test]
fn validate_writes_a_self_contained_html_page() {
    let dir = std::env::temp_dir().join(format!("mbd-report-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_validate"))
        .args(["--case", "28", "--out"])
        .arg(&dir)
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(dir.join("report.html")).expect("report.html");
    std::fs::remove_dir_all(&dir).ok();
    assert!(html.starts_with("<!DOCTYPE html>"));
    // Self-contained: nothing is fetched.
    for remote in ["https://", "src=", "<link"] {
        assert!(!html.contains(remote), "{remote} in the page");
    }
    // Only the SVG namespace names a URL (each plot's root and the drawing's script).
    assert!(
        html.matches("http://").count() == html.matches("http://www.w3.org/2000/svg").count(),
        "a URL other than the SVG namespace in the page"
    );
    assert!(html.contains("<section id=\"case28\">"));
    assert!(html.contains("Case 28: Falling bar with a spring"));
    // The drawing: the four shapes of the model, animated frames and a still.
    assert!(
        html.contains(r#""kinds":["rigid","point","spring"]"#),
        "{html}"
    );
    assert!(html.contains(r#""names":["bar","anchor_c","spring"]"#));
    // The table: the manual's values, mbd's at seven figures, run time in microseconds.
    assert!(html.contains("<td>0.909"), "the manual's theory");
    assert!(html.contains("<td>0.901</td>"), "RecurDyn");
    assert!(html.contains("<td>0.9101583</td>"), "mbd's value");
    assert!(html.contains("run time [µs]"));
    // Where the manual is wrong, from the case's documentation.
    assert!(html.contains("class=\"wrong\""));
    assert!(html.contains("is not the minimum even of its own formula"));
    // The plot marks theory, RecurDyn and mbd.
    for mark in [
        "theory: 0.909",
        "RecurDyn: 0.901",
        "mbd omega_min: 0.910158",
    ] {
        assert!(html.contains(mark), "{mark} missing");
    }
}

#[test]
fn the_drawing_follows_the_case_model() {
    // Case 28: the bar's frame is at its mass centre, 1.2 m from the pivot O; drawn as the
    // slender bar of its mass and inertia (2.4 m), its lower end is O at every instant.
    let anim = (case("28").draw)(0.8, &[0.5]).expect("drawn");
    assert_eq!(anim.frames.len(), mechanisms::sim::FRAMES + 1);
    assert_eq!(anim.stills.len(), 1);
    for f in anim.frames.iter().chain(&anim.stills) {
        let bar = &f.shapes[0].points;
        let pivot = bar[2];
        assert!(
            pivot[0].abs() < 1e-12 && pivot[1].abs() < 1e-12,
            "{pivot:?}"
        );
        let spring = &f.shapes[2].points;
        assert_eq!(spring[0], [-1.2, 0.0, 0.0]);
        assert_eq!(spring[1], bar[0]);
    }
    // Case 19: the crank's far end is the rod's pin B, the rod's other end the piston.
    let anim = (case("19").draw)(0.0, &[]).expect("drawn");
    for f in &anim.frames {
        let (crank, rod, piston) = (
            &f.shapes[0].points,
            &f.shapes[1].points,
            &f.shapes[2].points,
        );
        let gap = |a: [f64; 3], b: [f64; 3]| (a[0] - b[0]).hypot(a[1] - b[1]);
        assert!(gap(crank[1], rod[1]).min(gap(crank[1], rod[2])) < 1e-9);
        assert!(gap(piston[0], rod[1]).min(gap(piston[0], rod[2])) < 1e-9);
    }
}

#[test]
fn documentation_gives_the_summary_and_the_discrepancies() {
    let c = case("21");
    assert!(c.summary().contains("P6/25"));
    let d = c.discrepancies().expect("documented");
    assert!(d.contains("234.375"));
    assert!(error_pct(235.375, 234.375) > 0.4);
    assert!(case("13").discrepancies().unwrap().starts_with("None"));
}

#[test]
fn every_compared_quantity_is_on_a_curve_of_its_run() {
    // Each row carries its curve from the case's own run or sweep; mbd's value, marked
    // where it is compared, must lie on it (to the sampling error, OFF_CURVE of the curve's
    // height).
    let mut rows = 0;
    for c in cases() {
        let out = (c.run)().expect("the case runs");
        assert!(!out.rows.is_empty(), "case {}", c.id);
        for r in &out.rows {
            let what = format!("case {} {}", c.id, r.quantity);
            assert!(
                r.curve.points.len() > 50,
                "{what}: {} points",
                r.curve.points.len()
            );
            let off = r
                .curve
                .offset(r.value)
                .unwrap_or_else(|| panic!("{what}: outside"));
            assert!(
                off <= OFF_CURVE,
                "{what}: {off:e} of the curve's height off"
            );
            rows += 1;
        }
    }
    assert_eq!(rows, 60, "the manual's 60 compared rows");
}

#[test]
fn a_spatial_body_is_drawn_by_its_axes() {
    // Case 29: the disk (radius 0.1 m, diag(mR²/4, mR²/2, mR²/4)) has the second moments
    // J = mR²/4 in its plane (body x and z) and 0 along its axle (body y): its axes' ends at
    // sqrt(3 J/m) = (√3/2) R, which the page scales by 2/√3 to the rim. The frame's shaft
    // (0.1 m) and arm (0.3 m) are bars: one axis each, of half their length.
    let anim = (case("29").draw)(0.5, &[0.0]).expect("drawn");
    let still = &anim.stills[0];
    let names: Vec<&str> = still.shapes.iter().map(|s| s.name).collect();
    assert_eq!(names, ["shaft", "arm", "disk"]);
    let half = |s: usize| -> Vec<f64> {
        let p = &still.shapes[s].points;
        assert_eq!(p.len(), 4, "centre and three axis ends");
        p[1..]
            .iter()
            .map(|e| (0..3).map(|k| (e[k] - p[0][k]).powi(2)).sum::<f64>().sqrt())
            .collect()
    };
    let r = 0.1 * 3f64.sqrt() / 2.0;
    for (got, want) in half(2).iter().zip([r, 0.0, r]) {
        assert!((got - want).abs() < 1e-12, "disk {got} vs {want}");
    }
    for (got, want) in half(0).iter().zip([0.0, 0.0, 0.05]) {
        assert!((got - want).abs() < 1e-12, "shaft {got} vs {want}");
    }
    for (got, want) in half(1).iter().zip([0.15, 0.0, 0.0]) {
        assert!((got - want).abs() < 1e-12, "arm {got} vs {want}");
    }
    // At t = 0 the disk is in the x-z plane, centred at (0.3, 0, 0.1); its body z end is
    // straight above the centre, towards A.
    let disk = &still.shapes[2].points;
    assert_eq!(disk[0], [0.3, 0.0, 0.1]);
    assert!((disk[3][2] - (0.1 + r)).abs() < 1e-12 && disk[3][0] == 0.3);
}

#[test]
fn cranks_are_drawn_from_pivot_to_pin() {
    // Case 11: the crank OB ends at the rod's end B; the rod's other end is the piston A.
    let anim = (case("11").draw)(0.04, &[]).expect("drawn");
    let gap = |a: [f64; 3], b: [f64; 3]| (a[0] - b[0]).hypot(a[1] - b[1]);
    for f in &anim.frames {
        let (crank, rod, piston) = (
            &f.shapes[0].points,
            &f.shapes[1].points,
            &f.shapes[2].points,
        );
        assert!(gap(crank[1], [0.0; 3]).min(gap(crank[2], [0.0; 3])) < 1e-9);
        let b = if gap(crank[1], [0.0; 3]) < 1e-9 {
            crank[2]
        } else {
            crank[1]
        };
        assert!(gap(b, rod[1]).min(gap(b, rod[2])) < 1e-9, "crank misses B");
        assert!(gap(piston[0], rod[1]).min(gap(piston[0], rod[2])) < 1e-9);
    }
}

#[test]
fn case23_is_drawn_over_both_phases() {
    // The torque reverses at 45°: at the compared instant the block has stopped at 90°, its
    // mass centre straight above the axis (drawing the first phase's model alone, it would
    // have turned 180°).
    let out = (case("23").run)().expect("runs");
    let t = out.rows[0].value;
    let anim = (case("23").draw)(t, &[t]).expect("drawn");
    let g = anim.stills[0].shapes[0].points[0];
    assert!(g[1] > 0.0 && g[0].abs() < 1e-6 * g[1], "{g:?}");
}

/// A report row of `case` with mbd's and RecurDyn's errors in percent.
fn row(case: &str, quantity: &str, mbd: f64, recurdyn: Option<f64>) -> ReportRow {
    ReportRow {
        case: case.into(),
        quantity: quantity.into(),
        unit: "m".into(),
        theory: Some(1.0),
        recurdyn: recurdyn.map(|e| 1.0 + e / 100.0),
        value: 1.0 + mbd / 100.0,
        error_pct: mbd,
        recurdyn_error_pct: recurdyn,
        reference: 1.0,
        method: "test".into(),
        runtime_s: 0.0,
    }
}

#[test]
fn the_summary_names_the_worst_rows_and_every_failed_case() {
    let rows = [
        row("01", "h", 2e-12, Some(0.5)),
        row("01", "v", 3e-9, None),
        row("02", "a", 1e-14, Some(2.6)),
    ];
    let failed = [("05".to_string(), "step size underflow at t = 1".to_string())];
    let lines = summary(&rows, &failed);
    assert_eq!(
        lines,
        [
            "3 quantities of 2 cases compared.",
            "Largest mbd error: 3.0e-9 % (case 01 v).",
            "Largest RecurDyn error: 2.6 % (case 02 a).",
            "Case 05 FAILED and is not in the table: step size underflow at t = 1",
        ]
    );
}
