//! `droplet audit` certifies only a complete map: every point of the points table has one run
//! of each of the spec's initial conditions, and its label is the one its runs give. A run
//! deleted, duplicated or of a foreign condition, an empty table, and a label edited by hand
//! each fail the audit (exit 1) with the kind that names them.
use crate::common::{droplet, read};
use droplet_sweep::tables::sweep_tables::{read_metadata, write_parquet};
use polars::prelude::*;
use std::path::{Path, PathBuf};

/// A copy of the committed smoke map's tables (N = 96, 16 points, 64 runs; audited clean).
fn smoke_copy(dir: &Path, name: &str) -> PathBuf {
    let to = dir.join(name);
    std::fs::create_dir_all(&to).unwrap();
    for t in ["runs.parquet", "points.parquet"] {
        std::fs::copy(Path::new("results/smoke").join(t), to.join(t)).unwrap();
    }
    to
}

/// Rewrites a table with `f` applied, keeping its metadata (the spec the audit reads).
fn rewrite(path: &Path, f: impl Fn(DataFrame) -> DataFrame) {
    let meta: Vec<(String, String)> = read_metadata(path).unwrap().into_iter().collect();
    let mut df = f(read(path));
    write_parquet(&mut df, path, meta).unwrap();
}

/// The audit's JSON and exit code.
fn audit(dir: &Path) -> (serde_json::Value, Option<i32>) {
    let o = droplet()
        .args(["audit", dir.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    let json =
        serde_json::from_slice(&o.stdout).unwrap_or_else(|_| serde_json::json!({ "stderr": err }));
    (json, o.status.code())
}

fn kinds(audit: &serde_json::Value) -> Vec<String> {
    let mut k: Vec<String> = audit["list"]
        .as_array()
        .map(|c| {
            c.iter()
                .map(|c| c["kind"].as_str().unwrap().to_string())
                .collect()
        })
        .unwrap_or_default();
    k.dedup();
    k
}

#[test]
fn audit_fails_a_map_with_a_missing_a_duplicated_a_foreign_or_a_mislabelled_run() {
    let dir = tempfile::tempdir().unwrap();
    // Every run of point 3 deleted: its four conditions are missing.
    let missing = smoke_copy(dir.path(), "missing");
    rewrite(&missing.join("runs.parquet"), |df| {
        let keep = df.column("point").unwrap().u32().unwrap().not_equal(3);
        df.filter(&keep).unwrap()
    });
    // The first run twice.
    let duplicated = smoke_copy(dir.path(), "duplicated");
    rewrite(&duplicated.join("runs.parquet"), |df| {
        df.vstack(&df.head(Some(1))).unwrap()
    });
    // One run's condition renamed to one the spec does not have.
    let foreign = smoke_copy(dir.path(), "foreign");
    rewrite(&foreign.join("runs.parquet"), |mut df| {
        let ic = df.column("ic").unwrap().str().unwrap().clone();
        let new: Vec<Option<String>> = (0..df.height())
            .map(|i| {
                if i == 5 {
                    Some("v".into())
                } else {
                    ic.get(i).map(str::to_string)
                }
            })
            .collect();
        df.with_column(Column::new("ic".into(), new)).unwrap();
        df
    });
    // One point's label edited.
    let mislabelled = smoke_copy(dir.path(), "mislabelled");
    rewrite(&mislabelled.join("points.parquet"), |mut df| {
        let class = df.column("class").unwrap().str().unwrap().clone();
        let new: Vec<Option<String>> = (0..df.height())
            .map(|i| match (i, class.get(i)) {
                (0, Some("MD")) => Some("IC".into()),
                (0, _) => Some("MD".into()),
                (_, c) => c.map(str::to_string),
            })
            .collect();
        df.with_column(Column::new("class".into(), new)).unwrap();
        df
    });
    for (dir, kind, count) in [
        (&missing, "missing_run", 4),
        (&duplicated, "duplicate_run", 1),
        (&foreign, "unknown_run", 1),
        (&mislabelled, "label_mismatch", 1),
    ] {
        let (a, code) = audit(dir);
        assert_eq!(code, Some(1), "{kind}: {a}");
        assert!(kinds(&a).contains(&kind.to_string()), "{kind}: {a}");
        let n = a["list"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["kind"] == kind)
            .count();
        assert_eq!(n, count, "{kind}: {a}");
        assert!(a["points_clean"].as_u64().unwrap() < 16, "{kind}: {a}");
    }
    // An empty runs table certifies nothing: refused as input.
    let empty = smoke_copy(dir.path(), "empty");
    rewrite(&empty.join("runs.parquet"), |df| df.head(Some(0)));
    let (a, code) = audit(&empty);
    assert_eq!(code, Some(2), "{a}");
    assert!(
        a["stderr"].as_str().unwrap().contains("nothing to certify"),
        "{a}"
    );
}
