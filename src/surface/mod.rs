//! The Surface Octree (paper 1, section 2.2): the Discretized Marching Cubes
//! isosurface of the Volume Octree's terminal nodes, its coplanar facets
//! merged losslessly into faces and re-triangulated; or, in interpolated
//! mode, the classic linearly interpolated Marching Cubes surface.
//!
//! [`table`] derives the watertight case table, [`extract`] marches a node's
//! cells, [`faces`] merges coplanar regions into faces, [`straight`] drops
//! straight vertices without T-junctions, [`earclip`] triangulates faces
//! ([`exact`]: integer geometry), [`assemble`] names vertices and builds the
//! mesh, [`place`] computes points and normals (from the polygons' area
//! vectors, [`polygon`]), [`build`] runs it all in parallel into a
//! [`Surface`] (the types: [`mesh`]), [`check`] measures it (edges, area,
//! volume), [`distance`] compares two surfaces.

pub mod assemble;
pub mod build;
pub mod check;
pub mod distance;
pub mod earclip;
pub mod exact;
pub mod extract;
pub mod faces;
pub mod mesh;
pub mod place;
pub mod polygon;
pub mod straight;
pub mod table;

pub use mesh::{Surface, SurfaceMode, SurfaceOptions, SurfaceStats};
