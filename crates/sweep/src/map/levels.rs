//! The point set of a refined sweep ([`crate::map::refine`]), level by level from the stored runs:
//! the points of level `l + 1` follow from the classes of the points up to level `l`, so the
//! sweep that runs the levels and `droplet status` that reads them plan the same points, and a
//! resumed sweep plans exactly the points an uninterrupted one would.
use crate::error::SweepError;
use crate::map::phase_map::PhaseMap;
use crate::map::point_class::{PointClass, DIVERGED, MISSING, NOT_CLASSIFIED, UNSETTLED};
use crate::map::refine::{midway, split, Verdict};
use crate::spec::lattice::{Lattice, Node};
use crate::spec::SweepSpec;
use crate::store::plan::{plan_nodes, Plan};
use crate::store::run_store::Store;
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// A point is settled for refinement ([`Verdict::settled`]): one class or a bistable pair
/// (one class only with `split_bistable`), every run's class settled, none diverged.
fn settled(c: &PointClass, split_bistable: bool) -> bool {
    (!split_bistable || !c.label.contains('/'))
        && ![NOT_CLASSIFIED, DIVERGED, MISSING, UNSETTLED].contains(&c.label.as_str())
        && c.n_unsettled == 0
        && c.n_diverged == 0
}

/// One slice's refinement state: its points with their levels, the points known, and the
/// cells of the current level.
struct Slice {
    nodes: Vec<(Node, u32)>,
    known: BTreeSet<Node>,
    cells: Vec<Node>,
}

/// The points of `level` that lie midway between two points of lower levels of their slice
/// ([`crate::map::refine::midway`]), as plan point indices (the plan lists the slices' points
/// in order): point -> its pairs.
fn midpoints(lattice: &Lattice, slices: &[Slice], level: u32) -> Between {
    let mut between = Between::new();
    let mut first = 0;
    for s in slices {
        let index: HashMap<Node, (usize, u32)> = s
            .nodes
            .iter()
            .enumerate()
            .map(|(i, &(n, l))| (n, (first + i, l)))
            .collect();
        for (i, &(n, l)) in s.nodes.iter().enumerate() {
            if l != level {
                continue;
            }
            let pairs = midway(lattice, n, l, |m| index.get(&m).map(|&(_, l)| l));
            if !pairs.is_empty() {
                let pairs = pairs.iter().map(|pair| pair.map(|m| index[&m].0));
                between.insert(first + i, pairs.collect());
            }
        }
        first += s.nodes.len();
    }
    between
}

/// Plan point index -> the plan point indices of the pairs of lower-level points it lies
/// midway between, in the order a certificate tries them ([`midpoints`]).
pub type Between = BTreeMap<usize, Vec<[usize; 2]>>;

/// Walks the levels of `spec`'s refinement on `lattice`, each slice of a third axis on its own
/// (its cells split by its own points' classes). At each level `visit(level, plan, runs,
/// between)` gets the plan of every point so far (slice by slice), the run indices of this
/// level's points and which of them lie midway between two points of lower levels
/// ([`Between`]); it returns whether the walk goes on (those runs are now stored) or stops
/// there. Returns the plan of the last level visited.
pub fn walk(
    spec: &SweepSpec,
    lattice: &Lattice,
    store: &Store,
    mut visit: impl FnMut(u32, &Plan, &[usize], &Between) -> Result<bool, SweepError>,
) -> Result<Plan, SweepError> {
    let zs = spec.grid.z_values();
    let mut slices: Vec<Slice> = zs
        .iter()
        .map(|_| {
            let nodes: Vec<(Node, u32)> = lattice.level0().into_iter().map(|n| (n, 0)).collect();
            Slice {
                known: nodes.iter().map(|&(n, _)| n).collect(),
                nodes,
                cells: lattice.cells0(),
            }
        })
        .collect();
    // The runs of the levels walked so far (each level's are read once).
    let mut records = HashMap::new();
    let mut level = 0;
    loop {
        let all: Vec<(Node, u32, f64)> = slices
            .iter()
            .zip(&zs)
            .flat_map(|(s, &z)| s.nodes.iter().map(move |&(n, l)| (n, l, z)))
            .collect();
        let plan = plan_nodes(spec, lattice, &all);
        let per_point = plan.ic_names.len().max(1);
        let runs: Vec<usize> = (0..plan.len())
            .filter(|&i| plan.levels[i / per_point] == level)
            .collect();
        let between = midpoints(lattice, &slices, level);
        let no_cells = slices.iter().all(|s| s.cells.is_empty());
        if !visit(level, &plan, &runs, &between)? || !lattice.splittable(level) || no_cells {
            return Ok(plan);
        }
        records.extend(store.load_many(runs.iter().map(|&i| plan.task(i).key)));
        let map = PhaseMap::new(&plan, &records);
        let mut entries = map.points.iter();
        let mut grew = false;
        for slice in &mut slices {
            let verdicts: BTreeMap<Node, Verdict> = slice
                .nodes
                .iter()
                .zip(entries.by_ref())
                .map(|(&(n, _), e)| {
                    let verdict = Verdict {
                        label: e.shown_label().to_string(),
                        settled: e.complete() && settled(&e.class, lattice.refine.split_bistable),
                    };
                    (n, verdict)
                })
                .collect();
            let (added, children) = split(lattice, level, &slice.cells, &verdicts, &slice.known);
            grew |= !children.is_empty();
            slice.known.extend(added.iter().copied());
            slice
                .nodes
                .extend(added.into_iter().map(|n| (n, level + 1)));
            slice.cells = children;
        }
        if !grew {
            return Ok(plan);
        }
        level += 1;
    }
}

/// The plan of the sweep `spec` as far as its stored runs go: the spec's grid, or for a
/// refined sweep every level whose points are known (up to the first unfinished level).
pub fn stored_plan(spec: &SweepSpec, store: &Store) -> Result<Plan, SweepError> {
    match &spec.refine {
        None => Ok(crate::store::plan::plan(spec)),
        Some(lattice) => walk(spec, lattice, store, |_, plan, runs, _| {
            Ok(runs.iter().all(|&i| store.has(&plan.task(i).key)))
        }),
    }
}
