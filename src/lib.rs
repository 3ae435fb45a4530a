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

pub mod camera;
pub mod datasets;
pub mod error;
#[allow(missing_docs)]
pub mod ffi;
pub mod ftb;
pub mod grid;
pub mod hybrid;
pub mod io;
pub mod limits;
pub mod octree;
pub mod plan;
pub mod points;
pub mod render;
pub mod spacing;
pub mod surface;
pub mod transfer;
pub mod vec3;
pub mod volume;

pub use error::{Error, Result};
pub use plan::{order, select, slab};
