//! The planning layer, from the octree to what the renderers execute:
//! [`select`] chooses the nodes under a texture budget, [`cost`] predicts a
//! DrawList's time and chooses the budget that meets a frame-time target, [`order`] sorts them
//! back to front, [`slab`] places the surface triangles between the slices
//! of each brick, [`point_slabs`] buckets the points of the hybrid
//! representation into them, the draw list (`draw_list`) says which passes
//! a scene needs and what each draws, [`crop`] says which samples VTK's
//! cropping and clipping planes keep, [`dependent`] plans a two-field volume
//! with dependent components, [`jitter`] moves each pixel's samples by a
//! fixed fraction of the slice spacing, [`sampling`] refines the slices of
//! the effects that alias at one sample a lattice step, [`slice`](mod@slice) is the Slice blend mode's
//! plane, [`texel_format`] says what a texel costs and holds, and [`draw_geometry`] makes the OpenGL
//! mapper's vertices of a draw list.

pub mod blend;
pub mod cost;
pub mod crop;
pub mod dependent;
pub mod draw_geometry;
mod draw_list;
pub mod jitter;
pub mod order;
pub mod point_slabs;
pub mod sampling;
pub mod scattering;
pub mod select;
pub mod slab;
pub mod slice;
pub mod texel_format;

pub use blend::{Blend, BlendMode};
pub use draw_list::{
    draw_list, needs_gradients, plan, recrop, replan_effects, replan_transfer_2d, BrickDraw, DrawList, Plan,
    PointBucket, Scene, SurfacePass,
};
pub use point_slabs::add_points;
pub use slab::Batch;
pub use slice::SlicePlane;
