//! Slurm job scripts for a sharded sweep: `DIR/slurm/sweep.sbatch`, an array of shards each
//! running `droplet sweep --shard $SLURM_ARRAY_TASK_ID/N` into the shared directory, and
//! `DIR/slurm/merge.sbatch`, `droplet merge DIR` to run after the array (`afterany`).
//!
//! A spec with `refine:` is run one level at a time ([`crate::execution::execute`]): `sweep.sbatch` then
//! takes the level as its argument (`sbatch sweep.sbatch L`), one array per
//! level, each submitted with `--dependency=afterok:<the previous level's array>` (a level's
//! points follow from the classes of the levels below), and the merge after the last.
use crate::error::SweepError;
use std::path::PathBuf;

/// What the scripts run, and with which resources.
#[derive(Debug, Clone)]
pub struct SlurmJob {
    /// The sweep's name (job names).
    pub name: String,
    /// The spec and the output directory, absolute (the nodes share the file system).
    pub spec: PathBuf,
    pub out: PathBuf,
    /// The droplet binary the jobs run.
    pub exe: PathBuf,
    pub shards: usize,
    pub cpus: usize,
    pub partition: Option<String>,
    /// Wall time and memory per shard, in Slurm's formats.
    pub time: String,
    pub mem: String,
    pub max_runs: u64,
    /// `Some(levels)` for a spec with `refine:`: the script runs the level given as `$1`.
    pub levels: Option<u32>,
}

/// Writes both scripts (atomically); returns `[sweep.sbatch, merge.sbatch]`.
pub fn write_scripts(job: &SlurmJob) -> Result<[PathBuf; 2], SweepError> {
    let dir = job.out.join("slurm");
    crate::store::atomic::create_output_dir(&dir)?;
    let partition = job
        .partition
        .as_ref()
        .map(|p| format!("#SBATCH --partition={p}\n"))
        .unwrap_or_default();
    let header = |name: &str, extra: &str| {
        format!(
            "#!/bin/bash\n#SBATCH --job-name={name}\n{partition}#SBATCH --time={}\n#SBATCH --mem={}\n#SBATCH --output={}/%x-%A_%a.out\n{extra}set -euo pipefail\n",
            job.time,
            job.mem,
            dir.display()
        )
    };
    let (level_doc, level_arg) = match job.levels {
        None => (String::new(), ""),
        Some(levels) => (
            format!("# A refined sweep: the level (0..={levels}) is the argument; run them in order, each array\n# after the one before: sbatch --dependency=afterok:<previous array> sweep.sbatch L\nLEVEL=\"${{1:?the refinement level 0..={levels}}}\"\n"),
            " --level \"$LEVEL\"",
        ),
    };
    let sweep_script = format!(
        "{}# Shard $SLURM_ARRAY_TASK_ID of {n}: finished runs are skipped, so resubmitting resumes.\n{level_doc}\"{}\" sweep \"{}\" --out \"{}\" --shard \"$SLURM_ARRAY_TASK_ID/{n}\"{level_arg} --jobs \"${{SLURM_CPUS_PER_TASK:-1}}\" --max-runs {max_runs} --json\n",
        header(&format!("droplet-{}", job.name), &format!("#SBATCH --array=0-{}\n#SBATCH --cpus-per-task={}\n", job.shards - 1, job.cpus)),
        job.exe.display(),
        job.spec.display(),
        job.out.display(),
        n = job.shards,
        max_runs = job.max_runs,
    );
    let merge_script = format!(
        "{}\"{}\" merge \"{}\" --json\n",
        header(
            &format!("droplet-{}-merge", job.name),
            "#SBATCH --cpus-per-task=1\n"
        ),
        job.exe.display(),
        job.out.display()
    );
    let sweep_path = dir.join("sweep.sbatch");
    let merge_path = dir.join("merge.sbatch");
    crate::store::atomic::write_atomic(&sweep_path, sweep_script.as_bytes())?;
    crate::store::atomic::write_atomic(&merge_path, merge_script.as_bytes())?;
    Ok([sweep_path, merge_path])
}
