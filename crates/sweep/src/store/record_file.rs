//! A run record as its file holds it: the run, sealed with the digest of its outcome so that
//! an outcome edited by hand (a class, a status) is told from one the sweep wrote; and the
//! records of earlier releases without a digest (`Store::upgrade` seals them).
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
struct Unsealed {
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

/// A record file's record and its digest (`None`: written before records were sealed).
pub(super) fn unseal(bytes: &[u8]) -> Result<(RunRecord, Option<String>), serde_json::Error> {
    serde_json::from_slice::<Unsealed>(bytes).map(|u| (u.record, u.digest))
}
