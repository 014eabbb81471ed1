//! The steady field of a `K`-mode droplet in the lab frame (for the run picture of `droplet
//! simulate --modes K`): the co-moving steady field of [`ModeSolver`] (paper eq. S13 with the
//! droplet of modes `2..K`) moved to the droplet's centre by the exact phase shift
//! `e^(-i k . r_c)`, as the 2-mode scheme's field is.
use crate::model::modes::Modes;
use crate::numerics::fft2::PrunedFft2;
use crate::roots::mode_solver::ModeSolver;
use crate::stepping::Field;

/// The steady field of the droplet `z = (vx, vy, a_2..a_K, b_2..b_K)` centred at `(x, y)`, on
/// the solver's grid (row-major, `values[iy * n + ix]` at `((ix - n/2) dx, (iy - n/2) dx)`).
pub fn lab_field(solver: &mut ModeSolver, z: &[f64], x: f64, y: f64) -> Field {
    solver.forces(z[0], z[1], &Modes::of_state(z));
    let n = solver.n();
    let len = solver.params().box_len;
    let mut spec = solver.field_spectrum().to_vec();
    solver.grid().shift_spectrum(&mut spec, x, y);
    let mut values = vec![0.0; n * n];
    PrunedFft2::new(n).inverse(&mut spec, &mut values, 0, n - 1);
    Field { n, len, values }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::ModelParams;
    use crate::roots::steady_solver::SteadySolver;

    #[test]
    fn with_two_modes_at_the_centre_it_is_the_two_mode_steady_field() {
        let p = ModelParams::at(0.085, 0.112);
        let mut modes = ModeSolver::new(p, 64).unwrap();
        let mut two = SteadySolver::new(p, 64).unwrap();
        let f = lab_field(&mut modes, &[0.3, 0.1, -0.2, 0.05], 0.0, 0.0);
        let g = two.field(0.3, 0.1, -0.2, 0.05);
        let peak = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = f
            .values
            .iter()
            .zip(&g)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(peak > 0.01 && diff < 1e-12 * peak, "{diff} of {peak}");
    }

    #[test]
    fn moving_the_centre_by_whole_cells_moves_the_field() {
        // A shift by (3, -2) cells moves the field's samples with it, exactly but for the
        // Nyquist modes, which the spectral shift (like the derivatives) leaves out: a part in
        // 1e-4 of the peak at N = 64. A shift the wrong way would be off by a fifth of it.
        let p = ModelParams::at(0.085, 0.112);
        let mut s = ModeSolver::new(p, 64).unwrap();
        let z = [0.3, 0.0, -0.2, 0.04, 0.0, 0.01];
        let at0 = lab_field(&mut s, &z, 0.0, 0.0);
        let dx = p.box_len / 64.0;
        let moved = lab_field(&mut s, &z, 3.0 * dx, -2.0 * dx);
        let peak = at0.values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for iy in 10..54 {
            for ix in 10..54 {
                let a = moved.values[iy * 64 + ix];
                let b = at0.values[(iy + 2) * 64 + ix - 3];
                assert!((a - b).abs() < 1e-4 * peak, "({ix}, {iy}): {a} vs {b}");
            }
        }
    }
}
