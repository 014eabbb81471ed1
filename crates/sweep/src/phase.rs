//! Point classification from the runs of one point (paper Sect. 3).
//!
//! Rules:
//! - a run that ended `steady` counts with its class (IC, ID, MD, MC);
//! - a run that hit `t_max` counts with the class of its final state (the paper's
//!   "not classified" points come from such slowly converging runs), and is counted in
//!   `n_t_max` so it can be told apart; so does a run that ended unconverged at the step cap
//!   (`step_limit`, see `droplet_solver::limits`), and one stopped beside a saddle it could
//!   not leave before `t_max` (`saddle`, solver setting `stop_beside_saddle`); of these, the runs whose speed and
//!   deformation had not settled either (`RunOutcome::class_settled`) are `n_unsettled`;
//! - with [`BesideUnstable::Exclude`] (spec `classify: {beside_unstable: exclude}`), an
//!   unfinished run that stopped beside an unstable steady state
//!   (`RunOutcome::beside_unstable`) does not count with a class either: it is still on its
//!   way, and its final class is only where it had crept to by `t_max`;
//! - a `diverged` run has no class and does not count; it is counted in `n_diverged`;
//! - one distinct class -> that class; two -> a bistable pair written in the order
//!   IC, ID, MD, MC (`IC/MD`, `ID/MD`, `IC/MC`, ...); three or more -> `not classified`;
//!   no classified run at all (every run diverged, or none finished) -> `diverged` / `missing`,
//!   and `not classified` when runs were excluded and none is left.
pub use crate::beside_unstable::BesideUnstable;
use crate::store::RunRecord;
use droplet_solver::StateClass;
use std::collections::BTreeSet;

/// Label of a point whose runs gave three or more classes.
pub const NOT_CLASSIFIED: &str = "not classified";
/// Label of a point whose runs all diverged.
pub const DIVERGED: &str = "diverged";
/// Label of a point without finished runs.
pub const MISSING: &str = "missing";

/// Classification of one point.
#[derive(Debug, Clone, PartialEq)]
pub struct PointClass {
    pub label: String,
    pub n_runs: usize,
    pub n_steady: usize,
    pub n_t_max: usize,
    /// Unfinished runs whose class is not settled ([`RunOutcome::class_settled`]).
    ///
    /// [`RunOutcome::class_settled`]: droplet_solver::RunOutcome::class_settled
    pub n_unsettled: usize,
    pub n_diverged: usize,
}

/// Classifies a point from its runs (any order).
pub fn classify_point<'a>(
    runs: impl IntoIterator<Item = &'a RunRecord>,
    beside_unstable: BesideUnstable,
) -> PointClass {
    let mut classes = BTreeSet::new();
    let (mut n_runs, mut n_steady, mut n_t_max, mut n_unsettled, mut n_diverged) = (0, 0, 0, 0, 0);
    let mut n_excluded = 0;
    for r in runs {
        n_runs += 1;
        match r.outcome.status {
            droplet_solver::RunStatus::Steady => n_steady += 1,
            droplet_solver::RunStatus::TMax
            | droplet_solver::RunStatus::StepLimit
            | droplet_solver::RunStatus::Saddle => {
                n_t_max += 1;
                n_unsettled += usize::from(!r.outcome.class_settled());
            }
            droplet_solver::RunStatus::Diverged => n_diverged += 1,
        }
        if beside_unstable == BesideUnstable::Exclude && r.outcome.beside_unstable() {
            n_excluded += 1;
        } else if let Some(c) = r.outcome.class {
            classes.insert(c);
        }
    }
    let label = label_of(&classes, n_runs, n_diverged, n_excluded);
    PointClass {
        label,
        n_runs,
        n_steady,
        n_t_max,
        n_unsettled,
        n_diverged,
    }
}

fn label_of(
    classes: &BTreeSet<StateClass>,
    n_runs: usize,
    n_diverged: usize,
    n_excluded: usize,
) -> String {
    let names: Vec<&str> = classes.iter().map(|c| c.as_str()).collect();
    match names.len() {
        0 if n_runs == 0 => MISSING.into(),
        0 if n_excluded > 0 => NOT_CLASSIFIED.into(),
        0 if n_diverged > 0 => DIVERGED.into(),
        0 => MISSING.into(),
        1 | 2 => names.join("/"),
        _ => NOT_CLASSIFIED.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use droplet_solver::{InitialCondition, ModelParams, RunOutcome, RunStatus, SolverSettings};

    fn rec(status: RunStatus, class: Option<StateClass>) -> RunRecord {
        RunRecord {
            key: String::new(),
            params: ModelParams::default(),
            ic: InitialCondition::parse("i").unwrap(),
            settings: SolverSettings::default(),
            solver_version: String::new(),
            outcome: RunOutcome {
                status,
                class,
                state: Default::default(),
                v: 0.0,
                s: 0.0,
                t_end: 0.0,
                t_steady: None,
                steps: 0,
                rejected: 0,
                max_step_error: None,
                wall_s: 0.0,
                ended_by: None,
                diagnosis: None,
                t_leapt: 0.0,
                series: vec![],
            },
        }
    }

    #[test]
    fn single_bistable_not_classified_and_divergence() {
        use RunStatus::*;
        use StateClass::*;
        let p = |v: Vec<RunRecord>| classify_point(&v, BesideUnstable::Count).label;
        assert_eq!(p(vec![rec(Steady, Some(IC)); 4]), "IC");
        assert_eq!(
            p(vec![
                rec(Steady, Some(MD)),
                rec(Steady, Some(IC)),
                rec(Steady, Some(IC))
            ]),
            "IC/MD"
        );
        assert_eq!(
            p(vec![rec(Steady, Some(MD)), rec(Steady, Some(ID))]),
            "ID/MD"
        );
        assert_eq!(
            p(vec![rec(Steady, Some(MC)), rec(Steady, Some(IC))]),
            "IC/MC"
        );
        assert_eq!(
            p(vec![
                rec(Steady, Some(MC)),
                rec(Steady, Some(IC)),
                rec(TMax, Some(MD))
            ]),
            NOT_CLASSIFIED
        );
        // Diverged runs do not count; t_max runs count by their final state.
        let mixed = vec![
            rec(Steady, Some(ID)),
            rec(Diverged, None),
            rec(TMax, Some(ID)),
        ];
        let c = classify_point(&mixed, BesideUnstable::Count);
        assert_eq!(
            (c.label.as_str(), c.n_diverged, c.n_t_max, c.n_steady),
            ("ID", 1, 1, 1)
        );
        assert_eq!(p(vec![rec(Diverged, None); 4]), DIVERGED);
        // An unfinished run is unsettled unless its diagnosis says v and s are settled.
        let mut turning = rec(TMax, Some(MD));
        turning.outcome.diagnosis = Some(format!(
            "rotation mode -1e-4: turns slowly; {}",
            droplet_solver::newton_finish::SETTLED
        ));
        let mut saddle = rec(TMax, Some(MD));
        saddle.outcome.diagnosis = Some("near an unstable steady state".into());
        let c = classify_point(
            &[turning, saddle, rec(TMax, Some(MD))],
            BesideUnstable::Count,
        );
        assert_eq!((c.n_t_max, c.n_unsettled), (3, 2));
        assert_eq!(p(vec![]), MISSING);
    }

    #[test]
    fn runs_beside_an_unstable_state_are_left_out_only_when_asked() {
        use RunStatus::*;
        use StateClass::*;
        let beside = |class| {
            let mut r = rec(TMax, Some(class));
            r.outcome.diagnosis = Some(format!(
                "{} (1 growing mode(s), largest +6.12e-4)",
                droplet_solver::newton_finish::BESIDE_UNSTABLE
            ));
            r
        };
        let slow = |class| {
            let mut r = rec(TMax, Some(class));
            r.outcome.diagnosis = Some("slowest eigenvalue -6.11e-4: converging slowly".into());
            r
        };
        let label = |runs: &[RunRecord], rule| classify_point(runs, rule).label;
        // The ID/MD band's creepers: two steady MD, two ID runs stuck beside the unstable ID.
        let band = [
            rec(Steady, Some(MD)),
            rec(Steady, Some(MD)),
            beside(ID),
            beside(ID),
        ];
        assert_eq!(label(&band, BesideUnstable::Count), "ID/MD");
        assert_eq!(label(&band, BesideUnstable::Exclude), "MD");
        let c = classify_point(&band, BesideUnstable::Exclude);
        assert_eq!((c.n_runs, c.n_t_max, c.n_unsettled), (4, 2, 2));
        // Such a run is always unsettled, so its point's cells are split under either rule
        // and the rule never changes a refined sweep's points.
        assert!(band[2].outcome.beside_unstable() && !band[2].outcome.class_settled());
        // Other unfinished runs still count by their final state.
        let converging = [rec(Steady, Some(IC)), slow(MC)];
        assert_eq!(label(&converging, BesideUnstable::Exclude), "IC/MC");
        // Nothing left: not classified (not missing: the runs exist).
        assert_eq!(
            label(&[beside(MC), beside(MC)], BesideUnstable::Exclude),
            NOT_CLASSIFIED
        );
        // A steady run is never excluded, whatever its diagnosis.
        let mut steady = rec(Steady, Some(IC));
        steady.outcome.diagnosis = beside(IC).outcome.diagnosis;
        assert_eq!(label(&[steady], BesideUnstable::Exclude), "IC");
    }
}
