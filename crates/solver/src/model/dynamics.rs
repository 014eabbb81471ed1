//! The droplet's equations of motion (paper eqs. 36-39 with the inertia `m` of docs/model.md,
//! "Inertia": `m = 0.1`, the value that reproduces the paper's IC/MD bistability), in the one place every scheme and the steady equations take them from:
//!
//! `m dv/dt = -eta_t v + F`,   `eta2 da2/dt = Ga - kappa2 a2`,   `eta2 db2/dt = Gb - kappa2 b2`,
//!
//! with `m = 0` meaning the overdamped law `eta_t v = F`, and a pinned droplet (deformation-only
//! runs, Appendix E) keeping `v = 0`.
use crate::model::forces::parseval::Forces;
use crate::model::params::ModelParams;

/// The force balance `(-eta_t vx + Fx, -eta_t vy + Fy, Ga - kappa2 a2, Gb - kappa2 b2)`: `M`
/// times the rates, `M = diag(m, m, eta2, eta2)`; zero at a steady state.
pub fn force_balance(p: &ModelParams, z: [f64; 4], f: &Forces) -> [f64; 4] {
    let [vx, vy, a2, b2] = z;
    [
        -p.eta_t * vx + f.fx,
        -p.eta_t * vy + f.fy,
        f.ga - p.kappa2 * a2,
        f.gb - p.kappa2 * b2,
    ]
}

/// The linear decay rates of the velocity and of the shape, `(-eta_t / m, -kappa2 / eta2)`
/// (the velocity's is 0 when it is not integrated: overdamped or pinned). Exponential
/// integrators treat them exactly.
pub fn linear_rates(p: &ModelParams, pinned: bool) -> (f64, f64) {
    let inertial = p.mass > 0.0 && !pinned;
    (
        if inertial { -p.eta_t / p.mass } else { 0.0 },
        -p.kappa2 / p.eta2,
    )
}

/// The rates of `(vx, vy, a2, b2)` beyond [`linear_rates`]: `(F / m, Ga / eta2, Gb / eta2)`
/// (no velocity forcing when the velocity is not integrated).
pub fn forcing(p: &ModelParams, f: &Forces, pinned: bool) -> [f64; 4] {
    let (ax, ay) = if pinned || p.mass == 0.0 {
        (0.0, 0.0)
    } else {
        (f.fx / p.mass, f.fy / p.mass)
    };
    [ax, ay, f.ga / p.eta2, f.gb / p.eta2]
}

/// The overdamped velocity `F / eta_t` (`m = 0`).
pub fn overdamped_velocity(p: &ModelParams, f: &Forces) -> (f64, f64) {
    (f.fx / p.eta_t, f.fy / p.eta_t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_split_forms_agree_with_the_force_balance() {
        let p = ModelParams::default();
        let f = Forces {
            fx: 0.03,
            fy: -0.01,
            ga: 0.02,
            gb: 0.005,
            area: 3.1,
        };
        let z = [0.5, -0.2, -0.1, 0.05];
        let balance = force_balance(&p, z, &f);
        let (lv, ls) = linear_rates(&p, false);
        let forced = forcing(&p, &f, false);
        let rates = [
            lv * z[0] + forced[0],
            lv * z[1] + forced[1],
            ls * z[2] + forced[2],
            ls * z[3] + forced[3],
        ];
        let m = [p.mass, p.mass, p.eta2, p.eta2];
        for i in 0..4 {
            assert!((rates[i] * m[i] - balance[i]).abs() < 1e-15, "{i}");
        }
        assert_eq!(linear_rates(&p, true).0, 0.0);
        assert_eq!(forcing(&p, &f, true)[0], 0.0);
        let over = ModelParams { mass: 0.0, ..p };
        let (vx, _) = overdamped_velocity(&over, &f);
        assert_eq!(force_balance(&over, [vx, 0.0, 0.0, 0.0], &f)[0], 0.0);
    }
}
