//! `refine.certify_midpoints` end to end: certified midpoints end where their runs do, and
//! are stepped once the option is off.
use crate::common::{json, read, run, sweep, write_spec};
use crate::refine::points;
use polars::prelude::*;
use std::collections::HashMap;
use std::path::Path;

/// A PDE map at N = 96 (4 x 4 points over the Fig. 2a window, `levels` levels), with
/// `refine.certify_midpoints: certify` (`false`, `true`, `chained`).
fn pde_map(certify: &str, levels: u32) -> String {
    format!(
        "grid:
  eta_t: {{start: 0.070, stop: 0.100, step: 0.01}}
  kappa2: {{start: 0.100, stop: 0.160, step: 0.02}}
initial_conditions: [i, ii, iii, iv]
solver: {{n: 96}}
refine: {{levels: {levels}, certify_midpoints: {certify}}}
"
    )
}

/// The points of a map whose runs were certified, `(eta_t, kappa2)`.
fn certified_points(dir: &Path) -> Vec<(f64, f64)> {
    let df = read(&dir.join("runs.parquet"));
    let col = |c: &str| df.column(c).unwrap().f64().unwrap().clone();
    let (eta_t, kappa2, ended) = (col("eta_t"), col("kappa2"), df.column("ended_by").unwrap());
    let mut out: Vec<(f64, f64)> = (0..df.height())
        .filter(|&i| ended.str().unwrap().get(i) == Some("certified_midway"))
        .map(|i| (eta_t.get(i).unwrap(), kappa2.get(i).unwrap()))
        .collect();
    out.sort_by(|a, b| a.partial_cmp(b).unwrap());
    out.dedup();
    out
}

/// `(class, v, s, ended_by)` of every run of a map, by key.
fn run_ends(dir: &Path) -> HashMap<String, (String, f64, f64, String)> {
    let df = read(&dir.join("runs.parquet"));
    let s = |c: &str| df.column(c).unwrap().str().unwrap().clone();
    let f = |c: &str| df.column(c).unwrap().f64().unwrap().clone();
    let (key, class, ended) = (s("key"), s("class"), s("ended_by"));
    let (v, sh) = (f("v"), f("s"));
    (0..df.height())
        .map(|i| {
            let text = |c: &StringChunked| c.get(i).unwrap_or("").to_string();
            let ends = (
                text(&class),
                v.get(i).unwrap(),
                sh.get(i).unwrap(),
                text(&ended),
            );
            (text(&key), ends)
        })
        .collect()
}

/// How many runs of the map in `out` are certified at cell centres (midway between a split
/// cell's opposite corners), four per point.
fn certified_cell_centres(out: &Path) -> usize {
    // Edge midpoints and cell centres (midway between a split cell's opposite corners) alike:
    // here (0.085, 0.13), the centre of the cell (0.08..0.09, 0.12..0.14), among them.
    let df = read(&out.join("runs.parquet"));
    let col = |c: &str| df.column(c).unwrap().f64().unwrap().clone();
    let (eta_t, kappa2, ended) = (col("eta_t"), col("kappa2"), df.column("ended_by").unwrap());
    let off_grid = |x: f64, start: f64, step: f64| ((x - start) / step).fract().abs() > 0.25;
    let centres = (0..df.height())
        .filter(|&i| ended.str().unwrap().get(i) == Some("certified_midway"))
        .filter(|&i| {
            off_grid(eta_t.get(i).unwrap(), 0.07, 0.01)
                && off_grid(kappa2.get(i).unwrap(), 0.10, 0.02)
        })
        .count();
    assert!(centres.is_multiple_of(4), "{centres}");
    centres
}

/// How many level-2 points of the map in `out` are certified midway (along an axis or a
/// diagonal of their level's cell) between two points, one of them certified on level 1
/// (`level_1`).
fn certified_from_certified_neighbours(out: &Path, level_1: &[(f64, f64)]) -> usize {
    let all = points(out);
    let near = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9;
    let exists = |q: (f64, f64)| all.iter().any(|p| near((p.eta_t, p.kappa2), q));
    let on_level_1 = |q: (f64, f64)| level_1.iter().any(|&c| near(c, q));
    let (h, k) = (0.01 / 4.0, 0.02 / 4.0);
    let from_certified = certified_points(out)
        .into_iter()
        .filter(|&(e, kk)| {
            all.iter()
                .any(|p| p.level == 2 && near((p.eta_t, p.kappa2), (e, kk)))
        })
        .filter(|&(e, kk)| {
            [(h, 0.0), (0.0, k), (h, k), (h, -k)]
                .iter()
                .any(|&(de, dk)| {
                    let (a, b) = ((e - de, kk - dk), (e + de, kk + dk));
                    exists(a) && exists(b) && (on_level_1(a) || on_level_1(b))
                })
        })
        .count();
    from_certified
}

#[test]
fn certified_midpoints_end_where_their_runs_do_and_are_stepped_once_the_option_is_off() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("map");
    let spec = write_spec(dir.path(), "on.yaml", &pde_map("true", 1));
    let on = json(&sweep(&spec, &out, &[]));
    let certified_1 = on["certified"].as_u64().unwrap();
    assert!(certified_1 > 0 && certified_1.is_multiple_of(4), "{on}");
    let level_1 = certified_points(&out);
    // A second level, chained: its midpoints may be certified from certified neighbours
    // (the first level's certified runs are reused as they are). One such point at least:
    // a level-2 point midway (along an axis or a diagonal of its level's cell) between two
    // points, one of them certified on level 1.
    let spec = write_spec(dir.path(), "chained.yaml", &pde_map("chained", 2));
    let chained = json(&sweep(&spec, &out, &[]));
    let certified_2 = chained["certified"].as_u64().unwrap();
    assert!(
        certified_2 > 0 && certified_2.is_multiple_of(4),
        "{chained}"
    );
    assert!(
        chained["certify_refused"]
            .get("neighbour_certified")
            .is_none(),
        "{chained}"
    );
    let certified = certified_1 + certified_2;
    let from_certified = certified_from_certified_neighbours(&out, &level_1);
    assert!(from_certified > 0, "{chained}");
    let ends = run_ends(&out);
    let certified_keys: Vec<&String> = ends
        .iter()
        .filter(|(_, e)| e.3 == "certified_midway")
        .map(|(k, _)| k)
        .collect();
    assert_eq!(certified_keys.len() as u64, certified);
    assert!(certified_cell_centres(&out) > 0);
    // Every label a stable state, the certified runs' included.
    let o = run(&["audit", out.to_str().unwrap(), "--json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let labels = |d: &Path| -> Vec<(f64, f64, String)> {
        let mut p: Vec<(f64, f64, String)> = points(d)
            .into_iter()
            .map(|p| (p.eta_t, p.kappa2, p.class))
            .collect();
        p.sort_by(|a, b| a.partial_cmp(b).unwrap());
        p
    };
    let certified_labels = labels(&out);
    // The option off in the same directory: the certified runs (only they) are stepped, and
    // each ends on the certificate's class and root.
    let spec = write_spec(dir.path(), "off.yaml", &pde_map("false", 2));
    let off = json(&sweep(&spec, &out, &[]));
    assert_eq!(off["computed"].as_u64().unwrap(), certified, "{off}");
    assert_eq!(off["certified"], 0);
    let stepped = run_ends(&out);
    for k in certified_keys {
        let (c, v, s, how) = &ends[k];
        let (c2, v2, s2, how2) = &stepped[k];
        assert_ne!(how2, "certified_midway");
        assert_eq!((c, how.as_str()), (c2, "certified_midway"), "{k}: {how2}");
        assert!(
            (v - v2).abs() < 1e-6 && (s - s2).abs() < 1e-6,
            "{k}: {v} {s} vs {v2} {s2}"
        );
    }
    assert_eq!(labels(&out), certified_labels);
    // What the option would make of the map, from its tables alone (`bench --map --certify`):
    // each certified run with its stepped run's class; chained, the levels in order as the
    // sweep takes them.
    for mode in [None, Some("chained")] {
        let map = out.to_str().unwrap();
        let args = ["bench", "--map", map, "--json", "--certify"];
        let check = json(&run(&[&args[..], mode.as_slice()].concat()));
        assert_eq!(check["mode"], mode.unwrap_or("true"), "{check}");
        assert!(check["certified_points"].as_u64().unwrap() > 0, "{check}");
        assert_eq!(check["class_differences"], 0, "{check}");
    }
}

#[test]
fn bad_certify_values_exit_2_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    // Bad values exit 2 naming the field; runs that end otherwise than by the spectral PDE's
    // Newton finish (the reduced model, the paper's test) have no certificate.
    for (name, text) in [
        (
            "test",
            pde_map("chained", 1).replace("solver: {n: 96}", "solver: {n: 96, steady: test}"),
        ),
        ("number", pde_map("1", 1)),
        ("word", pde_map("chain", 1)),
        (
            "ode",
            format!(
                "model: ode\n{}",
                pde_map("true", 1).replace("solver: {n: 96}\n", "")
            ),
        ),
    ] {
        let spec = write_spec(dir.path(), &format!("{name}.yaml"), &text);
        let o = sweep(&spec, &dir.path().join(name), &[]);
        assert_eq!(o.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("refine.certify_midpoints"), "{name}: {err}");
    }
}
