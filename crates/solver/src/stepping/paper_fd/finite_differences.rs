//! The finite differences of the paper's scheme on the periodic lab grid: central
//! differences for `grad u` and one forward-Euler step of the field with the 5-point Laplacian.

/// `grad u` at cell `(ix, iy)` of the periodic `n x n` field `u` by central differences
/// (`inv2dx = 1 / (2 dx)`).
pub(crate) fn central_gradient(
    u: &[f64],
    n: usize,
    (ix, iy): (usize, usize),
    inv2dx: f64,
) -> (f64, f64) {
    let ux = (u[iy * n + (ix + 1) % n] - u[iy * n + (ix + n - 1) % n]) * inv2dx;
    let uy = (u[((iy + 1) % n) * n + ix] - u[((iy + n - 1) % n) * n + ix]) * inv2dx;
    (ux, uy)
}

/// One forward-Euler step of `h` of the field on the periodic `n x n` lab grid of spacing
/// `dx`: `u <- u + h (Lap u - u + Theta / A)`, the 5-point Laplacian, into `u` (`u_next` is
/// scratch).
pub(crate) fn euler_field_step(
    u: &mut Vec<f64>,
    u_next: &mut Vec<f64>,
    theta: &[f64],
    (n, dx): (usize, f64),
    h: f64,
    area: f64,
) {
    let inv_dx2 = 1.0 / (dx * dx);
    let inv_a = 1.0 / area;
    for iy in 0..n {
        let up = ((iy + n - 1) % n) * n;
        let dn = ((iy + 1) % n) * n;
        let row = iy * n;
        for ix in 0..n {
            let l = if ix == 0 { n - 1 } else { ix - 1 };
            let r = if ix == n - 1 { 0 } else { ix + 1 };
            let c = u[row + ix];
            let lap = (u[row + l] + u[row + r] + u[up + ix] + u[dn + ix] - 4.0 * c) * inv_dx2;
            u_next[row + ix] = c + h * (lap - c + theta[row + ix] * inv_a);
        }
    }
    std::mem::swap(u, u_next);
}
