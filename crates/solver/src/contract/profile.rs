//! Where a run's wall time goes: time stepping, the Newton solves of its finish, the
//! eigenvalue problems of their roots, the landing's and the orientation flow's samples, the
//! leap and the diagnosis of an unfinished run (`droplet bench --map`, the sweep's closing
//! line; docs/performance.md).
//!
//! Each part's time is exclusive: a Newton solve made for the landing counts as Newton, not
//! as landing, so the parts add up to the run's time but for the driver's own bookkeeping.
//! The steady field solves (the transforms, the field and its forces for one droplet) that
//! every part but stepping makes are counted across the parts. The profiler is one per
//! thread (a run is computed on one thread from start to end): [`start`] at a run's start,
//! [`enter`] around each part, [`finish`] at its end.
use serde::Serialize;
use std::cell::RefCell;
use std::time::Instant;

/// One part of a run's work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Time steps of the scheme (the field and the droplet).
    Stepping,
    /// Newton solves of the steady equations (the finish's tries, the landing's and the
    /// turn's confirmations, the diagnosis).
    Newton,
    /// Eigenvalue problems of the roots found (the linearisation with the field).
    Eigen,
    /// The slow flow's samples along a mirror line ([`crate::runs::landing`]).
    Landing,
    /// The orientation's slow flow ([`crate::runs::rotation_flow`]).
    Flow,
    /// The steady field a leap scales the run towards.
    Leap,
    /// What an unfinished run is diagnosed with, beyond its Newton solves.
    Diagnosis,
}

/// Seconds and counts of one run's parts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct RunProfile {
    pub stepping_s: f64,
    pub newton_s: f64,
    pub eigen_s: f64,
    pub landing_s: f64,
    pub flow_s: f64,
    pub leap_s: f64,
    pub diagnosis_s: f64,
    /// Newton solves of the steady equations.
    pub newton_solves: u64,
    /// Eigenvalue problems solved.
    pub eigen_problems: u64,
    /// Steady field solves, in every part.
    pub field_solves: u64,
    /// The steady field solves of each part (time stepping makes none).
    pub fields: FieldSolves,
}

/// Steady field solves per part.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct FieldSolves {
    pub newton: u64,
    pub eigen: u64,
    pub landing: u64,
    pub flow: u64,
    pub leap: u64,
    pub diagnosis: u64,
    /// Outside every part (none in a run; a computation that is not a run).
    pub other: u64,
}

impl FieldSolves {
    fn add(&mut self, o: &FieldSolves) {
        self.newton += o.newton;
        self.eigen += o.eigen;
        self.landing += o.landing;
        self.flow += o.flow;
        self.leap += o.leap;
        self.diagnosis += o.diagnosis;
        self.other += o.other;
    }

    fn of(&mut self, part: Option<Part>) -> &mut u64 {
        match part {
            Some(Part::Newton) => &mut self.newton,
            Some(Part::Eigen) => &mut self.eigen,
            Some(Part::Landing) => &mut self.landing,
            Some(Part::Flow) => &mut self.flow,
            Some(Part::Leap) => &mut self.leap,
            Some(Part::Diagnosis) => &mut self.diagnosis,
            Some(Part::Stepping) | None => &mut self.other,
        }
    }
}

impl RunProfile {
    /// The seconds of every part together.
    pub fn total_s(&self) -> f64 {
        self.stepping_s
            + self.newton_s
            + self.eigen_s
            + self.landing_s
            + self.flow_s
            + self.leap_s
            + self.diagnosis_s
    }

    /// Adds another run's profile.
    pub fn add(&mut self, o: &RunProfile) {
        self.stepping_s += o.stepping_s;
        self.newton_s += o.newton_s;
        self.eigen_s += o.eigen_s;
        self.landing_s += o.landing_s;
        self.flow_s += o.flow_s;
        self.leap_s += o.leap_s;
        self.diagnosis_s += o.diagnosis_s;
        self.newton_solves += o.newton_solves;
        self.eigen_problems += o.eigen_problems;
        self.field_solves += o.field_solves;
        self.fields.add(&o.fields);
    }

    fn seconds(&mut self, part: Part) -> &mut f64 {
        match part {
            Part::Stepping => &mut self.stepping_s,
            Part::Newton => &mut self.newton_s,
            Part::Eigen => &mut self.eigen_s,
            Part::Landing => &mut self.landing_s,
            Part::Flow => &mut self.flow_s,
            Part::Leap => &mut self.leap_s,
            Part::Diagnosis => &mut self.diagnosis_s,
        }
    }
}

/// The parts open on this thread (innermost last, with the time it last resumed) and the
/// run's totals.
#[derive(Default)]
struct Profiler {
    open: Vec<(Part, Instant)>,
    totals: RunProfile,
}

thread_local! {
    static PROFILER: RefCell<Profiler> = RefCell::new(Profiler::default());
}

/// Starts a run's profile on this thread (what an earlier run left is dropped).
pub fn start() {
    PROFILER.with(|p| *p.borrow_mut() = Profiler::default());
}

/// The profile of the run since [`start`].
pub fn finish() -> RunProfile {
    PROFILER.with(|p| std::mem::take(&mut *p.borrow_mut()).totals)
}

/// An open part: its time counts until the guard is dropped, less the parts opened inside it.
#[must_use = "the part's time counts until the guard is dropped"]
pub struct Timed(());

/// Opens `part` (pausing the part open around it) until the returned guard is dropped.
pub fn enter(part: Part) -> Timed {
    PROFILER.with(|p| {
        let mut p = p.borrow_mut();
        let now = Instant::now();
        if let Some(&(outer, since)) = p.open.last() {
            *p.totals.seconds(outer) += (now - since).as_secs_f64();
        }
        match part {
            Part::Newton => p.totals.newton_solves += 1,
            Part::Eigen => p.totals.eigen_problems += 1,
            _ => {}
        }
        p.open.push((part, now));
    });
    Timed(())
}

impl Drop for Timed {
    fn drop(&mut self) {
        PROFILER.with(|p| {
            let mut p = p.borrow_mut();
            let now = Instant::now();
            if let Some((part, since)) = p.open.pop() {
                *p.totals.seconds(part) += (now - since).as_secs_f64();
            }
            if let Some(outer) = p.open.last_mut() {
                outer.1 = now;
            }
        });
    }
}

/// Counts one steady field solve, for the part open.
pub fn field_solve() {
    PROFILER.with(|p| {
        let mut p = p.borrow_mut();
        let part = p.open.last().map(|&(part, _)| part);
        p.totals.field_solves += 1;
        *p.totals.fields.of(part) += 1;
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn busy(ms: u64) {
        let t = Instant::now();
        while t.elapsed().as_millis() < u128::from(ms) {
            std::hint::spin_loop();
        }
    }

    #[test]
    fn nested_parts_count_their_own_time_only() {
        start();
        {
            let _landing = enter(Part::Landing);
            busy(10);
            {
                let _newton = enter(Part::Newton);
                busy(40);
                field_solve();
            }
            busy(10);
        }
        let p = finish();
        assert_eq!(
            (p.newton_solves, p.field_solves, p.fields.newton),
            (1, 1, 1)
        );
        // The landing's own 20 ms, not the 60 ms it was open (25 ms of slack for a busy
        // machine).
        assert!(p.newton_s >= 0.040, "{p:?}");
        assert!(p.landing_s >= 0.020 && p.landing_s < 0.045, "{p:?}");
        assert!((p.total_s() - p.newton_s - p.landing_s).abs() < 1e-12);
        // A new run starts from nothing.
        start();
        assert_eq!(finish(), RunProfile::default());
    }
}
