//! What a phase map's picture shows beside the labels.
use crate::common::{read, run, sweep, write_spec};

#[test]
fn points_whose_runs_left_the_model_are_marked_on_the_map() {
    // Modes 2..6 at N = 96 in the strongly deformed corner: from iii the resting droplet
    // stretches until its boundary reaches its centre (`diverged`), from ii it moves (MD).
    // The label counts only the run that settled (the paper's rule): every point is MD with
    // one diverged run, and the picture crosses it out, drawn from the runs as from the tables.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("k6");
    let spec = "name: k6\nparams: {modes: 6}\ngrid:\n  eta_t: [0.084, 0.086]\n  kappa2: [0.1, 0.102]\ninitial_conditions: [ii, iii]\nsolver:\n  n: 96\n  t_max: 200\n  run_on: false\n";
    let o = sweep(&write_spec(dir.path(), "k6.yaml", spec), &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let points = read(&out.join("points.parquet"));
    let class = points.column("class").unwrap().str().unwrap().clone();
    let left = points.column("n_diverged").unwrap().u32().unwrap().clone();
    for i in 0..points.height() {
        assert_eq!(class.get(i), Some("MD"), "point {i}");
        assert_eq!(left.get(i), Some(1), "point {i}");
    }
    let legend =
        |dir: &std::path::Path| std::fs::read_to_string(dir.join("phase_map.svg")).unwrap();
    let o = run(&["plot", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(legend(&out).contains("runs left the model (4)"));
    // From the tables alone (a committed map: no run store).
    let tables = dir.path().join("tables");
    std::fs::create_dir(&tables).unwrap();
    for f in ["points.parquet", "runs.parquet"] {
        std::fs::copy(out.join(f), tables.join(f)).unwrap();
    }
    let o = run(&["plot", tables.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(legend(&tables).contains("runs left the model (4)"));
    // A map without such runs has no cross in its legend.
    let (smoke, _) = crate::common::smoke_sweep();
    assert!(!legend(smoke).contains("runs left the model"));
}
