//! Reliability through the `droplet` binary: nothing lost, nothing hung.
//!
//! - a catalogue of malformed and extreme inputs: each exits with its documented code
//!   (2 for bad input), names what is wrong, never panics, and returns within seconds (the
//!   tiny-step cases within one);
//! - corrupt stored runs are reported, moved aside and recomputed; `merge` refuses to build
//!   tables while a run is missing or unreadable;
//! - an oversized spec is refused before anything is written;
//! - SIGKILL at many moments, then resume: tables identical to an uninterrupted sweep;
//! - stale temporaries of interrupted table and picture writes are removed by the next run;
//! - a whole sweep and a shard never work on one directory at the same time.
//!
//! With `DROPLET_RELIABILITY_DIR` set, the catalogue and kill tests write their counts there
//! (`inputs.md`, `kills.md`): the README's reliability section quotes them.
mod common;

use common::{droplet, json, kill_at_random_moments, run, sweep, table_without_wall, write_spec};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

/// Writes a report section when `DROPLET_RELIABILITY_DIR` is set.
fn report(name: &str, text: &str) {
    if let Ok(dir) = std::env::var("DROPLET_RELIABILITY_DIR") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(Path::new(&dir).join(name), text).unwrap();
    }
}

/// A tiny sweep: 12 runs at N = 32, fixed steps; a fraction of a second per run.
const TINY: &str = "name: tiny
grid:
  eta_t: [0.07, 0.09, 0.11]
  kappa2: [0.10, 0.12]
initial_conditions: [i, iii]
solver:
  n: 32
  dt: 0.05
  tol: 0
  t_max: 150
";

fn tables_equal(a: &Path, b: &Path) {
    for t in ["runs.parquet", "points.parquet"] {
        let x = table_without_wall(&a.join(t));
        let y = table_without_wall(&b.join(t));
        assert!(x.equals_missing(&y), "{t} differs:\n{x}\n{y}");
    }
}

fn run_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir.join("runs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    v.sort();
    v
}

#[test]
fn corrupt_stored_runs_are_moved_aside_and_recomputed_and_merge_refuses_gaps() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let reference = dir.path().join("ref");
    json(&sweep(&spec, &reference, &[]));
    let out = dir.path().join("o");
    json(&sweep(&spec, &out, &[]));
    let files = run_files(&out);
    assert_eq!(files.len(), 12);
    // Truncated, empty, garbage, and another run's (valid) record under this key.
    let whole = std::fs::read(&files[0]).unwrap();
    std::fs::write(&files[0], &whole[..whole.len() / 2]).unwrap();
    std::fs::write(&files[1], b"").unwrap();
    std::fs::write(&files[2], b"\xff\xfe not json").unwrap();
    std::fs::copy(&files[4], &files[3]).unwrap();

    // merge: exit 1, no tables, the unreadable runs named.
    std::fs::remove_file(out.join("runs.parquet")).unwrap();
    let m = run(&["merge", out.to_str().unwrap()]);
    assert_eq!(m.status.code(), Some(1));
    let err = String::from_utf8_lossy(&m.stderr);
    assert!(err.contains("4 of 12 runs are missing"), "{err}");
    assert!(err.contains("unreadable"), "{err}");
    assert!(!out.join("runs.parquet").exists());
    // status counts them.
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(st["runs_corrupt"], 4, "{st}");
    assert_eq!(st["runs_done"], 8, "{st}");
    // The pace: every file is seconds old, so it is measured over the 60 s floor; with one
    // stored 5 min ago, over those 5 min; one stored 20 min ago is outside the window.
    let eta = |st: &serde_json::Value| st["eta_s"].as_f64().unwrap();
    assert_eq!(st["runs_recent"], 12, "{st}");
    assert_eq!(st["pace_s"], 60.0, "{st}");
    assert!((eta(&st) - 4.0 * 60.0 / 12.0).abs() < 1e-9, "{st}");
    let age = |f: &Path, s: u64| {
        let file = std::fs::File::options().write(true).open(f).unwrap();
        let t = std::time::SystemTime::now() - Duration::from_secs(s);
        file.set_modified(t).unwrap();
    };
    age(&files[6], 300);
    age(&files[7], 1200);
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(st["runs_recent"], 11, "{st}");
    let pace = st["pace_s"].as_f64().unwrap();
    assert!((300.0..310.0).contains(&pace), "{st}");
    assert!((eta(&st) - 4.0 * pace / 11.0).abs() < 1e-9, "{st}");

    // The sweep moves them aside (never deletes), recomputes them, and the tables are whole.
    let o = sweep(&spec, &out, &[]);
    let summary = json(&o);
    assert_eq!(summary["computed"], 4, "{summary}");
    assert_eq!(summary["reused"], 8, "{summary}");
    assert_eq!(summary["corrupt"].as_array().unwrap().len(), 4, "{summary}");
    let aside: Vec<_> = std::fs::read_dir(out.join("corrupt"))
        .unwrap()
        .flatten()
        .collect();
    assert_eq!(aside.len(), 4);
    let moved = summary["corrupt"][0]["moved_to"].as_str().unwrap();
    assert!(Path::new(moved).exists());
    tables_equal(&reference, &out);
    assert_eq!(run_files(&out).len(), 12);

    // A missing run: merge exits 1 and writes nothing; with all runs present it succeeds.
    std::fs::remove_file(&files[5]).unwrap();
    let before = std::fs::metadata(out.join("runs.parquet"))
        .unwrap()
        .modified()
        .unwrap();
    let m = run(&["merge", out.to_str().unwrap()]);
    assert_eq!(m.status.code(), Some(1));
    assert_eq!(
        std::fs::metadata(out.join("runs.parquet"))
            .unwrap()
            .modified()
            .unwrap(),
        before
    );
    json(&sweep(&spec, &out, &[]));
    json(&run(&[
        "merge",
        out.to_str().unwrap(),
        "--json",
        "--no-plot",
    ]));
    tables_equal(&reference, &out);
}

#[test]
fn an_oversized_spec_is_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("huge-out");
    // 1e5 x 1e5 points x 4 initial conditions = 4e10 runs.
    let spec = write_spec(
        dir.path(),
        "huge.yaml",
        &format!(
            "output: {}\ngrid:\n  eta_t: {{start: 0.05, stop: 0.14999, step: 1.0e-6}}\n  kappa2: {{start: 0.05, stop: 0.14999, step: 1.0e-6}}\n",
            out.display()
        ),
    );
    let started = Instant::now();
    let o = run(&["sweep", spec.to_str().unwrap()]);
    assert!(started.elapsed() < Duration::from_secs(5));
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("more than the limit of 1000000"), "{err}");
    assert!(err.contains("--max-runs"), "{err}");
    assert!(!out.exists(), "output directory created");
    // The limit is a deliberate choice: a small sweep over a lowered limit is refused too,
    // and runs once the limit allows it.
    let tiny = write_spec(dir.path(), "tiny.yaml", TINY);
    let o2 = dir.path().join("o2");
    let o = sweep(&tiny, &o2, &["--max-runs", "11"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!o2.exists());
    json(&sweep(&tiny, &o2, &["--max-runs", "12"]));
    let o = run(&["slurm", spec.to_str().unwrap(), "--shards", "4"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists(), "slurm wrote into the output directory");
}

/// One malformed or extreme input: arguments (`SPEC` replaced by the spec file, `DIR` by a
/// scratch directory), the exit code, and words the message must contain.
struct Case {
    what: &'static str,
    args: Vec<String>,
    code: i32,
    says: &'static [&'static str],
    /// Must return within this many seconds.
    within: f64,
}

fn case(what: &'static str, args: &[&str], code: i32, says: &'static [&'static str]) -> Case {
    Case {
        what,
        args: args.iter().map(|s| s.to_string()).collect(),
        code,
        says,
        within: 10.0,
    }
}

/// `c`, which must return within one second.
fn fast(c: Case) -> Case {
    Case { within: 1.0, ..c }
}

fn spec_case(what: &'static str, replace: (&str, &str), says: &'static [&'static str]) -> Case {
    let good = "name: m\ngrid:\n  eta_t: [0.08]\n  kappa2: [0.11]\nsolver:\n  n: 32\n  dt: 0.05\n  t_max: 10\n";
    assert!(good.contains(replace.0), "{what}");
    Case {
        what,
        args: vec![
            "sweep".into(),
            format!("SPEC:{}", good.replacen(replace.0, replace.1, 1)),
            "--out".into(),
            "DIR/out".into(),
        ],
        code: 2,
        says,
        within: 5.0,
    }
}

fn catalogue() -> Vec<Case> {
    let sim = |extra: &[&str]| -> Vec<String> {
        let mut v: Vec<String> = ["simulate", "--eta-t", "0.085", "--kappa2", "0.12"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        v.extend(extra.iter().map(|s| s.to_string()));
        v
    };
    let simc = |what, extra: &[&str], says, within| Case {
        what,
        args: sim(extra),
        code: 2,
        says,
        within,
    };
    vec![
        // Steps and intervals that would never finish.
        simc(
            "fixed step 1e-300",
            &["--dt", "1e-300", "--tol", "0", "--t-max", "50"],
            &["dt", "steps"],
            1.0,
        ),
        simc(
            "fixed step 1e-9",
            &["--dt", "1e-9", "--tol", "0"],
            &["dt", "steps"],
            1.0,
        ),
        simc(
            "adaptive cap 1e-300",
            &["--dt", "1e-300", "--dt-max", "1e-300"],
            &["dt_max", "steps"],
            1.0,
        ),
        simc(
            "series every 1e-300",
            &["--every", "1e-300", "--series", "DIR/s.parquet"],
            &["every", "rows"],
            1.0,
        ),
        simc(
            "picture every 1e-9",
            &["--every", "1e-9", "--picture", "DIR/p.png"],
            &["every", "rows"],
            1.0,
        ),
        simc("every 0", &["--every", "0"], &["every"], 1.0),
        simc("every nan", &["--every", "NaN"], &["every"], 1.0),
        spec_case(
            "spec fixed step 1e-300",
            ("dt: 0.05", "dt: 1.0e-300\n  tol: 0"),
            &["solver.dt", "steps"],
        ),
        spec_case(
            "spec dt_max 1e-300",
            ("dt: 0.05", "dt: 1.0e-300\n  dt_max: 1.0e-300"),
            &["solver.dt_max"],
        ),
        // Negative numbers are values, rejected with the field's message.
        Case {
            what: "negative eta_t first",
            args: ["simulate", "--eta-t", "-0.1", "--kappa2", "0.1"]
                .iter()
                .map(|s| s.to_string())
                .collect(),
            code: 2,
            says: &["eta_t", "> 0"],
            within: 5.0,
        },
        case(
            "negative kappa2",
            &["simulate", "--eta-t", "0.085", "--kappa2", "-1"],
            2,
            &["kappa2", ">= 0"],
        ),
        simc("negative mass", &["--mass", "-0.1"], &["mass"], 5.0),
        simc("negative dt", &["--dt", "-0.01"], &["dt"], 5.0),
        simc("negative t_max", &["--t-max", "-5"], &["t_max"], 5.0),
        simc("zero eta2", &["--eta2", "0"], &["eta2"], 5.0),
        simc("infinite box", &["--box-len", "inf"], &["box_len"], 5.0),
        // Initial conditions: the bound that is broken.
        simc(
            "custom ic s >= 1",
            &["--ic", "custom:0,0,2,0"],
            &["s = sqrt(a2^2 + b2^2) = 2", "< 1"],
            5.0,
        ),
        simc(
            "custom ic three numbers",
            &["--ic", "custom:0,0,0.1"],
            &["four numbers", "got 3"],
            5.0,
        ),
        simc(
            "custom ic not numbers",
            &["--ic", "custom:a,b,c,d"],
            &["four numbers"],
            5.0,
        ),
        simc(
            "custom ic nan",
            &["--ic", "custom:NaN,0,0,0"],
            &["finite"],
            5.0,
        ),
        simc(
            "unknown ic",
            &["--ic", "vii"],
            &["unknown initial condition"],
            5.0,
        ),
        // Geometry: the field at fault, and an unresolved droplet.
        simc(
            "sigma 10",
            &["--sigma", "10"],
            &["`sigma`", "thinner than the droplet"],
            5.0,
        ),
        simc(
            "sigma far below dx",
            &["--sigma", "1e-4"],
            &["`sigma`", "grid cell"],
            5.0,
        ),
        simc(
            "radius far below dx",
            &["--radius", "0.12"],
            &["`radius`", "grid cells"],
            5.0,
        ),
        simc(
            "radius too big for the box",
            &["--radius", "5"],
            &["`box_len`"],
            5.0,
        ),
        simc("coarse grid", &["--n", "16"], &["`radius`", "raise n"], 5.0),
        simc("odd n", &["--n", "31"], &["`n`"], 5.0),
        simc(
            "paper-fd above its stability limit",
            &["--scheme", "paper-fd", "--dt", "1e-3"],
            &["`dt`", "stability limit"],
            5.0,
        ),
        simc(
            "adaptive paper-fd",
            &["--scheme", "paper-fd", "--tol", "1e-4"],
            &["`tol`"],
            5.0,
        ),
        simc("unknown scheme", &["--scheme", "rk4"], &["rk4"], 5.0),
        simc(
            "stop beside a saddle with the paper's test",
            &["--steady", "test", "--stop-beside-saddle"],
            &["stop_beside_saddle", "steady = newton"],
            5.0,
        ),
        simc(
            "leap departures with the paper's test",
            &["--steady", "test", "--leap-departures"],
            &["leap_departures", "steady = newton"],
            5.0,
        ),
        simc(
            "leap departures with fixed steps",
            &["--tol", "0", "--leap-departures"],
            &["leap_departures", "adaptive"],
            5.0,
        ),
        simc(
            "series into a missing directory",
            &["--series", "DIR/no/such/s.parquet"],
            &["does not exist"],
            5.0,
        ),
        spec_case(
            "spec sigma below dx",
            ("solver:", "params: {sigma: 1.0e-4}\nsolver:"),
            &["params.sigma", "grid cell"],
        ),
        spec_case(
            "spec with the removed classify section",
            ("solver:", "classify: {beside_unstable: exclude}\nsolver:"),
            &["classify", "removed", "stable steady state"],
        ),
        spec_case(
            "spec stop_beside_saddle not true or false",
            ("solver:", "solver:\n  stop_beside_saddle: maybe"),
            &["solver.stop_beside_saddle", "maybe", "true"],
        ),
        spec_case(
            "spec stop_beside_saddle with the paper's test",
            (
                "solver:",
                "solver:\n  steady: test\n  stop_beside_saddle: true",
            ),
            &["solver.stop_beside_saddle", "steady = newton"],
        ),
        spec_case(
            "spec leap_departures not true or false",
            ("solver:", "solver:\n  leap_departures: 1"),
            &["solver.leap_departures", "1", "true"],
        ),
        spec_case(
            "spec sigma 10",
            ("solver:", "params: {sigma: 10}\nsolver:"),
            &["params.sigma"],
        ),
        spec_case(
            "spec radius below dx",
            ("solver:", "params: {radius: 0.5}\nsolver:"),
            &["params.radius"],
        ),
        spec_case(
            "spec unstable paper-fd",
            (
                "  n: 32\n  dt: 0.05\n",
                "  scheme: paper-fd\n  n: 64\n  dt: 0.01\n  tol: 0\n",
            ),
            &["solver.dt", "stability limit"],
        ),
        spec_case(
            "spec custom ic s >= 1",
            (
                "solver:",
                "initial_conditions: [\"custom:0,0,2,0\"]\nsolver:",
            ),
            &["initial_conditions", "< 1"],
        ),
        spec_case(
            "spec negative step",
            (
                "eta_t: [0.08]",
                "eta_t: {start: 0.07, stop: 0.08, step: -0.01}",
            ),
            &["grid.eta_t.step"],
        ),
        spec_case(
            "spec unknown key",
            ("name: m", "name: m\ncolour: red"),
            &["colour"],
        ),
        spec_case("spec not yaml", ("name: m", "name: [m"), &["(document)"]),
        spec_case("spec n huge", ("n: 32", "n: 100000"), &["solver.n"]),
        spec_case(
            "spec t_max inf",
            ("t_max: 10", "t_max: .inf"),
            &["solver.t_max"],
        ),
        spec_case(
            "spec mass string",
            ("solver:", "params: {mass: heavy}\nsolver:"),
            &["params.mass"],
        ),
        // Files that cannot be read, and outputs that cannot be written.
        case(
            "missing spec file",
            &["sweep", "DIR/none.yaml"],
            2,
            &["none.yaml", "cannot be read"],
        ),
        case(
            "spec is a directory",
            &["sweep", "DIR"],
            2,
            &["cannot be read"],
        ),
        case(
            "spec not UTF-8",
            &["sweep", "BINARY"],
            2,
            &["bin.yaml", "UTF-8"],
        ),
        case(
            "out under a regular file",
            &[
                "sweep",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\nsolver: {n: 32, t_max: 1}\n",
                "--out",
                "FILE/out",
            ],
            2,
            &["output directory", "--out"],
        ),
        case(
            "slurm out under a regular file",
            &[
                "slurm",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shards",
                "2",
                "--out",
                "FILE/out",
            ],
            2,
            &["output directory"],
        ),
        case(
            "ode out under a regular file",
            &[
                "ode",
                "bifurcation",
                "--kappa2",
                "0.13",
                "--from",
                "0.07",
                "--to",
                "0.1",
                "--out",
                "FILE/out",
            ],
            2,
            &["output directory"],
        ),
        case(
            "fit-h0 out under a regular file",
            &["fit-h0", "--n", "32", "--out", "FILE/out"],
            2,
            &["output directory"],
        ),
        case(
            "status of no sweep",
            &["status", "DIR/nothing"],
            2,
            &["holds no sweep"],
        ),
        case(
            "merge of no sweep",
            &["merge", "DIR/nothing"],
            2,
            &["holds no sweep"],
        ),
        case(
            "plot of no sweep",
            &["plot", "DIR/nothing"],
            2,
            &["holds no sweep"],
        ),
        case(
            "sweep --jobs 0",
            &[
                "sweep",
                "SPEC:grid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--jobs",
                "0",
            ],
            2,
            &["--jobs"],
        ),
        case(
            "bad shard",
            &[
                "sweep",
                "SPEC:grid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shard",
                "3/3",
            ],
            2,
            &["shard"],
        ),
        case(
            "ode reversed line",
            &[
                "ode",
                "bifurcation",
                "--kappa2",
                "0.13",
                "--from",
                "0.1",
                "--to",
                "0.07",
            ],
            2,
            &["from < to"],
        ),
        Case {
            within: 1.0,
            ..case(
                "fit-h0 step 1e-300",
                &["fit-h0", "--step", "1e-300", "--out", "DIR/h0"],
                2,
                &["--step", "more than"],
            )
        },
        Case {
            within: 1.0,
            ..case(
                "ode line of 1e12 samples",
                &[
                    "ode",
                    "bifurcation",
                    "--kappa2",
                    "0.13",
                    "--from",
                    "0.07",
                    "--to",
                    "0.1",
                    "--steps",
                    "1000000000000",
                    "--out",
                    "DIR/ode",
                ],
                2,
                &["steps"],
            )
        },
        case(
            "ode negative radius",
            &["ode", "coefficients", "--radius", "-1"],
            2,
            &["radius"],
        ),
        // Parameter windows beyond the model's limits are refused before any work, naming the
        // option (a line to 1e10 once gave a wrong onset of motion, 1e300 wrong states).
        fast(case(
            "continue to 1e10",
            &[
                "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "1e10", "--n", "64",
                "--branch", "ic", "--out", "DIR/c",
            ],
            2,
            &["--to", "at most 10"],
        )),
        fast(case(
            "continue at kappa2 1e300",
            &[
                "continue", "--kappa2", "1e300", "--from", "0.07", "--to", "0.1", "--n", "64",
                "--out", "DIR/c",
            ],
            2,
            &["--kappa2", "at most 10"],
        )),
        fast(case(
            "continue from -inf",
            &[
                "continue", "--kappa2", "0.13", "--from", "-inf", "--to", "0.1", "--out", "DIR/c",
            ],
            2,
            &["--from", "finite"],
        )),
        fast(case(
            "ode line to 1e300",
            &[
                "ode", "bifurcation", "--kappa2", "0.13", "--from", "0.07", "--to", "1e300",
                "--out", "DIR/ode",
            ],
            2,
            &["--to", "at most 10"],
        )),
        fast(case(
            "boundaries window to 1e300",
            &["boundaries", "--eta-t", "0.07,1e300", "--n", "64", "--out", "DIR/b"],
            2,
            &["--eta-t", "at most 10"],
        )),
        fast(case(
            "boundaries negative window",
            &["boundaries", "--eta-t", "-0.1,0.1", "--out", "DIR/b"],
            2,
            &["--eta-t", "-0.1,0.1", "0 < LO < HI"],
        )),
        fast(case(
            "stability seed of negative numbers",
            &[
                "stability", "--eta-t", "0.085", "--kappa2", "0.112", "--seed", "-0.5,-2",
                "--n", "64",
            ],
            2,
            &["--seed", "|SHAPE| < 1"],
        )),
        // Specs: duplicated keys on their own line, sizes refused at once.
        spec_case(
            "spec name twice",
            ("t_max: 10", "t_max: 10\nname: x"),
            &[":9: `name`", "each key once"],
        ),
        spec_case(
            "spec grid axis twice",
            ("kappa2: [0.11]", "kappa2: [0.11]\n  eta_t: [0.09]"),
            &[":5: `grid.eta_t`", "each key once"],
        ),
        fast(Case {
            what: "spec refine min_step above the grid step",
            args: vec![
                "sweep".into(),
                "SPEC:name: m\ngrid:\n  eta_t: {start: 0.07, stop: 0.09, step: 0.01}\n  kappa2: {start: 0.1, stop: 0.12, step: 0.01}\nrefine: {levels: 1, min_step: {eta_t: 1.0e3, kappa2: 1.0e3}}\nsolver:\n  n: 32\n  dt: 0.05\n  t_max: 10\n".into(),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["refine.min_step.eta_t", "half the grid's eta_t step"],
            within: 1.0,
        }),
        fast(Case {
            what: "spec list of 400000 values",
            args: vec![
                "sweep".into(),
                format!(
                    "SPEC:grid:\n  eta_t: [{}]\n  kappa2: [0.1]\n",
                    (0..400_000).map(|i| (i + 1).to_string()).collect::<Vec<_>>().join(",")
                ),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["grid.eta_t", "a list of 400000 values", "at most 100000"],
            within: 1.0,
        }),
        fast(Case {
            what: "spec of 5 MB",
            args: vec![
                "sweep".into(),
                format!("SPEC:name: m\n#{}\n", "x".repeat(5 << 20)),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["(file)", "at most 4194304 bytes"],
            within: 1.0,
        }),
        fast(Case {
            what: "spec name of 1 MB",
            args: vec![
                "sweep".into(),
                format!(
                    "SPEC:name: {}\ngrid:\n  eta_t: [0.08]\n  kappa2: [0.11]\n",
                    "n".repeat(1 << 20)
                ),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["`name`", "a name of 1048576 characters", "at most 100"],
            within: 1.0,
        }),
        case("unknown command", &["fly"], 2, &["fly"]),
        case("no command", &[], 2, &["Usage"]),
    ]
}

#[test]
fn malformed_and_extreme_inputs_exit_with_their_code_name_the_problem_and_never_hang() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let file = write_spec(d, "a-file", "x");
    let binary = d.join("bin.yaml");
    std::fs::write(&binary, b"name: \xff\xfe\n").unwrap();
    let cases = catalogue();
    let mut lines = Vec::new();
    let mut slowest = 0.0f64;
    let mut slowest_s = 0.0f64;
    let mut codes = std::collections::BTreeMap::new();
    for (i, c) in cases.iter().enumerate() {
        let args: Vec<String> = c
            .args
            .iter()
            .map(|a| {
                if let Some(text) = a.strip_prefix("SPEC:") {
                    write_spec(d, &format!("spec-{i}.yaml"), text)
                        .display()
                        .to_string()
                } else {
                    a.replace("DIR", d.to_str().unwrap())
                        .replace("FILE", file.to_str().unwrap())
                        .replace("BINARY", binary.to_str().unwrap())
                }
            })
            .collect();
        let started = Instant::now();
        let o = droplet().args(&args).stdin(Stdio::null()).output().unwrap();
        let secs = started.elapsed().as_secs_f64();
        slowest = slowest.max(secs / c.within);
        slowest_s = slowest_s.max(secs);
        *codes.entry(c.code).or_insert(0usize) += 1;
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(c.code), "{}: {args:?}\n{err}", c.what);
        assert!(!err.contains("panicked"), "{}: panic\n{err}", c.what);
        for s in c.says {
            assert!(err.contains(s), "{}: message lacks {s:?}:\n{err}", c.what);
        }
        assert!(
            secs <= c.within,
            "{}: took {secs:.2} s (limit {} s)",
            c.what,
            c.within
        );
        lines.push(format!(
            "| {} | `{}` | {} | {:.2} s |",
            c.what,
            err.lines()
                .next()
                .unwrap_or("")
                .replace(d.to_str().unwrap(), "DIR")
                .replace('|', "/")
                .replace('`', "'"),
            c.code,
            secs
        ));
    }
    // Nothing was left in the scratch directory by a refused command but its own inputs.
    for written in ["out", "b", "c", "ode", "h0"] {
        assert!(!d.join(written).exists(), "{written} was created");
    }
    assert!(cases.len() >= 50);
    report(
        "inputs.md",
        &format!(
            "{} malformed or extreme inputs, each refused with its exit code and a message naming the problem ({}), 0 panics, 0 wrong answers (every case exits non-zero with nothing written), slowest refusal {:.2} s, none slower than {:.1} % of its time limit:\n\n| input | first line of the message | exit | time |\n|---|---|---|---|\n{}\n",
            cases.len(),
            codes
                .iter()
                .map(|(c, n)| format!("exit {c}: {n}"))
                .collect::<Vec<_>>()
                .join(", "),
            slowest_s,
            100.0 * slowest,
            lines.join("\n")
        ),
    );
}

#[test]
fn sigkill_at_many_moments_then_resume_gives_identical_tables() {
    let dir = tempfile::tempdir().unwrap();
    // Slow enough to be cut mid-way: 12 runs at N = 64.
    let spec_text = TINY.replace("n: 32", "n: 64");
    let spec = write_spec(dir.path(), "tiny.yaml", &spec_text);
    let reference = dir.path().join("ref");
    let started = Instant::now();
    json(&sweep(&spec, &reference, &["--jobs", "2"]));
    let full_ms = started.elapsed().as_millis() as u64;
    let resumed = dir.path().join("resumed");
    // Moments spread over the sweep's length by a fixed-seed generator (LCG).
    let (kills, tries) = kill_at_random_moments(&spec, &resumed, full_ms, 16, 40);
    assert!(kills >= 8, "only {kills} of {tries} tries were interrupted");
    json(&sweep(&spec, &resumed, &[]));
    assert_eq!(run_files(&resumed).len(), 12);
    tables_equal(&reference, &resumed);
    report(
        "kills.md",
        &format!(
            "{kills} SIGKILLs at fixed-seed random moments of a 12-run sweep ({tries} tries; a sweep that finished first was started over), each followed by a resume: the final tables equal an uninterrupted sweep's in every column but wall_s, with one record per run.\n"
        ),
    );
}

#[test]
fn stale_temporaries_of_interrupted_writes_are_gone_after_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let out = dir.path().join("o");
    json(&sweep(&spec, &out, &[]));
    // What a SIGKILL during the table, picture or run writes leaves behind.
    let old = std::time::SystemTime::now() - Duration::from_secs(3600);
    let stale: Vec<PathBuf> = [
        "runs.4242.tmp",
        "points.4242.tmp",
        "phase_map.4242.tmp",
        "runs/0123.4242.tmp",
    ]
    .iter()
    .map(|n| out.join(n))
    .collect();
    for p in &stale {
        std::fs::File::create(p).unwrap().set_modified(old).unwrap();
    }
    let o = run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    json(&o);
    for p in &stale {
        assert!(!p.exists(), "{} survived", p.display());
    }
    // Nothing partial: every picture is complete, no temporary anywhere.
    for name in [
        "phase_map.png",
        "phase_map.svg",
        "runs.parquet",
        "points.parquet",
    ] {
        assert!(
            std::fs::metadata(out.join(name)).unwrap().len() > 100,
            "{name}"
        );
    }
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .chain(std::fs::read_dir(out.join("runs")).unwrap())
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn a_whole_sweep_and_a_shard_never_share_a_directory() {
    let dir = tempfile::tempdir().unwrap();
    let slow = TINY
        .replace("n: 32", "n: 64")
        .replace("t_max: 150", "t_max: 600");
    let spec = write_spec(dir.path(), "slow.yaml", &slow);
    for (first, second) in [(None, Some("0/2")), (Some("1/2"), None)] {
        let out = dir.path().join(format!("o-{}", first.is_some()));
        let args = |shard: Option<&str>| {
            let mut v = vec![
                "sweep".to_string(),
                spec.display().to_string(),
                "--out".into(),
                out.display().to_string(),
                "--jobs".into(),
                "1".into(),
            ];
            if let Some(s) = shard {
                v.extend(["--shard".into(), s.to_string()]);
            }
            v
        };
        let mut child = droplet()
            .args(args(first))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        for _ in 0..200 {
            if out.join(".lock").exists() {
                break;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        std::thread::sleep(Duration::from_millis(150));
        let o = droplet().args(args(second)).output().unwrap();
        let still_running = child.try_wait().unwrap().is_none();
        child.kill().ok();
        child.wait().unwrap();
        assert!(still_running, "the first sweep ended too soon");
        assert_eq!(o.status.code(), Some(2), "{first:?} then {second:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("in use by another droplet process"), "{err}");
    }
}

/// A full disk (a 400 KiB tmpfs; needs root to mount, skipped with a message otherwise): the
/// write that fails is named, exits 1, and leaves no partial or empty file and no temporary.
#[test]
fn a_full_disk_is_named_and_leaves_no_partial_file() {
    let dir = tempfile::tempdir().unwrap();
    let mnt = dir.path().join("disk");
    std::fs::create_dir(&mnt).unwrap();
    let mounted = std::process::Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=400k", "tmpfs"])
        .arg(&mnt)
        .output()
        .is_ok_and(|o| o.status.success());
    if !mounted {
        eprintln!("skipped: cannot mount a small tmpfs here (needs root)");
        return;
    }
    let result = std::panic::catch_unwind(|| {
        let spec = write_spec(dir.path(), "tiny.yaml", TINY);
        let out = mnt.join("o");
        // Fill the disk, then free room step by step: each failure must be clean.
        let filler = mnt.join("filler");
        let mut failures = 0;
        for free_kib in [0usize, 60, 110, 160, 400] {
            std::fs::write(&filler, vec![0u8; (400 - free_kib.min(400)) * 1024]).ok();
            let o = droplet()
                .args([
                    "sweep",
                    spec.to_str().unwrap(),
                    "--out",
                    out.to_str().unwrap(),
                ])
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&o.stderr);
            if !o.status.success() {
                failures += 1;
                assert_eq!(o.status.code(), Some(1), "{err}");
                assert!(err.contains("No space left on device"), "{err}");
                assert!(err.contains(out.to_str().unwrap()), "no file named: {err}");
            }
            if out.is_dir() {
                for e in std::fs::read_dir(&out).unwrap().flatten() {
                    let name = e.file_name().to_string_lossy().to_string();
                    let len = e.metadata().unwrap().len();
                    assert!(!name.ends_with(".tmp"), "temporary {name} left");
                    assert!(
                        name.starts_with('.') || e.path().is_dir() || len > 0,
                        "empty {name}"
                    );
                }
            }
            std::fs::remove_file(&filler).ok();
        }
        assert!(failures >= 1, "the disk never filled up");
        assert!(out.join("phase_map.png").exists(), "never completed");
    });
    let _ = std::process::Command::new("umount").arg(&mnt).status();
    if let Err(e) = result {
        std::panic::resume_unwind(e);
    }
}

/// Runs `droplet args` with its stdout already closed by the reader (`droplet ... | true`).
fn into_closed_pipe(args: &[&str]) -> std::process::Output {
    let mut child = droplet()
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

#[test]
fn a_closed_stdout_ends_every_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let out = dir.path().join("o");
    let o = out.to_str().unwrap();
    let spec_s = spec.to_str().unwrap();
    let commands: Vec<Vec<&str>> = vec![
        vec!["sweep", spec_s, "--out", o],
        vec!["sweep", spec_s, "--out", o, "--json"],
        vec!["status", o],
        vec!["status", o, "--json"],
        vec!["merge", o],
        vec!["plot", o],
        vec![
            "simulate", "--eta-t", "0.085", "--kappa2", "0.12", "--n", "32", "--t-max", "5",
        ],
        vec![
            "stability",
            "--eta-t",
            "0.085",
            "--kappa2",
            "0.112",
            "--n",
            "32",
        ],
        vec!["ode", "coefficients"],
        vec!["ode", "coefficients", "--json"],
        vec![
            "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "0.1", "--n", "32",
            "--branch", "ic", "--out",
        ],
        vec!["--help"],
        vec!["sweep", "--help"],
        vec!["--version"],
    ];
    let cont = dir.path().join("c");
    for mut args in commands {
        if args.last() == Some(&"--out") {
            args.push(cont.to_str().unwrap());
        }
        let r = into_closed_pipe(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(!err.contains("panicked"), "{args:?}: panic\n{err}");
        assert_eq!(r.status.code(), Some(0), "{args:?}:\n{err}");
    }
    // The work was done all the same.
    assert!(out.join("runs.parquet").exists() && out.join("phase_map.png").exists());
}

#[test]
fn plot_draws_one_consistent_snapshot_and_says_when_points_are_missing() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let out = dir.path().join("o");
    let o = out.to_str().unwrap();
    json(&sweep(&spec, &out, &[]));
    // Complete: exit 0, nothing missing.
    let p = json(&run(&["plot", o, "--json"]));
    assert_eq!(
        (p["points"].as_u64(), p["missing"].as_u64()),
        (Some(6), Some(0)),
        "{p}"
    );
    // While another process holds the directory (a sweep at work), plot refuses and writes
    // nothing: its picture could land after the sweep's final one.
    let png = out.join("phase_map.png");
    let before = std::fs::metadata(&png).unwrap().modified().unwrap();
    let mut holder = std::process::Command::new("flock")
        // -o: the lock stays with flock itself, so killing it releases the lock.
        .args([
            "-x",
            "-o",
            out.join(".lock").to_str().unwrap(),
            "-c",
            "sleep 5",
        ])
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(500));
    let r = run(&["plot", o]);
    holder.kill().unwrap();
    holder.wait().unwrap();
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(err.contains("in use by another droplet process"), "{err}");
    assert_eq!(std::fs::metadata(&png).unwrap().modified().unwrap(), before);
    // An unreadable run: the picture shows the point as missing, and plot says so (exit 1).
    let files = run_files(&out);
    std::fs::write(&files[0], b"{ not json").unwrap();
    let r = run(&["plot", o]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("1 of 6 points are drawn as missing"), "{err}");
    assert!(err.contains("droplet status"), "{err}");
}

#[test]
fn boundaries_with_a_curve_outside_the_window_and_stability_messages_are_plain() {
    let dir = tempfile::tempdir().unwrap();
    // The reduced model's ID-stability curve lies outside this window: an empty curve is a
    // normal answer, not a panic.
    let b = dir.path().join("b");
    let r = run(&[
        "boundaries",
        "--eta-t",
        "0.07,0.1",
        "--kappa2",
        "0.16,0.17",
        "--n",
        "64",
        "--samples",
        "5",
        "--out",
        b.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    let text = String::from_utf8_lossy(&r.stdout);
    assert_eq!(r.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(text.contains("none in this window"), "{text}");
    let b2 = dir.path().join("b2");
    let r = run(&[
        "boundaries",
        "--eta-t",
        "0.0764,0.07641",
        "--n",
        "64",
        "--samples",
        "5",
        "--json",
        "--out",
        b2.to_str().unwrap(),
    ]);
    let v = json(&r);
    assert!(
        v["curves"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c["points"] == 0),
        "{v}"
    );
    // A Newton solve for MD that lands on the resting disk says so, not "did not converge".
    let r = run(&[
        "stability",
        "--eta-t",
        "0.085",
        "--kappa2",
        "0.112",
        "--seed",
        "0.9999,0.9999",
        "--n",
        "64",
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("to a resting droplet"), "{err}");
    assert!(!err.contains("did not converge"), "{err}");
}
