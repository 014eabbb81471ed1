//! Issue 24 end to end: every label an attractor. Slow runs end on the stable state their
//! slow flow reaches (checked against long time stepping in results/landing), a run that
//! does not settle has no class, and `droplet audit` proves every label of a map (and
//! catches a false one).

use crate::common::{edit, json, read, run, write_spec};
use std::path::Path;

/// `simulate --json` at N = 192 with the defaults and `extra`.
fn simulate(eta_t: &str, kappa2: &str, ic: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "simulate", "--eta-t", eta_t, "--kappa2", kappa2, "--ic", ic, "--json",
    ];
    args.extend_from_slice(extra);
    json(&run(&args))
}

/// The direction of motion of a run's end (`simulate --json`), in degrees from the x axis.
fn direction_degrees(out: &serde_json::Value) -> f64 {
    let (vx, vy) = (out["vx"].as_f64().unwrap(), out["vy"].as_f64().unwrap());
    vy.atan2(vx).to_degrees()
}

#[test]
fn just_below_the_onset_of_motion_every_initial_condition_ends_md() {
    // (0.0763, 0.16): the disk's drift grows at +1.44e-3, the moving branch's s > 0.01. Plain
    // time stepping from IC iii is still at v = 0.09 at t = 2000 (labelled MC before numerics
    // 4) and reaches the diagonal MD at v = 0.298959 at t = 3258 (results/landing).
    for ic in ["i", "ii", "iii", "iv"] {
        let out = simulate("0.0763", "0.16", ic, &[]);
        assert_eq!(out["status"], "steady", "{ic}: {out}");
        assert_eq!(out["class"], "MD", "{ic}: {out}");
        let v = out["v"].as_f64().unwrap();
        assert!((v - 0.298959).abs() < 1e-4, "{ic}: {out}");
        assert!(out["t_end"].as_f64().unwrap() < 500.0, "{ic}: {out}");
    }
    // The paper's give-up at t_max without the landing: no class, and where it was going.
    let slow = simulate("0.0763", "0.16", "iii", &["--no-landing", "--no-run-on"]);
    assert_eq!(slow["status"], "t_max", "{slow}");
    assert!(slow["class"].is_null(), "{slow}");
    assert_eq!(slow["unsettled"], "beside_saddle", "{slow}");
    assert_eq!(slow["heading"], "MD", "{slow}");
}

#[test]
fn just_above_the_onset_of_motion_every_initial_condition_ends_at_rest() {
    // (0.0765, 0.16): no moving state at all (the drift pitchfork is supercritical here);
    // runs decay to the resting disk at a rate of about 1e-4.
    for ic in ["i", "ii", "iii", "iv"] {
        let out = simulate("0.0765", "0.16", ic, &[]);
        assert_eq!(out["status"], "steady", "{ic}: {out}");
        assert_eq!(out["class"], "IC", "{ic}: {out}");
        assert!(out["v"].as_f64().unwrap() < 1e-9, "{ic}: {out}");
    }
}

#[test]
fn a_run_where_two_slow_modes_meet_settles_by_running_on() {
    // (0.07675, 0.11875) from IC iv: the disk leaves along its diagonal deformation (growth
    // 4e-4) towards a slightly deformed rest whose drift grows too; the one-dimensional flow
    // does not decide, and at 4 t_max (t = 8000) the run is still beside that saddle
    // (unsettled in numerics 5). Run on (numerics 6: to 64 t_max with its own steps) it
    // reaches the diagonal MD at t = 11 092, which is unstable in rotation (+6.2e-3): with
    // a lean of round-off it turns there (numerics 7) to the x-axis MD. Plain time stepping
    // without the Newton finish (`--steady test --steady-tol 1e-300 --t-max 20000`) rests
    // on the diagonal MD (v = 1.040376) from t ~ 11 500 to 14 000, turns, and is on the
    // x-axis MD by t = 17 000: v = 1.03097251, s = 0.26868118 (docs/classification.md).
    let out = simulate("0.07675", "0.11875", "iv", &[]);
    assert_eq!(out["status"], "steady", "{out}");
    assert_eq!(out["class"], "MD", "{out}");
    assert!(out["t_end"].as_f64().unwrap() > 8000.0, "{out}");
    let (v, s) = (out["v"].as_f64().unwrap(), out["s"].as_f64().unwrap());
    assert!(
        (v - 1.03097251).abs() < 1e-6 && (s - 0.26868118).abs() < 1e-6,
        "{out}"
    );
}

#[test]
fn a_run_that_turns_while_it_departs_lands_where_plain_stepping_ends() {
    // (0.09, 0.104) from iii: the resting deformed droplet starts to move along the y axis
    // and turns, over 900 time units, to the stable MD 1.3 degrees off the diagonal (v =
    // 0.314753). Before numerics 7 the landing held its lean fixed and ended on the MD at 111
    // degrees (v = 0.337419): it now waits while the lean grows, and since numerics 9 while
    // it turns in towards the diagonal too (the Newton finish ends it, at t = 929).
    let landed = simulate("0.09", "0.104", "iii", &[]);
    let plain = simulate("0.09", "0.104", "iii", &["--no-landing"]);
    for out in [&landed, &plain] {
        assert_eq!(out["class"], "MD", "{out}");
        let v = out["v"].as_f64().unwrap();
        assert!((v - 0.314753).abs() < 1e-6, "{out}");
    }
    // (0.0805, 0.118) from iii: the run rests on the diagonal for 8e4 time units with a lean
    // of round-off, then moves along it and turns to the x-axis MD, v = 0.811184 (plain
    // stepping to t = 84 723, results/landing/table.md); the diagonal MD (v = 0.805135,
    // where numerics 6 landed) is unstable in rotation. The landing names the x-axis MD.
    let out = simulate("0.0805", "0.118", "iii", &[]);
    assert_eq!(out["ended_by"], "steady_by_landing", "{out}");
    let v = out["v"].as_f64().unwrap();
    assert!((v - 0.811184).abs() < 1e-6, "{out}");
}

#[test]
fn a_run_beyond_a_bump_of_the_orientation_flow_ends_where_pure_stepping_does() {
    // The box's anisotropy makes the orientation's flow bumpy: the x-axis MD at (0.072,
    // 0.132) is stable in rotation (-3.2e-4), but an unstable root 4.8 degrees off it bounds
    // its basin. From iii the run leaves the disk leaning 6.5 degrees and, by pure time
    // stepping (`--steady test --steady-tol 1e-300 --t-max 10000`), turns on to the stable
    // MD 8.7 degrees off the axis (v = 1.175454 at t = 10 000, still converging). Numerics 7
    // landed it on the x axis (v = 1.173823); numerics 8 asks the flow first.
    let out = simulate("0.072", "0.132", "iii", &[]);
    assert_eq!(out["class"], "MD", "{out}");
    let v = out["v"].as_f64().unwrap();
    assert!((v - 1.1755).abs() < 1e-6, "{out}");
    // Without the flow (numerics 7) it lands on the x axis: the flow is what changes it.
    let default = simulate("0.072", "0.132", "iii", &["--no-orientation-flow"]);
    let v = default["v"].as_f64().unwrap();
    assert!((v - 1.173823).abs() < 1e-6, "{default}");
    // (0.096, 0.1) from i: at rest, the deformed droplet on the x axis (s = 0.371008, stable,
    // rotation -1.1e-3) has an unstable root 0.57 degrees off it; the run, leaning 12
    // degrees, turns on to the diagonal one (s = 0.376292), as pure stepping does by t = 2800.
    let out = simulate("0.096", "0.1", "i", &[]);
    assert_eq!(out["class"], "ID", "{out}");
    let s = out["s"].as_f64().unwrap();
    assert!((s - 0.376292).abs() < 1e-6, "{out}");
    // (0.076, 0.1535) from ii: the x-axis MD (v = 0.528044) is unstable in rotation; the
    // flow turns the run to its first stable zero that way, the MD 22.15 degrees off the axis
    // (v = 0.530204, where the run from iii ends by the paper's test), not past the unstable
    // zero at 34 degrees to the diagonal (v = 0.532016, numerics 7's end).
    let out = simulate("0.076", "0.1535", "ii", &[]);
    assert_eq!(out["class"], "MD", "{out}");
    let v = out["v"].as_f64().unwrap();
    assert!((v - 0.530204).abs() < 1e-6, "{out}");
    let angle = direction_degrees(&out);
    assert!((angle.abs() - 22.151).abs() < 1e-2, "{out}");
}

#[test]
fn a_run_turning_away_from_a_turned_root_does_not_end_there() {
    // (0.089, 0.1075) from i, N = 192: the run turns up to the stable MD 18.0 degrees off the
    // x axis (v = 0.314157, where pure stepping, `--steady test --steady-tol 1e-9`, ends at
    // t = 2839). At t = 186 it is at 16.3 degrees, 12 % below that speed, next to a root of the
    // lattice at 16.6 degrees unstable in rotation; the flow on that root's family leads down
    // to the MD 1.7 degrees off the axis (v = 0.329282, where the run from ii ends), the way
    // the run is not turning. It ended there; it now steps on to the next try.
    let out = simulate("0.089", "0.1075", "i", &[]);
    assert_eq!(out["ended_by"], "steady_by_newton", "{out}");
    let v = out["v"].as_f64().unwrap();
    assert!((v - 0.314157).abs() < 1e-6, "{out}");
    let angle = direction_degrees(&out);
    assert!((angle - 18.003).abs() < 1e-2, "{out}");
}

#[test]
fn a_run_landed_from_a_departure_turns_as_the_departure_turns_it() {
    // (0.088, 0.1095) from iii leaves the resting ID with its long axis turning; it lands
    // (v = 0.0074) 13 degrees off the diagonal MD, which is unstable in rotation. The flow on
    // the MD family at that orientation points to the y-axis MD (v = 0.358618, numerics 8's
    // first end); the run arrives on the family 1 degree off the diagonal instead and, by pure
    // time stepping, ends on the stable MD 3.65 degrees off it (v = 0.318565 at t = 10 000).
    // A run far from the family, its lean shrinking, does not end by the flow: it steps on.
    // (0.08625, 0.1135) from iii lands 9.9 degrees off the diagonal MD next to a stable zero
    // of the flow (v = 0.256724, numerics 8's first end), but its lean relaxes with the
    // resting ID's (stable in rotation) while it leaves the ID at +1.4e-4; pure stepping
    // reaches the diagonal MD with a lean of round-off at t ~ 50 000 and turns, by t = 60 000
    // 0.68 degrees, towards the pitchfork pair 2.83 degrees off the diagonal (v = 0.244299).
    for (eta_t, kappa2, v_end, off) in [
        ("0.088", "0.1095", 0.318565, 3.647),
        ("0.08625", "0.1135", 0.244299, 2.827),
    ] {
        let out = simulate(eta_t, kappa2, "iii", &[]);
        assert_eq!(out["class"], "MD", "{out}");
        let v = out["v"].as_f64().unwrap();
        assert!((v - v_end).abs() < 1e-6, "{out}");
        let angle = direction_degrees(&out);
        assert!(((135.0 - angle).abs() - off).abs() < 1e-2, "{out}");
    }
}

/// A two-point sweep at N = 96: an MD point and an IC point far from every boundary.
const TWO_POINTS: &str = "name: two
grid:
  eta_t: [0.07, 0.1]
  kappa2: [0.16]
initial_conditions: [i, iii]
solver:
  n: 96
";

fn audit(dir: &Path) -> (Option<i32>, serde_json::Value) {
    let o = run(&["audit", dir.to_str().unwrap(), "--json"]);
    (
        o.status.code(),
        serde_json::from_slice(&o.stdout).expect("one JSON object"),
    )
}

/// `droplet audit DIR --sample POINTS --seed 42 --json`.
fn audit_sample(dir: &Path, points: usize) -> (Option<i32>, serde_json::Value) {
    let p = points.to_string();
    let o = run(&[
        "audit",
        dir.to_str().unwrap(),
        "--sample",
        &p,
        "--seed",
        "42",
        "--json",
    ]);
    (
        o.status.code(),
        serde_json::from_slice(&o.stdout).expect("one JSON object"),
    )
}

#[test]
fn audit_passes_a_settled_map_and_fails_a_false_label() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "two.yaml", TWO_POINTS);
    let out = dir.path().join("two");
    let o = run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (code, clean) = audit(&out);
    assert_eq!(code, Some(0), "{clean}");
    assert_eq!(clean["points_clean"], 2, "{clean}");
    let points = read(&out.join("points.parquet"));
    let labels = points.column("class").unwrap().str().unwrap().clone();
    assert_eq!(labels.get(0), Some("MD"));
    assert_eq!(labels.get(1), Some("IC"));

    // A false IC at eta_t = 0.07, where the resting disk's drift grows: the runs table and
    // the points table both edited, so only the stability check can tell.
    let forged = dir.path().join("forged");
    std::fs::create_dir(&forged).unwrap();
    for f in ["runs.parquet", "points.parquet"] {
        std::fs::copy(out.join(f), forged.join(f)).unwrap();
    }
    edit(&forged.join("runs.parquet"), "class", |i, c| {
        if i == 0 {
            Some("IC".into())
        } else {
            c.map(String::from)
        }
    });
    edit(&forged.join("points.parquet"), "class", |i, c| {
        if i == 0 {
            Some("IC/MD".into())
        } else {
            c.map(String::from)
        }
    });
    let (code, report) = audit(&forged);
    assert_eq!(code, Some(1), "{report}");
    assert_eq!(report["by_kind"]["unstable_disk"], 1, "{report}");
    assert_eq!(report["contradictions"], 1, "{report}");
    assert_eq!(report["list"][0]["eta_t"], 0.07, "{report}");

    // A label edited alone no longer matches its runs; an MD run called MC is checked
    // against its root's deformation.
    for f in ["runs.parquet", "points.parquet"] {
        std::fs::copy(out.join(f), forged.join(f)).unwrap();
    }
    edit(&forged.join("points.parquet"), "class", |i, c| {
        if i == 1 {
            Some("IC/MD".into())
        } else {
            c.map(String::from)
        }
    });
    edit(&forged.join("runs.parquet"), "class", |i, c| {
        if i == 1 {
            Some("MC".into())
        } else {
            c.map(String::from)
        }
    });
    let (code, report) = audit(&forged);
    assert_eq!(code, Some(1), "{report}");
    assert_eq!(report["by_kind"]["other_class"], 1, "{report}");
    // Point 0's label MD no longer matches its runs (MD and MC), point 1's IC/MD neither.
    assert_eq!(report["by_kind"]["label_mismatch"], 2, "{report}");
}

/// Committed maps whose audit lists unsettled runs: the map and how many (each such run is
/// listed by `droplet audit` and its point flagged). None since numerics 6 (the Fig. 2a map's
/// 13 settle by running on; results/fig2a-map/README.md): every committed map is audit-clean.
const UNSETTLED: &[(&str, u64)] = &[];

/// Points of each committed map whose stable states the suite audits (seeded).
const SAMPLE: usize = 8;

/// The folders under `results/`, one or two deep (results/convergence-n/sweep), sorted.
fn result_folders() -> Vec<std::path::PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("results");
    let folders = |d: &Path| -> Vec<std::path::PathBuf> {
        let mut v: Vec<_> = std::fs::read_dir(d)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.is_dir())
            .collect();
        v.sort();
        v
    };
    folders(&root)
        .into_iter()
        .flat_map(|d| std::iter::once(d.clone()).chain(folders(&d)))
        .collect()
}

#[test]
fn every_committed_map_passes_the_audit() {
    let mut audited = Vec::new();
    // Every map under results/.
    for dir in result_folders() {
        if !dir.join("runs.parquet").exists() {
            continue;
        }
        let runs = read(&dir.join("runs.parquet"));
        let model = runs
            .column("model")
            .unwrap()
            .str()
            .unwrap()
            .get(0)
            .map(String::from);
        if model.as_deref() != Some("pde") {
            // The reduced model's maps: its own stable states, not the PDE's.
            continue;
        }
        // Completeness and labels at every point, the stable states at a seeded sample of
        // 8 points (the full audit of every point is `results/audit.sh`, recorded in each
        // map's audit.json, checked below).
        let (code, report) = audit_sample(&dir, SAMPLE);
        let name = dir.file_name().unwrap().to_str().unwrap().to_string();
        let record: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join("audit.json"))
                .unwrap_or_else(|_| panic!("{name}: no audit.json (results/audit.sh)")),
        )
        .unwrap();
        assert_eq!(
            record["points"], report["points"],
            "{name}: audit.json is of another map"
        );
        assert_eq!(
            record["runs"], report["runs"],
            "{name}: audit.json is of another map"
        );
        assert!(
            record["sampled"].is_null(),
            "{name}: audit.json is a sample's"
        );
        let allowed = UNSETTLED
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(0, |(_, k)| *k);
        let kinds = report["by_kind"].as_object().unwrap();
        assert!(
            kinds.keys().all(|k| k == "unsettled"),
            "{name}: {}",
            serde_json::to_string_pretty(&report["by_kind"]).unwrap()
        );
        let unsettled = kinds.get("unsettled").map_or(0, |n| n.as_u64().unwrap());
        assert_eq!(unsettled, allowed, "{name}: {report}");
        assert_eq!(
            record["contradictions"], allowed,
            "{name}: the full audit: {record}"
        );
        assert_eq!(
            report["sampled"],
            (SAMPLE as u64).min(report["points"].as_u64().unwrap()),
            "{name}"
        );
        assert_eq!(code, Some(if allowed == 0 { 0 } else { 1 }), "{name}");
        audited.push(name);
    }
    assert!(audited.len() >= 3, "{audited:?}");
    assert!(
        audited.iter().any(|n| n == "sweep"),
        "results/convergence-n/sweep: {audited:?}"
    );
}
