//! The parameter line shared by `droplet ode bifurcation` and `droplet continue`: one of
//! eta_t / kappa2 fixed, the other varied from --from to --to.
use super::CliError;
use droplet_solver::reduced::bifurcation::Axis;
use droplet_solver::ModelParams;

#[derive(clap::Args)]
pub struct LineArgs {
    /// Fix eta_t and vary kappa2.
    #[arg(long, conflicts_with = "kappa2", required_unless_present = "kappa2")]
    pub eta_t: Option<f64>,
    /// Fix kappa2 and vary eta_t.
    #[arg(long)]
    pub kappa2: Option<f64>,
    /// Start of the varied parameter.
    #[arg(long)]
    pub from: f64,
    /// End of the varied parameter.
    #[arg(long)]
    pub to: f64,
}

impl LineArgs {
    /// The varied parameter, the fixed one's name and value.
    pub fn parameter(&self) -> (Axis, &'static str, f64) {
        match (self.eta_t, self.kappa2) {
            (Some(e), _) => (Axis::Kappa2, "eta_t", e),
            (_, Some(k)) => (Axis::EtaT, "kappa2", k),
            _ => unreachable!("clap requires one"),
        }
    }

    /// The varied parameter's name.
    pub fn varied(&self) -> &'static str {
        match self.parameter().0 {
            Axis::EtaT => "eta_t",
            Axis::Kappa2 => "kappa2",
        }
    }

    /// `base` at the line's start, after checking that the line runs forward and that both
    /// of its ends are valid parameters.
    pub fn start(&self, base: ModelParams) -> Result<ModelParams, CliError> {
        if !(self.from.is_finite() && self.to.is_finite() && self.from < self.to) {
            return Err(CliError::usage(format!(
                "invalid line --from {} --to {}: two finite numbers with from < to",
                self.from, self.to
            )));
        }
        let (axis, _, fixed) = self.parameter();
        let at = |x: f64| match axis {
            Axis::EtaT => ModelParams {
                eta_t: x,
                kappa2: fixed,
                ..base
            },
            Axis::Kappa2 => ModelParams {
                eta_t: fixed,
                kappa2: x,
                ..base
            },
        };
        at(self.to).validate()?;
        let start = at(self.from);
        start.validate()?;
        Ok(start)
    }
}
