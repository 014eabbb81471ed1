//! The runs of a refined level's midpoints certified without stepping
//! (`refine.certify_midpoints`, [`crate::map::certify`]), before the level's other runs are
//! stepped ([`crate::execution::execute`]).
use crate::error::SweepError;
use crate::store::plan::Plan;
use crate::store::run_store::Store;
use rayon::prelude::*;
use std::collections::{BTreeMap, BTreeSet};

/// What certifying a level's midpoints did.
#[derive(Default)]
pub(super) struct Certified {
    /// The runs saved (plan run indices).
    pub(super) runs: BTreeSet<usize>,
    /// Their certificates' time.
    pub(super) run_time_s: f64,
    /// The candidates left to their runs, by reason ([`crate::map::certify::Refusal`]).
    pub(super) refused: BTreeMap<String, usize>,
}

/// Certifies without runs ([`crate::map::certify`]) the points of `runs` that lie midway
/// between two lower-level points (`between`) and have none of `runs` stored yet, and saves
/// the runs of `runs` among each certified point's.
pub(super) fn certify_pending(
    store: &Store,
    plan: &Plan,
    runs: &[usize],
    between: &crate::map::levels::Between,
    mode: crate::spec::lattice::Certify,
    pool: &rayon::ThreadPool,
) -> Result<Certified, SweepError> {
    let per_point = plan.ic_names.len().max(1);
    let mine: BTreeSet<usize> = runs.iter().copied().collect();
    let points: Vec<(usize, &[[usize; 2]])> = between
        .iter()
        .filter(|(&p, _)| {
            let of_p = (p * per_point..(p + 1) * per_point).filter(|i| mine.contains(i));
            of_p.clone().count() > 0 && of_p.clone().all(|i| !store.has(&plan.task(i).key))
        })
        .map(|(&p, pairs)| (p, pairs.as_slice()))
        .collect();
    let neighbours = store.load_many(points.iter().flat_map(|(_, pairs)| {
        pairs
            .iter()
            .flatten()
            .flat_map(|&q| (q * per_point..(q + 1) * per_point).map(|i| plan.task(i).key))
            .collect::<Vec<_>>()
    }));
    let done = pool.install(|| {
        points
            .par_iter()
            .map(|&(p, pairs)| -> Result<Certified, SweepError> {
                let mut out = Certified::default();
                let certify = |pair| crate::map::certify::certify(plan, p, pair, &neighbours, mode);
                let records = match crate::map::certify::first_candidate(pairs, certify) {
                    Ok(records) => records,
                    Err(why) => {
                        if why != crate::map::certify::Refusal::NotCandidate {
                            out.refused.insert(why.as_str().to_string(), 1);
                        }
                        return Ok(out);
                    }
                };
                for (i, record) in (p * per_point..).zip(records) {
                    if mine.contains(&i) {
                        store.save(&record)?;
                        out.run_time_s += record.outcome.wall_s;
                        out.runs.insert(i);
                    }
                }
                Ok(out)
            })
            .collect::<Result<Vec<_>, SweepError>>()
    })?;
    let mut total = Certified::default();
    for c in done {
        total.runs.extend(c.runs);
        total.run_time_s += c.run_time_s;
        for (why, n) in c.refused {
            *total.refused.entry(why).or_default() += n;
        }
    }
    Ok(total)
}
