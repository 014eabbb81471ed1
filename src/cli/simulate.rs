//! `droplet simulate`: one run, its class, and optionally its time series and Fig. 1 picture,
//! with the paper's two shape modes or with modes 2..K (`--modes K`), by the one run driver
//! (`droplet_solver::runs::driver`); one report with the same keys for every K.
use super::run_settings::{check_outputs, model_of, Args};
use super::{print_json, CliError};
use droplet_solver::contract::outcome::RunOutcome;
use droplet_solver::contract::profile::RunProfile;
use droplet_solver::{
    contract::settings::SolverSettings, model::initial::InitialCondition,
    model::params::ModelParams, runs::driver::Run, stepping::Field, stepping::SchemeKind,
};
use droplet_sweep::pictures::run_figure;
use serde::Serialize;
use std::path::PathBuf;

#[derive(Serialize)]
struct FinalState {
    stable: bool,
    /// Largest real part of the root's eigenvalues.
    slowest_eigenvalue: f64,
    /// Growing modes (rotation mode excluded).
    unstable: usize,
    note: String,
}

#[derive(Serialize)]
struct Report {
    /// Shape modes `2..modes`.
    modes: usize,
    status: String,
    class: Option<String>,
    v: f64,
    s: f64,
    vx: f64,
    vy: f64,
    a2: f64,
    b2: f64,
    /// Every shape mode's amplitudes, `a_2..a_K` and `b_2..b_K`.
    a_k: Vec<f64>,
    b_k: Vec<f64>,
    x: f64,
    y: f64,
    t_end: f64,
    t_steady: Option<f64>,
    /// Time leapt along departures from unstable steady states (`--leap-departures`).
    t_leapt: f64,
    /// Time moved on by projective steps along slow phases (`--no-projective-steps` turns
    /// them off).
    t_projected: f64,
    steps: u64,
    rejected: u64,
    max_step_error: Option<f64>,
    /// Set when a fixed step is too large to trust (see `RunOutcome::dt_warning`).
    dt_warning: Option<String>,
    /// `steady_by_test` or `steady_by_newton` for a steady run.
    ended_by: Option<String>,
    /// Why the run did not end on a stable steady state (null when it did).
    unsettled: Option<String>,
    /// The class of the stable state an unsettled run was heading to, when known.
    heading: Option<String>,
    /// For a run that did not finish: what the steady equations say near its end.
    diagnosis: Option<String>,
    /// For a run that the paper's test alone ended: the stability of the steady state it
    /// stopped at (a root found by Newton from there; rotation mode included).
    final_state: Option<FinalState>,
    wall_s: f64,
    /// Where the run's wall time went: stepping, Newton solves, eigenvalue problems, the
    /// landing's and the orientation flow's samples, the leap, the diagnosis (as `droplet
    /// bench --map` profiles a map's runs).
    profile: RunProfile,
    /// The surfactant's integral over the box at the end.
    mass_integral: f64,
    params: ModelParams,
    settings: SolverSettings,
    ic: InitialCondition,
    series: Option<PathBuf>,
    picture: Vec<PathBuf>,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let (params, settings) = model_of(&a)?;
    let ic = InitialCondition::parse(&a.ic)?;
    ic.check_modes(a.modes)
        .map_err(|e| CliError::usage(format!("invalid --ic with --modes {}: {e}", a.modes)))?;
    let every = check_outputs(&a, &settings)?.then_some(a.every);
    let mut run = Run::new(&params, &ic, &settings)?.record_every(every);
    let out = run.execute();
    let pictures = a.picture.is_some().then(|| run.scheme_mut().field());
    let mass_integral = run.scheme_mut().mass();
    if let Some(path) = &a.series {
        droplet_sweep::tables::series::write(
            path,
            &out.series,
            &out.higher_series,
            &params,
            &settings,
            &ic,
        )?;
    }
    let pictures = match (&a.picture, pictures) {
        (Some(path), Some(field)) => picture(path, &params, &ic, &out, &field)?,
        _ => Vec::new(),
    };
    let final_state = final_state_of(&params, &settings, &out);
    let z = out.unknowns();
    let (a_k, b_k) = z[2..].split_at(z.len() / 2 - 1);
    let report = Report {
        modes: params.modes,
        status: out.status.as_str().into(),
        class: out.class.map(|c| c.as_str().into()),
        v: out.v,
        s: out.s,
        vx: out.state.vx,
        vy: out.state.vy,
        a2: out.state.a2,
        b2: out.state.b2,
        a_k: a_k.to_vec(),
        b_k: b_k.to_vec(),
        x: out.state.x,
        y: out.state.y,
        t_end: out.t_end,
        t_steady: out.t_steady,
        t_leapt: out.t_leapt,
        t_projected: out.t_projected,
        steps: out.steps,
        rejected: out.rejected,
        max_step_error: out.max_step_error,
        dt_warning: out.dt_warning(&settings),
        ended_by: out.ended_by.map(|e| e.as_str().into()),
        unsettled: out.unsettled.map(|u| u.as_str().into()),
        heading: out.heading.map(|c| c.as_str().into()),
        diagnosis: out.diagnosis.clone(),
        final_state,
        wall_s: out.wall_s,
        profile: out.profile,
        mass_integral,
        params,
        settings,
        ic,
        series: a.series.clone(),
        picture: pictures,
    };
    if a.json {
        print_json(&report);
    } else {
        print_text(&report);
    }
    Ok(())
}

/// The run's Fig. 1 panels: the run's own field at its end, the outline with every mode, and
/// `v(t)`, `s(t)`.
fn picture(
    path: &std::path::Path,
    params: &ModelParams,
    ic: &InitialCondition,
    out: &RunOutcome,
    field: &Field,
) -> Result<Vec<PathBuf>, CliError> {
    let modes = match params.modes {
        2 => String::new(),
        k => format!(", modes 2..{k}"),
    };
    let title = format!(
        "eta_t = {}, kappa2 = {}, IC {}{modes}: {} ({}), t = {:.1}",
        params.eta_t,
        params.kappa2,
        ic.name,
        out.class.map_or("-", |c| c.as_str()),
        out.status.as_str(),
        out.t_end
    );
    Ok(run_figure::run_picture(
        path,
        &title,
        params,
        field,
        &out.state,
        &out.higher_modes,
        &out.series,
    )?)
}

/// For a run the paper's test ended (`--steady test`): the root near its final state and its
/// stability, so that a stop on an unstable state is reported.
fn final_state_of(
    params: &ModelParams,
    settings: &SolverSettings,
    out: &RunOutcome,
) -> Option<FinalState> {
    (out.ended_by == Some(droplet_solver::contract::ending::Ending::Test)
        && settings.steady == droplet_solver::contract::ending::SteadyMethod::Test
        && settings.scheme == SchemeKind::Spectral
        && !settings.pinned)
        .then(|| {
            let mut f = droplet_solver::runs::finish::NewtonFinish::new(params, settings);
            let z = out.unknowns();
            f.root_near(&z).ok().map(|found| FinalState {
                stable: found.stable(),
                slowest_eigenvalue: found.slowest(),
                unstable: found.verdict.unstable,
                note: found.describe(&z),
            })
        })
        .flatten()
}

/// The text report of a run.
fn print_text(report: &Report) {
    outln!(
        "status {}  class {}  v = {:.6}  s = {:.6}  t = {:.2}  ({} steps, {:.2} s wall)",
        report.status,
        report.class.as_deref().unwrap_or("-"),
        report.v,
        report.s,
        report.t_end,
        report.steps,
        report.wall_s
    );
    let p = &report.profile;
    outln!(
        "time: stepping {:.2} s, Newton {:.2} s, eigenvalues {:.2} s, landing {:.2} s, flow {:.2} s",
        p.stepping_s,
        p.newton_s,
        p.eigen_s,
        p.landing_s,
        p.flow_s
    );
    if report.modes > 2 {
        outln!(
            "shape modes 2..{}: a_k {:?}  b_k {:?}",
            report.modes,
            report.a_k,
            report.b_k
        );
    }
    if let Some(e) = &report.ended_by {
        outln!("ended by {}", e.replace('_', " "));
    }
    if report.t_leapt > 0.0 {
        outln!(
            "leapt {:.1} time units along a departure from an unstable steady state",
            report.t_leapt
        );
    }
    if report.t_projected > 0.0 {
        outln!(
            "moved {:.1} of its {:.1} time units by projective steps along slow phases",
            report.t_projected,
            report.t_end
        );
    }
    if let Some(u) = &report.unsettled {
        outln!(
            "unsettled ({}): no class{}",
            u.replace('_', " "),
            report
                .heading
                .as_ref()
                .map_or(String::new(), |h| format!("; heading to {h}"))
        );
    }
    if let Some(d) = &report.diagnosis {
        outln!("not finished: {d}");
    }
    if let Some(f) = report.final_state.as_ref().filter(|f| !f.stable) {
        errln!(
                "warning: the paper's test stopped this run on an unstable state ({}); with --steady newton it would go on",
                f.note
            );
    }
    if let Some(w) = &report.dt_warning {
        errln!("warning: {w}");
    }
    for p in report.series.iter().chain(&report.picture) {
        outln!("wrote {}", p.display());
    }
}
