//! The droplet model of Kitahata, Koyano, Kobayashi & Nagayama, "Energetics-based model for a
//! diffusiophoretic motion of a deformable droplet", its runs, its steady states and their
//! continuation.
//!
//! # Map of the crate
//!
//! Each folder holds one concern and uses only the folders listed before it (checked by
//! `tests/suite/module_graph.rs`):
//!
//! | folder | what it holds |
//! |---|---|
//! | [`numerics`] | Bessel functions, the row-pruned 2-D FFT, Newton's method for small systems |
//! | [`model`] | parameters, state, initial conditions, grid, indicator, forces, equations of motion, the classes IC / ID / MD / MC |
//! | [`stepping`] | the time integrators: co-moving ETD2RK (default, adaptive), the paper's finite differences |
//! | [`contract`] | what a run is asked (settings, limits, stop rules, how it may end) and what it answers (outcome) |
//! | [`reduced`] | the reduced ODE model of the paper's Sect. 4-5 and appendices |
//! | [`roots`] | steady states as roots: steady solver, linearisation, stability verdict, named states, `h0` fit |
//! | [`runs`] | one run: the driver, the Newton finish and diagnosis, the leap, the landing |
//! | [`continuation`] | branches of roots in a parameter, their bifurcations and the exact phase boundaries |
//!
//! [`error`] holds the crate's one error type.
//!
//! # The path of one run
//!
//! [`contract::settings::SolverSettings`] and [`model::params::ModelParams`] are checked
//! ([`contract::limits`]), [`runs::driver::Run::new`] builds the scheme of
//! [`stepping`] from an [`model::initial::InitialCondition`], [`runs::driver::Run::execute`]
//! steps it while the stop rules of [`contract::stop_rule`] and the Newton finish of
//! [`runs::finish`] watch it; a run that settles is checked by [`roots::verdict`] and classed by
//! [`model::classify`]; one that does not is diagnosed (unsettled, with the state it heads
//! to). The answer is a [`contract::outcome::RunOutcome`].
pub mod continuation;
pub mod contract;
pub mod error;
pub mod model;
pub mod numerics;
pub mod reduced;
pub mod roots;
pub mod runs;
pub mod stepping;

use contract::settings::ModelKind;

/// Version of the solver's numerics (the PDE model's runs); part of every run's cache key.
/// 2: the Newton finish compares a run's orientation with its root's like with like, so a run
/// slowing down onto a resting ID ends there instead of creeping on (some to `t_max`).
/// 3: an unfinished run's diagnosis calls its speed and deformation settled (it only turns)
/// only if they are within the class threshold of its root's, with its class.
/// 4: only a run that ends on a stable root has a class (`unsettled`, `heading` for the
/// rest); slow runs end where their one-dimensional quasi-steady flow lands
/// ([`runs::landing`]); the rotation mode is only looked for at states away from the disk
/// (`roots::verdict::ROTATION_MIN_NORM`) and among near-neutral eigenvalues.
/// 5: no landing on a root unstable in its rotation mode (the run's turn decides between
/// competing orientations); a turn may end on a root of another class within the box's
/// anisotropy (MD on one mirror line, MC on the other).
/// 6: an adaptive run not yet on a stable state at 4 `t_max` runs on to 64 `t_max` (runs that
/// end before 4 `t_max` are unchanged).
/// 7: the landing waits while the run's lean from its mirror line grows (a run turning away
/// from the line may end on another orientation than the flow's).
/// 8: the orientation's slow flow decides where a leaning run ends (`orientation_flow`, on:
/// a root stable in rotation only if the flow turns the run back there; from a root unstable
/// in rotation, the flow's first stable zero the way the run turns); off gives numerics 7.
/// 9: with the flow, a landing from a departure (the run far from the root's family, its
/// lean shrinking) does not end by a turn from a root unstable in rotation: the lean it
/// arrives with is not known yet, and the run steps on.
/// 10: the same decisions at half the steady field solves: the Newton finish solves near a
/// root it found before by the chord method with that root's Jacobian, remembers what
/// Newton found from a root turned by each angle of the turn search, and keeps the
/// landing's walks for its later tries; the landing's zero is located by Illinois instead of
/// bisection and its shape solves start with the last derivative (roots equal to about
/// 1e-10 in `v` and `s`; results/map-profile).
/// 11: a turned root (the flow's or the turn search's, from a root unstable in rotation) ends
/// no run turning away from it since the last try (`runs::finish`): (0.089, 0.1075) from i,
/// still gaining speed and turning up to the MD at 18.0 degrees where pure stepping ends, had
/// ended on the one at 1.7 degrees; 1 of the Fig. 2a map's 7488 stepped runs
/// (results/fig2a-map-certify).
/// 12: projective steps along slow phases (setting `projective_steps`, [`runs::projection`]):
/// once 8 steps at one size show the fast parts decayed, the chord of the last step is
/// continued over up to 20 steps' time, its error kept below `tol` and every unknown's slope
/// changing by at most a tenth; the whole Fig. 2a map has every label and 9231 of its 9232
/// runs as before, with half the steps (results/fig2a-map-projective).
pub const SOLVER_VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "+numerics-12");

/// Version of the reduced ODE model's numerics (2: unstable states no longer end a run;
/// 3: a run that does not end steady has no class).
pub const ODE_SOLVER_VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "+numerics-1+ode-3");

/// Version of the time stepping of the general model with shape modes `2..K`, `K > 2`
/// (`stepping::comoving_etd`) on top of [`SOLVER_VERSION`]; 2: the field's advection and source
/// explicit over a step, as in the production scheme's predictor (same fixed points); 3:
/// ETD2RK with its error estimate on the 2-mode runs' clock, adaptive steps under `tol` and
/// `dt_max` by default (was exponential Euler at fixed steps `dt`), run on as 2-mode runs; 4:
/// the 2-mode runs' Newton finish (its orientation check, turn search and diagnosis) and
/// verdict (`roots::verdict::assess`) at every `K`; 5: a real eigenvalue is real (its
/// imaginary part of round-off dropped), so the verdict finds the rotation mode at every `K`,
/// a run to turn from a root unstable only in rotation ends once it has settled on that root
/// (before, only once within the box's anisotropy of the turned one), the landing walks
/// the families of every `K` (a leaning run held by a root stable in rotation only within
/// 0.05 degrees of its line), and the finish is tried once the rates across the rotation are
/// below its trigger (a turning run then ends only on a turned root); 6: a run caught turning
/// between two mirror lines lands on the line's root stable in rotation only if it turns
/// towards it (modes 2..3, N = 192, (0.085, 0.112) from iv turned away from it to a root of
/// the lattice, and had landed 42.75 degrees from where stepping ends). 7: the time step's
/// predictor droplet is extrapolated from the last two states' (sampled and transformed once
/// per step, not twice), as the 2-mode scheme's is: the same fixed points, transients changed
/// at `O(h^2)`; at K = 2 the general step now equals the fast path's to round-off. 8: the
/// Newton finish solves by the chord method with the Jacobians kept at earlier roots, as
/// 2-mode runs do, and forms a Jacobian by forward differences (2K field solves, not 4K), a
/// droplet's source sampled once for both velocity columns: the same roots to about 1e-9.
/// 9: a run whose boundary `f(theta)` reaches the centre ends `diverged` (it had only the
/// 2-mode rule `s >= 1`): at K = 6 the resting droplet at (0.084, 0.1) from iii stretches
/// (a2, a4, a6 growing together; a4 = -0.9 and b6 = 17 by t = 10) and had gone on stepping
/// at ever smaller steps; runs that never leave the model are unchanged to the last digit.
/// 10: two slow tails of the 4-mode map cut, each run on the state it reached before:
/// the landing ends a run on the resting disk although the box holds its mode 4 at an
/// amplitude of its own (a4 = -2.8e-5 at (0.0765, 0.16425): the disk was taken to have an
/// orientation, and such runs crept to the Newton finish for 7000 time units); the turn
/// search takes a stable root it finds past the next mirror line as its mirror image in that
/// line (the run from ii at (0.076, 0.14175) turns from the x-axis MD to the root 5 degrees
/// short of the diagonal, which it had reached by the paper's test at t = 101 884).
/// 11: a run is tried for the resting disk alone once its rates are below the 2-mode runs'
/// trigger (1e-3, its own is 1e-4 for the orientation of the other roots), by Newton and by
/// the landing's slow flow (`runs::early_try`): runs near the onset of motion that
/// crept onto the disk, or past the MD fold's ghost, for 1000-1800 time units end on the
/// same disk by t = 20-110 ((0.0785, 0.12775) from ii: t = 1136 -> 62).
/// 12: a run leaning from a root stable in rotation ends there once its speed and shape are
/// within the settling bound of the state of the root's family at the run's own orientation
/// (the box's anisotropy moves them by `O(lean^2)` from the root's) and the orientation's
/// flow, sampled from the root out to the run, points back all the way
/// (`runs::turning`, `settled_beside`): (0.07625, 0.14425) from iv, turning back to the
/// x-axis MD at a rate of 5.7e-5, ended by the paper's test at t = 20 869 and now by Newton
/// at t = 2801, on the same root.
/// 13: the landing ends a run leaving a saddle on a mirror line on the stable root its slow
/// flow takes it to although the run leans beyond the linear lean, when the orientation's
/// flow on that root's family points back at every sample from the root out to the run's
/// lean (`runs::turning`, `arrives_turning_back`); every scan of a K-mode flow samples at
/// most 0.05 degree apart (roots of the lattice lie 0.2 to 0.5 degree off the lines) out to
/// 5 degrees (a lean beyond licenses nothing), a sample where the fast balances fail
/// counting as pointing outward: four runs of the
/// 4-mode map leaving the diagonal ID at (0.08725, 0.115) and (0.08975, 0.11275) end on the
/// diagonal's slow MD at t = 725-850 instead of 25 800-47 100, on the same state.
/// 14: the early try (`runs::early_try`, from the 2-mode runs' trigger) also ends a run on a
/// root with an orientation, stable in every mode, when the run has settled on it, is not
/// turning and leans from it by at most one degree: within 0.05 degree, or turning towards
/// it on the root's family with the orientation's flow pointing back at every sample out to
/// the run (the Fig. 1c run from ii, modes 2..4, 0.17 degree off the x-axis MD: t = 71 -> 42);
/// and the landing of a run leaving the resting disk samples the orientation's flow out to 8
/// degrees instead of 5 (`runs::rotation_flow::DEPARTURE_REACH`): the disk has no
/// orientation for the lattice to hold, and the paper's initial conditions leave it 5.71
/// degrees off the axes ((0.07625, 0.13725) from iv, modes 2..4: t = 1965 -> 19, the same
/// root). 200 runs of the 4-mode map: 0.85x the run time, every run on its map's state.
/// 15: the early try from three times the 2-mode runs' rate (`runs::early_try::EARLY_FACTOR`
/// 30, was 10; a landing that finds the slow flow going elsewhere than the disk leaves one
/// more try below 10), no Newton solve at an early try while the run, beside the root the
/// last one found in speed and shape, leans more than a degree from it, and two roots one
/// state when they agree to 1e-6 (was 1e-9: Newton fixes a K-mode root along its slow
/// rotation only to 1e-8, and its verdict was computed again): the Fig. 1c run from ii,
/// modes 2..4, t = 41.9 -> 27.4; two samples of the 4-mode map (150 and 200 runs): 0.948x
/// and 0.965x the run time, every run on the same state.
/// 16: the general step's predictor takes the field's gradient on its droplet from the last
/// two accepted states (`stepping::comoving_etd::predictor`, `cur + beta (cur - prev)`,
/// `beta = h / h_last`) instead of transforming its own field's back: three transforms a
/// step instead of five, second order still, the fixed points unchanged, and the error of a
/// transient at Fig. 1c (modes 2..4, fixed steps) 28 to 64 times smaller; K-mode Newton halves
/// a step that more than doubles the residual (`NewtonOptions::backtrack`: from a run 0.18 degree off
/// the x-axis MD it had stepped 10 degrees along the MD's family and failed); and the turn
/// search from a root of the lattice between two mirror lines reflects a root found past
/// the next line in that line, not in the one 45 degrees on (modes 2..3, N = 192, (0.085,
/// 0.112) from iv: 137.25 -> 132.75 degrees, where pure stepping ends).
/// 17: projective steps along slow phases, as numerics 12 of the 2-mode runs.
pub const MODES_SOLVER_VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "+numerics-9+modes-17");

/// The numerics version of a model's runs with shape modes `2..=modes`, part of their cache
/// key: a change to one model's results invalidates its stored runs only.
pub fn solver_version(model: ModelKind, modes: usize) -> &'static str {
    match model {
        ModelKind::Pde if modes > 2 => MODES_SOLVER_VERSION,
        ModelKind::Pde => SOLVER_VERSION,
        ModelKind::Ode => ODE_SOLVER_VERSION,
    }
}
