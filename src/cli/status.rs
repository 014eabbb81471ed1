//! `droplet status`: progress and class counts of a sweep directory.
use super::{print_json, CliError};
use std::path::PathBuf;

/// Show how far a sweep is (finished or still running) and its class counts.
#[derive(clap::Args)]
pub struct Args {
    /// The sweep's output directory.
    out: PathBuf,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
}

pub fn run(a: Args) -> Result<(), CliError> {
    let st = droplet_sweep::status::status(&a.out)?;
    if a.json {
        print_json(&st);
    } else {
        println!(
            "{}: {}/{} runs done ({}), {} points, {:.0} CPU s so far",
            st.name,
            st.runs_done,
            st.runs_total,
            if st.complete {
                "complete"
            } else {
                "incomplete"
            },
            st.points,
            st.cpu_s
        );
        let fmt = |m: &std::collections::BTreeMap<String, usize>| {
            m.iter()
                .map(|(k, v)| format!("{k}: {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if st.runs_corrupt > 0 {
            println!(
                "{} stored runs cannot be used (unreadable or not matching their key): the next `droplet sweep` on this directory moves them to corrupt/ and recomputes them",
                st.runs_corrupt
            );
        }
        println!("run statuses: {}", fmt(&st.run_statuses));
        println!("run classes: {}", fmt(&st.run_classes));
        println!(
            "point classes (complete points): {}",
            fmt(&st.point_classes)
        );
    }
    Ok(())
}
