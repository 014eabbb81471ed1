//! Spec -> tasks: every (point, initial condition) pair is one run, keyed by a hash of
//! everything that determines its result.
use crate::spec::axes::{Plane, Point};
use crate::spec::lattice::{Lattice, Node};
use crate::spec::SweepSpec;
use droplet_solver::{
    contract::settings::SolverSettings, model::initial::InitialCondition,
    model::params::ModelParams,
};
use serde::Serialize;
use sha2::{Digest, Sha256};

/// One run of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Index of the point: `i_x * n_y + i_y` on a uniform grid.
    pub point: usize,
    /// Index of the initial condition in the spec.
    pub ic_index: usize,
    pub ic: InitialCondition,
    pub params: ModelParams,
    pub settings: SolverSettings,
    pub key: String,
}

/// All points and runs of a spec. The points are stored (16 bytes each); the runs are made
/// on demand from a point and an initial condition ([`Plan::task`]), so a plan's memory does
/// not grow with the number of runs.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The swept parameters.
    pub plane: Plane,
    /// `[x, y, z]` of each point ([`Plane`]).
    pub points: Vec<Point>,
    /// Refinement level of each point (0: the spec's grid; [`crate::map::refine`]).
    pub levels: Vec<u32>,
    /// Cell size `(dx, dy)` of each point: the grid step of its level (`NaN` on
    /// an axis given as a list of one value).
    pub cells: Vec<(f64, f64)>,
    pub ic_names: Vec<String>,
    ics: Vec<InitialCondition>,
    params: ModelParams,
    settings: SolverSettings,
}

impl Plan {
    /// Number of runs: points x initial conditions.
    pub fn len(&self) -> usize {
        self.points.len() * self.ics.len()
    }

    /// True when the plan has no runs.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Run `index` (point-major, initial conditions in spec order), key included.
    pub fn task(&self, index: usize) -> Task {
        let (point, ic_index) = (index / self.ics.len(), index % self.ics.len());
        let (mut params, mut settings) = (self.params, self.settings);
        self.plane
            .apply(self.points[point], &mut params, &mut settings);
        // What the run reads, and only that, is what it is keyed and recorded with.
        let settings = settings.honoured(params.modes);
        let ic = &self.ics[ic_index];
        Task {
            point,
            ic_index,
            ic: ic.clone(),
            params,
            settings,
            key: run_key(&params, ic, &settings),
        }
    }

    /// Every run, in order.
    pub fn tasks(&self) -> impl ExactSizeIterator<Item = Task> + '_ {
        (0..self.len()).map(|i| self.task(i))
    }
}

/// Number of runs a spec asks for (points x initial conditions), computed without planning
/// them (saturating, so that an absurd spec cannot overflow). With `refine:` the most it can
/// ask for: every cell split down to the finest level.
pub fn run_count(spec: &SweepSpec) -> u64 {
    point_count(spec).saturating_mul(spec.initial_conditions.len() as u64)
}

/// Number of points of the spec's grid, or with `refine:` of its finest lattice.
fn point_count(spec: &SweepSpec) -> u64 {
    let count = |a: &Option<crate::spec::Swept>| a.as_ref().map_or(1, |a| a.values.len() as u64);
    let (ne, nk) = (spec.grid.x.values.len() as u64, count(&spec.grid.y));
    match &spec.refine {
        None => ne.saturating_mul(nk).saturating_mul(count(&spec.grid.z)),
        Some(l) => {
            let fine = |n: u64| (n - 1).saturating_mul(1 << l.refine.levels) + 1;
            fine(ne)
                .saturating_mul(fine(nk))
                .saturating_mul(count(&spec.grid.z))
        }
    }
}

/// Default of `--max-runs`: the most runs one sweep may plan (1e6 runs at N = 192 are about
/// two CPU-months; the ODE model's dense map is 17 324).
pub const DEFAULT_MAX_RUNS: u64 = 1_000_000;

/// Refuses a spec with more than `max_runs` runs, before anything is planned or written.
pub fn check_size(spec: &SweepSpec, max_runs: u64) -> Result<(), crate::error::SweepError> {
    let count = run_count(spec);
    if count > max_runs {
        return Err(crate::error::SweepError::TooLarge {
            runs: count,
            points: point_count(spec),
            limit: max_runs,
        });
    }
    Ok(())
}

#[derive(Serialize)]
struct KeyMaterial<'a> {
    params: KeyedParams,
    ic: [f64; 4],
    /// The condition's amplitudes of modes 3.. (absent for 2-mode conditions, whose keys
    /// are as before).
    #[serde(skip_serializing_if = "no_higher_modes")]
    ic_higher: &'a [[f64; 2]],
    settings: KeyedSettings<'a>,
    solver_version: &'a str,
}

/// The model parameters as a key hashes them: all but the shape modes and their friction
/// law, which it hashes with the settings, where run records held them before they were
/// model parameters, so that every stored run keeps its key.
#[derive(Serialize)]
struct KeyedParams {
    eta_t: f64,
    kappa2: f64,
    eta2: f64,
    radius: f64,
    sigma: f64,
    box_len: f64,
    mass: f64,
}

/// The settings as a key hashes them: with the model's shape modes and friction law after
/// them, each only when it is not its default (a 2-mode run's key holds neither).
#[derive(Serialize)]
struct KeyedSettings<'a> {
    #[serde(flatten)]
    settings: &'a SolverSettings,
    #[serde(skip_serializing_if = "is_two")]
    modes: usize,
    #[serde(skip_serializing_if = "is_zero")]
    eta_k_exponent: f64,
}

fn is_two(k: &usize) -> bool {
    *k == 2
}

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// The key's parts of `params` and `settings`. Every field of [`ModelParams`] is named here,
/// so that a new parameter cannot be left out of keys unnoticed.
fn keyed<'a>(
    params: &ModelParams,
    settings: &'a SolverSettings,
) -> (KeyedParams, KeyedSettings<'a>) {
    let ModelParams {
        eta_t,
        kappa2,
        eta2,
        radius,
        sigma,
        box_len,
        mass,
        modes,
        eta_k_exponent,
    } = *params;
    let params = KeyedParams {
        eta_t,
        kappa2,
        eta2,
        radius,
        sigma,
        box_len,
        mass,
    };
    let settings = KeyedSettings {
        settings,
        modes,
        eta_k_exponent,
    };
    (params, settings)
}

fn no_higher_modes(higher: &&[[f64; 2]]) -> bool {
    higher.is_empty()
}

/// Content key of a run: SHA-256 of the model parameters, the initial condition's values
/// (every mode it gives), the solver settings the run reads (`SolverSettings::honoured`: a
/// PDE run's key holds no `h0`, a K-mode run's no `tol`) and the solver's numerics version.
/// Equal runs in two sweeps share it.
pub fn run_key(params: &ModelParams, ic: &InitialCondition, settings: &SolverSettings) -> String {
    written_key(params, ic, &settings.honoured(params.modes))
}

/// The key of a run with `settings` hashed as they are written, unread settings included:
/// the key stored runs had before keys held only what a run reads. A stored run whose file
/// has this name, and whose [`run_key`] differs, is renamed to the latter when the store is
/// opened to be written (`Store::upgrade`), never recomputed.
pub fn written_key(
    params: &ModelParams,
    ic: &InitialCondition,
    settings: &SolverSettings,
) -> String {
    short_hash(key_material(params, ic, settings).as_bytes())
}

/// SHA-256 of `bytes`, its first 16 bytes in hex: a run's key, and its outcome's digest.
pub(crate) fn short_hash(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .take(16)
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The text [`run_key`] hashes.
fn key_material(params: &ModelParams, ic: &InitialCondition, settings: &SolverSettings) -> String {
    let (keyed_params, keyed_settings) = keyed(params, settings);
    let material = KeyMaterial {
        params: keyed_params,
        ic: [ic.vx, ic.vy, ic.a2, ic.b2],
        ic_higher: &ic.higher,
        settings: keyed_settings,
        solver_version: droplet_solver::solver_version(settings.model, params.modes),
    };
    serde_json::to_string(&material).expect("plain data serialises")
}

/// Smallest gap between the values of an axis (`NaN` for one value).
fn spacing(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let gap = v
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    if gap.is_finite() {
        gap
    } else {
        f64::NAN
    }
}

/// Expands a spec into its points (z-major, then x-major) and initial conditions; runs are made on
/// demand. Check [`check_size`] first: the points are allocated here. With `refine:` these
/// are the points of level 0; [`plan_nodes`] plans the refined point set.
pub fn plan(spec: &SweepSpec) -> Plan {
    let points = spec.grid.points();
    let cell = (spacing(&spec.grid.x.values), spacing(&spec.grid.y_values()));
    point_set(
        spec,
        points.clone(),
        vec![0; points.len()],
        vec![cell; points.len()],
    )
}

/// The plan of a refined point set: `nodes` on `lattice`, each with its level and the value of
/// the slice axis `z` it lies in (0 without one).
pub fn plan_nodes(spec: &SweepSpec, lattice: &Lattice, nodes: &[(Node, u32, f64)]) -> Plan {
    point_set(
        spec,
        nodes
            .iter()
            .map(|&(n, _, z)| {
                let (x, y) = lattice.coords(n);
                [x, y, z]
            })
            .collect(),
        nodes.iter().map(|&(_, l, _)| l).collect(),
        nodes
            .iter()
            .map(|&(_, l, _)| lattice.cell_size(l))
            .collect(),
    )
}

/// A plan of arbitrary points with the spec's initial conditions, parameters and settings:
/// the runs of `points` as the sweep of `spec` runs them (a map's runs computed again).
pub fn point_set(
    spec: &SweepSpec,
    points: Vec<Point>,
    levels: Vec<u32>,
    cells: Vec<(f64, f64)>,
) -> Plan {
    Plan {
        plane: spec.grid.plane(),
        points,
        levels,
        cells,
        ic_names: spec
            .initial_conditions
            .iter()
            .map(|i| i.name.clone())
            .collect(),
        ics: spec.initial_conditions.clone(),
        params: spec.params,
        settings: spec.solver,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_depend_on_what_determines_the_result() {
        let p = ModelParams::default();
        let ic = InitialCondition::parse("i").unwrap();
        let s = SolverSettings::default();
        let k = run_key(&p, &ic, &s);
        assert_eq!(k, run_key(&p, &ic, &s));
        assert_ne!(k, run_key(&ModelParams { kappa2: 0.113, ..p }, &ic, &s));
        assert_ne!(k, run_key(&p, &InitialCondition::parse("ii").unwrap(), &s));
        assert_ne!(k, run_key(&p, &ic, &SolverSettings { n: 128, ..s }));
        assert_eq!(k.len(), 32);
        // Conditions that differ in a higher mode only are different runs; a 2-mode
        // condition's key material is as it was before modes 3.. existed.
        let (p4, k4) = (p.with_modes(4), s);
        let with = |a3: f64| {
            let ic = InitialCondition::parse(&format!("custom:0.5,0,-0.1,0,{a3},0")).unwrap();
            run_key(&p4, &ic, &k4)
        };
        assert_ne!(with(0.1), with(-0.1));
        assert!(!key_material(&p, &ic, &s).contains("ic_higher"));
        // What a run does not read is not part of its key: a PDE run's h0 (the spec bug set
        // it to n), a K-mode run's orientation flow. A run that sets neither keeps its key.
        // A K-mode run's tol and landing are read (its steps are adaptive and it lands, as
        // a 2-mode run does).
        assert_eq!(k, run_key(&p, &ic, &SolverSettings { h0: 192.0, ..s }));
        assert_eq!(k, written_key(&p, &ic, &s));
        assert_ne!(k, written_key(&p, &ic, &SolverSettings { h0: 192.0, ..s }));
        assert_eq!(
            run_key(&p4, &ic, &k4),
            run_key(
                &p4,
                &ic,
                &SolverSettings {
                    orientation_flow: false,
                    ..k4
                }
            )
        );
        assert_ne!(
            run_key(&p4, &ic, &k4),
            run_key(
                &p4,
                &ic,
                &SolverSettings {
                    landing: false,
                    ..k4
                }
            )
        );
        assert_ne!(
            run_key(&p4, &ic, &k4),
            run_key(&p4, &ic, &SolverSettings { tol: 1e-6, ..k4 })
        );
        let ode = SolverSettings::ode();
        assert_ne!(
            run_key(&p, &ic, &ode),
            run_key(&p, &ic, &SolverSettings { h0: 0.2, ..ode })
        );
    }

    #[test]
    fn a_k_mode_key_hashes_the_shape_modes_with_the_settings_as_records_held_them() {
        // Keys of runs stored before the shape modes were model parameters: the modes and
        // the friction law after the settings, each only when not its default.
        let ic = InitialCondition::parse("i").unwrap();
        let s = SolverSettings::default();
        let p = ModelParams {
            eta_k_exponent: -1.0,
            ..ModelParams::default().with_modes(3)
        };
        let text = key_material(&p, &ic, &s);
        let settings = serde_json::to_string(&s).unwrap();
        // The parameters as every stored record's key held them.
        let params = r#"{"eta_t":0.085,"kappa2":0.112,"eta2":0.1,"radius":1.0,"sigma":0.03,"box_len":7.0,"mass":0.1}"#;
        assert!(
            text.starts_with(&format!("{{\"params\":{params},")),
            "{text}"
        );
        assert!(
            text.contains(&format!(
                "\"settings\":{},\"modes\":3,\"eta_k_exponent\":-1.0}}",
                settings.trim_end_matches('}')
            )),
            "{text}"
        );
        let two = key_material(&ModelParams::default(), &ic, &s);
        assert!(two.contains(&format!("\"settings\":{settings},")), "{two}");
    }

    #[test]
    fn lazy_tasks_are_point_major_and_sizes_are_checked_before_planning() {
        let spec = crate::spec::parse(
            "grid:\n  eta_t: [0.08, 0.09]\n  kappa2: [0.11, 0.12, 0.13]\ninitial_conditions: [i, iv]\n",
            "t.yaml",
            "t",
        )
        .unwrap();
        let p = plan(&spec);
        assert_eq!((p.len(), run_count(&spec)), (12, 12));
        let t = p.task(7);
        assert_eq!((t.point, t.ic_index, t.ic.name.as_str()), (3, 1, "iv"));
        assert_eq!((t.params.eta_t, t.params.kappa2), (0.09, 0.11));
        assert_eq!(t.key, run_key(&t.params, &t.ic, &spec.solver));
        assert_eq!(p.tasks().count(), 12);
        assert!(check_size(&spec, 12).is_ok());
        assert!(matches!(
            check_size(&spec, 11),
            Err(crate::error::SweepError::TooLarge {
                runs: 12,
                limit: 11,
                ..
            })
        ));
    }

    #[test]
    fn any_axis_sets_its_parameter_and_the_paper_plane_keeps_its_keys() {
        let parse = |text: &str| crate::spec::parse(text, "t.yaml", "t").unwrap();
        // The same points written as the paper's plane, its axes in the other order, or one
        // axis with the other parameter fixed: the same runs, keys included.
        let paper = plan(&parse("grid:\n  eta_t: [0.08, 0.09]\n  kappa2: [0.12]\n"));
        let swapped = plan(&parse("grid:\n  kappa2: [0.12]\n  eta_t: [0.08, 0.09]\n"));
        let line = plan(&parse(
            "params: {kappa2: 0.12}\ngrid:\n  eta_t: [0.08, 0.09]\n",
        ));
        let keys = |p: &Plan| p.tasks().map(|t| t.key).collect::<Vec<_>>();
        assert_eq!(keys(&paper), keys(&swapped));
        assert_eq!(keys(&paper), keys(&line));
        // A solver setting and a model parameter as axes.
        let p = plan(&parse("grid:\n  n: [64, 128]\n  mass: [0.05]\n"));
        let t = p.task(p.ic_names.len());
        assert_eq!((t.settings.n, t.params.mass), (128, 0.05));
        assert_eq!(t.key, run_key(&t.params, &t.ic, &t.settings));
        assert_ne!(t.key, p.task(0).key);
    }

    #[test]
    fn a_refined_spec_is_sized_by_its_finest_lattice() {
        let spec = crate::spec::parse(
            "grid:\n  eta_t: {start: 0.08, stop: 0.09, step: 0.01}\n  kappa2: {start: 0.1, stop: 0.12, step: 0.01}\ninitial_conditions: [i, iv]\nrefine: {levels: 2}\n",
            "t.yaml",
            "t",
        )
        .unwrap();
        // 2 x 3 points at level 0; every cell split twice: 5 x 9 points, 2 runs each.
        assert_eq!(run_count(&spec), 90);
        assert_eq!(plan(&spec).len(), 12);
        assert!(check_size(&spec, 89).is_err());
    }
}
