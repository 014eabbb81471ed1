//! `droplet slurm`: a Slurm job array for a sweep, plus a dependent merge job.
use super::{print_json, CliError};
use droplet_sweep::{error::SweepError, spec};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Write (and submit) Slurm array jobs that shard a sweep over a cluster.
///
/// Write (and with --submit, submit) DIR/slurm/sweep.sbatch, an array of N shards each running
/// `droplet sweep SPEC --shard $SLURM_ARRAY_TASK_ID/N`, and DIR/slurm/merge.sbatch, which runs
/// `droplet merge DIR` after the array (afterany). DIR must be on a file system all nodes share.
/// A spec with `refine:` runs one array per level (`sweep.sbatch L`), each after the one before
/// (afterok), and the merge after the last.
#[derive(clap::Args)]
#[command(
    after_help = "Example:\n  droplet slurm sweeps/fig2a.yaml --shards 32 --partition compute --time 08:00:00 --cpus 8 --submit\n  droplet status out/fig2a          # progress while it runs\n  resubmitting the array resumes: finished runs are never recomputed\n\nA spec with refine: (e.g. sweeps/fig2a-map.yaml) is submitted as one array per level,\neach after the one before (afterok; a failed level cancels the rest), then the merge; submit\nagain after a failure: finished levels are skipped in seconds"
)]
pub struct Args {
    /// The YAML spec.
    spec: PathBuf,
    /// Number of array tasks (shards).
    #[arg(long)]
    shards: usize,
    /// Output directory (default: the spec's `output`), shared by all nodes.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Slurm partition.
    #[arg(long)]
    partition: Option<String>,
    /// Wall-time limit per shard (Slurm format).
    #[arg(long, default_value = "24:00:00")]
    time: String,
    /// Memory per shard (Slurm format).
    #[arg(long, default_value = "4G")]
    mem: String,
    /// CPUs per shard (worker threads).
    #[arg(long, default_value_t = 1)]
    cpus: usize,
    /// The droplet binary the jobs run (default: this one).
    #[arg(long)]
    droplet: Option<PathBuf>,
    /// Refuse specs with more runs than this (passed on to every shard).
    #[arg(long, value_name = "RUNS", default_value_t = droplet_sweep::store::plan::DEFAULT_MAX_RUNS)]
    max_runs: u64,
    /// Submit with sbatch (array, then the merge job depending on it).
    #[arg(long)]
    submit: bool,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

fn abs(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

pub fn run(a: Args) -> Result<(), CliError> {
    let sweep = spec::load(&a.spec)?;
    if a.shards == 0 || a.cpus == 0 {
        return Err(CliError::usage("--shards and --cpus must be at least 1"));
    }
    droplet_sweep::store::plan::check_size(&sweep, a.max_runs)?;
    // A refined sweep's levels hold up to the finest lattice's runs; the spec's own grid is
    // what every level has at least.
    let runs = droplet_sweep::store::plan::run_count(&sweep);
    if a.shards as u64 > runs {
        return Err(CliError::usage(format!(
            "invalid --shards {}: the sweep has {runs} runs at most, so at most {runs} shards have work",
            a.shards
        )));
    }
    let out = abs(&a.out.clone().unwrap_or_else(|| sweep.output.clone()));
    let exe = match &a.droplet {
        Some(p) => abs(p),
        None => {
            std::env::current_exe().map_err(|e| CliError::from(SweepError::io("droplet", e)))?
        }
    };
    let scripts = droplet_sweep::execution::slurm::write_scripts(
        &droplet_sweep::execution::slurm::SlurmJob {
            name: sweep.name.clone(),
            spec: abs(&a.spec),
            out: out.clone(),
            exe,
            shards: a.shards,
            cpus: a.cpus,
            partition: a.partition.clone(),
            time: a.time.clone(),
            mem: a.mem.clone(),
            max_runs: a.max_runs,
            levels: sweep.refine.map(|l| l.refine.levels),
        },
    )?;
    let (sweep_path, merge_path) = (scripts[0].clone(), scripts[1].clone());
    let jobs = if a.submit {
        submit(
            &sweep_path,
            &merge_path,
            sweep.refine.map(|l| l.refine.levels),
        )?
    } else {
        Vec::new()
    };
    if a.json {
        print_json(
            &serde_json::json!({ "sweep_script": sweep_path, "merge_script": merge_path, "jobs": jobs, "output": out }),
        );
    } else {
        outln!(
            "wrote {}\nwrote {}",
            sweep_path.display(),
            merge_path.display()
        );
        match (jobs.split_last(), sweep.refine) {
            (None, None) => outln!(
                "submit: sbatch {} && sbatch --dependency=afterany:<array job id> {}",
                sweep_path.display(),
                merge_path.display()
            ),
            (None, Some(l)) => outln!(
                "submit (or rerun with --submit): sbatch {s} 0, then for L = 1..={}: sbatch --dependency=afterok:<level L-1's job id> --kill-on-invalid-dep=yes {s} L, then sbatch --dependency=afterany:<level {}'s job id> {}",
                l.refine.levels,
                l.refine.levels,
                merge_path.display(),
                s = sweep_path.display()
            ),
            (Some((merge, arrays)), _) => outln!(
                "submitted array job(s) {} and merge job {merge}",
                arrays.join(", ")
            ),
        }
    }
    Ok(())
}

/// Submits the sweep's array job (one per refinement level, each after the one before) and
/// the merge after the last; returns their job ids, the merge's last.
fn submit(
    sweep_path: &std::path::Path,
    merge_path: &std::path::Path,
    levels: Option<u32>,
) -> Result<Vec<String>, CliError> {
    let mut jobs = Vec::new();
    let sbatch = |args: &[&str]| -> Result<String, CliError> {
        let o = Command::new("sbatch")
            .args(args)
            .output()
            .map_err(|e| CliError {
                message: format!("cannot run sbatch: {e} (is Slurm installed here?)"),
                code: 1,
            })?;
        if !o.status.success() {
            return Err(CliError {
                message: format!(
                    "sbatch {}: {}",
                    args.join(" "),
                    String::from_utf8_lossy(&o.stderr).trim()
                ),
                code: 1,
            });
        }
        Ok(String::from_utf8_lossy(&o.stdout)
            .trim()
            .split(';')
            .next()
            .unwrap_or("")
            .to_string())
    };
    let script = sweep_path.to_str().unwrap_or_default();
    match levels {
        None => jobs.push(sbatch(&["--parsable", script])?),
        Some(levels) => {
            for level in 0..=levels {
                let level = level.to_string();
                let job = match jobs.last() {
                    None => sbatch(&["--parsable", script, &level])?,
                    Some(prev) => sbatch(&[
                        "--parsable",
                        &format!("--dependency=afterok:{prev}"),
                        "--kill-on-invalid-dep=yes",
                        script,
                        &level,
                    ])?,
                };
                jobs.push(job);
            }
        }
    }
    let dep = format!("--dependency=afterany:{}", jobs[jobs.len() - 1]);
    jobs.push(sbatch(&[
        "--parsable",
        &dep,
        merge_path.to_str().unwrap_or_default(),
    ])?);
    Ok(jobs)
}
