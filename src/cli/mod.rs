//! Command-line front end.

/// `println!` for command output: a closed stdout (`droplet status DIR | head -1`) ends the
/// output quietly, as in other command-line tools, and the command finishes its work.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::write_out(format_args!($($arg)*))
    };
}

/// `eprintln!` for messages: a full or closed stderr (`2>/dev/full`) loses the message but never
/// panics, so the exit code stays the command's own.
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::cli::write_err(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprint!` without the line end (a message finished by a later [`errln!`]).
macro_rules! err {
    ($($arg:tt)*) => {
        $crate::cli::write_err(format_args!($($arg)*))
    };
}

mod audit;
mod bench;
mod boundaries;
mod continuation;
mod fit_h0;
mod line;
mod merge;
mod ode;
mod param_line;
mod plot;
mod run_settings;
mod simulate;
mod slurm;
mod stability;
mod status;
mod sweep;
mod truncation;

use clap::{Parser, Subcommand};

/// Map the phase diagram of a self-propelled, deformable droplet (Kitahata, Koyano,
/// Kobayashi & Nagayama). Every command that prints results accepts --json.
#[derive(Parser)]
#[command(name = "droplet", version, about, long_about = None, after_help = "Quick start:\n  droplet sweep sweeps/smoke.yaml      # coarse phase map in seconds\n  droplet plot out/smoke               # out/smoke/phase_map.png\n  droplet simulate --eta-t 0.085 --kappa2 0.112 --ic i --picture md.png")]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    Simulate(run_settings::Args),
    Sweep(sweep::Args),
    Status(status::Args),
    Plot(plot::Args),
    Audit(audit::Args),
    Ode(ode::Args),
    FitH0(fit_h0::Args),
    Merge(merge::Args),
    Slurm(slurm::Args),
    Bench(bench::Args),
    Stability(stability::Args),
    Continue(continuation::Args),
    Boundaries(boundaries::Args),
    Truncation(truncation::Args),
}

/// Exit codes: 0 success, 1 failure while working, 2 bad input.
pub fn main() -> i32 {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Simulate(a) => simulate::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::Status(a) => status::run(a),
        Command::Plot(a) => plot::run(a),
        Command::Audit(a) => audit::run(a),
        Command::Ode(a) => ode::run(a),
        Command::FitH0(a) => fit_h0::run(a),
        Command::Merge(a) => merge::run(a),
        Command::Slurm(a) => slurm::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Stability(a) => stability::run(a),
        // The general model's continuation (the MD branch on the x axis), or why not.
        Command::Continue(a) => continuation::run(a),
        Command::Boundaries(a) => boundaries::run(a),
        Command::Truncation(a) => truncation::run(a),
    };
    match result {
        Ok(()) => 0,
        Err(e) => {
            errln!("error: {}", e.message);
            e.code
        }
    }
}

/// An error with its exit code.
pub struct CliError {
    pub message: String,
    pub code: i32,
}

impl CliError {
    pub fn usage(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            code: 2,
        }
    }
}

impl From<droplet_sweep::error::SweepError> for CliError {
    fn from(e: droplet_sweep::error::SweepError) -> Self {
        Self {
            code: if e.is_user_error() { 2 } else { 1 },
            message: e.to_string(),
        }
    }
}

impl From<droplet_solver::error::SolverError> for CliError {
    fn from(e: droplet_solver::error::SolverError) -> Self {
        Self::usage(e.to_string())
    }
}

/// Checks `--n` for the root-finding commands (stability, continue, boundaries, truncation):
/// the one grid limit every command has (`droplet_solver::model::grid::check_n`).
pub fn check_grid(n: usize) -> Result<(), CliError> {
    droplet_solver::model::grid::check_n(n).map_err(|_| {
        CliError::usage(format!(
            "invalid --n {n}: an even integer from 16 to {}",
            droplet_solver::model::grid::MAX_N
        ))
    })
}

/// Parses `--axis`: the mirror line a state lies on.
pub fn mirror_axis(text: &str) -> Result<droplet_solver::model::mirror::MirrorLine, CliError> {
    match text {
        "x" => Ok(droplet_solver::model::mirror::MirrorLine::X),
        "diagonal" => Ok(droplet_solver::model::mirror::MirrorLine::Diagonal),
        other => Err(CliError::usage(format!(
            "invalid --axis `{other}`: x or diagonal"
        ))),
    }
}

/// Prints one JSON object. A closed pipe (`droplet ... --json | head`) is not an error.
pub fn print_json<T: serde::Serialize>(value: &T) {
    match serde_json::to_string_pretty(value) {
        Ok(text) => write_out(format_args!("{text}")),
        Err(e) => errln!("error: the result could not be written as JSON ({e})"),
    }
}

/// Writes one line of output (see `outln!`). A reader that went away (a closed pipe) is not
/// an error; any other failure to write is reported once on stderr, never a panic.
/// Writes `text` to stderr; a write that fails (a full or closed stderr) is dropped.
pub fn write_err(text: std::fmt::Arguments) {
    use std::io::Write;
    let _ = std::io::stderr().write_fmt(text);
}

pub fn write_out(line: std::fmt::Arguments) {
    use std::io::Write;
    use std::sync::atomic::{AtomicBool, Ordering};
    static REPORTED: AtomicBool = AtomicBool::new(false);
    if let Err(e) = writeln!(std::io::stdout(), "{line}") {
        if e.kind() != std::io::ErrorKind::BrokenPipe && !REPORTED.swap(true, Ordering::Relaxed) {
            errln!("warning: output could not be written ({e})");
        }
    }
}
