//! The full model's boundaries over a sweep in a plane of two model parameters that the
//! paper's plane does not already give by crossings ([`crate::studies::across`]): any pair
//! with a geometric parameter (`radius`, `sigma`, `box_len`), or two non-paper parameters.
//! Each curve is continued in the pair itself (`droplet_solver::continuation::plane`), in
//! the window the sweep's two axes span, the other parameters the spec's.
use crate::error::SweepError;
use crate::spec::axes::Param;
use crate::spec::SweepSpec;
use crate::tables::boundaries::NamedCurve;
use droplet_solver::continuation::boundaries::boundaries;
use droplet_solver::continuation::window::{Axis, Window};
use droplet_solver::contract::settings::ModelKind;
use droplet_solver::model::params::ModelParams;
use std::path::Path;

/// Samples along each edge and midline of the window where the onset curves are looked for.
const EDGE_SAMPLES: usize = 16;

/// A sweep's plane of two model parameters, as the window of its axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Pair {
    pub x: Axis,
    pub y: Axis,
}

impl Pair {
    /// The pair of the sweep `s` (in `out`), if its plane is one: two model-parameter axes, not
    /// the paper's plane, and not `eta_t` or `kappa2` with a rate-only parameter (those are
    /// crossings of the paper's curves). Refused where an axis has one value (no window).
    pub fn of(s: &SweepSpec, out: &Path) -> Result<Option<Self>, SweepError> {
        let plane = s.grid.plane();
        let (Some(y), None) = (plane.y, plane.z) else {
            return Ok(None);
        };
        let (Some(mx), Some(my)) = (plane.x.model(), y.model()) else {
            return Ok(None);
        };
        let paper = |p: Param| matches!(p, Param::ETA_T | Param::KAPPA2);
        if plane.is_paper()
            || (paper(plane.x) && y.rate_only())
            || (paper(y) && plane.x.rate_only())
        {
            return Ok(None);
        }
        let window = |p: Param| {
            let (lo, hi) = s
                .grid
                .axis(p)
                .expect("a plane's axis is a grid axis")
                .span();
            if lo < hi {
                Ok((lo, hi))
            } else {
                Err(SweepError::Invalid(format!(
                    "{}: grid.{} has one value; the boundaries are drawn in the window of two \
                     axes that each span a range",
                    out.display(),
                    p.name()
                )))
            }
        };
        Ok(Some(Self {
            x: Axis::new(mx, window(plane.x)?),
            y: Axis::new(my, window(y)?),
        }))
    }

    /// The names of the plane's axes `(x, y)`.
    pub fn names(&self) -> (&'static str, &'static str) {
        (self.x.param.name(), self.y.param.name())
    }

    /// The window of the pair at grid size `n`, the other parameters (the shape modes among
    /// them) `base`'s.
    pub fn window(&self, base: &ModelParams, n: usize) -> Window {
        Window {
            base: *base,
            n,
            x: self.x,
            y: self.y,
            samples: EDGE_SAMPLES,
        }
    }

    /// The full model's boundaries in [`Pair::window`].
    pub fn curves(&self, base: &ModelParams, n: usize) -> Result<Vec<NamedCurve>, SweepError> {
        let pde = boundaries(&self.window(base, n))?;
        Ok(NamedCurve::from_boundaries(ModelKind::Pde, &pde))
    }
}
