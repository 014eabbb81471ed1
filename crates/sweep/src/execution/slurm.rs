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

/// A value as one single-quoted shell word: nothing in it is expanded (`$(...)`, backquotes,
/// `$VAR`), and a `'` in it is closed, escaped and reopened.
fn shell_word(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

/// Refuses a value that would change a script's lines: any control character (a newline
/// starts a command), and in an `#SBATCH` line, which sbatch splits at blanks and does not
/// unquote, also blanks and quotes.
fn check_value(what: &str, text: &str, in_directive: bool) -> Result<(), SweepError> {
    let bad = text
        .chars()
        .find(|c| c.is_control() || (in_directive && (c.is_whitespace() || "'\"\\".contains(*c))));
    match bad {
        None => Ok(()),
        Some(c) => Err(SweepError::Invalid(format!(
            "{what} {text:?} holds {c:?}, which cannot be written into a Slurm script{}",
            if in_directive {
                " (an #SBATCH line takes no control characters, blanks or quotes)"
            } else {
                " (no control characters)"
            }
        ))),
    }
}

/// Refuses every value of `job` that could not be written into a script as it is.
fn check_job(job: &SlurmJob) -> Result<(), SweepError> {
    let path = |p: &PathBuf| p.to_string_lossy().into_owned();
    let directive = [
        ("the sweep's name", job.name.clone()),
        ("--partition", job.partition.clone().unwrap_or_default()),
        ("--time", job.time.clone()),
        ("--mem", job.mem.clone()),
        ("the output directory", path(&job.out)),
    ];
    for (what, text) in &directive {
        check_value(what, text, true)?;
    }
    for (what, text) in [
        ("the spec's path", path(&job.spec)),
        ("the droplet binary's path", path(&job.exe)),
    ] {
        check_value(what, &text, false)?;
    }
    Ok(())
}

/// Writes both scripts (atomically); returns `[sweep.sbatch, merge.sbatch]`. Every path is
/// written as a single-quoted shell word; a value that cannot be written safely is refused
/// before anything is written.
pub fn write_scripts(job: &SlurmJob) -> Result<[PathBuf; 2], SweepError> {
    check_job(job)?;
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
        "{}# Shard $SLURM_ARRAY_TASK_ID of {n}: finished runs are skipped, so resubmitting resumes.\n{level_doc}{} sweep {} --out {} --shard \"$SLURM_ARRAY_TASK_ID/{n}\"{level_arg} --jobs \"${{SLURM_CPUS_PER_TASK:-1}}\" --max-runs {max_runs} --json\n",
        header(&format!("droplet-{}", job.name), &format!("#SBATCH --array=0-{}\n#SBATCH --cpus-per-task={}\n", job.shards - 1, job.cpus)),
        shell_word(&job.exe.to_string_lossy()),
        shell_word(&job.spec.to_string_lossy()),
        shell_word(&job.out.to_string_lossy()),
        n = job.shards,
        max_runs = job.max_runs,
    );
    let merge_script = format!(
        "{}{} merge {} --json\n",
        header(
            &format!("droplet-{}-merge", job.name),
            "#SBATCH --cpus-per-task=1\n"
        ),
        shell_word(&job.exe.to_string_lossy()),
        shell_word(&job.out.to_string_lossy())
    );
    let sweep_path = dir.join("sweep.sbatch");
    let merge_path = dir.join("merge.sbatch");
    crate::store::atomic::write_atomic(&sweep_path, sweep_script.as_bytes())?;
    crate::store::atomic::write_atomic(&merge_path, merge_script.as_bytes())?;
    Ok([sweep_path, merge_path])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(dir: &std::path::Path) -> SlurmJob {
        SlurmJob {
            name: "smoke".into(),
            spec: dir.join("spec.yaml"),
            out: dir.join("out"),
            exe: PathBuf::from("/bin/echo"),
            shards: 2,
            cpus: 1,
            partition: None,
            time: "01:00:00".into(),
            mem: "2G".into(),
            max_runs: 100,
            levels: None,
        }
    }

    #[test]
    fn a_path_is_one_word_that_the_shell_never_expands() {
        let dir = tempfile::tempdir().unwrap();
        let hostile = "s $(touch PWNED) `touch PWNED` $HOME 'q' \"d\".yaml";
        let j = SlurmJob {
            spec: dir.path().join(hostile),
            ..job(dir.path())
        };
        let [sweep, merge] = write_scripts(&j).unwrap();
        // The command line, run by bash with /bin/echo as the binary, prints the path as it is.
        let script = std::fs::read_to_string(&sweep).unwrap();
        let line = script.lines().find(|l| l.contains(" sweep ")).unwrap();
        let out = std::process::Command::new("bash")
            .args(["-c", &line.replace("$SLURM_ARRAY_TASK_ID", "0")])
            .current_dir(dir.path())
            .output()
            .unwrap();
        let printed = String::from_utf8(out.stdout).unwrap();
        assert!(
            printed.contains(&j.spec.to_string_lossy().into_owned()),
            "{printed}"
        );
        assert!(!dir.path().join("PWNED").exists());
        assert!(std::fs::read_to_string(merge).unwrap().contains(" merge '"));
    }

    #[test]
    fn control_characters_blanks_and_quotes_in_a_directive_are_refused_before_writing() {
        let dir = tempfile::tempdir().unwrap();
        let cases = [
            SlurmJob {
                partition: Some("p\necho INJECTED".into()),
                ..job(dir.path())
            },
            SlurmJob {
                time: "1:00 --wrap=x".into(),
                ..job(dir.path())
            },
            SlurmJob {
                mem: "2G\"".into(),
                ..job(dir.path())
            },
            SlurmJob {
                spec: dir.path().join("a\nb.yaml"),
                ..job(dir.path())
            },
            SlurmJob {
                out: dir.path().join("my out"),
                ..job(dir.path())
            },
        ];
        for j in cases {
            let e = write_scripts(&j).unwrap_err().to_string();
            assert!(e.contains("cannot be written into a Slurm script"), "{e}");
            assert!(!j.out.join("slurm").exists(), "{e}");
        }
    }
}
