//! `droplet boundaries`: the full model's phase boundaries in the (eta_t, kappa2) plane, or
//! in the plane of a sweep in --out.
use super::{print_json, CliError};
use droplet_sweep::studies::boundaries::BoundaryStudy;
use std::path::PathBuf;

/// Compute the full model's exact phase boundaries, in the paper's plane or a sweep's
///
/// Compute the full model's phase boundaries (N x N spectral grid, field included) from its
/// bifurcation points instead of from runs on a grid: the resting disk's onsets of motion and
/// of deformation (exact thresholds), the resting deformed droplet's onset of motion (one
/// Newton solve and one linearisation per kappa2), and the MD saddle-node that bounds the
/// bistable bands (two-parameter continuation of the fold). Each point solves its equations
/// to ~1e-10. Writes DIR/boundaries.parquet (model = pde, and the reduced model's analytic
/// curves as model = ode) and DIR/boundaries.png/.svg. If DIR holds a sweep, its window is
/// the default and its phase map is redrawn with the boundaries on it, in the sweep's plane:
/// in any plane of two model parameters (eta_t, kappa2, eta2, mass, radius, sigma, box_len)
/// each curve is continued in that pair over the window the sweep spans, the other
/// parameters the spec's (the onsets traced as zero sets of their eigenvalue, the MD fold and
/// the MC onset continued); over eta2 or mass with eta_t or kappa2, and over tol, dt_max or
/// t_max, they are lines (those move no boundary); over n they are computed at each N.
///
/// With several grid sizes (`--n 192,256,384`) it is a convergence study: the boundaries at
/// each N go to DIR/n<N>/, and DIR/convergence.parquet gives each curve's shift from the
/// previous N (the largest distance of its points from the coarser curve, in the plane),
/// drawn together in DIR/boundaries_by_n.png/.svg.
#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "Examples:\n  droplet boundaries --out results/boundaries                  # the Fig. 2a window\n  droplet boundaries --out out/fig2a                           # onto a sweep's phase map\n  droplet boundaries --out results/mass-eta_t                   # over a (mass, eta_t) map\n  droplet boundaries --out out/radius-sigma --n 128            # continued in (radius, sigma)\n  droplet boundaries --eta-t 0.07,0.1 --kappa2 0.1,0.17 --n 128 --json\n  droplet boundaries --n 128,192,256 --out out/convergence    # how far the grid moves each boundary"
)]
pub struct Args {
    /// eta_t window LO,HI (default: the sweep's in --out, else 0.07,0.10).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true)]
    eta_t: Option<String>,
    /// kappa2 window LO,HI (default: the sweep's in --out, else 0.10,0.17).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true)]
    kappa2: Option<String>,
    /// Grid points per side, or a list of them (N1,N2,...: a convergence study).
    #[arg(long, default_value = "192", value_name = "N[,N...]")]
    n: String,
    /// Points of the ID onset line.
    #[arg(long, default_value_t = 60)]
    samples: usize,
    /// Shape modes 2..K (the paper's general model; default 2). With K > 2 the curves of the
    /// states on the x axis (the onsets of motion and of the axis deformation, ID's onset of
    /// motion, the MD fold), in the paper's plane and its crossings with a sweep's line;
    /// about 25 s per curve set at N = 192, 90 s for K = 6. A sweep in a plane of two other
    /// model parameters is traced with K = 2 only (refused, exit 2). Default: the sweep's in
    /// --out (its spec's params.modes), else 2.
    #[arg(long)]
    modes: Option<usize>,
    /// Output directory (a sweep's directory redraws its phase map).
    #[arg(long, default_value = "out/boundaries")]
    out: PathBuf,
    /// Print one JSON object (keys: eta_t, kappa2 (the window), plane [x, y], n, modes, seconds,
    /// curves [{model, curve, points, <x> [..], <y> [..]}], files; for a list of N: eta_t,
    /// kappa2, ns, seconds [..], curves [{curve, n, points, shift}], files).
    #[arg(long)]
    json: bool,
}

/// Narrowest window: each boundary point is solved to about 1e-10 and drawn with its
/// neighbours, so a narrower window shows no curve at all, only the solver's noise.
const MIN_WIDTH: f64 = 1e-6;

/// A window `--FLAG LO,HI`: `0 < LO < HI`, at least [`MIN_WIDTH`] wide, within the
/// parameters' limit.
pub(super) fn range(text: &str, flag: &str) -> Result<(f64, f64), CliError> {
    let bad = || {
        CliError::usage(format!(
            "invalid --{flag} `{text}`: LO,HI with 0 < LO < HI and HI - LO >= {MIN_WIDTH:e}"
        ))
    };
    let parts: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    match parts[..] {
        [lo, hi] if lo.is_finite() && hi.is_finite() && lo > 0.0 && hi - lo >= MIN_WIDTH => {
            super::line::within_limit(&format!("--{flag} HI"), hi)?;
            Ok((lo, hi))
        }
        _ => Err(bad()),
    }
}

pub fn run(a: Args) -> Result<(), CliError> {
    let eta_t = a.eta_t.as_deref().map(|t| range(t, "eta-t")).transpose()?;
    let kappa2 = a
        .kappa2
        .as_deref()
        .map(|t| range(t, "kappa2"))
        .transpose()?;
    let ns = grid_sizes(&a.n)?;
    if !(2..=10_000).contains(&a.samples) {
        return Err(CliError::usage(format!(
            "invalid --samples {}: from 2 to 10000",
            a.samples
        )));
    }
    let study = BoundaryStudy::new(&a.out, eta_t, kappa2, ns[0], a.samples)?;
    let modes = a.modes.unwrap_or(study.base.modes);
    let study = study.with_modes(modes)?;
    super::line::within_limit("eta_t window HI (from the sweep in --out)", study.eta_t.1)?;
    super::line::within_limit("kappa2 window HI (from the sweep in --out)", study.kappa2.1)?;
    if ns.len() > 1 {
        if modes != 2 {
            return Err(CliError::usage(format!(
                "invalid --n {} with --modes {}: a convergence study is made with 2 modes",
                a.n, modes
            )));
        }
        if !study.in_paper_plane() {
            return Err(CliError::usage(format!(
                "invalid --n {}: a convergence study is made in the paper's plane, and the sweep \
                 in {} is in another; give another --out",
                a.n,
                a.out.display()
            )));
        }
        return convergence(&study, &ns, a.json);
    }
    errln!(
        "boundaries in {} at {} (about 10 s at N = 192 in the paper's plane)",
        study.window(),
        study.grid_words()
    );
    let done = study.run()?;
    match done.missing.filter(|m| m.0 > 0) {
        Some((missing, points)) if done.from_tables => errln!(
            "warning: {missing} of {points} points of {} lack a usable stored run (older \
             numerics, or unreadable): its phase map was redrawn from its tables",
            a.out.display()
        ),
        Some((missing, points)) => errln!(
            "warning: {}",
            super::plot::missing_message(missing, points, &a.out)
        ),
        None => {}
    }
    report(&study, &done, a.json);
    Ok(())
}

/// Prints what a study computed: one JSON object, or a line per curve and the files.
fn report(
    study: &BoundaryStudy,
    done: &droplet_sweep::studies::boundaries::BoundariesWritten,
    json: bool,
) {
    // The curves' coordinates: the paper's plane's, or the sweep's plane's in --out.
    let (xn, yn) = study.plane_names();
    if json {
        let curves: Vec<_> = done
            .curves
            .iter()
            .map(|c| {
                let mut o = serde_json::json!({
                    "model": c.model.as_str(), "curve": c.name, "points": c.points.len(),
                });
                o[xn] = serde_json::json!(c.points.iter().map(|p| p.0).collect::<Vec<_>>());
                o[yn] = serde_json::json!(c.points.iter().map(|p| p.1).collect::<Vec<_>>());
                o
            })
            .collect();
        print_json(&serde_json::json!({
            "eta_t": [study.eta_t.0, study.eta_t.1], "kappa2": [study.kappa2.0, study.kappa2.1],
            "plane": [xn, yn], "n": study.n, "modes": study.base.modes, "seconds": done.seconds,
            "curves": curves,
            "files": done.files,
        }));
    } else {
        for c in &done.curves {
            let model = c.model.as_str().to_uppercase();
            match (c.points.first(), c.points.last()) {
                (Some(first), Some(last)) => outln!(
                    "{model}: {:<40} {:>4} points in ({xn}, {yn}), from ({:.7}, {:.7}) to ({:.7}, {:.7})",
                    c.name,
                    c.points.len(),
                    first.0,
                    first.1,
                    last.0,
                    last.1
                ),
                _ => outln!("{model}: {:<40} none in this window", c.name),
            }
        }
        if !done
            .curves
            .iter()
            .any(|c| c.model == droplet_solver::contract::settings::ModelKind::Pde)
        {
            outln!("PDE: no boundary crosses this window (in a plane of eta2 and mass none can)");
        }
        for f in &done.files {
            outln!("wrote {}", f.display());
        }
        outln!("{:.1} s", done.seconds);
    }
}

/// `--n N` or `--n N1,N2,...`: each an even integer from 16 to 4096, each given once.
fn grid_sizes(text: &str) -> Result<Vec<usize>, CliError> {
    let ns = text
        .split(',')
        .map(|p| {
            p.trim().parse::<usize>().map_err(|_| {
                CliError::usage(format!(
                    "invalid --n `{text}`: an even integer from 16 to 4096, or a list N1,N2,..."
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if ns.len() > 8 {
        return Err(CliError::usage(format!(
            "invalid --n `{text}`: at most 8 grid sizes"
        )));
    }
    for (i, &n) in ns.iter().enumerate() {
        super::check_grid(n)?;
        if ns[..i].contains(&n) {
            return Err(CliError::usage(format!(
                "invalid --n `{text}`: {n} is given twice (each grid size once)"
            )));
        }
    }
    Ok(ns)
}

/// The boundaries at every N of `ns` and their shifts from one N to the next.
fn convergence(study: &BoundaryStudy, ns: &[usize], json: bool) -> Result<(), CliError> {
    errln!(
        "boundaries in eta_t {:?}, kappa2 {:?} at N = {ns:?}",
        study.eta_t,
        study.kappa2
    );
    let done = droplet_sweep::studies::convergence::run(study, ns)?;
    if json {
        let curves: Vec<_> = done
            .curves
            .iter()
            .map(|c| serde_json::json!({"curve": c.curve, "n": c.n, "points": c.points, "shift": c.shift}))
            .collect();
        print_json(&serde_json::json!({
            "eta_t": [study.eta_t.0, study.eta_t.1], "kappa2": [study.kappa2.0, study.kappa2.1],
            "ns": done.ns, "seconds": done.seconds, "curves": curves, "files": done.files,
        }));
        return Ok(());
    }
    for (n, s) in done.ns.iter().zip(&done.seconds) {
        outln!("N = {n}: {s:.1} s");
    }
    outln!(
        "{:<40} {:>6} {:>7} shift from the previous N",
        "curve",
        "N",
        "points"
    );
    for c in &done.curves {
        let shift = c.shift.map_or("-".to_string(), |d| format!("{d:.2e}"));
        outln!("{:<40} {:>6} {:>7} {shift}", c.curve, c.n, c.points);
    }
    for f in &done.files {
        outln!("wrote {}", f.display());
    }
    Ok(())
}
