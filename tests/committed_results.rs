//! `droplet status` and `droplet plot` on a committed result directory: one with the tables
//! and pictures of a finished map but no run store (`runs/`). Both work from the tables, and
//! `plot` redraws the committed picture byte for byte.
mod common;

use common::{droplet, json, read};
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
