//! Newton's method for small dense systems `f(x) = 0` (the steady states' force balance; the
//! continuation's corrector): central-difference Jacobian, LU with partial pivoting (nalgebra), damping
//! by a per-component step cap, and a convergence test on the residual (max norm) instead of
//! a fixed number of iterations. No line search on the residual: the force balance always has
//! the resting disk as a root, and a residual-decreasing search is drawn to it from states
//! that are not.
use crate::error::SolverError;

/// How to run [`solve`].
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonOptions {
    /// Converged when the max norm of the residual is below this.
    pub tol: f64,
    /// Give up after this many iterations (a safety net: converging solves take 3 to 8).
    pub max_iter: usize,
    /// Step of the central differences of the Jacobian.
    pub fd_step: f64,
    /// Largest change of each unknown in one step (the whole step is scaled down to respect
    /// every cap; `f64::INFINITY` for none).
    pub max_step: Vec<f64>,
    /// The Jacobian by forward differences ([`forward_jacobian`]: `n` evaluations of `f` for
    /// `n` unknowns, first order in `fd_step`) instead of central ones (`2 n`, second order).
    /// Either converges to the same root under `tol`: the residual decides, not the step.
    pub one_sided: bool,
    /// A step that more than doubles the residual is halved (at most [`BACKTRACKS`] times,
    /// one evaluation of `f` each) and the last one taken. Newton from a state beside a family
    /// of roots that the box's anisotropy barely breaks (a moving K-mode droplet leaning 0.2
    /// degree from its root) otherwise steps far along the family and wanders; a step that
    /// raises the residual less is kept (halving those too cost the Fig. 1c runs of modes
    /// 2..4 a quarter more field solves).
    pub backtrack: bool,
}

/// The most halvings of one step ([`NewtonOptions::backtrack`]).
pub const BACKTRACKS: usize = 3;

/// The factor of the residual beyond which a step is halved ([`NewtonOptions::backtrack`]).
pub const RAISED: f64 = 2.0;

/// A converged solve.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonResult {
    pub x: Vec<f64>,
    /// Max norm of the residual at `x`.
    pub residual: f64,
    pub iterations: usize,
}

fn max_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The Jacobian of `f` at `x` by central differences of step `h` (`jac[row][col]`).
pub fn fd_jacobian(f: &mut impl FnMut(&[f64]) -> Vec<f64>, x: &[f64], h: f64) -> Vec<Vec<f64>> {
    by_columns(x, |y, j| {
        y[j] = x[j] + h;
        let fp = f(y);
        y[j] = x[j] - h;
        let fm = f(y);
        fp.iter()
            .zip(&fm)
            .map(|(p, m)| (p - m) / (2.0 * h))
            .collect()
    })
}

/// The Jacobian of `f` at `x`, where `f(x) = fx`, by forward differences of step `h`
/// (`jac[row][col]`).
pub fn forward_jacobian(
    f: &mut impl FnMut(&[f64]) -> Vec<f64>,
    x: &[f64],
    fx: &[f64],
    h: f64,
) -> Vec<Vec<f64>> {
    by_columns(x, |y, j| {
        y[j] = x[j] + h;
        let fp = f(y);
        fp.iter().zip(fx).map(|(p, c)| (p - c) / h).collect()
    })
}

/// A Jacobian from its columns: `column(y, j)` is the derivative along unknown `j`, with `y`
/// a copy of `x` it may change in place `j` (restored after each column).
fn by_columns(x: &[f64], mut column: impl FnMut(&mut [f64], usize) -> Vec<f64>) -> Vec<Vec<f64>> {
    let mut y = x.to_vec();
    let cols: Vec<Vec<f64>> = (0..x.len())
        .map(|j| {
            let c = column(&mut y, j);
            y[j] = x[j];
            c
        })
        .collect();
    (0..cols.first().map_or(0, Vec::len))
        .map(|i| cols.iter().map(|c| c[i]).collect())
        .collect()
}

/// Solves `a x = b` (`a[row][col]`) by LU with partial pivoting (nalgebra); `None` when `a`
/// is singular or the solution is not finite.
pub fn lu_solve(a: Vec<Vec<f64>>, b: &[f64]) -> Option<Vec<f64>> {
    let n = b.len();
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| a[i][j]);
    let x = m.lu().solve(&nalgebra::DVector::from_column_slice(b))?;
    x.iter()
        .all(|v| v.is_finite())
        .then(|| x.iter().copied().collect())
}

/// Solves `f(x) = 0` from `x0`. Each step is the Newton step scaled down to respect
/// `opts.max_step`.
pub fn solve(
    f: impl FnMut(&[f64]) -> Vec<f64>,
    x0: &[f64],
    opts: &NewtonOptions,
) -> Result<NewtonResult, SolverError> {
    solve_keeping(f, x0, opts, &mut None)
}

/// [`solve`], leaving in `last` the Jacobian of its last step (taken at the iterate before
/// the solution: a Jacobian for the [`chord`] method near the same root).
pub fn solve_keeping(
    mut f: impl FnMut(&[f64]) -> Vec<f64>,
    x0: &[f64],
    opts: &NewtonOptions,
    last: &mut Option<Vec<Vec<f64>>>,
) -> Result<NewtonResult, SolverError> {
    let mut x = x0.to_vec();
    let mut r = f(&x);
    let mut norm = max_norm(&r);
    let failed = |residual: f64, iterations: usize| SolverError::NewtonFailed {
        residual,
        iterations,
    };
    for it in 0..=opts.max_iter {
        if norm < opts.tol {
            return Ok(NewtonResult {
                x,
                residual: norm,
                iterations: it,
            });
        }
        if it == opts.max_iter || !norm.is_finite() {
            break;
        }
        let jac = match opts.one_sided {
            true => forward_jacobian(&mut f, &x, &r, opts.fd_step),
            false => fd_jacobian(&mut f, &x, opts.fd_step),
        };
        let minus_r: Vec<f64> = r.iter().map(|v| -v).collect();
        *last = Some(jac.clone());
        let dx = lu_solve(jac, &minus_r).ok_or_else(|| failed(norm, it))?;
        let scale = dx
            .iter()
            .zip(&opts.max_step)
            .map(|(d, cap)| cap / d.abs().max(1e-300))
            .fold(1.0f64, f64::min);
        let start = x.clone();
        let mut s = scale;
        for (xi, d) in x.iter_mut().zip(&dx) {
            *xi += s * d;
        }
        r = f(&x);
        let mut halvings = 0;
        // More than doubled, or not a number.
        let raised =
            |r: &[f64]| max_norm(r).partial_cmp(&(RAISED * norm)) != Some(std::cmp::Ordering::Less);
        while opts.backtrack && raised(&r) && halvings < BACKTRACKS {
            s *= 0.5;
            halvings += 1;
            for ((xi, x0), d) in x.iter_mut().zip(&start).zip(&dx) {
                *xi = x0 + s * d;
            }
            r = f(&x);
        }
        norm = max_norm(&r);
    }
    Err(failed(norm, opts.max_iter))
}

/// Solves `f(x) = 0` from `x0` by the chord method: Newton steps with the fixed Jacobian
/// `jac` (from a nearby solve), each step one evaluation of `f`. Fails when a step does not
/// halve the residual (the Jacobian too far from the one at the root), or after
/// `opts.max_iter` steps; the caller then solves by [`solve`].
pub fn chord(
    mut f: impl FnMut(&[f64]) -> Vec<f64>,
    x0: &[f64],
    jac: &[Vec<f64>],
    opts: &NewtonOptions,
) -> Result<NewtonResult, SolverError> {
    let n = x0.len();
    let lu = nalgebra::DMatrix::from_fn(n, n, |i, j| jac[i][j]).lu();
    let mut x = x0.to_vec();
    let mut norm = f64::INFINITY;
    for it in 0..=opts.max_iter {
        let r = f(&x);
        let next = max_norm(&r);
        if next < opts.tol {
            return Ok(NewtonResult {
                x,
                residual: next,
                iterations: it,
            });
        }
        if it == opts.max_iter || !next.is_finite() || next > 0.5 * norm {
            return Err(SolverError::NewtonFailed {
                residual: next,
                iterations: it,
            });
        }
        norm = next;
        let minus_r = nalgebra::DVector::from_iterator(n, r.iter().map(|v| -v));
        let dx = lu.solve(&minus_r).ok_or(SolverError::NewtonFailed {
            residual: norm,
            iterations: it,
        })?;
        for (xi, d) in x.iter_mut().zip(dx.iter()) {
            *xi += d;
        }
    }
    unreachable!("the loop returns at it == max_iter")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_with_pivoting_and_refuses_singular_systems() {
        // A zero pivot in the first position needs a row swap.
        let a = vec![
            vec![0.0, 2.0, 1.0],
            vec![1.0, 1.0, 0.0],
            vec![2.0, 0.0, 3.0],
        ];
        let x = lu_solve(a.clone(), &[5.0, 3.0, 11.0]).unwrap();
        for (row, b) in a.iter().zip([5.0, 3.0, 11.0]) {
            let ax: f64 = row.iter().zip(&x).map(|(p, q)| p * q).sum();
            assert!((ax - b).abs() < 1e-14);
        }
        assert!(lu_solve(vec![vec![1.0, 2.0], vec![2.0, 4.0]], &[1.0, 2.0]).is_none());
    }

    #[test]
    fn converges_quadratically_and_the_jacobian_is_right() {
        // x^2 + y^2 = 4, x y = 1 from (2, 0.3).
        let f = |v: &[f64]| vec![v[0] * v[0] + v[1] * v[1] - 4.0, v[0] * v[1] - 1.0];
        let opts = NewtonOptions {
            tol: 1e-13,
            max_iter: 50,
            fd_step: 1e-6,
            max_step: vec![f64::INFINITY; 2],
            one_sided: false,
            backtrack: false,
        };
        let sol = solve(f, &[2.0, 0.3], &opts).unwrap();
        assert!(sol.residual < 1e-13 && sol.iterations <= 8, "{sol:?}");
        let (x, y) = (sol.x[0], sol.x[1]);
        assert!((x * y - 1.0).abs() < 1e-13);
        let mut g = f;
        let j = fd_jacobian(&mut g, &[1.0, 2.0], 1e-6);
        let exact = [[2.0, 4.0], [2.0, 1.0]];
        for i in 0..2 {
            for k in 0..2 {
                assert!((j[i][k] - exact[i][k]).abs() < 1e-8);
            }
        }
        // Forward differences: first order in the step, and the same root to the tolerance.
        let g0 = g(&[1.0, 2.0]);
        let j1 = forward_jacobian(&mut g, &[1.0, 2.0], &g0, 1e-6);
        for i in 0..2 {
            for k in 0..2 {
                assert!((j1[i][k] - exact[i][k]).abs() < 1e-5);
            }
        }
        let one_sided = NewtonOptions {
            one_sided: true,
            ..opts.clone()
        };
        let sol1 = solve(f, &[2.0, 0.3], &one_sided).unwrap();
        assert!(sol1.residual < 1e-13 && sol1.iterations <= 9, "{sol1:?}");
        assert!((sol1.x[0] - x).abs() < 1e-12 && (sol1.x[1] - y).abs() < 1e-12);
        // A step cap slows it down but it still converges; no root -> a typed error.
        let capped = NewtonOptions {
            max_step: vec![0.05; 2],
            ..opts.clone()
        };
        assert!(solve(f, &[2.0, 0.3], &capped).unwrap().iterations > sol.iterations);
        let none = |v: &[f64]| vec![v[0] * v[0] + 1.0];
        let o1 = NewtonOptions {
            max_step: vec![f64::INFINITY],
            ..opts
        };
        assert!(matches!(
            solve(none, &[0.5], &o1),
            Err(SolverError::NewtonFailed { .. })
        ));
    }

    #[test]
    fn halving_the_steps_that_raise_the_residual_converges_where_newton_wanders() {
        // exp(x) = 1 from x = -3: Newton's first step overshoots to x = 16.1 and comes back
        // one unit an iteration, past 12 iterations; halved three times, the step lands at
        // -0.61 and Newton converges.
        let f = |v: &[f64]| vec![v[0].exp() - 1.0];
        let opts = NewtonOptions {
            tol: 1e-12,
            max_iter: 12,
            fd_step: 1e-7,
            max_step: vec![f64::INFINITY],
            one_sided: false,
            backtrack: false,
        };
        assert!(matches!(
            solve(f, &[-3.0], &opts),
            Err(SolverError::NewtonFailed { .. })
        ));
        let damped = NewtonOptions {
            backtrack: true,
            ..opts
        };
        let sol = solve(f, &[-3.0], &damped).unwrap();
        assert!(sol.x[0].abs() < 1e-12 && sol.iterations <= 8, "{sol:?}");
    }

    #[test]
    fn the_chord_method_finds_the_root_with_a_nearby_jacobian_and_fails_with_a_wrong_one() {
        // x^2 + y^2 = 5, x y = 2: a root at (1, 2); the Jacobian taken at (1.1, 1.9).
        let mut f = |v: &[f64]| vec![v[0] * v[0] + v[1] * v[1] - 5.0, v[0] * v[1] - 2.0];
        let opts = NewtonOptions {
            tol: 1e-13,
            max_iter: 30,
            fd_step: 1e-7,
            max_step: vec![f64::INFINITY; 2],
            one_sided: false,
            backtrack: false,
        };
        let near = fd_jacobian(&mut f, &[1.1, 1.9], 1e-7);
        let sol = chord(f, &[1.05, 1.95], &near, &opts).unwrap();
        assert!((sol.x[0] - 1.0).abs() < 1e-12 && (sol.x[1] - 2.0).abs() < 1e-12);
        // Linear convergence: more steps than Newton's, each one evaluation.
        let newton = solve(f, &[1.05, 1.95], &opts).unwrap();
        assert!(sol.iterations > newton.iterations, "{sol:?} {newton:?}");
        // A Jacobian of the wrong sign makes the residual grow: refused at once.
        let wrong: Vec<Vec<f64>> = near
            .iter()
            .map(|r| r.iter().map(|v| -v).collect())
            .collect();
        assert!(matches!(
            chord(f, &[1.05, 1.95], &wrong, &opts),
            Err(SolverError::NewtonFailed { iterations: 1, .. })
        ));
    }
}
