//! The families a slow run's landing walks (`landing`): which coordinate
//! parametrises one, and the walks a run's landing tries made along them, kept so that a later
//! try of the same run that the walk's certificate covers lands without walking again.
use crate::model::mirror::MirrorLine;

/// Which coordinate parametrises the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coordinate {
    /// The speed `v` along the mirror line (moving runs).
    Speed,
    /// The deformation `c` along the mirror line's long axis, at rest.
    Shape,
}

/// The walks a run's landing tries made along a family: from the coordinate `from` the way
/// `dir` to the zero `to` (where the family's shape is `c_to`), no zero between. A later try
/// from a coordinate between `from` and `to`, drifting the same way, lands on the same zero:
/// the certificate of the walk holds for it (a run's tries follow it along the family).
#[derive(Debug, Clone, Default)]
pub struct Walks {
    done: Vec<Walk>,
}

/// One walk: along `axis`'s `coordinate` family from `from` the way `dir` to the zero `to`.
#[derive(Debug, Clone)]
pub(crate) struct Walk {
    pub(crate) axis: MirrorLine,
    pub(crate) coordinate: Coordinate,
    pub(crate) dir: f64,
    pub(crate) from: f64,
    pub(crate) to: f64,
    pub(crate) c_to: Vec<f64>,
}

impl Walks {
    /// The zero and its shape of a walk on `axis`'s `coordinate` family that passed `x`
    /// going the way `dir`.
    pub(crate) fn passed(
        &self,
        axis: MirrorLine,
        coordinate: Coordinate,
        dir: f64,
        x: f64,
    ) -> Option<(f64, Vec<f64>)> {
        self.done
            .iter()
            .find(|w| {
                w.axis == axis
                    && w.coordinate == coordinate
                    && w.dir == dir
                    && (x - w.from) * dir >= 0.0
                    && (w.to - x) * dir > 0.0
            })
            .map(|w| (w.to, w.c_to.clone()))
    }

    pub(crate) fn keep(&mut self, walk: Walk) {
        self.done.push(walk);
    }
}
