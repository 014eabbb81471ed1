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
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// A point on the finest lattice: `(i, j)` steps of `step / 2^levels` along each axis.
pub type Node = (u64, u64);

/// The refinement settings of a spec (`refine:`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Refine {
    /// Levels beyond the spec's grid.
    pub levels: u32,
    /// Smallest cell side on each axis `(eta_t, kappa2)`.
    pub min_step: (f64, f64),
    /// Also split cells whose corners all share one bistable class (fills bistable bands
    /// to the finest step; by default only their edges are refined).
    pub split_bistable: bool,
}

/// The spec's uniform grid along one axis: `start + i step`, `i < count`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Axis {
    pub start: f64,
    pub step: f64,
    pub count: u64,
}

/// The level-0 grid and the refinement settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Lattice {
    pub eta_t: Axis,
    pub kappa2: Axis,
    pub refine: Refine,
}

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

impl Lattice {
    /// Lattice units per level-0 step.
    fn scale(&self) -> u64 {
        1u64 << self.refine.levels
    }

    /// Side (lattice units) of a cell of `level`.
    pub fn side(&self, level: u32) -> u64 {
        self.scale() >> level
    }

    /// The cell size `(d_eta_t, d_kappa2)` of `level`.
    pub fn cell_size(&self, level: u32) -> (f64, f64) {
        let f = (1u64 << level) as f64;
        (self.eta_t.step / f, self.kappa2.step / f)
    }

    /// `(eta_t, kappa2)` of a node, on the spec grid's decimal rounding (equal to a uniform
    /// grid's value where a uniform grid has the point).
    pub fn coords(&self, (i, j): Node) -> (f64, f64) {
        let s = self.scale() as f64;
        let at = |a: &Axis, k: u64| crate::axes::round12(a.start + (k as f64) * (a.step / s));
        (at(&self.eta_t, i), at(&self.kappa2, j))
    }

    /// Whether cells of `level` may still be split (their quarters not below `min_step`).
    pub fn splittable(&self, level: u32) -> bool {
        let (de, dk) = self.cell_size(level + 1);
        let (me, mk) = self.refine.min_step;
        level < self.refine.levels && de >= me * (1.0 - 1e-9) && dk >= mk * (1.0 - 1e-9)
    }

    /// The points of level 0 (the spec grid), eta_t-major.
    pub fn level0(&self) -> Vec<Node> {
        let s = self.scale();
        (0..self.eta_t.count)
            .flat_map(|a| (0..self.kappa2.count).map(move |b| (a * s, b * s)))
            .collect()
    }

    /// The cells of level 0, by their lower-left node.
    pub fn cells0(&self) -> Vec<Node> {
        let s = self.scale();
        let (ne, nk) = (self.eta_t.count, self.kappa2.count);
        (0..ne.saturating_sub(1))
            .flat_map(|a| (0..nk.saturating_sub(1)).map(move |b| (a * s, b * s)))
            .collect()
    }
}

impl Lattice {
    /// The node of a point `(eta_t, kappa2)` of this lattice (the inverse of [`Self::coords`]).
    pub fn node_of(&self, (eta_t, kappa2): (f64, f64)) -> Node {
        let s = self.scale() as f64;
        let at = |a: &Axis, x: f64| ((x - a.start) / (a.step / s)).round().max(0.0) as u64;
        (at(&self.eta_t, eta_t), at(&self.kappa2, kappa2))
    }

    /// The picture of a refined point set: for each point, the rectangles
    /// `[eta_t0, kappa2_0, eta_t1, kappa2_1]` it stands for. Each cell that was not split (its
    /// centre is not a point) is divided into four quarters, each belonging to the corner it
    /// touches, so the map is tiled without gaps or overlaps at every level (a point in the
    /// middle of a coarser neighbour's side has quarters on the finer side only).
    pub fn tiles(&self, nodes: &BTreeSet<Node>) -> BTreeMap<Node, Vec<[f64; 4]>> {
        let mut out: BTreeMap<Node, Vec<[f64; 4]>> = BTreeMap::new();
        let mut stack: Vec<(Node, u32)> = self.cells0().into_iter().map(|c| (c, 0)).collect();
        while let Some(((i, j), level)) = stack.pop() {
            let side = self.side(level);
            let half = side / 2;
            if half > 0 && nodes.contains(&(i + half, j + half)) {
                for (di, dj) in [(0, 0), (half, 0), (0, half), (half, half)] {
                    stack.push(((i + di, j + dj), level + 1));
                }
                continue;
            }
            let (e0, k0) = self.coords((i, j));
            let (e1, k1) = self.coords((i + side, j + side));
            let (em, km) = (0.5 * (e0 + e1), 0.5 * (k0 + k1));
            for ((di, dj), rect) in [
                ((0, 0), [e0, k0, em, km]),
                ((side, 0), [em, k0, e1, km]),
                ((0, side), [e0, km, em, k1]),
                ((side, side), [em, km, e1, k1]),
            ] {
                out.entry((i + di, j + dj)).or_default().push(rect);
            }
        }
        out
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice(levels: u32) -> Lattice {
        Lattice {
            eta_t: Axis {
                start: 0.07,
                step: 0.01,
                count: 4,
            },
            kappa2: Axis {
                start: 0.1,
                step: 0.02,
                count: 3,
            },
            refine: Refine {
                levels,
                min_step: (0.0, 0.0),
                split_bistable: false,
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
            assert_eq!(e, crate::axes::round12(0.07 + a as f64 * 0.01));
            assert_eq!(k, crate::axes::round12(0.1 + b as f64 * 0.02));
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
            },
            ..l
        };
        assert!(coarse.splittable(0) && !coarse.splittable(1));
    }
}
