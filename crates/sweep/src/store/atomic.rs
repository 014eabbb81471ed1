//! Files written so that a crash or a full disk never leaves a partial one: a temporary file
//! in the same directory, fsync, rename; and the creation of user-given output directories.
use crate::error::SweepError;
use std::fs::{self, File};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Creates an output directory given by the user (`--out`, `output:`); failing is bad input
/// (exit code 2), reported with the directory.
pub fn create_output_dir(dir: &Path) -> Result<(), SweepError> {
    fs::create_dir_all(dir).map_err(|e| SweepError::Output {
        path: dir.to_path_buf(),
        source: e,
    })
}

/// Writes `bytes` to `path` via a temporary file (`<stem>.<pid>.tmp`), fsync and a rename, so a
/// crash leaves either the old file or the new one, never a partial one (and a stale
/// temporary that the next sweep on the directory removes). Errors name `path`; a failed
/// write removes its temporary.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<PathBuf, SweepError> {
    let tmp = path.with_extension(format!("{}.tmp", std::process::id()));
    let write = || -> std::io::Result<()> {
        let mut f = File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, path)
    };
    write().map_err(|e| {
        let _ = fs::remove_file(&tmp);
        SweepError::io(path, e)
    })?;
    Ok(path.to_path_buf())
}
