//! The parameter line shared by `droplet ode bifurcation` and `droplet continue`: one of
//! eta_t / kappa2 fixed, the other varied from --from to --to.
use super::CliError;
use droplet_solver::continuation::branch::PARAMETER_LIMIT;
use droplet_solver::error::show_number;
use droplet_solver::model::param::ModelParam;
use droplet_solver::model::params::ModelParams;

#[derive(clap::Args)]
pub struct LineArgs {
    /// Fix eta_t and vary kappa2.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with = "kappa2",
        required_unless_present = "kappa2"
    )]
    pub eta_t: Option<f64>,
    /// Fix kappa2 and vary eta_t.
    #[arg(long, allow_hyphen_values = true)]
    pub kappa2: Option<f64>,
    #[command(flatten)]
    pub span: Span,
}

/// Where a line runs: `--from A --to B`.
#[derive(clap::Args)]
pub struct Span {
    /// Start of the varied parameter.
    #[arg(long, allow_hyphen_values = true)]
    pub from: f64,
    /// End of the varied parameter.
    #[arg(long, allow_hyphen_values = true)]
    pub to: f64,
}

impl Span {
    /// Refuses a line that does not run forward between two finite numbers.
    pub fn check(&self) -> Result<(), CliError> {
        if self.from.is_finite() && self.to.is_finite() && self.from < self.to {
            return Ok(());
        }
        Err(CliError::usage(format!(
            "invalid line --from {} --to {}: two finite numbers with from < to",
            show_number(self.from),
            show_number(self.to)
        )))
    }
}

impl LineArgs {
    /// The varied parameter, the fixed one's name and value.
    pub fn parameter(&self) -> (ModelParam, ModelParam, f64) {
        match (self.eta_t, self.kappa2) {
            (Some(e), _) => (ModelParam::Kappa2, ModelParam::EtaT, e),
            (_, Some(k)) => (ModelParam::EtaT, ModelParam::Kappa2, k),
            _ => unreachable!("clap requires one"),
        }
    }

    /// The varied parameter's name.
    pub fn varied(&self) -> &'static str {
        self.parameter().0.name()
    }

    /// `base` at the line's start, after checking that the line runs forward and that both
    /// of its ends are valid parameters.
    pub fn start(&self, base: ModelParams) -> Result<ModelParams, CliError> {
        self.span.check()?;
        let (axis, fixed_param, fixed) = self.parameter();
        let fixed_name = fixed_param.name();
        let varied = self.varied();
        within_limit(&format!("--{}", fixed_name.replace('_', "-")), fixed)?;
        within_limit(&format!("--to (the line's {varied})"), self.span.to)?;
        let at = |x: f64| {
            let mut p = base;
            fixed_param.set(&mut p, fixed);
            axis.set(&mut p, x);
            p
        };
        at(self.span.to).validate()?;
        let start = at(self.span.from);
        start.validate()?;
        Ok(start)
    }
}

/// Refuses an `eta_t` or `kappa2` beyond [`PARAMETER_LIMIT`], naming the option.
pub fn within_limit(option: &str, value: f64) -> Result<(), CliError> {
    if value.is_finite() && value <= PARAMETER_LIMIT {
        Ok(())
    } else {
        Err(CliError::usage(format!(
            "invalid {option} {}: at most {PARAMETER_LIMIT} (far beyond the paper's window \
             eta_t 0.07-0.10, kappa2 0.10-0.17; wider lines lose the precision of the \
             bifurcation points)",
            show_number(value)
        )))
    }
}
