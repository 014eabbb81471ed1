//! `droplet stability`: one named steady state as a root, and its leading eigenvalues.
use super::param_line::parse_set;
use super::{print_json, CliError};
use droplet_solver::model::param::ModelParam;
use droplet_solver::model::params::ModelParams;
use droplet_solver::model::state::speed_and_deformation;
use droplet_solver::roots::balances::Balances;
use droplet_solver::roots::named_state::{find, StateKind};
use droplet_solver::roots::thresholds::{ic_thresholds, IcThresholds};
use serde::Serialize;

/// Compute one steady state directly, with its linear stability.
///
/// Compute a steady state of the full model directly (Newton on the co-moving force balance,
/// started from the reduced model's state or from --seed) and its linear stability, field
/// included: every eigenvalue with Re > -1 (the field's own modes decay at rate >= 1), from
/// the 2K x 2K nonlinear eigenproblem det(lambda M - E - C (lambda - D)^-1 B) = 0 (4 x 4 with
/// the paper's two modes, K = --modes). A state with
/// an eigenvalue of positive real part is unstable. Moving and deformed states have one
/// near-neutral eigenvalue (the rotation of the direction of motion or of the long axis,
/// weakly broken by the periodic box); it is listed with the others, identified by its mode
/// (`rotation`), and left out of `stable` / `unstable`, which decide the state's class.
/// For the resting disk it also prints where the disk loses stability: the eta_t below which
/// it starts to move and the kappa2 below which it deforms, exact at the grid (no scan).
#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "Examples:\n  droplet stability --eta-t 0.085 --kappa2 0.13 --state ic          # stable resting disk\n  droplet stability --eta-t 0.0763 --kappa2 0.16 --state ic --json  # just past the onset of motion: unstable\n  droplet stability --eta-t 0.085 --kappa2 0.112 --state md         # Fig. 1c, moving along its minor axis\n  droplet stability --eta-t 0.085 --kappa2 0.116 --state id --axis diagonal\n  droplet stability --eta-t 0.078 --kappa2 0.13 --state ic --set radius=1.05,sigma=0.025\n  droplet stability --eta-t 0.085 --kappa2 0.112 --state md --modes 4   # with shape modes 2..4"
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
    /// Newton's starting point: speed along the axis and shape amplitude, e.g. 0.6,-0.27
    /// (with --modes K the mode-2 amplitude; the modes 3..K then start from 0).
    #[arg(long, value_name = "V,SHAPE", allow_hyphen_values = true)]
    seed: Option<String>,
    /// Grid points per side.
    #[arg(long, default_value_t = 192)]
    n: usize,
    /// Inertia m (> 0 here).
    #[arg(long, default_value_t = 0.1)]
    mass: f64,
    /// Shape modes 2..K (the paper's general model; default 2, the paper's). With K > 2 the
    /// states on the x axis (motion along x, shapes symmetric about it), started from the
    /// 2-mode state with one mode added at a time, or with --axis diagonal the same state
    /// turned by 45 degrees and solved again on all 2K balances; from 2 to 16 and at most
    /// pi R N / (4 L).
    #[arg(long, default_value_t = 2)]
    modes: usize,
    /// With --modes K > 2: the friction law of the modes k >= 3, eta_k = eta2 (k/2)^P (default
    /// 0: every mode eta2; -1: the dissipation of the mode's own flow); from -4 to 4. It moves
    /// the eigenvalues, not the state.
    #[arg(
        long,
        value_name = "P",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    eta_k_exponent: f64,
    /// Other model parameters: NAME=VALUE[,NAME=VALUE...] of eta2, radius, sigma, box_len
    /// (default: eta2 0.1, R 1, sigma 0.03, box_len 7), e.g. radius=1.02,sigma=0.025.
    #[arg(long, value_name = "NAME=VALUE,...")]
    set: Option<String>,
    /// Print one JSON object (keys: state, axis, eta_t, kappa2, n, modes, eta_k_exponent, params {eta_t,
    /// kappa2, eta2, mass, radius, sigma, box_len, modes, eta_k_exponent}, vx, vy, a2, b2, a_k [a2..aK], b_k
    /// [b2..bK], v, s (the paper's, mode 2), residual, eigenvalues [{re, im}], rotation (the
    /// rotation mode's eigenvalue or null), unstable (rotation excluded), stable,
    /// ic_thresholds {eta_t, kappa2_a2, kappa2_b2, kappa2_a [k = 2..K], kappa2_b [k = 2..K]}
    /// for the resting disk, else null).
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
    modes: usize,
    /// The friction law's exponent of modes `k >= 3` (0 with two modes).
    eta_k_exponent: f64,
    params: ModelParams,
    vx: f64,
    vy: f64,
    a2: f64,
    b2: f64,
    a_k: Vec<f64>,
    b_k: Vec<f64>,
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
    let params = ModelParams {
        modes: a.modes,
        eta_k_exponent: a.eta_k_exponent,
        ..params
    };
    params.validate()?;
    super::check_grid(a.n)?;
    let k = a.modes;
    let mut balances = Balances::new(params, a.n)?;
    let st = find(&mut balances, a.state, axis, seed).map_err(|e| match e {
        droplet_solver::error::SolverError::NewtonFailed { .. }
        | droplet_solver::error::SolverError::RestingRoot { .. } => CliError {
            message: if k == 2 {
                format!("{e}; try another --seed or --axis")
            } else {
                format!(
                    "{e}: no {:?} state with {k} shape modes found here; try a --seed",
                    a.state
                )
            },
            code: 1,
        },
        other => CliError::from(other),
    })?;
    let z = &st.z;
    let (v, s) = speed_and_deformation(z);
    let report = Report {
        state: a.state,
        axis: a.axis.clone(),
        eta_t: a.eta_t,
        kappa2: a.kappa2,
        n: a.n,
        modes: k,
        eta_k_exponent: a.eta_k_exponent,
        params,
        vx: z[0],
        vy: z[1],
        a2: z[2],
        b2: z[k + 1],
        a_k: z[2..=k].to_vec(),
        b_k: z[k + 1..].to_vec(),
        v,
        s,
        residual: st.residual,
        eigenvalues: st
            .eigenvalues
            .iter()
            .map(|l| Eigen { re: l.re, im: l.im })
            .collect(),
        rotation: st.verdict.rotation,
        unstable: st.verdict.unstable,
        stable: st.verdict.stable(),
        ic_thresholds: match a.state {
            StateKind::IC => Some(ic_thresholds(&params, a.n, k)?),
            _ => None,
        },
    };
    emit(&report, a.json);
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

/// Prints the report: one JSON object, or text.
fn emit(report: &Report, json: bool) {
    if json {
        print_json(report);
    } else {
        print_text(report);
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
    if report.modes > 2 {
        let amps: Vec<String> = report
            .a_k
            .iter()
            .enumerate()
            .map(|(i, a)| format!("a{} {a:.6}", i + 2))
            .collect();
        outln!("  shape with {} modes: {}", report.modes, amps.join(", "));
    }
    if let Some(th) = &report.ic_thresholds {
        let ks: Vec<String> = th
            .kappa2_a
            .iter()
            .zip(&th.kappa2_b)
            .enumerate()
            .map(|(i, (ka, kb))| format!("a{0} for kappa2 < {ka:.9} (b{0} for < {kb:.9})", i + 2))
            .collect();
        outln!(
            "resting disk: moves for eta_t < {:.9}; deforms {}",
            th.eta_t,
            ks.join(", ")
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
