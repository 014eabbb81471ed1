//! The driving forces on the droplet (paper eqs. 35-37 and, for the modes `k >= 3`, the
//! smoothed eqs. dakdt_dl, dbkdt_dl) and the sampled source `Theta`, in two discretisations of
//! the same sums: [`parseval`], the fast path of the point-symmetric 2-mode droplet (forces by
//! Parseval, no inverse transform), and [`quadrature`], the sums in real space for a droplet of
//! any shape. They agree to round-off for `K = 2` (tested in [`crate::roots::steady_solver`]).
//! [`polar`] tabulates the window's radii, harmonics and powers for the second.
pub mod parseval;
pub mod polar;
pub mod quadrature;
