//! End-to-end test under a real Slurm cluster (issue 6): the smoke sweep as a job array of 3
//! shards plus the dependent merge job, compared with a single-process sweep; then a shard
//! cancelled mid-way, the merge refusing to write partial tables, and the shard resubmitted.
//!
//! It needs a cluster: `ci/slurm-up.sh` brings up a private single-node one and writes
//! `SLURM_CONF` into its env file; `.ci/run` does that and sets `DROPLET_SLURM_TEST=1`, which
//! makes this test mandatory. Without `SLURM_CONF` (and without that variable) it prints why
//! it is skipped and passes.

use crate::common::{droplet, table_without_wall};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn ok(out: Output, what: &str) -> String {
    assert!(
        out.status.success(),
        "{what}: {}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

fn sbatch(args: &[&str]) -> String {
    ok(
        Command::new("sbatch")
            .arg("--parsable")
            .args(args)
            .output()
            .expect("sbatch runs"),
        "sbatch",
    )
    .split(';')
    .next()
    .unwrap()
    .to_string()
}

/// States of a job (all tasks of an array), including finished ones.
fn states(job: &str) -> Vec<String> {
    let out = Command::new("squeue")
        .args(["-h", "-t", "all", "-j", job, "-o", "%T"])
        .output()
        .expect("squeue runs");
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.trim().to_string())
        .filter(|l| !l.is_empty())
        .collect()
}

const ACTIVE: [&str; 5] = [
    "PENDING",
    "RUNNING",
    "COMPLETING",
    "CONFIGURING",
    "SUSPENDED",
];

/// Waits until every task of every job has finished; returns their final states.
fn wait_for(jobs: &[&str], limit: Duration) -> Vec<String> {
    let start = Instant::now();
    loop {
        let all: Vec<String> = jobs.iter().flat_map(|j| states(j)).collect();
        if !all.is_empty() && all.iter().all(|s| !ACTIVE.contains(&s.as_str())) {
            return all;
        }
        assert!(
            start.elapsed() < limit,
            "jobs {jobs:?} still {all:?} after {limit:?}"
        );
        std::thread::sleep(Duration::from_millis(250));
    }
}

fn assert_same_tables(a: &Path, b: &Path) {
    for t in ["runs.parquet", "points.parquet"] {
        let (x, y) = (
            table_without_wall(&a.join(t)),
            table_without_wall(&b.join(t)),
        );
        assert!(x.equals_missing(&y), "{t} differs:\n{x}\n{y}");
    }
}

fn run_files(dir: &Path) -> usize {
    std::fs::read_dir(dir.join("runs"))
        .map(|d| {
            d.filter_map(Result::ok)
                .filter(|e| e.path().extension().is_some_and(|x| x == "json"))
                .count()
        })
        .unwrap_or(0)
}

/// Whether a cluster is there; without one, says why the test is skipped (and fails if
/// `DROPLET_SLURM_TEST=1` requires it).
fn cluster() -> bool {
    let required = std::env::var("DROPLET_SLURM_TEST").is_ok_and(|v| v == "1");
    if std::env::var_os("SLURM_CONF").is_none() {
        assert!(
            !required,
            "DROPLET_SLURM_TEST=1 but SLURM_CONF is not set (source the env file of ci/slurm-up.sh)"
        );
        eprintln!(
            "SKIPPED slurm end-to-end test: no Slurm cluster (SLURM_CONF unset); run ci/slurm-up.sh and source its env file"
        );
        return false;
    }
    true
}

/// The sweep `spec` in one process into `DIR/single` (the reference tables).
fn single_process(spec: &str, dir: &Path) -> PathBuf {
    let single = dir.join("single");
    ok(
        droplet()
            .args(["sweep", spec, "--out", single.to_str().unwrap(), "--json"])
            .output()
            .unwrap(),
        "single-process sweep",
    );
    single
}

/// `droplet slurm SPEC --shards N --out OUT --submit --json`: the submitted job ids.
fn submit(spec: &str, shards: &str, out: &str) -> Vec<String> {
    let out = ok(
        droplet()
            .args(["slurm", spec, "--shards", shards, "--out", out])
            .args(["--time", "00:20:00", "--mem", "1G", "--submit", "--json"])
            .output()
            .unwrap(),
        "droplet slurm --submit",
    );
    let j: serde_json::Value = serde_json::from_str(&out).unwrap();
    j["jobs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap().to_string())
        .collect()
}

#[test]
fn smoke_sweep_as_a_slurm_array_merges_to_the_single_process_tables() {
    if !cluster() {
        return;
    }
    let spec = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("sweeps/smoke.yaml");
    let spec = spec.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    // The single-process sweep of the same spec, shared with the other tests.
    let single = crate::common::smoke_sweep().0.clone();
    let limit = Duration::from_secs(600);

    // 1. `droplet slurm --submit`: an array of 3 shards, then the merge job (afterany).
    let arrayed = dir.path().join("arrayed");
    let a = arrayed.to_str().unwrap();
    let jobs = submit(spec, "3", a);
    assert_eq!(jobs.len(), 2, "{jobs:?}");
    let fin = wait_for(&[&jobs[0], &jobs[1]], limit);
    assert!(fin.iter().all(|s| s == "COMPLETED"), "{fin:?}");
    assert_eq!(fin.len(), 4, "3 shards + merge: {fin:?}");
    assert_same_tables(&single, &arrayed);

    // 2. Shard 0 cancelled mid-way (tasks one at a time, so the first runs are shard 0's).
    let killed = dir.path().join("killed");
    let k = killed.to_str().unwrap();
    ok(
        droplet()
            .args([
                "slurm", spec, "--shards", "3", "--out", k, "--time", "00:20:00",
            ])
            .args(["--mem", "1G", "--json"])
            .output()
            .unwrap(),
        "droplet slurm",
    );
    let (sweep_sh, merge_sh) = (
        killed.join("slurm/sweep.sbatch"),
        killed.join("slurm/merge.sbatch"),
    );
    let array = sbatch(&["--array=0-2%1", sweep_sh.to_str().unwrap()]);
    let merge = sbatch(&[
        &format!("--dependency=afterany:{array}"),
        merge_sh.to_str().unwrap(),
    ]);
    let start = Instant::now();
    while run_files(&killed) < 2 {
        assert!(start.elapsed() < limit, "shard 0 stored no runs");
        std::thread::sleep(Duration::from_millis(50));
    }
    ok(
        Command::new("scancel")
            .arg(format!("{array}_0"))
            .output()
            .unwrap(),
        "scancel",
    );
    let fin = wait_for(&[&array, &merge], limit);
    assert!(fin.iter().any(|s| s == "CANCELLED"), "{fin:?}");
    // The merge job found runs missing: it failed and wrote no final table.
    assert_eq!(states(&merge), ["FAILED"]);
    assert!(!killed.join("runs.parquet").exists() && !killed.join("points.parquet").exists());
    // So does a merge by hand, naming what is missing.
    let early = droplet().args(["merge", k]).output().unwrap();
    assert_eq!(early.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&early.stderr).contains("missing"));
    assert!(!killed.join("runs.parquet").exists());

    // 3. Shard 0 resubmitted: it resumes (its finished runs are reused), then the merge.
    let again = sbatch(&["--array=0", sweep_sh.to_str().unwrap()]);
    let merge2 = sbatch(&[
        &format!("--dependency=afterok:{again}"),
        merge_sh.to_str().unwrap(),
    ]);
    let fin = wait_for(&[&again, &merge2], limit);
    assert!(fin.iter().all(|s| s == "COMPLETED"), "{fin:?}");
    let log = std::fs::read_to_string(killed.join(format!("slurm/droplet-smoke-{again}_0.out")))
        .expect("the resubmitted shard's log");
    let report: serde_json::Value = serde_json::from_str(&log[log.find('{').unwrap()..])
        .unwrap_or_else(|e| panic!("shard log is not one JSON object ({e}): {log}"));
    assert!(
        report["reused"].as_u64().unwrap() >= 2,
        "finished runs were recomputed: {report}"
    );
    assert_same_tables(&single, &killed);
}

#[test]
fn refined_sweep_as_one_slurm_array_per_level_merges_to_the_single_process_tables() {
    if !cluster() {
        return;
    }
    // The ODE over the Fig. 2a window, refined 2 levels (cheap).
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("refined.yaml");
    std::fs::write(
        &spec,
        "name: refined\nmodel: ode\ngrid:\n  eta_t: {start: 0.070, stop: 0.100, step: 0.005}\n  kappa2: {start: 0.100, stop: 0.170, step: 0.01}\nsolver: {dt: 0.05, t_max: 3000}\nrefine: {levels: 2}\n",
    )
    .unwrap();
    let spec = spec.to_str().unwrap();
    let single = single_process(spec, dir.path());
    let arrayed = dir.path().join("arrayed");
    let jobs = submit(spec, "2", arrayed.to_str().unwrap());
    assert_eq!(jobs.len(), 4, "levels 0, 1, 2 and the merge: {jobs:?}");
    let refs: Vec<&str> = jobs.iter().map(String::as_str).collect();
    let fin = wait_for(&refs, Duration::from_secs(600));
    assert!(fin.iter().all(|s| s == "COMPLETED"), "{fin:?}");
    assert_eq!(fin.len(), 3 * 2 + 1, "{fin:?}");
    assert_same_tables(&single, &arrayed);
    // Each level's shards ran that level.
    for (level, job) in jobs[..3].iter().enumerate() {
        let log =
            std::fs::read_to_string(arrayed.join(format!("slurm/droplet-refined-{job}_1.out")))
                .expect("a shard's log");
        let report: serde_json::Value = serde_json::from_str(&log[log.find('{').unwrap()..])
            .unwrap_or_else(|e| panic!("shard log is not one JSON object ({e}): {log}"));
        assert_eq!(report["level"], level, "{report}");
    }
}
