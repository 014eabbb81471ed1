//! The catalogue's cases for negative values, files that cannot be read or written,
//! parameter windows beyond the model's limits, specs, and reliability round 4
//! ([`super::catalogue`] runs them).
use super::catalogue::{case, fast, simc, spec_case, Case};

pub(super) fn cases() -> Vec<Case> {
    [
        negative_values(),
        unreadable_inputs_and_unwritable_outputs(),
        missing_sweeps_and_bad_arguments(),
        sizes_out_of_range(),
        windows_beyond_the_models_limits(),
        boundary_windows_beyond_the_models_limits(),
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

/// Negative numbers: values, refused with the field's message.
fn negative_values() -> Vec<Case> {
    vec![
        // Negative numbers are values, rejected with the field's message.
        Case {
            what: "negative eta_t first",
            args: ["simulate", "--eta-t", "-0.1", "--kappa2", "0.1"]
                .iter()
                .map(|s| s.to_string())
                .collect(),
            code: 2,
            says: &["eta_t", "> 0"],
            within: 5.0,
        },
        case(
            "negative kappa2",
            &["simulate", "--eta-t", "0.085", "--kappa2", "-1"],
            2,
            &["kappa2", ">= 0"],
        ),
        simc("negative mass", &["--mass", "-0.1"], &["mass"], 5.0),
        simc("negative dt", &["--dt", "-0.01"], &["dt"], 5.0),
        simc("negative t_max", &["--t-max", "-5"], &["t_max"], 5.0),
        simc("zero eta2", &["--eta2", "0"], &["eta2"], 5.0),
        simc("infinite box", &["--box-len", "inf"], &["box_len"], 5.0),
    ]
}

/// Files that cannot be read, and outputs that cannot be written.
fn unreadable_inputs_and_unwritable_outputs() -> Vec<Case> {
    vec![
        // Files that cannot be read, and outputs that cannot be written.
        case(
            "missing spec file",
            &["sweep", "DIR/none.yaml"],
            2,
            &["none.yaml", "cannot be read"],
        ),
        case(
            "spec is a directory",
            &["sweep", "DIR"],
            2,
            &["cannot be read"],
        ),
        case(
            "spec not UTF-8",
            &["sweep", "BINARY"],
            2,
            &["bin.yaml", "UTF-8"],
        ),
        case(
            "out under a regular file",
            &[
                "sweep",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\nsolver: {n: 32, t_max: 1}\n",
                "--out",
                "FILE/out",
            ],
            2,
            &["output directory", "--out"],
        ),
        case(
            "slurm out under a regular file",
            &[
                "slurm",
                "SPEC:name: m\ngrid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shards",
                "2",
                "--out",
                "FILE/out",
            ],
            2,
            &["output directory"],
        ),
        case(
            "ode out under a regular file",
            &[
                "ode",
                "bifurcation",
                "--kappa2",
                "0.13",
                "--from",
                "0.07",
                "--to",
                "0.1",
                "--out",
                "FILE/out",
            ],
            2,
            &["output directory"],
        ),
    ]
}

/// An output under a regular file, commands on a directory that holds no sweep, and arguments
/// no command can take.
fn missing_sweeps_and_bad_arguments() -> Vec<Case> {
    vec![
        case(
            "fit-h0 out under a regular file",
            &["fit-h0", "--n", "32", "--out", "FILE/out"],
            2,
            &["output directory"],
        ),
        case(
            "status of no sweep",
            &["status", "DIR/nothing"],
            2,
            &["holds no sweep"],
        ),
        case(
            "merge of no sweep",
            &["merge", "DIR/nothing"],
            2,
            &["holds no sweep"],
        ),
        case(
            "plot of no sweep",
            &["plot", "DIR/nothing"],
            2,
            &["holds no sweep"],
        ),
        case(
            "sweep --jobs 0",
            &[
                "sweep",
                "SPEC:grid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--jobs",
                "0",
            ],
            2,
            &["--jobs"],
        ),
        case(
            "bad shard",
            &[
                "sweep",
                "SPEC:grid: {eta_t: [0.08], kappa2: [0.11]}\n",
                "--shard",
                "3/3",
            ],
            2,
            &["shard"],
        ),
        case(
            "ode reversed line",
            &[
                "ode",
                "bifurcation",
                "--kappa2",
                "0.13",
                "--from",
                "0.1",
                "--to",
                "0.07",
            ],
            2,
            &["from < to"],
        ),
    ]
}

/// Sizes that would run for ever: the h0 fit's step, the reduced model's samples and radius.
fn sizes_out_of_range() -> Vec<Case> {
    vec![
        Case {
            within: 1.0,
            ..case(
                "fit-h0 step 1e-300",
                &["fit-h0", "--step", "1e-300", "--out", "DIR/h0"],
                2,
                &["--step", "more than"],
            )
        },
        Case {
            within: 1.0,
            ..case(
                "ode line of 1e12 samples",
                &[
                    "ode",
                    "bifurcation",
                    "--kappa2",
                    "0.13",
                    "--from",
                    "0.07",
                    "--to",
                    "0.1",
                    "--steps",
                    "1000000000000",
                    "--out",
                    "DIR/ode",
                ],
                2,
                &["steps"],
            )
        },
        case(
            "ode negative radius",
            &["ode", "coefficients", "--radius", "-1"],
            2,
            &["radius"],
        ),
    ]
}

/// Parameter lines beyond the model's limits.
fn windows_beyond_the_models_limits() -> Vec<Case> {
    vec![
        // Parameter windows beyond the model's limits are refused before any work, naming the
        // option (a line to 1e10 once gave a wrong onset of motion, 1e300 wrong states).
        fast(case(
            "continue to 1e10",
            &[
                "continue", "--kappa2", "0.13", "--from", "0.07", "--to", "1e10", "--n", "64",
                "--branch", "ic", "--out", "DIR/c",
            ],
            2,
            &["--to", "at most 10"],
        )),
        fast(case(
            "continue at kappa2 1e300",
            &[
                "continue", "--kappa2", "1e300", "--from", "0.07", "--to", "0.1", "--n", "64",
                "--out", "DIR/c",
            ],
            2,
            &["--kappa2", "at most 10"],
        )),
        fast(case(
            "continue from -inf",
            &[
                "continue", "--kappa2", "0.13", "--from", "-inf", "--to", "0.1", "--out", "DIR/c",
            ],
            2,
            &["--from", "finite"],
        )),
        fast(case(
            "ode line to 1e300",
            &[
                "ode",
                "bifurcation",
                "--kappa2",
                "0.13",
                "--from",
                "0.07",
                "--to",
                "1e300",
                "--out",
                "DIR/ode",
            ],
            2,
            &["--to", "at most 10"],
        )),
    ]
}

/// Boundary windows and seeds beyond the model's limits.
fn boundary_windows_beyond_the_models_limits() -> Vec<Case> {
    vec![
        fast(case(
            "boundaries window to 1e300",
            &[
                "boundaries",
                "--eta-t",
                "0.07,1e300",
                "--n",
                "64",
                "--out",
                "DIR/b",
            ],
            2,
            &["--eta-t", "at most 10"],
        )),
        fast(case(
            "boundaries negative window",
            &["boundaries", "--eta-t", "-0.1,0.1", "--out", "DIR/b"],
            2,
            &["--eta-t", "-0.1,0.1", "0 < LO < HI"],
        )),
        fast(case(
            "stability seed of negative numbers",
            &[
                "stability",
                "--eta-t",
                "0.085",
                "--kappa2",
                "0.112",
                "--seed",
                "-0.5,-2",
                "--n",
                "64",
            ],
            2,
            &["--seed", "|SHAPE| < 1"],
        )),
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
