//! The report binaries refuse bad arguments with exit status 2, before doing any work.

use std::process::Command;

fn status(bin: &str, args: &[&str]) -> Option<i32> {
    Command::new(bin)
        .args(args)
        .output()
        .expect("the binary runs")
        .status
        .code()
}

#[test]
fn validate_refuses_a_case_outside_the_manual() {
    let bin = env!("CARGO_BIN_EXE_validate");
    assert_eq!(status(bin, &["--case", "31"]), Some(2));
    assert_eq!(status(bin, &["--case", "0"]), Some(2));
}

#[test]
fn validate_refuses_an_unwritable_output_directory_before_running() {
    // A directory cannot be made under a regular file, on any platform.
    let file = std::env::temp_dir().join(format!("mbd-cli-not-a-dir-{}", std::process::id()));
    std::fs::write(&file, b"").expect("a scratch file");
    let out_dir = file.join("report");
    let out = Command::new(env!("CARGO_BIN_EXE_validate"))
        .arg("--out")
        .arg(&out_dir)
        .output()
        .expect("the binary runs");
    std::fs::remove_file(&file).ok();
    assert_eq!(out.status.code(), Some(2));
    // No case ran: each prints a progress line `[i/30] case ..` first.
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("[1/30]"), "{stderr}");
    assert!(stderr.contains("cannot write the report"), "{stderr}");
}

#[test]
fn ensemble_refuses_no_members_and_bad_times() {
    let bin = env!("CARGO_BIN_EXE_ensemble");
    assert_eq!(status(bin, &["--members", "0"]), Some(2));
    assert_eq!(status(bin, &["--t-end=-1"]), Some(2));
    assert_eq!(status(bin, &["--t-end", "nan"]), Some(2));
}

#[test]
fn friction_and_modes_refuse_unknown_arguments() {
    assert_eq!(
        status(env!("CARGO_BIN_EXE_friction"), &["--bogus"]),
        Some(2)
    );
    assert_eq!(status(env!("CARGO_BIN_EXE_modes"), &["--bogus"]), Some(2));
    assert_eq!(status(env!("CARGO_BIN_EXE_modes"), &["--svg"]), Some(2));
}

#[test]
fn loops_refuses_unknown_arguments_and_methods() {
    let bin = env!("CARGO_BIN_EXE_loops");
    assert_eq!(status(bin, &["--bogus"]), Some(2));
    assert_eq!(status(bin, &["--only", "RK5"]), Some(2));
    assert_eq!(status(bin, &["--tol", "x"]), Some(2));
    assert_eq!(status(bin, &["--t1", "-1"]), Some(2));
}
