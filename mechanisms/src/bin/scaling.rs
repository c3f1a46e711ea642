//! How the derive scales with the number of bodies, each model compiled as its own throw-away
//! crate: planar chains of N = 2, 4, .., 256 uniform links (`--family planar`, the default;
//! up to `--max`, 256 by default, 32 for the explicit form), or spatial chains of N = 4, 8,
//! 10, 16, 32 bars on universal joints (`--family spatial`, 2 N coordinates).
//!
//! `cargo run --release -p mechanisms --bin scaling [-- --json --max 64 --sizes 2,4,10 --form explicit|chain --family planar|spatial]`
//!
//! Per N the report gives
//! - `expand_s`: the derive's own expansion time, written by the macro itself when the build
//!   runs with `MBD_EXPAND_DUMP=<dir>` (`<dir>/main.<Struct>.time`);
//! - `build_s`: the wall time of `cargo build --release` of the throw-away crate, expansion
//!   included, with every dependency already built by a warm-up build into the same shared
//!   target directory (so only the chain crate compiles);
//! - `generated_lines`: the macro's output (`<dir>/<Struct>.rs`, one token string) parsed with
//!   `syn::parse_file` and formatted with `prettyplease`, counted in lines (not counting the
//!   names and types, one per line, of the grouped declarations long bodies start with);
//! - `peak_mb`: the build's peak memory, the largest resident set of cargo and the compilers
//!   it waited for (GNU time's maximum RSS; absent without GNU time on the `PATH`);
//! - `rhs_ns` and `handwritten_rhs_ns`: the generated `OdeSystem::rhs` and the hand-written
//!   articulated-body algorithm ([`mechanisms::chain_by_hand`], in space
//!   [`mechanisms::spatial_chain_by_hand`]: the same algorithm) for the same chain at the
//!   same fixed pseudo-random state, both timed by the throw-away binary, in turns over five
//!   rounds, each round's figure the median of 201 batches long enough to be timed; the
//!   least of the five rounds is reported for each (the machine's other load only slows);
//! - `max_rel_diff`: `|rhs_generated - rhs_by_hand|_inf / |rhs_by_hand|_inf` at that state;
//! - `generated_parts`, and `recursive`: whether the derive chose its recursive
//!   (`articulated_body`) evaluation.
//!
//! Forms: `explicit` writes every link as a `#[rigid]` with its position and angle written
//! out; `chain` writes the joint-tree `#[chain(..)]`. Without `--form` the report probes
//! `chain` at N = 2 and falls back to `explicit` (saying so on stderr) when that fails.
//! A failed build or run is a row with an `error`, not a panic. Bad arguments (`--sizes 0`,
//! an empty list, `--max` below 2) are refused with exit status 2 before any work.

use clap::{CommandFactory, Parser, ValueEnum};
use mechanisms::chain_by_hand::{chain_source, explicit_source};
use mechanisms::spatial_chain_by_hand::spatial_chain_source;
use serde::Serialize;
use std::fs;
use std::io::Read;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The timer written into every throw-away crate, which times its generated chain and the
/// hand-written one in turns with it: median over 201 batches of ns per call, a batch long
/// enough (>= 200 us) to time.
const TIMER_SRC: &str = r#"
fn median_ns<F: FnMut()>(mut f: F) -> f64 {
    let mut batch: u64 = 1;
    loop {
        let start = std::time::Instant::now();
        for _ in 0..batch {
            f();
        }
        if start.elapsed().as_secs_f64() >= 2e-4 || batch >= 1 << 24 {
            break;
        }
        batch *= 2;
    }
    let mut samples: Vec<f64> = Vec::with_capacity(201);
    for _ in 0..201 {
        let start = std::time::Instant::now();
        for _ in 0..batch {
            f();
        }
        samples.push(start.elapsed().as_secs_f64() * 1e9 / batch as f64);
    }
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}
"#;

/// Rounds of (generated, hand-written) timings in a throw-away crate.
const ROUNDS: usize = 5;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
enum Form {
    /// Every link a `#[rigid]` with its position and angle written out.
    Explicit,
    /// The joint-tree `#[chain(..)]` attribute.
    Chain,
}

/// Which chains: planar links on revolute joints, or spatial bars on universal joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
enum Family {
    Planar,
    Spatial,
}

#[derive(Debug, Parser)]
#[command(about = "Compile cost and run-time cost of generated N-link chains")]
struct Args {
    /// Print the rows as JSON.
    #[arg(long)]
    json: bool,
    /// Largest N of the default sizes (planar 2, 4, .., 256; spatial 4, 8, 10, 16, 32).
    /// Default: 256 (planar), 32 (planar explicit form, whose build grows too fast), 32
    /// (spatial).
    #[arg(long, value_parser = clap::value_parser!(u64).range(2..))]
    max: Option<u64>,
    /// The chain lengths to build instead, e.g. `--sizes 2,4,8,10,16` (each at least 1).
    #[arg(long, value_delimiter = ',', num_args = 1.., value_parser = clap::value_parser!(u64).range(1..))]
    sizes: Option<Vec<u64>>,
    /// Planar chains (default) or spatial chains of bars on universal joints.
    #[arg(long, value_enum, default_value_t = Family::Planar)]
    family: Family,
    /// Planar model form; default: `chain` if it builds at N = 2, else `explicit`.
    #[arg(long, value_enum)]
    form: Option<Form>,
    /// Where the throw-away crates are written (default: `<workspace>/target/scaling`).
    #[arg(long)]
    work_dir: Option<PathBuf>,
    /// `CARGO_TARGET_DIR` shared by the throw-away crates (default: `<work-dir>/target`).
    #[arg(long)]
    target_dir: Option<PathBuf>,
    /// Give up one build after this many seconds (the row reports it).
    #[arg(long, default_value_t = 1200)]
    timeout: u64,
}

/// One row of the report.
#[derive(Debug, Clone, Default, Serialize)]
struct Row {
    n_bodies: usize,
    family: Option<Family>,
    form: Option<Form>,
    expand_s: Option<f64>,
    build_s: Option<f64>,
    peak_mb: Option<f64>,
    generated_lines: Option<usize>,
    rhs_ns: Option<f64>,
    handwritten_rhs_ns: Option<f64>,
    /// `rhs_ns / handwritten_rhs_ns`.
    ratio: Option<f64>,
    statements: Option<usize>,
    generated_parts: Vec<String>,
    recursive: Option<bool>,
    max_rel_diff: Option<f64>,
    /// The machine's 1-minute load average before the build: other processes slow builds
    /// and timings down.
    load_1min: Option<f64>,
    error: Option<String>,
}

const M: f64 = 1.3;
const L: f64 = 0.7;
const G: f64 = 9.81;
/// A spatial bar's centroidal moments of inertia: `m l^2 / 12` across, a thin bar's along.
const I: f64 = M * L * L / 12.0;
const J: f64 = 0.004;

fn main() {
    let args = Args::parse();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("mechanisms/ sits in the workspace")
        .to_path_buf();
    let work = args
        .work_dir
        .clone()
        .unwrap_or_else(|| root.join("target").join("scaling"));
    let target = args
        .target_dir
        .clone()
        .unwrap_or_else(|| work.join("target"));
    let timeout = Duration::from_secs(args.timeout);
    let max = args.max.map_or(
        match (args.family, args.form) {
            (Family::Planar, Some(Form::Explicit)) | (Family::Spatial, _) => 32,
            (Family::Planar, _) => 256,
        },
        |m| m as usize,
    );
    let defaults: &[usize] = match args.family {
        Family::Planar => &[2, 4, 8, 16, 32, 64, 128, 256],
        Family::Spatial => &[4, 8, 10, 16, 32],
    };
    let ns: Vec<usize> = match &args.sizes {
        Some(sizes) => sizes.iter().map(|&n| n as usize).collect(),
        None => defaults.iter().copied().filter(|&n| n <= max).collect(),
    };
    if ns.is_empty() {
        Args::command()
            .error(
                clap::error::ErrorKind::ValueValidation,
                format!("no chain sizes up to --max {max}"),
            )
            .exit();
    }
    let ctx = Ctx {
        root,
        work,
        target,
        timeout,
        family: args.family,
    };

    // The form, and the warm-up build that compiles every dependency once.
    let form = match args.form {
        Some(f) => f,
        None if args.family == Family::Spatial => Form::Chain,
        None => {
            eprintln!("scaling: probing the `chain` form at N = 2 (also the warm-up build)");
            match ctx.build(2, Form::Chain, false) {
                Ok(_) => Form::Chain,
                Err(e) => {
                    eprintln!(
                        "scaling: note: the `chain` form does not build yet, using `explicit`:\n{}",
                        indent(&e)
                    );
                    Form::Explicit
                }
            }
        }
    };
    eprintln!("scaling: warm-up build ({form:?} form, N = 2)");
    if let Err(e) = ctx.build(2, form, false) {
        eprintln!("scaling: warm-up build failed:\n{}", indent(&e));
    }

    let mut rows = Vec::new();
    for &n in &ns {
        let row = ctx.row(n, form);
        if let Some(e) = &row.error {
            eprintln!("[N={n}] error:\n{}", indent(e));
        }
        rows.push(row);
    }

    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&rows).expect("rows serialise")
        );
    } else {
        print_table(args.family, form, &rows);
    }
}

struct Ctx {
    root: PathBuf,
    work: PathBuf,
    target: PathBuf,
    timeout: Duration,
    family: Family,
}

impl Ctx {
    fn crate_dir(&self, n: usize) -> PathBuf {
        self.work.join(package_name(self.family, n))
    }

    fn dump_dir(&self, n: usize) -> PathBuf {
        self.crate_dir(n).join("expand")
    }

    /// Write the throw-away crate for `n` links and build it; returns the build's wall time
    /// or the compiler's error.
    fn build(&self, n: usize, form: Form, dump: bool) -> Result<f64, String> {
        let dir = self.crate_dir(n);
        write_crate(&self.root, &dir, n, self.family, form)
            .map_err(|e| format!("writing the crate: {e}"))?;
        let dump_dir = self.dump_dir(n);
        let _ = fs::remove_dir_all(&dump_dir);
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
        // GNU time reports the largest resident set of cargo and of the compilers it
        // waited for.
        let mut cmd = if gnu_time() {
            let mut c = Command::new("time");
            c.args(["-f", "%M", "-o"])
                .arg(dir.join("peak_kb"))
                .arg(cargo);
            c
        } else {
            Command::new(cargo)
        };
        let _ = fs::remove_file(dir.join("peak_kb"));
        cmd.args(["build", "--release", "--color", "never"])
            .current_dir(&dir)
            .env("CARGO_TARGET_DIR", &self.target)
            .env_remove("MBD_EXPAND_DUMP");
        if dump {
            cmd.env("MBD_EXPAND_DUMP", &dump_dir);
        }
        let log = dir.join("build.log");
        let start = Instant::now();
        let status = run_with_timeout(&mut cmd, &log, self.timeout)?;
        let seconds = start.elapsed().as_secs_f64();
        if status {
            Ok(seconds)
        } else {
            let text = fs::read_to_string(&log).unwrap_or_default();
            Err(compiler_errors(&text))
        }
    }

    fn row(&self, n: usize, form: Form) -> Row {
        let mut row = Row {
            n_bodies: n,
            family: Some(self.family),
            form: Some(form),
            ..Row::default()
        };
        row.load_1min = mechanisms::accuracy::load_average()
            .split_whitespace()
            .next()
            .and_then(|s| s.parse().ok());
        eprintln!(
            "[N={n}] building ({form:?} form), load average {}",
            row.load_1min.map_or("?".into(), |l| format!("{l:.2}"))
        );
        match self.build(n, form, true) {
            Ok(s) => row.build_s = Some(s),
            Err(e) => {
                row.error = Some(format!("build failed: {e}"));
                return row;
            }
        }
        row.peak_mb = fs::read_to_string(self.crate_dir(n).join("peak_kb"))
            .ok()
            .and_then(|s| s.trim().parse::<f64>().ok())
            .map(|kb| kb / 1024.0);
        let name = struct_name(self.family, n);
        let dump = self.dump_dir(n);
        row.expand_s = fs::read_to_string(dump.join(format!("main.{name}.time")))
            .ok()
            .and_then(|s| s.trim().parse().ok());
        match fs::read_to_string(dump.join(format!("main.{name}.rs"))) {
            Ok(code) => match syn::parse_file(&code) {
                Ok(file) => row.generated_lines = Some(code_lines(&prettyplease::unparse(&file))),
                Err(e) => eprintln!("[N={n}] the generated code does not parse as a file: {e}"),
            },
            Err(_) => eprintln!("[N={n}] no dump of the generated code (MBD_EXPAND_DUMP)"),
        }
        eprintln!(
            "[N={n}] built in {:.2} s, peak {} MB (expansion {}), {} generated lines; timing",
            row.build_s.unwrap_or(f64::NAN),
            row.peak_mb.map_or("?".into(), |m| format!("{m:.0}")),
            row.expand_s.map_or("?".into(), |s| format!("{s:.3} s")),
            row.generated_lines.map_or("?".into(), |l| l.to_string()),
        );

        // The generated model, timed by its own binary.
        let exe = self
            .target
            .join("release")
            .join(package_name(self.family, n));
        let out = dir_output(&exe, &self.crate_dir(n), self.timeout);
        let out = match out {
            Ok(o) => o,
            Err(e) => {
                row.error = Some(format!("running the chain binary: {e}"));
                return row;
            }
        };
        for line in out.lines() {
            let (key, value) = line.split_once(' ').unwrap_or((line, ""));
            match key {
                "rhs_ns" => row.rhs_ns = value.parse().ok(),
                "handwritten_rhs_ns" => row.handwritten_rhs_ns = value.parse().ok(),
                "max_rel_diff" => row.max_rel_diff = value.parse().ok(),
                "statements" => row.statements = value.parse().ok(),
                "part" => row.generated_parts.push(value.to_string()),
                "error" => row.error = Some(format!("rhs: {value}")),
                _ => {}
            }
        }
        row.recursive = Some(row.generated_parts.iter().any(|p| p == "articulated_body"));

        if let (Some(a), Some(b)) = (row.rhs_ns, row.handwritten_rhs_ns) {
            row.ratio = Some(a / b);
        }
        eprintln!(
            "[N={n}] rhs {} ns generated, {} ns by hand",
            row.rhs_ns.map_or("?".into(), |v| format!("{v:.1}")),
            row.handwritten_rhs_ns
                .map_or("?".into(), |v| format!("{v:.1}")),
        );
        row
    }
}

/// Lines of formatted code, without the one-per-line items of the grouped declarations
/// `let (t0, t1, ..): (f64, f64, ..);` that long generated bodies start with (they would
/// count every temporary twice).
fn code_lines(formatted: &str) -> usize {
    formatted
        .lines()
        .map(str::trim)
        .filter(|l| {
            let item = l.strip_suffix(',').unwrap_or(l);
            let temporary = item
                .strip_prefix('t')
                .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()));
            !(l.ends_with(',') && (temporary || item == "f64"))
        })
        .count()
}

/// Whether GNU time is on the `PATH` as `time` (`-f %M` prints the maximum resident set
/// in KB); without it the peak-memory column stays empty.
fn gnu_time() -> bool {
    static FOUND: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *FOUND.get_or_init(|| {
        Command::new("time")
            .args(["-f", "%M", "true"])
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

fn struct_name(family: Family, n: usize) -> String {
    match family {
        Family::Planar => format!("Chain{n}"),
        Family::Spatial => format!("Spatial{n}"),
    }
}

fn package_name(family: Family, n: usize) -> String {
    match family {
        Family::Planar => format!("mbd-scaling-chain{n}"),
        Family::Spatial => format!("mbd-scaling-spatial{n}"),
    }
}

/// The fixed pseudo-random state `[q; qd]` (entries in [-1, 1)), the same for every form.
fn state(n: usize) -> Vec<f64> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15 ^ n as u64;
    (0..2 * n)
        .map(|_| {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        })
        .collect()
}

fn write_crate(
    root: &Path,
    dir: &Path,
    n: usize,
    family: Family,
    form: Form,
) -> std::io::Result<()> {
    fs::create_dir_all(dir.join("src"))?;
    let manifest = format!(
        "[package]\nname = \"{}\"\nversion = \"0.0.0\"\nedition = \"2024\"\npublish = false\n\n\
         [dependencies]\nmbd = {{ path = {:?} }}\nmechanisms = {{ path = {:?} }}\n\n\
         # Not a member of the mbd workspace above it.\n[workspace]\n",
        package_name(family, n),
        root.display().to_string(),
        root.join("mechanisms").display().to_string(),
    );
    fs::write(dir.join("Cargo.toml"), manifest)?;
    // The workspace's lock file, so the throw-away crates use the same dependency versions.
    if let Ok(lock) = fs::read(root.join("Cargo.lock")) {
        fs::write(dir.join("Cargo.lock"), lock)?;
    }
    let name = struct_name(family, n);
    // The model, its parameters, the hand-written twin and the number of coordinates.
    let (model, fields, hand, coords) = match (family, form) {
        (Family::Planar, Form::Explicit) => (
            explicit_source(&name, n),
            format!("m: {M:?}, l: {L:?}, g: {G:?}"),
            format!("mechanisms::chain_by_hand::ChainByHand::<{n}>::new({M:?}, {L:?}, {G:?})"),
            n,
        ),
        (Family::Planar, Form::Chain) => (
            chain_source(&name, n),
            format!("m: {M:?}, l: {L:?}, g: {G:?}"),
            format!("mechanisms::chain_by_hand::ChainByHand::<{n}>::new({M:?}, {L:?}, {G:?})"),
            n,
        ),
        (Family::Spatial, _) => (
            spatial_chain_source(&name, n, ""),
            format!("m: {M:?}, l: {L:?}, i: {I:?}, j: {J:?}, g: {G:?}"),
            format!(
                "mechanisms::spatial_chain_by_hand::SpatialChainByHand::<{n}>::new({M:?}, {L:?}, {I:?}, {J:?}, {G:?})"
            ),
            2 * n,
        ),
    };
    let y: Vec<String> = state(coords).iter().map(|v| format!("{v:?}")).collect();
    // rustc expands a struct's attributes one level deeper each: a model written body by
    // body needs a recursion limit above its attribute count (default 128).
    let limit = (2 * n + 64).max(128);
    let main = format!(
        "//! Throw-away crate written by the mbd `scaling` report: a {n}-body chain.\n\
         #![recursion_limit = \"{limit}\"]\n\
         #![allow(dead_code)]\n\
         use mbd::prelude::*;\n\n\
         {model}\n\
         {TIMER_SRC}\n\n\
         fn main() {{\n\
         \x20   let model = {name} {{ {fields} }};\n\
         \x20   let y = mbd::Vector::<{d}>::from_column_slice(&[{y}]);\n\
         \x20   for part in {name}::GENERATED.parts {{ println!(\"part {{part}}\"); }}\n\
         \x20   println!(\"statements {{}}\", {name}::GENERATED.statements);\n\
         \x20   match model.rhs(0.0, &y) {{\n\
         \x20       Err(e) => println!(\"error {{e}}\"),\n\
         \x20       Ok(v) => {{\n\
         \x20           let hand = {hand};\n\
         \x20           match hand.rhs(0.0, &y) {{\n\
         \x20               Err(e) => println!(\"error hand-written: {{e}}\"),\n\
         \x20               Ok(h) => println!(\"max_rel_diff {{:?}}\", (v - h).amax() / h.amax()),\n\
         \x20           }}\n\
         \x20           // Generated and hand-written timed in turns, {ROUNDS} rounds: the least\n\
         \x20           // median of each is the one least disturbed by the rest of the machine.\n\
         \x20           let (mut generated, mut by_hand) = (f64::INFINITY, f64::INFINITY);\n\
         \x20           for _ in 0..{ROUNDS} {{\n\
         \x20               generated = generated.min(median_ns(|| {{\n\
         \x20                   let _ = std::hint::black_box(model.rhs(0.0, std::hint::black_box(&y)));\n\
         \x20               }}));\n\
         \x20               by_hand = by_hand.min(median_ns(|| {{\n\
         \x20                   let _ = std::hint::black_box(hand.rhs(0.0, std::hint::black_box(&y)));\n\
         \x20               }}));\n\
         \x20           }}\n\
         \x20           println!(\"rhs_ns {{generated:?}}\");\n\
         \x20           println!(\"handwritten_rhs_ns {{by_hand:?}}\");\n\
         \x20       }}\n\
         \x20   }}\n\
         }}\n",
        d = 2 * coords,
        y = y.join(", "),
    );
    fs::write(dir.join("src").join("main.rs"), main)
}

/// Run `cmd` in its own process group with stdout and stderr to `log`; kill the group after
/// `timeout`. `Ok(success)`, or an error when it could not start or timed out.
fn run_with_timeout(cmd: &mut Command, log: &Path, timeout: Duration) -> Result<bool, String> {
    let file = fs::File::create(log).map_err(|e| e.to_string())?;
    let err = file.try_clone().map_err(|e| e.to_string())?;
    let mut child = cmd
        .stdout(Stdio::from(file))
        .stderr(Stdio::from(err))
        .stdin(Stdio::null())
        .process_group(0)
        .spawn()
        .map_err(|e| format!("cannot start {cmd:?}: {e}"))?;
    let start = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return Ok(status.success()),
            Ok(None) if start.elapsed() > timeout => {
                // The whole group: cargo and the rustc it started.
                let _ = Command::new("kill")
                    .args(["-KILL", "--", &format!("-{}", child.id())])
                    .status();
                let _ = child.wait();
                return Err(format!("timed out after {} s", timeout.as_secs()));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return Err(e.to_string()),
        }
    }
}

/// Run the chain binary and return its stdout.
fn dir_output(exe: &Path, dir: &Path, timeout: Duration) -> Result<String, String> {
    let log = dir.join("run.log");
    let mut cmd = Command::new(exe);
    if !run_with_timeout(&mut cmd, &log, timeout)? {
        let text = fs::read_to_string(&log).unwrap_or_default();
        return Err(format!("{} failed:\n{text}", exe.display()));
    }
    let mut text = String::new();
    fs::File::open(&log)
        .and_then(|mut f| f.read_to_string(&mut text))
        .map_err(|e| e.to_string())?;
    Ok(text)
}

/// The compiler's errors from a cargo log: from each `error` line to the next blank line,
/// at most 40 lines; the log's tail when there is none.
fn compiler_errors(log: &str) -> String {
    let mut out = Vec::new();
    let mut inside = false;
    for line in log.lines() {
        if line.starts_with("error") {
            inside = true;
        }
        if inside {
            if line.trim().is_empty() {
                inside = false;
                out.push("");
            } else {
                out.push(line);
            }
        }
    }
    if out.is_empty() {
        out = log.lines().rev().take(20).collect();
        out.reverse();
    }
    out.truncate(40);
    out.join("\n")
}

fn indent(s: &str) -> String {
    s.lines()
        .map(|l| format!("    {l}"))
        .collect::<Vec<_>>()
        .join("\n")
}

fn print_table(family: Family, form: Form, rows: &[Row]) {
    let f = |v: Option<f64>, p: usize| v.map_or("-".to_string(), |v| format!("{v:.p$}"));
    match family {
        Family::Planar => println!("scaling of generated planar N-link chains ({form:?} form)"),
        Family::Spatial => {
            println!("scaling of generated spatial chains of N bodies on universal joints")
        }
    }
    println!(
        "{:>4} {:>10} {:>9} {:>8} {:>9} {:>11} {:>11} {:>7} {:>9} {:>10}  parts",
        "N",
        "expand_s",
        "build_s",
        "peak_mb",
        "stmts",
        "rhs_ns",
        "by_hand_ns",
        "ratio",
        "rel_diff",
        "recursive"
    );
    for r in rows {
        println!(
            "{:>4} {:>10} {:>9} {:>8} {:>9} {:>11} {:>11} {:>7} {:>9} {:>10} {:>5}  {}",
            r.n_bodies,
            f(r.expand_s, 3),
            f(r.build_s, 2),
            f(r.peak_mb, 0),
            r.statements.map_or("-".into(), |l| l.to_string()),
            f(r.rhs_ns, 1),
            f(r.handwritten_rhs_ns, 1),
            f(r.ratio, 2),
            r.max_rel_diff.map_or("-".into(), |v| format!("{v:.1e}")),
            r.recursive.map_or("-".into(), |b| b.to_string()),
            f(r.load_1min, 1),
            r.generated_parts.join(","),
        );
        if let Some(e) = &r.error {
            println!("      error: {}", e.lines().next().unwrap_or_default());
        }
    }
    println!(
        "build_s is the wall time of `cargo build --release` of the chain crate alone (dependencies \
         prebuilt), expansion included; peak_mb its largest resident set (cargo or rustc); ratio = rhs_ns / by_hand_ns; load = 1-minute load average before the build \
         (2 cores)"
    );
}
