//! Texture-budget selection (paper 1 section 4.2, after Boada et al. 2001):
//! a cut of the Volume Octree and a voxel-to-texel level `p` per node of the
//! cut, within a texture budget.
//!
//! A node at level `k` drawn at level `p` samples its box every
//! `stride = 2^(L - k - p)` cells, so it needs `2^p + 1` texels per axis
//! (fewer where the box is clipped by the grid), borders included: adjacent
//! bricks share their face samples, which keeps filtering seamless.
//!
//! ```text
//! bytes(n, p)  = texels_x * texels_y * texels_z * bytes_per_texel
//! error(n, p)  = Imp(n) * e_p(n)              (e_p normalised by the data range)
//! Imp(n)       = 1                            inside the region of interest, or without one
//!              = r / (r + dist(box(n), c) - r) = r / dist(box(n), c)   outside it
//! ```
//!
//! (`c`, `r`: the region's centre and radius in index space; `dist` from the
//! centre to the nearest point of the node's box). Greedy refinement from the
//! root at `p = 0`: while the budget allows, take the step that removes the
//! most error mass per byte, where the error mass is
//! `Imp(n) max(Q_p(n), e_p(n)^2)`: `Q_p` is the node's squared error at
//! level `p` summed over its samples (stored by the build, see
//! [`crate::octree`]), `e_p(n)^2` that of its worst sample (see
//! `error_mass`). The max `e_p` says how wrong the worst sample is, `Q_p`
//! how much of the picture is wrong, and a node crossed by one sharp edge
//! keeps its max near the top at every level but the finest while its sum
//! drops with every level. Each node offers the better of:
//! raise its `p` to the level that removes the most
//! mass per byte (up to `max_brick_log2`, never past full resolution), or split it into its children at the same
//! stride (`p - 1`), which costs only their shared borders and lets each child
//! refine on its own. A node stops when its weighted error is at most the
//! tolerance `Eu` (`e_p(n) <= Eu / Imp(n)`). Ties go to the smaller node id, so the result
//! is deterministic. Nodes whose value range the caller's `visible` test
//! rejects (fully transparent under the transfer function) cost nothing and
//! are never refined.
//!
//! With the points of the hybrid representation ([`select_with_points`],
//! paper 3), a brick whose stride is the points' factor offers a third step:
//! take its points, removing the squared error of those it can correct
//! ([`crate::points::mass`]) for their bytes; a brick that has its points can
//! still be raised or split (its points are then dropped). The budget covers
//! texture and point bytes together.

mod brick;
mod cache;
mod estimate;
mod forms;
mod mass;
mod refine;
mod screen;
mod selector;
mod stand_in;
mod steps;
mod uniform;
mod view;
mod visibility;

#[cfg(test)]
pub(crate) use brick::test_brick;
pub use brick::{importance, Brick, Roi, SelectOptions, Selection};
pub use estimate::{estimated_error, estimated_rms_error, seen_rms_error, Seen};
pub use refine::{select, select_in_view, select_with_points, take_all_points};
pub use screen::ScreenSpace;
pub use selector::Selector;
pub use stand_in::{merged_stand_ins, stand_in};
pub use uniform::uniform;
pub use view::{view_change_degrees, ViewImportance, ViewInputs, ViewSelection};
pub use visibility::{Medium, Occluder, Transmittance};
