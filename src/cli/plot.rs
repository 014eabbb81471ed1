//! `droplet plot`: the phase-map picture of a sweep directory.
use super::{print_json, CliError};
use std::path::PathBuf;

/// Draw OUT/phase_map.png and OUT/phase_map.svg (paper Fig. 2a colours) from a sweep's runs;
/// points whose runs are not all finished are drawn as `missing`.
#[derive(clap::Args)]
pub struct Args {
    /// The sweep's output directory.
    out: PathBuf,
    /// Print the written paths as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let files = droplet_sweep::pictures::plot(&a.out)?;
    if a.json {
        print_json(&serde_json::json!({ "files": files }));
    } else {
        for f in files {
            println!("wrote {}", f.display());
        }
    }
    Ok(())
}
