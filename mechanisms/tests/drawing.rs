//! The drawings hold together, checked numerically on the frames the report animates.
//!
//! For every case, at every frame and still: each end of every bar the page draws (a planar
//! rigid body's bar, a massless link, a body drawn through its joints) is a joint of the
//! model: it coincides, to `SAME` (1e-9) of the drawing's size, with a point of another
//! shape the model generated; or it never moves (a ground pivot, drawn as one); or it runs
//! on a guide; or the case's sketch declares it free. A bar that falls short of its pin (the
//! inertia bar of a non-uniform rod), a platform above its pins, or a link to the wrong
//! point fails here. Each massless link keeps its length (a rigid member). Then the faults
//! that were fixed, against positions written from each case's own geometry (not from the
//! generated code): 22's platform on its pins, 25's rod from the crank pin to the piston, the
//! links of 06, 10 and 21, and 05's incline.

use mechanisms::cases;
use mechanisms::drawing::{self, Added, At, SAME};
use mechanisms::validation::{Animation, Case, Frame};
use mechanisms::{
    case05_crate_on_incline as c05, case06_sliders_and_link as c06, case10_pendulum_on_cart as c10,
    case21_parallelogram_linkage as c21, case22_driven_platform as c22,
    case25_engine_wrist_pin as c25,
};

fn case(id: &str) -> Case {
    cases()
        .into_iter()
        .find(|c| c.id == id)
        .expect("the case exists")
}

/// Each case drawn over a span of its own run, with stills inside it.
fn drawn(c: &Case) -> Animation {
    let span = match c.id {
        "06" => 0.15, // B reaches O at 0.166 s
        "16" => 0.06, // the linkage reaches a singular position at 0.078 s
        "23" => 80.0, // both phases
        _ => 0.5,
    };
    (c.draw)(span, &[span / 3.0, 2.0 * span / 3.0]).unwrap_or_else(|e| panic!("case {}: {e}", c.id))
}

fn gap(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// Every point a frame draws, with its owner's name (not the bar of a body the sketch
/// draws through its joints instead).
fn points(f: &Frame) -> Vec<(&'static str, [f64; 3])> {
    let through = |n: &str| f.added.iter().any(|d| d.kind == Added::Body && d.name == n);
    let own = f
        .shapes
        .iter()
        .filter(|s| !through(s.name))
        .flat_map(|s| s.points.iter().map(|p| (s.name, *p)));
    let added = f
        .added
        .iter()
        .flat_map(|d| d.points.iter().map(|p| (d.name, *p)));
    own.chain(added).collect()
}

/// The sketch's declarations of a case, by its id (the module's `SKETCH`).
fn sketch(id: &str) -> drawing::Sketch {
    use mechanisms::*;
    match id {
        "01" => case01_vertical_throw::SKETCH,
        "02" => case02_polar_motion::SKETCH,
        "03" => case03_slotted_arm::SKETCH,
        "04" => case04_pendulum_acceleration::SKETCH,
        "05" => case05_crate_on_incline::SKETCH,
        "06" => case06_sliders_and_link::SKETCH,
        "07" => case07_collar_spring::SKETCH,
        "08" => case08_slider_bumper::SKETCH,
        "09" => case09_rotating_tube::SKETCH,
        "10" => case10_pendulum_on_cart::SKETCH,
        "11" => case11_engine_rod_velocity::SKETCH,
        "12" => case12_crank_slotted_link::SKETCH,
        "13" => case13_slider_crank_rod::SKETCH,
        "14" => case14_inclined_slider::SKETCH,
        "15" => case15_four_bar::SKETCH,
        "16" => case16_two_input_linkage::SKETCH,
        "17" => case17_slotted_rocker::SKETCH,
        "18" => case18_rod_through_collar::SKETCH,
        "19" => case19_slider_crank_max_speed::SKETCH,
        "20" => case20_pendulum_bearing::SKETCH,
        "21" => case21_parallelogram_linkage::SKETCH,
        "22" => case22_driven_platform::SKETCH,
        "23" => case23_block_reversing_torque::SKETCH,
        "24" => case24_crank_bar_roller::SKETCH,
        "25" => case25_engine_wrist_pin::SKETCH,
        "26" => case26_crank_bar_released::SKETCH,
        "27" => case27_bar_spring_released::SKETCH,
        "28" => case28_falling_bar_spring::SKETCH,
        "29" => case29_disk_on_rotating_frame::SKETCH,
        "30" => case30_damped_vibration::SKETCH,
        _ => panic!("no case {id}"),
    }
}

#[test]
fn every_drawn_bar_end_is_a_joint_a_pivot_a_guided_point_or_free() {
    let mut checked = 0;
    for c in cases() {
        let anim = drawn(&c);
        let sk = sketch(c.id);
        let tol = SAME * drawing::size(&anim.frames);
        assert!(anim.frames.len() > 100, "case {}", c.id);
        for f in anim.frames.iter().chain(&anim.stills) {
            let all = points(f);
            for (at, p) in drawing::ends(f) {
                let what = format!(
                    "case {} t = {}: end {} of `{}` at {p:?}",
                    c.id, f.t, at.1, at.0
                );
                let joint = all
                    .iter()
                    .any(|&(name, q)| name != at.0 && gap(p, q) <= tol);
                let pivot = anim.pivots.iter().any(|&q| gap(p, q) <= tol);
                let guided = sk.guides.contains(&at);
                let free = sk.free.contains(&at);
                assert!(
                    joint || pivot || guided || free,
                    "{what} is attached to nothing"
                );
                checked += 1;
            }
        }
        // What the sketch declares free or guided is an end or a point the model draws.
        let first = &anim.frames[0];
        for &at in sk.free.iter().chain(sk.guides) {
            let known = drawing::ends(first).iter().any(|(a, _)| *a == at)
                || drawing::point(&first.shapes, at).is_ok();
            assert!(known, "case {}: {at:?} is drawn nowhere", c.id);
        }
        // A pivot never moves: it is where it is in every frame's shapes.
        for &q in &anim.pivots {
            for f in &anim.frames {
                let here = points(f).iter().any(|&(_, p)| gap(p, q) <= tol);
                assert!(here, "case {}: pivot {q:?} missing at t = {}", c.id, f.t);
            }
        }
        // A massless link keeps its length.
        for &(name, from, to) in sk.links {
            let len = |f: &Frame| {
                gap(
                    drawing::point(&f.shapes, from).unwrap(),
                    drawing::point(&f.shapes, to).unwrap(),
                )
            };
            let l0 = len(&anim.frames[0]);
            for f in &anim.frames {
                let drift = (len(f) - l0).abs() / l0;
                assert!(
                    drift <= SAME,
                    "case {} link {name}: length drifts {drift:e}",
                    c.id
                );
            }
        }
    }
    assert!(checked > 5000, "{checked} ends checked");
}

#[test]
fn a_sketch_naming_a_point_the_model_does_not_draw_is_an_error() {
    let frames = drawn(&case("22"));
    const BAD: drawing::Sketch = drawing::Sketch {
        links: &[("cd", At("pivot_c", 0), At("pin_x", 0))],
        ..drawing::Sketch::NONE
    };
    let err = drawing::apply(frames, &BAD).expect_err("no pin_x");
    assert!(err.to_string().contains("pin_x"), "{err}");
}

/// The drawn element `name` of a frame (a link or a body through its joints).
fn added<'a>(f: &'a Frame, name: &str) -> &'a [[f64; 3]] {
    &f.added.iter().find(|d| d.name == name).expect(name).points
}

fn near(a: [f64; 3], b: [f64; 3], scale: f64) {
    assert!(gap(a, b) <= 1e-9 * scale, "{a:?} vs {b:?}");
}

#[test]
fn case22_platform_sits_on_its_pins() {
    // F = E + l (sin θ, cos θ), E = (−spacing, 0), θ = amplitude (1 − cos(rate t)); the
    // platform translates (a parallelogram), so D = F + (spacing, 0) and G = F + (along,
    // normal); the link CD runs from C = O to D, of length l.
    let m = c22::MODEL;
    let anim = drawn(&case("22"));
    for f in anim.frames.iter().chain(&anim.stills) {
        let th = m.amplitude * (1.0 - (m.rate * f.t).cos());
        let pf = [-m.spacing + m.l * th.sin(), m.l * th.cos(), 0.0];
        let pd = [pf[0] + m.spacing, pf[1], 0.0];
        let pg = [pf[0] + m.fg_along, pf[1] + m.fg_normal, 0.0];
        let platform = added(f, "platform");
        near(platform[0], pg, m.l);
        near(platform[1], pf, m.l);
        near(platform[2], pd, m.l);
        let cd = added(f, "link_cd");
        near(cd[0], [0.0; 3], m.l);
        near(cd[1], pd, m.l);
    }
}

#[test]
fn case25_rod_runs_from_the_crank_pin_to_the_piston() {
    // B = r (cos ωt, sin ωt); the piston A on the cylinder's axis x = 0 above O, at
    // y = r sin θ + sqrt(l² − r² cos² θ); G on BA at ρ from B.
    let m = c25::MODEL;
    let anim = drawn(&case("25"));
    for f in anim.frames.iter().chain(&anim.stills) {
        let th = m.omega * f.t;
        let b = [m.r * th.cos(), m.r * th.sin(), 0.0];
        let y = m.r * th.sin() + (m.l * m.l - (m.r * th.cos()).powi(2)).sqrt();
        let a = [0.0, y, 0.0];
        let g = [
            b[0] + m.rho / m.l * (a[0] - b[0]),
            b[1] + m.rho / m.l * (a[1] - b[1]),
            0.0,
        ];
        let rod = added(f, "rod");
        near(rod[0], g, m.l);
        near(rod[1], b, m.l);
        near(rod[2], a, m.l);
    }
    // The guide is the cylinder's axis x = 0.
    assert!(anim.guides[0].path.iter().all(|p| p[0].abs() <= 1e-12));
}

#[test]
fn massless_links_of_06_10_and_21_are_drawn_between_their_joints() {
    // 06: A on the x axis, B on the y axis, the bar between them of length l.
    let m = c06::MODEL;
    for f in &drawn(&case("06")).frames {
        let bar = added(f, "bar_ab");
        assert!(
            bar[0][1].abs() <= 1e-12 && bar[1][0].abs() <= 1e-12,
            "{bar:?}"
        );
        assert!((gap(bar[0], bar[1]) - m.l).abs() <= 1e-9 * m.l);
    }
    // 10: the rod from the cart on the track y = 0 to the bob, of length l.
    let m = c10::MODEL;
    for f in &drawn(&case("10")).frames {
        let rod = added(f, "rod");
        assert!(rod[0][1].abs() <= 1e-12);
        assert!((gap(rod[0], rod[1]) - m.l).abs() <= 1e-9 * m.l);
    }
    // 21: AB from A = O and CD from C = (0, −h), both of length r, parallel; BD of length h.
    let m = c21::MODEL;
    for f in &drawn(&case("21")).frames {
        let (ab, cd, bar) = (added(f, "link_ab"), added(f, "link_cd"), added(f, "bar"));
        near(ab[0], [0.0; 3], m.h);
        near(cd[0], [0.0, -m.h, 0.0], m.h);
        let dir = |l: &[[f64; 3]]| [l[1][0] - l[0][0], l[1][1] - l[0][1], 0.0];
        near(dir(ab), dir(cd), m.h);
        assert!((gap(ab[0], ab[1]) - m.r).abs() <= 1e-9 * m.r);
        near(bar[1], ab[1], m.h);
        near(bar[2], cd[1], m.h);
        assert!((gap(bar[1], bar[2]) - m.h).abs() <= 1e-9 * m.h);
    }
}

#[test]
fn case05_incline_is_the_plane_at_its_slope() {
    // The crate starts at O and slides down the 15° plane: every point of the guide is on
    // y = −x tan(15°), and the guide runs the distance it slides.
    let anim = drawn(&case("05"));
    let slope = c05::MODEL.slope;
    let path = &anim.guides[0].path;
    for p in path {
        assert!(
            (p[1] + p[0] * slope.tan()).abs() <= 1e-12 * (1.0 + p[0].abs()),
            "{p:?}"
        );
    }
    let run = gap(path[0], *path.last().unwrap());
    assert!(run > 1.0, "the incline drawn over {run} m");
}
