//! Where a slow run lands: the one-dimensional quasi-steady flow (docs/model.md, "Where a slow run lands").
//!
//! Runs are slow only beside a bifurcation, and there only one direction is slow: the field
//! relaxes at rate >= 1, the shape at about `|kappa2 - G'| / eta2`, while the drift (or
//! deformation) mode crossing zero has a rate of 1e-3 or less. After a short transient the
//! run moves along a one-dimensional family of quasi-steady states, and where it lands is
//! decided by a scalar function of the family's coordinate, not by thousands of time units.
//!
//! Speed family (a moving run): on a mirror line of the box (x axis, or the diagonal; the
//! run's direction of motion turned onto the nearest one), fix the speed `v`, take the
//! co-moving steady field at that speed (exact, [`Balances`]), solve only the shape
//! balances `G_k(v, c) = kappa_k c_k` for the shape amplitudes `c*(v) = (a_2..a_K)*(v)` on
//! the line (mirror-symmetric about it: in the line's frame `b_k = 0`), and evaluate what is
//! left of the velocity balance,
//!
//! `g(v) = F(v, c*(v)) - eta_t v`    (the paper's eq. 36 at steady field and shape).
//!
//! Its zeros are the steady states on the line (the resting state at `v = 0`, where `F = 0`
//! by symmetry, and the moving roots); between two zeros its sign is the direction in which a
//! run on the family drifts (`m dv/dt = g`). So a run on the family with speed `v_run` lands
//! on the next zero of `g` in the direction of `sign g(v_run)`, or on the resting state if
//! `g < 0` all the way down to `v = 0`.
//!
//! Shape family (a resting run): with `v = 0` the velocity balance holds by symmetry, and
//! `h(c) = G_2(0, c) - kappa2 c` (paper eq. 38) plays the part of `g`, with `c >= 0` the
//! mode-2 deformation along the line's long axis (the disk, `c = 0`, is always a zero) and
//! the modes `3..K` solved from their own balances at each `c` (the odd ones vanish at rest by
//! the point symmetry).
//!
//! The certificate that a run's future is decided ([`land`]): its fast residual is small
//! (every shape amplitude within [`FAMILY_TOL`] of `c*(v_run)`'s), the walk along the family from the run
//! to the landing root finds no zero in between (steps of at most [`MAX_STEP`], and at most
//! half the distance to the zero that the local slope of `g` points at, so a dip of `g`
//! towards zero is resolved before it can be stepped over), and the caller confirms that the
//! landing root is a root of all `2K` force-balance equations and is stable
//! ([`crate::runs::finish`]).
//!
//! Limits: where two modes are slow at once (where the moving branch's fold meets the onset
//! of motion, and where the ID and MD onsets meet) the family is two-dimensional and the
//! scalar flow does not decide; the landing root's stability check then usually refuses it,
//! and the run goes on by time stepping. The run's orientation is a slow coordinate too: the
//! walk holds the run's lean from its line fixed, so the caller lands only runs whose lean does
//! not grow on the way, and confirms the flow's root on its line ([`Landing::on_line`]),
//! letting the run turn from there if that root is unstable in rotation
//! ([`crate::runs::finish`], numerics 7).
//!
//! Every `K` walks the same families through [`Balances`] (for `K = 2` its fast path, the
//! same arithmetic as before the general model had a landing).
use crate::model::mirror::MirrorLine;
use crate::model::state::turned;
use crate::numerics::bracket::illinois;
use crate::roots::balances::Balances;
use crate::runs::walks::Walk;
pub use crate::runs::walks::{Coordinate, Walks};
use std::f64::consts::FRAC_PI_4;

/// Largest distance of a run's shape amplitudes from the family's, `max_k |c_run - c*(v_run)|`,
/// for the run to be on the family (its fast parts relaxed).
pub const FAMILY_TOL: f64 = 2e-3;

/// Largest step of the walk along the family (in `v` or `c`).
pub const MAX_STEP: f64 = 0.01;

/// Smallest step of the walk: a dip of `g` narrower than this is not resolved.
pub const MIN_STEP: f64 = 1e-5;

/// The largest speed (or deformation) the walk goes to before giving up.
pub const MAX_COORDINATE: f64 = 2.0;

/// A resting run (speed at most this) is placed on the shape family.
pub const RESTING_SPEED: f64 = 1e-4;

/// Where the run lands, and how it was found.
#[derive(Debug, Clone, PartialEq)]
pub struct Landing {
    /// The landing root `(vx, vy, a_2..a_K, b_2..b_K)` in the run's own orientation (on the
    /// mirror line nearest the run, turned by the run's lean from it).
    pub z: Vec<f64>,
    /// The same root on the mirror line the flow walked, before the run's lean.
    pub on_line: Vec<f64>,
    pub coordinate: Coordinate,
    /// The run's coordinate, and the landing root's.
    pub from: f64,
    pub to: f64,
    /// Samples of the scalar flow taken by the walk.
    pub samples: usize,
}

/// The two mirror lines next to a run's orientation (direction of motion, or long axis at
/// rest), the nearest first: each line, the box rotation `psi` (a multiple of 90 degrees)
/// that brings the run next to it, and the run's lean from it. A run caught turning between
/// the lines may be on the family of either (the box's anisotropy makes them differ).
fn lines_near(orientation: f64) -> [(MirrorLine, f64, f64); 2] {
    let nearest = (orientation / FRAC_PI_4).round();
    let other = nearest
        + if orientation >= nearest * FRAC_PI_4 {
            1.0
        } else {
            -1.0
        };
    [nearest, other].map(|n| {
        let (axis, base) = if (n as i64).rem_euclid(2) == 0 {
            (MirrorLine::X, 0.0)
        } else {
            (MirrorLine::Diagonal, FRAC_PI_4)
        };
        (axis, n * FRAC_PI_4 - base, orientation - n * FRAC_PI_4)
    })
}

/// The shape balances `r` (the line's `a_k`, from index `from` of [`Balances::residual_on`])
/// in the amplitudes `c` (`c[..from - 1]` held): `c` moved by `dc` where needed.
type Shape<'b> = &'b mut dyn FnMut(&[f64]) -> Vec<f64>;

/// Newton's step `-J^(-1) r` (for one unknown `-r / J`), or `None` if `J` is singular.
fn newton_step(j: &[Vec<f64>], r: &[f64]) -> Option<Vec<f64>> {
    if r.len() == 1 {
        return Some(vec![-r[0] / j[0][0]]);
    }
    let m = nalgebra::DMatrix::from_fn(r.len(), r.len(), |i, k| j[i][k]);
    let b = nalgebra::DVector::from_iterator(r.len(), r.iter().map(|x| -x));
    m.lu().solve(&b).map(|x| x.iter().copied().collect())
}

/// The largest `|x_i|`.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The scalar flows of one mirror line.
pub struct SlowFlow<'a> {
    balances: &'a mut Balances,
    axis: MirrorLine,
    /// Samples taken.
    pub samples: usize,
    /// The shape balances' Jacobian in the shape amplitudes at the last sample: the next
    /// sample's Newton steps start with it (it changes little between samples).
    slope: Option<Vec<Vec<f64>>>,
    /// At rest, the amplitudes of the modes `3..K` at the last sample (the next one's start).
    higher: Vec<f64>,
}

impl<'a> SlowFlow<'a> {
    pub fn new(balances: &'a mut Balances, axis: MirrorLine) -> Self {
        let higher = vec![0.0; balances.modes() - 2];
        Self {
            balances,
            axis,
            samples: 0,
            slope: None,
            higher,
        }
    }

    /// The family's shape amplitudes `c*(v) = (a_2..a_K)` on the line at speed `v` (the shape
    /// balances solved from `c0` by Newton steps with the Jacobian of the last sample, taken
    /// again by central differences whenever a step does not shrink the residual tenfold),
    /// or `None` if they do not converge.
    pub fn shape_at(&mut self, v: f64, c0: &[f64]) -> Option<Vec<f64>> {
        let (balances, axis) = (&mut *self.balances, self.axis);
        let mut shape = |c: &[f64]| balances.residual_on(axis, v, c)[1..].to_vec();
        Self::solve(&mut shape, &mut self.slope, c0)
    }

    /// Newton on `shape(c) = 0` from `c0` with the kept Jacobian `slope` ([`Self::shape_at`]).
    fn solve(shape: Shape<'_>, slope: &mut Option<Vec<Vec<f64>>>, c0: &[f64]) -> Option<Vec<f64>> {
        let h = 1e-7;
        let mut c = c0.to_vec();
        let mut before = f64::INFINITY;
        for _ in 0..60 {
            let r = shape(&c);
            if max_abs(&r) < 1e-13 {
                return Some(c);
            }
            let d = match slope.take() {
                Some(d) if max_abs(&r) <= 0.1 * before => d,
                _ => {
                    let mut d = vec![vec![0.0; c.len()]; c.len()];
                    for k in 0..c.len() {
                        let (mut up, mut down) = (c.clone(), c.clone());
                        up[k] += h;
                        down[k] -= h;
                        let (ru, rd) = (shape(&up), shape(&down));
                        for (row, (u, l)) in d.iter_mut().zip(ru.iter().zip(&rd)) {
                            row[k] = (u - l) / (2.0 * h);
                        }
                    }
                    d
                }
            };
            before = max_abs(&r);
            let step = newton_step(&d, &r);
            *slope = Some(d);
            let Some(step) = step.filter(|s| s.iter().all(|x| x.is_finite())) else {
                *slope = None;
                return None;
            };
            for (x, dx) in c.iter_mut().zip(&step) {
                *x += dx.clamp(-0.005, 0.005);
            }
            if max_abs(&step) < 1e-14 {
                return Some(c);
            }
        }
        None
    }

    /// `g(v)` on the speed family, and `c*(v)` (Newton from `c0`).
    pub fn drift(&mut self, v: f64, c0: &[f64]) -> Option<(f64, Vec<f64>)> {
        self.samples += 1;
        let c = self.shape_at(v, c0)?;
        Some((self.balances.residual_on(self.axis, v, &c)[0], c))
    }

    /// `h(c)` on the shape family at rest (the modes `3..K` solved at `c`; `NaN` where they
    /// do not converge), and the shape `(c, a_3..a_K)`.
    pub fn shape_drive(&mut self, c: f64) -> (f64, Vec<f64>) {
        self.samples += 1;
        let (balances, axis) = (&mut *self.balances, self.axis);
        let at = |higher: &[f64]| -> Vec<f64> {
            std::iter::once(c).chain(higher.iter().copied()).collect()
        };
        let shape: Vec<f64> = if self.higher.is_empty() {
            vec![c]
        } else {
            let mut higher = |y: &[f64]| balances.residual_on(axis, 0.0, &at(y))[2..].to_vec();
            let mut slope = None;
            match Self::solve(&mut higher, &mut slope, &self.higher) {
                Some(y) => {
                    self.higher.clone_from(&y);
                    at(&y)
                }
                None => return (f64::NAN, at(&self.higher)),
            }
        };
        (balances.residual_on(axis, 0.0, &shape)[1], shape)
    }
}

/// The next step of a walk from `x` with value `f` (the previous sample `prev`): at most
/// [`MAX_STEP`], at most half the distance to the zero the secant points at.
fn step_size(x: f64, f: f64, prev: Option<(f64, f64)>) -> f64 {
    let mut step = MAX_STEP;
    if let Some((xp, fp)) = prev {
        let slope = (f - fp) / (x - xp);
        let to_zero = -f / slope;
        // Only a zero ahead (same direction as the walk) limits the step.
        if to_zero.is_finite() && to_zero * (x - xp) > 0.0 {
            step = step.min(0.5 * to_zero.abs());
        }
    }
    step.max(MIN_STEP)
}

/// Where a run at `z = (vx, vy, a_2..a_K, b_2..b_K)` may land, the likelier first: along the speed
/// family if it moves at all, along the shape family if it is nearly at rest (speed at most
/// [`RESTING_SPEED`]: a resting deformed droplet whose drift grows slowly leaves along the
/// speed family; one whose drift decays stays on the shape family). Each is a landing the
/// walk found (see the module's certificate); the caller takes the first whose root it
/// confirms stable.
pub fn landings(balances: &mut Balances, z: &[f64], walks: &mut Walks) -> Vec<Landing> {
    let speed = z[0].hypot(z[1]);
    let moving = (speed > 0.0)
        .then(|| land_moving(balances, z, walks))
        .flatten();
    let resting = (speed <= RESTING_SPEED)
        .then(|| land_resting(balances, z, walks))
        .flatten();
    moving.into_iter().chain(resting).collect()
}

/// The first of [`landings`] (no walks kept).
pub fn land(solver: &mut Balances, z: &[f64]) -> Option<Landing> {
    landings(solver, z, &mut Walks::default())
        .into_iter()
        .next()
}

fn land_moving(balances: &mut Balances, z: &[f64], walks: &mut Walks) -> Option<Landing> {
    let [near, other] = lines_near(z[1].atan2(z[0]));
    land_moving_on(balances, z, near, walks).or_else(|| land_moving_on(balances, z, other, walks))
}

/// [`land_moving`] on one mirror line (`(axis, psi, lean)` of [`lines_near`]).
fn land_moving_on(
    balances: &mut Balances,
    z: &[f64],
    (axis, psi, lean): (MirrorLine, f64, f64),
    walks: &mut Walks,
) -> Option<Landing> {
    let here = turned(z, -psi);
    let v_run = z[0].hypot(z[1]);
    // The run's shape amplitudes on the line, turned back by its lean.
    let c_run = balances.shape_on(axis, &turned(&here, -lean));
    let mut flow = SlowFlow::new(balances, axis);
    let (g_run, c_fam) = flow.drift(v_run, &c_run)?;
    let off = c_fam.iter().zip(&c_run).map(|(f, r)| (f - r).abs());
    if off.fold(0.0f64, f64::max) > FAMILY_TOL || g_run == 0.0 {
        return None;
    }
    let dir = g_run.signum();
    let (to, c_to) = match walks.passed(axis, Coordinate::Speed, dir, v_run) {
        Some(known) => known,
        None => {
            let (to, c_to) = walk_speed(&mut flow, (v_run, g_run, c_fam))?;
            walks.keep(Walk {
                axis,
                coordinate: Coordinate::Speed,
                dir,
                from: v_run,
                to,
                c_to: c_to.clone(),
            });
            (to, c_to)
        }
    };
    let samples = flow.samples;
    let line_root = balances.on_mirror(axis, to, &c_to);
    Some(Landing {
        z: turned(&turned(&line_root, lean), psi),
        on_line: turned(&line_root, psi),
        coordinate: Coordinate::Speed,
        from: v_run,
        to,
        samples,
    })
}

/// The walk along the speed family from the run's sample `(v, g, c)`, the way `g` points, to
/// the next zero of `g` (see the module's certificate): the zero and the family's shape there.
fn walk_speed(
    flow: &mut SlowFlow<'_>,
    (v_run, g_run, c_fam): (f64, f64, Vec<f64>),
) -> Option<(f64, Vec<f64>)> {
    let dir = g_run.signum();
    let (mut v, mut g, mut c) = (v_run, g_run, c_fam);
    let mut prev: Option<(f64, f64)> = None;
    let (to, c_to) = loop {
        let mut next = v + dir * step_size(v, g, prev);
        if next <= 0.0 {
            // Down to rest: the resting state on the line is the landing root.
            next = 0.0;
        }
        if next > MAX_COORDINATE {
            return None;
        }
        let (gn, cn) = flow.drift(next, &c)?;
        if next == 0.0 {
            // g(0) = 0 by symmetry (a sample there is round-off): the resting state.
            break (0.0, cn);
        }
        if gn == 0.0 || gn.signum() != dir {
            // A zero in (v, next]: bisection on the bracket, the shape tracked.
            break bisect(flow, (v, g, c), (next, gn, cn))?;
        }
        prev = Some((v, g));
        (v, g, c) = (next, gn, cn);
    };
    Some((to, c_to))
}

/// A zero of `g` between two samples `(v, g, c)` of opposite sign (or a zero sample), to
/// 1e-10 in `v` (Illinois, the shape tracked from sample to sample): the zero and the
/// family's shape there.
fn bisect(
    flow: &mut SlowFlow<'_>,
    a: (f64, f64, Vec<f64>),
    b: (f64, f64, Vec<f64>),
) -> Option<(f64, Vec<f64>)> {
    if b.1 == 0.0 {
        return Some((b.0, b.2));
    }
    let (lo, hi) = ((a.0, a.1), (b.0, b.1));
    let mut sampled = vec![(a.0, a.2), (b.0, b.2)];
    let mut drift = |v: f64| {
        let guess = sampled.last().expect("two samples").1.clone();
        match flow.drift(v, &guess) {
            Some((g, c)) => {
                sampled.push((v, c));
                g
            }
            None => f64::NAN,
        }
    };
    let zero = illinois(&mut drift, lo, hi, 1e-10)?;
    let (_, c) = sampled.into_iter().rev().find(|(v, _)| *v == zero)?;
    Some((zero, c))
}

fn land_resting(balances: &mut Balances, z: &[f64], walks: &mut Walks) -> Option<Landing> {
    // Mode 2's amplitudes (a2, b2).
    let (a2, b2) = (z[2], z[z.len() / 2 + 1]);
    let s_run = a2.hypot(b2);
    if s_run == 0.0 {
        return None;
    }
    let [near, other] = lines_near(0.5 * b2.atan2(a2));
    land_resting_on(balances, s_run, near, walks)
        .or_else(|| land_resting_on(balances, s_run, other, walks))
}

/// [`land_resting`] on one mirror line (`(axis, psi, lean)` of [`lines_near`]): the
/// deformation is the family's coordinate itself, so a resting run is on it.
fn land_resting_on(
    balances: &mut Balances,
    s_run: f64,
    (axis, psi, lean): (MirrorLine, f64, f64),
    walks: &mut Walks,
) -> Option<Landing> {
    let mut flow = SlowFlow::new(balances, axis);
    let (h_run, _) = flow.shape_drive(s_run);
    if h_run == 0.0 || !h_run.is_finite() {
        return None;
    }
    let dir = h_run.signum();
    let (to, c_to) = match walks.passed(axis, Coordinate::Shape, dir, s_run) {
        Some(known) => known,
        None => {
            let (to, c_to) = walk_shape(&mut flow, (s_run, h_run))?;
            walks.keep(Walk {
                axis,
                coordinate: Coordinate::Shape,
                dir,
                from: s_run,
                to,
                c_to: c_to.clone(),
            });
            (to, c_to)
        }
    };
    let samples = flow.samples;
    let line_root = balances.on_mirror(axis, 0.0, &c_to);
    Some(Landing {
        z: turned(&turned(&line_root, lean), psi),
        on_line: turned(&line_root, psi),
        coordinate: Coordinate::Shape,
        from: s_run,
        to,
        samples,
    })
}

/// The walk along the shape family at rest from the run's sample `(c, h)`, the way `h`
/// points, to the next zero of `h`: the zero and the family's shape there `(c, a_3..a_K)`.
fn walk_shape(flow: &mut SlowFlow<'_>, (s_run, h_run): (f64, f64)) -> Option<(f64, Vec<f64>)> {
    let dir = h_run.signum();
    let (mut c, mut h) = (s_run, h_run);
    let mut prev: Option<(f64, f64)> = None;
    let to = loop {
        let next = (c + dir * step_size(c, h, prev)).max(0.0);
        if next > MAX_COORDINATE.min(1.0) {
            return None;
        }
        if next == 0.0 {
            break 0.0;
        }
        let (hn, _) = flow.shape_drive(next);
        if !hn.is_finite() {
            return None;
        }
        if hn == 0.0 {
            break next;
        }
        if hn.signum() != dir {
            // The zero in (c, next], to 1e-10 (Illinois).
            break illinois(&mut |x| flow.shape_drive(x).0, (c, h), (next, hn), 1e-10)?;
        }
        prev = Some((c, h));
        (c, h) = (next, hn);
    };
    // The family's shape at the zero (the modes 3..K solved there; none at the disk).
    let shape = if to == 0.0 || flow.higher.is_empty() {
        std::iter::once(to)
            .chain(flow.higher.iter().map(|_| 0.0))
            .collect()
    } else {
        flow.shape_drive(to).1
    };
    Some((to, shape))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;

    fn solver(eta_t: f64, kappa2: f64) -> Balances {
        Balances::new(ModelParams::at(eta_t, kappa2), 192).unwrap()
    }

    #[test]
    fn the_speed_family_matches_the_design_notes() {
        // Design notes Sect. 7 (independent numpy prototype, N = 192): at (0.0763, 0.16)
        // g > 0 below v ~ 0.29 (max +2.2e-5 near v = 0.175); c*(v) = -0.00177, -0.00697,
        // -0.01527 at v = 0.1, 0.2, 0.3.
        let mut s = solver(0.0763, 0.16);
        let mut flow = SlowFlow::new(&mut s, MirrorLine::X);
        let (g, c) = flow.drift(0.1, &[0.0]).unwrap();
        assert!(g > 0.0 && (c[0] + 0.00177).abs() < 2e-5, "{g} {c:?}");
        let (g, c) = flow.drift(0.2, &c).unwrap();
        assert!(g > 0.0 && (c[0] + 0.00697).abs() < 2e-5, "{g} {c:?}");
        let (g175, _) = flow.drift(0.175, &c).unwrap();
        assert!((g175 - 2.2e-5).abs() < 2e-6, "{g175}");
        let (g, c) = flow.drift(0.3, &c).unwrap();
        assert!(g < 0.0 && (c[0] + 0.01527).abs() < 2e-5, "{g} {c:?}");
        // (0.0765, 0.16): g < 0 for all 0 < v <= 0.45, -1.8e-5 at v = 0.2.
        let mut s = solver(0.0765, 0.16);
        let mut flow = SlowFlow::new(&mut s, MirrorLine::X);
        let (g, _) = flow.drift(0.2, &[-0.007]).unwrap();
        assert!((g + 1.8e-5).abs() < 2e-6, "{g}");
    }

    #[test]
    fn runs_land_where_the_design_notes_say() {
        // Just below the onset of motion a slow run leaving the disk lands on MD, v = 0.2926
        // (along x; here leaning 3 degrees and moving along -y: the same root, turned).
        let mut s = solver(0.0763, 0.16);
        let turn = std::f64::consts::FRAC_PI_2 + 3f64.to_radians();
        let run = turned(&[0.05, 0.0, -0.0005, 0.0], turn);
        let l = land(&mut s, &run).unwrap();
        let (v, sd) = (l.z[0].hypot(l.z[1]), l.z[2].hypot(l.z[3]));
        assert!(
            (v - 0.2926).abs() < 5e-4 && l.coordinate == Coordinate::Speed,
            "{l:?}"
        );
        assert!(
            (l.z[1].atan2(l.z[0]) - turn).abs() < 1e-9 && sd > 0.01,
            "{l:?}"
        );
        // Just above it, a run decays to rest however fast it moves.
        let mut s = solver(0.0765, 0.16);
        let l = land(&mut s, &[0.3, 0.0, -0.0153, 0.0]).unwrap();
        assert!(l.z.iter().all(|x| x.abs() < 1e-9), "{l:?}");
        // Inside the IC/MD band the unstable MD root is the separatrix (~0.27).
        let mut s = solver(0.078, 0.13);
        let mut flow = SlowFlow::new(&mut s, MirrorLine::X);
        let (c2, c33) = (
            flow.shape_at(0.2, &[0.0]).unwrap()[0],
            flow.shape_at(0.33, &[0.0]).unwrap()[0],
        );
        let low = land(&mut s, &[0.2, 0.0, c2 + 1e-3, 0.0]).unwrap();
        assert_eq!(low.to, 0.0, "{low:?}");
        let high = land(&mut s, &[0.33, 0.0, c33, 0.0]).unwrap();
        assert!(high.to > 0.33, "{high:?}");
        // A run off the family (its shape far from c*(v)) is not placed on it.
        assert!(land(&mut s, &[0.2, 0.0, c2 + 0.01, 0.0]).is_none());
    }

    #[test]
    fn a_resting_run_lands_on_the_deformed_state_below_the_deformation_onset() {
        // (0.085, 0.112): the disk is unstable to deformation (docs/model.md reference values), a
        // slightly deformed resting run grows to the ID state; along the diagonal here.
        let mut s = solver(0.085, 0.112);
        let l = land(&mut s, &[0.0, 0.0, 0.0, 0.02]).unwrap();
        assert_eq!(l.coordinate, Coordinate::Shape);
        assert!(
            l.to > 0.05 && l.z[2].abs() < 1e-12 && l.z[3] > 0.05,
            "{l:?}"
        );
        // Above the onset the disk is stable: a deformed resting run relaxes to it.
        let mut s = solver(0.085, 0.13);
        let l = land(&mut s, &[0.0, 0.0, 0.03, 0.0]).unwrap();
        assert_eq!(l.to, 0.0, "{l:?}");
    }
}
