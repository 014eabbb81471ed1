//! The catalogue's cases for specs (geometry, settings that contradict each other, values
//! and structure, duplicated keys, sizes) and for reliability round 4's settings, spec
//! settings, Slurm values and grid checks ([`super::catalogue`] runs them).
use super::catalogue::{case, fast, simc, spec_case, Case};

/// The spec cases the catalogue runs before [`super::refusals`]' cases.
pub(super) fn structure() -> Vec<Case> {
    [spec_geometry_and_settings(), spec_values_and_structure()]
        .into_iter()
        .flatten()
        .collect()
}

/// The other spec cases and round 4's, run after [`super::refusals`]' cases.
pub(super) fn cases() -> Vec<Case> {
    [
        specs(),
        round_four_settings(),
        round_four_spec_settings(),
        round_four_slurm_values(),
        round_four_grid_checks(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// Specs: geometry out of range and settings that contradict each other.
fn spec_geometry_and_settings() -> Vec<Case> {
    vec![
        spec_case(
            "spec sigma below dx",
            ("solver:", "params: {sigma: 1.0e-4}\nsolver:"),
            &["params.sigma", "grid cell"],
        ),
        spec_case(
            "spec with the removed classify section",
            ("solver:", "classify: {beside_unstable: exclude}\nsolver:"),
            &["classify", "removed", "stable steady state"],
        ),
        spec_case(
            "spec stop_beside_saddle not true or false",
            ("solver:", "solver:\n  stop_beside_saddle: maybe"),
            &["solver.stop_beside_saddle", "maybe", "true"],
        ),
        spec_case(
            "spec stop_beside_saddle with the paper's test",
            (
                "solver:",
                "solver:\n  steady: test\n  stop_beside_saddle: true",
            ),
            &["solver.stop_beside_saddle", "Newton finish"],
        ),
        spec_case(
            "spec leap_departures not true or false",
            ("solver:", "solver:\n  leap_departures: 1"),
            &["solver.leap_departures", "1", "true"],
        ),
        spec_case(
            "spec sigma 10",
            ("solver:", "params: {sigma: 10}\nsolver:"),
            &["params.sigma"],
        ),
        spec_case(
            "spec radius below dx",
            ("solver:", "params: {radius: 0.5}\nsolver:"),
            &["params.radius"],
        ),
    ]
}

/// Specs: an unstable scheme, initial conditions, steps, unknown keys, YAML, sizes and types.
fn spec_values_and_structure() -> Vec<Case> {
    vec![
        spec_case(
            "spec unstable paper-fd",
            (
                "  n: 32\n  dt: 0.05\n",
                "  scheme: paper-fd\n  n: 64\n  dt: 0.01\n  tol: 0\n",
            ),
            &["solver.dt", "stability limit"],
        ),
        spec_case(
            "spec custom ic s >= 1",
            (
                "solver:",
                "initial_conditions: [\"custom:0,0,2,0\"]\nsolver:",
            ),
            &["initial_conditions", "< 1"],
        ),
        spec_case(
            "spec negative step",
            (
                "eta_t: [0.08]",
                "eta_t: {start: 0.07, stop: 0.08, step: -0.01}",
            ),
            &["grid.eta_t.step"],
        ),
        spec_case(
            "spec unknown key",
            ("name: m", "name: m\ncolour: red"),
            &["colour"],
        ),
        spec_case("spec not yaml", ("name: m", "name: [m"), &["(document)"]),
        spec_case("spec n huge", ("n: 32", "n: 100000"), &["solver.n"]),
        spec_case(
            "spec t_max inf",
            ("t_max: 10", "t_max: .inf"),
            &["solver.t_max"],
        ),
        spec_case(
            "spec mass string",
            ("solver:", "params: {mass: heavy}\nsolver:"),
            &["params.mass"],
        ),
    ]
}

/// Specs: duplicated keys, sizes refused at once.
fn specs() -> Vec<Case> {
    vec![
        // Specs: duplicated keys on their own line, sizes refused at once.
        spec_case(
            "spec name twice",
            ("t_max: 10", "t_max: 10\nname: x"),
            &[":9: `name`", "each key once"],
        ),
        spec_case(
            "spec grid axis twice",
            ("kappa2: [0.11]", "kappa2: [0.11]\n  eta_t: [0.09]"),
            &[":5: `grid.eta_t`", "each key once"],
        ),
        fast(Case {
            what: "spec refine min_step above the grid step",
            args: vec![
                "sweep".into(),
                "SPEC:name: m\ngrid:\n  eta_t: {start: 0.07, stop: 0.09, step: 0.01}\n  kappa2: {start: 0.1, stop: 0.12, step: 0.01}\nrefine: {levels: 1, min_step: {eta_t: 1.0e3, kappa2: 1.0e3}}\nsolver:\n  n: 32\n  dt: 0.05\n  t_max: 10\n".into(),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["refine.min_step.eta_t", "half the grid's eta_t step"],
            within: 1.0,
        }),
        fast(Case {
            what: "spec list of 400000 values",
            args: vec![
                "sweep".into(),
                format!(
                    "SPEC:grid:\n  eta_t: [{}]\n  kappa2: [0.1]\n",
                    (0..400_000).map(|i| (i + 1).to_string()).collect::<Vec<_>>().join(",")
                ),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["grid.eta_t", "a list of 400000 values", "at most 100000"],
            within: 1.0,
        }),
        fast(Case {
            what: "spec of 5 MB",
            args: vec![
                "sweep".into(),
                format!("SPEC:name: m\n#{}\n", "x".repeat(5 << 20)),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["(file)", "at most 4194304 bytes"],
            within: 1.0,
        }),
        fast(Case {
            what: "spec name of 1 MB",
            args: vec![
                "sweep".into(),
                format!(
                    "SPEC:name: {}\ngrid:\n  eta_t: [0.08]\n  kappa2: [0.11]\n",
                    "n".repeat(1 << 20)
                ),
                "--out".into(),
                "DIR/out".into(),
            ],
            code: 2,
            says: &["`name`", "a name of 1048576 characters", "at most 100"],
            within: 1.0,
        }),
    ]
}

/// Reliability round 4: an initial speed that overflows, options a run would ignore.
fn round_four_settings() -> Vec<Case> {
    vec![
        // Reliability round 4: an initial speed that overflows the first step (it hung the
        // K-mode eigenvalues), settings a run would ignore, values that would change a Slurm
        // script, and checks that disagreed between commands.
        fast(simc(
            "K-mode IC at speed 1e308",
            &[
                "--modes",
                "3",
                "--n",
                "64",
                "--t-max",
                "1",
                "--no-run-on",
                "--ic",
                "custom:1e308,0,0.1,0,0,0",
            ],
            &["initial speed", "at most 10"],
            1.0,
        )),
        spec_case(
            "spec IC at speed 1e308",
            (
                "name: m\n",
                "name: m\ninitial_conditions: ['custom:1e308,0,0.1,0']\n",
            ),
            &["initial_conditions", "initial speed"],
        ),
        fast(simc(
            "--tol with --modes 3 and paper-fd",
            &[
                "--modes", "3", "--n", "64", "--scheme", "paper-fd", "--tol", "1e-5",
            ],
            &["--tol", "fixed step"],
            1.0,
        )),
        fast(simc(
            "--dt-max with --modes 3 and --tol 0",
            &["--modes", "3", "--n", "64", "--tol", "0", "--dt-max", "0.1"],
            &["--dt-max", "fixed steps"],
            1.0,
        )),
        fast(simc(
            "--no-orientation-flow with --modes 3",
            &["--modes", "3", "--n", "64", "--no-orientation-flow"],
            &["--no-orientation-flow", "2-mode runs only"],
            1.0,
        )),
        fast(simc(
            "--no-run-on with paper-fd",
            &["--scheme", "paper-fd", "--no-run-on"],
            &["--no-run-on", "Newton finish"],
            1.0,
        )),
        fast(simc(
            "--no-projective-steps with fixed steps",
            &["--tol", "0", "--no-projective-steps"],
            &["--no-projective-steps", "fixed steps"],
            1.0,
        )),
        fast(simc(
            "--dt-max with fixed steps",
            &["--tol", "0", "--dt-max", "0.5"],
            &["--dt-max", "fixed steps"],
            1.0,
        )),
        fast(simc(
            "--modes 0",
            &["--modes", "0"],
            &["--modes 0", "from 2"],
            1.0,
        )),
        fast(simc(
            "--modes 1",
            &["--modes", "1"],
            &["--modes 1", "from 2"],
            1.0,
        )),
    ]
}

/// Reliability round 4: spec settings a run would ignore.
fn round_four_spec_settings() -> Vec<Case> {
    vec![
        spec_case(
            "spec h0 for a PDE run",
            ("dt: 0.05", "dt: 0.05\n  h0: 0.2"),
            &["solver.h0", "ODE"],
        ),
        spec_case(
            "spec orientation_flow with params.modes 3",
            ("name: m\n", "name: m\nparams: {modes: 3}\n"),
            &[],
        )
        .replaced(
            "  t_max: 10\n",
            "  t_max: 10\n  orientation_flow: false\n",
            &["solver.orientation_flow", "modes > 2"],
        ),
        spec_case(
            "spec landing with steady test",
            ("dt: 0.05", "dt: 0.05\n  steady: test\n  landing: false"),
            &["solver.landing", "Newton finish"],
        ),
        spec_case(
            "spec n with model ode",
            ("name: m\n", "name: m\nmodel: ode\n"),
            &["solver.n", "no grid"],
        ),
        spec_case(
            "spec params.modes 1",
            ("name: m\n", "name: m\nparams: {modes: 1}\n"),
            &["params.modes", "from 2"],
        ),
        spec_case(
            "spec modes as a grid axis",
            ("  kappa2: [0.11]\n", "  modes: [2, 3]\n"),
            &["grid.modes", "not an axis", "params.modes"],
        ),
    ]
}

/// Reliability round 4: values that would change a Slurm script.
fn round_four_slurm_values() -> Vec<Case> {
    vec![
        fast(case(
            "slurm partition with a newline",
            &[
                "slurm",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shards",
                "2",
                "--partition",
                "p\necho INJECTED",
                "--out",
                "DIR/out",
            ],
            2,
            &["--partition", "cannot be written into a Slurm script"],
        )),
        fast(case(
            "slurm time with a blank",
            &[
                "slurm",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shards",
                "2",
                "--time",
                "1:00 --wrap=x",
                "--out",
                "DIR/out",
            ],
            2,
            &["--time", "blanks"],
        )),
        fast(case(
            "slurm 100000 shards for 4 runs",
            &[
                "slurm",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shards",
                "100000",
                "--out",
                "DIR/out",
            ],
            2,
            &["--shards 100000", "4 runs"],
        )),
    ]
}

/// Reliability round 4: checks of `--n` and windows that disagreed between commands; commands
/// that do not exist.
fn round_four_grid_checks() -> Vec<Case> {
    vec![
        fast(case(
            "boundaries --n 64,64",
            &["boundaries", "--n", "64,64", "--out", "DIR/b"],
            2,
            &["--n", "given twice"],
        )),
        fast(case(
            "boundaries --n 8192",
            &["boundaries", "--n", "8192", "--out", "DIR/b"],
            2,
            &["--n 8192", "16 to 4096"],
        )),
        fast(case(
            "stability --n 8192",
            &[
                "stability",
                "--eta-t",
                "0.085",
                "--kappa2",
                "0.13",
                "--n",
                "8192",
            ],
            2,
            &["--n 8192", "16 to 4096"],
        )),
        fast(case(
            "boundaries window 1e-300..1e-299",
            &["boundaries", "--eta-t", "1e-300,1e-299", "--out", "DIR/b"],
            2,
            &["--eta-t", "HI - LO"],
        )),
        fast(case(
            "continue --kappa2 with --set kappa2",
            &[
                "continue",
                "--kappa2",
                "0.13",
                "--set",
                "kappa2=0.2",
                "--from",
                "0.07",
                "--to",
                "0.1",
                "--n",
                "64",
                "--out",
                "DIR/c",
            ],
            2,
            &["--set kappa2=0.2", "give it once"],
        )),
        case("unknown command", &["fly"], 2, &["fly"]),
        case("no command", &[], 2, &["Usage"]),
    ]
}
