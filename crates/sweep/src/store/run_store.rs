//! The run store of an output directory: one JSON file per finished run under `runs/`,
//! written atomically (temporary file, fsync, rename) the moment the run finishes, and an
//! exclusive lock so that two sweeps cannot write one directory at once.
use crate::error::SweepError;
use crate::merge_report::MergeReport;
use crate::spec::axes::{ETA_T, KAPPA2};
use crate::store::atomic::{create_output_dir, write_atomic};
use crate::store::plan::Plan;
pub use crate::store::record_file::RunRecord;
use crate::store::record_file::{digest_of, seal, unseal};
use fs2::FileExt;
use serde::Serialize;
use std::collections::HashMap;
use std::fs::{self, File, OpenOptions};
use std::path::{Path, PathBuf};

/// What the store holds for one key.
#[derive(Debug, Clone, PartialEq)]
pub enum Stored {
    /// No file.
    Missing,
    /// A record that parses and whose key matches its content.
    Valid(Box<RunRecord>),
    /// A file that cannot be read or parsed, or whose content does not hash to its key.
    Corrupt(String),
}

/// A stored run that could not be used, and where its file went.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorruptRun {
    pub key: String,
    pub reason: String,
    /// Where the file was moved (`DIR/corrupt/`); it is never deleted.
    pub moved_to: PathBuf,
}

/// An output directory's run store.
pub struct Store {
    dir: PathBuf,
    runs: PathBuf,
    _locks: Vec<File>,
    /// Only sealed records are valid: true once the store is opened to be written (its
    /// records upgraded); a read-only view also accepts records not yet sealed.
    sealed_only: bool,
    /// Records of earlier releases upgraded when the store was opened ([`Self::upgrade`]).
    upgraded: usize,
}

/// Name of the directory-wide lock file.
const LOCK: &str = ".lock";

/// The runs stored within a recent window ([`Store::stored_within`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Recent {
    pub runs: usize,
    /// Age of the oldest of them (zero when there are none).
    pub oldest: std::time::Duration,
    /// Age of the newest of them (`None` when there are none).
    pub newest: Option<std::time::Duration>,
}

impl Store {
    /// Opens `dir` for a whole sweep, creating it, and takes its lock exclusively: refused
    /// while another sweep or any shard works on it (the OS releases a lock when its process
    /// dies, even by SIGKILL).
    pub fn open_locked(dir: &Path) -> Result<Self, SweepError> {
        Self::create(dir)?.lock_exclusively()
    }

    /// This store with the directory lock taken exclusively (refused while held).
    fn lock_exclusively(self) -> Result<Self, SweepError> {
        let lock = self.lock_file(LOCK)?;
        if lock.try_lock_exclusive().is_err() {
            return Err(SweepError::Locked(self.dir.clone(), self.dir.join(LOCK)));
        }
        self.with_lock(lock)
    }

    /// Opens `dir` for one shard: the directory lock shared (shards run side by side, a whole
    /// sweep on the same directory is refused both ways) and the shard's own lock `lock_name`
    /// exclusively (the same shard twice is refused). Shards write separate run files.
    pub fn open_shard(dir: &Path, lock_name: &str) -> Result<Self, SweepError> {
        let store = Self::create(dir)?;
        let shared = store.lock_file(LOCK)?;
        if FileExt::try_lock_shared(&shared).is_err() {
            return Err(SweepError::Locked(dir.to_path_buf(), dir.join(LOCK)));
        }
        let own = store.lock_file(lock_name)?;
        if own.try_lock_exclusive().is_err() {
            return Err(SweepError::Locked(dir.to_path_buf(), dir.join(lock_name)));
        }
        let store = store.with_lock(shared)?;
        Ok(Self {
            _locks: store._locks.into_iter().chain([own]).collect(),
            ..store
        })
    }

    fn create(dir: &Path) -> Result<Self, SweepError> {
        let runs = dir.join("runs");
        create_output_dir(&runs)?;
        Ok(Self {
            dir: dir.to_path_buf(),
            runs,
            _locks: Vec::new(),
            sealed_only: false,
            upgraded: 0,
        })
    }

    fn lock_file(&self, name: &str) -> Result<File, SweepError> {
        let path = self.dir.join(name);
        OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(|e| SweepError::Output { path, source: e })
    }

    fn with_lock(mut self, lock: File) -> Result<Self, SweepError> {
        self._locks.push(lock);
        self.remove_temporaries();
        self.upgraded = self.upgrade()?;
        self.sealed_only = true;
        Ok(self)
    }

    /// How many stored records of earlier releases were upgraded (sealed, or re-keyed) when
    /// this store was opened to be written ([`Self::upgrade`]).
    pub fn upgraded(&self) -> usize {
        self.upgraded
    }

    /// Opens an existing sweep directory while nothing else works on it, its lock taken
    /// exclusively: what is read is one consistent snapshot, and what is written (pictures)
    /// cannot race a sweep's or a merge's own writes. Refused while a sweep or shard runs.
    pub fn open_idle(dir: &Path) -> Result<Self, SweepError> {
        Self::open_read(dir)?.lock_exclusively()
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
            _locks: Vec::new(),
            sealed_only: false,
            upgraded: 0,
        })
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    fn path_of(&self, key: &str) -> PathBuf {
        self.runs.join(format!("{key}.json"))
    }

    /// Leftovers of writes interrupted by a crash, in `runs/` and in the directory itself
    /// (tables and pictures): names ending in `.tmp`. A temporary lives for milliseconds to
    /// seconds (write, fsync, rename), so only those older than a minute are removed: a
    /// concurrent shard's write in progress is never touched.
    fn remove_temporaries(&self) {
        let stale = |e: &fs::DirEntry| {
            e.metadata()
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok())
                .is_some_and(|age| age > std::time::Duration::from_secs(60))
        };
        for dir in [&self.runs, &self.dir] {
            if let Ok(entries) = fs::read_dir(dir) {
                for e in entries.flatten() {
                    if e.file_name().to_string_lossy().ends_with(".tmp") && stale(&e) {
                        let _ = fs::remove_file(e.path());
                    }
                }
            }
        }
    }

    /// What is stored under `key`: a valid record only if the file parses, names `key`, and
    /// its parameters, initial condition, settings and solver version hash to `key`.
    pub fn check(&self, key: &str) -> Stored {
        let path = self.path_of(key);
        let bytes = match fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Stored::Missing,
            Err(e) => return Stored::Corrupt(format!("cannot be read: {e}")),
        };
        let (rec, digest) = match unseal(&bytes) {
            Ok(u) => (u.record, u.digest),
            Err(e) => {
                return Stored::Corrupt(format!("not a run record ({} bytes): {e}", bytes.len()))
            }
        };
        match digest {
            Some(d) if d == digest_of(&rec.outcome) => {}
            Some(_) => {
                return Stored::Corrupt(
                    "its outcome does not match its digest (edited after the run wrote it)".into(),
                )
            }
            None if !self.sealed_only => {}
            None => {
                return Stored::Corrupt(
                    "it has no digest of its outcome (edited, or written before records were sealed and not yet upgraded)".into(),
                )
            }
        }
        let content_key = crate::store::plan::run_key(&rec.params, &rec.ic, &rec.settings);
        if rec.key != key
            || rec.solver_version
                != droplet_solver::solver_version(rec.settings.model, rec.params.modes)
            || content_key != key
        {
            return Stored::Corrupt(format!(
                "its content does not match its key (names key {}, solver {}, content hashes to {content_key})",
                rec.key, rec.solver_version
            ));
        }
        Stored::Valid(Box::new(rec))
    }

    /// Upgrades the records of earlier releases in place; returns how many it changed:
    /// - a record without the digest of its outcome (written before records were sealed) is
    ///   sealed as it is (an edit made before that cannot be told; every later one can);
    /// - a record whose file is named by its settings as they were written
    ///   ([`crate::store::plan::written_key`]) while its key is now another
    ///   ([`crate::store::plan::run_key`]: settings it does not read left out, such as the
    ///   `h0` that a spec-parsing bug once set to `n` in every PDE run). Its result is
    ///   the one its new key asks for, so it is re-keyed, never recomputed; its record keeps
    ///   the settings it read;
    /// - a record that holds the model's shape modes among its settings (written before they
    ///   were model parameters) is rewritten with them among its parameters (its key, which
    ///   hashes them where they were, and its outcome unchanged).
    ///
    /// Called when a store is opened to be written, before any run is checked.
    fn upgrade(&self) -> Result<usize, SweepError> {
        let Ok(entries) = fs::read_dir(&self.runs) else {
            return Ok(0);
        };
        let mut renamed = 0;
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            let Some(stem) = name.strip_suffix(".json") else {
                continue;
            };
            let Ok(bytes) = fs::read(e.path()) else {
                continue;
            };
            let Ok(u) = unseal(&bytes) else {
                continue;
            };
            let (mut rec, digest, modes_in_settings) = (u.record, u.digest, u.modes_in_settings);
            let current = droplet_solver::solver_version(rec.settings.model, rec.params.modes);
            let key = crate::store::plan::run_key(&rec.params, &rec.ic, &rec.settings);
            let written = crate::store::plan::written_key(&rec.params, &rec.ic, &rec.settings);
            if rec.key != stem || rec.solver_version != current || written != stem {
                // Of another numerics, or corrupt: `check` decides.
                continue;
            }
            if key == stem {
                let sealed_intact = digest.as_ref() == Some(&digest_of(&rec.outcome));
                if digest.is_none() || (modes_in_settings && sealed_intact) {
                    // Written before records were sealed, or before the shape modes were
                    // model parameters: written as it is now.
                    self.save(&rec)?;
                    renamed += 1;
                }
                continue;
            }
            if digest.is_some_and(|d| d != digest_of(&rec.outcome)) {
                continue;
            }
            rec.key = key;
            rec.settings = rec.settings.honoured(rec.params.modes);
            if !self.path_of(&rec.key).exists() {
                self.save(&rec)?;
            }
            match fs::remove_file(e.path()) {
                Err(err) if err.kind() != std::io::ErrorKind::NotFound => {
                    return Err(SweepError::io(e.path(), err))
                }
                _ => renamed += 1,
            }
        }
        Ok(renamed)
    }

    /// Moves the file of `key` to `DIR/corrupt/<key>.<unix seconds>.json` (never deleted, so
    /// that nothing is lost), so the run can be recomputed.
    pub fn quarantine(&self, key: &str, reason: &str) -> Result<CorruptRun, SweepError> {
        let aside = self.dir.join("corrupt");
        fs::create_dir_all(&aside).map_err(|e| SweepError::io(&aside, e))?;
        let stamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        let to = aside.join(format!("{key}.{stamp}.json"));
        let from = self.path_of(key);
        fs::rename(&from, &to).map_err(|e| SweepError::io(&from, e))?;
        Ok(CorruptRun {
            key: key.to_string(),
            reason: reason.to_string(),
            moved_to: to,
        })
    }

    /// The runs of `plan` that have no valid record here (absent, or unreadable).
    pub fn report_missing(&self, plan: &Plan) -> MergeReport {
        let (mut missing, mut unreadable, mut examples) = (0, 0, Vec::new());
        for t in plan.tasks() {
            let why = match self.check(&t.key) {
                Stored::Valid(_) => continue,
                Stored::Missing => String::new(),
                Stored::Corrupt(reason) => {
                    unreadable += 1;
                    format!(": runs/{}.json unreadable ({reason})", t.key)
                }
            };
            missing += 1;
            if examples.len() < 20 {
                // The point by its own axes (any swept parameter), then the paper's plane
                // where no axis gives it.
                let plane = &plan.plane;
                let at = plan.points[t.point];
                let axes = [Some(plane.x), plane.y, plane.z];
                let mut parts: Vec<String> = axes
                    .iter()
                    .zip(at)
                    .filter_map(|(p, x)| p.map(|p| format!("{} = {x}", p.name())))
                    .collect();
                for (name, value) in [(ETA_T, t.params.eta_t), (KAPPA2, t.params.kappa2)] {
                    if !axes.iter().flatten().any(|p| p.name() == name) {
                        parts.push(format!("{name} = {value}"));
                    }
                }
                examples.push(format!("{}, ic = {}{why}", parts.join(", "), t.ic.name));
            }
        }
        MergeReport {
            output: self.dir.clone(),
            runs_total: plan.len(),
            runs_missing: missing,
            runs_unreadable: unreadable,
            missing_examples: examples,
            tables: Vec::new(),
        }
    }

    /// Persists a finished run atomically, sealed with the digest of its outcome.
    pub fn save(&self, record: &RunRecord) -> Result<(), SweepError> {
        write_atomic(&self.path_of(&record.key), &seal(record)).map(|_| ())
    }

    /// True when a valid run `key` is stored.
    pub fn has(&self, key: &str) -> bool {
        matches!(self.check(key), Stored::Valid(_))
    }

    /// Loads one run, if stored and valid (see [`Self::check`]).
    pub fn load(&self, key: &str) -> Option<RunRecord> {
        match self.check(key) {
            Stored::Valid(r) => Some(*r),
            _ => None,
        }
    }

    /// Loads the valid runs with the given keys (missing or corrupt ones are absent).
    pub fn load_many<K: AsRef<str>>(
        &self,
        keys: impl IntoIterator<Item = K>,
    ) -> HashMap<String, RunRecord> {
        self.load_counting(keys).0
    }

    /// How many of the runs `keys` were stored within the last `window` (by their files'
    /// modification times), and the age of the oldest of them: the pace of a sweep at work,
    /// whichever processes run it.
    pub fn stored_within<K: AsRef<str>>(
        &self,
        keys: impl IntoIterator<Item = K>,
        window: std::time::Duration,
    ) -> Recent {
        let mut recent = Recent::default();
        for k in keys {
            let age = fs::metadata(self.path_of(k.as_ref()))
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.elapsed().ok());
            if let Some(age) = age.filter(|age| *age <= window) {
                recent.runs += 1;
                recent.oldest = recent.oldest.max(age);
                recent.newest = Some(recent.newest.map_or(age, |n| n.min(age)));
            }
        }
        recent
    }

    /// As [`Self::load_many`], also counting the keys whose file is corrupt.
    pub fn load_counting<K: AsRef<str>>(
        &self,
        keys: impl IntoIterator<Item = K>,
    ) -> (HashMap<String, RunRecord>, usize) {
        let mut records = HashMap::new();
        let mut corrupt = 0;
        for k in keys {
            match self.check(k.as_ref()) {
                Stored::Valid(r) => {
                    records.insert(k.as_ref().to_string(), *r);
                }
                Stored::Corrupt(_) => corrupt += 1,
                Stored::Missing => {}
            }
        }
        (records, corrupt)
    }

    /// Writes `bytes` to `name` in the output directory atomically.
    pub fn write_file(&self, name: &str, bytes: &[u8]) -> Result<PathBuf, SweepError> {
        write_atomic(&self.dir.join(name), bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use droplet_solver::{
        contract::outcome::RunOutcome, contract::settings::SolverSettings,
        model::initial::InitialCondition, model::params::ModelParams,
    };

    fn record() -> RunRecord {
        let (params, ic, settings) = (
            ModelParams::default(),
            InitialCondition::parse("i").unwrap(),
            SolverSettings::default(),
        );
        RunRecord {
            key: crate::store::plan::run_key(&params, &ic, &settings),
            params,
            ic,
            settings,
            solver_version: droplet_solver::SOLVER_VERSION.into(),
            outcome: RunOutcome {
                status: droplet_solver::contract::outcome::RunStatus::Steady,
                class: Some(droplet_solver::model::classify::StateClass::MD),
                state: Default::default(),
                v: 0.5,
                s: 0.2,
                t_end: 10.0,
                t_steady: Some(10.0),
                steps: 500,
                rejected: 0,
                max_step_error: None,
                wall_s: 0.1,
                ended_by: None,
                diagnosis: None,
                t_leapt: 0.0,
                t_projected: 0.0,
                unsettled: None,
                heading: None,
                higher_modes: vec![],
                series: vec![],
                higher_series: vec![],
                profile: Default::default(),
            },
        }
    }

    #[test]
    fn lock_is_exclusive_and_records_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open_locked(dir.path()).unwrap();
        assert!(matches!(
            Store::open_locked(dir.path()),
            Err(SweepError::Locked(..))
        ));
        // A shard is refused while the whole sweep holds the directory.
        assert!(matches!(
            Store::open_shard(dir.path(), ".lock-shard-0-of-2"),
            Err(SweepError::Locked(..))
        ));
        let rec = record();
        let key = rec.key.clone();
        store.save(&rec).unwrap();
        assert!(store.has(&key));
        assert_eq!(store.load(&key).unwrap(), rec);
        drop(store);
        // A fresh temporary (another process writing) survives a second open; no stale ones.
        let fresh = dir.path().join("runs").join("x.1.tmp");
        std::fs::write(&fresh, b"{").unwrap();
        let other = Store::open_shard(dir.path(), ".lock-shard-0-of-2").unwrap();
        assert!(fresh.exists());
        // Shards run side by side, but not the same shard twice, and no whole sweep meanwhile.
        let second = Store::open_shard(dir.path(), ".lock-shard-1-of-2").unwrap();
        assert!(matches!(
            Store::open_shard(dir.path(), ".lock-shard-0-of-2"),
            Err(SweepError::Locked(..))
        ));
        assert!(matches!(
            Store::open_locked(dir.path()),
            Err(SweepError::Locked(..))
        ));
        drop((other, second));
        assert!(Store::open_locked(dir.path()).is_ok());
    }

    #[test]
    fn corrupt_runs_are_told_apart_and_moved_aside() {
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open_locked(dir.path()).unwrap();
        let rec = record();
        let key = rec.key.clone();
        assert_eq!(store.check(&key), Stored::Missing);
        let file = dir.path().join("runs").join(format!("{key}.json"));
        for bad in [
            Vec::new(),
            b"{\"key\":".to_vec(),
            b"garbage \xff".to_vec(),
            // Valid JSON of another run under this key.
            serde_json::to_vec(&RunRecord {
                params: ModelParams::at(0.08, 0.12),
                ..rec.clone()
            })
            .unwrap(),
        ] {
            std::fs::write(&file, &bad).unwrap();
            let Stored::Corrupt(reason) = store.check(&key) else {
                panic!("{bad:?} accepted")
            };
            assert!(store.load(&key).is_none());
            let moved = store.quarantine(&key, &reason).unwrap();
            assert!(!file.exists());
            assert_eq!(std::fs::read(&moved.moved_to).unwrap(), bad);
            std::fs::remove_file(&moved.moved_to).unwrap();
        }
        store.save(&rec).unwrap();
        assert_eq!(store.check(&key), Stored::Valid(Box::new(rec)));
    }

    #[test]
    fn a_run_keyed_by_a_setting_it_does_not_read_is_renamed_not_recomputed() {
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open_locked(dir.path()).unwrap();
        let mut old = record();
        // As the spec bug wrote it: h0 = n in a PDE run, keyed with it.
        old.settings.h0 = 192.0;
        old.key = crate::store::plan::written_key(&old.params, &old.ic, &old.settings);
        // Written unsealed, as releases before records were sealed wrote them.
        let file = dir.path().join("runs").join(format!("{}.json", old.key));
        std::fs::write(&file, serde_json::to_vec(&old).unwrap()).unwrap();
        let new_key = record().key;
        assert_ne!(old.key, new_key);
        assert!(matches!(store.check(&old.key), Stored::Corrupt(_)));
        assert_eq!(store.check(&new_key), Stored::Missing);
        drop(store);
        let store = Store::open_locked(dir.path()).unwrap();
        assert_eq!(store.upgraded(), 1);
        assert_eq!(store.check(&old.key), Stored::Missing);
        // The same outcome under the new key, with the settings the run read.
        let Stored::Valid(got) = store.check(&new_key) else {
            panic!("not re-keyed")
        };
        assert_eq!(*got, record());
        // Nothing more to rename; a corrupt file is left for `check`.
        std::fs::write(dir.path().join("runs/abc.json"), b"{").unwrap();
        assert_eq!(store.upgrade().unwrap(), 0);
        assert!(dir.path().join("runs/abc.json").exists());
    }

    #[test]
    fn an_edited_outcome_is_corrupt_and_an_unsealed_record_is_sealed_at_the_next_open() {
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open_locked(dir.path()).unwrap();
        let rec = record();
        store.save(&rec).unwrap();
        let file = dir.path().join("runs").join(format!("{}.json", rec.key));
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(text.contains("\"digest\":"));
        // A class and a status changed by hand.
        let edited = text
            .replace("\"class\":\"MD\"", "\"class\":\"IC\"")
            .replace("\"status\":\"steady\"", "\"status\":\"t_max\"");
        assert_ne!(edited, text);
        std::fs::write(&file, &edited).unwrap();
        let Stored::Corrupt(reason) = store.check(&rec.key) else {
            panic!("an edited outcome was accepted")
        };
        assert!(reason.contains("digest"), "{reason}");
        // Its digest removed too: refused by a store opened to be written.
        std::fs::write(
            &file,
            serde_json::to_vec(&RunRecord { ..rec.clone() }).unwrap(),
        )
        .unwrap();
        assert!(matches!(store.check(&rec.key), Stored::Corrupt(_)));
        // A read-only view accepts it; the next open to write seals it.
        assert!(matches!(
            Store::open_read(dir.path()).unwrap().check(&rec.key),
            Stored::Valid(_)
        ));
        drop(store);
        let store = Store::open_locked(dir.path()).unwrap();
        assert_eq!(store.upgraded(), 1);
        assert_eq!(store.check(&rec.key), Stored::Valid(Box::new(rec)));
    }

    #[test]
    fn stale_temporaries_of_tables_and_pictures_are_removed_at_the_next_open() {
        let dir = tempfile::tempdir().unwrap();
        drop(Store::open_locked(dir.path()).unwrap());
        let old = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
        let stale: Vec<PathBuf> = ["runs.4242.tmp", "phase_map.4242.tmp", "runs/k.4242.tmp"]
            .iter()
            .map(|n| dir.path().join(n))
            .collect();
        for p in &stale {
            let f = File::create(p).unwrap();
            f.set_modified(old).unwrap();
        }
        drop(Store::open_locked(dir.path()).unwrap());
        assert!(stale.iter().all(|p| !p.exists()));
    }

    #[test]
    fn a_record_with_the_shape_modes_among_its_settings_is_read_and_rewritten_under_its_key() {
        // As records were written before the shape modes were model parameters: `modes` and
        // `eta_k_exponent` after the settings, the key hashing them there.
        let dir = tempfile::tempdir().unwrap();
        let mut rec = record();
        rec.params = ModelParams {
            eta_k_exponent: -1.0,
            ..rec.params.with_modes(3)
        };
        rec.key = crate::store::plan::run_key(&rec.params, &rec.ic, &rec.settings);
        rec.solver_version =
            droplet_solver::solver_version(rec.settings.model, rec.params.modes).into();
        assert_ne!(rec.key, record().key);
        let legacy = |rec: &RunRecord| {
            let mut v: serde_json::Value = serde_json::from_slice(&seal(rec)).unwrap();
            let params = v["params"].as_object_mut().unwrap();
            let (k, p) = (params.remove("modes"), params.remove("eta_k_exponent"));
            let settings = v["settings"].as_object_mut().unwrap();
            settings.insert("modes".into(), k.unwrap());
            settings.insert("eta_k_exponent".into(), p.unwrap());
            serde_json::to_vec(&v).unwrap()
        };
        let store = Store::open_locked(dir.path()).unwrap();
        let file = store.path_of(&rec.key);
        std::fs::write(&file, legacy(&rec)).unwrap();
        assert_eq!(store.check(&rec.key), Stored::Valid(Box::new(rec.clone())));
        // One with an edited outcome stays corrupt, and is not rewritten.
        let mut edited = rec.clone();
        edited.params.kappa2 = 0.113;
        edited.key = crate::store::plan::run_key(&edited.params, &edited.ic, &edited.settings);
        let mut bytes: serde_json::Value = serde_json::from_slice(&legacy(&edited)).unwrap();
        bytes["outcome"]["v"] = 0.6.into();
        let edited_file = store.path_of(&edited.key);
        std::fs::write(&edited_file, serde_json::to_vec(&bytes).unwrap()).unwrap();
        assert!(matches!(store.check(&edited.key), Stored::Corrupt(_)));
        drop(store);
        let store = Store::open_locked(dir.path()).unwrap();
        assert_eq!(store.upgraded(), 1);
        let written: serde_json::Value =
            serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
        assert_eq!(written["params"]["modes"], 3);
        assert!(written["settings"].get("modes").is_none());
        assert_eq!(store.check(&rec.key), Stored::Valid(Box::new(rec)));
        assert!(matches!(store.check(&edited.key), Stored::Corrupt(_)));
    }
}
