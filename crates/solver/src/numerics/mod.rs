//! General numerics with no knowledge of the droplet: modified Bessel functions, the row-pruned
//! 2-D real FFT, Newton's method for small dense systems, a bracketed scalar root and the
//! guarded eigenvalues of a small dense matrix.
//!
//! May use: nothing of this crate but `error`. Used by every other folder.
pub mod bessel;
pub mod bracket;
pub mod eigen;
pub mod fft2;
pub mod newton;
