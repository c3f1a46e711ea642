//! The 30 cases of the validation manual ("Dynamics of Rigid Bodies", Meriam & Kraige 7th
//! ed. problems checked against RecurDyn) as generated mbd models.
//!
//! Each `caseNN_*` module documents its problem, the geometry reconstructed from the worked
//! solution (the manual's figures were lost), the model, and the exact references with every
//! discrepancy found in the manual; its tests run with `cargo test -p mechanisms caseNN`.

pub mod accuracy;
pub mod bricard;
pub mod chain_by_hand;
pub mod drawing;
pub mod fourbar_assembly;
pub mod handwritten;
pub mod linear_io;
pub mod loop_rows;
pub mod mode_svg;
pub mod modes;
#[cfg(feature = "report")]
pub mod plot;
#[cfg(feature = "report")]
pub mod report;
pub mod sim;
pub mod spatial_chain_by_hand;
pub mod stick_slip;
pub mod validation;
pub mod workprecision;

pub mod case01_vertical_throw;
pub mod case02_polar_motion;
pub mod case03_slotted_arm;
pub mod case04_pendulum_acceleration;
pub mod case05_crate_on_incline;
pub mod case06_sliders_and_link;
pub mod case07_collar_spring;
pub mod case08_slider_bumper;
pub mod case09_rotating_tube;
pub mod case10_pendulum_on_cart;
pub mod case11_engine_rod_velocity;
pub mod case12_crank_slotted_link;
pub mod case13_slider_crank_rod;
pub mod case14_inclined_slider;
pub mod case15_four_bar;
pub mod case16_two_input_linkage;
pub mod case17_slotted_rocker;
pub mod case18_rod_through_collar;
pub mod case19_slider_crank_max_speed;
pub mod case20_pendulum_bearing;
pub mod case21_parallelogram_linkage;
pub mod case22_driven_platform;
pub mod case23_block_reversing_torque;
pub mod case24_crank_bar_roller;
pub mod case25_engine_wrist_pin;
pub mod case26_crank_bar_released;
pub mod case27_bar_spring_released;
pub mod case28_falling_bar_spring;
pub mod case29_disk_on_rotating_frame;
pub mod case30_damped_vibration;

use validation::Case;

/// A case's [`validation::Draw`]: its `MODEL` from its initial state, with its outputs (or
/// `no_outputs`), over the span the report asks for or, where given, one of the model's
/// own (a fast drive's turn), with what the case's `SKETCH` adds.
macro_rules! draw {
    ($case:ident :: $model:ident $(, span = |$m:ident| $span:expr)?) => {
        |requested, at| {
            let model = $case::MODEL;
            let own: Option<f64> = None $(.or(Some({ let $m = &model; $span })))?;
            let span = own.unwrap_or(requested);
            let outputs = |t: f64, y: &_| -> mbd::Result<Vec<(&'static str, f64)>> {
                let values = model.output_values(t, y)?;
                Ok(std::iter::zip($case::$model::OUTPUTS, values).collect())
            };
            let drawn = sim::animate(&model, model.initial_state(), span, at, &outputs)?;
            drawing::apply(drawn, &$case::SKETCH)
        }
    };
    ($case:ident :: $model:ident, no_outputs) => {
        |span, at| {
            let model = $case::MODEL;
            let drawn =
                sim::animate(&model, model.initial_state(), span, at, &|_, _| Ok(Vec::new()))?;
            drawing::apply(drawn, &$case::SKETCH)
        }
    };
}

/// Every case, in the manual's order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            id: "01",
            title: "Vertical throw: height, time and speed at B",
            generated: &[case01_vertical_throw::VerticalThrow::GENERATED],
            run: case01_vertical_throw::run,
            draw: draw!(case01_vertical_throw::VerticalThrow),
            source: include_str!("case01_vertical_throw.rs"),
        },
        Case {
            id: "02",
            title: "Polar coordinates: speed and acceleration of B",
            generated: &[case02_polar_motion::PolarMotion::GENERATED],
            run: case02_polar_motion::run,
            draw: draw!(case02_polar_motion::PolarMotion),
            source: include_str!("case02_polar_motion.rs"),
        },
        Case {
            id: "03",
            title: "Pin in a slotted arm driven by a crank: r', r'', θ', θ''",
            generated: &[case03_slotted_arm::SlottedArm::GENERATED],
            run: case03_slotted_arm::run,
            draw: draw!(case03_slotted_arm::SlottedArm),
            source: include_str!("case03_slotted_arm.rs"),
        },
        Case {
            id: "04",
            title: "Pendulum on the small-oscillation law: extreme accelerations",
            generated: &[case04_pendulum_acceleration::Pendulum::GENERATED],
            run: case04_pendulum_acceleration::run,
            draw: draw!(case04_pendulum_acceleration::Pendulum),
            source: include_str!("case04_pendulum_acceleration.rs"),
        },
        Case {
            id: "05",
            title: "Crate sliding down an incline with friction: stop time and distance",
            generated: &[case05_crate_on_incline::CrateOnIncline::GENERATED],
            run: case05_crate_on_incline::run,
            draw: draw!(case05_crate_on_incline::CrateOnIncline),
            source: include_str!("case05_crate_on_incline.rs"),
        },
        Case {
            id: "06",
            title: "Two sliders joined by a light bar: accelerations and bar force",
            generated: &[case06_sliders_and_link::SlidersAndLink::GENERATED],
            run: case06_sliders_and_link::run,
            draw: draw!(case06_sliders_and_link::SlidersAndLink),
            source: include_str!("case06_sliders_and_link.rs"),
        },
        Case {
            id: "07",
            title: "Collar pulled up a smooth rod by a spring: speed at B",
            generated: &[case07_collar_spring::CollarOnRod::GENERATED],
            run: case07_collar_spring::run,
            draw: draw!(case07_collar_spring::CollarOnRod),
            source: include_str!("case07_collar_spring.rs"),
        },
        Case {
            id: "08",
            title: "Slider down a guide into a bumper: speed at B and largest deflection",
            generated: &[
                case08_slider_bumper::SliderOnGuide::GENERATED,
                case08_slider_bumper::SliderOnBumper::GENERATED,
            ],
            run: case08_slider_bumper::run,
            draw: draw!(case08_slider_bumper::SliderOnGuide),
            source: include_str!("case08_slider_bumper.rs"),
        },
        Case {
            id: "09",
            title: "Particle sliding out of a rotating tube: exit time and angle",
            generated: &[case09_rotating_tube::TubeAndParticle::GENERATED],
            run: case09_rotating_tube::run,
            draw: draw!(case09_rotating_tube::TubeAndParticle),
            source: include_str!("case09_rotating_tube.rs"),
        },
        Case {
            id: "10",
            title: "Pendulum on a free cart falling from upright: θ' and v_x at the bottom",
            generated: &[case10_pendulum_on_cart::PendulumOnCart::GENERATED],
            run: case10_pendulum_on_cart::run,
            draw: draw!(case10_pendulum_on_cart::PendulumOnCart),
            source: include_str!("case10_pendulum_on_cart.rs"),
        },
        Case {
            id: "11",
            title: "Reciprocating engine: speed of the rod's mass centre and ω_AB",
            generated: &[case11_engine_rod_velocity::Engine::GENERATED],
            run: case11_engine_rod_velocity::run,
            draw: draw!(case11_engine_rod_velocity::Engine),
            source: include_str!("case11_engine_rod_velocity.rs"),
        },
        Case {
            id: "12",
            title: "Crank pin in a slotted link: the link's angular velocity",
            generated: &[case12_crank_slotted_link::SlottedLink::GENERATED],
            run: case12_crank_slotted_link::run,
            draw: draw!(case12_crank_slotted_link::SlottedLink),
            source: include_str!("case12_crank_slotted_link.rs"),
        },
        Case {
            id: "13",
            title: "Slider-crank: the rod's angular velocity and acceleration",
            generated: &[case13_slider_crank_rod::SliderCrank::GENERATED],
            run: case13_slider_crank_rod::run,
            draw: draw!(case13_slider_crank_rod::SliderCrank),
            source: include_str!("case13_slider_crank_rod.rs"),
        },
        Case {
            id: "14",
            title: "Crank, link and inclined slider: speeds of A and of the link's midpoint",
            generated: &[case14_inclined_slider::InclinedSlider::GENERATED],
            run: case14_inclined_slider::run,
            draw: draw!(case14_inclined_slider::InclinedSlider),
            source: include_str!("case14_inclined_slider.rs"),
        },
        Case {
            id: "15",
            title: "Four-bar linkage: angular velocities of coupler and rocker",
            generated: &[case15_four_bar::FourBar::GENERATED],
            run: case15_four_bar::run,
            draw: draw!(case15_four_bar::FourBar),
            source: include_str!("case15_four_bar.rs"),
        },
        Case {
            id: "16",
            title: "Two-input linkage: angular velocity of BC",
            generated: &[case16_two_input_linkage::TwoInputLinkage::GENERATED],
            run: case16_two_input_linkage::run,
            draw: draw!(case16_two_input_linkage::TwoInputLinkage),
            source: include_str!("case16_two_input_linkage.rs"),
        },
        Case {
            id: "17",
            title: "Crank and slotted rocker: ω_BC and v_B",
            generated: &[case17_slotted_rocker::SlottedRocker::GENERATED],
            run: case17_slotted_rocker::run,
            draw: draw!(case17_slotted_rocker::SlottedRocker),
            source: include_str!("case17_slotted_rocker.rs"),
        },
        Case {
            id: "18",
            title: "Rod sliding through a pivoted collar: angular acceleration of BD",
            generated: &[case18_rod_through_collar::RodThroughCollar::GENERATED],
            run: case18_rod_through_collar::run,
            draw: draw!(case18_rod_through_collar::RodThroughCollar),
            source: include_str!("case18_rod_through_collar.rs"),
        },
        Case {
            id: "19",
            title: "Slider-crank: maximum piston speed and its crank angle",
            generated: &[case19_slider_crank_max_speed::SliderCrank::GENERATED],
            run: case19_slider_crank_max_speed::run,
            draw: draw!(
                case19_slider_crank_max_speed::SliderCrank,
                span = |m| std::f64::consts::TAU / m.omega
            ),
            source: include_str!("case19_slider_crank_max_speed.rs"),
        },
        Case {
            id: "20",
            title: "Pendulum released from rest: bearing force at 60°",
            generated: &[case20_pendulum_bearing::Pendulum::GENERATED],
            run: case20_pendulum_bearing::run,
            draw: draw!(case20_pendulum_bearing::Pendulum),
            source: include_str!("case20_pendulum_bearing.rs"),
        },
        Case {
            id: "21",
            title: "Parallelogram linkage driven by a couple: pin force at D and angular acceleration",
            generated: &[case21_parallelogram_linkage::Parallelogram::GENERATED],
            run: case21_parallelogram_linkage::run,
            draw: draw!(case21_parallelogram_linkage::Parallelogram),
            source: include_str!("case21_parallelogram_linkage.rs"),
        },
        Case {
            id: "22",
            title: "Platform on a driven parallelogram: pin force at D at t = 0 and 1 s",
            generated: &[case22_driven_platform::DrivenPlatform::GENERATED],
            run: case22_driven_platform::run,
            draw: draw!(case22_driven_platform::DrivenPlatform),
            source: include_str!("case22_driven_platform.rs"),
        },
        Case {
            id: "23",
            title: "Block turned 90° by a reversing torque: time taken",
            generated: &[case23_block_reversing_torque::Block::GENERATED],
            run: case23_block_reversing_torque::run,
            draw: case23_block_reversing_torque::draw,
            source: include_str!("case23_block_reversing_torque.rs"),
        },
        Case {
            id: "24",
            title: "Crank-driven bar with a roller on the floor: normal force at B",
            generated: &[case24_crank_bar_roller::CrankBar::GENERATED],
            run: case24_crank_bar_roller::run,
            draw: draw!(case24_crank_bar_roller::CrankBar),
            source: include_str!("case24_crank_bar_roller.rs"),
        },
        Case {
            id: "25",
            title: "Engine with the crank at 90°: force in the wrist pin",
            generated: &[case25_engine_wrist_pin::Engine::GENERATED],
            run: case25_engine_wrist_pin::run,
            draw: draw!(case25_engine_wrist_pin::Engine),
            source: include_str!("case25_engine_wrist_pin.rs"),
        },
        Case {
            id: "26",
            title: "Crank and bar released from rest: speed of B as OA passes the vertical",
            generated: &[case26_crank_bar_released::CrankAndBar::GENERATED],
            run: case26_crank_bar_released::run,
            draw: draw!(case26_crank_bar_released::CrankAndBar),
            source: include_str!("case26_crank_bar_released.rs"),
        },
        Case {
            id: "27",
            title: "Bar with a spring released from rest: maximum angular speed",
            generated: &[case27_bar_spring_released::BarWithSpring::GENERATED],
            run: case27_bar_spring_released::run,
            draw: draw!(case27_bar_spring_released::BarWithSpring),
            source: include_str!("case27_bar_spring_released.rs"),
        },
        Case {
            id: "28",
            title: "Falling bar with a spring: minimum angular speed and ω at 90°",
            generated: &[case28_falling_bar_spring::FallingBar::GENERATED],
            run: case28_falling_bar_spring::run,
            draw: draw!(case28_falling_bar_spring::FallingBar),
            source: include_str!("case28_falling_bar_spring.rs"),
        },
        Case {
            id: "29",
            title: "Disk spinning on a rotating frame: angular acceleration and acceleration of A",
            generated: &[case29_disk_on_rotating_frame::SpinningDisk::GENERATED],
            run: case29_disk_on_rotating_frame::run,
            draw: draw!(case29_disk_on_rotating_frame::SpinningDisk),
            source: include_str!("case29_disk_on_rotating_frame.rs"),
        },
        Case {
            id: "30",
            title: "Free damped vibration: position after half a damped cycle",
            generated: &[case30_damped_vibration::DampedBlock::GENERATED],
            run: case30_damped_vibration::run,
            draw: draw!(case30_damped_vibration::DampedBlock, no_outputs),
            source: include_str!("case30_damped_vibration.rs"),
        },
    ]
}
