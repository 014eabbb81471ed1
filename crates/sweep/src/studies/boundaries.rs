//! `droplet boundaries`: the full model's phase boundaries in a window of `(eta_t, kappa2)`
//! (the onsets of motion and deformation, the resting deformed droplet's onset of motion, the
//! MD fold and the MC onset; `droplet_solver::continuation::boundaries`), with the reduced
//! model's analytic ones, as `boundaries.parquet` and a picture; a sweep's phase map in the
//! same directory is redrawn with them.
use crate::error::SweepError;
use crate::pictures::map_figure::{boundary_picture, Curve};
use crate::spec::axes::Param;
use crate::tables::boundaries::{self as table, NamedCurve};
use droplet_solver::contract::settings::{ModelKind, H0_PAPER};
use droplet_solver::model::params::ModelParams;
use droplet_solver::reduced::coefficients::Coefficients;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Half the width of the paper-plane window around a rate-only sweep's line ([`Across`]):
/// wide enough that the MD fold is found on a one-parameter line inside it and continued
/// across the sweep's line.
const ACROSS_HALF_WIDTH: f64 = 0.01;

/// Least samples of the ID onset lines across a rate-only sweep's line: where they cross it
/// is interpolated between samples, to about 1e-6 with this many (about 1e-4 with 60).
const ACROSS_SAMPLES: usize = 600;

/// The paper's Fig. 2a window, the default without a sweep.
pub const FIG2A_WINDOW: ((f64, f64), (f64, f64)) = ((0.07, 0.10), (0.10, 0.17));

/// A boundaries study: where, at what resolution, written where.
#[derive(Debug, Clone)]
pub struct BoundaryStudy {
    pub out: PathBuf,
    pub eta_t: (f64, f64),
    pub kappa2: (f64, f64),
    /// The other parameters (the sweep's in `out`, else the defaults), at the window's corner.
    pub base: ModelParams,
    pub h0: f64,
    /// Grid points per side.
    pub n: usize,
    /// Points of the ID onset line.
    pub samples: usize,
    /// The spec of the sweep in `out`, if there is one (its map is redrawn).
    pub sweep_spec: Option<String>,
    /// For a sweep in a plane of a rate-only parameter and `eta_t` or `kappa2`: the line of
    /// the paper's plane it lies on.
    pub across: Option<Across>,
}

/// A sweep's line in the paper's plane: the sweep varies `along` (`eta_t` or `kappa2`) and the
/// rate-only parameter `rate` (`eta2` or `mass`, [`Param::rate_only`]), and fixes the other of
/// `eta_t`, `kappa2` at `fixed`. The boundaries where a real eigenvalue crosses zero do not
/// depend on `rate`, so each crosses the sweep's plane as a line at a fixed value of `along`.
/// (A Hopf point would depend on `rate`; none was found on the continuation lines, and
/// `droplet continue --param mass` or `--param eta2` looks for them along a branch.)
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Across {
    pub rate: Param,
    pub along: Param,
    pub fixed: f64,
}

impl Across {
    /// The line of the sweep `s` (in `out`): `None` in the paper's plane; refused in a plane
    /// where the boundaries cannot be drawn.
    fn of(s: &crate::spec::SweepSpec, out: &Path) -> Result<Option<Self>, SweepError> {
        let plane = s.grid.plane();
        if plane.is_paper() {
            return Ok(None);
        }
        let Some((rate, along)) = plane.across_rate() else {
            let names: Vec<&str> = plane.params().iter().map(|p| p.name()).collect();
            return Err(SweepError::Invalid(format!(
                "{}: the sweep there is in ({}); the exact boundaries are computed in the \
                 paper's plane (eta_t, kappa2), and drawn over a sweep in that plane or in a \
                 plane of eta2 or mass with eta_t or kappa2; give another --out",
                out.display(),
                names.join(", ")
            )));
        };
        let fixed = match along {
            Param::ETA_T => s.params.kappa2,
            _ => s.params.eta_t,
        };
        Ok(Some(Self { rate, along, fixed }))
    }

    /// Where a curve of the paper's plane crosses the line: the values of `along`.
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
        out
    }

    /// A value of `along` as a point of the paper's plane.
    pub fn point(&self, along: f64) -> (f64, f64) {
        match self.along {
            Param::ETA_T => (along, self.fixed),
            _ => (self.fixed, along),
        }
    }
}

/// What a boundaries study computed and wrote.
#[derive(Debug, Clone)]
pub struct BoundariesWritten {
    /// The full model's curves (`model` = pde) and the reduced model's (ode).
    pub curves: Vec<NamedCurve>,
    pub files: Vec<PathBuf>,
    /// Wall seconds of the full model's boundaries.
    pub seconds: f64,
    /// The redrawn sweep map's points drawn as missing, and its points (a sweep in `out`).
    pub missing: Option<(usize, usize)>,
}

impl BoundaryStudy {
    /// A study into `out`: the window given, else the sweep's in `out` (if it spans both
    /// axes), else [`FIG2A_WINDOW`]; the other parameters the sweep's, else the defaults.
    pub fn new(
        out: &Path,
        eta_t: Option<(f64, f64)>,
        kappa2: Option<(f64, f64)>,
        n: usize,
        samples: usize,
    ) -> Result<Self, SweepError> {
        // A sweep's directory, or a committed map's (its spec in its tables' metadata).
        let sweep = crate::spec::load_stored(out).ok().or_else(|| {
            crate::tables::read::is_tables_only(out)
                .then(|| crate::tables::read::stored_spec(&out.join(crate::tables::read::POINTS)))
                .and_then(Result::ok)
        });
        let across = match sweep.as_ref() {
            Some(s) => Across::of(s, out)?,
            None => None,
        };
        let swept = |p: Param| {
            sweep
                .as_ref()
                .and_then(|s| s.grid.axis(p))
                .filter(|a| a.values.len() > 1)
                .map(|a| a.span())
        };
        // Across a rate-only plane: a thin window around the sweep's line.
        let around = |p: Param| {
            across.filter(|a| a.along != p).map(|a| {
                (
                    (a.fixed - ACROSS_HALF_WIDTH).max(0.5 * a.fixed),
                    a.fixed + ACROSS_HALF_WIDTH,
                )
            })
        };
        let eta_t = eta_t
            .or_else(|| swept(Param::ETA_T))
            .or_else(|| around(Param::ETA_T))
            .unwrap_or(FIG2A_WINDOW.0);
        let kappa2 = kappa2
            .or_else(|| swept(Param::KAPPA2))
            .or_else(|| around(Param::KAPPA2))
            .unwrap_or(FIG2A_WINDOW.1);
        let base = ModelParams {
            eta_t: eta_t.0,
            kappa2: kappa2.0,
            ..sweep
                .as_ref()
                .map_or_else(ModelParams::default, |s| s.params)
        };
        base.validate()
            .map_err(|e| SweepError::Invalid(e.to_string()))?;
        Ok(Self {
            out: out.to_path_buf(),
            eta_t,
            kappa2,
            base,
            h0: sweep.as_ref().map_or(H0_PAPER, |s| s.solver.h0),
            n,
            sweep_spec: sweep.map(|s| s.source),
            samples: if across.is_some() {
                samples.max(ACROSS_SAMPLES)
            } else {
                samples
            },
            across,
        })
    }

    /// Computes the boundaries and writes `boundaries.parquet` and `boundaries.png/.svg`
    /// (and the sweep's redrawn pictures) into `out`.
    pub fn run(&self) -> Result<BoundariesWritten, SweepError> {
        crate::store::atomic::create_output_dir(&self.out)?;
        let started = Instant::now();
        let window = droplet_solver::continuation::boundaries::Window {
            base: self.base,
            n: self.n,
            eta_t: self.eta_t,
            kappa2: self.kappa2,
            id_samples: self.samples,
        };
        let pde = droplet_solver::continuation::boundaries::boundaries(&window)?;
        let seconds = started.elapsed().as_secs_f64();
        let ode = droplet_solver::reduced::boundaries::boundaries(
            &Coefficients::new(self.base.radius, self.h0),
            self.eta_t,
            self.kappa2,
        );
        let mut curves: Vec<NamedCurve> = NamedCurve::from_boundaries(ModelKind::Pde, &pde)
            .into_iter()
            .chain(NamedCurve::from_boundaries(ModelKind::Ode, &ode))
            .collect();
        if let Some(a) = self.across {
            // Only where each curve crosses the sweep's line.
            curves = curves
                .into_iter()
                .filter_map(|c| {
                    let points: Vec<(f64, f64)> = a
                        .crossings(&c.points)
                        .into_iter()
                        .map(|x| a.point(x))
                        .collect();
                    (!points.is_empty()).then_some(NamedCurve { points, ..c })
                })
                .collect();
        }
        let path = self.out.join(table::FILE);
        table::write(
            &path,
            &curves,
            self.sweep_spec.as_deref(),
            vec![
                ("n".into(), self.n.to_string()),
                (
                    "window".into(),
                    format!("eta_t {:?}, kappa2 {:?}", self.eta_t, self.kappa2),
                ),
            ],
        )?;
        let drawn: Vec<Curve> = curves.iter().map(Curve::of).collect();
        let mut files = if self.across.is_some() {
            // Crossing points, drawn as lines over the sweep's map below.
            Vec::new()
        } else {
            boundary_picture(
                &self.out,
                "boundaries",
                &format!("Phase boundaries: PDE (N = {}) solid, ODE dashed", self.n),
                &drawn,
                self.eta_t,
                self.kappa2,
            )?
        };
        files.push(path);
        let mut missing = None;
        if self.sweep_spec.is_some() {
            let map = crate::pictures::sweep_pictures::plot(&self.out)?;
            missing = Some((map.missing, map.points));
            for f in map.files {
                if !files.contains(&f) {
                    files.push(f);
                }
            }
        }
        Ok(BoundariesWritten {
            curves,
            files,
            seconds,
            missing,
        })
    }
}
