//! What one run may ask for, checked before it starts, so that no request can hang or return
//! a meaningless number:
//! - a step count: `t_max / dt` (fixed steps) or `t_max / dt_max` (the fewest adaptive steps)
//!   at most [`MAX_STEPS`]; adaptive runs also stop at [`adaptive_step_cap`] accepted steps with
//!   status `step_limit` (a controller stuck at tiny steps would otherwise run for ever);
//! - a recorded series of at most [`MAX_SERIES_ROWS`] rows;
//! - a droplet resolved by the grid: radius at least [`MIN_RADIUS_CELLS`] cells and interface
//!   width `sigma` at least [`MIN_SIGMA_CELLS`] of a cell (a thinner `Theta` is a staircase
//!   whose forces are grid noise: such runs come out "steady IC" whatever the parameters);
//! - for the paper's explicit scheme, a step below forward Euler's stability limit for
//!   `u_t = Lap u - u` on the 5-point stencil, `dt (8 / dx^2 + 1) <= 2` (above it every run
//!   diverges, whatever the physics).
use crate::contract::ending::SteadyMethod;
use crate::contract::settings::MAX_STEPS;
use crate::contract::settings::{ModelKind, SolverSettings};
use crate::error::{require, SolverError};
use crate::model::params::ModelParams;
use crate::stepping::SchemeKind;

/// Most rows of a recorded time series (about 72 MB in memory).
pub const MAX_SERIES_ROWS: f64 = 1e6;
/// Least droplet radius in grid cells.
pub const MIN_RADIUS_CELLS: f64 = 4.0;
/// Least interface width `sigma` in grid cells (the smoke sweeps' N = 32..64 give 0.14..0.27).
pub const MIN_SIGMA_CELLS: f64 = 0.1;

/// Accepted adaptive steps after which a run ends with status `step_limit`: 100 times the
/// fewest steps that could reach where the run is given up (`t_max`, or 64 `t_max` with
/// `run_on`, [`SolverSettings::give_up_at`]), at least 1e6, at most [`MAX_STEPS`]. At the
/// defaults (t_max = 2000, dt_max = 0.25) that is 5.12e7; a normal run takes 1e3 to 1e4.
pub fn adaptive_step_cap(settings: &SolverSettings) -> u64 {
    (100.0 * settings.give_up_at() / settings.dt_max).clamp(1e6, MAX_STEPS) as u64
}

/// What a `K`-mode run (`modes` > 2, [`crate::runs::driver`]) can do: the modes the
/// grid resolves ([`check_modes`]), its steps as a 2-mode run's
/// ([`SolverSettings::check_steps`]), a free centre; the spectral scheme with the Newton
/// finish (its saddle stop and leap as a 2-mode run's, no orientation flow) or the paper's
/// test, or the paper's scheme with its test.
fn check_k_mode_run(params: &ModelParams, settings: &SolverSettings) -> Result<(), SolverError> {
    check_modes(params, settings.n, params.modes)?;
    let k = params.modes as f64;
    // The paper's scheme is ended by its test alone (its end is not a root of the spectral
    // steady solver).
    let unsupported = [
        (settings.pinned, "pinned"),
        (
            settings.scheme == SchemeKind::PaperFd && settings.steady != SteadyMethod::Test,
            "steady",
        ),
    ];
    for (given, name) in unsupported {
        require(
            !given,
            "modes",
            k,
            format!(
                "2 with the setting '{name}' given: a K-mode run of the {} scheme is ended \
                 by the Newton finish (steady: newton, spectral scheme only) or by the \
                 paper's test (steady: test), with a free centre",
                settings.scheme,
            ),
        )?;
    }
    Ok(())
}

/// The largest stable step of the paper's forward-Euler scheme on a grid of spacing `dx`.
pub fn paper_fd_max_dt(dx: f64) -> f64 {
    2.0 / (8.0 / (dx * dx) + 1.0)
}

/// Checks a recording interval against the time a run may last, `until` (`t_max`, or where a
/// run that runs on is given up, [`SolverSettings::give_up_at`]).
pub fn check_series(until: f64, every: f64) -> Result<(), SolverError> {
    let rows = until / every;
    require(
        every > 0.0 && rows <= MAX_SERIES_ROWS,
        "every",
        every,
        format!(
            "a finite interval > 0 giving at most {MAX_SERIES_ROWS:e} series rows up to t = {until} (t_max, or where a run not yet steady is given up: 64 t_max unless run_on is off) (this one gives {rows:.3e})"
        ),
    )
}

/// Checks that a grid of `n` points per side resolves the droplet of `params`: its radius at
/// least [`MIN_RADIUS_CELLS`] cells, its interface at least [`MIN_SIGMA_CELLS`] of a cell
/// (every PDE computation: runs, steady states, continuation, boundaries).
pub fn check_resolved(params: &ModelParams, n: usize) -> Result<(), SolverError> {
    let dx = params.box_len / n as f64;
    require(
        params.radius >= MIN_RADIUS_CELLS * dx,
        "radius",
        params.radius,
        format!(
            "at least {MIN_RADIUS_CELLS} grid cells (dx = L/N = {dx:.4}, so >= {:.4}): the droplet must span several cells; raise n",
            MIN_RADIUS_CELLS * dx
        ),
    )?;
    require(
        params.sigma >= MIN_SIGMA_CELLS * dx,
        "sigma",
        params.sigma,
        format!(
            "at least {MIN_SIGMA_CELLS} of a grid cell (dx = L/N = {dx:.4}, so >= {:.5}): a thinner interface is not resolved; raise n",
            MIN_SIGMA_CELLS * dx
        ),
    )?;
    Ok(())
}

pub use crate::model::modes::MAX_MODES;
/// Least grid cells along half a wavelength of the highest mode on the boundary, `pi R / K`.
pub const MIN_MODE_CELLS: f64 = 4.0;

/// Checks a number of shape modes `K` (modes `2..=K`): from 2 to [`MAX_MODES`], and resolved by
/// the grid: half a wavelength of mode `K` along the boundary, `pi R / K`, at least
/// [`MIN_MODE_CELLS`] cells (`K <= pi R N / (4 L)`: 7 at the paper's R = 1, L = 7 and N = 64, 21 at N = 192).
pub fn check_modes(params: &ModelParams, n: usize, k_max: usize) -> Result<(), SolverError> {
    crate::model::modes::check_count(k_max)?;
    let dx = params.box_len / n as f64;
    let most = (std::f64::consts::PI * params.radius / (MIN_MODE_CELLS * dx)).floor();
    require(
        k_max as f64 <= most,
        "modes",
        k_max as f64,
        format!(
            "at most {most} at N = {n} (half a wavelength of the highest mode on the boundary, \
             pi R / K, must span {MIN_MODE_CELLS} grid cells of dx = L/N = {dx:.4}); raise n"
        ),
    )
}

/// Checks that `settings` can resolve and integrate the droplet of `params` (PDE runs; the
/// ODE model has no grid).
pub fn check_run(params: &ModelParams, settings: &SolverSettings) -> Result<(), SolverError> {
    settings.check_steps()?;
    if settings.model != ModelKind::Pde {
        return require(
            params.modes == 2,
            "modes",
            params.modes as f64,
            "2 for the reduced ODE model (mode 2 only)",
        );
    }
    // A label is the stable state a run ends on, and stability needs the linearisation,
    // which needs inertia: an overdamped run could only be ended by the paper's test, whose
    // label is not checked (at m = 0 a run from the paper's ICs rests on the unstable disk
    // below the onset of motion, held there by their mirror symmetry).
    require(
        params.mass > 0.0 || settings.steady != SteadyMethod::Newton,
        "mass",
        params.mass,
        "a finite number > 0 with steady: newton (the stability of the end state needs \
         inertia); for the overdamped model (m = 0) choose steady: test, the paper's test \
         alone, whose labels are not checked",
    )?;
    check_resolved(params, settings.n)?;
    if params.modes != 2 {
        check_k_mode_run(params, settings)?;
    }
    let dx = params.box_len / settings.n as f64;
    if settings.scheme == SchemeKind::PaperFd {
        let limit = paper_fd_max_dt(dx);
        require(
            settings.dt <= limit,
            "dt",
            settings.dt,
            format!(
                "at most {limit:.4e} for paper-fd at N = {} (forward Euler's stability limit dt (8/dx^2 + 1) <= 2, dx = {dx:.4}); above it every run diverges",
                settings.n
            ),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_from_two_to_what_the_grid_resolves() {
        let p = ModelParams::default();
        assert!(check_modes(&p, 192, 2).is_ok() && check_modes(&p, 192, MAX_MODES).is_ok());
        for (n, k) in [(192, 1), (192, 0), (192, MAX_MODES + 1), (64, 8), (32, 4)] {
            assert!(check_modes(&p, n, k).is_err(), "N = {n}, K = {k}");
        }
        assert!(check_modes(&p, 64, 7).is_ok());
    }

    fn name_of(e: SolverError) -> &'static str {
        match e {
            SolverError::InvalidParameter { name, .. } => name,
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn the_paper_settings_pass_and_each_limit_names_its_field() {
        let p = ModelParams::default();
        assert!(check_run(&p, &SolverSettings::default()).is_ok());
        assert!(check_run(&p, &SolverSettings::paper_fd()).is_ok());
        let tiny = SolverSettings {
            dt: 1e-300,
            tol: 0.0,
            ..SolverSettings::default()
        };
        assert_eq!(name_of(check_run(&p, &tiny).unwrap_err()), "dt");
        let tiny_cap = SolverSettings {
            dt: 1e-12,
            dt_max: 1e-12,
            ..SolverSettings::default()
        };
        assert_eq!(name_of(check_run(&p, &tiny_cap).unwrap_err()), "dt_max");
        let thin = ModelParams { sigma: 1e-3, ..p };
        assert_eq!(
            name_of(check_run(&thin, &SolverSettings::default()).unwrap_err()),
            "sigma"
        );
        let small = ModelParams { radius: 0.1, ..p };
        assert_eq!(
            name_of(check_run(&small, &SolverSettings::default()).unwrap_err()),
            "radius"
        );
        let unstable = SolverSettings {
            dt: 2e-4,
            ..SolverSettings::paper_fd()
        };
        assert_eq!(name_of(check_run(&p, &unstable).unwrap_err()), "dt");
        assert_eq!(name_of(check_series(50.0, 1e-300).unwrap_err()), "every");
        assert!(check_series(2000.0, 0.5).is_ok());
    }

    #[test]
    fn the_stability_limit_is_forward_eulers() {
        // Paper grid: dx = 0.025 -> 1.5624e-4, above the paper's dt = 1e-4.
        let limit = paper_fd_max_dt(0.025);
        assert!((limit - 2.0 / 12801.0).abs() < 1e-15);
        assert!(limit > 1e-4);
        // 100 x (64 t_max) / dt_max: the default runs on to 64 t_max.
        assert_eq!(adaptive_step_cap(&SolverSettings::default()), 51_200_000);
    }
}
