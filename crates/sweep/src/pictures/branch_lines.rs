//! Sampled steady states along a parameter line, joined into drawable branches: at each
//! sample the states of one family are matched to the nearest states of the previous sample
//! (greedy, in `(v, s)` scaled by their ranges), and a track is cut where its stability
//! changes, so that stable parts can be drawn solid and unstable parts dashed (Fig. 3b).

/// One sampled steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSample {
    /// The family (colour key), e.g. `IC`, `MD minor-axis`.
    pub key: String,
    pub x: f64,
    pub v: f64,
    pub s: f64,
    pub stable: bool,
}

/// A piece of a branch of uniform stability: `(x, v, s)` in order along the branch.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchLine {
    pub key: String,
    pub points: Vec<(f64, f64, f64)>,
    pub stable: bool,
}

/// Largest scaled distance between matched states of neighbouring samples (a quarter of the
/// picture's range; states further apart start a new track).
const MAX_JUMP: f64 = 0.25;

/// Extends the open tracks by one `column` of samples at the same `x`: the nearest (track,
/// sample) pairs within [`MAX_JUMP`] first; a track left without a sample is closed, a sample
/// left without a track starts a new one. Returns the tracks still open.
fn extend_tracks<'a>(
    mut open: Vec<Vec<&'a BranchSample>>,
    column: &[&'a BranchSample],
    closed: &mut Vec<Vec<&'a BranchSample>>,
    dist: &dyn Fn(&BranchSample, &BranchSample) -> f64,
) -> Vec<Vec<&'a BranchSample>> {
    let mut pairs: Vec<(f64, usize, usize)> = open
        .iter()
        .enumerate()
        .flat_map(|(t, track)| {
            let end = *track.last().expect("tracks are never empty");
            column
                .iter()
                .enumerate()
                .map(move |(c, p)| (dist(end, p), t, c))
        })
        .filter(|(d, _, _)| *d <= MAX_JUMP)
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut track_used, mut point_used) = (vec![false; open.len()], vec![false; column.len()]);
    for (_, t, c) in pairs {
        if !track_used[t] && !point_used[c] {
            track_used[t] = true;
            point_used[c] = true;
            open[t].push(column[c]);
        }
    }
    let mut still_open = Vec::new();
    for (t, track) in open.into_iter().enumerate() {
        if track_used[t] {
            still_open.push(track);
        } else {
            closed.push(track);
        }
    }
    still_open.extend(
        column
            .iter()
            .zip(&point_used)
            .filter(|(_, used)| !**used)
            .map(|(p, _)| vec![*p]),
    );
    still_open
}

/// A track cut where its stability changes; the joining segment takes the new stability.
fn stability_runs(key: &str, track: &[BranchSample]) -> Vec<BranchLine> {
    let mut lines = Vec::new();
    let mut start: usize = 0;
    for k in 1..=track.len() {
        if k == track.len() || track[k].stable != track[k - 1].stable {
            let from = start.saturating_sub(1);
            lines.push(BranchLine {
                key: key.to_string(),
                points: track[from..k].iter().map(|p| (p.x, p.v, p.s)).collect(),
                stable: track[start].stable,
            });
            start = k;
        }
    }
    lines
}

/// Joins `samples` into lines (see the module doc). Samples of one family share their `x`
/// values when they come from one line of parameter values. `events` are bifurcation points
/// `(family, x)` found between samples: there the tracks are closed up, so that a branch runs
/// through its fold (two track ends meet: saddle-node) or starts on the state it bifurcates
/// from (one track end: pitchfork) instead of stopping one sample short.
pub fn branch_lines(samples: &[BranchSample], events: &[(String, f64)]) -> Vec<BranchLine> {
    let range = |f: fn(&BranchSample) -> f64| {
        let (lo, hi) = samples
            .iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        if hi > lo {
            hi - lo
        } else {
            1.0
        }
    };
    let (sv, ss) = (range(|p| p.v), range(|p| p.s));
    let dist = |a: &BranchSample, b: &BranchSample| (a.v - b.v).abs() / sv + (a.s - b.s).abs() / ss;
    let mut keys: Vec<&str> = samples.iter().map(|p| p.key.as_str()).collect();
    keys.sort();
    keys.dedup();
    let mut lines = Vec::new();
    for key in keys {
        let mut mine: Vec<&BranchSample> = samples.iter().filter(|p| p.key == key).collect();
        mine.sort_by(|a, b| a.x.total_cmp(&b.x));
        let mut open: Vec<Vec<&BranchSample>> = Vec::new();
        let mut closed: Vec<Vec<&BranchSample>> = Vec::new();
        let mut i = 0;
        while i < mine.len() {
            let j = i + mine[i..].iter().take_while(|p| p.x == mine[i].x).count();
            let column = &mine[i..j];
            open = extend_tracks(open, column, &mut closed, &dist);
            i = j;
        }
        closed.extend(open);
        let mut tracks: Vec<Vec<BranchSample>> = closed
            .into_iter()
            .map(|t| t.into_iter().cloned().collect())
            .collect();
        let step = mine
            .windows(2)
            .map(|w| w[1].x - w[0].x)
            .filter(|d| *d > 0.0)
            .fold(f64::INFINITY, f64::min);
        for &(_, at) in events.iter().filter(|(k, _)| k == key) {
            join_at(&mut tracks, at, 1.5 * step, samples, key, &dist);
        }
        for track in tracks {
            lines.extend(stability_runs(key, &track));
        }
    }
    lines
}

/// Closes up the tracks of family `key` at the event `at` (see [`branch_lines`]): track ends
/// within `reach` of `at` are joined to each other (two ends) or to the nearest state of
/// another family there (one end).
fn join_at(
    tracks: &mut Vec<Vec<BranchSample>>,
    at: f64,
    reach: f64,
    samples: &[BranchSample],
    key: &str,
    dist: &dyn Fn(&BranchSample, &BranchSample) -> f64,
) {
    // (track, at its start?) for every end near the event.
    let ends: Vec<(usize, bool)> = tracks
        .iter()
        .enumerate()
        .flat_map(|(t, tr)| {
            let first = (t, true, tr[0].x);
            let last = (t, false, tr[tr.len() - 1].x);
            let both = tr.len() > 1;
            std::iter::once(first).chain(both.then_some(last))
        })
        .filter(|(_, _, x)| (x - at).abs() <= reach)
        .map(|(t, start, _)| (t, start))
        .collect();
    match ends[..] {
        [(a, a_start), (b, b_start)] if a != b => {
            // A fold: one track continues into the other.
            let mut tb = std::mem::take(&mut tracks[b]);
            let ta = &mut tracks[a];
            if a_start {
                ta.reverse();
            }
            if !b_start {
                tb.reverse();
            }
            ta.extend(tb);
            tracks.remove(b);
        }
        [(t, start)] => {
            let tr = &mut tracks[t];
            let end = if start { &tr[0] } else { &tr[tr.len() - 1] };
            let Some(root) = samples
                .iter()
                .filter(|p| p.key != key && (p.x - at).abs() <= reach)
                .min_by(|a, b| dist(a, end).total_cmp(&dist(b, end)))
            else {
                return;
            };
            let joint = BranchSample {
                key: key.to_string(),
                stable: end.stable,
                ..root.clone()
            };
            if start {
                tr.insert(0, joint);
            } else {
                tr.push(joint);
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(key: &str, x: f64, v: f64, stable: bool) -> BranchSample {
        BranchSample {
            key: key.into(),
            x,
            v,
            s: 0.0,
            stable,
        }
    }

    #[test]
    fn a_fold_gives_two_tracks_and_stability_changes_cut_them() {
        // A saddle-node at x = 0: upper branch stable, lower unstable, both ending there;
        // and a resting state that loses stability at x = 0.5.
        let mut samples = Vec::new();
        for i in 0..=10 {
            let x = i as f64 * 0.1;
            let r = x.sqrt();
            samples.push(sample("MD", x, 1.0 + r, true));
            if i > 0 {
                samples.push(sample("MD", x, 1.0 - r, false));
            }
            samples.push(sample("IC", x, 0.0, x < 0.5));
        }
        let lines = branch_lines(&samples, &[]);
        let md: Vec<&BranchLine> = lines.iter().filter(|l| l.key == "MD").collect();
        assert_eq!(md.len(), 2, "{md:?}");
        assert!(md.iter().any(|l| l.stable && l.points.len() == 11));
        assert!(md.iter().any(|l| !l.stable && l.points.len() == 10));
        let ic: Vec<&BranchLine> = lines.iter().filter(|l| l.key == "IC").collect();
        assert_eq!(ic.len(), 2);
        let (stable, unstable) = if ic[0].stable {
            (ic[0], ic[1])
        } else {
            (ic[1], ic[0])
        };
        assert_eq!(stable.points.len(), 5);
        // The unstable part starts at the last stable sample: no gap in the drawing.
        assert_eq!(unstable.points[0], *stable.points.last().unwrap());
        assert_eq!(unstable.points.len(), 7);
        // With the fold and the resting state's pitchfork as events, the fold is closed up
        // into one branch (stable part, then unstable part from the joint on).
        let lines = branch_lines(
            &samples,
            &[("MD".to_string(), 0.05), ("IC".to_string(), 0.45)],
        );
        let md: Vec<&BranchLine> = lines.iter().filter(|l| l.key == "MD").collect();
        assert_eq!(md.len(), 2, "{md:?}");
        let total: usize = md.iter().map(|l| l.points.len()).sum();
        assert_eq!(total, 22, "one point shared at the stability change");
        let stable = md.iter().find(|l| l.stable).unwrap();
        let unstable = md.iter().find(|l| !l.stable).unwrap();
        assert_eq!(stable.points.last(), unstable.points.first(), "{md:?}");
    }

    #[test]
    fn a_pitchfork_branch_starts_on_the_state_it_leaves() {
        // A branch v = sqrt(x) emerging from the resting state at x = 0, sampled from x = 0.1.
        let mut samples: Vec<BranchSample> = (0..=10)
            .map(|i| sample("IC", i as f64 * 0.1, 0.0, false))
            .collect();
        samples.extend((1..=10).map(|i| {
            let x = i as f64 * 0.1;
            sample("MD", x, x.sqrt(), true)
        }));
        let lines = branch_lines(&samples, &[("MD".to_string(), 0.05)]);
        let md = lines.iter().find(|l| l.key == "MD").unwrap();
        assert_eq!(md.points.len(), 11);
        assert_eq!(md.points[0], (0.0, 0.0, 0.0));
    }
}
