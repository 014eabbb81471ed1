//! Steady states of the reduced model along a line in one model parameter, with their
//! stability (eigenvalues of the Jacobian of eqs. 58-59) and the bifurcation points
//! (pitchfork `P`, saddle-node `SN`): the paper's Fig. 3(b).
//!
//! Steady states (Appendix F): IC (`v = s = 0`); ID (`v = 0`, `s = sqrt((g0~ - kappa2)/h0)`);
//! MD moving along the minor axis (`cos 2(psi - phi) = -1`) or the major axis (`+1`), with
//! `v^2 = (f1 - eta_t - c f1~ s) / f3` and `(g0~ - kappa2) s - c g2 v^2 - g2~ s v^2 - h0 s^3 = 0`,
//! found by bracketing and bisection in `0 < s < 1`. Every state lies on the mirror axis
//! (`vy = b2 = 0`, motion along x), where the Jacobian splits into the (vx, a2) and (vy, b2)
//! blocks; the latter holds the neutral rotation mode of ID and MD states, which is excluded.
use crate::model::param::ModelParam;
use crate::model::params::ModelParams;
use crate::reduced::coefficients::Coefficients;
use crate::reduced::ode::rhs;
use serde::Serialize;

/// Which family a steady state belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, PartialOrd, Ord)]
pub enum Branch {
    IC,
    ID,
    /// Moving along its minor axis (the paper's MD).
    MdMinor,
    /// Moving along its major axis (always unstable in the paper's analysis).
    MdMajor,
}

impl Branch {
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::IC => "IC",
            Self::ID => "ID",
            Self::MdMinor => "MD minor-axis",
            Self::MdMajor => "MD major-axis",
        }
    }
}

/// A steady state with its stability.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadyPoint {
    pub branch: Branch,
    /// The parameters of the state.
    pub params: ModelParams,
    pub v: f64,
    pub s: f64,
    /// Largest real part of the eigenvalues (neutral rotation mode excluded).
    pub max_re: f64,
    pub stable: bool,
}

/// A bifurcation point found between two samples of a line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Event {
    /// `P` (pitchfork / drift pitchfork) or `SN` (saddle-node).
    pub kind: &'static str,
    pub branch: Branch,
    /// The swept parameter's value (midpoint of the bracketing samples).
    pub at: f64,
}

/// The MD states (`c = -1` minor axis, `+1` major axis): `(v, s)` pairs.
pub fn md_states(c: &Coefficients, eta_t: f64, kappa2: f64, axis: f64) -> Vec<(f64, f64)> {
    let v2 = |s: f64| (c.f1 - eta_t - axis * c.f1t * s) / c.f3;
    let g = |s: f64| {
        let w = v2(s);
        (c.g0t - kappa2) * s - axis * c.g2 * w - c.g2t * s * w - c.h0 * s.powi(3)
    };
    let samples = 4000;
    let mut out = Vec::new();
    let mut prev: Option<(f64, f64)> = None;
    for i in 1..samples {
        let s = i as f64 / samples as f64;
        if v2(s) <= 0.0 {
            prev = None;
            continue;
        }
        let gs = g(s);
        if let Some((s0, g0)) = prev {
            if g0 == 0.0 || g0.signum() != gs.signum() {
                let (mut lo, mut hi) = (s0, s);
                for _ in 0..80 {
                    let mid = 0.5 * (lo + hi);
                    if g(mid).signum() == g(lo).signum() {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let root = 0.5 * (lo + hi);
                out.push((v2(root).sqrt(), root));
            }
        }
        prev = Some((s, gs));
    }
    out
}

fn block_max_re(j: [[f64; 2]; 2], drop_zero_mode: bool) -> f64 {
    let tr = j[0][0] + j[1][1];
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if drop_zero_mode {
        // One eigenvalue is the neutral rotation (0); the other is the trace.
        return tr;
    }
    let disc = tr * tr / 4.0 - det;
    if disc >= 0.0 {
        tr / 2.0 + disc.sqrt()
    } else {
        tr / 2.0
    }
}

/// Largest real part of the Jacobian's eigenvalues at the axis state `(v, 0, a2, 0)`.
pub fn max_real_eigenvalue(
    c: &Coefficients,
    p: &ModelParams,
    v: f64,
    a2: f64,
    rotation_mode: bool,
) -> f64 {
    let mut f = |y: &[f64]| rhs(c, p, [y[0], y[1], y[2], y[3]]).to_vec();
    let jac = crate::numerics::newton::fd_jacobian(&mut f, &[v, 0.0, a2, 0.0], 1e-7);
    let a = [[jac[0][0], jac[0][2]], [jac[2][0], jac[2][2]]];
    let b = [[jac[1][1], jac[1][3]], [jac[3][1], jac[3][3]]];
    block_max_re(a, false).max(block_max_re(b, rotation_mode))
}

/// All steady states at one parameter point.
pub fn steady_states(c: &Coefficients, p: &ModelParams) -> Vec<SteadyPoint> {
    let mut out = Vec::new();
    let mut push = |branch: Branch, v: f64, s: f64, a2: f64| {
        let max_re = max_real_eigenvalue(c, p, v, a2, branch != Branch::IC);
        out.push(SteadyPoint {
            branch,
            params: *p,
            v,
            s,
            max_re,
            stable: max_re < -1e-9,
        });
    };
    push(Branch::IC, 0.0, 0.0, 0.0);
    if p.kappa2 < c.g0t {
        let s = ((c.g0t - p.kappa2) / c.h0).sqrt();
        push(Branch::ID, 0.0, s, s);
    }
    for (branch, axis) in [(Branch::MdMinor, -1.0), (Branch::MdMajor, 1.0)] {
        for (v, s) in md_states(c, p.eta_t, p.kappa2, axis) {
            push(branch, v, s, axis * s);
        }
    }
    out
}

/// Steady states along a line in `param` (the coefficients `c` stay as given: a line in
/// `radius` needs coefficients of each radius), and the bifurcation points between its
/// samples: a change of IC or ID stability is a pitchfork (`P`); a change by two in the
/// number of MD states of one family is a saddle-node (`SN`); by one, a pitchfork where the
/// branch meets IC or ID.
pub fn diagram(
    c: &Coefficients,
    base: &ModelParams,
    param: ModelParam,
    values: &[f64],
) -> (Vec<SteadyPoint>, Vec<Event>) {
    let at = |x: f64| {
        let mut p = *base;
        param.set(&mut p, x);
        p
    };
    let per: Vec<Vec<SteadyPoint>> = values.iter().map(|&x| steady_states(c, &at(x))).collect();
    let mut events = Vec::new();
    for (i, w) in per.windows(2).enumerate() {
        let mid = 0.5 * (values[i] + values[i + 1]);
        for b in [Branch::IC, Branch::ID] {
            let st = |pts: &[SteadyPoint]| pts.iter().find(|p| p.branch == b).map(|p| p.stable);
            let (s0, s1) = (st(&w[0]), st(&w[1]));
            if s0.is_some() != s1.is_some() || (s0.is_some() && s0 != s1) {
                events.push(Event {
                    kind: "P",
                    branch: b,
                    at: mid,
                });
            }
        }
        for b in [Branch::MdMinor, Branch::MdMajor] {
            let n = |pts: &[SteadyPoint]| pts.iter().filter(|p| p.branch == b).count() as i64;
            match (n(&w[1]) - n(&w[0])).abs() {
                0 => {}
                1 => events.push(Event {
                    kind: "P",
                    branch: b,
                    at: mid,
                }),
                _ => events.push(Event {
                    kind: "SN",
                    branch: b,
                    at: mid,
                }),
            }
        }
    }
    (per.into_iter().flatten().collect(), events)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(axis: ModelParam, fixed: f64, lo: f64, hi: f64) -> (Vec<SteadyPoint>, Vec<Event>) {
        let c = Coefficients::paper();
        let base = match axis {
            ModelParam::EtaT => ModelParams::at(0.08, fixed),
            _ => ModelParams::at(fixed, 0.12),
        };
        let values: Vec<f64> = (0..=400)
            .map(|i| lo + (hi - lo) * i as f64 / 400.0)
            .collect();
        diagram(&c, &base, axis, &values)
    }

    fn stable_md_at(pts: &[SteadyPoint], x: f64, axis: ModelParam) -> bool {
        pts.iter().any(|p| {
            let px = axis.get(&p.params);
            (px - x).abs() < 1e-12 && p.branch == Branch::MdMinor && p.stable
        })
    }

    #[test]
    fn drift_pitchfork_is_supercritical_above_kappa2_0156_and_subcritical_below() {
        let c = Coefficients::paper();
        // kappa2 = 0.160: no MD state above eta_t = f1 (supercritical).
        assert!(md_states(&c, c.f1 + 0.001, 0.16, -1.0).is_empty());
        assert!(!md_states(&c, c.f1 - 0.001, 0.16, -1.0).is_empty());
        // kappa2 = 0.130: a stable and an unstable MD coexist with stable IC above f1
        // (subcritical, hysteresis), ending in a saddle-node.
        let (pts, ev) = line(ModelParam::EtaT, 0.13, 0.070, 0.095);
        let x = (c.f1 + 0.002 - 0.070) / (0.025 / 400.0);
        let x = 0.070 + x.round() * 0.025 / 400.0;
        assert!(
            stable_md_at(&pts, x, ModelParam::EtaT),
            "stable MD at eta_t = {x}"
        );
        assert!(ev
            .iter()
            .any(|e| e.kind == "SN" && e.branch == Branch::MdMinor && e.at > c.f1));
    }

    #[test]
    fn id_to_md_is_supercritical_above_eta_0925_and_subcritical_below() {
        let c = Coefficients::paper();
        // The ID stability line at eta_t; MD states just above it in kappa2 exist only when
        // the transition is subcritical.
        let kc = |eta: f64| c.g0t - c.h0 * ((eta - c.f1) / c.f1t).powi(2);
        assert!(
            md_states(&c, 0.095, kc(0.095) + 0.0005, -1.0).is_empty(),
            "eta 0.095"
        );
        assert!(
            !md_states(&c, 0.085, kc(0.085) + 0.0005, -1.0).is_empty(),
            "eta 0.085"
        );
        // The switch lies near 0.0925 (the paper's value).
        let switch = (0..200)
            .map(|i| 0.085 + 0.0001 * i as f64)
            .find(|&e| md_states(&c, e, kc(e) + 1e-5, -1.0).is_empty())
            .unwrap();
        assert!((switch - 0.0925).abs() < 0.001, "switch at {switch}");
    }

    #[test]
    fn md_loses_stability_by_saddle_node_only_between_kappa2_0114_and_0156() {
        let has_sn = |k: f64| {
            let (_, ev) = line(ModelParam::EtaT, k, 0.075, 0.11);
            ev.iter()
                .any(|e| e.kind == "SN" && e.branch == Branch::MdMinor)
        };
        assert!(has_sn(0.12) && has_sn(0.15));
        assert!(!has_sn(0.105) && !has_sn(0.16));
        // Only minor-axis motion is stable.
        let (pts, _) = line(ModelParam::EtaT, 0.12, 0.07, 0.10);
        assert!(pts
            .iter()
            .filter(|p| p.branch == Branch::MdMajor)
            .all(|p| !p.stable));
        assert!(pts.iter().any(|p| p.branch == Branch::MdMinor && p.stable));
    }
}
