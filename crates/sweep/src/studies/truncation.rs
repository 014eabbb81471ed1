//! `droplet truncation`: how far the paper's 2-mode truncation moves its results, from the
//! general model with shape modes `k = 2..K` (`droplet_solver::roots::steady_solver`), for
//! each `K` asked:
//! - the MD state at the paper's Fig. 1c point (`eta_t` = 0.085, `kappa2` = 0.112): `v`, the
//!   paper's `s` (mode 2), the total deformation, every `a_k`, and its stability (the `2K x 2K`
//!   eigenproblem, `droplet_solver::roots::linearisation`);
//! - the resting disk's onsets at `kappa2` = 0.13: of motion, and of each mode's deformation;
//! - the MD branch along `eta_t` at `kappa2` = 0.13 and its fold, the right edge of the IC/MD
//!   bistable band (its left edge is the onset of motion);
//! - the phase boundaries of the Fig. 2a window for the states on the x axis
//!   (`droplet_solver::continuation::boundaries::general_boundaries`: the onsets, ID's onset of
//!   motion, the MD fold curve, the MC onset, from the general solver at every `K`), drawn for
//!   every `K` over each other;
//!
//! each with the time it took, as `truncation.parquet`, a picture of the Fig. 1c droplet's
//! outline for each `K`, and the rows returned for the CLI.
use crate::error::SweepError;
use crate::pictures::map_figure::{boundary_picture, outline_picture, Curve, CURVE_COLOURS};
use crate::tables::boundaries::NamedCurve;
use crate::tables::truncation::TruncationRow;
use droplet_solver::continuation::boundaries::general_boundaries;
use droplet_solver::continuation::fold_curve::walk_to_fold;
use droplet_solver::continuation::window::{Axis, Window};
use droplet_solver::contract::settings::ModelKind;
use droplet_solver::model::mirror::MirrorLine;
use droplet_solver::model::modes::Modes;
use droplet_solver::model::param::ModelParam;
use droplet_solver::model::params::ModelParams;
use droplet_solver::roots::balances::Balances;
use droplet_solver::roots::linearisation::Linearization;
use droplet_solver::roots::named_state::md_state;
use droplet_solver::roots::steady_solver::SteadySolver;
use droplet_solver::roots::thresholds::disk_thresholds;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The paper's Fig. 1c point `(eta_t, kappa2)`.
pub const FIG1C: (f64, f64) = (0.085, 0.112);
/// The `kappa2` of the bistable band's line (Fig. 3b iv) and its `eta_t` range.
pub const BAND_LINE: (f64, (f64, f64)) = (0.13, (0.07, 0.10));

/// What `droplet truncation` computed and wrote.
#[derive(Debug, Clone)]
pub struct TruncationWritten {
    pub rows: Vec<TruncationRow>,
    pub files: Vec<PathBuf>,
}

/// Computes one row, and the boundaries of the Fig. 2a window with `k_max` modes.
fn row(
    k_max: usize,
    n: usize,
    base: &ModelParams,
    (window_eta_t, window_kappa2): ((f64, f64), (f64, f64)),
) -> Result<(TruncationRow, Vec<NamedCurve>), SweepError> {
    let started = Instant::now();
    let at = ModelParams {
        eta_t: FIG1C.0,
        kappa2: FIG1C.1,
        ..*base
    };
    let mut solver = SteadySolver::new(at, n)?;
    let fig1c = md_state(&mut solver, k_max)?;
    let z = droplet_solver::roots::steady_solver::on_x_axis(fig1c.v, &fig1c.a);
    let fig1c_verdict = Linearization::at(&mut solver, &z).verdict();
    let fig1c_seconds = started.elapsed().as_secs_f64();
    let deformation = Modes {
        a: fig1c.a.clone(),
        b: vec![0.0; fig1c.a.len()],
    }
    .deformation();
    let started = Instant::now();
    let (kappa2, (from, to)) = BAND_LINE;
    let line_base = ModelParams {
        eta_t: from,
        kappa2,
        ..*base
    };
    let mut disk_solver = SteadySolver::new(line_base, n)?;
    let disk = disk_thresholds(&mut disk_solver, k_max);
    // The general balances at every K, K = 2 included (one method for every model).
    let balances = Balances::General(SteadySolver::new(line_base.with_modes(k_max), n)?);
    let line = Axis::new(ModelParam::EtaT, (from, to));
    let fold = walk_to_fold(balances, MirrorLine::X, line, kappa2);
    let fold_seconds = started.elapsed().as_secs_f64();
    let started = Instant::now();
    // The general computation at every K, K = 2 included, so that the models are compared
    // by one method.
    let window = Window::paper(
        ModelParams {
            eta_t: window_eta_t.0,
            kappa2: window_kappa2.0,
            ..base.with_modes(k_max)
        },
        n,
        window_eta_t,
        window_kappa2,
        30,
    );
    let curves = general_boundaries(&window)?
        .into_iter()
        .map(|b| NamedCurve {
            model: ModelKind::Pde,
            name: format!("K = {k_max}: {}", b.name),
            points: b.points,
        })
        .collect();
    Ok((
        TruncationRow {
            k_max,
            fig1c,
            fig1c_verdict,
            deformation,
            fig1c_seconds,
            disk,
            fold,
            fold_seconds,
            boundaries_seconds: started.elapsed().as_secs_f64(),
        },
        curves,
    ))
}

/// The Fig. 1c droplet's outline for each row, labelled with its `K` and speed.
fn outlines(rows: &[TruncationRow], base: &ModelParams) -> Vec<Curve> {
    let shape = base.shape();
    rows.iter()
        .map(|r| {
            let m = Modes {
                a: r.fig1c.a.clone(),
                b: vec![0.0; r.fig1c.a.len()],
            };
            let points = (0..=360)
                .map(|i| {
                    let th = (i as f64).to_radians();
                    let f = m.boundary(&shape, th.cos(), th.sin());
                    (f * th.cos(), f * th.sin())
                })
                .collect();
            Curve {
                label: format!("K = {}: v = {:.4}", r.k_max, r.fig1c.v),
                points,
                dashed: false,
                colour: None,
            }
        })
        .collect()
}

/// Runs the study for each `K` of `modes` at grid size `n` (the other parameters the
/// defaults), the boundaries in the window `(eta_t, kappa2)`, each `(lo, hi)` (the paper's
/// study: the Fig. 2a window,
/// [`crate::studies::boundaries::FIG2A_WINDOW`]), and writes
/// `truncation.parquet` and `truncation.png/.svg` into `out`.
pub fn run(
    out: &Path,
    modes: &[usize],
    n: usize,
    window: ((f64, f64), (f64, f64)),
) -> Result<TruncationWritten, SweepError> {
    let base = ModelParams::default();
    for &k in modes {
        droplet_solver::contract::limits::check_modes(&base, n, k)?;
    }
    crate::store::atomic::create_output_dir(out)?;
    let mut rows = Vec::new();
    let mut boundaries: Vec<NamedCurve> = Vec::new();
    for &k in modes {
        let (r, curves) = row(k, n, &base, window)?;
        rows.push(r);
        boundaries.extend(curves);
    }
    let mut files = vec![crate::tables::truncation::write(out, &rows, n)?];
    let path = out.join("truncation_boundaries.parquet");
    crate::tables::boundaries::write(
        &path,
        &boundaries,
        None,
        vec![
            ("n".into(), n.to_string()),
            ("modes".into(), format!("{modes:?}")),
        ],
    )?;
    files.push(path);
    // One colour per K, in the order given.
    let colour_of = |name: &str| {
        modes
            .iter()
            .position(|k| name.starts_with(&format!("K = {k}:")))
            .map(|i| CURVE_COLOURS[i % CURVE_COLOURS.len()])
    };
    let drawn: Vec<Curve> = boundaries
        .iter()
        .map(|c| Curve {
            colour: colour_of(&c.name),
            dashed: c.name.contains("ID onset"),
            ..Curve::of(c)
        })
        .collect();
    files.extend(boundary_picture(
        out,
        "truncation_boundaries",
        &format!("Phase boundaries with shape modes 2..K (x-axis states), N = {n}"),
        &drawn,
        window.0,
        window.1,
    )?);
    let curves = outlines(&rows, &base);
    files.extend(outline_picture(
        out,
        "truncation",
        &format!(
            "MD droplet at Fig. 1c (eta_t {}, kappa2 {}), moving along +x; N = {n}",
            FIG1C.0, FIG1C.1
        ),
        &curves,
    )?);
    Ok(TruncationWritten { rows, files })
}
