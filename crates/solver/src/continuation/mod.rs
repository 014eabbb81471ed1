//! Steady and travelling states of the full model as roots, followed in a parameter with
//! their stability (paper Fig. 3b, for the PDE): pseudo-arclength continuation
//! ([`arclength`]) of the co-moving force balance of one family ([`problem`]), the stability
//! verdict of every state with the near-neutral rotation mode set aside ([`crate::roots::verdict`]), the
//! bifurcation points along a branch ([`branch`], located by [`events`]), and their continuation in both parameters,
//! the PDE's own phase boundaries in a [`window`] of two model parameters, one entry point
//! ([`boundaries`]): in the paper's plane at any number of shape modes, the onset lines
//! sampled in `kappa2` ([`onset_lines`]); in a plane of any other two ([`plane`], two shape
//! modes) traced as zero sets ([`level_set`]); the MD fold continued in either ([`fold_curve`],
//! every `K`). Families
//! and branches hold the
//! shape modes `2..K` ([`problem`], [`branch`]): `droplet continue --modes K` follows every
//! branch, on either mirror line, in any model parameter.
//!
//! May use: `numerics`, `model`, `contract`, `reduced`, `roots`. Used by: the sweep crate and
//! the CLI (`droplet continue`, `droplet boundaries`).
pub mod arclength;
pub mod boundaries;
pub mod branch;
pub mod events;
pub mod fold_curve;
pub mod level_set;
pub mod onset_lines;
pub mod plane;
pub mod polyline;
pub mod problem;
pub mod window;
