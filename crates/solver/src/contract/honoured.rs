//! What a run honours: which solver settings a run of a given model, scheme, shape modes and
//! ending reads, and the settings with every unread one at its kind's base value (what a run
//! is keyed by and recorded with). The spec, every command and the tables ask here, so that a
//! setting is never accepted and then ignored, and two runs that differ only in settings they
//! do not read are one run.
use crate::contract::ending::SteadyMethod;
use crate::contract::settings::{ModelKind, SolverSettings};
use crate::stepping::SchemeKind;

impl SolverSettings {
    /// The settings a run of this kind starts from: the ODE model's, the paper's scheme's or
    /// the default spectral ones. A setting the run does not read has this value in its key.
    fn base(&self) -> Self {
        match (self.model, self.scheme) {
            (ModelKind::Ode, _) => Self::ode(),
            (ModelKind::Pde, SchemeKind::PaperFd) => Self::paper_fd(),
            (ModelKind::Pde, SchemeKind::Spectral) => Self::default(),
        }
    }

    /// Why a run with these settings does not read the setting `field` (its key in a spec's
    /// `solver` section, and its column in `runs.parquet`), or `None` when it reads it. This
    /// is the one account of what a run honours: the spec, every command and the tables use it.
    /// `modes` is the model's `K` ([`crate::model::params::ModelParams::modes`]).
    pub fn unread_reason(&self, modes: usize, field: &str) -> Option<&'static str> {
        let ode = self.model == ModelKind::Ode;
        let k_modes = !ode && modes > 2;
        let newton = self.steady == SteadyMethod::Newton;
        let spectral = !ode && self.scheme == SchemeKind::Spectral;
        match field {
            "h0" if !ode => Some("h0 is the reduced (ODE) model's cubic coefficient; a PDE run does not read it (model: ode uses it)"),
            "n" | "scheme" if ode => Some("the ODE model has no grid and no scheme: it takes RK4 steps dt"),
            "tol" | "dt_max" | "projective_steps" if ode => Some("the ODE model takes fixed RK4 steps dt"),
            "tol" | "dt_max" | "projective_steps" if !spectral => Some("the paper's scheme takes fixed steps dt"),
            "dt_max" if !self.adaptive() => Some("tol = 0 gives fixed steps dt; dt_max caps adaptive steps only"),
            "landing" | "orientation_flow" | "stop_beside_saddle" | "leap_departures" | "run_on" if !newton => Some("it acts in the Newton finish; steady = test ends a run by the paper's test alone"),
            "orientation_flow" if k_modes => Some("runs with modes > 2 end by the Newton finish, its turn search and the landing, without the orientation flow's choice of where a run turns (2-mode runs only; they sample the flow only to confirm that a run settled beside a root, or landing on one, turns back to it, whatever this setting)"),
            "steady_window" if k_modes => Some("runs with modes > 2 are steady when every rate is below steady_tol; steady_window is the 2-mode test's window"),
            "pinned" if ode || k_modes => Some("only a 2-mode PDE run can hold its centre fixed"),
            "projective_steps" if !self.adaptive() => Some("tol = 0 gives fixed steps dt; projective steps continue adaptive steps at their cap"),
            "projective_steps" if self.pinned => Some("a run with its centre held fixed takes every step"),
            _ => None,
        }
    }

    /// True when a run with these settings reads `field` ([`Self::unread_reason`]).
    pub fn reads(&self, modes: usize, field: &str) -> bool {
        self.unread_reason(modes, field).is_none()
    }

    /// These settings with every setting the run does not read at the value of its kind's
    /// base settings ([`Self::unread_reason`]): what a run is keyed by and recorded with. Two
    /// settings that differ only where the run does not read them give one run. (A PDE run's
    /// `h0`, once set to `n` by a spec-parsing bug, is such a setting.)
    pub fn honoured(&self, modes: usize) -> Self {
        let base = self.base();
        let mut out = *self;
        let keep = |field: &str| self.reads(modes, field);
        if !keep("h0") {
            out.h0 = base.h0;
        }
        if !keep("n") {
            out.n = base.n;
        }
        if !keep("scheme") {
            out.scheme = base.scheme;
        }
        if !keep("tol") {
            out.tol = base.tol;
        }
        if !keep("dt_max") {
            out.dt_max = base.dt_max;
        }
        if !keep("steady_window") {
            out.steady_window = base.steady_window;
        }
        if !keep("pinned") {
            out.pinned = base.pinned;
        }
        if !keep("landing") {
            out.landing = base.landing;
        }
        if !keep("orientation_flow") {
            out.orientation_flow = base.orientation_flow;
        }
        if !keep("stop_beside_saddle") {
            out.stop_beside_saddle = base.stop_beside_saddle;
        }
        if !keep("leap_departures") {
            out.leap_departures = base.leap_departures;
        }
        if !keep("run_on") {
            out.run_on = base.run_on;
        }
        if !keep("projective_steps") {
            out.projective_steps = base.projective_steps;
        }
        out
    }

    /// The first of the settings a user gave (`given`: spec keys, or the fields of
    /// command-line options) that these settings do not read and that differs from the value
    /// the run goes by (`tol: 0` for the paper's scheme is what it does, not ignored), with
    /// the reason: it would be accepted and ignored, so the spec and every command refuse it.
    pub fn first_unread<'a>(
        &self,
        modes: usize,
        given: &[&'a str],
    ) -> Option<(&'a str, &'static str)> {
        let honoured = self.honoured(modes);
        given.iter().find_map(|&field| {
            let why = self.unread_reason(modes, field)?;
            self.differs(&honoured, field).then_some((field, why))
        })
    }

    /// True when `field` has another value in `other`.
    fn differs(&self, other: &Self, field: &str) -> bool {
        match field {
            "h0" => self.h0 != other.h0,
            "n" => self.n != other.n,
            "scheme" => self.scheme != other.scheme,
            "tol" => self.tol != other.tol,
            "dt_max" => self.dt_max != other.dt_max,
            "steady_window" => self.steady_window != other.steady_window,
            "pinned" => self.pinned != other.pinned,
            "landing" => self.landing != other.landing,
            "orientation_flow" => self.orientation_flow != other.orientation_flow,
            "stop_beside_saddle" => self.stop_beside_saddle != other.stop_beside_saddle,
            "leap_departures" => self.leap_departures != other.leap_departures,
            "run_on" => self.run_on != other.run_on,
            "projective_steps" => self.projective_steps != other.projective_steps,
            // Every other setting is read by every run ([`Self::unread_reason`]).
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every setting a spec's `solver` section or a command may give.
    const FIELDS: [&str; 15] = [
        "h0",
        "n",
        "scheme",
        "dt",
        "tol",
        "dt_max",
        "t_max",
        "steady_tol",
        "steady_window",
        "landing",
        "orientation_flow",
        "stop_beside_saddle",
        "leap_departures",
        "run_on",
        "projective_steps",
    ];

    /// The settings of the 3-mode runs below (the model's K is the `modes` they are asked with).
    fn k_modes() -> SolverSettings {
        SolverSettings::default()
    }

    #[test]
    fn a_two_mode_newton_run_reads_everything_but_h0() {
        let s = SolverSettings::default();
        let unread: Vec<&str> = FIELDS.into_iter().filter(|f| !s.reads(2, f)).collect();
        assert_eq!(unread, ["h0"]);
        assert!(SolverSettings::ode().reads(2, "h0"));
        assert!(!SolverSettings::ode().reads(2, "n") && !SolverSettings::ode().reads(2, "landing"));
    }

    #[test]
    fn settings_a_run_does_not_read_give_the_same_honoured_settings() {
        let base = k_modes();
        let changed = SolverSettings {
            orientation_flow: false,
            steady_window: 0.5,
            h0: 192.0,
            ..base
        };
        assert_ne!(changed, base);
        assert_eq!(changed.honoured(3), base.honoured(3));
        // What the run reads stays.
        for other in [
            SolverSettings { dt: 0.01, ..base },
            SolverSettings { tol: 1e-5, ..base },
            SolverSettings {
                dt_max: 0.1,
                ..base
            },
        ] {
            assert_ne!(other.honoured(3), base.honoured(3));
        }
        // A PDE run's h0 (the spec bug set it to n) is not part of it; an ODE run's is.
        let pde = SolverSettings {
            h0: 192.0,
            ..SolverSettings::default()
        };
        assert_eq!(pde.honoured(2), SolverSettings::default());
        let ode = SolverSettings {
            h0: 0.2,
            ..SolverSettings::ode()
        };
        assert_eq!(ode.honoured(2).h0, 0.2);
        // Honouring is idempotent and keeps a valid setting valid.
        for s in [changed, pde, ode, SolverSettings::paper_fd()] {
            assert_eq!(s.honoured(2).honoured(2), s.honoured(2));
            assert!(s.honoured(2).validate().is_ok(), "{s:?}");
        }
    }

    #[test]
    fn a_given_setting_that_is_not_read_is_named_with_the_reason() {
        let k3 = SolverSettings {
            orientation_flow: false,
            ..k_modes()
        };
        let (field, why) = k3
            .first_unread(3, &["dt", "tol", "orientation_flow"])
            .unwrap();
        assert!(
            field == "orientation_flow" && why.contains("Newton finish, its turn search"),
            "{why}"
        );
        // K-mode runs step as 2-mode runs do, fixed or adaptive, and land as they do.
        let no_landing = SolverSettings {
            landing: false,
            ..k_modes()
        };
        assert!(no_landing
            .first_unread(3, &["dt", "tol", "dt_max", "t_max", "run_on", "landing"])
            .is_none());
        let test = SolverSettings {
            steady: SteadyMethod::Test,
            ..SolverSettings::default()
        };
        // The value the run goes by is no setting ignored; another one is.
        assert!(test.first_unread(2, &["landing"]).is_none());
        let off = SolverSettings {
            landing: false,
            ..test
        };
        let (_, why) = off.first_unread(2, &["landing"]).unwrap();
        assert!(why.contains("Newton finish"), "{why}");
        let h0 = SolverSettings {
            h0: 0.2,
            ..SolverSettings::default()
        };
        let (_, why) = h0.first_unread(2, &["h0"]).unwrap();
        assert!(why.contains("ODE"), "{why}");
        let fixed = SolverSettings {
            tol: 0.0,
            ..SolverSettings::default()
        };
        assert!(fixed.first_unread(2, &["tol"]).is_none());
        let capped = SolverSettings {
            dt_max: 0.5,
            ..fixed
        };
        assert!(capped.first_unread(2, &["dt_max"]).is_some());
        assert!(SolverSettings::paper_fd()
            .first_unread(2, &["tol"])
            .is_none());
        assert_eq!(
            SolverSettings::paper_fd().honoured(2).scheme,
            SchemeKind::PaperFd
        );
    }
}
