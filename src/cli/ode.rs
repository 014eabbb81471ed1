//! `droplet ode`: the reduced model's coefficients and bifurcation diagrams (Fig. 3b).
use super::{print_json, CliError};
use clap::Subcommand;
use droplet_solver::model::params::ModelParams;
use droplet_solver::reduced::bifurcation::diagram;
use droplet_solver::reduced::coefficients::Coefficients;
use std::path::PathBuf;

/// The reduced ODE model (eqs. 58-59): coefficients and bifurcation diagrams.
///
/// The reduced ODE model (paper eqs. 58-59): coefficients and bifurcation diagrams. For ODE
/// phase maps run a sweep spec with `model: ode` (see sweeps/ode.yaml).
#[derive(clap::Args)]
pub struct Args {
    #[command(subcommand)]
    command: OdeCommand,
}

#[derive(Subcommand)]
enum OdeCommand {
    /// Print f1, f1~, f3, f3~, g0~, g2, g2~ from the Bessel formulas (eqs. F1 - tildeG2a).
    #[command(allow_negative_numbers = true)]
    Coefficients {
        /// Droplet radius R.
        #[arg(long, default_value_t = 1.0)]
        radius: f64,
        /// Cubic coefficient h0 (reported alongside).
        #[arg(long, default_value_t = droplet_solver::contract::settings::H0_PAPER)]
        h0: f64,
        /// Print one JSON object (keys f1, f1t, f3, f3t, g0t, g2, g2t, h0, radius).
        #[arg(long)]
        json: bool,
    },
    /// Steady states along a line with their stability and the bifurcation points (Fig. 3b):
    /// writes DIR/<stem>.parquet, DIR/<stem>_events.parquet and DIR/<stem>.png/.svg.
    #[command(
        allow_negative_numbers = true,
        after_help = "Examples:\n  droplet ode bifurcation --kappa2 0.130 --from 0.07 --to 0.10 --out results/ode   # vary eta_t\n  droplet ode bifurcation --eta-t 0.085 --from 0.10 --to 0.17 --out results/ode    # vary kappa2"
    )]
    Bifurcation {
        #[command(flatten)]
        line: super::line::LineArgs,
        /// Samples along the line.
        #[arg(long, default_value_t = 600)]
        steps: usize,
        #[arg(long, default_value_t = 1.0)]
        radius: f64,
        #[arg(long, default_value_t = droplet_solver::contract::settings::H0_PAPER)]
        h0: f64,
        #[arg(long, default_value_t = 0.1)]
        mass: f64,
        #[arg(long, default_value_t = 0.1)]
        eta2: f64,
        /// Output directory.
        #[arg(long, default_value = "out/ode")]
        out: PathBuf,
        /// Print a JSON summary (events and files).
        #[arg(long)]
        json: bool,
    },
}

/// Most samples of one bifurcation line.
const MAX_STEPS: usize = 1_000_000;

pub fn run(a: Args) -> Result<(), CliError> {
    match a.command {
        OdeCommand::Coefficients { radius, h0, json } => coefficients(radius, h0, json),
        OdeCommand::Bifurcation {
            line,
            steps,
            radius,
            h0,
            mass,
            eta2,
            out,
            json,
        } => bifurcation(
            &line,
            steps,
            ModelParams {
                mass,
                eta2,
                radius,
                ..ModelParams::default()
            },
            h0,
            &out,
            json,
        ),
    }
}

/// `droplet ode coefficients`: the reduced model's coefficients at radius `radius`.
fn coefficients(radius: f64, h0: f64, json: bool) -> Result<(), CliError> {
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(CliError::usage(format!(
            "invalid --radius {radius}: a finite number > 0"
        )));
    }
    let c = Coefficients::new(radius, h0);
    if json {
        print_json(&c);
    } else {
        outln!(
            "R = {radius}: f1 = {:.6}  f1~ = {:.6}  f3 = {:.6}  f3~ = {:.6}",
            c.f1,
            c.f1t,
            c.f3,
            c.f3t
        );
        outln!(
            "        g0~ = {:.6}  g2 = {:.6}  g2~ = {:.6}  h0 = {}",
            c.g0t,
            c.g2,
            c.g2t,
            c.h0
        );
    }
    Ok(())
}

/// `droplet ode bifurcation`: the reduced model's steady states along `line` (`steps`
/// values), with their stability and bifurcation points, as tables and a picture in `out`.
fn bifurcation(
    line: &super::line::LineArgs,
    steps: usize,
    params: ModelParams,
    h0: f64,
    out: &std::path::Path,
    json: bool,
) -> Result<(), CliError> {
    let radius = params.radius;
    if !(2..=MAX_STEPS).contains(&steps) {
        return Err(CliError::usage(format!(
            "invalid --steps {steps}: from 2 to {MAX_STEPS}"
        )));
    }
    let (axis, fixed_param, fixed) = line.parameter();
    let fixed_name = fixed_param.name();
    let x_label = line.varied();
    let fixed_label = format!("{fixed_name} = {fixed}");
    let (from, to) = (line.span.from, line.span.to);
    let base = line.start(params)?;
    droplet_sweep::store::atomic::create_output_dir(out)?;
    let c = Coefficients::new(radius, h0);
    let values: Vec<f64> = (0..steps)
        .map(|i| from + (to - from) * i as f64 / (steps - 1) as f64)
        .collect();
    let (pts, events) = diagram(&c, &base, axis, &values);
    let stem = format!("bifurcation_{}", fixed_label.replace(" = ", "_"));
    let [p1, p2] = droplet_sweep::tables::bifurcation::write(
        out,
        &stem,
        &pts,
        &events,
        axis,
        &c,
        &format!("{fixed_label}, {x_label} from {from} to {to}"),
    )?;
    let mut files = droplet_sweep::pictures::branch_pictures::ode_bifurcation(
        out,
        &stem,
        &pts,
        &events,
        axis,
        &format!("ODE model, {fixed_label}: solid = stable, dashed = unstable, dots = P / SN"),
    )?;
    files.extend([p1, p2]);
    if json {
        print_json(&serde_json::json!({ "events": events, "files": files, "points": pts.len() }));
    } else {
        for e in &events {
            outln!(
                "{:>3} on {:<14} at {x_label} = {:.5}",
                e.kind,
                e.branch.as_str(),
                e.at
            );
        }
        for f in files {
            outln!("wrote {}", f.display());
        }
    }
    Ok(())
}
