//! Steady states as roots: the exact co-moving steady solver (`steady_solver`: any `K`, and
//! the fast path of `K = 2`), the linearisation about a root
//! (field included, docs/numerics.md "Stability"), the stability verdict with the rotation mode
//! set aside, the steady balances of any `K` behind one interface (`balances`), the named
//! states of the paper (IC, ID, MD on a mirror axis of the box, any `K`), where resting states
//! lose stability (`thresholds`) and the Appendix E fit of `h0`, and the Jacobians kept at roots for the chord method
//! (`kept_jacobians`).
//!
//! May use: `numerics`, `model`, `contract`, `reduced` (starting guesses). Used by: `runs`,
//! `continuation`.
pub mod balances;
mod forces_memo;
pub mod h0_fit;
pub mod kept_jacobians;
pub mod linearisation;
pub mod named_state;
pub mod steady_solver;
pub mod thresholds;
pub mod verdict;
