//! From runs to a phase map: the class of a point from its runs' endings (`point_class`), the
//! map of a sweep computed once from its plan and stored runs (`phase_map`), the refinement
//! rule (`refine`) and the point set it gives level by level (`levels`), label counts
//! (`tally`), a 1-D sweep's class changes against continuation (`line_compare`), the
//! shape each run ended with for the K-mode columns (`end_shape`), a seeded sample of
//! points or runs (`sample`), and the points certified without runs (`certify`, opt-in).
//!
//! May use: `spec`, `store`. Used by: `tables`, `pictures`, `execution`, `audit`, `bench`.
pub mod certify;
pub mod end_shape;
pub mod levels;
pub mod line_compare;
pub mod phase_map;
pub mod point_class;
pub mod refine;
pub mod sample;
pub mod tally;
