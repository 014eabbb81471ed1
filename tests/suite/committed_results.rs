//! `droplet status` and `droplet plot` on a committed result directory: one with the tables
//! and pictures of a finished map but no run store (`runs/`). Both work from the tables, and
//! `plot` redraws the committed picture byte for byte.

use crate::common::{droplet, json, read};
use std::collections::BTreeMap;
use std::path::Path;

/// A copy of `results/<name>` without its `runs/`.
fn tables_only_copy(name: &str, tmp: &Path) -> std::path::PathBuf {
    let from = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("results")
        .join(name);
    let to = tmp.join(name);
    std::fs::create_dir_all(&to).unwrap();
    for e in std::fs::read_dir(&from).unwrap().flatten() {
        if e.path().is_file() {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
    to
}

#[test]
fn status_and_plot_read_a_committed_map_from_its_tables() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tables_only_copy("ode_map", tmp.path());
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/ode_map");

    let out = droplet()
        .args(["status", dir.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let st = json(&out);
    assert_eq!(st["from_tables"], true, "{st}");
    assert_eq!(st["complete"], true, "{st}");
    let points = read(&dir.join("points.parquet"));
    let runs = read(&dir.join("runs.parquet"));
    assert_eq!(st["points"].as_u64().unwrap() as usize, points.height());
    assert_eq!(st["runs_done"].as_u64().unwrap() as usize, runs.height());
    let counted: u64 = st["point_classes"]
        .as_object()
        .unwrap()
        .values()
        .map(|v| v.as_u64().unwrap())
        .sum();
    assert_eq!(counted as usize, points.height(), "{st}");

    // The picture is redrawn from the tables, equal to the committed one.
    std::fs::remove_file(dir.join("phase_map.png")).unwrap();
    let out = droplet()
        .args(["plot", dir.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let drawn = json(&out);
    assert_eq!(drawn["missing"], 0, "{drawn}");
    assert_eq!(
        std::fs::read(dir.join("phase_map.png")).unwrap(),
        std::fs::read(committed.join("phase_map.png")).unwrap(),
        "the picture drawn from the tables differs from the committed one"
    );
}

#[test]
fn boundaries_onto_a_committed_map_take_its_window_from_its_tables() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tables_only_copy("ode_map", tmp.path());
    let points = read(&dir.join("points.parquet"));
    let span = |c: &str| {
        let v = points.column(c).unwrap().f64().unwrap().clone();
        let v: Vec<f64> = v.into_no_null_iter().collect();
        [
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ]
    };
    let out = droplet()
        .args([
            "boundaries",
            "--n",
            "64",
            "--samples",
            "4",
            "--out",
            dir.to_str().unwrap(),
            "--json",
        ])
        .output()
        .unwrap();
    let r = json(&out);
    assert_eq!(r["eta_t"], serde_json::json!(span("eta_t")), "{r}");
    assert_eq!(r["kappa2"], serde_json::json!(span("kappa2")), "{r}");
    let files: Vec<&str> = r["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert!(files.iter().any(|f| f.ends_with("phase_map.png")), "{r}");
    let mut unique = files.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), files.len(), "each file named once: {r}");
}

/// `droplet plot THIS --beside OTHER --json` (it must succeed) and its label changes per
/// kind, `(from, to) -> points`.
fn beside(this: &Path, other: &Path) -> (serde_json::Value, BTreeMap<(String, String), u64>) {
    let out = droplet()
        .args(["plot", this.to_str().unwrap(), "--beside"])
        .arg(other)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let c = json(&out);
    let changes = c["changes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|ch| {
            (
                (
                    ch["from"].as_str().unwrap().to_string(),
                    ch["to"].as_str().unwrap().to_string(),
                ),
                ch["points"].as_u64().unwrap(),
            )
        })
        .collect();
    (c, changes)
}

#[test]
fn plot_beside_draws_two_committed_maps_and_counts_what_the_modes_change() {
    // The 4-mode level 0 beside the paper's 2-mode map: the six labels results/fig2a-modes
    // lists change at the 171 points both hold, and each map's labels tile the window.
    let tmp = tempfile::tempdir().unwrap();
    let modes = tables_only_copy("fig2a-modes", tmp.path());
    let two = tables_only_copy("fig2a-map", tmp.path());
    let (c, changes) = beside(&modes, &two);
    assert!(modes.join("beside.png").is_file() && modes.join("beside.svg").is_file());
    assert_eq!(c["common_points"], 171, "{c}");
    let expected: BTreeMap<(String, String), u64> =
        [("IC/MD", "IC", 1), ("ID", "MD", 4), ("ID/MD", "MD", 1)]
            .into_iter()
            .map(|(from, to, n)| ((from.to_string(), to.to_string()), n))
            .collect();
    assert_eq!(changes, expected, "{c}");
    // Both maps cover the window (0.068..0.100 x 0.100..0.172) edge to edge.
    for side in ["this", "other"] {
        let total: f64 = c["areas"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a[side].as_f64().unwrap())
            .sum();
        assert!((total - 0.032 * 0.072).abs() < 1e-12, "{side}: {total}");
    }
    assert_eq!(c["other_model"], "PDE");
    assert_eq!(c["this_model"], "PDE (shape modes 2..4)");

    // A 1-D sweep is no map to compare: refused as bad input.
    let line = tables_only_copy("fig2b-i", tmp.path());
    let out = droplet()
        .args(["plot", modes.to_str().unwrap(), "--beside"])
        .arg(&line)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("two axes"));
    // So is a directory without a finished map.
    let out = droplet()
        .args(["plot", modes.to_str().unwrap(), "--beside"])
        .arg(tmp.path().join("nothing"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no finished map"));
}

#[test]
fn the_refined_k_mode_map_beside_the_papers_changes_the_labels_its_table_lists() {
    // results/fig2a-modes/map beside results/fig2a-map: `plot --beside` counts, per kind of
    // change, the rows of label_changes.csv (written from the two points tables by
    // changes.py, a separate computation).
    let tmp = tempfile::tempdir().unwrap();
    let modes = tables_only_copy("fig2a-modes/map", tmp.path());
    let two = tables_only_copy("fig2a-map", tmp.path());
    let (c, counted) = beside(&modes, &two);
    assert_eq!(c["common_points"], 1555, "{c}");
    let mut listed = BTreeMap::<(String, String), u64>::new();
    let csv = std::fs::read_to_string(modes.join("label_changes.csv")).unwrap();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.splitn(5, ',').collect();
        *listed.entry((f[2].into(), f[3].into())).or_default() += 1;
    }
    assert_eq!(counted, listed, "{c}");
    assert_eq!(listed.values().sum::<u64>(), 200);
    // The bistable bands shrink with modes 3 and 4 (README: IC/MD -39 %, ID/MD -83 %).
    let area = |label: &str, side: &str| {
        c["areas"]
            .as_array()
            .unwrap()
            .iter()
            .find(|a| a["label"] == label)
            .map_or(0.0, |a| a[side].as_f64().unwrap())
    };
    assert!(area("IC/MD", "this") < 0.65 * area("IC/MD", "other"), "{c}");
    assert!(area("ID/MD", "this") < 0.2 * area("ID/MD", "other"), "{c}");
}
