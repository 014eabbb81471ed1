//! Pictures, each drawn as PNG and SVG by one scaffold (`render`): the phase map of Fig. 2a
//! (`map_figure`, colours and legend in `legend`; maps side by side in `slice_figure`: a
//! 3-axis sweep's slices, or two maps of one plane compared in `map_comparison`), the
//! single-run panels of Fig. 1
//! (`run_figure`), `v` and `s` against a parameter of Fig. 2b/3b (`line_figure`), the
//! Appendix E fit (`h0_figure`), a sweep's pictures from its runs with the boundaries
//! (`sweep_pictures`), bifurcation diagrams of the reduced model and of continuation
//! (`branch_pictures`), and sampled steady states joined into drawable branches
//! (`branch_lines`).
//!
//! May use: `spec`, `store`, `map`, `tables`. Used by: `execution`, `studies`, `bench`, the CLI.
pub mod branch_lines;
pub mod branch_pictures;
pub mod h0_figure;
pub mod legend;
pub mod line_figure;
pub mod map_comparison;
pub mod map_figure;
pub mod render;
pub mod run_figure;
pub mod slice_figure;
pub mod sweep_pictures;
