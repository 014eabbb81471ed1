//! `droplet merge`: the final tables of a sharded sweep.
use super::{print_json, CliError};
use std::path::PathBuf;

/// Build a sweep's tables and picture from its stored runs (e.g. after Slurm shards).
///
/// Build DIR/runs.parquet, DIR/points.parquet and the picture from every stored run (e.g. after
/// the shards of a Slurm array job). With runs missing or unreadable it lists them, writes
/// nothing and exits with code 1. Safe to repeat.
#[derive(clap::Args)]
pub struct Args {
    /// The sweep's output directory.
    out: PathBuf,
    /// Do not draw the phase map.
    #[arg(long)]
    no_plot: bool,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    match droplet_sweep::execution::merge::merge(&a.out, !a.no_plot) {
        Ok(report) => {
            if a.json {
                print_json(&report);
            } else {
                outln!(
                    "{}: all {} runs present",
                    a.out.display(),
                    report.runs_total
                );
                for f in &report.tables {
                    outln!("wrote {}", f.display());
                }
            }
            Ok(())
        }
        Err(droplet_sweep::error::SweepError::Incomplete(report)) => {
            if a.json {
                print_json(&report);
            }
            let list = report.missing_examples.join("\n  ");
            Err(CliError {
                message: format!(
                    "{} of {} runs are missing in {} ({} of them stored but unreadable); no tables written; re-run the sweep or the shards (unreadable runs are then moved to corrupt/ and recomputed). Missing (first {}):\n  {list}",
                    report.runs_missing,
                    report.runs_total,
                    a.out.display(),
                    report.runs_unreadable,
                    report.missing_examples.len()
                ),
                code: 1,
            })
        }
        Err(e) => Err(e.into()),
    }
}
