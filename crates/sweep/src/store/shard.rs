//! Sharding a sweep over independent processes (e.g. a Slurm job array): deterministic slices
//! balanced by expected cost. The cost of a PDE run is estimated by the reduced ODE model's
//! number of steps to its steady state from the same point and initial condition
//! (microseconds per run): runs near transitions relax slowly in both models. Slices are
//! assigned greedily, most expensive first, to the currently cheapest shard (LPT).
use crate::store::plan::{Plan, Task};
use droplet_solver::{contract::settings::SolverSettings, runs::driver::simulate};

/// Which slice of a sweep this process runs: `index` in `0..count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Parses `I/N` with `0 <= I < N`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| format!("invalid shard `{text}`: expected I/N, e.g. 0/4"))?;
        let index: usize = i
            .trim()
            .parse()
            .map_err(|_| format!("invalid shard index `{i}` in `{text}`"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| format!("invalid shard count `{n}` in `{text}`"))?;
        if count == 0 || index >= count {
            return Err(format!("invalid shard `{text}`: need 0 <= I < N"));
        }
        Ok(Self { index, count })
    }

    /// From Slurm's job-array variables, when both are set.
    pub fn from_slurm_env() -> Option<Result<Self, String>> {
        let id = std::env::var("SLURM_ARRAY_TASK_ID").ok()?;
        let count = std::env::var("SLURM_ARRAY_TASK_COUNT").ok()?;
        Some(Self::parse(&format!("{id}/{count}")))
    }

    /// Name of this shard's lock file.
    pub fn lock_name(&self) -> String {
        format!(".lock-shard-{}-of-{}", self.index, self.count)
    }
}

/// Expected relative cost of a run: ODE steps to its steady state (at least 1).
pub fn expected_cost(task: &Task) -> f64 {
    let ode = SolverSettings {
        t_max: task.settings.t_max,
        ..SolverSettings::ode()
    };
    simulate(&task.params, &task.ic, &ode).map_or(1.0, |o| o.steps.max(1) as f64)
}

/// The shard (`0..count`) of each of the runs `among` (indices into [`Plan::task`]), in
/// that order, balanced by expected cost; deterministic.
pub fn assign(plan: &Plan, among: &[usize], count: usize) -> Vec<usize> {
    let costs: Vec<f64> = among
        .iter()
        .map(|&i| expected_cost(&plan.task(i)))
        .collect();
    let mut order: Vec<usize> = (0..among.len()).collect();
    // Most expensive first; ties by task order, so the result never depends on timing.
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    let mut load = vec![0.0f64; count];
    let mut owner = vec![0; among.len()];
    for t in order {
        let s = (0..count)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .expect("count > 0");
        load[s] += costs[t];
        owner[t] = s;
    }
    owner
}

/// The runs of `shard` among the runs `among` (indices into [`Plan::task`]).
pub fn indices_of(plan: &Plan, among: &[usize], shard: Shard) -> Vec<usize> {
    assign(plan, among, shard.count)
        .into_iter()
        .zip(among)
        .filter(|(s, _)| *s == shard.index)
        .map(|(_, &i)| i)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::parse;

    #[test]
    fn shards_partition_the_runs_and_balance_cost() {
        let spec = parse(
            "grid:\n  eta_t: {start: 0.07, stop: 0.10, step: 0.005}\n  kappa2: {start: 0.10, stop: 0.16, step: 0.01}\n",
            "t.yaml",
            "t",
        )
        .unwrap();
        let plan = crate::store::plan::plan(&spec);
        let all: Vec<usize> = (0..plan.len()).collect();
        let n = 3;
        let mut seen = std::collections::HashSet::new();
        let mut loads = vec![0.0; n];
        for (i, load) in loads.iter_mut().enumerate() {
            for t in indices_of(&plan, &all, Shard { index: i, count: n }) {
                let t = plan.task(t);
                assert!(seen.insert(t.key.clone()), "run in two shards");
                *load += expected_cost(&t);
            }
        }
        assert_eq!(seen.len(), plan.len());
        let (lo, hi) = loads
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(hi / lo < 1.05, "unbalanced: {loads:?}");
        assert_eq!(assign(&plan, &all, n), assign(&plan, &all, n));
        // A subset (a refined sweep's level) is partitioned among the shards too.
        let odd: Vec<usize> = all.iter().copied().filter(|i| i % 2 == 1).collect();
        let mut parts: Vec<usize> = (0..n)
            .flat_map(|i| indices_of(&plan, &odd, Shard { index: i, count: n }))
            .collect();
        parts.sort_unstable();
        assert_eq!(parts, odd);
        assert!(Shard::parse("3/3").is_err() && Shard::parse("x").is_err());
        assert_eq!(Shard::parse("1/4").unwrap(), Shard { index: 1, count: 4 });
    }
}
