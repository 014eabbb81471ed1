//! `droplet simulate`'s arguments, the model parameters and solver settings they ask for, and
//! the arguments' checks: an option the run would not read is refused
//! (`SolverSettings::first_unread`, the check a spec makes too), and so are shape modes
//! outside 2..16.
use super::CliError;
use droplet_solver::{
    contract::settings::SolverSettings, model::params::ModelParams, stepping::SchemeKind,
};
use std::path::PathBuf;

/// Simulate one droplet from one initial condition until it settles.
///
/// Simulate one droplet from one initial condition until it is steady, reaches --t-max, or
/// diverges; print status, class (IC/ID/MD/MC), final v, s and timings.
#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "Examples:\n  droplet simulate --eta-t 0.085 --kappa2 0.112 --ic i                 # MD (Fig. 1c)\n  droplet simulate --eta-t 0.085 --kappa2 0.116 --ic i --json          # ID (Fig. 1b)\n  droplet simulate --eta-t 0.085 --kappa2 0.120 --ic i --series s.parquet --picture ic.png"
)]
pub struct Args {
    /// Translational friction eta_t (> 0).
    #[arg(long)]
    pub(super) eta_t: f64,
    /// Mode-2 stiffness kappa2 (>= 0).
    #[arg(long)]
    pub(super) kappa2: f64,
    /// Initial condition: i, ii, iii, iv (paper Sect. 3), i', ii' (Fig. 2b; also ip, iip), or custom:vx,vy,a2,b2 (with --modes K > 2 followed by a3,b3,a4,b4,... up to mode K; modes not given start at 0).
    #[arg(long, default_value = "i")]
    pub(super) ic: String,
    /// Inertia m (0.1 reproduces the paper's IC/MD bistability; 0 = overdamped, with
    /// --steady test only: its labels cannot be checked for stability).
    #[arg(long, default_value_t = 0.1)]
    pub(super) mass: f64,
    /// Mode-2 friction eta2.
    #[arg(long, default_value_t = 0.1)]
    pub(super) eta2: f64,
    /// Droplet radius R.
    #[arg(long, default_value_t = 1.0)]
    pub(super) radius: f64,
    /// Interface width sigma of Theta.
    #[arg(long, default_value_t = 0.03)]
    pub(super) sigma: f64,
    /// Side L of the periodic box.
    #[arg(long, default_value_t = 7.0)]
    pub(super) box_len: f64,
    /// Scheme: spectral (co-moving ETD2RK, default) or paper-fd (the paper's explicit scheme).
    #[arg(long, default_value = "spectral")]
    pub(super) scheme: String,
    /// Grid points per side (default: 192 spectral, 280 paper-fd).
    #[arg(long)]
    pub(super) n: Option<usize>,
    /// Time step: the first step of adaptive runs, else the fixed step (default: 0.02
    /// spectral, 1e-4 paper-fd).
    #[arg(long)]
    pub(super) dt: Option<f64>,
    /// Adaptive stepping: largest accepted embedded error estimate per step (units of v, a2,
    /// b2); 0 = fixed step --dt. Default 1e-4 for spectral (see `droplet bench`), 0 for
    /// paper-fd (no estimate). For accurate time series use 1e-5.
    #[arg(long)]
    pub(super) tol: Option<f64>,
    /// Largest adaptive step (default 0.25: larger steps relax slow modes at the wrong rate).
    #[arg(long)]
    pub(super) dt_max: Option<f64>,
    /// Give up at this time (status t_max).
    #[arg(long, default_value_t = 2000.0)]
    pub(super) t_max: f64,
    /// Steady when max change of vx, vy, a2, b2 over one window is below this.
    #[arg(long, default_value_t = 1e-6)]
    pub(super) steady_tol: f64,
    /// Window of the steady test in time units (default 0.1, the paper's).
    #[arg(long)]
    pub(super) steady_window: Option<f64>,
    /// How the run decides it is steady: newton (default for the spectral scheme: once the
    /// run slows down, Newton on the steady equations; it ends at a root only if the root is
    /// stable and the run is approaching it) or test (the paper's test alone; default for
    /// paper-fd). With test, a steady run is checked afterwards and a warning printed if the
    /// state it stopped on is unstable.
    #[arg(long)]
    pub(super) steady: Option<droplet_solver::contract::ending::SteadyMethod>,
    /// With --steady newton: stop a run beside an unstable steady state as soon as its growth
    /// rate shows it cannot leave before --t-max with another class (status saddle, the
    /// diagnosis says how far it would get) instead of creeping there.
    #[arg(long)]
    pub(super) stop_beside_saddle: bool,
    /// With --steady newton and adaptive steps: once two Newton tries see the run leaving an
    /// unstable steady state along one growing mode, still linear, leap along the mode to a
    /// distance 0.05 from it instead of stepping through the exponential (t_leapt says how
    /// long; the final state is unaffected, t_end moves with the later Newton tries).
    #[arg(long)]
    pub(super) leap_departures: bool,
    /// With --steady newton: do not end slow runs where their one-dimensional quasi-steady
    /// flow lands (on by default: a slow run ends `steady_by_landing` on the stable root its
    /// flow reaches, confirmed by Newton and the root's eigenvalues); plain time stepping.
    #[arg(long)]
    pub(super) no_landing: bool,
    /// With --steady newton: leave out the orientation's slow flow (numerics 7). By default a
    /// run leaning from a root stable in rotation ends there only if that flow (speed and
    /// shape solved at each orientation, the force across the motion left) turns it back,
    /// and a run leaning from a root unstable in rotation turns to the flow's first stable
    /// zero; the box's anisotropy puts such zeros a few degrees off the mirror lines
    /// (docs/classification.md, "The orientation's flow").
    #[arg(long)]
    pub(super) no_orientation_flow: bool,
    /// With --steady newton: give up at --t-max, as the paper (by default a run not yet on a
    /// stable state runs on to 64 t_max, 4 t_max with fixed steps, before it is reported
    /// unsettled).
    #[arg(long)]
    pub(super) no_run_on: bool,
    /// Take every step (by default an adaptive run moves on along a slow phase by projective
    /// steps: once 8 steps at one size show its fast parts decayed, the chord of the last step
    /// is continued over up to 20 steps' time, its error kept below --tol and every
    /// unknown's slope changing by at most a tenth; never past a series row, so a run
    /// recorded every 0.5, the default --every, takes every step; t_projected says how long;
    /// docs/numerics.md, "Projective steps along slow phases").
    #[arg(long)]
    pub(super) no_projective_steps: bool,
    /// Hold the centre fixed (deformation-only run, Appendix E).
    #[arg(long)]
    pub(super) pinned: bool,
    /// Write the time series (t, x, y, vx, vy, a2, b2, v, s) to this Parquet file.
    #[arg(long)]
    pub(super) series: Option<PathBuf>,
    /// Sampling interval of the series / picture in time units. Adaptive steps are shortened
    /// to land on the sample times, so a recorded run's steps differ from an unrecorded one's:
    /// its values agree within the step tolerance, except in runs still leaving a saddle at
    /// --t-max, whose final values are sensitive to any integration error (README,
    /// Classification).
    #[arg(long, default_value_t = 0.5)]
    pub(super) every: f64,
    /// Draw the Fig. 1 panels (final field, outline, velocity; v(t), s(t)) to this PNG (+ .svg).
    #[arg(long)]
    pub(super) picture: Option<PathBuf>,
    /// Shape modes 2..K (the paper's general model; default 2, the paper's). With K > 2 the
    /// K-mode model is time-stepped by ETD2RK in the droplet's frame (adaptive steps under
    /// --tol and --dt-max as a 2-mode run, or fixed steps --dt with --tol 0) from the IC
    /// (modes 3..K as --ic custom gives them, else 0; field 0), ended like a 2-mode run by
    /// the Newton finish: steady on a root of the 2K force balances whose eigenvalues all
    /// decay (or where its slow flow lands, as a 2-mode run), else unsettled where a 2-mode
    /// run gives up (as a sweep with params.modes: K
    /// runs it). Its --series gains a3..aK, b3..bK; --picture draws every mode. With
    /// --scheme paper-fd: the paper's forward Euler with every mode to t_max, ended by the
    /// steady test (every rate below --steady-tol). No pinning; the orientation's flow only
    /// confirms that a run settled beside a root stable in rotation turns back to it (the
    /// saddle stop and the leap act at every K).
    #[arg(long, default_value_t = 2)]
    pub(super) modes: usize,
    /// With --modes K > 2: the friction law of the modes k >= 3, eta_k = eta2 (k/2)^P
    /// (default 0: every mode eta2; -1: the dissipation of the mode's own flow, eta_k = (2/k)
    /// eta2); from -4 to 4. It changes how fast the shape relaxes, not where it settles.
    #[arg(
        long,
        value_name = "P",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub(super) eta_k_exponent: f64,
    /// Print one JSON object instead of text (the same keys for every K; `profile`: where the
    /// run's wall time went, as `droplet bench --map` profiles a map's runs: stepping_s,
    /// newton_s, eigen_s, landing_s, flow_s, leap_s, diagnosis_s and the solves' counts).
    #[arg(long)]
    pub(super) json: bool,
}

/// Checks `--every` and the output paths; whether the run records a series.
pub(super) fn check_outputs(a: &Args, settings: &SolverSettings) -> Result<bool, CliError> {
    let record = a.series.is_some() || a.picture.is_some();
    if record {
        droplet_solver::contract::limits::check_series(settings.give_up_at(), a.every)?;
    } else if !(a.every > 0.0 && a.every.is_finite()) {
        return Err(CliError::usage(format!(
            "invalid --every {}: a finite number > 0",
            a.every
        )));
    }
    for p in [&a.series, &a.picture].into_iter().flatten() {
        if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            if !dir.is_dir() {
                return Err(CliError::usage(format!(
                    "directory {} does not exist",
                    dir.display()
                )));
            }
        }
    }
    Ok(record)
}

/// The model parameters and solver settings the arguments ask for.
pub(super) fn model_of(a: &Args) -> Result<(ModelParams, SolverSettings), CliError> {
    let scheme: SchemeKind = a.scheme.parse()?;
    let base = match scheme {
        SchemeKind::Spectral => SolverSettings::default(),
        SchemeKind::PaperFd => SolverSettings::paper_fd(),
    };
    let settings = SolverSettings {
        scheme,
        n: a.n.unwrap_or(base.n),
        dt: a.dt.unwrap_or(base.dt),
        tol: a.tol.unwrap_or(base.tol),
        dt_max: a.dt_max.unwrap_or(base.dt_max.max(a.dt.unwrap_or(base.dt))),
        t_max: a.t_max,
        steady_tol: a.steady_tol,
        steady_window: a.steady_window.unwrap_or(base.steady_window),
        pinned: a.pinned,
        steady: match (a.steady, a.pinned) {
            (Some(m), _) => m,
            (None, true) => droplet_solver::contract::ending::SteadyMethod::Test,
            (None, false) => base.steady,
        },
        stop_beside_saddle: a.stop_beside_saddle,
        leap_departures: a.leap_departures,
        landing: !a.no_landing,
        orientation_flow: !a.no_orientation_flow,
        run_on: !a.no_run_on,
        projective_steps: !a.no_projective_steps,
        ..base
    };
    check_read(a, &settings)?;
    let most = droplet_solver::contract::limits::MAX_MODES;
    if !(2..=most).contains(&a.modes) {
        return Err(CliError::usage(format!(
            "invalid --modes {}: an integer from 2 (the paper's a2, b2) to {most}",
            a.modes
        )));
    }
    let params = ModelParams {
        eta_t: a.eta_t,
        kappa2: a.kappa2,
        eta2: a.eta2,
        radius: a.radius,
        sigma: a.sigma,
        box_len: a.box_len,
        mass: a.mass,
        modes: a.modes,
        eta_k_exponent: a.eta_k_exponent,
    };
    Ok((params, settings))
}

/// Refuses an option this run would not read (`SolverSettings::first_unread`, the check a
/// spec makes too), naming the option.
fn check_read(a: &Args, settings: &SolverSettings) -> Result<(), CliError> {
    let given = [
        (a.tol.is_some(), "tol", "--tol"),
        (a.dt_max.is_some(), "dt_max", "--dt-max"),
        (
            a.steady_window.is_some(),
            "steady_window",
            "--steady-window",
        ),
        (a.no_landing, "landing", "--no-landing"),
        (
            a.no_orientation_flow,
            "orientation_flow",
            "--no-orientation-flow",
        ),
        (a.no_run_on, "run_on", "--no-run-on"),
        (
            a.no_projective_steps,
            "projective_steps",
            "--no-projective-steps",
        ),
        (
            a.stop_beside_saddle,
            "stop_beside_saddle",
            "--stop-beside-saddle",
        ),
        (a.leap_departures, "leap_departures", "--leap-departures"),
        (a.pinned, "pinned", "--pinned"),
    ];
    let fields: Vec<&str> = given.iter().filter(|g| g.0).map(|g| g.1).collect();
    match settings.first_unread(a.modes, &fields) {
        None => Ok(()),
        Some((field, why)) => {
            let flag = given.iter().find(|g| g.1 == field).map_or(field, |g| g.2);
            Err(CliError::usage(format!(
                "invalid {flag}: this run does not read it ({why})"
            )))
        }
    }
}
