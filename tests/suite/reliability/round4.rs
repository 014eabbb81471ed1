//! Reliability round 4, end to end: a stored run edited by hand is recomputed, a run keyed by
//! a setting it does not read is re-keyed and not recomputed, a full stderr never panics,
//! `merge` and `boundaries` refuse a directory a sweep works in before writing anything, and a
//! continuation with a parameter set off its default never takes the default line's files.
use super::{run_files, TINY};
use crate::common::{droplet, json, run, sweep, write_spec};
use std::path::Path;
use std::process::Stdio;
use std::time::Duration;

#[test]
fn an_edited_stored_run_is_recomputed_and_an_old_key_is_renamed_not_recomputed() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let out = dir.path().join("o");
    json(&sweep(&spec, &out, &[]));
    let files = run_files(&out);
    // A class and a status changed by hand: detected by the outcome's digest.
    let text = std::fs::read_to_string(&files[0]).unwrap();
    let mut rec: serde_json::Value = serde_json::from_str(&text).unwrap();
    let class = rec["outcome"]["class"].clone();
    rec["outcome"]["class"] = serde_json::json!(if class == "IC" { "MD" } else { "IC" });
    rec["outcome"]["status"] = serde_json::json!("steady");
    std::fs::write(&files[0], rec.to_string()).unwrap();
    let again = json(&sweep(&spec, &out, &[]));
    assert_eq!(again["computed"], 1, "{again}");
    assert_eq!(again["corrupt"].as_array().unwrap().len(), 1, "{again}");
    assert!(
        again["corrupt"][0]["reason"]
            .as_str()
            .unwrap()
            .contains("digest"),
        "{again}"
    );
    let recomputed: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&files[0]).unwrap()).unwrap();
    assert_eq!(recomputed["outcome"]["class"], class);

    // A run stored under the key of its settings as the spec bug wrote them (h0 = n): the
    // next sweep renames it to its key, says so, and recomputes nothing.
    let mut rec: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&files[1]).unwrap()).unwrap();
    rec["settings"]["h0"] = serde_json::json!(32.0);
    rec.as_object_mut().unwrap().remove("digest");
    let written: droplet_sweep::store::run_store::RunRecord =
        serde_json::from_value(rec.clone()).unwrap();
    let old_key =
        droplet_sweep::store::plan::written_key(&written.params, &written.ic, &written.settings);
    rec["key"] = serde_json::json!(old_key);
    std::fs::remove_file(&files[1]).unwrap();
    std::fs::write(
        out.join("runs").join(format!("{old_key}.json")),
        rec.to_string(),
    )
    .unwrap();
    let o = sweep(&spec, &out, &[]);
    let resumed = json(&o);
    assert_eq!(resumed["computed"], 0, "{resumed}");
    assert_eq!(resumed["upgraded"], 1, "{resumed}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("upgraded in place"));
    assert!(files[1].exists() && !out.join("runs").join(format!("{old_key}.json")).exists());
}

#[test]
fn a_full_stderr_loses_the_message_but_keeps_the_exit_code() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    for (args, code) in [
        (vec!["simulate", "--eta-t", "-1", "--kappa2", "0.1"], 2),
        (vec!["sweep", "nonexist.yaml"], 2),
    ] {
        let o = droplet()
            .args(&args)
            .stdin(Stdio::null())
            .stderr(full.try_clone().unwrap())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(code), "{args:?}");
    }
}

/// Holds `dir`'s lock as a sweep at work does, for a few seconds.
fn hold(dir: &Path) -> std::process::Child {
    let child = std::process::Command::new("flock")
        .args([
            "-x",
            "-o",
            dir.join(".lock").to_str().unwrap(),
            "-c",
            "sleep 5",
        ])
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(500));
    child
}

#[test]
fn merge_and_boundaries_refuse_a_directory_a_sweep_works_in_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "tiny.yaml", TINY);
    let out = dir.path().join("o");
    json(&sweep(&spec, &out, &[]));
    std::fs::remove_file(out.join("points.parquet")).unwrap();
    let mut holder = hold(&out);
    let merge = run(&["merge", out.to_str().unwrap()]);
    let bounds = run(&["boundaries", "--n", "32", "--out", out.to_str().unwrap()]);
    holder.kill().unwrap();
    holder.wait().unwrap();
    for (what, o) in [("merge", merge), ("boundaries", bounds)] {
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{what}: {err}");
        assert!(
            err.contains("in use by another droplet process"),
            "{what}: {err}"
        );
    }
    assert!(!out.join("points.parquet").exists());
    assert!(!out.join("boundaries.parquet").exists());
}

#[test]
fn a_continuation_off_the_default_parameters_has_files_of_its_own_with_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c");
    let line = |extra: &[&str]| {
        let mut args = vec![
            "continue",
            "--kappa2",
            "0.13",
            "--branch",
            "ic",
            "--from",
            "0.08",
            "--to",
            "0.085",
            "--n",
            "32",
            "--out",
            out.to_str().unwrap(),
            "--json",
        ];
        args.extend_from_slice(extra);
        json(&run(&args))
    };
    line(&[]);
    line(&["--set", "sigma=0.06"]);
    let default = out.join("continuation_kappa2_0.13.parquet");
    let other = out.join("continuation_kappa2_0.13_sigma_0.06.parquet");
    assert!(default.is_file() && other.is_file());
    let meta = droplet_sweep::tables::sweep_tables::read_metadata(&other).unwrap();
    let params: serde_json::Value = serde_json::from_str(&meta["params"]).unwrap();
    assert_eq!(params["sigma"], 0.06, "{params}");
    let meta = droplet_sweep::tables::sweep_tables::read_metadata(&default).unwrap();
    let params: serde_json::Value = serde_json::from_str(&meta["params"]).unwrap();
    assert_eq!(params["sigma"], 0.03, "{params}");
}
