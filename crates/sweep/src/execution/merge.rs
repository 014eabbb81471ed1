//! The final tables of a sharded sweep, built only when every run is present and valid.
use crate::error::SweepError;
use crate::map::phase_map::PhaseMap;
use crate::merge_report::MergeReport;
use crate::store::run_store::Store;
use crate::tables::sweep_tables::write_tables;
use std::path::Path;

/// Builds the final tables of the sweep in `dir` from all its stored runs (e.g. after the
/// shards of an array job). With runs missing or unreadable, writes nothing and fails with a
/// report. Idempotent: the tables depend only on the stored runs. `draw` adds the pictures.
/// Refused while a sweep or a shard works in `dir` (its lock is taken exclusively): a merge
/// then would find runs missing that are only not finished yet.
pub fn merge(dir: &Path, draw: bool) -> Result<MergeReport, SweepError> {
    let store = Store::open_idle(dir)?;
    let spec = crate::spec::load_stored(dir)?;
    let plan = crate::map::levels::stored_plan(&spec, &store)?;
    let report = store.report_missing(&plan);
    if report.runs_missing > 0 {
        return Err(SweepError::Incomplete(Box::new(report)));
    }
    let records = store.load_many(plan.tasks().map(|t| t.key));
    if records.len() != plan.len() {
        // A run went bad between the check and the load.
        return Err(SweepError::Incomplete(Box::new(
            store.report_missing(&plan),
        )));
    }
    let map = PhaseMap::new(&plan, &records);
    let mut tables = write_tables(&store, &spec, &plan, &records, &map)?;
    if draw {
        tables.extend(crate::pictures::sweep_pictures::plot_records(
            dir, &spec, &plan, &records, &map,
        )?);
    }
    Ok(MergeReport { tables, ..report })
}
