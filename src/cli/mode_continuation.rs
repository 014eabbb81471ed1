//! `droplet continue --modes K` (K > 2): the MD branch of the paper's general model with shape
//! modes 2..K along a line in `eta_t` or `kappa2`, with its folds and the stability of every
//! state (`droplet_sweep::studies::mode_continuation`).
use super::continuation::Args;
use super::{print_json, CliError};
use droplet_solver::continuation::arclength::ArclengthOptions;
use droplet_solver::continuation::mode_branch::ModeLine;
use droplet_solver::continuation::mode_line::ModeBranchEnd;
use droplet_solver::model::param::ModelParam;
use droplet_sweep::studies::mode_continuation::{ModeContinuationStudy, ModeContinuationWritten};

/// The study `--modes K` asks for, or why it cannot be done (exit 2).
fn study_of(a: &Args) -> Result<ModeContinuationStudy, CliError> {
    let k = a.modes;
    let refuse = |what: String| {
        CliError::usage(format!(
            "invalid {what} with --modes {k}: the K-mode continuation follows the MD branch on \
             the x axis (--branch md or all, --axis x) in eta_t or kappa2 (--kappa2 K or \
             --eta-t E, other parameters fixed with --set)"
        ))
    };
    if a.branch != "all" && a.branch != "md" {
        return Err(refuse(format!("--branch {}", a.branch)));
    }
    if a.axis != "x" {
        return Err(refuse(format!("--axis {}", a.axis)));
    }
    let (parameter, base) = a.line.line(a.mass)?;
    if !matches!(parameter, ModelParam::EtaT | ModelParam::Kappa2) {
        return Err(refuse(format!("--param {}", parameter.name())));
    }
    droplet_solver::contract::limits::check_modes(&base, a.n, k)?;
    Ok(ModeContinuationStudy {
        out: a.out.clone(),
        line: ModeLine {
            base,
            n: a.n,
            k_max: k,
            parameter,
            from: a.line.span.from,
            to: a.line.span.to,
            eta_k_exponent: a.eta_k_exponent,
        },
        max_points: a.max_points,
        opts: ArclengthOptions {
            ds_max: a.ds_max,
            ..ArclengthOptions::default()
        },
    })
}

/// `droplet continue --modes K` with K > 2.
pub fn run(a: &Args) -> Result<(), CliError> {
    super::continuation::check_common(a)?;
    droplet_solver::model::friction::check_exponent(a.eta_k_exponent, a.modes)?;
    let study = study_of(a)?;
    err!("following md (x, modes 2..{}) ... ", a.modes);
    let done = study.run()?;
    errln!(
        "{} states, {} fold(s) in {:.1} s",
        done.branch.points.len(),
        done.branch.folds().count(),
        done.seconds
    );
    if a.json {
        print_json(&json_summary(&done, a.n, study.line.parameter.name()));
    } else {
        print_text(&done, study.line.parameter.name());
    }
    Ok(())
}

fn print_text(done: &ModeContinuationWritten, varied: &str) {
    let b = &done.branch;
    let stable = b.points.iter().filter(|p| p.verdict.stable()).count();
    outln!(
        "md (modes 2..{}) {:>4} states ({stable} stable); ends: {:?}",
        b.k_max,
        b.points.len(),
        b.end
    );
    for f in b.folds() {
        outln!(
            "  SN at {varied} = {:.9}  v = {:.6}  s = {:.6}  a_k {:?}",
            f.at,
            f.v,
            f.a[0].abs(),
            f.a
        );
    }
    for f in &done.files {
        outln!("wrote {}", f.display());
    }
    outln!("{:.1} s", done.seconds);
}

/// The `--json` object, with the keys of the 2-mode one (`super::continuation`): the one
/// branch (md on x, from the line's start), its folds as SN events.
fn json_summary(done: &ModeContinuationWritten, n: usize, varied: &str) -> serde_json::Value {
    let b = &done.branch;
    let events: Vec<_> = b
        .folds()
        .map(|f| {
            serde_json::json!({
                "kind": "SN", "what": "fold", "branch": "md", "mirror": "x",
                "parameter": varied, "at": f.at, "eta_t": f.eta_t, "kappa2": f.kappa2,
                "v": f.v, "s": f.a[0].abs(), "a_k": f.a, "b_k": vec![0.0; f.a.len()],
                "eigenvalue": null, "precision": null,
            })
        })
        .collect();
    let end = match b.end {
        ModeBranchEnd::LineEnd => "reached the line's end".to_string(),
        ModeBranchEnd::AtRest => "meets a resting state (v below 1e-3)".to_string(),
        ModeBranchEnd::Stalled => "no continuation step converged".to_string(),
        ModeBranchEnd::MaxPoints => "stopped at --max-points".to_string(),
    };
    serde_json::json!({
        "modes": b.k_max, "eta_k_exponent": b.eta_k_exponent, "line": done.description,
        "n": n, "seconds": done.seconds,
        "branches": [{
            "branch": "md", "mirror": "x", "points": b.points.len(),
            "stable_points": b.points.iter().filter(|p| p.verdict.stable()).count(),
            "ends": [format!("the line's start ({varied} followed one way)"), end],
        }],
        "events": events, "files": done.files,
    })
}
