//! How runs with shape modes 2..K end their slow stretches, each against pure time stepping
//! or the run stepped all the way: a turn to a root short of the next mirror line, a slow
//! approach to the resting disk, a departure leapt, a saddle the run cannot leave.
use crate::modes::{committed, orientation_deg, same_end};
use droplet_solver::contract::ending::{Ending, SteadyMethod};
use droplet_solver::contract::outcome::{RunOutcome, RunStatus};
use droplet_solver::contract::settings::SolverSettings;
use droplet_solver::model::{classify::StateClass, initial::InitialCondition, params::ModelParams};
use droplet_solver::runs::driver::simulate;

/// The default settings at N = 96, the grid of these tests (their model has shape modes
/// 2..4, [`four`]).
fn n96() -> SolverSettings {
    SolverSettings {
        n: 96,
        ..SolverSettings::default()
    }
}

/// The model at `(eta_t, kappa2)` with shape modes 2..4.
fn four(eta_t: f64, kappa2: f64) -> ModelParams {
    ModelParams::at(eta_t, kappa2).with_modes(4)
}

/// Asserts that `out` ended steady on the resting disk by the landing before `t_below`.
fn assert_landed_on_the_disk(out: &RunOutcome, t_below: f64) {
    assert_eq!(out.status, RunStatus::Steady, "{out:?}");
    assert_eq!(out.class, Some(StateClass::IC), "{out:?}");
    assert_eq!(out.ended_by, Some(Ending::Landing), "{out:?}");
    assert!(out.t_end < t_below && out.v == 0.0, "{out:?}");
}

#[test]
fn a_four_mode_run_turning_towards_a_root_short_of_the_next_line_ends_there_early() {
    // Modes 2..4 at N = 96, (0.076, 0.14175) and (0.076, 0.14225) from ii: the x-axis MD is
    // unstable in rotation, and the run turns to the stable root a few degrees short of the
    // diagonal, where pure time stepping ends at t = 6050 and 6810
    // (results/k-mode-endings/runs/pure-tails-k4-n96.json). Newton from the turned states
    // finds only that root's mirror image past the diagonal; the turn search takes the image's
    // image (numerics modes-10), and the run ends within a few hundred time units.
    let pure = committed("pure-tails-k4-n96");
    assert_eq!(pure.len(), 2);
    let settings = n96();
    for end in &pure {
        assert!(end.orientation_deg > 37.0 && end.orientation_deg < 40.0);
        let p = four(end.eta_t, end.kappa2);
        let out = simulate(&p, &InitialCondition::parse(&end.ic).unwrap(), &settings).unwrap();
        assert!(same_end(&out, end), "{}: {out:?}", end.kappa2);
        assert!(out.t_end < 1000.0, "{}: {out:?}", end.kappa2);
    }
}

#[test]
fn a_four_mode_run_turning_slowly_back_to_a_stable_root_ends_once_settled_beside_it() {
    // Modes 2..4 at N = 192 (at N = 96 the run ends on the diagonal), (0.07625, 0.14425) from
    // iii: the run settles 4.8 degrees off the x axis by t = 2600 and turns back to the x-axis
    // MD, stable in rotation, at a rate of 5.7e-5, where pure time stepping ends
    // (results/k-mode-endings/runs/pure-rotation-k4-n192.json). Its speed and shape are those
    // of the MD's family at its own orientation (the root's differ by 1.2e-4 there): numerics
    // modes-12 ended it on the root by Newton at t = 2845, where the paper's test had ended
    // it at t = 26 504; modes-13 at t = 3557, the orientation's flow sampled only out to 5
    // degrees (0.05 degree apart). With the landing (the default) the run is landed as it
    // leaves the disk (numerics modes-14, the next test); without it, it steps to the turn.
    let pure = committed("pure-rotation-k4-n192");
    let end = pure
        .iter()
        .find(|e| e.ic == "iii")
        .expect("the run from iii");
    let settings = SolverSettings {
        n: 192,
        landing: false,
        ..n96()
    };
    let p = four(end.eta_t, end.kappa2);
    let out = simulate(&p, &InitialCondition::parse("iii").unwrap(), &settings).unwrap();
    assert!(same_end(&out, end), "{out:?}");
    assert_eq!(out.ended_by, Some(Ending::Newton), "{out:?}");
    assert!(out.t_end > 2000.0 && out.t_end < 4000.0, "{out:?}");
    assert!(orientation_deg(&out).abs() < 1e-5, "{out:?}");
}

#[test]
fn a_four_mode_run_leaving_the_disk_lands_at_the_lean_its_initial_condition_gave_it() {
    // The same point from iii and iv (numerics modes-14): each leaves the resting disk along
    // the x axis leaning 5.7 degrees, atan(0.1) from its initial condition, and its lean
    // holds while its speed grows 20-fold. The orientation's flow on the x-axis MD's family,
    // sampled 0.05 degree apart out to 8 degrees for a run leaving the disk, points back at
    // every sample, and the landing ends the run there as it leaves; out to 5 degrees (for
    // any other run) the landing waited until the run had turned within them, at t = 2240
    // (iv), or Newton ended it at t = 3557 (iii).
    let settings = SolverSettings { n: 192, ..n96() };
    for end in committed("pure-rotation-k4-n192") {
        let p = four(end.eta_t, end.kappa2);
        let ic = InitialCondition::parse(&end.ic).unwrap();
        let out = simulate(&p, &ic, &settings).unwrap();
        assert!(same_end(&out, &end), "{}: {out:?}", end.ic);
        assert_eq!(out.ended_by, Some(Ending::Landing), "{}: {out:?}", end.ic);
        assert!(out.t_end < 100.0, "{}: {out:?}", end.ic);
    }
}

#[test]
fn a_four_mode_run_turning_back_to_its_root_from_below_a_degree_ends_early() {
    // Modes 2..4 at N = 96, Fig. 1c (0.085, 0.112) from ii (numerics modes-14): the run turns
    // back to the x-axis MD, stable in every mode, from 0.57 degrees. Its own trigger (rates
    // below 1e-4) ended it at t = 59.6; the early try (rates below 3e-3 from numerics
    // modes-15, 1e-3 before: t = 32.4) ends it on the same root at t = 24.8 once it is seen
    // turning towards it on the root's family, the orientation's flow pointing back out to
    // its lean (results/k-mode-endings/runs/pure-k4-n96.json).
    let end = committed("pure-k4-n96")
        .into_iter()
        .find(|e| (e.eta_t, e.kappa2) == (0.085, 0.112) && e.ic == "ii")
        .expect("the run from ii");
    let p = four(end.eta_t, end.kappa2);
    let out = simulate(&p, &InitialCondition::parse("ii").unwrap(), &n96()).unwrap();
    assert!(same_end(&out, &end), "{out:?}");
    assert_eq!(out.ended_by, Some(Ending::Newton), "{out:?}");
    assert!(out.t_end < 30.0, "{out:?}");
}

#[test]
fn a_four_mode_run_leaving_a_saddle_leaning_lands_once_the_flow_turns_it_back() {
    // Modes 2..4 at N = 192 (0.08725, 0.115) from iii: the run leaves the diagonal ID along
    // its drift (growth 2.1e-4) leaning 0.56 degrees from the diagonal, its lean shrinking at
    // 4e-5, and pure time stepping reaches the diagonal's slow MD (v = 0.0213) at t = 28 500
    // (results/k-mode-endings/runs/pure-departure-k4-n192.json). The landing's slow flow takes
    // it there; the orientation's flow on that MD's family points back to the diagonal at
    // every sample, 0.05 degree apart, out to the run's lean, so the landing ends the run
    // there (numerics modes-13; before, it stepped through the departure).
    let pure = committed("pure-departure-k4-n192");
    let end = pure
        .iter()
        .find(|e| e.eta_t == 0.08725 && e.ic == "iii")
        .expect("the run from iii");
    let settings = SolverSettings { n: 192, ..n96() };
    let p = four(end.eta_t, end.kappa2);
    let out = simulate(&p, &InitialCondition::parse("iii").unwrap(), &settings).unwrap();
    assert!(same_end(&out, end), "{out:?}");
    // Pure stepping stops (every rate below 1e-9) 2.9e-6 short of the root in `v`: near its
    // onset the MD attracts at about twice the ID's growth, 4e-4, so a rate of 1e-9 is
    // 2.5e-6 from it.
    assert!(
        (out.v - end.v).abs() < 1e-5 && (out.s - end.s).abs() < 1e-6,
        "{out:?}"
    );
    assert_eq!(out.ended_by, Some(Ending::Landing), "{out:?}");
    // t = 1139 (numerics modes-16; 804 with modes-15), pure stepping 44 371.
    assert!(out.t_end < 1500.0, "{out:?}");
}

#[test]
fn a_four_mode_run_slowing_onto_the_resting_disk_lands_there() {
    // Modes 2..4 at N = 96, (0.0765, 0.16425) from i, just past the disk's onset of motion:
    // the run slows down along the speed family to the resting disk, which the box deforms
    // in its mode 4 (a4 = -5.4e-4, b4 = 0, no orientation of its own). The landing ends the
    // run there (numerics modes-10; before, the disk's a4 was taken for an orientation and
    // the run crept on to the Newton finish, at t = 6860 with N = 192).
    let out = simulate(
        &four(0.0765, 0.16425),
        &InitialCondition::parse("i").unwrap(),
        &n96(),
    )
    .unwrap();
    assert_landed_on_the_disk(&out, 1000.0);
    let [a3, a4, b3, b4] = out.higher_modes[..] else {
        panic!("{out:?}")
    };
    assert!(out.v == 0.0 && out.s < 1e-12, "{out:?}");
    assert!(
        a4 < -1e-4 && (a3.abs() + b3.abs() + b4.abs()) < 1e-12,
        "{out:?}"
    );
}

#[test]
fn a_four_mode_run_past_the_md_fold_lands_on_the_disk_long_before_its_own_trigger() {
    // Modes 2..4 at N = 96, (0.07875, 0.12775) from ii, just past the MD fold: the run moves
    // on along the ghost of the fold, slowing down for hundreds of time units, and comes to
    // rest on the disk. Its rates fall below the 2-mode runs' trigger long before its own;
    // there the disk's try hands it to the landing, whose slow flow takes it to the disk
    // (numerics modes-11; before, it crept to the Newton finish at t = 647). Pure time
    // stepping ends on the same disk.
    let p = four(0.07875, 0.12775);
    let ic = InitialCondition::parse("ii").unwrap();
    let defaults = n96();
    let out = simulate(&p, &ic, &defaults).unwrap();
    assert_landed_on_the_disk(&out, 200.0);
    let pure = simulate(
        &p,
        &ic,
        &SolverSettings {
            steady: SteadyMethod::Test,
            steady_tol: 1e-9,
            t_max: 20_000.0,
            ..defaults
        },
    )
    .unwrap();
    assert_eq!(pure.class, Some(StateClass::IC), "{pure:?}");
    assert!(pure.t_end > 500.0 && pure.v < 1e-6, "{pure:?}");
    assert!((pure.s - out.s).abs() < 1e-6, "{pure:?} {out:?}");
    for (a, b) in pure.higher_modes.iter().zip(&out.higher_modes) {
        assert!((a - b).abs() < 1e-6, "{pure:?} {out:?}");
    }
}

#[test]
fn a_four_mode_run_leaps_along_a_departure_and_ends_where_stepping_does() {
    // Modes 2..4 at N = 96, (0.07625, 0.14) from iii, the landing off: the run leaves the
    // resting disk (unstable in its drift, growth 1.9e-3) along the growing mode; with
    // leap_departures it leaps over more than 500 time units of that departure and ends on
    // the same MD state as the run stepped all the way (the leap scales the field and every
    // unknown towards the saddle's own), in fewer steps.
    let p = four(0.07625, 0.14);
    let ic = InitialCondition::parse("iii").unwrap();
    let stepped = SolverSettings {
        t_max: 4000.0,
        landing: false,
        ..n96()
    };
    let leapt = SolverSettings {
        leap_departures: true,
        ..stepped
    };
    let (a, b) = (
        simulate(&p, &ic, &stepped).unwrap(),
        simulate(&p, &ic, &leapt).unwrap(),
    );
    assert_eq!(a.t_leapt, 0.0, "{a:?}");
    assert!(b.t_leapt > 500.0, "{b:?}");
    assert!(b.steps < a.steps, "{} against {}", b.steps, a.steps);
    assert_eq!(b.status, RunStatus::Steady, "{b:?}");
    assert_eq!(b.class, Some(StateClass::MD), "{b:?}");
    assert!(
        (a.v - b.v).abs() < 1e-9 && (a.s - b.s).abs() < 1e-9,
        "{a:?} {b:?}"
    );
    let turn = orientation_deg(&a) - orientation_deg(&b);
    assert!(turn.abs() < 1e-6, "{turn}");
}

#[test]
fn a_four_mode_run_beside_a_saddle_it_cannot_leave_stops_there() {
    // Modes 2..4 at N = 96, (0.08725, 0.115) from iv, landing and run-on off: the run rests on
    // the diagonal's deformed state, whose drift grows at 1e-3, and cannot leave it before
    // t_max = 2000; with stop_beside_saddle it stops within a few hundred time units,
    // unsettled beside the saddle, as plain stepping ends at t_max.
    let p = four(0.08725, 0.115);
    let ic = InitialCondition::parse("iv").unwrap();
    let waited = SolverSettings {
        landing: false,
        run_on: false,
        ..n96()
    };
    let stopped = SolverSettings {
        stop_beside_saddle: true,
        ..waited
    };
    let (a, b) = (
        simulate(&p, &ic, &waited).unwrap(),
        simulate(&p, &ic, &stopped).unwrap(),
    );
    assert_eq!(a.status, RunStatus::TMax, "{a:?}");
    assert_eq!(b.status, RunStatus::Saddle, "{b:?}");
    assert!(b.t_end < 1000.0, "{b:?}");
    for out in [&a, &b] {
        assert_eq!(
            out.unsettled,
            Some(droplet_solver::contract::outcome::Unsettled::BesideSaddle),
            "{out:?}"
        );
        assert_eq!(out.class, None, "{out:?}");
    }
}
