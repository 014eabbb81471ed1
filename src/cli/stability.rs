//! `droplet stability`: one named steady state as a root, and its leading eigenvalues.
use super::param_line::parse_set;
use super::{print_json, CliError};
use droplet_solver::model::param::ModelParam;
use droplet_solver::model::params::ModelParams;
use droplet_solver::roots::named_state::{find, ic_thresholds, IcThresholds, StateKind};
use serde::Serialize;

/// Compute one steady state directly, with its linear stability.
///
/// Compute a steady state of the full model directly (Newton on the co-moving force balance,
/// started from the reduced model's state or from --seed) and its linear stability, field
/// included: every eigenvalue with Re > -1 (the field's own modes decay at rate >= 1), from
/// the 4 x 4 nonlinear eigenproblem det(lambda M - E - C (lambda - D)^-1 B) = 0. A state with
/// an eigenvalue of positive real part is unstable. Moving and deformed states have one
/// near-neutral eigenvalue (the rotation of the direction of motion or of the long axis,
/// weakly broken by the periodic box); it is listed with the others, identified by its mode
/// (`rotation`), and left out of `stable` / `unstable`, which decide the state's class.
/// For the resting disk it also prints where the disk loses stability: the eta_t below which
/// it starts to move and the kappa2 below which it deforms, exact at the grid (no scan).
#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "Examples:\n  droplet stability --eta-t 0.085 --kappa2 0.13 --state ic          # stable resting disk\n  droplet stability --eta-t 0.0763 --kappa2 0.16 --state ic --json  # just past the onset of motion: unstable\n  droplet stability --eta-t 0.085 --kappa2 0.112 --state md         # Fig. 1c, moving along its minor axis\n  droplet stability --eta-t 0.085 --kappa2 0.116 --state id --axis diagonal\n  droplet stability --eta-t 0.078 --kappa2 0.13 --state ic --set radius=1.05,sigma=0.025"
)]
pub struct Args {
    /// Translational friction eta_t (> 0).
    #[arg(long)]
    eta_t: f64,
    /// Mode-2 stiffness kappa2 (>= 0).
    #[arg(long)]
    kappa2: f64,
    /// The state: ic (resting disk), id (resting, deformed), md (moving along its minor axis).
    #[arg(long, default_value = "md")]
    state: StateKind,
    /// The mirror axis the state lies on: x, or diagonal (motion along (1, 1), long axis on it).
    #[arg(long, default_value = "x")]
    axis: String,
    /// Newton's starting point: speed along the axis and shape amplitude, e.g. 0.6,-0.27.
    #[arg(long, value_name = "V,SHAPE", allow_hyphen_values = true)]
    seed: Option<String>,
    /// Grid points per side.
    #[arg(long, default_value_t = 192)]
    n: usize,
    /// Inertia m (> 0 here).
    #[arg(long, default_value_t = 0.1)]
    mass: f64,
    /// Other model parameters: NAME=VALUE[,NAME=VALUE...] of eta2, radius, sigma, box_len
    /// (default: eta2 0.1, R 1, sigma 0.03, box_len 7), e.g. radius=1.02,sigma=0.025.
    #[arg(long, value_name = "NAME=VALUE,...")]
    set: Option<String>,
    /// Print one JSON object (keys: state, axis, eta_t, kappa2, n, params {eta_t, kappa2,
    /// eta2, mass, radius, sigma, box_len}, vx, vy, a2, b2, v, s, residual, eigenvalues [{re, im}], rotation (the rotation mode's eigenvalue or null),
    /// unstable (rotation excluded), stable, ic_thresholds {eta_t, kappa2_a2,
    /// kappa2_b2} for the resting disk, else null).
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Eigen {
    re: f64,
    im: f64,
}

#[derive(Serialize)]
struct Report {
    state: StateKind,
    axis: String,
    eta_t: f64,
    kappa2: f64,
    n: usize,
    params: ModelParams,
    vx: f64,
    vy: f64,
    a2: f64,
    b2: f64,
    v: f64,
    s: f64,
    residual: f64,
    eigenvalues: Vec<Eigen>,
    /// The near-neutral rotation mode's eigenvalue (moving or deformed states).
    rotation: Option<f64>,
    /// Eigenvalues with a positive real part, the rotation mode excluded.
    unstable: usize,
    stable: bool,
    /// For the resting disk: where it loses stability (independent of the point).
    ic_thresholds: Option<IcThresholds>,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let axis = super::mirror_axis(&a.axis)?;
    let seed = seed_of(a.seed.as_deref())?;
    let mut params = ModelParams {
        eta_t: a.eta_t,
        kappa2: a.kappa2,
        mass: a.mass,
        ..ModelParams::default()
    };
    for (p, x) in a.set.as_deref().map_or(Ok(Vec::new()), parse_set)? {
        if matches!(p, ModelParam::EtaT | ModelParam::Kappa2 | ModelParam::Mass) {
            return Err(CliError::usage(format!(
                "invalid --set {p}={x}: {p} has its own option (--{})",
                p.name().replace('_', "-")
            )));
        }
        p.set(&mut params, x);
    }
    params.validate()?;
    super::check_grid(a.n)?;
    let st = find(&params, a.n, a.state, axis, seed).map_err(|e| match e {
        droplet_solver::error::SolverError::NewtonFailed { .. }
        | droplet_solver::error::SolverError::RestingRoot { .. } => CliError {
            message: format!("{e}; try another --seed or --axis"),
            code: 1,
        },
        other => CliError::from(other),
    })?;
    let [vx, vy, a2, b2] = st.z;
    let unstable = st.verdict.unstable;
    let report = Report {
        state: a.state,
        axis: a.axis.clone(),
        eta_t: a.eta_t,
        kappa2: a.kappa2,
        n: a.n,
        params,
        vx,
        vy,
        a2,
        b2,
        v: vx.hypot(vy),
        s: a2.hypot(b2),
        residual: st.residual,
        eigenvalues: st
            .eigenvalues
            .iter()
            .map(|l| Eigen { re: l.re, im: l.im })
            .collect(),
        rotation: st.verdict.rotation,
        unstable,
        stable: unstable == 0,
        ic_thresholds: match a.state {
            StateKind::IC => Some(ic_thresholds(&params, a.n)?),
            _ => None,
        },
    };
    if a.json {
        print_json(&report);
    } else {
        print_text(&report);
    }
    Ok(())
}

/// `--seed V,SHAPE`: a starting guess for Newton, if given.
fn seed_of(text: Option<&str>) -> Result<Option<(f64, f64)>, CliError> {
    let Some(text) = text else {
        return Ok(None);
    };
    let parts: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| CliError::usage(format!("invalid --seed `{text}`: V,SHAPE")))?;
    match parts[..] {
        [v, c] if v.is_finite() && c.is_finite() && c.abs() < 1.0 => Ok(Some((v, c))),
        _ => Err(CliError::usage(format!(
            "invalid --seed `{text}`: two finite numbers V,SHAPE with |SHAPE| < 1"
        ))),
    }
}

/// The text report of a state and its stability.
fn print_text(report: &Report) {
    outln!(
        "{:?} on {} at eta_t = {}, kappa2 = {} (N = {}): v = {:.6}  s = {:.6}  (vx {:.6}, vy {:.6}, a2 {:.6}, b2 {:.6}; residual {:.1e})",
        report.state, report.axis, report.eta_t, report.kappa2, report.n, report.v, report.s, report.vx, report.vy, report.a2, report.b2, report.residual
    );
    for l in &report.eigenvalues {
        outln!("  eigenvalue {:+.6} {:+.6}i", l.re, l.im);
    }
    if let Some(th) = &report.ic_thresholds {
        outln!(
            "resting disk: moves for eta_t < {:.9}; deforms (a2) for kappa2 < {:.9}, (b2, diagonal) for kappa2 < {:.9}",
            th.eta_t, th.kappa2_a2, th.kappa2_b2
        );
    }
    outln!(
        "{}",
        if report.stable {
            "stable".to_string()
        } else {
            format!(
                "unstable ({} eigenvalues with positive real part)",
                report.unstable
            )
        }
    );
    if let Some(r) = report.rotation {
        outln!(
            "rotation mode {r:+.6} (box effect: which orientation the box prefers; not counted)"
        );
    }
}
