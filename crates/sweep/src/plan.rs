//! Spec -> tasks: every (point, initial condition) pair is one run, keyed by a hash of
//! everything that determines its result.
use crate::spec::SweepSpec;
use droplet_solver::{InitialCondition, ModelParams, SolverSettings, SOLVER_VERSION};
use serde::Serialize;
use sha2::{Digest, Sha256};

/// One run of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Index of the point: `i_eta * n_kappa + i_kappa`.
    pub point: usize,
    /// Index of the initial condition in the spec.
    pub ic_index: usize,
    pub ic: InitialCondition,
    pub params: ModelParams,
    pub settings: SolverSettings,
    pub key: String,
}

/// All points and runs of a spec.
#[derive(Debug, Clone)]
pub struct Plan {
    /// `(eta_t, kappa2)` of each point.
    pub points: Vec<(f64, f64)>,
    pub tasks: Vec<Task>,
    pub ic_names: Vec<String>,
}

#[derive(Serialize)]
struct KeyMaterial<'a> {
    params: &'a ModelParams,
    ic: [f64; 4],
    settings: &'a SolverSettings,
    solver_version: &'a str,
}

/// Content key of a run: SHA-256 of the model parameters, the initial condition's values,
/// the solver settings and the solver's numerics version. Equal runs in two sweeps share it.
pub fn run_key(params: &ModelParams, ic: &InitialCondition, settings: &SolverSettings) -> String {
    let material = KeyMaterial {
        params,
        ic: [ic.vx, ic.vy, ic.a2, ic.b2],
        settings,
        solver_version: SOLVER_VERSION,
    };
    let json = serde_json::to_string(&material).expect("plain data serialises");
    let digest = Sha256::digest(json.as_bytes());
    digest.iter().take(16).map(|b| format!("{b:02x}")).collect()
}

/// Expands a spec into its points and tasks (point-major, initial conditions in spec order).
pub fn plan(spec: &SweepSpec) -> Plan {
    let mut points = Vec::new();
    let mut tasks = Vec::new();
    for &eta_t in &spec.eta_t {
        for &kappa2 in &spec.kappa2 {
            let point = points.len();
            points.push((eta_t, kappa2));
            let params = ModelParams {
                eta_t,
                kappa2,
                ..spec.params
            };
            for (ic_index, ic) in spec.initial_conditions.iter().enumerate() {
                tasks.push(Task {
                    point,
                    ic_index,
                    ic: ic.clone(),
                    params,
                    settings: spec.solver,
                    key: run_key(&params, ic, &spec.solver),
                });
            }
        }
    }
    Plan {
        points,
        tasks,
        ic_names: spec
            .initial_conditions
            .iter()
            .map(|i| i.name.clone())
            .collect(),
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
    }
}
