//! The point lattice of a sweep: integer coordinates `(i, j)` in units of `step / 2^levels`
//! from the spec grid's start, so that a point is the same point at every refinement level and
//! its coordinates (hence its runs' keys) equal a uniform grid's where they coincide.
//! Level 0 is the spec's grid; the refinement rule that adds points is [`crate::map::refine`].
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
/// A point on the finest lattice: `(i, j)` steps of `step / 2^levels` along each axis.
pub type Node = (u64, u64);

/// The refinement settings of a spec (`refine:`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Refine {
    /// Levels beyond the spec's grid.
    pub levels: u32,
    /// Smallest cell side on each axis `(x, y)`.
    pub min_step: (f64, f64),
    /// Also split cells whose corners all share one bistable class (fills bistable bands
    /// to the finest step; by default only their edges are refined).
    pub split_bistable: bool,
    /// Certify a refined point without runs where it lies midway between two coarser points
    /// of one single state (the ends of its edge, or opposite corners of the cell it is the
    /// centre of) and its own stability shows that state alone is stable there
    /// ([`crate::map::certify`]). Off by default: such a point's runs are not stepped.
    pub certify_midpoints: Certify,
}

/// Which refined points `refine.certify_midpoints` certifies without runs
/// ([`crate::map::certify`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Certify {
    /// None: every run is stepped (`false`, the default).
    #[default]
    Off,
    /// Points whose two coarser neighbours' runs were all stepped (`true`).
    Stepped,
    /// Also points whose neighbours were certified themselves (`chained`): every chain of
    /// certificates starts at points whose runs were stepped.
    Chained,
}

impl Certify {
    /// Whether any point is certified.
    pub fn is_on(self) -> bool {
        self != Self::Off
    }

    /// The spec's value (`false`, `true`, `chained`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Off => "false",
            Self::Stepped => "true",
            Self::Chained => "chained",
        }
    }
}

/// The uniform steps of the spec's grid along one of its axes: `start + i step`, `i < count`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Steps {
    pub start: f64,
    pub step: f64,
    pub count: u64,
}

/// The level-0 grid and the refinement settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Lattice {
    /// The plane's first axis.
    pub x: Steps,
    /// Its second.
    pub y: Steps,
    pub refine: Refine,
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

    /// The cell size `(dx, dy)` of `level`.
    pub fn cell_size(&self, level: u32) -> (f64, f64) {
        let f = (1u64 << level) as f64;
        (self.x.step / f, self.y.step / f)
    }

    /// The coordinates of a node, on the spec grid's decimal rounding (equal to a uniform
    /// grid's value where a uniform grid has the point).
    pub fn coords(&self, (i, j): Node) -> (f64, f64) {
        let s = self.scale() as f64;
        let at =
            |a: &Steps, k: u64| crate::spec::axes::round12(a.start + (k as f64) * (a.step / s));
        (at(&self.x, i), at(&self.y, j))
    }

    /// Whether cells of `level` may still be split (their quarters not below `min_step`).
    pub fn splittable(&self, level: u32) -> bool {
        let (de, dk) = self.cell_size(level + 1);
        let (me, mk) = self.refine.min_step;
        level < self.refine.levels && de >= me * (1.0 - 1e-9) && dk >= mk * (1.0 - 1e-9)
    }

    /// The points of level 0 (the spec grid), x-major.
    pub fn level0(&self) -> Vec<Node> {
        let s = self.scale();
        (0..self.x.count)
            .flat_map(|a| (0..self.y.count).map(move |b| (a * s, b * s)))
            .collect()
    }

    /// The cells of level 0, by their lower-left node.
    pub fn cells0(&self) -> Vec<Node> {
        let s = self.scale();
        let (ne, nk) = (self.x.count, self.y.count);
        (0..ne.saturating_sub(1))
            .flat_map(|a| (0..nk.saturating_sub(1)).map(move |b| (a * s, b * s)))
            .collect()
    }
}

impl Lattice {
    /// The node of a point `(x, y)` of this lattice (the inverse of [`Self::coords`]).
    pub fn node_of(&self, (x, y): (f64, f64)) -> Node {
        let s = self.scale() as f64;
        let at = |a: &Steps, x: f64| ((x - a.start) / (a.step / s)).round().max(0.0) as u64;
        (at(&self.x, x), at(&self.y, y))
    }

    /// The picture of a refined point set: for each point, the rectangles
    /// `[x0, y0, x1, y1]` it stands for. Each cell that was not split (its
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
