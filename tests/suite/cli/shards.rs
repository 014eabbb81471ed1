//! Sharded sweeps: shards (by hand, or from a Slurm array's variables) merged equal a single
//! sweep, and a merge before every shard has finished writes nothing.
use crate::cli::TINY;
use crate::common::{droplet, json, run, table_without_wall, write_spec};
use std::process::Stdio;
use std::time::Duration;

/// `droplet sweep SPEC --out OUT --shard SHARD --jobs 1`, started and left running.
fn spawn_shard(spec: &std::path::Path, out: &str, shard: &str) -> std::process::Child {
    droplet()
        .args([
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out,
            "--shard",
            shard,
            "--jobs",
            "1",
            "--json",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

#[test]
fn shards_then_merge_equal_a_single_sweep_and_early_merge_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let single = dir.path().join("single");
    json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        single.to_str().unwrap(),
        "--json",
    ]));

    let sharded = dir.path().join("sharded");
    let s = sharded.to_str().unwrap();
    // Shard 0 alone, then merging reports the missing runs and writes no table.
    let first = json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        s,
        "--shard",
        "0/3",
        "--json",
        "--jobs",
        "1",
    ]));
    assert!(first["runs"].as_u64().unwrap() > 0 && first["runs"].as_u64().unwrap() < 18);
    let early = run(&["merge", s]);
    assert_eq!(early.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&early.stderr).contains("missing"));
    assert!(!sharded.join("runs.parquet").exists() && !sharded.join("points.parquet").exists());
    // Shards 1 and 2 concurrently (separate locks), shard 1 killed mid-way and re-run.
    let spawn = |shard: &str| spawn_shard(&spec, s, shard);
    let mut one = spawn("1/3");
    let mut two = spawn("2/3");
    std::thread::sleep(Duration::from_millis(300));
    one.kill().ok();
    one.wait().unwrap();
    assert!(two.wait().unwrap().success());
    json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        s,
        "--shard",
        "1/3",
        "--json",
    ]));
    // The environment of a Slurm array task selects the shard too (all done: nothing to run).
    let o = droplet()
        .args(["sweep", spec.to_str().unwrap(), "--out", s, "--json"])
        .env("SLURM_ARRAY_TASK_ID", "2")
        .env("SLURM_ARRAY_TASK_COUNT", "3")
        .output()
        .unwrap();
    let j = json(&o);
    assert_eq!(
        (j["shard"].as_str(), j["computed"].as_u64()),
        (Some("2/3"), Some(0))
    );
    for _ in 0..2 {
        // Idempotent.
        json(&run(&["merge", s, "--json", "--no-plot"]));
    }
    for t in ["runs.parquet", "points.parquet"] {
        let a = table_without_wall(&single.join(t));
        let b = table_without_wall(&sharded.join(t));
        assert!(a.equals_missing(&b), "{t} differs");
    }
}

#[test]
fn slurm_writes_an_array_script_of_shards_and_a_merge_script() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let sharded = dir.path().join("sharded");
    let s = sharded.to_str().unwrap();
    // The Slurm scripts.
    let sl = json(&run(&[
        "slurm",
        spec.to_str().unwrap(),
        "--shards",
        "3",
        "--out",
        s,
        "--partition",
        "debug",
        "--json",
    ]));
    let script = std::fs::read_to_string(sl["sweep_script"].as_str().unwrap()).unwrap();
    assert!(
        script.contains("#SBATCH --array=0-2")
            && script.contains("--shard \"$SLURM_ARRAY_TASK_ID/3\"")
    );
    assert!(script.contains("#SBATCH --partition=debug"));
    let merge = std::fs::read_to_string(sl["merge_script"].as_str().unwrap()).unwrap();
    assert!(merge.contains(" merge "));
}
