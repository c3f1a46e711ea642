//! The `scaling` report refuses bad arguments with exit status 2 before any work: no crate
//! is written, nothing is built.

use std::process::Command;

fn refused(args: &[&str]) {
    let work = std::env::temp_dir().join(format!("mbd-scaling-cli-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_scaling"))
        .args(args)
        .arg("--work-dir")
        .arg(&work)
        .output()
        .expect("the scaling binary runs");
    assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
    assert!(out.stdout.is_empty(), "{args:?}");
    assert!(!String::from_utf8_lossy(&out.stderr).is_empty(), "{args:?}");
    assert!(!work.exists(), "{args:?} wrote {}", work.display());
}

#[test]
fn a_zero_size_is_refused() {
    refused(&["--sizes", "0"]);
    refused(&["--sizes", "4,0,8"]);
}

#[test]
fn no_size_at_all_is_refused() {
    refused(&["--sizes="]);
    refused(&["--max", "1"]);
    refused(&["--family", "spatial", "--max", "3"]);
}

#[test]
fn an_unknown_family_is_refused() {
    refused(&["--family", "cubic"]);
}
