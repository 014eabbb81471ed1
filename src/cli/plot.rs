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
///
/// With --beside OTHER: draw OUT/beside.png and .svg instead, OTHER's map on the left and
/// OUT's on the right, the exact boundaries of both on each (OUT's solid black, OTHER's dashed
/// purple; those `droplet boundaries --out` put in each directory), and print
/// how much of the window each label covers in each map and which labels change at the
/// points both maps hold. Both must be finished maps of the same plane (their tables
/// written); a committed map (tables only) will do.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  droplet plot out/smoke\n  droplet plot results/fig2a-modes --beside results/fig2a-map   # modes 2..4 beside the paper's 2 modes"
)]
pub struct Args {
    /// The sweep's output directory.
    out: PathBuf,
    /// Another finished map of the same plane to draw OUT beside (OUT/beside.png), with the
    /// label areas and changes from it.
    #[arg(long, value_name = "OTHER")]
    beside: Option<PathBuf>,
    /// Print the written paths as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    if let Some(other) = &a.beside {
        return beside(&a.out, other, a.json);
    }
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

/// `plot OUT --beside OTHER`.
fn beside(out: &std::path::Path, other: &std::path::Path, json: bool) -> Result<(), CliError> {
    let c = droplet_sweep::pictures::map_comparison::compare(out, other)?;
    if json {
        print_json(&serde_json::to_value(&c).expect("plain data"));
        return Ok(());
    }
    for f in &c.files {
        outln!("wrote {}", f.display());
    }
    outln!(
        "area of the window each label covers ({} = {}, {} = {}):",
        other.display(),
        c.other_model,
        out.display(),
        c.this_model
    );
    outln!(
        "  {:<8} {:>12} {:>12} {:>12}",
        "label",
        "other",
        "this",
        "change"
    );
    for a in &c.areas {
        outln!(
            "  {:<8} {:>12.4e} {:>12.4e} {:>+12.4e}",
            a.label,
            a.other,
            a.this,
            a.this - a.other
        );
    }
    let changed: usize = c.changes.iter().map(|ch| ch.points).sum();
    outln!(
        "{} points in both maps, {changed} with another label:",
        c.common_points
    );
    for ch in &c.changes {
        outln!("  {} -> {}: {}", ch.from, ch.to, ch.points);
    }
    Ok(())
}
