//! `droplet continue`: branches of steady states of the full model followed in one parameter,
//! with their stability and bifurcation points (the PDE's Fig. 3b).
use super::{print_json, CliError};
use droplet_solver::continuation::arclength::ArclengthOptions;
use droplet_solver::continuation::{branch::Line, branch::EVENT_PRECISION, problem::Family};
use droplet_sweep::studies::continuation::{
    ContinuationStudy, ContinuationWritten, ImpreciseEvent, Progress,
};
use std::path::PathBuf;

/// Follow branches of steady states in one parameter, with stability and bifurcations.
///
/// Follow steady states of the full model (field included, N x N spectral grid) as roots of
/// the co-moving force balance, by pseudo-arclength continuation through folds in any model
/// parameter (--param, the others fixed by --set; --kappa2 K and --eta-t E are the paper's
/// lines), with the linear stability of every state (eigenvalues with Re > -1 of the 2K x 2K
/// nonlinear eigenproblem, 4 x 4 with the paper's two modes; the near-neutral rotation mode,
/// a box effect, is reported apart and left out of the verdict), for the model with shape
/// modes 2..K (--modes). Pitchfork (P), saddle-node (SN) and Hopf (H) points are
/// located on the branch to ~1e-10 in the parameter (R: where the rotation mode's rate passes
/// 0.05 and the verdict counts it, no eigenvalue crossing zero). Writes DIR/<stem>.parquet (every state),
/// DIR/<stem>_events.parquet and DIR/<stem>.png/.svg (solid stable, dashed unstable), with
/// <stem> = continuation_<fixed parameter>_<value> on the paper's lines,
/// continuation_<varied>_eta_t_<E>_kappa2_<K>[_<other set parameter>_<value>...] on the others
/// (+ _diagonal for --axis diagonal).
#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "Examples:\n  droplet continue --kappa2 0.13 --from 0.070 --to 0.100 --out results/continuation    # all branches, vary eta_t\n  droplet continue --eta-t 0.085 --from 0.100 --to 0.170 --out results/continuation   # vary kappa2\n  droplet continue --branch md --kappa2 0.13 --from 0.07 --to 0.1 --json             # the MD branch and its fold\n  droplet continue --param mass --set eta_t=0.078,kappa2=0.13 --from 0.01 --to 1    # in the inertia: stability only\n  droplet continue --modes 3 --kappa2 0.13 --from 0.075 --to 0.1 --n 96 --json      # every branch with modes 2..3"
)]
pub struct Args {
    /// Which branch: all, ic, id, md (moving along its minor axis), md-major.
    #[arg(long, default_value = "all")]
    pub(super) branch: String,
    #[command(flatten)]
    pub(super) line: super::param_line::ParamLineArgs,
    /// The mirror axis the states lie on: x (motion along x), or diagonal.
    #[arg(long, default_value = "x")]
    pub(super) axis: String,
    /// Grid points per side.
    #[arg(long, default_value_t = 192)]
    pub(super) n: usize,
    /// Inertia m (> 0: it scales the eigenvalues, not the states; default 0.1).
    #[arg(long)]
    pub(super) mass: Option<f64>,
    /// Most states per branch and direction.
    #[arg(long, default_value_t = 400)]
    pub(super) max_points: usize,
    /// Longest continuation step (arclength in (v, shape, parameter scaled to [0, 1])).
    #[arg(long, default_value_t = 0.03)]
    pub(super) ds_max: f64,
    /// Shape modes 2..K (the paper's general model; default 2, the paper's): every branch,
    /// axis and parameter as with two modes; the states hold the modes their symmetry allows
    /// (MD every one, ID the even ones, IC the multiples of 4 the square box drives). The
    /// files are DIR/continuation_modes<K>_..., their tables with a3..aK, b3..bK after the
    /// 2-mode columns. K from 2 to 16 and at most pi R N / (4 L).
    #[arg(long, default_value_t = 2)]
    pub(super) modes: usize,
    /// With --modes K > 2: the friction law of the modes k >= 3, eta_k = eta2 (k/2)^P (default
    /// 0: every mode eta2; -1: the dissipation of the mode's own flow); from -4 to 4. It moves
    /// the eigenvalues of the verdicts, not the branch or its folds.
    #[arg(
        long,
        value_name = "P",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub(super) eta_k_exponent: f64,
    /// Output directory.
    #[arg(long, default_value = "out/continuation")]
    pub(super) out: PathBuf,
    /// Print one JSON object, the same keys for every K (modes, eta_k_exponent, line, n,
    /// seconds, branches [{branch, mirror, points, stable_points, ends}], events [{kind, what,
    /// branch, mirror, parameter, at, eta_t, kappa2, v, s, a_k [a2..aK], b_k [b2..bK],
    /// eigenvalue, precision}], files).
    #[arg(long)]
    pub(super) json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    check_common(&a)?;
    let study = study_of(&a)?;
    let axis = a.axis.clone();
    let done = study.run(&mut |p| match p {
        Progress::Following(f) => err!("following {} ({axis}) ... ", f.as_str()),
        Progress::Followed {
            states,
            events,
            seconds,
        } => errln!("{states} states, {events} events in {seconds:.1} s"),
        Progress::NoneOnLine => errln!("none on this line"),
    })?;
    let varied = study.varied();
    if a.json {
        print_json(&json_summary(&done, &study.line, varied));
    } else {
        print_text(&study, &done);
    }
    precise_events(&done.imprecise, varied)
}

/// The grid, the number of states and the step.
fn check_common(a: &Args) -> Result<(), CliError> {
    super::check_grid(a.n)?;
    if !(2..=100_000).contains(&a.max_points) {
        return Err(CliError::usage(format!(
            "invalid --max-points {}: from 2 to 100000",
            a.max_points
        )));
    }
    if !(a.ds_max > 0.0 && a.ds_max <= 0.5) {
        return Err(CliError::usage(format!(
            "invalid --ds-max {}: a number in (0, 0.5]",
            a.ds_max
        )));
    }
    Ok(())
}

/// The study the arguments ask for, every value checked.
fn study_of(a: &Args) -> Result<ContinuationStudy, CliError> {
    let mirror = super::mirror_axis(&a.axis)?;
    let families: Vec<Family> = if a.branch == "all" {
        vec![Family::IC, Family::ID, Family::MdMinor, Family::MdMajor]
    } else {
        vec![a
            .branch
            .parse()
            .map_err(|e: String| CliError::usage(format!("invalid --branch: {e}, or all")))?]
    };
    let (parameter, base) = a.line.line(a.mass)?;
    let base = droplet_solver::model::params::ModelParams {
        modes: a.modes,
        eta_k_exponent: a.eta_k_exponent,
        ..base
    };
    base.validate()?;
    droplet_solver::contract::limits::check_modes(&base, a.n, a.modes)?;
    Ok(ContinuationStudy {
        out: a.out.clone(),
        line: Line {
            base,
            n: a.n,
            parameter,
            from: a.line.span.from,
            to: a.line.span.to,
            max_points: a.max_points,
            opts: ArclengthOptions {
                ds_max: a.ds_max,
                ..ArclengthOptions::default()
            },
        },
        families,
        mirror,
    })
}

/// The text report: each branch with its states and events, the files, the time.
fn print_text(study: &ContinuationStudy, done: &ContinuationWritten) {
    let varied = study.varied();
    for b in &done.branches {
        outln!(
            "{:<14} {:>4} states ({} stable); ends: {} | {}",
            b.family.as_str(),
            b.points.len(),
            b.points.iter().filter(|p| p.verdict.stable()).count(),
            b.ends[0],
            b.ends[1]
        );
        for e in &b.events {
            outln!(
                "  {:>2} at {varied} = {:.9}  v = {:.6}  s = {:.6}  ({}){}",
                e.kind,
                study.at(&e.point),
                e.point.v,
                e.point.s,
                e.what,
                if study.line.base.modes == 2 {
                    String::new()
                } else {
                    format!("  a_k {:?}", e.point.a_k())
                }
            );
        }
    }
    for f in &done.files {
        outln!("wrote {}", f.display());
    }
    outln!("{:.1} s", done.seconds);
}

/// The `--json` object: the line, the branches, every event with its precision, the files.
fn json_summary(done: &ContinuationWritten, line: &Line, varied: &str) -> serde_json::Value {
    let events: Vec<_> = done
        .branches
        .iter()
        .flat_map(|b| {
            b.events.iter().map(move |e| {
                serde_json::json!({
                    "kind": e.kind, "what": e.what, "branch": b.family.as_str(),
                    "mirror": b.mirror, "parameter": varied, "at": e.point.at,
                    "eta_t": e.point.eta_t, "kappa2": e.point.kappa2,
                    "v": e.point.v, "s": e.point.s, "a_k": e.point.a_k(),
                    "b_k": e.point.b_k(), "eigenvalue": e.eigenvalue,
                    "precision": e.precision,
                })
            })
        })
        .collect();
    let summary: Vec<_> = done
        .branches
        .iter()
        .map(|b| {
            serde_json::json!({
                "branch": b.family.as_str(), "mirror": b.mirror, "points": b.points.len(),
                "stable_points": b.points.iter().filter(|p| p.verdict.stable()).count(),
                "ends": b.ends,
            })
        })
        .collect();
    serde_json::json!({
        "modes": line.base.modes, "eta_k_exponent": line.base.eta_k_exponent,
        "line": done.description, "n": line.n,
        "seconds": done.seconds, "branches": summary, "events": events, "files": done.files,
    })
}

/// An error (exit 1) naming every event not located to [`EVENT_PRECISION`] in the varied
/// parameter; the tables mark them in their `precision` column.
fn precise_events(imprecise: &[ImpreciseEvent], varied: &str) -> Result<(), CliError> {
    if imprecise.is_empty() {
        return Ok(());
    }
    let named: Vec<String> = imprecise
        .iter()
        .map(|e| {
            format!(
                "{} {} at {varied} = {} only to {:e}",
                e.family.as_str(),
                e.kind,
                e.at,
                e.precision
            )
        })
        .collect();
    Err(CliError {
        message: format!(
            "{} bifurcation point(s) could not be located to {EVENT_PRECISION:e} in {varied} \
             ({}); the tables mark them in their `precision` column: follow a shorter line \
             around them (--from/--to) or lower --ds-max",
            imprecise.len(),
            named.join("; ")
        ),
        code: 1,
    })
}
