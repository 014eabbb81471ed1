//! `droplet boundaries`: the full model's phase boundaries in the (eta_t, kappa2) plane.
use super::{print_json, CliError};
use droplet_solver::continuation::boundaries::{boundaries, Window};
use droplet_solver::model::params::ModelParams;
use droplet_solver::reduced::coefficients::Coefficients;
use droplet_sweep::pictures::figures::Curve;
use droplet_sweep::tables::boundaries::{self, NamedCurve};
use std::path::PathBuf;
use std::time::Instant;

/// Compute the full model's exact phase boundaries in the (eta_t, kappa2) plane.
///
/// Compute the full model's phase boundaries (N x N spectral grid, field included) from its
/// bifurcation points instead of from runs on a grid: the resting disk's onsets of motion and
/// of deformation (exact thresholds), the resting deformed droplet's onset of motion (one
/// Newton solve and one linearisation per kappa2), and the MD saddle-node that bounds the
/// bistable bands (two-parameter continuation of the fold). Each point solves its equations
/// to ~1e-10. Writes DIR/boundaries.parquet (model = pde, and the reduced model's analytic
/// curves as model = ode) and DIR/boundaries.png/.svg. If DIR holds a sweep, its window is
/// the default and its phase map is redrawn with the boundaries on it.
#[derive(clap::Args)]
#[command(
    allow_negative_numbers = true,
    after_help = "Examples:\n  droplet boundaries --out results/boundaries                  # the Fig. 2a window\n  droplet boundaries --out out/fig2a                           # onto a sweep's phase map\n  droplet boundaries --eta-t 0.07,0.1 --kappa2 0.1,0.17 --n 128 --json"
)]
pub struct Args {
    /// eta_t window LO,HI (default: the sweep's in --out, else 0.07,0.10).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true)]
    eta_t: Option<String>,
    /// kappa2 window LO,HI (default: the sweep's in --out, else 0.10,0.17).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true)]
    kappa2: Option<String>,
    /// Grid points per side.
    #[arg(long, default_value_t = 192)]
    n: usize,
    /// Points of the ID onset line.
    #[arg(long, default_value_t = 60)]
    samples: usize,
    /// Output directory (a sweep's directory redraws its phase map).
    #[arg(long, default_value = "out/boundaries")]
    out: PathBuf,
    /// Print one JSON object (keys: eta_t, kappa2, n, seconds, curves [{model, curve,
    /// points, eta_t [..], kappa2 [..]}], files).
    #[arg(long)]
    json: bool,
}

fn range(text: &str, flag: &str) -> Result<(f64, f64), CliError> {
    let bad = || CliError::usage(format!("invalid --{flag} `{text}`: LO,HI with 0 < LO < HI"));
    let parts: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    match parts[..] {
        [lo, hi] if lo.is_finite() && hi.is_finite() && lo > 0.0 && lo < hi => {
            super::line::within_limit(&format!("--{flag} HI"), hi)?;
            Ok((lo, hi))
        }
        _ => Err(bad()),
    }
}

pub fn run(a: Args) -> Result<(), CliError> {
    let sweep = droplet_sweep::spec::load_stored(&a.out).ok();
    let span = |v: &[f64]| {
        v.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            })
    };
    let eta_t = match (&a.eta_t, &sweep) {
        (Some(t), _) => range(t, "eta-t")?,
        (None, Some(s)) if s.eta_t.len() > 1 => span(&s.eta_t),
        _ => (0.07, 0.10),
    };
    let kappa2 = match (&a.kappa2, &sweep) {
        (Some(t), _) => range(t, "kappa2")?,
        (None, Some(s)) if s.kappa2.len() > 1 => span(&s.kappa2),
        _ => (0.10, 0.17),
    };
    super::line::within_limit("eta_t window HI (from the sweep in --out)", eta_t.1)?;
    super::line::within_limit("kappa2 window HI (from the sweep in --out)", kappa2.1)?;
    super::check_grid(a.n)?;
    if !(2..=10_000).contains(&a.samples) {
        return Err(CliError::usage(format!(
            "invalid --samples {}: from 2 to 10000",
            a.samples
        )));
    }
    let base = match &sweep {
        Some(s) => s.params,
        None => ModelParams::default(),
    };
    let base = ModelParams {
        eta_t: eta_t.0,
        kappa2: kappa2.0,
        ..base
    };
    base.validate()?;
    droplet_sweep::store::atomic::create_output_dir(&a.out)?;
    let started = Instant::now();
    eprintln!(
        "boundaries in eta_t {:?}, kappa2 {:?} at N = {} (about a minute at N = 192)",
        eta_t, kappa2, a.n
    );
    let w = Window {
        base,
        n: a.n,
        eta_t,
        kappa2,
        id_samples: a.samples,
    };
    let pde = boundaries(&w).map_err(|e| CliError {
        message: e.to_string(),
        code: 1,
    })?;
    let seconds = started.elapsed().as_secs_f64();
    let h0 = sweep
        .as_ref()
        .map_or(droplet_solver::contract::settings::H0_PAPER, |s| {
            s.solver.h0
        });
    let ode = droplet_solver::reduced::boundaries::boundaries(
        &Coefficients::new(base.radius, h0),
        eta_t,
        kappa2,
    );
    let all: Vec<NamedCurve> = NamedCurve::from_boundaries("pde", &pde)
        .into_iter()
        .chain(NamedCurve::from_boundaries("ode", &ode))
        .collect();
    let path = a.out.join(boundaries::FILE);
    boundaries::write(
        &path,
        &all,
        sweep.as_ref().map(|s| s.source.as_str()),
        vec![
            ("n".into(), a.n.to_string()),
            (
                "window".into(),
                format!("eta_t {eta_t:?}, kappa2 {kappa2:?}"),
            ),
        ],
    )?;
    let drawn: Vec<Curve> = all
        .iter()
        .map(|c| Curve {
            label: format!("{}: {}", c.model.to_uppercase(), c.name),
            points: c.points.clone(),
            dashed: c.model == "ode",
        })
        .collect();
    let mut files = droplet_sweep::pictures::figures::boundary_picture(
        &a.out,
        "boundaries",
        &format!("Phase boundaries: PDE (N = {}) solid, ODE dashed", a.n),
        &drawn,
        eta_t,
        kappa2,
    )?;
    files.push(path);
    if sweep.is_some() {
        let drawn = droplet_sweep::pictures::sweep_pictures::plot(&a.out)?;
        if drawn.missing > 0 {
            eprintln!(
                "warning: {}",
                super::plot::missing_message(drawn.missing, drawn.points, &a.out)
            );
        }
        files.extend(drawn.files);
    }
    if a.json {
        let curves: Vec<_> = all
            .iter()
            .map(|c| {
                serde_json::json!({
                    "model": c.model, "curve": c.name, "points": c.points.len(),
                    "eta_t": c.points.iter().map(|p| p.0).collect::<Vec<_>>(),
                    "kappa2": c.points.iter().map(|p| p.1).collect::<Vec<_>>(),
                })
            })
            .collect();
        print_json(&serde_json::json!({
            "eta_t": [eta_t.0, eta_t.1], "kappa2": [kappa2.0, kappa2.1], "n": a.n,
            "seconds": seconds, "curves": curves, "files": files,
        }));
    } else {
        for c in &all {
            match (c.points.first(), c.points.last()) {
                (Some(first), Some(last)) => outln!(
                    "{}: {:<40} {:>4} points, from ({:.7}, {:.7}) to ({:.7}, {:.7})",
                    c.model.to_uppercase(),
                    c.name,
                    c.points.len(),
                    first.0,
                    first.1,
                    last.0,
                    last.1
                ),
                _ => outln!(
                    "{}: {:<40} none in this window",
                    c.model.to_uppercase(),
                    c.name
                ),
            }
        }
        for f in files {
            outln!("wrote {}", f.display());
        }
        outln!("{seconds:.1} s");
    }
    Ok(())
}
