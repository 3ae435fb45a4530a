//! What the OpenGL mapper draws, computed here and tested with the CPU
//! compositor's rules, so that the C++ only uploads and draws:
//!
//! - [`slice_polygon`]: the view basis, and the polygon of a view-aligned
//!   slice inside a brick's box as a triangle fan;
//! - [`occupancy`]: a brick's block value ranges (measured with its
//!   texels) and, under the transfer function's opacity table, the box of
//!   its visible blocks, which its slices are clipped to;
//! - [`brick_geometry`](mod@brick_geometry): the vertex stream of every brick: its slices, the
//!   translucent surface's triangles placed in the slabs between them by the
//!   rule the CPU compositor uses ([`crate::plan::slab::slab_copies`]), the
//!   hybrid points, or its ray-marched box;
//! - [`slice_plane`](mod@slice_plane): under the Slice blend mode, the
//!   polygon where its plane cuts each brick instead.

pub mod brick_geometry;
pub mod occupancy;
pub mod slice_plane;
pub mod slice_polygon;

pub use brick_geometry::{
    brick_geometry, list_bricks, BrickGeometry, BrickSlabs, GeometryView, PointVertices, PrimitiveKind,
    SurfaceVertices, FLOATS_PER_VERTEX, MAX_BRICKS, UNBOUNDED,
};
pub use occupancy::{OpacityTable, TexelBox};
pub use slice_plane::slice_plane_geometry;
pub use slice_polygon::{append_slice_polygon, view_basis};
