//! A run record as its file holds it: the run, sealed with the digest of its outcome so that
//! an outcome edited by hand (a class, a status) is told from one the sweep wrote; and the
//! records of earlier releases without a digest (`Store::upgrade` seals them), or with the
//! model's shape modes and friction law among the settings (read with them among the
//! parameters, where they are now; `Store::upgrade` rewrites them so).
use droplet_solver::{
    contract::outcome::RunOutcome, contract::settings::SolverSettings,
    model::initial::InitialCondition, model::params::ModelParams,
};
use serde::{Deserialize, Serialize};

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

/// A record as its file holds it: the run and the digest of its outcome, so that an outcome
/// edited by hand (a class, a status) is told from one the sweep wrote.
#[derive(Serialize)]
struct Sealed<'a> {
    #[serde(flatten)]
    record: &'a RunRecord,
    digest: String,
}

/// A record file read back; `digest` is absent in files written before records were sealed.
#[derive(Deserialize)]
struct File {
    #[serde(flatten)]
    record: RunRecord,
    #[serde(default)]
    digest: Option<String>,
}

/// The digest of a run's outcome: SHA-256 of its JSON, first 16 bytes in hex.
pub(super) fn digest_of(outcome: &RunOutcome) -> String {
    crate::store::plan::short_hash(&serde_json::to_vec(outcome).expect("outcomes serialise"))
}

/// The bytes of `record`'s file: the record and its outcome's digest.
pub(super) fn seal(record: &RunRecord) -> Vec<u8> {
    let sealed = Sealed {
        record,
        digest: digest_of(&record.outcome),
    };
    serde_json::to_vec(&sealed).expect("records serialise")
}

/// What a record file held: the record, its digest (`None`: written before records were
/// sealed) and whether it held the shape modes among the settings (written before they were
/// model parameters).
pub(super) struct Unsealed {
    pub record: RunRecord,
    pub digest: Option<String>,
    pub modes_in_settings: bool,
}

/// A record file's record and its digest, with the shape modes of an earlier record moved
/// from its settings to its parameters (every other field is read as strictly as before).
pub(super) fn unseal(bytes: &[u8]) -> Result<Unsealed, serde_json::Error> {
    let mut value: serde_json::Value = serde_json::from_slice(bytes)?;
    let mut modes_in_settings = false;
    if let Some(settings) = value.get_mut("settings").and_then(|s| s.as_object_mut()) {
        let moved: Vec<(&str, serde_json::Value)> = ModelParams::SHAPE_MODE_FIELDS
            .iter()
            .filter_map(|&k| settings.remove(k).map(|v| (k, v)))
            .collect();
        if let (false, Some(params)) = (
            moved.is_empty(),
            value.get_mut("params").and_then(|p| p.as_object_mut()),
        ) {
            modes_in_settings = true;
            for (k, v) in moved {
                params.insert(k.to_string(), v);
            }
        }
    }
    let file: File = serde_json::from_value(value)?;
    Ok(Unsealed {
        record: file.record,
        digest: file.digest,
        modes_in_settings,
    })
}
