//! `droplet fit-h0`: the Appendix E fit of the cubic coefficient h0.
use super::{print_json, CliError};
use droplet_solver::model::params::ModelParams;
use droplet_solver::reduced::coefficients::Coefficients;
use droplet_solver::roots::h0_fit::fit_h0;
use droplet_sweep::pictures::h0_figure::{h0_picture, H0Picture};
use std::path::PathBuf;

/// Fit the reduced model's h0 to deformation-only PDE steady states (Appendix E).
///
/// Fit kappa2 = p0 - p2 s^2 to deformation-only PDE steady states (droplet held in place)
/// over 0.001 < s < 0.3, as in Appendix E; p2 is the reduced model's h0. The steady states come
/// from the exact steady evaluator (Newton on the co-moving steady field with v = 0), which
/// gives the fixed points that deformation-only time stepping converges to, in a fraction of
/// the time. Writes DIR/h0_fit.parquet and DIR/h0_fit.png/.svg (Fig. A).
#[derive(clap::Args)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// Grid points per side.
    #[arg(long, default_value_t = 192)]
    n: usize,
    /// First kappa2.
    #[arg(long, default_value_t = 0.100)]
    from: f64,
    /// Last kappa2.
    #[arg(long, default_value_t = 0.119)]
    to: f64,
    /// kappa2 step.
    #[arg(long, default_value_t = 0.001)]
    step: f64,
    /// Interface width sigma.
    #[arg(long, default_value_t = 0.03)]
    sigma: f64,
    /// Output directory.
    #[arg(long, default_value = "out/h0_fit")]
    out: PathBuf,
    /// Print one JSON object (keys p0, p2, used, n, points).
    #[arg(long)]
    json: bool,
}

/// Most kappa2 values of one fit (each a Newton solve of about 10 ms at N = 192).
const MAX_POINTS: f64 = 10_000.0;

pub fn run(a: Args) -> Result<(), CliError> {
    if !(a.from.is_finite() && a.to.is_finite() && a.step > 0.0 && a.from < a.to) {
        return Err(CliError::usage(format!(
            "invalid range --from {} --to {} --step {}: need from < to, step > 0",
            a.from, a.to, a.step
        )));
    }
    let count = ((a.to - a.from) / a.step + 1e-9).floor() + 1.0;
    if count > MAX_POINTS {
        return Err(CliError::usage(format!(
            "invalid --step {}: {count:.3e} values of kappa2 from {} to {}, more than {MAX_POINTS}",
            a.step, a.from, a.to
        )));
    }
    let count = count as usize;
    droplet_sweep::store::atomic::create_output_dir(&a.out)?;
    let ks: Vec<f64> = (0..count)
        .map(|i| droplet_sweep::spec::axes::round12(a.from + i as f64 * a.step))
        .collect();
    let base = ModelParams {
        sigma: a.sigma,
        ..ModelParams::default()
    };
    let fit = fit_h0(&base, a.n, &ks)?;
    if fit.used < 2 {
        return Err(CliError {
            message: format!(
                "only {} points with 0.001 < s < 0.3: widen the kappa2 range",
                fit.used
            ),
            code: 1,
        });
    }
    let table = droplet_sweep::tables::h0::write(&a.out, &fit, a.n)?;
    let g0t = Coefficients::new(base.radius, fit.p2).g0t;
    let pic = H0Picture {
        points: fit.points.clone(),
        p0: fit.p0,
        p2: fit.p2,
        g0t,
        n: a.n,
    };
    let mut files = h0_picture(&a.out, "h0_fit", &pic)?;
    files.push(table);
    if a.json {
        print_json(&serde_json::json!({
            "p0": fit.p0, "p2": fit.p2, "used": fit.used, "n": fit.n,
            "method": "exact steady evaluator", "points": fit.points, "files": files,
        }));
    } else {
        outln!("p0 = {:.5}  p2 = h0 = {:.5}  ({} of {} points in 0.001 < s < 0.3, N = {}, exact steady evaluator)", fit.p0, fit.p2, fit.used, fit.points.len(), a.n);
        outln!("paper: p0 = 0.1184, p2 = 0.1436");
        for f in files {
            outln!("wrote {}", f.display());
        }
    }
    Ok(())
}
