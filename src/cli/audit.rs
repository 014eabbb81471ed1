//! `droplet audit`: every point's label checked against the stable states at that point.
use super::{print_json, CliError};
use std::path::PathBuf;

/// Check a sweep's labels against the model's stable states, point by point.
///
/// Every class a point's label names must be a stable steady state of the PDE model there.
/// For each point the resting disk's eigenvalues are computed (an IC run contradicts when one
/// grows), and Newton on the four steady equations starts from every other run's final state
/// (it contradicts when no root is found, when the root has another class, or when it has a
/// growing eigenvalue besides the near-neutral rotation mode). Runs that did not end on a
/// stable state are listed as unsettled, and a label the points table has but its runs do not
/// give as a label mismatch. The map must be complete: every point of the points table has
/// exactly one run of each of the spec's initial conditions (a run missing, duplicated, or of
/// another condition or point is a contradiction; an empty table is refused). Exits 1 when anything contradicts, listing each contradiction
/// with the run that caused it; 0 when the map is clean. Reads DIR/runs.parquet and
/// DIR/points.parquet (a finished sweep, or a committed map in results/); about 0.1 s per
/// point at N = 192, on all cores.
#[derive(clap::Args)]
pub struct Args {
    /// A finished sweep's output directory (or any directory with its runs.parquet and
    /// points.parquet).
    dir: PathBuf,
    /// List at most this many contradictions in the text output (all of them with --json).
    #[arg(long, default_value_t = 20)]
    show: usize,
    /// Check the stable states at a fixed random sample of this many points only (drawn by
    /// --seed; completeness and labels are still checked at every point). The full audit of
    /// results/fig2a-map takes minutes; a sample of 24 points takes seconds.
    #[arg(long, value_name = "POINTS")]
    sample: Option<usize>,
    /// The seed of --sample's draw (the same points for the same map and seed).
    #[arg(long, default_value_t = 1, requires = "sample")]
    seed: u64,
    /// Print one JSON object: points, runs, points_clean, sampled (null: every point),
    /// states_checked, by_kind,
    /// list (point, eta_t, kappa2, label, ic, class, kind, detail, key). Kinds: unsettled,
    /// unstable_disk, no_root, other_class, unstable_root, label_mismatch, missing_run,
    /// duplicate_run, unknown_run.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    if a.sample == Some(0) {
        return Err(CliError::usage(
            "invalid --sample 0: at least one point (leave it out to check every point)",
        ));
    }
    let sample = a.sample.map(|points| droplet_sweep::audit::Sample {
        points,
        seed: a.seed,
    });
    let audit = droplet_sweep::audit::audit(&a.dir, sample)?;
    let by_kind: serde_json::Map<String, serde_json::Value> = audit
        .by_kind()
        .into_iter()
        .map(|(k, n)| (k.as_str().to_string(), n.into()))
        .collect();
    if a.json {
        print_json(&serde_json::json!({
            "dir": a.dir,
            "points": audit.points,
            "runs": audit.runs,
            "points_clean": audit.points_clean,
            "sampled": audit.sampled,
            "states_checked": audit.states_checked,
            "contradictions": audit.contradictions.len(),
            "by_kind": by_kind,
            "list": audit.contradictions,
        }));
    } else {
        let at = audit.sampled.map_or(String::new(), |n| {
            format!(" at {n} sampled points (seed {})", a.seed)
        });
        outln!(
            "{}: {} points, {} runs; {} points clean, {} contradictions ({} steady states checked{at})",
            a.dir.display(),
            audit.points,
            audit.runs,
            audit.points_clean,
            audit.contradictions.len(),
            audit.states_checked
        );
        for (kind, n) in audit.by_kind() {
            outln!("  {}: {n}", kind.as_str());
        }
        for c in audit.contradictions.iter().take(a.show) {
            outln!(
                "  ({}, {}) {} from {}: {} ({}) [{}]",
                c.eta_t,
                c.kappa2,
                c.label,
                c.ic,
                c.kind.as_str(),
                c.detail,
                c.key
            );
        }
        if audit.contradictions.len() > a.show {
            outln!(
                "  ... {} more (--show N, or --json for all)",
                audit.contradictions.len() - a.show
            );
        }
    }
    if audit.contradictions.is_empty() {
        Ok(())
    } else {
        Err(CliError {
            message: format!(
                "{} contradictions in {} of {} points: those labels do not name stable states",
                audit.contradictions.len(),
                audit.points - audit.points_clean,
                audit.points
            ),
            code: 1,
        })
    }
}
