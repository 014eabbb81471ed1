//! The zero set of a scalar function `g(q)` on the unit square `q = (qx, qy) in [0, 1]^2` (a
//! window of two parameters, each scaled to `[0, 1]`), as curves. A curve is found where it
//! crosses one of the square's edges or its two midlines (`g` sampled along each, the sign
//! change located by [`crate::numerics::bracket::illinois`]) and followed from there both
//! ways by pseudo-arclength continuation ([`super::arclength`]) of `g(q) / |grad g(q0)| = 0`
//! (so the corrector's tolerance is a distance in `q`), until it leaves the square (its last
//! point is put on the edge), closes on itself, or `g` stops being defined (`NaN`: the state
//! `g` is evaluated on ends there). A start point within [`SAME_CURVE`] of a curve already
//! traced is that curve.
//!
//! What it cannot see: a closed curve inside the square that touches neither an edge nor a
//! midline, and two curves closer than [`SAME_CURVE`].
use crate::continuation::arclength::{point_at, start, ArclengthOptions, CurvePoint, Stepper};
use crate::continuation::polyline::distance_to_polyline;
use crate::numerics::bracket::illinois;

/// How closely a start point must lie to a traced curve to be on it (in `q`).
pub const SAME_CURVE: f64 = 1e-3;

/// Where to look for curves and how to follow them.
#[derive(Debug, Clone)]
pub struct LevelSetOptions {
    /// Samples of `g` along each edge and midline.
    pub samples: usize,
    pub arclength: ArclengthOptions,
    /// Most steps each way from a start point.
    pub max_steps: usize,
}

impl Default for LevelSetOptions {
    fn default() -> Self {
        Self {
            samples: 16,
            arclength: ArclengthOptions {
                ds: 0.01,
                ds_max: 0.04,
                tol: 1e-9,
                // Small, so that a curve ending where g stops being defined (ID meeting IC)
                // is followed to within ~1e-7 of its end.
                fd_step: 1e-7,
                max_iter: 10,
                ..ArclengthOptions::default()
            },
            max_steps: 400,
        }
    }
}

/// The six lines searched for crossings: the edges, then the midlines, each as `t -> q`.
fn search_lines() -> [fn(f64) -> (f64, f64); 6] {
    [
        |t| (t, 0.0),
        |t| (t, 1.0),
        |t| (0.0, t),
        |t| (1.0, t),
        |t| (t, 0.5),
        |t| (0.5, t),
    ]
}

/// Where `g` changes sign along the search lines (located to `1e-10` in `q`).
fn crossings(g: &mut impl FnMut(f64, f64) -> f64, samples: usize) -> Vec<(f64, f64)> {
    let m = samples.max(2);
    let mut out = Vec::new();
    for line in search_lines() {
        let mut prev: Option<(f64, f64)> = None;
        for i in 0..m {
            let t = i as f64 / (m - 1) as f64;
            let (x, y) = line(t);
            let gt = g(x, y);
            let here = gt.is_finite().then_some((t, gt));
            if let (Some((t0, g0)), Some((t1, g1))) = (prev, here) {
                if g0 * g1 <= 0.0 && !(g0 == 0.0 && i > 1) {
                    let mut along = |t: f64| {
                        let (x, y) = line(t);
                        g(x, y)
                    };
                    if let Some(t) = illinois(&mut along, (t0, g0), (t1, g1), 1e-10) {
                        out.push(line(t));
                    }
                }
            }
            prev = here;
        }
    }
    out
}

fn inside((x, y): (f64, f64)) -> bool {
    (0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y)
}

/// The point where the segment from `a` (inside) to `b` (outside) leaves the square.
fn onto_edge(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let mut t: f64 = 1.0;
    for (p, q) in [(a.0, b.0), (a.1, b.1)] {
        if q > 1.0 {
            t = t.min((1.0 - p) / (q - p));
        }
        if q < 0.0 {
            t = t.min(p / (p - q));
        }
    }
    let t = t.clamp(0.0, 1.0);
    (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
}

/// Where the curve leaves the square between `p` (inside) and the point `ds` further along
/// it, `out` (outside): the arclength at which the coordinate that left reaches its edge,
/// located by [`illinois`] on points of the curve; the chord's crossing where that fails.
fn edge_point(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    p: &CurvePoint,
    ds: f64,
    out: (f64, f64),
    opts: &ArclengthOptions,
) -> (f64, f64) {
    let chord = onto_edge((p.y[0], p.y[1]), out);
    // The coordinate that leaves first along the chord, and its edge.
    let (i, edge) = [(0, chord.0), (1, chord.1)]
        .into_iter()
        .find_map(|(i, c)| {
            let o = [out.0, out.1][i];
            (o < 0.0 && c.abs() < 1e-12)
                .then_some((i, 0.0))
                .or((o > 1.0 && (c - 1.0).abs() < 1e-12).then_some((i, 1.0)))
        })
        .unwrap_or((0, chord.0));
    let mut beyond = |s: f64| point_at(f, p, s, opts).map_or(f64::NAN, |(c, _)| c.y[i] - edge);
    let (a, b) = (p.y[i] - edge, [out.0, out.1][i] - edge);
    match illinois(&mut beyond, (0.0, a), (ds, b), 1e-12) {
        Some(s) => match point_at(f, p, s, opts) {
            Some((c, _)) => {
                let mut q = [c.y[0], c.y[1]];
                q[i] = edge;
                (q[0], q[1])
            }
            None => chord,
        },
        None => chord,
    }
}

/// One way along the curve from `p0`; whether it closed on itself.
fn walk(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    p0: &CurvePoint,
    opts: &LevelSetOptions,
) -> (Vec<(f64, f64)>, bool) {
    let at = |p: &CurvePoint| (p.y[0], p.y[1]);
    let mut stepper = Stepper::new(opts.arclength.clone());
    let mut p = p0.clone();
    let mut pts = vec![at(&p)];
    let mut length = 0.0;
    for _ in 0..opts.max_steps {
        let Some(step) = stepper.advance(f, &p) else {
            break;
        };
        let q = at(&step.point);
        if !inside(q) {
            pts.push(edge_point(f, &p, step.ds, q, &opts.arclength));
            return (pts, false);
        }
        length += step.ds;
        let home = at(p0);
        if length > 4.0 * opts.arclength.ds_max
            && (q.0 - home.0).hypot(q.1 - home.1) < stepper.ds.max(step.ds)
        {
            pts.push(q);
            pts.push(home);
            return (pts, true);
        }
        pts.push(q);
        p = step.point;
    }
    (pts, false)
}

/// The zero set of `g` on the unit square (see the module doc), each curve from one end to
/// the other.
pub fn zero_set(
    g: &mut impl FnMut(f64, f64) -> f64,
    opts: &LevelSetOptions,
) -> Vec<Vec<(f64, f64)>> {
    let starts = crossings(g, opts.samples);
    let mut curves: Vec<Vec<(f64, f64)>> = Vec::new();
    let h = opts.arclength.fd_step;
    for q0 in starts {
        if curves
            .iter()
            .any(|c| distance_to_polyline(q0, c) < SAME_CURVE)
        {
            continue;
        }
        // Scale g to a distance: its gradient at the start.
        let gx = (g(q0.0 + h, q0.1) - g(q0.0 - h, q0.1)) / (2.0 * h);
        let gy = (g(q0.0, q0.1 + h) - g(q0.0, q0.1 - h)) / (2.0 * h);
        let scale = gx.hypot(gy);
        if !(scale.is_finite() && scale > 0.0) {
            continue;
        }
        let mut f = |y: &[f64]| vec![g(y[0], y[1]) / scale];
        let mut halves: Vec<Vec<(f64, f64)>> = Vec::new();
        for sign in [-1.0, 1.0] {
            let prev = [-gy * sign, gx * sign];
            let Some(p0) = start(&mut f, &[q0.0, q0.1], &prev, &opts.arclength) else {
                continue;
            };
            let (pts, closed) = walk(&mut f, &p0, opts);
            halves.push(pts);
            if closed {
                break;
            }
        }
        let mut curve: Vec<(f64, f64)> = Vec::new();
        if let Some(back) = halves.first() {
            curve.extend(back.iter().rev());
        }
        if let Some(fwd) = halves.get(1) {
            curve.extend(fwd.iter().skip(1));
        }
        curve.dedup_by(|a, b| (a.0 - b.0).hypot(a.1 - b.1) < 1e-12);
        if curve.len() > 1 {
            curves.push(curve);
        }
    }
    curves
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circle crossing two edges (an arc) and an ellipse inside crossing the midlines (a
    /// closed curve): both found, once each, every point on its curve.
    #[test]
    fn finds_an_arc_and_a_closed_curve_once_each() {
        let arc = |x: f64, y: f64| x * x + y * y - 0.3f64.powi(2);
        let ellipse = |x: f64, y: f64| ((x - 0.6) / 0.2).powi(2) + ((y - 0.55) / 0.3).powi(2) - 1.0;
        let mut calls = 0;
        let mut g = |x: f64, y: f64| {
            calls += 1;
            arc(x, y) * ellipse(x, y)
        };
        let curves = zero_set(&mut g, &LevelSetOptions::default());
        assert_eq!(curves.len(), 2, "{curves:?}");
        let on = |c: &Vec<(f64, f64)>, f: &dyn Fn(f64, f64) -> f64| {
            c.iter().all(|&(x, y)| f(x, y).abs() < 1e-6)
        };
        let arc_curve = curves.iter().find(|c| on(c, &arc)).expect("the arc");
        let loop_curve = curves
            .iter()
            .find(|c| on(c, &ellipse))
            .expect("the ellipse");
        // The arc runs from one edge to the other; the ellipse closes.
        let (a, b) = (arc_curve[0], *arc_curve.last().unwrap());
        assert!(a.0.min(a.1) < 1e-12 && b.0.min(b.1) < 1e-12, "{a:?} {b:?}");
        assert!((a.0 - b.0).abs() > 0.29, "{a:?} {b:?}");
        assert_eq!(loop_curve.first(), loop_curve.last());
        // Its length is the ellipse's perimeter (Ramanujan), to the chords' error.
        let len: f64 = loop_curve
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
            .sum();
        let (p, q) = (0.3f64, 0.2f64);
        let h = ((p - q) / (p + q)).powi(2);
        let perimeter =
            std::f64::consts::PI * (p + q) * (1.0 + 3.0 * h / (10.0 + (4.0 - 3.0 * h).sqrt()));
        assert!(
            (len - perimeter).abs() < 2e-3 * perimeter,
            "{len} {perimeter}"
        );
        assert!(calls < 20_000, "{calls}");
    }

    /// A function undefined beyond `x = 0.7` (a state that ends there): its line ends there.
    #[test]
    fn a_curve_ends_where_g_is_undefined() {
        let mut g = |x: f64, y: f64| if x > 0.7 { f64::NAN } else { y - 0.4 - 0.1 * x };
        let curves = zero_set(&mut g, &LevelSetOptions::default());
        assert_eq!(curves.len(), 1, "{curves:?}");
        let c = &curves[0];
        let (lo, hi) = c
            .iter()
            .fold((1.0f64, 0.0f64), |(l, h), p| (l.min(p.0), h.max(p.0)));
        assert!(lo == 0.0 && hi > 0.69 && hi <= 0.7, "{lo} {hi}");
        assert!(c.iter().all(|&(x, y)| (y - 0.4 - 0.1 * x).abs() < 1e-9));
    }
}
