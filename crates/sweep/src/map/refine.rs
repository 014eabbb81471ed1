//! Adaptive refinement of a phase map: which points a level adds, from the classes of the
//! points before it.
//!
//! Points live on the lattice of the finest level: integer coordinates `(i, j)` in units of
//! `step / 2^levels` from the spec grid's start, so that a point is the same point at every
//! level and its `(eta_t, kappa2)` (hence its runs' keys) equal a uniform grid's where they
//! coincide. Level 0 is the spec's grid; its cells are the rectangles between neighbouring
//! grid points. A cell of level `l` is split, adding its edge midpoints and centre as points of
//! level `l + 1` and its four quarters as cells of level `l + 1`, when its corners do not all
//! have the same point class, or any corner needs a closer look (bistable, not classified,
//! diverged or missing, or a run that ended at `t_max` or diverged), as long as a quarter's
//! sides are not below `min_step`.
//!
//! Everything here is a pure function of the grid and the point classes: the points of each
//! level follow from the finished runs of the levels before, so a resumed sweep plans exactly
//! the points an uninterrupted one would.
use crate::spec::lattice::{Lattice, Node};
use std::collections::{BTreeMap, BTreeSet};

/// How a point's runs ended, as refinement needs it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verdict {
    /// The point class (`IC`, `IC/MD`, `not classified`, ...).
    pub label: String,
    /// The point's class can be trusted as a corner of a cell whose corners agree: every run
    /// settled (steady, or unfinished with `v` and `s` settled), none diverged, at most two
    /// classes (one, with `split_bistable`).
    pub settled: bool,
}

/// Whether a cell with these corner verdicts is split.
pub fn needs_split(corners: [&Verdict; 4]) -> bool {
    let first = &corners[0].label;
    corners.iter().any(|c| !c.settled || c.label != *first)
}

/// One step of refinement: the cells of `level` (lower-left nodes) that are split, the new
/// points of level `level + 1` (not among `known`), and the cells of level `level + 1`.
/// `verdicts` must hold every corner of `cells`.
pub fn split(
    lattice: &Lattice,
    level: u32,
    cells: &[Node],
    verdicts: &BTreeMap<Node, Verdict>,
    known: &BTreeSet<Node>,
) -> (Vec<Node>, Vec<Node>) {
    if !lattice.splittable(level) {
        return (Vec::new(), Vec::new());
    }
    let side = lattice.side(level);
    let half = side / 2;
    let mut points = BTreeSet::new();
    let mut children = Vec::new();
    for &(i, j) in cells {
        let corner = |di: u64, dj: u64| &verdicts[&(i + di, j + dj)];
        if !needs_split([
            corner(0, 0),
            corner(side, 0),
            corner(0, side),
            corner(side, side),
        ]) {
            continue;
        }
        for (di, dj) in [
            (half, 0),
            (0, half),
            (half, half),
            (side, half),
            (half, side),
        ] {
            let node = (i + di, j + dj);
            if !known.contains(&node) {
                points.insert(node);
            }
        }
        for (di, dj) in [(0, 0), (half, 0), (0, half), (half, half)] {
            children.push((i + di, j + dj));
        }
    }
    (points.into_iter().collect(), children)
}

/// The pairs of points of lower levels that a point of `level` (>= 1) lies midway between,
/// in the order a certificate tries them: the midpoint of a split cell's edge has one, on a
/// line of the lattice (along `x` first, then `y`); a cell's centre, whose neighbours along
/// the lattice's lines are of its own level, lies midway between the cell's opposite corners,
/// on its two diagonals. Empty for a point of level 0. `level_of` gives the level of every
/// known point.
pub fn midway(
    lattice: &Lattice,
    (i, j): Node,
    level: u32,
    level_of: impl Fn(Node) -> Option<u32>,
) -> Vec<[Node; 2]> {
    if level == 0 {
        return Vec::new();
    }
    let d = lattice.side(level);
    let lower = |pair: &[Node; 2]| pair.iter().all(|&n| level_of(n).is_some_and(|l| l < level));
    let along_x = (i >= d).then(|| [(i - d, j), (i + d, j)]);
    let along_y = (j >= d).then(|| [(i, j - d), (i, j + d)]);
    if let Some(pair) = [along_x, along_y].into_iter().flatten().find(lower) {
        return vec![pair];
    }
    let diagonals = (i >= d && j >= d).then(|| {
        [
            [(i - d, j - d), (i + d, j + d)],
            [(i - d, j + d), (i + d, j - d)],
        ]
    });
    diagonals.into_iter().flatten().filter(lower).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::lattice::{Refine, Steps};

    fn lattice(levels: u32) -> Lattice {
        Lattice {
            x: Steps {
                start: 0.07,
                step: 0.01,
                count: 4,
            },
            y: Steps {
                start: 0.1,
                step: 0.02,
                count: 3,
            },
            refine: Refine {
                levels,
                min_step: (0.0, 0.0),
                split_bistable: false,
                certify_midpoints: Default::default(),
            },
        }
    }

    fn settled(label: &str) -> Verdict {
        Verdict {
            label: label.into(),
            settled: true,
        }
    }

    #[test]
    fn lattice_points_are_the_uniform_grids_where_they_coincide() {
        let l = lattice(3);
        for (a, b) in [(0u64, 0u64), (1, 2), (3, 1)] {
            let (e, k) = l.coords((a * 8, b * 8));
            assert_eq!(e, crate::spec::axes::round12(0.07 + a as f64 * 0.01));
            assert_eq!(k, crate::spec::axes::round12(0.1 + b as f64 * 0.02));
        }
        assert_eq!(l.coords((4, 4)), (0.075, 0.11));
        assert_eq!(l.level0().len(), 12);
        assert_eq!(l.cells0().len(), 6);
        assert_eq!(l.cell_size(2), (0.0025, 0.005));
    }

    #[test]
    fn tiles_cover_the_map_once() {
        let l = lattice(2);
        let mut nodes: BTreeSet<Node> = l.level0().into_iter().collect();
        // Split the cell at (8, 4), then its upper-right quarter once more.
        nodes.extend([(8, 6), (10, 4), (10, 6), (10, 8), (12, 6)]);
        nodes.extend([(10, 7), (11, 6), (11, 7), (12, 7), (11, 8)]);
        let tiles = l.tiles(&nodes);
        assert_eq!(tiles.len(), nodes.len(), "every point has a tile");
        let area: f64 = tiles
            .values()
            .flatten()
            .map(|r| (r[2] - r[0]) * (r[3] - r[1]))
            .sum();
        let whole = (0.03 * 0.04f64).abs();
        assert!((area - whole).abs() < 1e-15, "{area} vs {whole}");
        // No two tiles overlap, so with the area above they tile the map exactly.
        let all: Vec<&[f64; 4]> = tiles.values().flatten().collect();
        for (a, r) in all.iter().enumerate() {
            for q in &all[a + 1..] {
                let w = r[2].min(q[2]) - r[0].max(q[0]);
                let h = r[3].min(q[3]) - r[1].max(q[1]);
                assert!(w <= 1e-15 || h <= 1e-15, "{r:?} overlaps {q:?}");
            }
        }
        // A point in the middle of an unsplit neighbour's side: tiles on the fine side only.
        assert!(tiles[&(8, 6)].iter().all(|r| r[0] >= 0.09 - 1e-15));
        for n in &nodes {
            assert_eq!(l.node_of(l.coords(*n)), *n);
        }
    }

    #[test]
    fn only_cells_whose_corners_differ_or_are_unsettled_split() {
        let l = lattice(2);
        let mut v: BTreeMap<Node, Verdict> =
            l.level0().into_iter().map(|n| (n, settled("IC"))).collect();
        let known: BTreeSet<Node> = v.keys().copied().collect();
        // One MD corner at (eta index 3, kappa index 2): only the cell below-left of it splits.
        v.insert((12, 8), settled("MD"));
        let (points, cells) = split(&l, 0, &l.cells0(), &v, &known);
        assert_eq!(cells, vec![(8, 4), (10, 4), (8, 6), (10, 6)]);
        assert_eq!(points, vec![(8, 6), (10, 4), (10, 6), (10, 8), (12, 6)]);
        // An unsettled corner (a t_max run) splits its cells too, even with equal labels.
        let mut w = v.clone();
        w.insert((12, 8), settled("IC"));
        w.insert(
            (0, 0),
            Verdict {
                label: "IC".into(),
                settled: false,
            },
        );
        let (_, cells) = split(&l, 0, &l.cells0(), &w, &known);
        assert_eq!(cells.len(), 4);
        // No level beyond the last, and none below min_step.
        assert!(split(&l, 2, &l.cells0(), &v, &known).0.is_empty());
        let coarse = Lattice {
            refine: Refine {
                levels: 2,
                min_step: (0.004, 0.0),
                split_bistable: false,
                certify_midpoints: Default::default(),
            },
            ..l
        };
        assert!(coarse.splittable(0) && !coarse.splittable(1));
    }

    #[test]
    fn edge_midpoints_lie_midway_on_the_lattice_and_centres_on_the_diagonals() {
        let l = lattice(2);
        let mut levels: BTreeMap<Node, u32> = l.level0().into_iter().map(|n| (n, 0)).collect();
        let added = [(8, 6), (10, 4), (10, 6), (10, 8), (12, 6)];
        levels.extend(added.map(|n| (n, 1)));
        let of = |n: Node| levels.get(&n).copied();
        assert_eq!(midway(&l, (10, 4), 1, of), vec![[(8, 4), (12, 4)]]);
        assert_eq!(midway(&l, (8, 6), 1, of), vec![[(8, 4), (8, 8)]]);
        assert_eq!(
            midway(&l, (10, 6), 1, of),
            vec![[(8, 4), (12, 8)], [(8, 8), (12, 4)]],
            "a centre: its cell's diagonals"
        );
        assert!(midway(&l, (0, 0), 0, of).is_empty(), "level 0");
        // A point of level 2 between a level-1 point and a level-0 one.
        levels.insert((9, 4), 2);
        let of = |n: Node| levels.get(&n).copied();
        assert_eq!(midway(&l, (9, 4), 2, of), vec![[(8, 4), (10, 4)]]);
        // The centre of a level-1 cell whose corners are of levels 0 and 1.
        levels.insert((9, 5), 2);
        let of = |n: Node| levels.get(&n).copied();
        assert_eq!(
            midway(&l, (9, 5), 2, of),
            vec![[(8, 4), (10, 6)], [(8, 6), (10, 4)]]
        );
    }
}
