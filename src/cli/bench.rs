//! `droplet bench`: the work-precision benchmark ([`droplet_sweep::bench`]).
use super::{print_json, CliError};
use droplet_sweep::bench::certify_check::check_certificates;
use droplet_sweep::bench::map_profile::{profile_map, Group, MapProfile, MapProfileOptions};
use droplet_sweep::bench::run::{run_benchmark, BenchOptions};
use droplet_sweep::map::sample::Sample;
use droplet_sweep::spec::lattice::Certify;
use std::path::PathBuf;

/// Time representative runs against their references: speed and the error it costs.
///
/// Time representative runs (the Fig. 1 IC, ID and MD points, a point in the IC/MD bistable
/// band, and the transient t <= 20 through the MD instability) with the paper's FD scheme,
/// the spectral scheme at N = 96..256 and dt = 0.005..0.1, and the adaptive scheme at several
/// tolerances, and measure each run's error against a fine reference (Newton on the exact
/// steady equations at N = 384 for steady states; spectral N = 256, dt = 0.001 for the time
/// series). The reference is computed once and kept in OUT/reference.json; later runs reuse it.
/// Writes OUT/bench.parquet (one row per run, diverged runs included), OUT/summary.json and
/// the log-log picture OUT/work_precision.png/.svg. The full profile takes about half an hour
/// on 2 cores; use --quick for a seconds-long miniature.
///
/// With --map DIR: where a map's run time goes. The runs of the finished map in DIR (a seeded
/// sample with --sample N --seed S, else all) are computed again as its sweep runs them (its
/// spec, two at a time on 2 cores), each profiled: time stepping, the Newton solves, the
/// eigenvalue problems of their roots, the landing's and the orientation flow's samples, the
/// leap and the diagnosis, per way of ending (the map's) and per refinement level, with the
/// map's own run time for the same runs and whether each run ends as the map's did (the same
/// class, v and s within 1e-6). Writes OUT/map_profile.parquet (one row per run) and
/// OUT/map_profile.json (the groups).
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  droplet bench --quick --out /tmp/bench     # miniature, seconds\n  droplet bench --out results/bench --jobs 2  # the committed benchmark\n  droplet bench --map results/fig2a-map --sample 200 --seed 1 --out out/map-profile\n  droplet bench --map results/fig2a-map --certify   # what refine.certify_midpoints would make of it\n  droplet bench --map results/fig2a-map --certify chained"
)]
pub struct Args {
    /// Output directory (default: out/bench, with --map out/map-profile).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Profile the runs of the finished map in this directory instead of the work-precision
    /// benchmark.
    #[arg(long, value_name = "DIR")]
    map: Option<PathBuf>,
    /// With --map DIR of a refined map: instead of the profile, what refine.certify_midpoints
    /// would make of it, from its tables (nothing is stepped): at every point midway between
    /// two coarser points of one state (an edge midpoint, or a cell centre between opposite
    /// corners), the certificate from the neighbours' runs against the
    /// point's own runs (class, root, time). JSON keys: map, points, candidates,
    /// certified_points, certified_runs, refused, class_differences, other_root,
    /// other_root_max_dv, other_root_max_ds, same_root_max_dv, same_root_max_ds,
    /// certificates_s, their_runs_s, map_run_time_s, wall_s, mode. `--certify` alone is
    /// `certify_midpoints: true` (the neighbours' runs as the map has them); `--certify
    /// chained` takes the levels in order as the sweep does, a neighbour certified here
    /// lending its certified ends.
    #[arg(long, requires = "map", conflicts_with = "sample", value_name = "MODE",
          num_args = 0..=1, default_missing_value = "true", value_parser = ["true", "chained"])]
    certify: Option<String>,
    /// With --map: a seeded random sample of this many runs (default: every run).
    #[arg(long, requires = "map", value_name = "N")]
    sample: Option<usize>,
    /// With --sample: the sample's seed (the same runs for the same map and seed).
    #[arg(long, requires = "sample", default_value_t = 1)]
    seed: u64,
    /// The miniature profile (N = 32..64, short windows) for tests and a first look.
    #[arg(long, conflicts_with = "map")]
    quick: bool,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
    /// Replace an existing OUT/bench.parquet.
    #[arg(long, conflicts_with = "map")]
    force: bool,
    /// Re-score the runs of OUT/bench.parquet against OUT/reference.json (recomputed when
    /// absent) without re-running them; rewrites the table, summary and picture.
    #[arg(long, conflicts_with_all = ["force", "map"])]
    rescore: bool,
    /// Print one JSON object (keys: out, profile, rows, summary, reference_wall_s, wall_s,
    /// files; with --map: map, map_runs, runs, seed, jobs, total, by_ending, by_level,
    /// by_duration (by decade of t_end; each group: name, runs, wall_s, map_wall_s,
    /// same_end, profile {stepping_s, newton_s, eigen_s, landing_s, flow_s, leap_s,
    /// diagnosis_s, newton_solves, eigen_problems, field_solves}), changed, wall_s, files).
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    if let Some(map) = a.map.clone() {
        return run_map(a, map);
    }
    let report = run_benchmark(&BenchOptions {
        out: a.out.clone().unwrap_or_else(|| PathBuf::from("out/bench")),
        quick: a.quick,
        jobs: a.jobs,
        force: a.force,
        rescore: a.rescore,
        progress: !a.json,
    })?;
    let reused = report.reference_reused;
    let refs_wall = report.reference_wall_s;
    if a.json {
        print_json(&report);
        return Ok(());
    }
    outln!(
        "{} runs in {:.0} s (reference {}: {:.0} s)",
        report.rows,
        report.wall_s,
        if reused { "reused" } else { "computed" },
        refs_wall
    );
    if let Some(rate) = report.summary.paper_fd_s_per_time {
        outln!("paper-fd: {rate:.2} s of wall time per simulated time unit");
    }
    for d in report.summary.vs_paper_fd.iter().filter(|d| d.is_default) {
        outln!(
            "default on {:<11} err v {:.1e}  err s {:.1e}  class {}  {:.2} s{}",
            d.case,
            d.err_v,
            d.err_s,
            if d.class_ok { "ok" } else { "WRONG" },
            d.wall_s,
            d.speedup
                .map(|x| format!("  ({x:.0}x faster than paper-fd, extrapolated)"))
                .unwrap_or_default()
        );
    }
    for d in &report.summary.diverged {
        outln!("diverged: {d}");
    }
    for d in &report.summary.class_mismatches {
        outln!("class differs from the reference: {d}");
    }
    for f in &report.files {
        outln!("wrote {}", f.display());
    }
    Ok(())
}

/// `droplet bench --map DIR`.
fn run_map(a: Args, map: PathBuf) -> Result<(), CliError> {
    if let Some(mode) = &a.certify {
        let mode = match mode.as_str() {
            "chained" => Certify::Chained,
            _ => Certify::Stepped,
        };
        let check = check_certificates(&map, mode, a.jobs)?;
        if a.json {
            print_json(&check);
        } else {
            outln!(
                "{} ({}): {} points, {} midway between two coarser points of one state: {} certified ({} runs), refused {:?}; {} certified runs of another class than their own run, {} on another root (up to {:.1e} in v, {:.1e} in s); certificates {:.1} s against {:.1} s of the map's run time for those runs ({:.1} s in all)",
                check.map.display(),
                check.mode,
                check.points,
                check.candidates,
                check.certified_points,
                check.certified_runs,
                check.refused,
                check.class_differences,
                check.other_root,
                check.other_root_max_dv,
                check.other_root_max_ds,
                check.certificates_s,
                check.their_runs_s,
                check.map_run_time_s
            );
        }
        return Ok(());
    }
    if a.sample == Some(0) {
        return Err(CliError::usage("invalid --sample 0: at least one run"));
    }
    let report = profile_map(&MapProfileOptions {
        map,
        out: a.out.unwrap_or_else(|| PathBuf::from("out/map-profile")),
        sample: a.sample.map(|points| Sample {
            points,
            seed: a.seed,
        }),
        jobs: a.jobs,
        progress: !a.json,
    })?;
    if a.json {
        print_json(&report);
    } else {
        print_profile(&report);
    }
    Ok(())
}

/// The profile as a table: a row per way of ending, per level, and in all.
fn print_profile(p: &MapProfile) {
    outln!(
        "{}: {} of {} runs{}, {} threads, {:.0} s",
        p.map.display(),
        p.runs,
        p.map_runs,
        p.seed.map(|s| format!(" (seed {s})")).unwrap_or_default(),
        p.jobs,
        p.wall_s
    );
    outln!(
        "{:<18} {:>5} {:>9} {:>9} {:>6}  {:>5} {:>5} {:>5} {:>5} {:>5} {:>5}  {:>7} {:>5}",
        "group",
        "runs",
        "time (s)",
        "map's",
        "ratio",
        "step",
        "newt",
        "eig",
        "land",
        "flow",
        "other",
        "fields",
        "same"
    );
    let pct = |x: f64, g: &Group| 100.0 * x / g.wall_s.max(1e-300);
    for g in p
        .by_ending
        .iter()
        .chain(&p.by_level)
        .chain(&p.by_duration)
        .chain([&p.total])
    {
        let q = &g.profile;
        outln!(
            "{:<18} {:>5} {:>9.1} {:>9.1} {:>6.3}  {:>4.0}% {:>4.0}% {:>4.0}% {:>4.0}% {:>4.0}% {:>4.0}%  {:>7.1} {:>5}",
            g.name,
            g.runs,
            g.wall_s,
            g.map_wall_s,
            g.wall_s / g.map_wall_s.max(1e-300),
            pct(q.stepping_s, g),
            pct(q.newton_s, g),
            pct(q.eigen_s, g),
            pct(q.landing_s, g),
            pct(q.flow_s, g),
            pct(g.other_s() + q.leap_s + q.diagnosis_s, g),
            q.field_solves as f64 / g.runs.max(1) as f64,
            g.same_end
        );
    }
    outln!("(fields: steady field solves per run; other: leaps, diagnoses and the driver)");
    for r in &p.changed {
        outln!(
            "ends otherwise: point {} ({}, {}) from {}: {} v {:.6} s {:.6}, the map's {} v {:.6} s {:.6}",
            r.point,
            r.coords[0],
            r.coords[1],
            r.ic,
            r.class.as_deref().unwrap_or("unsettled"),
            r.v,
            r.s,
            r.map_class.as_deref().unwrap_or("unsettled"),
            r.map_v,
            r.map_s
        );
    }
    for f in &p.files {
        outln!("wrote {}", f.display());
    }
}
