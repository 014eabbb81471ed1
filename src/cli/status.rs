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

/// The ETA line: at the recent pace, or unknown when no run has been stored for longer
/// than that pace promised.
fn print_eta(st: &droplet_sweep::execution::status::SweepStatus) {
    match (st.eta_s, st.since_last_s) {
        (Some(eta), Some(since)) if since > eta => outln!(
            "ETA: unknown: the pace of the last {:.0} min ({} runs stored) gave {:.0} min, \
             but no run has been stored for {:.0} min: the {} runs left are slower than \
             the finished ones",
            st.pace_s / 60.0,
            st.runs_recent,
            eta / 60.0,
            since / 60.0,
            st.runs_total - st.runs_done
        ),
        (Some(eta), _) => outln!(
            "ETA: about {:.0} min at the pace of the last {:.0} min ({} runs stored)",
            eta / 60.0,
            st.pace_s / 60.0,
            st.runs_recent
        ),
        _ => {}
    }
}

pub fn run(a: Args) -> Result<(), CliError> {
    let st = droplet_sweep::execution::status::status(&a.out)?;
    if a.json {
        print_json(&st);
    } else {
        outln!(
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
        if st.from_tables {
            outln!("(read from its tables: the directory has no runs/, as a committed result)");
        }
        if st.runs_corrupt > 0 {
            outln!(
                "{} stored runs cannot be used (unreadable or not matching their key): the next `droplet sweep` on this directory moves them to corrupt/ and recomputes them",
                st.runs_corrupt
            );
        }
        for l in &st.levels {
            outln!(
                "level {}: {} points, {}/{} runs done",
                l.level,
                l.points,
                l.runs_done,
                l.runs_total
            );
        }
        if let (Some(eta), false) = (st.eta_cpu_s, st.complete) {
            let more = if st.levels.is_empty() {
                ""
            } else {
                " (of the levels known so far; the next follow from them)"
            };
            outln!("remaining: about {eta:.0} CPU s at the mean cost of the finished runs{more}");
        }
        print_eta(&st);
        outln!("run statuses: {}", fmt(&st.run_statuses));
        outln!("run classes: {}", fmt(&st.run_classes));
        outln!(
            "point classes (complete points): {}",
            fmt(&st.point_classes)
        );
        outln!(
            "unsettled points (a run not on a stable state; label not proven): {}",
            st.points_unsettled
        );
    }
    Ok(())
}
