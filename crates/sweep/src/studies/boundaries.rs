//! `droplet boundaries`: the full model's phase boundaries in a window of `(eta_t, kappa2)`
//! (the onsets of motion and deformation, the resting deformed droplet's onset of motion, the
//! MD fold and the MC onset; `droplet_solver::continuation::boundaries`), with the reduced
//! model's analytic ones, as `boundaries.parquet` and a picture; a sweep's phase map in the
//! same directory is redrawn with them.
use crate::error::SweepError;
use crate::pictures::map_figure::{boundary_picture, Curve};
use crate::spec::axes::{Param, ETA_T, KAPPA2};
use crate::studies::across::Across;
use crate::studies::pair::Pair;
use crate::tables::boundaries::{self as table, NamedCurve};
use droplet_solver::continuation::boundaries::boundaries;
use droplet_solver::continuation::window::Window;
use droplet_solver::contract::settings::{ModelKind, H0_PAPER};
use droplet_solver::model::params::ModelParams;
use droplet_solver::reduced::coefficients::Coefficients;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Half the width of the paper-plane window around a rate-only sweep's line ([`Across`]):
/// wide enough that the MD fold is found on a one-parameter line inside it and continued
/// across the sweep's line.
const ACROSS_HALF_WIDTH: f64 = 0.01;

/// Least samples of the ID onset lines across a sweep's line: where they cross it is
/// interpolated between samples, to about 1e-6 with 600 (about 1e-4 with 60). Across a
/// geometric axis the lines are computed once per sweep value, so with fewer.
const ACROSS_SAMPLES: (usize, usize) = (600, 200);

/// The paper's Fig. 2a window, the default without a sweep.
pub const FIG2A_WINDOW: ((f64, f64), (f64, f64)) = ((0.07, 0.10), (0.10, 0.17));

/// A boundaries study: where, at what resolution, written where.
#[derive(Debug, Clone)]
pub struct BoundaryStudy {
    pub out: PathBuf,
    pub eta_t: (f64, f64),
    pub kappa2: (f64, f64),
    /// The other parameters (the sweep's in `out`, else the defaults), at the window's corner.
    /// With shape modes `2..=base.modes`, `K > 2` (the paper's general model; 2 is the
    /// paper's), the full model's curves are those of the states on the x axis, computed in
    /// the paper's plane (also for the crossings of `across`); a `pair` is traced with two
    /// (`droplet_solver::continuation::window::Window::check` refuses more).
    pub base: ModelParams,
    pub h0: f64,
    /// Grid points per side.
    pub n: usize,
    /// Points of the ID onset line.
    pub samples: usize,
    /// The spec of the sweep in `out`, if there is one (its map is redrawn).
    pub sweep_spec: Option<String>,
    /// For a sweep outside the paper's plane: how its plane meets the paper's
    /// ([`crate::studies::across`]).
    pub across: Option<Across>,
    /// For a sweep in a plane of two model parameters that crossings do not give: the window
    /// its curves are continued in ([`crate::studies::pair`]; the reduced model's curves are
    /// then `across`'s crossings, where there is one).
    pub pair: Option<Pair>,
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
    /// The map was drawn from its tables: a finished map whose stored runs no longer give
    /// `missing` of its points (older numerics, unreadable); its pictures show the tables.
    pub from_tables: bool,
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
        let pair = match sweep.as_ref() {
            Some(s) => Pair::of(s, out)?,
            None => None,
        };
        let across = match sweep.as_ref() {
            // Two non-paper parameters have no crossings: the pair alone.
            Some(s) if pair.is_some() => Across::of(s, out).ok().flatten(),
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
            across.as_ref().filter(|a| a.along != p).map(|a| {
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
        let spec_params = sweep
            .as_ref()
            .map_or_else(ModelParams::default, |s| s.params);
        let base = match pair {
            // The pair's window sets its own axes; the others are the spec's.
            Some(_) => spec_params,
            None => ModelParams {
                eta_t: eta_t.0,
                kappa2: kappa2.0,
                ..spec_params
            },
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
            samples: match &across {
                Some(a) if Across::moves_nothing(a.other) => samples.max(ACROSS_SAMPLES.0),
                Some(_) => samples.max(ACROSS_SAMPLES.1),
                None => samples,
            },
            across,
            pair,
        })
    }

    /// The same study with shape modes `2..=modes`, refused where its window cannot be
    /// computed with them ([`Window::check`]).
    pub fn with_modes(self, modes: usize) -> Result<Self, SweepError> {
        let study = Self {
            base: self.base.with_modes(modes),
            ..self
        };
        let window = match &study.pair {
            Some(p) => p.window(&study.base, study.n),
            None => study.paper_window(&study.base, study.n),
        };
        window
            .check()
            .map_err(|e| SweepError::Invalid(format!("{}: {e}", study.out.display())))?;
        Ok(study)
    }

    /// The paper plane's window of the study at the parameters `base` and grid size `n`.
    fn paper_window(&self, base: &ModelParams, n: usize) -> Window {
        Window::paper(*base, n, self.eta_t, self.kappa2, self.samples)
    }

    /// The names of the plane the curves are drawn in: the paper's, or the sweep's in `out`.
    pub fn plane_names(&self) -> (&'static str, &'static str) {
        match (&self.pair, &self.across) {
            (Some(p), _) => p.names(),
            (None, Some(a)) => a.names(),
            (None, None) => (ETA_T, KAPPA2),
        }
    }

    /// Whether the curves are drawn in the paper's plane.
    pub fn in_paper_plane(&self) -> bool {
        self.pair.is_none() && self.across.is_none()
    }

    /// The grid sizes the full model's curves are computed at, in words.
    pub fn grid_words(&self) -> String {
        match &self.across {
            Some(a) if a.other == Param::N => {
                let ns: Vec<String> = a.samples.iter().map(|n| n.to_string()).collect();
                format!("N = {} (the sweep's)", ns.join(", "))
            }
            _ => format!("N = {}", self.n),
        }
    }

    /// The window, in words (for messages and the table's metadata).
    pub fn window(&self) -> String {
        match &self.pair {
            Some(p) => format!(
                "{} {:?}, {} {:?}",
                p.x.param.name(),
                p.x.range,
                p.y.param.name(),
                p.y.range
            ),
            None => format!("eta_t {:?}, kappa2 {:?}", self.eta_t, self.kappa2),
        }
    }

    /// The full model's boundaries (`pde`, at grid size `n`) and the reduced model's (`ode`)
    /// in the paper-plane window, at the parameters `base`.
    fn curves_at(&self, base: &ModelParams, n: usize) -> Result<Vec<NamedCurve>, SweepError> {
        let pde = boundaries(&self.paper_window(base, n))?;
        Ok(NamedCurve::from_boundaries(ModelKind::Pde, &pde)
            .into_iter()
            .chain(self.ode_curves_at(base))
            .collect())
    }

    /// The reduced model's boundaries in the paper-plane window, at the parameters `base`.
    fn ode_curves_at(&self, base: &ModelParams) -> Vec<NamedCurve> {
        let ode = droplet_solver::reduced::boundaries::boundaries(
            &Coefficients::new(base.radius, self.h0),
            self.eta_t,
            self.kappa2,
        );
        NamedCurve::from_boundaries(ModelKind::Ode, &ode)
    }

    /// Computes the boundaries and writes `boundaries.parquet` and `boundaries.png/.svg`
    /// (and the sweep's redrawn pictures) into `out`.
    pub fn run(&self) -> Result<BoundariesWritten, SweepError> {
        // A sweep's directory is held from the start: refused while a sweep works in it,
        // before anything is computed or written.
        let held = match &self.sweep_spec {
            Some(_) if !crate::tables::read::is_tables_only(&self.out) => {
                Some(crate::store::run_store::Store::open_idle(&self.out)?)
            }
            _ => None,
        };
        crate::store::atomic::create_output_dir(&self.out)?;
        let started = Instant::now();
        let curves = match (&self.pair, &self.across) {
            (Some(p), across) => {
                let mut curves = p.curves(&self.base, self.n)?;
                if let Some(a) = across {
                    curves.extend(
                        a.plane_curves(&self.base, self.n, |b, _| Ok(self.ode_curves_at(b)))?,
                    );
                }
                curves
            }
            (None, None) => self.curves_at(&self.base, self.n)?,
            (None, Some(a)) => a.plane_curves(&self.base, self.n, |b, n| self.curves_at(b, n))?,
        };
        let seconds = started.elapsed().as_secs_f64();
        let path = self.out.join(table::FILE);
        let names = self.plane_names();
        table::write_in(
            &path,
            names,
            &curves,
            self.sweep_spec.as_deref(),
            vec![
                ("n".into(), self.n.to_string()),
                ("window".into(), self.window()),
                ("modes".into(), self.base.modes.to_string()),
            ],
        )?;
        let drawn: Vec<Curve> = curves.iter().map(Curve::of).collect();
        let mut files = if !self.in_paper_plane() {
            // In the sweep's plane: drawn over its map below.
            Vec::new()
        } else {
            boundary_picture(
                &self.out,
                "boundaries",
                &match self.base.modes {
                    2 => format!("Phase boundaries: PDE (N = {}) solid, ODE dashed", self.n),
                    k => format!(
                        "Phase boundaries: PDE with modes 2..{k} (N = {}, x-axis states) solid, ODE dashed",
                        self.n
                    ),
                },
                &drawn,
                self.eta_t,
                self.kappa2,
            )?
        };
        files.push(path);
        let (missing, from_tables) = match self.sweep_spec {
            Some(_) => self.draw_over_map(held.as_ref(), &mut files)?,
            None => (None, false),
        };
        Ok(BoundariesWritten {
            curves,
            files,
            seconds,
            missing,
            from_tables,
        })
    }

    /// Redraws the sweep's map in `out` with the curves just written (from the tables when
    /// the store's runs are stale), adding its files to `files`: the points the map lacks and
    /// whether it came from the tables.
    fn draw_over_map(
        &self,
        held: Option<&crate::store::run_store::Store>,
        files: &mut Vec<std::path::PathBuf>,
    ) -> Result<(Option<(usize, usize)>, bool), SweepError> {
        let mut from_tables = false;
        use crate::pictures::sweep_pictures::{plot, plot_in, plot_tables};
        let map = match held.map(plot_in) {
            Some(Err(SweepError::StaleRuns {
                missing: m, points, ..
            })) => {
                from_tables = true;
                crate::pictures::sweep_pictures::Drawn {
                    missing: m,
                    points,
                    ..plot_tables(&self.out)?
                }
            }
            Some(drawn) => drawn?,
            None => plot(&self.out)?,
        };
        for f in map.files {
            if !files.contains(&f) {
                files.push(f);
            }
        }
        Ok((Some((map.missing, map.points)), from_tables))
    }
}
