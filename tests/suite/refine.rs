//! Adaptive refinement (`refine:` in a spec) end to end, on the reduced ODE model (cheap):
//! the refined map reproduces the ODE's analytic boundaries to its finest step, a refined
//! sweep killed and resumed gives the uninterrupted tables, and a uniform and a refined sweep
//! share their runs in one directory.
use crate::common::{
    json, kill_at_random_moments, read, run, sweep, table_without_wall, write_spec,
};
use droplet_sweep::tables::boundaries;
use polars::prelude::*;
use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

/// The ODE over the Fig. 2a window on a coarse grid (7 x 8 points), refined `levels` levels
/// (none: the uniform grid). Three levels reach 0.000625 x 0.00125.
fn ode(levels: Option<u32>) -> String {
    let refine = levels.map_or(String::new(), |l| format!("refine: {{levels: {l}}}\n"));
    format!(
        "model: ode
grid:
  eta_t: {{start: 0.070, stop: 0.100, step: 0.005}}
  kappa2: {{start: 0.100, stop: 0.170, step: 0.01}}
initial_conditions: [i, ii, iii, iv]
solver: {{dt: 0.05, t_max: 3000}}
{refine}"
    )
}

pub(crate) struct Point {
    pub(crate) eta_t: f64,
    pub(crate) kappa2: f64,
    pub(crate) level: u32,
    pub(crate) class: String,
}

/// The points of a map's `points.parquet`: coordinates, level and class.
pub(crate) fn points(dir: &Path) -> Vec<Point> {
    let df = read(&dir.join("points.parquet"));
    let f = |c: &str| df.column(c).unwrap().f64().unwrap().clone();
    let (e, k) = (f("eta_t"), f("kappa2"));
    let level = df.column("level").unwrap().u32().unwrap().clone();
    let class = df.column("class").unwrap().str().unwrap().clone();
    (0..df.height())
        .map(|i| Point {
            eta_t: e.get(i).unwrap(),
            kappa2: k.get(i).unwrap(),
            level: level.get(i).unwrap(),
            class: class.get(i).unwrap().to_string(),
        })
        .collect()
}

/// Distance from `p` to a polyline, in units of the finest cell `(de, dk)` on each axis (a
/// line of fewer than two points is nowhere near).
fn distance(p: (f64, f64), line: &[(f64, f64)], (de, dk): (f64, f64)) -> f64 {
    if line.len() < 2 {
        return f64::INFINITY;
    }
    let scaled = |q: (f64, f64)| (q.0 / de, q.1 / dk);
    let line: Vec<(f64, f64)> = line.iter().map(|&q| scaled(q)).collect();
    droplet_solver::continuation::polyline::distance_to_polyline(scaled(p), &line)
}

/// The reduced model's analytic boundaries a sweep in `out` wrote (curves of two points or
/// more).
fn analytic_curves(out: &Path) -> Vec<Vec<(f64, f64)>> {
    boundaries::read(
        &out.join(boundaries::FILE),
        droplet_solver::contract::settings::ModelKind::Ode,
    )
    .unwrap()
    .into_iter()
    .map(|c| c.points)
    .filter(|p| p.len() >= 2)
    .collect()
}

#[test]
fn ode_refinement_reproduces_the_analytic_boundaries_to_the_finest_step() {
    let dir = tempfile::tempdir().unwrap();
    // Three levels (a finest step of 1/8 of the coarse one): the property (every class
    // change on an analytic boundary to the finest step, every boundary refined to it) is
    // the same at any depth; four levels cost 2.8x the runs.
    const FINEST: u32 = 3;
    let spec = write_spec(dir.path(), "ode.yaml", &ode(Some(FINEST)));
    let out = dir.path().join("ode");
    let j = json(&run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let pts = points(&out);
    assert_eq!(pts.len() as u64, j["points"].as_u64().unwrap());
    let cells = f64::from(1u32 << FINEST);
    let finest = (0.005 / cells, 0.01 / cells);
    let uniform_finest = (0.03 / finest.0 + 1.0) * (0.07 / finest.1 + 1.0);
    // A small window with a coarse level 0 (the Fig. 2a spec saves far more).
    assert!(
        (pts.len() as f64) < uniform_finest / 4.0,
        "{} points against {uniform_finest} on the finest uniform grid",
        pts.len()
    );
    assert!(
        pts.iter().any(|p| p.level == FINEST),
        "the finest level is reached"
    );
    let curves = analytic_curves(&out);
    assert!(!curves.is_empty());
    let near_a_boundary =
        |p: (f64, f64), within: f64| curves.iter().any(|c| distance(p, c, finest) <= within);
    // 1. Every edge of the resting disk's region (IC next to another class) between
    //    finest-level neighbours lies on an analytic boundary (f1, g0~, MD existence). (The
    //    edge between MD and ID/MD is where one of the four initial conditions starts to
    //    reach ID, a basin boundary with no formula.)
    let at: HashMap<(i64, i64), &Point> = pts
        .iter()
        .map(|p| {
            let key = (
                ((p.eta_t - 0.07) / finest.0).round() as i64,
                ((p.kappa2 - 0.1) / finest.1).round() as i64,
            );
            (key, p)
        })
        .collect();
    let mut changes = 0;
    for (&(i, j), p) in &at {
        for (di, dj) in [(1, 0), (0, 1)] {
            let Some(q) = at.get(&(i + di, j + dj)) else {
                continue;
            };
            if p.class != q.class && (p.class == "IC" || q.class == "IC") {
                changes += 1;
                let mid = (0.5 * (p.eta_t + q.eta_t), 0.5 * (p.kappa2 + q.kappa2));
                assert!(
                    near_a_boundary(mid, 1.5),
                    "{} at ({}, {}) next to {} at ({}, {}): no analytic boundary within 1.5 finest cells",
                    p.class, p.eta_t, p.kappa2, q.class, q.eta_t, q.kappa2
                );
            }
        }
    }
    assert!(changes > 10, "only {changes} class changes resolved");
    // 2. Along every analytic boundary inside the window the map is refined to the finest
    //    level: a finest-level point within two finest cells.
    let finest_pts: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| p.level == FINEST)
        .map(|p| (p.eta_t, p.kappa2))
        .collect();
    for c in &curves {
        for w in c.windows(2) {
            let m = (0.5 * (w[0].0 + w[1].0), 0.5 * (w[0].1 + w[1].1));
            let inside = m.0 > 0.075 && m.0 < 0.095 && m.1 > 0.11 && m.1 < 0.16;
            if !inside {
                continue;
            }
            let ok = finest_pts
                .iter()
                .any(|&f| distance(f, &[m, m], finest) <= 2.0);
            assert!(ok, "boundary near ({}, {}) not refined", m.0, m.1);
        }
    }
}

#[test]
fn a_refined_sweep_killed_and_resumed_gives_the_uninterrupted_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "ode.yaml", &ode(Some(2)));
    let reference = dir.path().join("ref");
    let started = Instant::now();
    json(&sweep(&spec, &reference, &[]));
    let full_ms = started.elapsed().as_millis() as u64;
    let resumed = dir.path().join("resumed");
    let (kills, tries) = kill_at_random_moments(&spec, &resumed, full_ms, 6, 30);
    assert!(kills >= 3, "only {kills} of {tries} tries were interrupted");
    json(&sweep(&spec, &resumed, &[]));
    for t in ["runs.parquet", "points.parquet"] {
        let sort = |df: DataFrame| {
            df.sort(["eta_t", "kappa2"], SortMultipleOptions::default())
                .unwrap()
        };
        let a = table_without_wall(&reference.join(t));
        let b = table_without_wall(&resumed.join(t));
        assert!(a.equals_missing(&b), "{t} differs");
        // Also equal as sets of rows (the order is the plan's, deterministic).
        assert!(sort(a.clone()).equals_missing(&sort(b)));
    }
}

#[test]
fn a_uniform_and_a_refined_sweep_share_their_runs() {
    let dir = tempfile::tempdir().unwrap();
    let uniform = write_spec(dir.path(), "uniform.yaml", &ode(None));
    let refined = write_spec(dir.path(), "refined.yaml", &ode(Some(2)));
    let out = dir.path().join("shared");
    let o = out.to_str().unwrap();
    let u = json(&sweep(&uniform, &out, &[]));
    let runs0 = u["runs"].as_u64().unwrap();
    assert_eq!(runs0, 7 * 8 * 4);
    let r = json(&sweep(&refined, &out, &[]));
    assert_eq!(
        r["reused"].as_u64().unwrap(),
        runs0,
        "level 0 is the uniform sweep's runs"
    );
    assert!(r["computed"].as_u64().unwrap() > 0);
    // Run again: everything is stored.
    let again = json(&sweep(&refined, &out, &[]));
    assert_eq!(again["computed"].as_u64().unwrap(), 0);
    // status reads the levels from the stored runs.
    let st = json(&run(&["status", o, "--json"]));
    let levels = st["levels"].as_array().unwrap();
    assert!(levels.len() >= 2, "{st}");
    assert!(
        levels.iter().all(|l| l["runs_done"] == l["runs_total"]),
        "{st}"
    );
    assert_eq!(st["complete"], true);
    // Every run was stored within the pace window; nothing remains, so no ETA.
    assert_eq!(st["runs_recent"], st["runs_done"], "{st}");
    assert!(st["eta_s"].is_null(), "{st}");
}

#[test]
fn a_refined_sweep_sharded_level_by_level_merges_to_the_unsharded_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path(), "ode.yaml", &ode(Some(2)));
    let single = dir.path().join("single");
    json(&sweep(&spec, &single, &[]));
    let sharded = dir.path().join("sharded");
    let s = sharded.to_str().unwrap();
    // A shard of a refined spec needs its level; a level needs the ones below it.
    let no_level = sweep(&spec, &sharded, &["--shard", "0/2"]);
    assert_eq!(no_level.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&no_level.stderr).contains("--level"));
    let early = sweep(&spec, &sharded, &["--shard", "0/2", "--level", "1"]);
    assert_eq!(early.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&early.stderr).contains("level 0 has 224 of its runs missing"),
        "{}",
        String::from_utf8_lossy(&early.stderr)
    );
    let too_deep = sweep(&spec, &sharded, &["--shard", "0/2", "--level", "3"]);
    assert_eq!(too_deep.status.code(), Some(2));
    // Level by level, two shards each (as `droplet slurm` chains the arrays).
    let mut runs_by_level = Vec::new();
    for level in ["0", "1", "2"] {
        let mut runs = 0;
        for shard in ["0/2", "1/2"] {
            let r = json(&sweep(
                &spec,
                &sharded,
                &["--shard", shard, "--level", level],
            ));
            assert_eq!(r["level"].as_u64().unwrap().to_string(), level);
            runs += r["runs"].as_u64().unwrap();
        }
        runs_by_level.push(runs);
    }
    assert_eq!(runs_by_level[0], 7 * 8 * 4);
    assert!(
        runs_by_level[1] > 0 && runs_by_level[2] > 0,
        "{runs_by_level:?}"
    );
    // No tables until the merge, which gives the unsharded sweep's.
    assert!(!sharded.join("points.parquet").exists());
    json(&run(&["merge", s, "--json"]));
    for t in ["runs.parquet", "points.parquet"] {
        let a = table_without_wall(&single.join(t));
        let b = table_without_wall(&sharded.join(t));
        assert!(a.equals_missing(&b), "{t} differs");
    }
    let st = json(&run(&["status", s, "--json"]));
    let per_level: Vec<u64> = st["levels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["runs_total"].as_u64().unwrap())
        .collect();
    assert_eq!(per_level, runs_by_level);
}
