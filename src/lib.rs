//! # Hybrid Octree
//!
//! The core of a hybrid volume + surface renderer for VTK and ParaView, after
//! *The Hybrid Octree* (Volume Octree with nodal errors, Surface Octree from
//! Discretized Marching Cubes, texture-budget multiresolution rendering).
//! The crate knows nothing of VTK: `src/ffi/` is the only bridge.
//!
//! ```
//! use hybrid_octree::datasets::{Dataset, generate};
//! use hybrid_octree::octree::{BuildOptions, VolumeOctree};
//!
//! let volume = generate(Dataset::SheppLogan, 33, hybrid_octree::grid::ScalarType::F32);
//! let grid = volume.grid(None).unwrap();
//! let octree = VolumeOctree::build(&grid, &BuildOptions { leaf_size: 8 }).unwrap();
//! octree.validate().unwrap();
//! let stats = octree.stats();
//! assert_eq!(stats.levels, 3); // 32-cell root, 16-cell nodes, 8-cell leaf bricks
//! let cut = octree.cut(0.05).unwrap(); // nodes whose error E_0 <= 5 % of the data range
//! assert!(!cut.is_empty());
//! ```
#![warn(missing_docs)]
#![deny(unsafe_op_in_unsafe_fn)]

// The crate by layer, lowest first (`scripts/layers.py` checks that no
// file imports from a layer above its own, and that no files import each
// other in a loop):
//
// - base: the error type and the limits checked before allocating;
// - data, geometry: grids, volumes and spacings; vectors and the camera;
// - datasets, io: the volumes read or generated;
// - octree: the Volume Octree; store: it and its volume on disk (OME-Zarr);
// - surface: the Surface Octree;
// - transfer: transfer functions; points: the hybrid point representation;
// - plan: budget selection, back-to-front order, slabs, the draw list;
// - render, ftb: the compositor and reference ray caster; front-to-back display;
// - hybrid and the ffi modules: what the C++ bridge calls.
pub mod base;
pub mod data;
pub mod datasets;
#[allow(missing_docs)]
pub mod ffi;
pub mod ftb;
pub mod geometry;
pub mod hybrid;
pub mod io;
pub mod octree;
pub mod plan;
pub mod points;
pub mod render;
pub mod store;
pub mod surface;
pub mod transfer;

pub use base::error::{Error, Result};
pub use base::{error, limits};
pub use data::{grid, planes, spacing, volume};
pub use geometry::{camera, vec3};
pub use plan::{order, select, slab};
