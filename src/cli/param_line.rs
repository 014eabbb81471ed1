//! The line of `droplet continue`: any model parameter varied from --from to --to, the others
//! fixed by --set (and the defaults). `--kappa2 K` and `--eta-t E` are the paper's lines.
use super::line::within_limit;
use super::CliError;
use droplet_solver::error::show_number;
use droplet_solver::model::{param::ModelParam, params::ModelParams};

#[derive(clap::Args)]
pub struct ParamLineArgs {
    /// Vary this model parameter: eta_t, kappa2, eta2, mass, radius, sigma or box_len (eta2
    /// and mass move the eigenvalues only: their branches are level, their stability is
    /// not). The others: --set, else the defaults.
    #[arg(long, conflicts_with_all = ["eta_t", "kappa2"], required_unless_present_any = ["eta_t", "kappa2"])]
    pub param: Option<String>,
    /// Fixed values of other parameters: NAME=VALUE[,NAME=VALUE...], e.g.
    /// eta_t=0.085,kappa2=0.13 (default: eta_t 0.085, kappa2 0.112, eta2 0.1, R 1,
    /// sigma 0.03, box_len 7, mass 0.1).
    #[arg(long, requires = "param")]
    pub set: Option<String>,
    /// The paper's line: fix eta_t and vary kappa2 (= --param kappa2 --set eta_t=E).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "kappa2")]
    pub eta_t: Option<f64>,
    /// The paper's line: fix kappa2 and vary eta_t (= --param eta_t --set kappa2=K).
    #[arg(long, allow_hyphen_values = true)]
    pub kappa2: Option<f64>,
    #[command(flatten)]
    pub span: super::line::Span,
}

impl ParamLineArgs {
    /// The varied parameter and the line's base parameters (at --from), every value checked:
    /// names, `NAME=VALUE` syntax, both ends valid, `eta_t` and `kappa2` within
    /// [`droplet_solver::continuation::branch::PARAMETER_LIMIT`], and `m > 0` everywhere on
    /// the line (the eigenvalues need inertia). `mass` is the `--mass` option's value unless
    /// set here.
    pub fn line(&self, mass: Option<f64>) -> Result<(ModelParam, ModelParams), CliError> {
        let mut base = ModelParams {
            mass: mass.unwrap_or(ModelParams::default().mass),
            ..ModelParams::default()
        };
        let varied = match (&self.param, self.eta_t, self.kappa2) {
            (Some(name), _, _) => ModelParam::parse(name).ok_or_else(|| {
                CliError::usage(format!(
                    "invalid --param {name}: one of {}",
                    ModelParam::names()
                ))
            })?,
            (None, Some(e), _) => {
                within_limit("--eta-t", e)?;
                base.eta_t = e;
                ModelParam::Kappa2
            }
            (None, None, Some(k)) => {
                within_limit("--kappa2", k)?;
                base.kappa2 = k;
                ModelParam::EtaT
            }
            _ => unreachable!("clap requires one"),
        };
        // The paper's lines fix eta_t (--eta-t) or kappa2 (--kappa2) by an option of their own.
        let fixed = match (self.param.is_some(), self.eta_t, self.kappa2) {
            (false, Some(_), _) => Some(ModelParam::EtaT),
            (false, None, Some(_)) => Some(ModelParam::Kappa2),
            _ => None,
        };
        for (p, x) in self.settings()? {
            if Some(p) == fixed {
                return Err(CliError::usage(format!(
                    "invalid --set {p}={x}: {p} is given by --{} too; give it once",
                    p.name().replace('_', "-")
                )));
            }
            if p == varied {
                return Err(CliError::usage(format!(
                    "invalid --set {p}={x}: {p} is the varied parameter (--from, --to)"
                )));
            }
            if p == ModelParam::Mass && mass.is_some() {
                return Err(CliError::usage(
                    "invalid --set mass: given by --mass too; give it once".to_string(),
                ));
            }
            if matches!(p, ModelParam::EtaT | ModelParam::Kappa2) {
                within_limit(&format!("--set {p}"), x)?;
            }
            p.set(&mut base, x);
        }
        if varied == ModelParam::Mass && mass.is_some() {
            return Err(CliError::usage(
                "invalid --mass with --param mass: the line gives the mass (--from, --to)"
                    .to_string(),
            ));
        }
        self.check_ends(varied, &base)?;
        Ok((varied, varied.with(&base, self.span.from)))
    }

    /// `--set` as (parameter, value) pairs.
    fn settings(&self) -> Result<Vec<(ModelParam, f64)>, CliError> {
        self.set.as_deref().map_or(Ok(Vec::new()), parse_set)
    }

    /// The line runs forward, its ends are valid parameters, and `m > 0` on it.
    fn check_ends(&self, varied: ModelParam, base: &ModelParams) -> Result<(), CliError> {
        self.span.check()?;
        if matches!(varied, ModelParam::EtaT | ModelParam::Kappa2) {
            within_limit(&format!("--to (the line's {varied})"), self.span.to)?;
        }
        for end in [self.span.from, self.span.to] {
            varied.with(base, end).validate()?;
        }
        let mass_low = if varied == ModelParam::Mass {
            self.span.from
        } else {
            base.mass
        };
        if mass_low.is_nan() || mass_low <= 0.0 {
            return Err(CliError::usage(format!(
                "invalid mass {}: a finite number > 0 along the whole line (the eigenvalues \
                 need inertia)",
                show_number(mass_low)
            )));
        }
        Ok(())
    }
}

/// `--set NAME=VALUE[,NAME=VALUE...]` as (parameter, value) pairs: each name a model
/// parameter, given once, each value a finite number (its range is checked where it is used).
pub fn parse_set(text: &str) -> Result<Vec<(ModelParam, f64)>, CliError> {
    let mut out: Vec<(ModelParam, f64)> = Vec::new();
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let bad = |why: String| CliError::usage(format!("invalid --set {item}: {why}"));
        let (name, value) = item
            .split_once('=')
            .ok_or_else(|| bad("NAME=VALUE, e.g. eta_t=0.085".into()))?;
        let p = ModelParam::parse(name.trim())
            .ok_or_else(|| bad(format!("NAME one of {}", ModelParam::names())))?;
        let x: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|x: &f64| x.is_finite())
            .ok_or_else(|| bad("VALUE a finite number".into()))?;
        if out.iter().any(|(q, _)| *q == p) {
            return Err(bad(format!("{p} given twice")));
        }
        out.push((p, x));
    }
    Ok(out)
}
