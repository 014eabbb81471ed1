//! Corrupt stored runs, an oversized spec, resume after SIGKILL, stale temporaries, and the
//! lock between a sweep and a shard.
use super::{report, run_files, tables_equal, TINY};
use crate::common::{droplet, json, kill_at_random_moments, run, sweep, write_spec};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

/// `droplet status` on the sweep in `out` (4 of its 12 run files `files` corrupt; `st`, its
/// status now): the pace from the files' ages, and no ETA once the runs left are slower.
fn status_paces_by_the_files_ages(out: &Path, files: &[PathBuf], st: &serde_json::Value) {
    // The pace: every file is seconds old, so it is measured over the 60 s floor; with one
    // stored 5 min ago, over those 5 min; one stored 20 min ago is outside the window.
    let eta = |st: &serde_json::Value| st["eta_s"].as_f64().unwrap();
    assert_eq!(st["runs_recent"], 12, "{st}");
    assert_eq!(st["pace_s"], 60.0, "{st}");
    assert!((eta(st) - 4.0 * 60.0 / 12.0).abs() < 1e-9, "{st}");
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
    // No run stored for 4 min, longer than that estimate (4 x 300 s / 11): the runs left are
    // slower than the finished ones, and the text says so instead of an ETA.
    for f in files.iter().filter(|f| *f != &files[7]) {
        age(f, 240);
    }
    age(&files[6], 300);
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    let since = st["since_last_s"].as_f64().unwrap();
    assert!((240.0..250.0).contains(&since) && eta(&st) < since, "{st}");
    let text = String::from_utf8_lossy(&run(&["status", out.to_str().unwrap()]).stdout).to_string();
    assert!(
        text.contains("ETA: unknown") && text.contains("no run has been stored for 4 min"),
        "{text}"
    );
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
    status_paces_by_the_files_ages(&out, &files, &st);

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

#[test]
fn sigkill_at_many_moments_then_resume_gives_identical_tables() {
    let dir = tempfile::tempdir().unwrap();
    // 12 runs at N = 32, about 10 ms each: the kills land at moments spread over the whole
    // sweep (before its first run, mid-run, mid-write, in the tables), each costs a tenth of
    // a second.
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
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
