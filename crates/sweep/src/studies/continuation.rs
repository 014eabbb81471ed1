//! `droplet continue`: branches of steady states of the full model followed in one parameter
//! (pseudo-arclength, through folds), with the stability of every state and the bifurcation
//! points located on them (`droplet_solver::continuation`), written as tables and a picture.
use crate::error::SweepError;
use droplet_solver::continuation::branch::{follow, Branch, BranchPoint, Line, EVENT_PRECISION};
use droplet_solver::continuation::problem::Family;
use droplet_solver::error::SolverError;
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::model::{param::ModelParam, params::ModelParams};
use std::path::PathBuf;
use std::time::Instant;

/// A continuation study: the line, the families followed on it, written where.
#[derive(Debug, Clone)]
pub struct ContinuationStudy {
    pub out: PathBuf,
    pub line: Line,
    /// The families to follow; with more than one, a family with no state on the line is
    /// skipped, with one it is an error.
    pub families: Vec<Family>,
    pub mirror: MirrorLine,
}

/// Where a study is, for a progress line.
#[derive(Debug, Clone, Copy)]
pub enum Progress {
    Following(Family),
    Followed {
        states: usize,
        events: usize,
        seconds: f64,
    },
    NoneOnLine,
}

/// A bifurcation point not located to [`EVENT_PRECISION`] in the varied parameter.
#[derive(Debug, Clone)]
pub struct ImpreciseEvent {
    pub family: Family,
    pub kind: String,
    /// The varied parameter's value there.
    pub at: f64,
    pub precision: f64,
}

/// What a continuation study computed and wrote.
#[derive(Debug, Clone)]
pub struct ContinuationWritten {
    pub branches: Vec<Branch>,
    /// The line in words: `kappa2 = 0.13, eta_t from 0.07 to 0.1`.
    pub description: String,
    pub files: Vec<PathBuf>,
    pub seconds: f64,
    /// Events the tables mark as imprecise (the command then exits 1).
    pub imprecise: Vec<ImpreciseEvent>,
}

impl ContinuationStudy {
    /// The fixed parameters that name the line: on the paper's lines the other of `eta_t`
    /// and `kappa2`; on a line in another parameter `eta_t`, `kappa2` and every other
    /// parameter that differs from its default.
    pub fn fixed(&self) -> Vec<(&'static str, f64)> {
        fixed_parameters(&self.line.base, self.line.parameter)
    }

    /// The fixed parameters in words: `eta_t = 0.085, kappa2 = 0.13`.
    fn fixed_text(&self) -> String {
        let parts: Vec<String> = self
            .fixed()
            .iter()
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        parts.join(", ")
    }

    /// The varied parameter's name.
    pub fn varied(&self) -> &'static str {
        self.line.parameter.name()
    }

    /// The varied parameter's value at `p`.
    pub fn at(&self, p: &BranchPoint) -> f64 {
        p.at
    }

    /// The files' common stem: `continuation_<fixed>_<value>` (+ `_diagonal`) on the
    /// paper's lines, `continuation_<varied>_<fixed>_<value>...` on the others, each value to
    /// ten significant digits (short and stable for any value within the limits); with shape
    /// modes `2..K`, `K > 2`, `continuation_modes<K>_...`, and the friction law's exponent
    /// when it is not 0 (`_eta_k_exponent_<p>`): a line of another model never takes
    /// another's files.
    pub fn stem(&self) -> String {
        let short = |v: f64| format!("{v:.9e}").parse::<f64>().unwrap_or(v);
        let mut parts = vec!["continuation".to_string()];
        if self.line.base.modes != 2 {
            parts.push(format!("modes{}", self.line.base.modes));
        }
        if !matches!(self.line.parameter, ModelParam::EtaT | ModelParam::Kappa2) {
            parts.push(self.varied().to_string());
        }
        for (name, value) in self.fixed() {
            parts.push(format!("{name}_{}", short(value)));
        }
        if self.line.base.eta_k_exponent != 0.0 {
            parts.push(format!(
                "eta_k_exponent_{}",
                short(self.line.base.eta_k_exponent)
            ));
        }
        if self.mirror == MirrorLine::Diagonal {
            parts.push("diagonal".into());
        }
        parts.join("_")
    }

    /// Follows every family, then writes `<stem>.parquet`, `<stem>_events.parquet` and
    /// `<stem>.png/.svg` into `out`; `progress` hears of each family as it goes.
    pub fn run(
        &self,
        progress: &mut dyn FnMut(Progress),
    ) -> Result<ContinuationWritten, SweepError> {
        crate::store::atomic::create_output_dir(&self.out)?;
        let started = Instant::now();
        let mut branches: Vec<Branch> = Vec::new();
        for f in &self.families {
            let t0 = Instant::now();
            progress(Progress::Following(*f));
            match follow(&self.line, *f, self.mirror) {
                Ok(b) => {
                    progress(Progress::Followed {
                        states: b.points.len(),
                        events: b.events.len(),
                        seconds: t0.elapsed().as_secs_f64(),
                    });
                    branches.push(b);
                }
                Err(SolverError::NoBranch { .. }) if self.families.len() > 1 => {
                    progress(Progress::NoneOnLine);
                }
                Err(e) => return Err(e.into()),
            }
        }
        let seconds = started.elapsed().as_secs_f64();
        let fixed = self.fixed_text();
        let description = format!(
            "{fixed}, {} from {} to {}",
            self.varied(),
            self.line.from,
            self.line.to
        );
        let stem = self.stem();
        let tables = crate::tables::continuation::write(
            &self.out,
            &stem,
            &branches,
            &description,
            &self.line,
        )?;
        let mut files = crate::pictures::branch_pictures::continuation(
            &self.out,
            &stem,
            &branches,
            self.line.parameter,
            &format!(
                "PDE (N = {}{}), {fixed}: solid = stable, dashed = unstable",
                self.line.n,
                if self.line.base.modes == 2 {
                    String::new()
                } else {
                    format!(", modes 2..{}", self.line.base.modes)
                }
            ),
        )?;
        files.extend(tables);
        let imprecise = branches
            .iter()
            .flat_map(|b| b.events.iter().map(move |e| (b, e)))
            .filter(|(_, e)| e.precision.is_nan() || e.precision > EVENT_PRECISION)
            .map(|(b, e)| ImpreciseEvent {
                family: b.family,
                kind: e.kind.to_string(),
                at: self.at(&e.point),
                precision: e.precision,
            })
            .collect();
        Ok(ContinuationWritten {
            branches,
            description,
            files,
            seconds,
            imprecise,
        })
    }
}

/// The parameters a line in `varied` holds fixed, as its files' names and tables give them:
/// the other of `eta_t` and `kappa2` (both on a line in another parameter), then every other
/// parameter that differs from its default (`--set sigma=0.05` on the paper's line is a line
/// of its own, never the default line's files).
pub(crate) fn fixed_parameters(b: &ModelParams, varied: ModelParam) -> Vec<(&'static str, f64)> {
    let default = ModelParams::default();
    let plane = |p: ModelParam| matches!(p, ModelParam::EtaT | ModelParam::Kappa2);
    ModelParam::ALL
        .into_iter()
        .filter(|&p| p != varied)
        .filter(|&p| plane(p) || p.get(b) != p.get(&default))
        .map(|p| (p.name(), p.get(b)))
        .collect()
}
