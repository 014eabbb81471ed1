//! `droplet simulate --modes K` (K > 2): the paper's general model with shape modes 2..K,
//! time-stepped from the initial condition and ended by the Newton finish, or with
//! `--scheme paper-fd` by the paper's scheme and its test (`droplet_solver::runs::mode_outcome`).
use super::simulate::Args;
use super::{print_json, CliError};
use droplet_solver::contract::settings::SolverSettings;
use droplet_solver::model::{initial::InitialCondition, params::ModelParams};
use droplet_solver::roots::{mode_field::lab_field, mode_solver::ModeSolver};
use droplet_sweep::pictures::run_figure;

/// `--modes K` with K > 2: the K-mode model from the IC (modes 3..K at rest), stepped as a
/// 2-mode run is and ended by the Newton finish, or by the steady test with --scheme paper-fd
/// (`droplet_solver::runs::mode_outcome`, as a sweep with `params.modes: K` runs it).
pub fn run(
    a: &Args,
    params: ModelParams,
    settings: SolverSettings,
    ic: &InitialCondition,
) -> Result<(), CliError> {
    droplet_solver::contract::limits::check_modes(&params, settings.n, a.modes)?;
    let k = a.modes;
    let settings = SolverSettings {
        modes: k,
        ..settings
    };
    let every = super::simulate::check_outputs(a, &settings)?.then_some(a.every);
    let out =
        droplet_solver::runs::mode_outcome::simulate_modes_recorded(&params, ic, &settings, every)?;
    if let Some(path) = &a.series {
        droplet_sweep::tables::series::write(
            path,
            &out.series,
            &out.higher_series,
            &params,
            &settings,
            ic,
        )?;
    }
    let st = &out.state;
    let picture = match &a.picture {
        Some(path) => picture(path, &params, &settings, ic, &out)?,
        None => Vec::new(),
    };
    let (a_k, b_k): (Vec<f64>, Vec<f64>) = {
        let h = &out.higher_modes;
        let a: Vec<f64> = std::iter::once(st.a2)
            .chain(h[..k - 2].iter().copied())
            .collect();
        let b: Vec<f64> = std::iter::once(st.b2)
            .chain(h[k - 2..].iter().copied())
            .collect();
        (a, b)
    };
    let report = serde_json::json!({
        "modes": k, "status": out.status.as_str(), "class": out.class.map(|c| c.as_str()),
        "v": out.v, "s": out.s, "vx": st.vx, "vy": st.vy, "a_k": a_k, "b_k": b_k,
        "t_end": out.t_end, "steps": out.steps, "ended_by": out.ended_by.map(|e| e.as_str()),
        "unsettled": out.unsettled.map(|u| u.as_str()),
        "heading": out.heading.map(|c| c.as_str()), "diagnosis": out.diagnosis,
        "wall_s": out.wall_s, "params": params, "settings": settings, "ic": ic,
        "picture": picture,
    });
    if a.json {
        print_json(&report);
    } else {
        outln!(
            "{} with {k} modes ({}): v = {:.6}  s = {:.6}  a_k {a_k:?}  b_k {b_k:?}  t = {:.1}, {} steps{}",
            out.class.map_or("-", |c| c.as_str()),
            out.ended_by.map_or(out.status.as_str(), |e| e.as_str()),
            out.v,
            out.s,
            out.t_end,
            out.steps,
            out.diagnosis.map(|d| format!("; {d}")).unwrap_or_default()
        );
    }
    Ok(())
}

/// The run's Fig. 1 panels: the steady field of its final state (modes `2..K`, centred where
/// the run ends; the run's own field is not kept), the outline with every mode, and `v(t)`,
/// `s(t)`.
fn picture(
    path: &std::path::Path,
    params: &ModelParams,
    settings: &SolverSettings,
    ic: &InitialCondition,
    out: &droplet_solver::contract::outcome::RunOutcome,
) -> Result<Vec<std::path::PathBuf>, CliError> {
    let st = &out.state;
    let (a, b) = out.higher_modes.split_at(out.higher_modes.len() / 2);
    let mut z = vec![st.vx, st.vy, st.a2];
    z.extend(a);
    z.push(st.b2);
    z.extend(b);
    let mut solver = ModeSolver::new(*params, settings.n)?;
    let field = lab_field(&mut solver, &z, st.x, st.y);
    let title = format!(
        "eta_t = {}, kappa2 = {}, IC {}, modes 2..{}: {} ({}), t = {:.1}",
        params.eta_t,
        params.kappa2,
        ic.name,
        settings.modes,
        out.class.map_or("-", |c| c.as_str()),
        out.status.as_str(),
        out.t_end
    );
    Ok(run_figure::run_picture(
        path,
        &title,
        params,
        &field,
        st,
        &out.higher_modes,
        &out.series,
    )?)
}
