//! Sweeps over three axes of the reduced model: one map per slice and one with all, and
//! refinement of each slice on its own, resumed equal.
use crate::cli::axes::{columns, floats, sweep_with_pictures};
use crate::common::{json, read, run, sweep, table_without_wall, write_spec};

#[test]
fn a_three_axis_ode_sweep_draws_one_map_per_slice_and_one_with_all() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "three.yaml",
        "model: ode\ngrid:\n  mass: [0.02, 0.3]\n  eta_t: {start: 0.07, stop: 0.1, step: 0.01}\n  kappa2: [0.11, 0.15]\ninitial_conditions: [i, iii]\n",
    );
    let out = dir.path().join("three");
    let s = sweep_with_pictures(&spec, &out);
    assert_eq!(s["runs"], 2 * 4 * 2 * 2, "{s}");
    let points = read(&out.join("points.parquet"));
    let cols = columns(&points);
    assert_eq!(&cols[1..4], ["mass", "eta_t", "kappa2"], "{cols:?}");
    // Slice-major: the first slice's 8 points, then the second's.
    let kappa = floats(&points, "kappa2");
    assert!(kappa[..8].iter().all(|&k| k == 0.11) && kappa[8..].iter().all(|&k| k == 0.15));
    // The runs carry all three coordinates.
    let runs = read(&out.join("runs.parquet"));
    let point = runs.column("point").unwrap().u32().unwrap().clone();
    let (pm, pe) = (floats(&points, "mass"), floats(&points, "eta_t"));
    let (rm, re, rk) = (
        floats(&runs, "mass"),
        floats(&runs, "eta_t"),
        floats(&runs, "kappa2"),
    );
    for i in 0..runs.height() {
        let p = point.get(i).unwrap() as usize;
        assert_eq!((rm[i], re[i], rk[i]), (pm[p], pe[p], kappa[p]));
    }
    for f in [
        "phase_map.png",
        "phase_map.svg",
        "phase_map_kappa2_0.11.png",
        "phase_map_kappa2_0.15.svg",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    // Status from the store and from the tables alone, and the pictures redrawn.
    let st = json(&run(&["status", out.to_str().unwrap(), "--json"]));
    assert_eq!(st["points"].as_u64(), Some(16), "{st}");
    std::fs::remove_dir_all(out.join("runs")).unwrap();
    std::fs::remove_file(out.join("phase_map_kappa2_0.15.png")).unwrap();
    let o = run(&["plot", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("phase_map_kappa2_0.15.png").exists());
    // Boundaries are drawn in planes of two parameters, not over slices.
    let o = run(&["boundaries", "--out", out.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("(mass, eta_t, kappa2)"));
}

#[test]
fn a_refined_three_axis_ode_sweep_refines_each_slice_on_its_own_and_resumes_equal() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(
        dir.path(),
        "three-r.yaml",
        "model: ode\ngrid:\n  mass: {start: 0.02, stop: 0.32, step: 0.1}\n  eta_t: {start: 0.07, stop: 0.1, step: 0.01}\n  kappa2: [0.11, 0.15]\ninitial_conditions: [i, iii]\nrefine: {levels: 2}\n",
    );
    let out = dir.path().join("r");
    assert!(sweep(&spec, &out, &[]).status.success());
    let points = read(&out.join("points.parquet"));
    let (kappa, level) = (
        floats(&points, "kappa2"),
        points.column("level").unwrap().u32().unwrap().clone(),
    );
    // Each slice has its 4 x 4 level-0 points, and its own refined ones.
    for k in [0.11, 0.15] {
        let mine: Vec<u32> = (0..points.height())
            .filter(|&i| kappa[i] == k)
            .map(|i| level.get(i).unwrap())
            .collect();
        assert_eq!(mine.iter().filter(|&&l| l == 0).count(), 16, "{k}");
        assert!(mine.iter().any(|&l| l > 0), "slice {k} was not refined");
    }
    // The two slices differ (ID at the top of 0.11 only): each is refined where it changes.
    let (m, e) = (floats(&points, "mass"), floats(&points, "eta_t"));
    let refined = |k: f64| {
        (0..points.height())
            .filter(|&i| kappa[i] == k && level.get(i).unwrap() > 0)
            .map(|i| (m[i].to_bits(), e[i].to_bits()))
            .collect::<std::collections::BTreeSet<_>>()
    };
    assert_ne!(refined(0.11), refined(0.15));
    // A second sweep into its own directory gives equal tables; with half of its runs
    // removed, a third recomputes exactly those.
    let again = dir.path().join("again");
    assert!(sweep(&spec, &again, &[]).status.success());
    for t in ["runs.parquet", "points.parquet"] {
        let (a, b) = (
            table_without_wall(&out.join(t)),
            table_without_wall(&again.join(t)),
        );
        assert!(a.equals_missing(&b), "{t} differs");
    }
    let files: Vec<_> = std::fs::read_dir(again.join("runs"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    for f in files.iter().step_by(2) {
        std::fs::remove_file(f).unwrap();
    }
    let done = json(&sweep(&spec, &again, &[]));
    assert_eq!(
        done["computed"].as_u64().unwrap() as usize,
        files.len().div_ceil(2),
        "{done}"
    );
    for t in ["runs.parquet", "points.parquet"] {
        let (a, b) = (
            table_without_wall(&out.join(t)),
            table_without_wall(&again.join(t)),
        );
        assert!(a.equals_missing(&b), "{t} differs after the resume");
    }
    let st = json(&run(&["status", again.to_str().unwrap(), "--json"]));
    assert_eq!(st["levels"].as_array().unwrap().len(), 3, "{st}");
}
