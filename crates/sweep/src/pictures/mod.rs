//! Pictures, each drawn as PNG and SVG by one scaffold (`render`): the figures (`figures`: the
//! phase map of Fig. 2a, the single-run panels of Fig. 1, `v` and `s` against a parameter of
//! Fig. 2b/3b, the Appendix E fit), a sweep's pictures from its runs with the boundaries
//! (`sweep_pictures`), and sampled steady states joined into drawable branches
//! (`branch_lines`).
//!
//! May use: `spec`, `store`, `map`, `tables`. Used by: `execution`, `bench`, the CLI.
pub mod branch_lines;
pub mod figures;
pub mod render;
pub mod sweep_pictures;
