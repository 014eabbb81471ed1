//! `droplet plot`: the phase-map picture of a sweep directory.
use super::{print_json, CliError};
use std::path::PathBuf;

/// Draw a sweep's phase-map picture (Fig. 2a) from its stored runs.
///
/// Draw OUT/phase_map.png and OUT/phase_map.svg (paper Fig. 2a colours) from a sweep's runs;
/// points whose runs are not all finished (or are unreadable) are drawn as `missing`, and
/// then the command says so and exits 1. A finished map (its tables written) whose stored
/// runs lack points (unreadable, or of an older numerics) is not redrawn: plot says so and
/// exits 1, its pictures as they were. Refused while a sweep works on OUT: its own pictures
/// are drawn when it ends.
#[derive(clap::Args)]
pub struct Args {
    /// The sweep's output directory.
    out: PathBuf,
    /// Print the written paths as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let drawn = droplet_sweep::pictures::sweep_pictures::plot(&a.out)?;
    if a.json {
        print_json(&serde_json::json!({
            "files": drawn.files, "points": drawn.points, "missing": drawn.missing,
        }));
    } else {
        for f in &drawn.files {
            outln!("wrote {}", f.display());
        }
    }
    match drawn.missing {
        0 => Ok(()),
        n => Err(CliError {
            message: missing_message(n, drawn.points, &a.out),
            code: 1,
        }),
    }
}

/// What a picture with missing points means, and what to do.
pub fn missing_message(missing: usize, points: usize, dir: &std::path::Path) -> String {
    format!(
        "{missing} of {points} points are drawn as missing: a run is not finished or cannot be \
         read (`droplet status {0}` counts them; `droplet sweep` on {0} recomputes them)",
        dir.display()
    )
}
