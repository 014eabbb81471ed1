//! The catalogue's cases for negative values, files that cannot be read or written, missing
//! sweeps and bad arguments, sizes out of range and parameter windows beyond the model's
//! limits ([`super::catalogue`] runs them; specs in [`super::spec_refusals`]).
use super::catalogue::{case, fast, simc, Case};

pub(super) fn cases() -> Vec<Case> {
    [
        negative_values(),
        unreadable_inputs_and_unwritable_outputs(),
        missing_sweeps_and_bad_arguments(),
        sizes_out_of_range(),
        windows_beyond_the_models_limits(),
        boundary_windows_beyond_the_models_limits(),
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
