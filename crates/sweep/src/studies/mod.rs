//! Whole studies behind one command each, from a checked request to the files written: the
//! full model's exact phase boundaries in a window (`boundaries`, `droplet boundaries`; over a
//! sweep outside the paper's plane, `across` (crossings of the paper's curves) or `pair`
//! (continued in any two model parameters)) and
//! branches of steady states followed in one parameter at any number of shape modes
//! (`continuation`, `droplet continue`),
//! and the boundaries at several grid sizes with their shifts (`convergence`), and how far
//! the paper's 2-mode truncation moves its results (`truncation`, `droplet truncation`).
//! Each returns what it computed and the paths it wrote; the CLI only parses and prints.
//!
//! May use: `spec`, `store`, `map`, `tables`, `pictures`. Used by: the CLI.
pub mod across;
pub mod boundaries;
pub mod continuation;
pub mod convergence;
pub mod pair;
pub mod truncation;
