//! `droplet truncation`: the paper's results with shape modes 2..K, for several K.
use super::{boundaries::range, print_json, CliError};
use droplet_sweep::studies::boundaries::FIG2A_WINDOW;
use droplet_sweep::studies::truncation::{run as run_study, BAND_LINE, FIG1C};
use std::path::PathBuf;

/// How far the paper's 2-mode truncation moves its results (shape modes k = 2..K).
///
/// The paper derives its model for every shape mode, r = R [1 + sum_k (a_k cos k theta + b_k
/// sin k theta)], and keeps k = 2. This solves the general model's steady states (modes
/// 2..K, each with its own force G_k and stiffness kappa_k = (k^2/4) kappa2, N x N spectral
/// grid, field included) for each K of --modes and reports: the MD state at the paper's Fig. 1c
/// point (eta_t 0.085, kappa2 0.112: v, the paper's s = |a2|, the total deformation, every
/// a_k, and its stability from the 2K x 2K eigenproblem with the field, the rotation mode set
/// aside; a droplet moving along +x has a_k on the x axis only); the resting disk's onset of
/// motion at kappa2 = 0.13; the MD branch along eta_t at kappa2 = 0.13 and its fold, the right
/// edge of the IC/MD bistable band; and the phase boundaries of the Fig. 2a window for the
/// states on the x axis (the onsets of motion and of the axis deformation, ID's onset of
/// motion, the MD fold curve; a fold or an onset is where a real eigenvalue crosses zero;
/// --eta-t and --kappa2 choose another window).
/// Writes DIR/truncation.parquet (one row per K), DIR/truncation_boundaries.parquet (curves named `K = k: <boundary>`), DIR/truncation.png/.svg
/// (the Fig. 1c droplet's outline for each K) and DIR/truncation_boundaries.png/.svg (the
/// boundaries for every K over each other). About 25 s per K at N = 192 (100 s for K = 6).
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  droplet truncation --out results/truncation                 # K = 2, 3, 4, 6 at N = 192\n  droplet truncation --modes 2,3 --n 96 --json --out out/trunc\n  droplet truncation --modes 2,4 --eta-t 0.075,0.085 --kappa2 0.12,0.14   # boundaries in a smaller window"
)]
pub struct Args {
    /// The numbers of modes K to compare (modes 2..K each), e.g. 2,3,4,6: each from 2 to 16
    /// and at most pi R N / (4 L) (half a wavelength of mode K along the boundary spans 4
    /// grid cells).
    #[arg(long, default_value = "2,3,4,6", value_name = "K[,K...]")]
    modes: String,
    /// Grid points per side.
    #[arg(long, default_value_t = 192)]
    n: usize,
    /// eta_t window LO,HI of the boundaries (default: the Fig. 2a window's, 0.07,0.10).
    #[arg(long, value_name = "LO,HI")]
    eta_t: Option<String>,
    /// kappa2 window LO,HI of the boundaries (default: the Fig. 2a window's, 0.10,0.17).
    #[arg(long, value_name = "LO,HI")]
    kappa2: Option<String>,
    /// Output directory.
    #[arg(long, default_value = "out/truncation")]
    out: PathBuf,
    /// Print one JSON object (keys: n, fig1c [eta_t, kappa2], band_kappa2, eta_t and kappa2
    /// (the boundaries' window), rows [{k_max,
    /// v, s, deformation, a [a2..aK], stable, leading (largest real part but the rotation
    /// mode), eigenvalues [[re, im]], rotation, fig1c_seconds, onset_eta_t, fold_eta_t, fold_v,
    /// band_width, fold_seconds, boundaries_seconds}], files).
    #[arg(long)]
    json: bool,
}

/// `--modes K1,K2,...`: integers (their range is the solver's check), at most 8, no repeats.
fn modes(text: &str) -> Result<Vec<usize>, CliError> {
    let bad = |why: &str| CliError::usage(format!("invalid --modes `{text}`: {why}"));
    let ks = text
        .split(',')
        .map(|p| p.trim().parse::<usize>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|_| bad("integers K1,K2,... (modes 2..K each), e.g. 2,3,4,6"))?;
    if ks.is_empty() || ks.len() > 8 {
        return Err(bad("one to eight values"));
    }
    for (i, k) in ks.iter().enumerate() {
        if ks[..i].contains(k) {
            return Err(bad(&format!("{k} given twice")));
        }
    }
    Ok(ks)
}

pub fn run(a: Args) -> Result<(), CliError> {
    let ks = modes(&a.modes)?;
    super::check_grid(a.n)?;
    let window = (
        a.eta_t
            .as_deref()
            .map_or(Ok(FIG2A_WINDOW.0), |t| range(t, "eta-t"))?,
        a.kappa2
            .as_deref()
            .map_or(Ok(FIG2A_WINDOW.1), |t| range(t, "kappa2"))?,
    );
    let base = droplet_solver::model::params::ModelParams::default();
    for &k in &ks {
        droplet_solver::contract::limits::check_modes(&base, a.n, k)?;
    }
    errln!(
        "truncation: K = {ks:?} at N = {} (about 25 s per K at N = 192)",
        a.n
    );
    let done = run_study(&a.out, &ks, a.n, window)?;
    if a.json {
        let rows: Vec<_> = done
            .rows
            .iter()
            .map(|r| {
                serde_json::json!({
                    "k_max": r.k_max, "v": r.fig1c.v, "s": r.fig1c.a[0].abs(),
                    "deformation": r.deformation, "a": r.fig1c.a,
                    "stable": r.fig1c_verdict.stable(), "leading": r.fig1c_verdict.max_re,
                    "eigenvalues": r.fig1c_verdict.eigenvalues,
                    "rotation": r.fig1c_verdict.rotation,
                    "fig1c_seconds": r.fig1c_seconds, "onset_eta_t": r.disk.eta_t,
                    "fold_eta_t": r.fold.as_ref().map(|f| f.x),
                    "fold_v": r.fold.as_ref().map(|f| f.v),
                    "band_width": r.fold.as_ref().map(|f| f.x - r.disk.eta_t),
                    "fold_seconds": r.fold_seconds,
                    "boundaries_seconds": r.boundaries_seconds,
                })
            })
            .collect();
        print_json(&serde_json::json!({
            "n": a.n, "fig1c": [FIG1C.0, FIG1C.1], "band_kappa2": BAND_LINE.0,
            "eta_t": [window.0 .0, window.0 .1], "kappa2": [window.1 .0, window.1 .1],
            "rows": rows, "files": done.files,
        }));
    } else {
        outln!(
            "{:>3} {:>9} {:>7} {:>9} {:>9} {:>11} {:>11} {:>11}",
            "K",
            "v(1c)",
            "stable",
            "s(1c)",
            "a3(1c)",
            "onset",
            "fold",
            "band"
        );
        for r in &done.rows {
            let fold = r.fold.as_ref().map_or(f64::NAN, |f| f.x);
            outln!(
                "{:>3} {:>9.6} {:>7} {:>9.6} {:>9.6} {:>11.7} {:>11.7} {:>11.7}",
                r.k_max,
                r.fig1c.v,
                r.fig1c_verdict.stable(),
                r.fig1c.a[0].abs(),
                r.fig1c.a.get(1).copied().unwrap_or(0.0),
                r.disk.eta_t,
                fold,
                fold - r.disk.eta_t
            );
        }
        for f in &done.files {
            outln!("wrote {}", f.display());
        }
    }
    Ok(())
}
