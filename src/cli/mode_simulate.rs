//! `droplet simulate --modes K` (K > 2): the paper's general model with shape modes 2..K,
//! time-stepped from the initial condition until steady (`droplet_solver::runs::mode_run`).
use super::simulate::Args;
use super::{print_json, CliError};
use droplet_solver::model::{initial::InitialCondition, params::ModelParams};

/// `--modes K` with K > 2: the K-mode model time-stepped from the IC until steady.
pub fn run(a: &Args, params: ModelParams, n: usize, ic: &InitialCondition) -> Result<(), CliError> {
    droplet_solver::contract::limits::check_modes(&params, n, a.modes)?;
    let not_yet = [
        (a.series.is_some(), "--series"),
        (a.picture.is_some(), "--picture"),
        (a.scheme != "spectral", "--scheme"),
        (a.pinned, "--pinned"),
        (a.steady.is_some(), "--steady"),
        (a.stop_beside_saddle, "--stop-beside-saddle"),
        (a.leap_departures, "--leap-departures"),
        (a.no_landing, "--no-landing"),
        (a.no_run_on, "--no-run-on"),
        (a.tol.is_some(), "--tol"),
        (a.dt_max.is_some(), "--dt-max"),
    ];
    if let Some((_, flag)) = not_yet.iter().find(|(given, _)| *given) {
        return Err(CliError::usage(format!(
            "invalid {flag} with --modes {}: the K-mode run is one fixed-step scheme to a \
             steady state (--dt, --t-max, --steady-tol)",
            a.modes
        )));
    }
    let k = a.modes;
    let mut z0 = vec![ic.vx, ic.vy, ic.a2];
    z0.extend(std::iter::repeat_n(0.0, k - 2));
    z0.push(ic.b2);
    z0.extend(std::iter::repeat_n(0.0, k - 2));
    let settings = droplet_solver::runs::mode_run::ModeRunSettings {
        dt: a.dt.unwrap_or(0.05),
        t_max: a.t_max,
        tol: a.steady_tol,
    };
    let started = std::time::Instant::now();
    let run = droplet_solver::runs::mode_run::run_modes(&params, n, &z0, &settings)?;
    let (vx, vy) = (run.z[0], run.z[1]);
    let (a2, b2) = (run.z[2], run.z[k + 1]);
    let (v, s) = (vx.hypot(vy), a2.hypot(b2));
    let class = run
        .steady
        .then(|| droplet_solver::model::classify::StateClass::of(v, s).as_str());
    let report = serde_json::json!({
        "modes": k, "status": if run.steady { "steady" } else { "t_max" }, "class": class,
        "v": v, "s": s, "vx": vx, "vy": vy, "a_k": &run.z[2..k + 1], "b_k": &run.z[k + 1..],
        "t_end": run.t_end, "steps": run.steps, "rate": run.rate,
        "wall_s": started.elapsed().as_secs_f64(), "params": params, "ic": ic, "n": n,
    });
    if a.json {
        print_json(&report);
    } else {
        outln!(
            "{} with {k} modes ({}): v = {v:.6}  s = {s:.6}  a_k {:?}  b_k {:?}  t = {:.1}, {} steps, largest rate {:.1e}",
            class.unwrap_or("-"),
            if run.steady { "steady" } else { "t_max" },
            &run.z[2..k + 1],
            &run.z[k + 1..],
            run.t_end,
            run.steps,
            run.rate
        );
    }
    Ok(())
}
