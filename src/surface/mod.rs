//! The Surface Octree (paper 1, section 2.2): the Discretized Marching Cubes
//! isosurface of the Volume Octree's terminal nodes, compressed losslessly
//! into convex coplanar polygons; or, in interpolated mode, the classic
//! linearly interpolated Marching Cubes surface.
//!
//! [`table`] derives the watertight case table, [`extract`] marches a node's
//! cells, [`compress`] merges coplanar facets, [`collinear`] drops straight
//! vertices without T-junctions, [`build`] runs it all in parallel and
//! assembles the mesh, [`check`] measures it (edges, area, volume),
//! [`distance`] compares two surfaces.

pub mod assemble;
pub mod build;
pub mod check;
pub mod distance;
pub mod earclip;
pub mod exact;
pub mod extract;
pub mod faces;
pub mod straight;
pub mod table;

pub use build::{Surface, SurfaceMode, SurfaceOptions, SurfaceStats};
