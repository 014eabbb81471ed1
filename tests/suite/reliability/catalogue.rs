//! The catalogue of malformed and extreme inputs: each exits with its documented code, names
//! what is wrong, never panics and returns within seconds.
use super::report;
use crate::common::{droplet, write_spec};
use std::process::Stdio;
use std::time::Instant;

/// One malformed or extreme input: arguments (`SPEC` replaced by the spec file, `DIR` by a
/// scratch directory), the exit code, and words the message must contain.
pub(super) struct Case {
    pub(super) what: &'static str,
    pub(super) args: Vec<String>,
    pub(super) code: i32,
    pub(super) says: &'static [&'static str],
    /// Must return within this many seconds.
    pub(super) within: f64,
}

pub(super) fn case(
    what: &'static str,
    args: &[&str],
    code: i32,
    says: &'static [&'static str],
) -> Case {
    Case {
        what,
        args: args.iter().map(|s| s.to_string()).collect(),
        code,
        says,
        within: 10.0,
    }
}

impl Case {
    /// This case with `from` replaced by `to` in its spec, and the words it must say.
    pub(super) fn replaced(mut self, from: &str, to: &str, says: &'static [&'static str]) -> Self {
        for a in &mut self.args {
            if a.starts_with("SPEC:") {
                assert!(a.contains(from), "{}", self.what);
                *a = a.replacen(from, to, 1);
            }
        }
        Self { says, ..self }
    }
}

/// `c`, which must return within one second.
pub(super) fn fast(c: Case) -> Case {
    Case { within: 1.0, ..c }
}

pub(super) fn spec_case(
    what: &'static str,
    replace: (&str, &str),
    says: &'static [&'static str],
) -> Case {
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

/// `droplet simulate` at a point of the Fig. 2a window with `extra` arguments.
fn sim(extra: &[&str]) -> Vec<String> {
    let mut v: Vec<String> = ["simulate", "--eta-t", "0.085", "--kappa2", "0.12"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    v.extend(extra.iter().map(|s| s.to_string()));
    v
}

/// A `droplet simulate` case ([`sim`]) refused with exit 2 within `within` seconds.
pub(super) fn simc(
    what: &'static str,
    extra: &[&str],
    says: &'static [&'static str],
    within: f64,
) -> Case {
    Case {
        what,
        args: sim(extra),
        code: 2,
        says,
        within,
    }
}

/// Every case: steps, initial conditions and geometry here, the rest in
/// [`super::refusals`] and [`super::spec_refusals`].
fn catalogue() -> Vec<Case> {
    [
        steps_that_never_finish(),
        initial_conditions(),
        geometry_and_scheme(),
        super::spec_refusals::structure(),
        super::refusals::cases(),
        super::spec_refusals::cases(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// Steps and intervals that would never finish.
fn steps_that_never_finish() -> Vec<Case> {
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
    ]
}

/// Initial conditions: the bound that is broken.
fn initial_conditions() -> Vec<Case> {
    vec![
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
    ]
}

/// Geometry (the field at fault, an unresolved droplet) and the scheme, on the command line.
fn geometry_and_scheme() -> Vec<Case> {
    vec![
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
            &["--tol", "fixed steps"],
            5.0,
        ),
        simc("unknown scheme", &["--scheme", "rk4"], &["rk4"], 5.0),
        simc(
            "stop beside a saddle with the paper's test",
            &["--steady", "test", "--stop-beside-saddle"],
            &["--stop-beside-saddle", "Newton finish"],
            5.0,
        ),
        simc(
            "leap departures with the paper's test",
            &["--steady", "test", "--leap-departures"],
            &["--leap-departures", "Newton finish"],
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
    for written in ["out", "b", "c", "ode", "h0", "PWNED"] {
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
