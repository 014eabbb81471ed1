//! Typed errors of the sweep crate.
use std::path::PathBuf;
use thiserror::Error;

/// A problem with a YAML spec: where it is, what was found, what is allowed.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{file}:{line}: `{path}` = {value}: {allowed}", line = line.map(|l| l.to_string()).unwrap_or_else(|| "?".into()))]
pub struct SpecError {
    pub file: String,
    /// Dotted key path, e.g. `grid.eta_t.step`.
    pub path: String,
    /// 1-based line of the key, when it can be located.
    pub line: Option<usize>,
    pub value: String,
    pub allowed: String,
}

/// Everything that can go wrong in a sweep.
#[derive(Debug, Error)]
pub enum SweepError {
    #[error(transparent)]
    Spec(#[from] SpecError),
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{0} is in use by another droplet process (lock held on {1}); wait for it or use another --out")]
    Locked(PathBuf, PathBuf),
    /// The output directory cannot be created or written (a bad `--out` or `output:`).
    #[error("output directory {path}: {source}; choose a writable directory with --out")]
    Output {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A spec asks for more runs than allowed.
    #[error("the spec asks for {runs} runs ({points} points x initial conditions), more than the limit of {limit}; coarsen the grid, or raise the limit deliberately with --max-runs {runs}")]
    TooLarge { runs: u64, points: u64, limit: u64 },
    #[error(transparent)]
    Solver(#[from] droplet_solver::error::SolverError),
    #[error("parquet: {0}")]
    Parquet(#[from] polars::error::PolarsError),
    #[error("plot: {0}")]
    Plot(String),
    #[error("{0}")]
    Invalid(String),
    #[error("{} of {} runs are missing or unreadable in {} (e.g. {}); no tables written; re-run the sweep (or the shard) to recompute them", .0.runs_missing, .0.runs_total, .0.output.display(), .0.missing_examples.first().map(String::as_str).unwrap_or("-"))]
    Incomplete(Box<crate::merge_report::MergeReport>),
    /// A finished map (its tables are there) whose stored runs no longer give every point: a
    /// picture from them would replace the map's own with one of missing points.
    #[error("{missing} of {points} points of {} lack a usable stored run (unfinished, unreadable, or of an older numerics), though its tables hold a finished map; nothing was drawn, so its pictures stay as they are (`droplet status {0}` counts the runs; `droplet sweep` on it recomputes them)", .dir.display())]
    StaleRuns {
        dir: PathBuf,
        missing: usize,
        points: usize,
    },
    /// A shard of a refined sweep's level started before the levels below it were finished.
    #[error("level {level} cannot start in {}: level {earlier} has {missing} of its runs missing or unreadable, and level {level}'s points follow from them; run level {earlier}'s shards first (--level {earlier})", .output.display())]
    LevelNotReady {
        level: u32,
        earlier: u32,
        missing: usize,
        output: PathBuf,
    },
}

impl SweepError {
    /// Wraps an I/O error with the path it concerns.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }

    /// True for errors in what the user gave (exit code 2), false for failures while working.
    pub fn is_user_error(&self) -> bool {
        matches!(
            self,
            Self::Spec(_)
                | Self::Locked(..)
                | Self::Invalid(_)
                | Self::Output { .. }
                | Self::TooLarge { .. }
        )
    }
}
