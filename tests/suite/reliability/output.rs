//! Output under trouble: a full disk, a closed stdout, a picture drawn while runs are missing,
//! and plain messages from `boundaries` and `stability`.
use super::{run_files, TINY};
use crate::common::{droplet, json, run, sweep, write_spec};
use std::process::Stdio;
use std::time::Duration;

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
    // An unreadable run in a finished map: plot says so (exit 1) and leaves the map's own
    // picture as it is.
    let files = run_files(&out);
    std::fs::write(&files[0], b"{ not json").unwrap();
    let r = run(&["plot", o]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("1 of 6 points") && err.contains("nothing was drawn"),
        "{err}"
    );
    assert_eq!(std::fs::metadata(&png).unwrap().modified().unwrap(), before);
    // Without tables (a sweep interrupted before its end) the picture shows the point as
    // missing, and plot says so (exit 1).
    std::fs::remove_file(out.join("points.parquet")).unwrap();
    let r = run(&["plot", o]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("1 of 6 points are drawn as missing"), "{err}");
    assert!(err.contains("droplet status"), "{err}");
    assert_ne!(std::fs::metadata(&png).unwrap().modified().unwrap(), before);
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
