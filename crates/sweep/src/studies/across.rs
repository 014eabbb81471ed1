//! The full model's boundaries over a sweep outside the paper's plane, as crossings of the
//! paper-plane curves: a plane of `eta_t` or `kappa2` (the parameter the sweep varies *along*
//! the paper's plane, the other of the two fixed) with one more parameter, the *other* axis.
//!
//! - **An other axis that moves no steady state**: the rate-only model parameters (`eta2`,
//!   `mass`; [`Param::rate_only`]) multiply time derivatives only, and the time-stepping
//!   settings (`tol`, `dt_max`, `t_max`) do not enter the steady equations. No boundary where a
//!   real eigenvalue crosses zero moves. Each paper-plane boundary is computed once, where it
//!   crosses the sweep's line, and drawn as a line across the other axis. (A Hopf point would
//!   depend on a rate-only parameter; none was found on the continuation lines, and `droplet
//!   continue --param mass` or `--param eta2` looks for one along a branch.)
//! - **The grid `n`**: the paper-plane boundaries are computed again at each of the sweep's
//!   values of it, and where each crosses the line becomes a point of its curve: how far the
//!   grid moves each boundary, in the sweep's plane.
//! - **A geometric other axis** (`radius`, `sigma`, `box_len`): the full model's curves are
//!   continued in the pair ([`crate::studies::pair`]); the reduced model's are sampled here,
//!   computed again at each of the sweep's values.
//!
//! Other planes (a solver setting with a non-paper parameter, two settings, a slice axis) are
//! refused.
use crate::error::SweepError;
use crate::spec::axes::Param;
use crate::spec::SweepSpec;
use crate::tables::boundaries::NamedCurve;
use droplet_solver::model::params::ModelParams;
use std::collections::BTreeMap;
use std::path::Path;

/// A sweep's plane seen from the paper's plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Across {
    /// The sweep's other axis.
    pub other: Param,
    /// The paper parameter the sweep varies (`eta_t` or `kappa2`).
    pub along: Param,
    /// The value of the paper parameter the sweep fixes (the other of `eta_t`, `kappa2`).
    pub fixed: f64,
    /// Whether the other axis is the plane's `x`.
    pub other_is_x: bool,
    /// The other axis's smallest and largest value.
    pub span: (f64, f64),
    /// Where the paper-plane boundaries are computed: the sweep's values of `n` or of a
    /// geometric axis, sorted; the middle value of an axis that moves nothing (any value gives
    /// the same boundaries; the
    /// smallest mass makes the eigenvalue solves slow: 26 s at m = 0.01 against 4.8 s at
    /// m = 0.21 for results/mass-eta_t).
    pub samples: Vec<f64>,
}

impl Across {
    /// The view of the sweep `s` (in `out`): `None` in the paper's plane; refused in a plane
    /// where the boundaries cannot be drawn.
    pub fn of(s: &SweepSpec, out: &Path) -> Result<Option<Self>, SweepError> {
        let plane = s.grid.plane();
        if plane.is_paper() {
            return Ok(None);
        }
        let paper = |p: Param| matches!(p, Param::ETA_T | Param::KAPPA2);
        let pair = match (plane.y, plane.z) {
            (Some(y), None) if paper(y) && !paper(plane.x) => Some((plane.x, y, true)),
            (Some(y), None) if paper(plane.x) && !paper(y) => Some((y, plane.x, false)),
            _ => None,
        };
        let Some((other, along, other_is_x)) = pair else {
            let names: Vec<&str> = plane.params().iter().map(|p| p.name()).collect();
            return Err(SweepError::Invalid(format!(
                "{}: the sweep there is in ({}); the exact boundaries are drawn in a plane of \
                 two of eta_t, kappa2, eta2, mass, radius, sigma, box_len, or of eta_t or \
                 kappa2 with one of n, tol, dt_max, t_max; give another --out",
                out.display(),
                names.join(", ")
            )));
        };
        let axis = s.grid.axis(other).expect("a plane's axis is a grid axis");
        let mut samples = axis.values.clone();
        samples.sort_by(f64::total_cmp);
        samples.dedup();
        if Self::moves_nothing(other) {
            // Any value gives the same boundaries: the middle one.
            samples = vec![samples[samples.len() / 2]];
        }
        Ok(Some(Self {
            other,
            along,
            fixed: match along {
                Param::ETA_T => s.params.kappa2,
                _ => s.params.eta_t,
            },
            other_is_x,
            span: axis.span(),
            samples,
        }))
    }

    /// Whether `p` moves no steady state: its boundaries are lines across it.
    pub fn moves_nothing(p: Param) -> bool {
        p.rate_only() || matches!(p, Param::Tol | Param::DtMax | Param::TMax)
    }

    /// Where a curve of the paper's plane crosses the line: the values of `along`, in order.
    pub fn crossings(&self, points: &[(f64, f64)]) -> Vec<f64> {
        // (along, other) of a point.
        let split = |&(e, k): &(f64, f64)| match self.along {
            Param::ETA_T => (e, k),
            _ => (k, e),
        };
        let mut out: Vec<f64> = Vec::new();
        for w in points.windows(2) {
            let ((a0, o0), (a1, o1)) = (split(&w[0]), split(&w[1]));
            let (d0, d1) = (o0 - self.fixed, o1 - self.fixed);
            if o0 == o1 || d0 * d1 > 0.0 {
                continue;
            }
            let at = a0 + (a1 - a0) * d0 / (d0 - d1);
            if !out.iter().any(|x| (x - at).abs() < 1e-12) {
                out.push(at);
            }
        }
        out.sort_by(f64::total_cmp);
        out
    }

    /// The names of the sweep's plane's axes `(x, y)`.
    pub fn names(&self) -> (&'static str, &'static str) {
        if self.other_is_x {
            (self.other.name(), self.along.name())
        } else {
            (self.along.name(), self.other.name())
        }
    }

    /// A point of the sweep's plane from a value of the other axis and one of `along`.
    fn point(&self, other: f64, along: f64) -> (f64, f64) {
        if self.other_is_x {
            (other, along)
        } else {
            (along, other)
        }
    }

    /// The boundaries in the sweep's plane. `curves_at(base, n)` computes the paper-plane
    /// curves with the other axis at its value in `base` (or, for the grid, at `n`); it is
    /// called once per sample (`base`, `n` themselves for an axis that moves nothing).
    pub fn plane_curves(
        &self,
        base: &ModelParams,
        n: usize,
        mut curves_at: impl FnMut(&ModelParams, usize) -> Result<Vec<NamedCurve>, SweepError>,
    ) -> Result<Vec<NamedCurve>, SweepError> {
        let lines = Self::moves_nothing(self.other);
        // Each curve's k-th crossing, by (model, name, k): its points across the samples.
        let mut joined: BTreeMap<(String, String, usize), NamedCurve> = BTreeMap::new();
        for &g in &self.samples {
            let (at_base, at_n) = match self.other {
                _ if lines => (*base, n),
                Param::N => (*base, g as usize),
                p => (p.model().expect("a model parameter").with(base, g), n),
            };
            for c in curves_at(&at_base, at_n)? {
                for (k, at) in self.crossings(&c.points).into_iter().enumerate() {
                    let key = (c.model.as_str().to_string(), c.name.clone(), k);
                    let points = if lines {
                        vec![self.point(self.span.0, at), self.point(self.span.1, at)]
                    } else {
                        vec![self.point(g, at)]
                    };
                    joined
                        .entry(key)
                        .or_insert_with(|| NamedCurve {
                            points: Vec::new(),
                            ..c.clone()
                        })
                        .points
                        .extend(points);
                }
            }
        }
        Ok(joined.into_values().collect())
    }
}
