//! `droplet continue --modes K`: the MD branch of the paper's general model with shape modes
//! `2..K`, followed in `eta_t` or `kappa2` through its folds with the stability of every state
//! (`droplet_solver::continuation::mode_line`), written as a table and a picture.
use crate::error::SweepError;
use crate::pictures::branch_lines::BranchLine;
use crate::pictures::line_figure::{vs_parameter, Marker};
use droplet_solver::continuation::arclength::ArclengthOptions;
use droplet_solver::continuation::mode_branch::ModeLine;
use droplet_solver::continuation::mode_line::{follow_md, ModeBranch};
use droplet_solver::model::param::ModelParam;
use std::path::PathBuf;
use std::time::Instant;

/// A `K`-mode continuation: the line (its `k_max` the modes), its limits, written where.
#[derive(Debug, Clone)]
pub struct ModeContinuationStudy {
    pub out: PathBuf,
    pub line: ModeLine,
    /// Most states on the branch.
    pub max_points: usize,
    pub opts: ArclengthOptions,
}

/// What the study computed and wrote.
#[derive(Debug, Clone)]
pub struct ModeContinuationWritten {
    pub branch: ModeBranch,
    /// The line in words: `modes 2..3, kappa2 = 0.13, eta_t from 0.075 to 0.1`.
    pub description: String,
    pub files: Vec<PathBuf>,
    pub seconds: f64,
}

impl ModeContinuationStudy {
    /// The fixed one of `eta_t` and `kappa2`, and its value.
    pub fn fixed(&self) -> (&'static str, f64) {
        match self.line.parameter {
            ModelParam::Kappa2 => ("eta_t", self.line.base.eta_t),
            _ => ("kappa2", self.line.base.kappa2),
        }
    }

    /// The files' stem: `continuation_modes<K>_<fixed>_<value>`, then every other parameter
    /// that differs from its default and the friction law's exponent when it is not 0
    /// (`_eta_k_exponent_<p>`): a line of other parameters never takes another's files.
    pub fn stem(&self) -> String {
        let short = |v: f64| format!("{v:.9e}").parse::<f64>().unwrap_or(v);
        let mut parts = vec![format!("continuation_modes{}", self.line.k_max)];
        for (name, value) in
            crate::studies::continuation::fixed_parameters(&self.line.base, self.line.parameter)
        {
            parts.push(format!("{name}_{}", short(value)));
        }
        if self.line.eta_k_exponent != 0.0 {
            parts.push(format!(
                "eta_k_exponent_{}",
                short(self.line.eta_k_exponent)
            ));
        }
        parts.join("_")
    }

    /// Follows the branch, then writes `<stem>.parquet` and `<stem>.png/.svg` into `out`.
    pub fn run(&self) -> Result<ModeContinuationWritten, SweepError> {
        crate::store::atomic::create_output_dir(&self.out)?;
        let started = Instant::now();
        let branch = follow_md(&self.line, self.max_points, &self.opts)?;
        let seconds = started.elapsed().as_secs_f64();
        let (name, value) = self.fixed();
        let description = format!(
            "modes 2..{}, {name} = {value}, {} from {} to {}",
            self.line.k_max,
            self.line.parameter.name(),
            self.line.from,
            self.line.to
        );
        let stem = self.stem();
        let table = crate::tables::mode_continuation::write(
            &self.out,
            &stem,
            &branch,
            &description,
            self.line.n,
            &self.line.base,
        )?;
        let (lines, markers, vlines) = drawing(&branch);
        let mut files = vs_parameter(
            &self.out,
            &stem,
            &format!(
                "PDE (N = {}), MD with modes 2..{}, {name} = {value}: solid = stable, dashed = unstable",
                self.line.n, self.line.k_max
            ),
            self.line.parameter.name(),
            &markers,
            &lines,
            &vlines,
        )?;
        files.push(table);
        Ok(ModeContinuationWritten {
            branch,
            description,
            files,
            seconds,
        })
    }
}

/// The branch as pieces of one stability (solid stable, dashed unstable; the paper's
/// `s = |a2|`), a marker and a labelled vertical line at each fold.
fn drawing(branch: &ModeBranch) -> (Vec<BranchLine>, Vec<Marker>, Vec<(f64, String)>) {
    let mut lines: Vec<BranchLine> = Vec::new();
    for p in &branch.points {
        let stable = p.verdict.stable();
        let xyz = (p.at, p.v, p.a[0].abs());
        match lines.last_mut() {
            Some(line) if line.stable == stable => line.points.push(xyz),
            last => {
                // The pieces meet at the state where stability changes.
                if let Some(line) = last {
                    line.points.push(xyz);
                }
                lines.push(BranchLine {
                    key: "MD".into(),
                    points: vec![xyz],
                    stable,
                });
            }
        }
    }
    let folds: Vec<_> = branch.folds().collect();
    let markers = folds
        .iter()
        .map(|p| Marker {
            x: p.at,
            v: p.v,
            s: p.a[0].abs(),
            key: "MD".into(),
            bold: true,
        })
        .collect();
    let vlines = folds.iter().map(|p| (p.at, "SN".to_string())).collect();
    (lines, markers, vlines)
}
