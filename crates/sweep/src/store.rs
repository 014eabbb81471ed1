//! The run store of an output directory: one JSON file per finished run under `runs/`,
//! written atomically (temporary file, fsync, rename) the moment the run finishes, and an
//! exclusive lock so that two sweeps cannot write one directory at once.
use crate::error::SweepError;
use droplet_solver::{InitialCondition, ModelParams, RunOutcome, SolverSettings};
use fs2::FileExt;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fs::{self, File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A finished run as persisted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    pub key: String,
    pub params: ModelParams,
    pub ic: InitialCondition,
    pub settings: SolverSettings,
    pub solver_version: String,
    pub outcome: RunOutcome,
}

/// An output directory's run store.
pub struct Store {
    dir: PathBuf,
    runs: PathBuf,
    _lock: Option<File>,
}

impl Store {
    /// Opens `dir` for writing, creating it, and takes its lock (refused while another
    /// process holds it; the OS releases it when that process dies, even by SIGKILL).
    pub fn open_locked(dir: &Path) -> Result<Self, SweepError> {
        Self::open_locked_as(dir, ".lock")
    }

    /// As [`Self::open_locked`] with the lock file `lock_name`: each shard of a sharded sweep
    /// has its own, so shards never serialise each other (their runs are separate files).
    pub fn open_locked_as(dir: &Path, lock_name: &str) -> Result<Self, SweepError> {
        let runs = dir.join("runs");
        fs::create_dir_all(&runs).map_err(|e| SweepError::io(&runs, e))?;
        let lock_path = dir.join(lock_name);
        let lock = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .map_err(|e| SweepError::io(&lock_path, e))?;
        if lock.try_lock_exclusive().is_err() {
            return Err(SweepError::Locked(dir.to_path_buf(), lock_path));
        }
        let store = Self {
            dir: dir.to_path_buf(),
            runs,
            _lock: Some(lock),
        };
        store.remove_temporaries();
        Ok(store)
    }

    /// Opens `dir` read-only (no lock; may see a sweep in progress).
    pub fn open_read(dir: &Path) -> Result<Self, SweepError> {
        let runs = dir.join("runs");
        if !runs.is_dir() {
            return Err(SweepError::Invalid(format!(
                "{} holds no sweep (no runs/ directory); run `droplet sweep SPEC --out {}` first",
                dir.display(),
                dir.display()
            )));
        }
        Ok(Self {
            dir: dir.to_path_buf(),
            runs,
            _lock: None,
        })
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    fn path_of(&self, key: &str) -> PathBuf {
        self.runs.join(format!("{key}.json"))
    }

    /// Leftovers of writes interrupted by a crash. A temporary lives for milliseconds (write,
    /// fsync, rename), so only those older than a minute are removed: a concurrent shard's
    /// write in progress is never touched.
    fn remove_temporaries(&self) {
        let stale = |e: &fs::DirEntry| {
            e.metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age > std::time::Duration::from_secs(60))
        };
        if let Ok(entries) = fs::read_dir(&self.runs) {
            for e in entries.flatten() {
                if e.file_name().to_string_lossy().ends_with(".tmp") && stale(&e) {
                    let _ = fs::remove_file(e.path());
                }
            }
        }
    }

    /// True when the run `key` is stored.
    pub fn has(&self, key: &str) -> bool {
        self.path_of(key).is_file()
    }

    /// Persists a finished run atomically.
    pub fn save(&self, record: &RunRecord) -> Result<(), SweepError> {
        let json = serde_json::to_vec(record).expect("records serialise");
        write_atomic(&self.path_of(&record.key), &json).map(|_| ())
    }

    /// Loads one run, if stored and readable.
    pub fn load(&self, key: &str) -> Option<RunRecord> {
        let bytes = fs::read(self.path_of(key)).ok()?;
        serde_json::from_slice(&bytes).ok()
    }

    /// Loads the runs with the given keys (missing ones are absent from the map).
    pub fn load_many<'a>(
        &self,
        keys: impl IntoIterator<Item = &'a str>,
    ) -> HashMap<String, RunRecord> {
        keys.into_iter()
            .filter_map(|k| self.load(k).map(|r| (k.to_string(), r)))
            .collect()
    }

    /// Writes `bytes` to `name` in the output directory atomically.
    pub fn write_file(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, SweepError> {
        write_atomic(&self.dir.join(name), bytes)
    }
}

/// Writes `bytes` to `path` via a temporary file (`<stem>.<pid>.tmp`), fsync and a rename, so a
/// crash leaves either the old file or the new one, never a partial one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<PathBuf, SweepError> {
    let tmp = path.with_extension(format!("{}.tmp", std::process::id()));
    let write = || -> std::io::Result<()> {
        let mut f = File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    };
    write().map_err(|e| SweepError::io(path, e))?;
    Ok(path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lock_is_exclusive_and_records_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open_locked(dir.path()).unwrap();
        assert!(matches!(
            Store::open_locked(dir.path()),
            Err(SweepError::Locked(..))
        ));
        let rec = RunRecord {
            key: "abc".into(),
            params: ModelParams::default(),
            ic: InitialCondition::parse("i").unwrap(),
            settings: SolverSettings::default(),
            solver_version: "x".into(),
            outcome: RunOutcome {
                status: droplet_solver::RunStatus::Steady,
                class: Some(droplet_solver::StateClass::MD),
                state: Default::default(),
                v: 0.5,
                s: 0.2,
                t_end: 10.0,
                t_steady: Some(10.0),
                steps: 500,
                rejected: 0,
                max_step_error: None,
                wall_s: 0.1,
                series: vec![],
            },
        };
        store.save(&rec).unwrap();
        assert!(store.has("abc"));
        // A fresh temporary (another process writing) survives a second open; no stale ones.
        let fresh = dir.path().join("runs").join("x.1.tmp");
        std::fs::write(&fresh, b"{").unwrap();
        let other = Store::open_locked_as(dir.path(), ".lock-shard-0-of-2").unwrap();
        assert!(fresh.exists());
        drop(other);
        assert_eq!(store.load("abc").unwrap(), rec);
        drop(store);
        assert!(Store::open_locked(dir.path()).is_ok());
    }
}
